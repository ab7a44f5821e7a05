"""Hostile input to the Python API: `flexrig.run`, `scene_text`, `sweep`, `impact`, `fig6`.

Every case runs in a child interpreter under a 2 GiB address-space cap (RLIMIT_AS), so a segfault,
an abort or an out-of-memory death is a failed case, not a dead pytest; a child still busy after
TIMEOUT_S is killed and the case fails as a hang (a generous limit: no test asserts a duration).
The children run the cases one after another and report each before and after it, so a crash
names the case it happened in; the next child goes on from the case after it.

The floors, per case:
- the child never dies by a signal and never hangs;
- bad input raises `flexrig.InputError` (a ValueError) whose message names the argument or field
  and whose `field` attribute holds it; no other exception type (TypeError, OverflowError,
  RecursionError, SystemError, pyo3's PanicException, ...) escapes;
- no message shows a Rust type name or Debug value (such as an escaped `\\u{feff}`);
- a result that is returned holds no NaN where a number must be (runs and impacts).
"""

from __future__ import annotations

import json
import math
import os
import queue
import resource
import subprocess
import sys
import threading
from pathlib import Path

import pytest

TIMEOUT_S = 120.0
AS_CAP = 2 * 1024**3
RUST_LEAKS = ("panicked", "RUST_BACKTRACE", "struct ", "enum ", "usize", "f64", "Some(", "None)", "Debug", "\\u{")
HERE = Path(__file__).resolve().parent
SCENES = HERE.parents[2] / "assets" / "scenes"

# ------------------------------------------------------------------------------------------------
# The cases: name -> (expected outcome, the names the error must hold one of, a thunk).
#   "input": must raise InputError naming one of the names
#   "input_or_ok": InputError naming one of the names, or a finite result
#   "not_found": FileNotFoundError


def _cyclic_dict():
    d = {}
    d["a"] = d
    return d


def _cyclic_list():
    lst = []
    lst.append(lst)
    return lst


def _deep_dict(depth):
    d = {"x": 1.0}
    for _ in range(depth):
        d = {"a": d}
    return d


def _deep_list(depth):
    lst = [1.0]
    for _ in range(depth):
        lst = [lst]
    return lst


class _Weird:
    def __repr__(self):
        return "<weird>"

    def __str__(self):
        raise RuntimeError("str() refused")

    def __float__(self):
        raise RuntimeError("float() refused")


def _run(**overrides):
    import flexrig

    return flexrig.run("cj_iron", overrides=overrides)


def _cases():
    import numpy as np

    cases = {}
    payload = "robot.payload_kg"

    def add(name, expect, names, thunk):
        cases[name] = (expect, names, thunk)

    # Overrides: cyclic, deep, huge ints, non-finite floats, odd types, long strings.
    for label, value in [
        ("cyclic_dict", _cyclic_dict),
        ("cyclic_list", _cyclic_list),
        ("deep_dict_1e5", lambda: _deep_dict(100_000)),
        ("deep_list_1e5", lambda: _deep_list(100_000)),
        ("deep_dict_200", lambda: _deep_dict(200)),
        ("deep_list_200", lambda: _deep_list(200)),
        ("int_10_400", lambda: 10**400),
        ("int_2_64", lambda: 2**64),
        ("int_minus_2_63_minus_1", lambda: -(2**63) - 1),
        ("nan", lambda: float("nan")),
        ("inf", lambda: float("inf")),
        ("minus_inf", lambda: float("-inf")),
        ("np_nan", lambda: np.float64("nan")),
        ("np_array_2d", lambda: np.zeros((2, 2))),
        ("complex", lambda: 1j),
        ("bytes", lambda: b"0.2"),
        ("none", lambda: None),
        ("object", object),
        ("weird", _Weird),
        ("set", lambda: {0.1, 0.2}),
        ("string_1e7", lambda: "x" * 10_000_000),
        ("string_nul", lambda: "0.2\x00"),
        ("string_bom", lambda: "\ufeff0.2"),
        ("list_1e6", lambda: [0.1] * 1_000_000),
        ("dict_int_keys", lambda: {1: 2}),
    ]:
        add(
            f"run_override_{label}",
            "input",
            [payload],
            lambda value=value: _run(**{payload: value()}),
        )
    # Override paths: deep dotted, long, empty, NUL, non-str key, cyclic whole-table overrides.
    add("run_override_np_int64", "input_or_ok", [payload], lambda: _run(**{payload: np.int64(1)}))
    add("run_path_deep_dotted", "input", ["robot", "x.x"], lambda: _run(**{"robot." + "x." * 50_000 + "y": 1}))
    add("run_path_long", "input", ["a" * 40], lambda: _run(**{"a" * 1_000_000: 1}))
    add("run_path_empty", "input", ["overrides", "path", "''"], lambda: _run(**{"": 1}))
    add("run_path_nul", "input", ["robot"], lambda: _run(**{"robot.\x00": 1}))
    add("run_path_dots", "input", ["..", "path"], lambda: _run(**{"..": 1}))
    add(
        "run_overrides_int_key",
        "input",
        ["overrides"],
        lambda: __import__("flexrig").run("cj_iron", overrides={1: 2}),
    )
    add(
        "run_overrides_not_mapping",
        "input",
        ["overrides"],
        lambda: __import__("flexrig").run("cj_iron", overrides=[("robot.payload_kg", 0.2)]),
    )
    add("run_table_cyclic", "input", ["robot"], lambda: _run(robot=_cyclic_dict()))
    add("run_table_deep", "input", ["robot"], lambda: _run(robot=_deep_dict(100_000)))
    add("run_design_weird", "input", ["robot.design"], lambda: _run(**{"robot.design": "CL\x00"}))
    # Scenes given as dicts: cyclic, deep, huge.
    add("scene_dict_cyclic", "input", ["scene", "a"], lambda: __import__("flexrig").run(_cyclic_dict()))
    add("scene_dict_deep", "input", ["scene", "a"], lambda: __import__("flexrig").run(_deep_dict(100_000)))
    add("scene_text_nul", "input", ["scene", "line", "name"], lambda: __import__("flexrig").run("name = \"\x00"))
    add("scene_missing_file", "not_found", [], lambda: __import__("flexrig").run("/nonexistent/x.toml"))
    add(
        "scene_text_deep_toml",
        "input",
        ["scene", "line", "nest"],
        lambda: __import__("flexrig").run("x = " + "[" * 100_000 + "]" * 100_000),
    )

    # Sweeps: grids, zips, threads, client, chunk_size.
    def sweep(grid, **kw):
        import flexrig

        return flexrig.sweep("cj_iron", grid, **kw)

    add("sweep_grid_list", "input", ["grid"], lambda: sweep([("robot.payload_kg", [0.1])]))
    add("sweep_grid_empty", "input", ["grid"], lambda: sweep({}))
    add("sweep_value_empty", "input", [payload, "grid"], lambda: sweep({payload: []}))
    add("sweep_value_cyclic", "input", [payload], lambda: sweep({payload: _cyclic_list()}))
    add("sweep_value_deep", "input", [payload], lambda: sweep({payload: [_deep_list(100_000)]}))
    add("sweep_value_generator", "input_or_ok", [payload], lambda: sweep({payload: (x for x in [0.1])}))
    add("sweep_value_set", "input_or_ok", [payload], lambda: sweep({payload: {0.1}}))
    add("sweep_value_huge_range_obj", "input", [payload, "grid"], lambda: sweep({payload: range(10**12)}))
    add("sweep_value_range_1e8", "input", [payload, "grid"], lambda: sweep({payload: "0.01:1:100000000"}))
    add(
        "sweep_three_large_ranges",
        "input",
        ["grid", "points"],
        lambda: sweep(
            {
                payload: "0.01:1:10000",
                "operator.start.release_angle_deg": "10:60:10000",
                "robot.length_m": "0.2:0.4:10000",
            }
        ),
    )
    add("sweep_value_nan_range", "input", [payload], lambda: sweep({payload: "nan:1:3"}))
    add("sweep_value_count_0", "input", [payload], lambda: sweep({payload: "0.1:1:0"}))
    add("sweep_value_file_missing", "input_or_not_found", [payload, "missing"], lambda: sweep({payload: "@missing.txt"}))
    add("sweep_value_dev_zero", "input", [payload, "/dev/zero"], lambda: sweep({payload: "@/dev/zero"}))
    add("sweep_value_np_2d", "input", [payload], lambda: sweep({payload: np.zeros((2, 2))}))
    add("sweep_value_np_nan", "input_or_ok", [payload], lambda: sweep({payload: np.array([np.nan])}))
    add("sweep_value_object", "input", [payload], lambda: sweep({payload: [object()]}))
    add("sweep_path_not_str", "input", ["grid", "1"], lambda: sweep({1: [0.1]}))
    add("sweep_path_unknown", "input", ["robot.nope"], lambda: sweep({"robot.nope": [0.1]}))
    add(
        "sweep_zip_mismatch",
        "input",
        ["zip", payload],
        lambda: sweep({payload: [0.1, 0.2], "operator.start.release_angle_deg": [30.0]}, zip=True),
    )
    add("sweep_zip_not_bool", "input_or_ok", ["zip"], lambda: sweep({payload: [0.1]}, zip="yes"))
    for label, threads in [("minus_1", -1), ("0", 0), ("2_40", 2**40), ("true", True), ("float", 1.5), ("str", "2")]:
        add(f"sweep_threads_{label}", "input", ["threads"], lambda t=threads: sweep({payload: [0.1]}, threads=t))
    add("sweep_client_object", "input", ["client"], lambda: sweep({payload: [0.1]}, client=object()))
    add("sweep_chunk_size_0", "input", ["chunk_size"], lambda: sweep({payload: [0.1]}, chunk_size=0))
    add(
        "sweep_native_cyclic",
        "input",
        [payload],
        lambda: __import__("flexrig").Sweep(
            (SCENES / "cj_iron.toml").read_text(), [(payload, _cyclic_list())], False, None
        ),
    )
    add(
        "sweep_native_indices_out_of_range",
        "input",
        ["indices", "index"],
        lambda: __import__("flexrig")
        .Sweep((SCENES / "cj_iron.toml").read_text(), [(payload, [0.1])], False, None)
        .run([5, -1, 2**70], None),
    )
    add(
        "sweep_native_threads_minus_1",
        "input",
        ["threads"],
        lambda: __import__("flexrig")
        .Sweep((SCENES / "cj_iron.toml").read_text(), [(payload, [0.1])], False, None)
        .run(None, -1),
    )

    # impact: broadcast arguments.
    def impact(**kw):
        import flexrig

        args = dict(m_h=4.0, m_eff=3.43, k_delta=1e8, k_c=1e8, n=2.0, v0=2.0)
        args.update(kw)
        return flexrig.impact(**args)

    for label, value in [
        ("nan", float("nan")),
        ("inf", float("inf")),
        ("neg", -1.0),
        ("huge_int", 10**400),
        ("object", object()),
        ("complex", 1j),
        ("cyclic", _cyclic_list()),
        ("array_nan", [4.0, float("nan")]),
        ("array_2d_ragged", [[4.0], [4.0, 5.0]]),
    ]:
        add(f"impact_m_h_{label}", "input", ["m_h"], lambda v=value: impact(m_h=v))
    add("impact_v0_1e300", "input_or_ok", ["v0"], lambda: impact(v0=1e300))
    add("impact_m_h_str", "input_or_ok", ["m_h"], lambda: impact(m_h="4"))
    add("impact_m_h_empty", "input_or_ok", ["m_h"], lambda: impact(m_h=[]))
    add("impact_n_0", "input", ["n"], lambda: impact(n=0.0))
    add("impact_shapes", "input", ["m_h", "shape", "broadcast"], lambda: impact(m_h=[1.0, 2.0], v0=[1.0, 2.0, 3.0]))

    # fig6: points.
    for label, points in [("minus_1", -1), ("0", 0), ("1", 1), ("huge", 10**12), ("float", 1.5), ("str", "x"), ("true", True), ("nan", float("nan"))]:
        add(f"fig6_points_{label}", "input", ["points"], lambda p=points: __import__("flexrig").fig6(points=p))
    return cases


# ------------------------------------------------------------------------------------------------
# The child: runs the named cases, one JSON line before and after each.


def _finite(value) -> bool:
    import numpy as np

    if isinstance(value, float):
        return math.isfinite(value)
    if isinstance(value, np.ndarray) and value.dtype.kind == "f":
        return bool(np.isfinite(value).all())
    return True


def _describe(result) -> dict:
    """What a returned result looks like: non-finite numbers where numbers must be finite."""
    bad = []
    for name in ("peak_force_n", "impact_velocity_mps", "f_max_n", "delta_max_m", "mu_kg"):
        if hasattr(result, name) and not _finite(getattr(result, name)):
            bad.append(name)
    return {"kind": "ok", "bad": bad}


def child(names) -> None:
    import flexrig

    cases = _cases()
    for name in names:
        print(json.dumps({"start": name}), flush=True)
        expect, fields, thunk = cases[name]
        try:
            verdict = _describe(thunk())
        except flexrig.InputError as e:
            verdict = {
                "kind": "InputError",
                "is_value_error": isinstance(e, ValueError),
                "field": str(getattr(e, "field", "")),
                "message": str(e)[:2000],
            }
        except BaseException as e:  # noqa: BLE001 - the point is to see every kind
            verdict = {"kind": type(e).__name__, "message": str(e)[:2000]}
        verdict["case"] = name
        print(json.dumps(verdict), flush=True)


# ------------------------------------------------------------------------------------------------
# The parent: runs the children, judges the verdicts.


def _limit():
    resource.setrlimit(resource.RLIMIT_AS, (AS_CAP, AS_CAP))


def _panic_lines(stderr: str) -> str:
    """The lines of a dead child's standard error that say why (not the backtrace's frames)."""
    keep = [
        line
        for line in stderr.splitlines()
        if line.strip() and not line.lstrip()[:1].isdigit() and not line.lstrip().startswith("at ")
    ]
    return "\n".join(keep)[:800]


def _run_children(names):
    """Runs `names` in children; returns {name: verdict or a crash/hang description}."""
    verdicts = {}
    todo = list(names)
    while todo:
        proc = subprocess.Popen(
            [sys.executable, "-c", f"import sys; sys.path.insert(0, {str(HERE)!r}); import test_fuzz; test_fuzz.child(sys.argv[1:])", *todo],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            preexec_fn=_limit,
            cwd=str(SCENES),
        )
        lines: "queue.Queue[str | None]" = queue.Queue()

        def pump(stream=proc.stdout):
            for line in stream:
                lines.put(line)
            lines.put(None)

        threading.Thread(target=pump, daemon=True).start()
        err_chunks = []
        threading.Thread(target=lambda: err_chunks.append(proc.stderr.read()), daemon=True).start()
        current = None
        ended = False
        while not ended:
            try:
                line = lines.get(timeout=TIMEOUT_S)
            except queue.Empty:
                proc.kill()
                verdicts[current or todo[0]] = {"kind": "hang", "message": f"still running after {TIMEOUT_S} s"}
                break
            if line is None:
                ended = True
                break
            msg = json.loads(line)
            if "start" in msg:
                current = msg["start"]
            else:
                verdicts[msg["case"]] = msg
                current = None
        proc.wait()
        if current is not None and current not in verdicts:
            stderr = _panic_lines("".join(err_chunks))
            verdicts[current] = {
                "kind": "crash",
                "message": f"the interpreter died (exit {proc.returncode}, signal {-proc.returncode if proc.returncode < 0 else None}): {stderr}",
            }
        elif current is None and len(verdicts) < len(names) and proc.returncode != 0 and not any(
            n in verdicts for n in todo
        ):
            verdicts[todo[0]] = {"kind": "crash", "message": _panic_lines("".join(err_chunks))}
        todo = [n for n in todo if n not in verdicts]
    return verdicts


def _judge(name, expect, fields, v):
    kind = v["kind"]
    message = v.get("message", "")
    problems = []
    if kind in ("crash", "hang"):
        return [f"{kind}: {message}"]
    for leak in RUST_LEAKS:
        if leak in message:
            problems.append(f"the message shows {leak!r}: {message[:300]}")
    if kind == "ok":
        if expect in ("input", "not_found"):
            problems.append(f"returned a result; expected {'InputError' if expect == 'input' else 'FileNotFoundError'}")
        if v.get("bad"):
            problems.append(f"non-finite result fields {v['bad']}")
    elif kind == "InputError":
        if expect == "not_found":
            problems.append(f"InputError; expected FileNotFoundError: {message[:300]}")
        if not v.get("is_value_error"):
            problems.append("InputError is not a ValueError")
        if fields and not any(f in message or f in v.get("field", "") for f in fields):
            problems.append(f"the InputError names none of {fields}: field={v.get('field')!r} {message[:300]}")
    elif kind == "FileNotFoundError":
        if expect not in ("not_found", "input_or_not_found"):
            problems.append(f"FileNotFoundError; expected InputError naming {fields}: {message[:300]}")
    else:
        problems.append(f"raised {kind} (expected InputError naming {fields}): {message[:300]}")
    return problems


def test_python_api_hostile_input_never_crashes_and_names_the_argument():
    pytest.importorskip("flexrig")
    cases = _cases()
    verdicts = _run_children(sorted(cases))
    failures = []
    for name in sorted(cases):
        expect, fields, _ = cases[name]
        v = verdicts.get(name, {"kind": "crash", "message": "no verdict"})
        for p in _judge(name, expect, fields, v):
            failures.append(f"{name}: {p}")
    assert not failures, f"{len(failures)} problems in {len(cases)} cases:\n" + "\n".join(failures)


if __name__ == "__main__" and len(sys.argv) > 1:
    child(sys.argv[1:])
