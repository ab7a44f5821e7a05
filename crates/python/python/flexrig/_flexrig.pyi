"""Type stubs of the native module ``flexrig._flexrig`` (PyO3). Use the ``flexrig`` package:
its functions wrap these with the documented conveniences (scene forms, keyword overrides,
broadcasting, DataFrames, Dask)."""

import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: The summary quantities of a sweep row, in column order (as in ``flexrig sweep``'s CSV).
SUMMARY_COLUMNS: List[str]

class InputError(ValueError):
    """Bad input: the message names the field, the value and what is allowed."""

    #: The field, e.g. ``robot.payload_kg``, ``m_h[3]``, ``grid``, ``scene``.
    field: str

class SimulationError(RuntimeError):
    """A run that could not finish (unstable, or its stop condition not reached)."""

def bundled_scenes() -> List[str]:
    """The names of the bundled scenes."""

def scene_descriptions() -> List[Tuple[str, str]]:
    """(name, one-line description) of every bundled scene, as `flexrig scenes` lists them."""

def write_scene(name: str, path: Union[str, "os.PathLike[str]"], force: bool = False) -> None:
    """Writes bundled scene `name` to `path` to edit it; an existing file is kept unless force."""

def scene_text(scene: Union[str, "os.PathLike[str]", Dict[str, Any]]) -> Tuple[str, Optional[Path]]:
    """(TOML text, directory of the scene file or None) of a path, bundled name, TOML text or dict."""

def apply_overrides(text: str, overrides: Sequence[Tuple[str, Any]]) -> str:
    """The scene text with the (dotted path, value) overrides applied, validated like the file."""

def run(
    text: str, overrides: Sequence[Tuple[str, Any]]
) -> Tuple[Dict[str, Any], Dict[str, npt.NDArray[np.float64]], Dict[str, npt.NDArray[np.float64]]]:
    """Runs the scene text with overrides: (summary as ``flexrig run --json``, sample traces,
    step traces). GIL released; Ctrl-C raises KeyboardInterrupt."""

def safety_json(input_json: str, body_model_toml: Optional[str] = None) -> str:
    """The report of ``flexrig safety --json`` for a safety input given as JSON (see
    ``flexrig.safety``)."""

def impact_exact(
    m_h: npt.NDArray[np.float64],
    m_eff: npt.NDArray[np.float64],
    k_delta: npt.NDArray[np.float64],
    k_c: npt.NDArray[np.float64],
    n: npt.NDArray[np.float64],
    v0: npt.NDArray[np.float64],
) -> Tuple[
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
    npt.NDArray[np.float64],
]:
    """Exact peak of every parameter set (1-D float64 arrays of one length): (f_max_n,
    delta_max_m, indentation_max_m, link_deflection_max_m, mu_kg, impact_energy_j)."""

def fig6(points: int = 101) -> List[Dict[str, Any]]:
    """Fig. 6 curves: dicts with m_h, k_delta, m_e, n, eta_at_2_3 and the arrays gamma, eta."""

class Sweep:
    """A sweep of a base scene over a grid (or zip) of scene fields; picklable."""

    def __init__(
        self,
        base_text: str,
        grid: Sequence[Tuple[str, Any]],
        zip: bool = False,
        base_dir: Optional[Union[str, "os.PathLike[str]"]] = None,
    ) -> None: ...
    def __len__(self) -> int: ...
    @property
    def paths(self) -> List[str]:
        """The varied paths, in grid order."""
    @property
    def zip(self) -> bool:
        """True for a zipped sweep."""
    @property
    def base_text(self) -> str:
        """The base scene's TOML text."""
    def grid(self) -> List[Tuple[str, List[Any]]]:
        """The grid with every spec resolved: (path, values)."""
    def fingerprint(self) -> str:
        """The fingerprint ``flexrig sweep`` writes to sweep.json."""
    def run(self, indices: Optional[Sequence[int]] = None, threads: Optional[int] = None) -> Dict[str, Any]:
        """Runs the points (all by default): a dict of columns index, values (a list per path),
        status, error and summary (float64, rows × SUMMARY_COLUMNS, NaN where absent)."""
    def __reduce__(self) -> Tuple[Any, ...]: ...
