"""``flexrig.arm``: a real arm from its URDF along a trajectory, the twin of ``flexrig arm
--json`` with the same arguments (the flags in snake_case, SI units): NumPy arrays in, a pandas
DataFrame out beside the report."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Optional, Sequence, Union

import numpy as np

from . import _flexrig
from ._checks import _finite, _input_error, _word
from ._safety import _area_model, _body_model_text, _contact_law, _methods

#: The columns of ``result["table"]``: one row per sample and contact point.
ARM_COLUMNS = (
    "time_s", "point", "x_m", "y_m", "z_m", "speed_mps", "reflected_mass_kg",
    "effective_mass_kg", "v_max_mps", "ratio", "method",
)


def arm(
    *,
    urdf: Optional[Union[str, "os.PathLike[str]"]] = None,
    trajectory: Optional[Union[str, "os.PathLike[str]"]] = None,
    times: Any = None,
    positions: Any = None,
    points: Optional[Sequence[str]] = None,
    joints: str = "rigid",
    armature: Any = None,
    speed_scale: float = 1.0,
    mass_step: float = 0.01,
    region: str = "chest",
    area: Optional[str] = None,
    contact: str = "transient",
    link: str = "cj",
    k_delta: Optional[float] = None,
    link_mass: Optional[float] = None,
    k_c: Optional[float] = None,
    n: Optional[float] = None,
    material: Optional[str] = None,
    area_model: Optional[str] = None,
    radius: Optional[float] = None,
    contact_area: Union[None, float, str] = None,
    drive: str = "free",
    tol: float = 1e-6,
    root_rtol: float = 1e-6,
    method: Optional[Union[str, Sequence[str]]] = None,
    body_model: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Dict[str, Any]:
    """The arm of ``urdf`` along ``trajectory`` (a CSV file: ``time_s`` and one column per
    moving joint) or along ``times`` [s] (shape (n,)) with ``positions`` [rad or m] (shape
    (n, joints), the URDF's joint order), judged at every sample and contact point against
    ``region``: the dict of ``flexrig arm --json`` (the verdict ``pass``, ``max_ratio``, the
    ``speed_scale_factor``, the ``governing`` sample, point and method with ``flexrig safety``'s
    answer there, ``masses``: the answer per distinct effective mass), with ``"table"``: a pandas
    DataFrame of :data:`ARM_COLUMNS`, one row per sample and point, in place of ``"samples"``.
    Without ``urdf`` and a trajectory: the bundled UR5 and its swing.

    ``points`` are ``"LINK:x,y,z"`` (m, in the link's frame; default for the bundled UR5: its
    four). ``joints`` ``"rigid"``, ``"armature"`` (with ``armature``: J_m N² per joint, kg·m²) or
    ``"elastic"``; ``link`` ``"cj"`` or ``"cl"`` with ``k_delta`` [N/m] (None: rigid) and
    ``link_mass`` [kg]; the skin ``k_c``/``n`` or ``material``; ``drive`` ``"free"`` or
    ``"held"``; ``mass_step`` the relative step of the mass grid (0: every mass exactly).
    """
    import pandas as pd

    for name, value in (("speed_scale", speed_scale), ("mass_step", mass_step), ("k_delta", k_delta),
                        ("link_mass", link_mass), ("k_c", k_c), ("n", n), ("radius", radius),
                        ("tol", tol), ("root_rtol", root_rtol)):
        _finite(name, value)
    _word("region", region)
    if link not in ("cj", "cl"):
        raise _input_error("link", f"invalid argument link = {link!r}: 'cj' or 'cl'")
    if drive not in ("free", "held"):
        raise _input_error("drive", f"invalid argument drive = {drive!r}: 'free' or 'held'")
    if joints == "armature":
        if armature is None:
            raise _input_error("armature", "invalid argument armature: joints='armature' needs one rotor inertia J_m N² (kg·m²) per moving joint")
        arr = np.asarray(armature, dtype=float).ravel()
        if not np.all(np.isfinite(arr)):
            raise _input_error("armature", f"invalid argument armature = {armature!r}: finite numbers (kg·m²)")
        joints_value: Any = {"armature": arr.tolist()}
    elif joints in ("rigid", "elastic"):
        if armature is not None:
            raise _input_error("armature", "invalid argument armature: only with joints='armature'")
        joints_value = joints
    else:
        raise _input_error("joints", f"invalid argument joints = {joints!r}: 'rigid', 'armature' or 'elastic'")
    t_list = q_list = None
    if (times is None) != (positions is None):
        raise _input_error("times", "invalid argument times: times and positions go together")
    if times is not None:
        if trajectory is not None:
            raise _input_error("trajectory", "invalid argument trajectory: give either a CSV file or times with positions")
        t = np.asarray(times, dtype=float)
        q = np.asarray(positions, dtype=float)
        if t.ndim != 1 or q.ndim != 2 or q.shape[0] != t.shape[0]:
            raise _input_error("positions", f"invalid argument positions: shape {q.shape} for {t.shape[0] if t.ndim == 1 else t.shape} times; one row per time, one column per moving joint")
        t_list, q_list = t.tolist(), q.tolist()
    points_value = [_word("points", p) for p in (points or [])]
    data = {
        "points": points_value,
        "joints": joints_value,
        "speed_scale": speed_scale,
        "mass_step": mass_step,
        "region": region,
        "area": area,
        "contact": contact.replace("-", "_"),
        "law": _contact_law(k_c, n, material),
        "area_model": _area_model(area_model, radius, contact_area),
        "link": link,
        "k_delta": k_delta,
        "link_mass": link_mass,
        "methods": _methods(method) if method is not None else [],
        "drive": drive,
        "tol": tol,
        "root_rtol": root_rtol,
        "simulation": None,
    }
    text = _flexrig.arm_json(
        json.dumps(data),
        None if urdf is None else os.fspath(urdf),
        None if trajectory is None else os.fspath(trajectory),
        t_list,
        q_list,
        _body_model_text(body_model),
    )
    report = json.loads(text)
    labels = [
        f"{p['link']}:{','.join(format(x, 'g') for x in p['xyz'])}" for p in report["points"]
    ]
    rows = []
    for s in report.pop("samples"):
        for label, p in zip(labels, s["points"]):
            v = p.get("v_max_mps")
            rows.append((
                s["time_s"], label, *p["position_m"], p["speed_mps"],
                p.get("reflected_mass_kg", np.nan), p.get("effective_mass_kg", np.nan),
                np.inf if v == "unlimited" else (np.nan if v is None else v),
                p["ratio"], p.get("method"),
            ))
    report["table"] = pd.DataFrame(rows, columns=list(ARM_COLUMNS))
    return report
