"""``flexrig.safety``: the permissible speed near a body region (ISO/TS 15066), the twin of
``flexrig safety --json`` with the same arguments (the flags in snake_case, SI units)."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Optional, Sequence, Union

from . import _flexrig
from ._flexrig import InputError


def _input_error(field: str, message: str) -> InputError:
    error = InputError(message)
    error.field = field
    return error


def safety(
    region: str,
    *,
    area: Optional[str] = None,
    contact: str = "transient",
    m_eff: Optional[float] = None,
    m_r: Optional[float] = None,
    m_e: Optional[float] = None,
    gamma: Optional[float] = None,
    k_delta: Optional[float] = None,
    k_c: Optional[float] = None,
    n: Optional[float] = None,
    material: Optional[str] = None,
    area_model: Optional[str] = None,
    radius: Optional[float] = None,
    contact_area: Optional[float] = None,
    moving_mass: Optional[float] = None,
    payload: float = 0.0,
    speed: Optional[float] = None,
    body_model: Optional[Union[str, "os.PathLike[str]"]] = None,
    method: Union[str, Sequence[str]] = ("standard", "energy"),
) -> Dict[str, Any]:
    """The permissible speed of a design near ``region`` by the standard's formula
    (``"standard"``), the paper's energy method (``"energy"``) and the simulated lumped impact
    (``"simulation"``): the dict of ``flexrig safety --json`` with the same numbers.

    Masses in kg (``m_eff``, or ``m_r``, ``m_e`` and ``gamma`` for m_eff = m_e + γ m_r/3;
    ``moving_mass`` and ``payload`` for the standard's m_R = M/2 + m_L), ``k_delta`` in N/m
    (None: rigid link), ``k_c`` in N/m^n with ``n`` (or ``material``; neither: the region's body
    spring, n = 1), ``area_model`` one of ``hertz_sphere``/``thin_layer`` (with ``radius`` in m)
    or ``fixed`` (with ``contact_area`` in m²), ``speed`` in m/s, ``contact`` ``transient`` or
    ``quasi_static``. Unbounded speeds are the word ``"unlimited"``; absent values are absent
    keys. Transient contact with skull/forehead or face raises ``InputError`` quoting the clause.
    """
    if m_eff is not None:
        mass: Optional[Dict[str, Any]] = {"given": m_eff}
    elif m_r is not None or m_e is not None or gamma is not None:
        if m_r is None or m_e is None or gamma is None:
            raise _input_error("gamma", "m_r, m_e and gamma go together (m_eff = m_e + gamma m_r/3)")
        mass = {"prb": {"gamma": gamma, "m_r": m_r, "m_e": m_e}}
    else:
        mass = None
    if (k_c is None) != (n is None):
        raise _input_error("k_c", "k_c and n go together (f = k_c δ^n)")
    if k_c is not None:
        if material is not None:
            raise _input_error("material", "give either k_c and n or material")
        law: Any = {"hertz": {"k_c": k_c, "n": n}}
    elif material is not None:
        law = {"material": material}
    else:
        law = "body_spring"
    model: Optional[Dict[str, Any]] = None
    if area_model is not None:
        kind = area_model.replace("-", "_")
        if kind in ("hertz_sphere", "thin_layer"):
            if radius is None:
                raise _input_error("radius", f"area_model {area_model} needs radius (m)")
            model = {"model": kind, "radius_m": radius}
        elif kind == "fixed":
            if contact_area is None:
                raise _input_error("contact_area", "area_model fixed needs contact_area (m²)")
            model = {"model": "fixed", "area_m2": contact_area}
        else:
            raise _input_error("area_model", f"unknown area_model {area_model!r}: hertz_sphere, thin_layer or fixed")
    methods = [method] if isinstance(method, str) else list(method)
    methods = [m for part in methods for m in part.split(",")]
    data = {
        "region": region,
        "area": area,
        "contact": contact.replace("-", "_"),
        "m_eff": mass,
        "k_delta": k_delta,
        "law": law,
        "area_model": model,
        "moving_mass": moving_mass,
        "payload": payload,
        "speed": speed,
        "methods": methods,
    }
    text = None
    if body_model is not None:
        with open(body_model, encoding="utf-8") as f:
            text = f.read()
    return json.loads(_flexrig.safety_json(json.dumps(data, allow_nan=True), text))
