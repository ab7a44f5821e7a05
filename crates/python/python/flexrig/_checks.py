"""The argument checks the Python twins share: each refuses a value with :class:`InputError`
whose ``field`` names the keyword argument, and says what is allowed, as the command line's
errors name the flag."""

from __future__ import annotations

from typing import Any, List, Optional

import numpy as np

from ._flexrig import InputError


def _input_error(field: str, message: str) -> InputError:
    """An :class:`InputError` for the keyword argument ``field``."""
    error = InputError(message)
    error.field = field  # type: ignore[attr-defined]
    return error


def _number(name: str, value: Any, optional: bool = False) -> Optional[float]:
    if value is None and optional:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise _input_error(name, f"invalid argument {name} = {value!r}: must be a number")
    return float(value)


def _finite(name: str, value: Any, optional: bool = True) -> Optional[float]:
    """A number that must be finite (NaN and ±inf refused naming the argument, as the command
    line refuses them naming the flag)."""
    v = _number(name, value, optional)
    if v is not None and not np.isfinite(v):
        raise _input_error(name, f"invalid argument {name} = {v!r}: must be a finite number")
    return v


def _count(name: str, value: Any, optional: bool = False) -> Optional[int]:
    if value is None and optional:
        return None
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)) or not 0 <= int(value) < 2**63:
        raise _input_error(name, f"invalid argument {name} = {value!r}: must be a whole number ≥ 0")
    return int(value)


def _flag(name: str, value: Any) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise _input_error(name, f"invalid argument {name} = {value!r}: must be True or False")
    return bool(value)


def _word(name: str, value: Any) -> str:
    if not isinstance(value, str):
        raise _input_error(name, f"invalid argument {name} = {value!r}: must be a str")
    return value


def _numbers(name: str, value: Any) -> List[float]:
    items = np.atleast_1d(np.asarray(value, dtype=object)).ravel().tolist()
    return [_number(f"{name}", v) for v in items]  # type: ignore[misc]


def _range(name: str, value: Any) -> str:
    """A ``FROM:TO`` range as the CLI reads it: the str itself, or a (from, to) pair."""
    if isinstance(value, str):
        return value
    if isinstance(value, (tuple, list)) and len(value) == 2:
        a, b = (_number(name, v) for v in value)
        return f"{a!r}:{b!r}"
    raise _input_error(name, f"invalid argument {name} = {value!r}: a (from, to) pair or 'FROM:TO'")


def _check_count(name: str, value: Any, none_means: str) -> None:
    """``value`` must be None or a whole number from 1 to 2**31 - 1 (not a bool, not a float)."""
    if value is None:
        return
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or not 1 <= int(value) < 2**31:
        raise _input_error(
            name,
            f"{name} = {value!r}: must be a whole number from 1 to 2147483647 ({none_means})",
        )
