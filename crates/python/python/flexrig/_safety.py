"""``flexrig.safety``: the permissible speed near a body region (ISO/TS 15066), the twin of
``flexrig safety --json`` with the same arguments (the flags in snake_case, SI units)."""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Optional, Sequence, Union

from . import _flexrig
from ._checks import _finite, _input_error, _word

#: Largest body-model file read, bytes (the command line's bound; the bundled table is about 10 kB).
_MAX_BODY_MODEL_BYTES = 1 << 20


def _body_model_text(body_model: Any) -> Optional[str]:
    """The TOML text of the ``body_model`` file, read up to the command line's bound (a device
    such as /dev/zero or a huge file is refused without reading it all)."""
    if body_model is None:
        return None
    with open(body_model, "rb") as f:
        data = f.read(_MAX_BODY_MODEL_BYTES + 1)
    if len(data) > _MAX_BODY_MODEL_BYTES:
        raise _input_error(
            "body_model",
            f"invalid argument body_model = {os.fspath(body_model)!r}: longer than "
            f"{_MAX_BODY_MODEL_BYTES} bytes (a body-model table is expected; the bundled one is "
            "about 10 kB)",
        )
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data[: e.start].count(b"\n") + 1
        raise _input_error(
            "body_model",
            f"invalid argument body_model = {os.fspath(body_model)!r}: not UTF-8 text (line "
            f"{line}, byte offset {e.start})",
        ) from None


def _methods(method: Any) -> list:
    """The methods as a list of words (a str with commas, or a sequence of str)."""
    items = [method] if isinstance(method, str) else method
    try:
        items = list(items)
    except TypeError:
        raise _input_error("method", f"invalid argument method = {method!r}: a str such as 'standard,energy' or a list of str") from None
    words = [m for part in items for m in _word("method", part).split(",")]
    if any(not w.strip() for w in words):
        raise _input_error("method", f"invalid argument method = {method!r}: an empty item in the list (a stray comma)")
    return words


def _contact_law(k_c: Optional[float], n: Optional[float], material: Optional[str]) -> Any:
    """The contact law of ``k_c`` and ``n`` (together), or ``material``, or the body's spring."""
    if (k_c is None) != (n is None):
        raise _input_error("k_c", "k_c and n go together (f = k_c δ^n)")
    if k_c is not None:
        if material is not None:
            raise _input_error("material", "give either k_c and n or material")
        return {"hertz": {"k_c": k_c, "n": n}}
    if material is not None:
        return {"material": material}
    return "body_spring"


def _area_m2(contact_area: Union[None, float, str]) -> Optional[float]:
    """``contact_area`` in m²: a number is m² (SI, as every keyword), a string carries its unit
    (``"1cm2"``, ``"1e-4m2"``, ``"100mm2"``, read as ``--contact-area`` reads it)."""
    if contact_area is None:
        return None
    if isinstance(contact_area, str):
        return _flexrig.parse_area(contact_area)
    if isinstance(contact_area, bool) or not isinstance(contact_area, (int, float)):
        raise _input_error("contact_area", f"invalid argument contact_area = {contact_area!r}: a number (m²) or a string with its unit such as '1cm2'")
    return float(contact_area)


def _area_model(
    area_model: Optional[str], radius: Optional[float], contact_area: Union[None, float, str]
) -> Optional[Dict[str, Any]]:
    """The contact-area model of ``area_model`` with the ``radius`` or ``contact_area`` it needs;
    without ``area_model``, the Hertz sphere of ``radius`` or the fixed ``contact_area`` (as the
    command line)."""
    area = _area_m2(contact_area)
    if area_model is None:
        if radius is not None and area is not None:
            raise _input_error("area_model", "radius and contact_area together need area_model to say which model")
        if radius is not None:
            return {"model": "hertz_sphere", "radius_m": radius}
        if area is not None:
            return {"model": "fixed", "area_m2": area}
        return None
    kind = area_model.replace("-", "_")
    if kind in ("hertz_sphere", "thin_layer") and area is not None:
        raise _input_error("contact_area", f"area_model {area_model} does not use contact_area: leave it out")
    if kind == "fixed" and radius is not None:
        raise _input_error("radius", "area_model fixed does not use radius: leave it out")
    if kind in ("hertz_sphere", "thin_layer"):
        if radius is None:
            raise _input_error("radius", f"area_model {area_model} needs radius (m)")
        return {"model": kind, "radius_m": radius}
    if kind == "fixed":
        if area is None:
            raise _input_error("contact_area", "area_model fixed needs contact_area (m², or a string with its unit such as '1cm2')")
        return {"model": "fixed", "area_m2": area}
    raise _input_error("area_model", f"unknown area_model {area_model!r}: hertz_sphere, thin_layer or fixed")


def safety(
    region: str,
    *,
    scene: Optional[Union[str, "os.PathLike[str]"]] = None,
    area: Optional[str] = None,
    contact: Optional[str] = None,
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
    contact_area: Union[None, float, str] = None,
    moving_mass: Optional[float] = None,
    payload: float = 0.0,
    speed: Optional[float] = None,
    body_model: Optional[Union[str, "os.PathLike[str]"]] = None,
    method: Optional[Union[str, Sequence[str]]] = None,
    link: Optional[str] = None,
    joint: str = "held",
    rotor_inertia: Optional[float] = None,
    length: Optional[float] = None,
    tol: float = 1e-6,
    root_rtol: float = 1e-6,
    trace: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Dict[str, Any]:
    """The permissible speed of a design near ``region`` by the standard's formula
    (``"standard"``), the paper's energy method (``"energy"``) and the simulated finite-element
    impact of the safe-speed maps (``"simulation"``: ``link`` ``"cj"`` or ``"cl"``, default from
    ``gamma`` 1 or 2/3; ``joint`` ``"held"`` or ``"free_hub"`` with ``rotor_inertia`` in kg·m²;
    ``length`` in m (required with a free hub: the rotor acts at the contact as J_R/L²);
    ``tol`` of the CL's modal integrator; ``root_rtol`` of the root search on
    the speed): the dict of ``flexrig safety --json`` with the same numbers.

    Masses in kg (``m_eff``, or ``m_r``, ``m_e`` and ``gamma`` for m_eff = m_e + γ m_r/3;
    ``moving_mass`` and ``payload`` for the standard's m_R = M/2 + m_L), ``k_delta`` in N/m
    (None: rigid link), ``k_c`` in N/m^n with ``n`` (or ``material``; neither: the region's body
    spring, n = 1), ``area_model`` one of ``hertz_sphere``/``thin_layer`` (with ``radius`` in m)
    or ``fixed`` (with ``contact_area`` in m²), ``speed`` in m/s, ``contact`` ``transient`` or
    ``quasi_static``. Unbounded speeds are the word ``"unlimited"``; absent values are absent
    keys. Transient contact with skull/forehead or face raises ``InputError`` quoting the clause.

    ``scene`` (a bundled driven scene's name such as ``"driven_cl_wall"``, or the path of a scene
    file with a ``[drive]`` section) is the design instead of the mass, stiffness and contact-law
    keywords: the simulation method then searches the scene's commanded tip speed, a wall is
    quasi-static contact and a free head transient (``contact`` is not given with a scene), and
    ``method`` defaults to all three whenever the design is known (a scene, or ``m_r``, ``m_e``
    with ``link`` or ``gamma`` 1 or 2/3), else standard and energy; ``result["overall"]`` is the
    most restrictive of them, named. A test-bed scene
    (``"cj_aluminium"``, ``"cl_iron"``, …) is transient contact with the operator's block; the
    simulation method searches the operator's speed at contact through its release angle (up
    to 170°): ``result["scene"]`` then has ``release_angle_at_root_deg`` and ``limit_reached``
    (false: the limit is not reached on the test bed, and the speed is the largest it reaches).

    ``contact_area`` is in m² as a number, or a string with its unit (``"1cm2"``, ``"1e-4m2"``);
    ``radius`` alone means the Hertz sphere, ``contact_area`` alone the fixed area. An implausible
    area (above 100 cm², below 0.01 cm²) is listed under ``"warnings"`` and warned about
    (:class:`PlausibilityWarning`).

    ``trace`` (the path of a CSV file: a header naming each column with its unit, e.g.
    ``t [s], F [N], a [m/s^2], delta [mm]``, docs/safety.md) judges a **measured impact**
    instead of a design, as ``flexrig safety --trace FILE --json``: its severity (peak force,
    pressure with ``area_model``/``radius``/``contact_area``, transferred energy, HIC15/HIC36)
    and the verdict against ``region``'s limits (with ``area``, ``contact``, ``body_model``; the
    design keywords are then refused).
    """
    _word("region", region)
    for name, value in (
        ("m_eff", m_eff), ("m_r", m_r), ("m_e", m_e), ("gamma", gamma), ("k_delta", k_delta),
        ("k_c", k_c), ("n", n), ("radius", radius),
        ("moving_mass", moving_mass), ("payload", payload), ("speed", speed),
        ("rotor_inertia", rotor_inertia), ("length", length), ("tol", tol), ("root_rtol", root_rtol),
    ):
        _finite(name, value)
    if not isinstance(contact_area, str):
        # a number in m²; a string carries its unit ("2cm2") and is read by the library
        _finite("contact_area", contact_area)
    if trace is not None:
        return _safety_trace(
            trace, region, area=area, contact=contact, area_model=area_model, radius=radius,
            contact_area=contact_area, body_model=body_model,
            design=dict(scene=scene, m_eff=m_eff, m_r=m_r, m_e=m_e, gamma=gamma, k_delta=k_delta, k_c=k_c, n=n,
                        material=material, moving_mass=moving_mass, speed=speed, method=method, link=link,
                        rotor_inertia=rotor_inertia),
        )
    if scene is not None and contact is not None:
        raise _input_error("contact", "contact comes from the scene's support (a wall: quasi_static, a free head: transient)")
    if contact is None:
        contact = "transient"
    if link is not None and link not in ("cj", "cl"):
        raise _input_error("link", f"unknown link {link!r}: cj or cl")
    if gamma is None and link is not None:
        gamma = 1.0 if link == "cj" else 2.0 / 3.0
    if m_eff is not None:
        mass: Optional[Dict[str, Any]] = {"given": m_eff}
    elif m_r is not None or m_e is not None or gamma is not None:
        if m_r is None or m_e is None or gamma is None:
            raise _input_error("gamma", "m_r, m_e and gamma (or link) go together (m_eff = m_e + gamma m_r/3)")
        mass = {"prb": {"gamma": gamma, "m_r": m_r, "m_e": m_e}}
    else:
        mass = None
    law = _contact_law(k_c, n, material)
    model = _area_model(area_model, radius, contact_area)
    if method is None:
        method = ()
    methods = _methods(method)
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
        "link": link,
        "simulation": {
            "joint": _joint(joint, rotor_inertia),
            "length": length,
            "tol": tol,
            "cj_rtol": 1e-10,
            "root_rtol": root_rtol,
        },
    }
    if scene is not None:
        data["scene"] = os.fspath(scene)
    report = json.loads(_flexrig.safety_json(json.dumps(data, allow_nan=False), _body_model_text(body_model)))
    _warn(report)
    return report


def _warn(report: Dict[str, Any]) -> None:
    """Each of the report's warnings (named by keyword argument, as the extension reports them)
    as a :class:`PlausibilityWarning`."""
    import warnings

    from . import PlausibilityWarning

    for w in report.get("warnings", ()):
        warnings.warn(f"{w['field']}: {w['message']}", PlausibilityWarning, stacklevel=3)


def _safety_trace(
    trace: Union[str, "os.PathLike[str]"],
    region: str,
    *,
    area: Optional[str],
    contact: Optional[str],
    area_model: Optional[str],
    radius: Optional[float],
    contact_area: Union[None, float, str],
    body_model: Optional[Union[str, "os.PathLike[str]"]],
    design: Dict[str, Any],
) -> Dict[str, Any]:
    """``flexrig safety --trace FILE --json``: the measured impact of ``trace`` judged."""
    for name, value in design.items():
        if value is not None:
            raise _input_error(name, f"{name} describes a design: leave it out with trace (a measured impact)")
    data = {
        "trace": os.fspath(trace),
        "region": region,
        "area": area,
        "contact": (contact or "transient").replace("-", "_"),
        "area_model": _area_model(area_model, radius, contact_area),
    }
    report = json.loads(_flexrig.safety_trace_json(json.dumps(data, allow_nan=False), _body_model_text(body_model)))
    _warn(report)
    return report


def _joint(joint: str, rotor_inertia: Optional[float]) -> Any:
    """The simulation's joint as the library's JSON."""
    kind_of_joint = joint.replace("-", "_")
    if kind_of_joint == "held":
        if rotor_inertia is not None:
            raise _input_error("rotor_inertia", "rotor_inertia only with joint='free_hub'")
        return "held"
    if kind_of_joint == "free_hub":
        if rotor_inertia is None:
            raise _input_error("rotor_inertia", "joint='free_hub' needs rotor_inertia (kg·m², > 0)")
        return {"free_hub": {"rotor_inertia": rotor_inertia}}
    raise _input_error("joint", f"unknown joint {joint!r}: held or free_hub")


#: Names of the map's design parameters: the flag's name (and its snake_case twin) to the
#: library's.
_MAP_PARAMETERS = {
    "m-e": "payload",
    "m-r": "link_mass",
    "k-delta": "link_stiffness",
    "ei": "bending_stiffness",
    "k-c": "contact_stiffness",
}


def _axis(field: str, axis: Any) -> Dict[str, Any]:
    """An axis as the library's JSON: from ``"PARAM=FROM:TO:N[:log]"`` (parsed by the
    library, as the command line does) or from ``(PARAM, values)``."""
    if isinstance(axis, str):
        return {"text": axis}
    try:
        name, values = axis
    except (TypeError, ValueError):
        raise _input_error(field, f"{field}: give 'PARAM=FROM:TO:N[:log]' or (PARAM, values), not {axis!r}")
    key = str(name).replace("_", "-")
    if key in ("region", "body-region"):
        names = [values] if isinstance(values, str) else [str(v) for v in values]
        return {"text": "region=" + ",".join(names)}
    if key not in _MAP_PARAMETERS:
        raise _input_error(field, f"{field}: the parameter must be one of {', '.join(_MAP_PARAMETERS)}, not {name!r}")
    try:
        items = list(values)
    except TypeError:
        raise _input_error(field, f"{field}: the values must be a sequence of numbers, not {values!r}") from None
    return {"parameter": _MAP_PARAMETERS[key], "values": [_finite(field, v, False) for v in items]}


def safety_map(
    region: Optional[str] = None,
    *,
    x: Any = "m-e=0.01:5:30:log",
    y: Any = "k-delta=10:1e7:30:log",
    area: Optional[str] = None,
    contact: str = "transient",
    m_r: Optional[float] = None,
    m_e: Optional[float] = None,
    k_delta: Optional[float] = None,
    length: Optional[float] = None,
    k_c: Optional[float] = None,
    n: Optional[float] = None,
    material: Optional[str] = None,
    area_model: Optional[str] = None,
    radius: Optional[float] = None,
    contact_area: Optional[float] = None,
    method: str = "energy",
    joint: str = "held",
    rotor_inertia: Optional[float] = None,
    tol: float = 1e-6,
    root_rtol: float = 1e-6,
    speed: Optional[float] = None,
    body_model: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Dict[str, Any]:
    """The safe-speed map of ``flexrig safety-map`` (the same numbers, no files): the permissible
    speed of the compliant joint (CJ) and the compliant link (CL) over two design parameters.

    ``x`` and ``y`` are ``"PARAM=FROM:TO:N[:log]"`` (or ``"PARAM=V1,V2"``) or
    ``(PARAM, values)`` with PARAM one of ``m-e`` (payload, kg), ``m-r`` (link mass, kg),
    ``k-delta`` (N/m), ``ei`` (N·m², with ``length`` in m), ``k-c`` (N/m^n), or the body region
    (``"region=all"``, ``"region=chest,abdomen"`` or ``("region", ["chest", "abdomen"])``: each
    cell then has its region's limits, and ``region`` may be left out). ``method`` is
    ``"standard"``, ``"energy"`` or ``"simulation"`` (the FE CJ and modal CL; ``joint`` ``"held"``
    or ``"free_hub"`` with ``rotor_inertia``). The other arguments are those of
    :func:`flexrig.safety`.

    Returns a dict: ``x``, ``y`` (1-D NumPy arrays), the names ``x_parameter``, ``y_parameter``,
    and 2-D arrays indexed ``[iy, ix]``: ``v_max_cj_mps``, ``v_max_cl_mps``, ``ratio_cl_cj``,
    ``by_force_cj_mps``, ``by_force_cl_mps``, ``m_eff_cj_kg``, ``m_eff_cl_kg`` (NaN where a cell
    failed, ``inf`` where no limit bounds the speed; the simulation searches only the limit that
    governs, so a force speed where the pressure governs is NaN, and ``map`` gives it as
    ``{"at_least": v}``), ``errors`` (a list of the failed cells'
    messages), ``force_limit_n``, ``pressure_limit_pa`` (None: not assessed), ``region_name``,
    ``area``, ``seconds``, ``warnings`` (the plausibility warnings, each a dict of ``field`` and
    ``message``, also raised as :class:`PlausibilityWarning`: a mass above 200 kg, a length above
    5 m, a speed above 10 m/s) and ``map`` (the library's full result as a dict). Ctrl-C stops it
    (KeyboardInterrupt).
    """
    import numpy as np

    if region is not None:
        _word("region", region)
    _word("method", method)
    for name, value in (
        ("m_r", m_r), ("m_e", m_e), ("k_delta", k_delta), ("length", length), ("k_c", k_c),
        ("n", n), ("radius", radius), ("contact_area", contact_area),
        ("rotor_inertia", rotor_inertia), ("tol", tol), ("root_rtol", root_rtol), ("speed", speed),
    ):
        _finite(name, value)
    law = _contact_law(k_c, n, material)
    model = _area_model(area_model, radius, contact_area)
    joint_data = _joint(joint, rotor_inertia)
    data = {
        "region": region if region is not None else "",
        "area": area,
        "contact": contact.replace("-", "_"),
        "m_r": m_r,
        "m_e": m_e,
        "k_delta": k_delta,
        "law": law,
        "area_model": model,
        "x": _axis("x", x),
        "y": _axis("y", y),
        "method": method,
        "simulation": {
            "joint": joint_data,
            "length": length,
            "tol": tol,
            "cj_rtol": 1e-10,
            "root_rtol": root_rtol,
        },
        "speed": speed,
    }
    text = _body_model_text(body_model)
    result = json.loads(_flexrig.safety_map_json(json.dumps(data, allow_nan=False), text))
    _warn(result)
    xs = np.asarray(result["input"]["x"]["values"], dtype=float)
    ys = np.asarray(result["input"]["y"]["values"], dtype=float)
    shape = (len(ys), len(xs))

    def speed_of(value: Any) -> float:
        # a limit that does not govern, not searched by the simulation: {"at_least": v}
        if isinstance(value, dict):
            return float("nan")
        return float("inf") if value == "unlimited" else float(value)

    def grid(design: str, key: str) -> Any:
        out = np.full(shape, np.nan)
        for i, cell in enumerate(result["cells"]):
            if design in cell:
                value = cell[design][key]
                out.flat[i] = speed_of(value) if key.endswith("_mps") else float(value)
        return out

    ratio = np.full(shape, np.nan)
    for i, cell in enumerate(result["cells"]):
        if "ratio_cl_cj" in cell:
            ratio.flat[i] = cell["ratio_cl_cj"]
    return {
        "x": xs,
        "y": ys,
        "x_parameter": result["input"]["x"]["parameter"],
        "y_parameter": result["input"]["y"]["parameter"],
        "x_names": result["input"]["x"].get("names", []),
        "y_names": result["input"]["y"].get("names", []),
        "v_max_cj_mps": grid("cj", "v_max_mps"),
        "v_max_cl_mps": grid("cl", "v_max_mps"),
        "ratio_cl_cj": ratio,
        "by_force_cj_mps": grid("cj", "by_force_mps"),
        "by_force_cl_mps": grid("cl", "by_force_mps"),
        "m_eff_cj_kg": grid("cj", "m_eff_kg"),
        "m_eff_cl_kg": grid("cl", "m_eff_kg"),
        "errors": [cell["error"] for cell in result["cells"] if "error" in cell],
        "force_limit_n": result["force_limit_n"],
        "pressure_limit_pa": result.get("pressure_limit_pa"),
        "region_name": result["region_name"],
        "area": result["area"],
        "seconds": result["seconds"],
        "warnings": result["warnings"],
        "map": result,
    }
