"""The Python twins of the study and tool commands (``flexrig eta``, ``eta-map``, ``eta-rotor``,
``experiment``, ``payload``, ``prb``, ``fit``, ``beam modal``, ``beam static``, ``validate``) and
the general lumped impact (``flexrig impact`` with every input and method).

Each takes the command's flags as keyword arguments (snake_case, SI units), checks them with the
same library functions and returns a :class:`Report`: ``data`` is the dict that ``flexrig COMMAND
--json`` prints for the same inputs, with the same numbers; ``table`` its rows as a pandas
DataFrame; ``figures`` the SVG text of each figure. Files are written into ``out`` when it is
given, otherwise into a temporary directory that is removed (``data``'s paths then name files
that are gone).
"""

from __future__ import annotations

import os
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _flexrig
from ._checks import _count, _flag, _input_error, _number, _numbers, _range, _word
from ._flexrig import InputError

PathLike = Union[str, "os.PathLike[str]"]

#: The default relative tolerance of the ode method of :func:`impact` (``flexrig impact --rtol``).
DEFAULT_RTOL: float = _flexrig.DEFAULT_RTOL


@dataclass(frozen=True, repr=False, eq=False)
class Report:
    """The result of a command twin.

    ``data``: the dict ``flexrig COMMAND --json`` prints for the same inputs (the same numbers;
    integers as int). Its keys are also attributes (``r.rows``, ``r.gamma``) and items
    (``r["rows"]``). ``table``: the command's rows as a pandas DataFrame (nested fields joined
    with ``_``, e.g. ``case_m_h``; integer columns int64), or None. ``figures``: the SVG text of
    each SVG figure the command drew, by file name (``{"eta.svg": "<svg ..."}``). ``files``: the
    files written into ``out`` (empty without ``out``).
    """

    command: str
    data: Dict[str, Any]
    table: Any = None
    figures: Dict[str, str] = field(default_factory=dict)
    files: List[str] = field(default_factory=list)

    def __getattr__(self, name: str) -> Any:
        data = self.__dict__.get("data", {})
        if name in data:
            return data[name]
        raise AttributeError(f"{type(self).__name__} of {self.__dict__.get('command', '?')} has no {name!r}")

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def keys(self):
        return self.data.keys()

    def __repr__(self) -> str:
        shape = "" if self.table is None else f", table={self.table.shape[0]} rows"
        return f"Report({self.command}, keys={list(self.data)}{shape}, figures={list(self.figures)})"


class _Out:
    """``out`` as a directory, or a temporary one removed at the end."""

    def __init__(self, out: Optional[PathLike]):
        self.given = out is not None
        self._tmp = None if self.given else tempfile.TemporaryDirectory(prefix="flexrig-")
        self.path = os.path.abspath(os.fspath(out)) if self.given else self._tmp.name  # type: ignore[union-attr]

    def __enter__(self) -> "_Out":
        return self

    def __exit__(self, *exc: Any) -> None:
        if self._tmp is not None:
            self._tmp.cleanup()

    def collect(self) -> Tuple[Dict[str, str], List[str]]:
        """(SVG text by file name, files written when ``out`` was given)."""
        figures: Dict[str, str] = {}
        files: List[str] = []
        if os.path.isdir(self.path):
            for name in sorted(os.listdir(self.path)):
                full = os.path.join(self.path, name)
                if name.endswith(".svg") and os.path.isfile(full):
                    figures[name] = Path(full).read_text(encoding="utf-8")
                if self.given:
                    files.append(full)
        return figures, files


def _figure_args(size: Any, format: Any, dpi: Any) -> Tuple[str, List[str], float]:
    size = str(size) if isinstance(size, (int, np.integer)) and not isinstance(size, bool) else _word("size", size)
    formats = [format] if isinstance(format, str) else list(format)
    return size, [_word("format", f) for f in formats], float(_number("dpi", dpi))  # type: ignore[arg-type]


def _table(rows: Any) -> Any:
    import pandas as pd

    if not rows:
        return pd.DataFrame()
    return pd.json_normalize(rows, sep="_")


def _report(command: str, data: Dict[str, Any], rows_key: Optional[str], out: _Out) -> Report:
    figures, files = out.collect()
    table = None if rows_key is None else _table(data.get(rows_key))
    return Report(command=command, data=data, table=table, figures=figures, files=files)


def _damping(damping: Any, restitution: Any, c_max: Any, depth: Any) -> Tuple[str, Any, Any, Any]:
    return (
        _word("damping", damping),
        _number("restitution", restitution, True),
        _number("c_max", c_max, True),
        _number("depth", depth, True),
    )


def _design(m_r: Any, k_c: Any, v0: Any) -> Tuple[float, float, float]:
    return float(_number("m_r", m_r)), float(_number("k_c", k_c)), float(_number("v0", v0))  # type: ignore[arg-type]


def _cases(m_h: Any, k_delta: Any, m_e: Any) -> Tuple[List[float], List[float], List[float]]:
    return _numbers("m_h", m_h), _numbers("k_delta", k_delta), _numbers("m_e", m_e)


def eta(
    *,
    out: Optional[PathLike] = None,
    joint: str = "held",
    rotor_inertia: Optional[float] = None,
    method: str = "modal",
    tol: Optional[float] = None,
    zone_elements: Optional[float] = None,
    window_periods: Optional[float] = None,
    elements: Optional[int] = None,
    steps_per_contact: Optional[int] = None,
    modes: Optional[int] = None,
    length: float = 1.0,
    damping: str = "none",
    restitution: Optional[float] = None,
    c_max: Optional[float] = None,
    depth: Optional[float] = None,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
    m_r: float = 10.0,
    k_c: float = 1e8,
    v0: float = 2.0,
    m_h: Union[float, Sequence[float]] = (4.0, 1000.0),
    k_delta: Union[float, Sequence[float]] = (1e8, 2e2),
    m_e: Union[float, Sequence[float]] = (0.1, 10.0),
) -> Report:
    """The Fig. 6 cases at finite-element fidelity, as ``flexrig eta``: the FE compliant link and
    the rigid compliant joint against a free head, η_FE beside the lumped η(2/3), the effective
    γ. ``joint`` held or free-hub (with ``rotor_inertia`` [kg·m²]); ``method`` modal (``tol``,
    ``zone_elements``, ``window_periods`` [first-mode periods]) or alpha (``elements``,
    ``steps_per_contact``, ``modes``); ``length`` [m]; ``damping`` none, hunt-crossley,
    lankarani-nikravesh (``restitution``) or adams-impact (``c_max`` [N·s/m], ``depth`` [m]).
    The design held fixed: link mass ``m_r`` [kg], contact stiffness ``k_c`` [N/mⁿ], approach
    speed ``v0`` [m/s]; the cases: every combination of head masses ``m_h`` [kg], link lateral
    stiffnesses ``k_delta`` [N/m] and payloads ``m_e`` [kg] (one to four values each); the
    paper's (§V) by default. ``table``: one row per (case, n) (``case_m_h``, ``f_cj_n``,
    ``f_cl_n``, ``eta_fe``, …); ``figures``: eta.svg and eta_fig6.svg.
    """
    model, e, c, d = _damping(damping, restitution, c_max, depth)
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.eta(
            o.path, _word("joint", joint), _number("rotor_inertia", rotor_inertia, True), _word("method", method),
            _number("tol", tol, True), _number("zone_elements", zone_elements, True),
            _number("window_periods", window_periods, True), _count("elements", elements, True),
            _count("steps_per_contact", steps_per_contact, True), _count("modes", modes, True),
            _number("length", length), model, e, c, d, size, formats, dpi,
            _design(m_r, k_c, v0), _cases(m_h, k_delta, m_e),
        )
        return _report("eta", data, "rows", o)


def eta_map(
    *,
    out: Optional[PathLike] = None,
    m_h: Union[float, Sequence[float]] = (4.0, 1000.0),
    n: float = 2.0,
    mass_ratio: Union[str, Tuple[float, float]] = "1e-3:1e2",
    stiffness_ratio: Union[str, Tuple[float, float]] = "1e-7:1",
    points: int = 30,
    joint: str = "held",
    rotor_inertia: Optional[float] = None,
    tol: float = 1e-5,
    damping: str = "none",
    restitution: Optional[float] = None,
    c_max: Optional[float] = None,
    depth: Optional[float] = None,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
    m_r: float = 10.0,
    k_c: float = 1e8,
    v0: float = 2.0,
    length: float = 1.0,
) -> Report:
    """Maps of η_FE, the lumped and placed models' errors and the effective γ over m_e/m_r ×
    k_δ/k_c, as ``flexrig eta-map``: one map per head mass ``m_h`` [kg], Hertz exponent ``n``,
    ranges ``mass_ratio`` and ``stiffness_ratio`` (``"FROM:TO"`` or a pair, log-spaced),
    ``points`` along each axis, ``tol`` of the modal method; joint and damping as :func:`eta`;
    the design held fixed ``m_r`` [kg], ``k_c`` [N/mⁿ], ``v0`` [m/s] (the axes are m_e and k_δ
    as ratios to m_r and k_c) and the link ``length`` [m], the paper's by default.
    ``table``: one summary row per map (``m_h_kg``, ``points``, ``failed``, ``seconds``, …);
    the grid itself is eta_map.csv in ``out``.
    """
    model, e, c, d = _damping(damping, restitution, c_max, depth)
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.eta_map(
            o.path, _numbers("m_h", m_h), _number("n", n), _range("mass_ratio", mass_ratio),
            _range("stiffness_ratio", stiffness_ratio), _count("points", points), _word("joint", joint),
            _number("rotor_inertia", rotor_inertia, True), _number("tol", tol), model, e, c, d, size, formats, dpi,
            _design(m_r, k_c, v0), _number("length", length),
        )
        return _report("eta-map", data, "maps", o)


def eta_rotor(
    *,
    out: Optional[PathLike] = None,
    ratio: Union[str, Tuple[float, float]] = "1e-4:1e6",
    points: int = 21,
    n: Union[float, Sequence[float]] = (1.0, 2.0),
    tol: float = 1e-6,
    damping: str = "none",
    restitution: Optional[float] = None,
    c_max: Optional[float] = None,
    depth: Optional[float] = None,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
    m_r: float = 10.0,
    k_c: float = 1e8,
    v0: float = 2.0,
    length: float = 1.0,
    m_h: Union[float, Sequence[float]] = (4.0, 1000.0),
    k_delta: Union[float, Sequence[float]] = (1e8, 2e2),
    m_e: Union[float, Sequence[float]] = (0.1, 10.0),
) -> Report:
    """η_FE of the Fig. 6 cases along the free hub's rotor inertia J_R/(m_r L²/3) (``ratio``,
    ``"FROM:TO"`` or a pair, ``points`` log-spaced, the held joint added as the limit), for the
    Hertz exponents ``n``, as ``flexrig eta-rotor``; design (``m_r``, ``k_c``, ``v0``), link
    ``length`` [m] and cases (``m_h``, ``k_delta``, ``m_e``) as :func:`eta`. ``table``: one row per point (``case_m_h``,
    ``n``, ``inertia_ratio`` (NaN: held), ``eta_fe``, …); ``figures``: eta_rotor.svg.
    """
    model, e, c, d = _damping(damping, restitution, c_max, depth)
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.eta_rotor(
            o.path, _range("ratio", ratio), _count("points", points), _numbers("n", n), _number("tol", tol),
            model, e, c, d, size, formats, dpi, _design(m_r, k_c, v0), _number("length", length),
            _cases(m_h, k_delta, m_e),
        )
        return _report("eta-rotor", data, "points", o)


def experiment(
    *,
    out: Optional[PathLike] = None,
    repeats: int = 5,
    jitter_deg: float = 0.5,
    seed: int = 1,
    scenes: Optional[PathLike] = None,
    overrides: Optional[Mapping[str, Any]] = None,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
    **kwargs: Any,
) -> Report:
    """The paper's §VI experiment replayed (Fig. 9), as ``flexrig experiment``: CJ and CL with
    two operators, ``repeats`` each with release-angle jitter (standard deviation
    ``jitter_deg`` [deg], RNG ``seed``), and the light-load case; an MCAP log per run. ``scenes``:
    a directory of scene files used instead of the bundled ones; overrides of every scene as in
    :func:`flexrig.run` (``overrides=`` or keyword arguments, like ``--set``). ``table``: one
    row per run (``runs``); ``data`` also holds ``groups`` (mean peak ± 95 % CI per scene) and
    ``ratios`` (paired CL/CJ); ``figures``: fig9.svg.
    """
    from . import _overrides

    pairs = _overrides(overrides, kwargs)
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.experiment(
            o.path, _count("repeats", repeats), _number("jitter_deg", jitter_deg), _count("seed", seed),
            None if scenes is None else os.fspath(scenes), pairs, size, formats, dpi,
        )
        return _report("experiment", data, "runs", o)


def payload(
    *,
    out: Optional[PathLike] = None,
    scene: PathLike = "cl_light_load",
    payloads: str = "0.01:1",
    points: int = 25,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
) -> Report:
    """The test bed's CL/CJ peak ratio over the payload, as ``flexrig payload``: ``scene`` (a
    bundled scene's name or a scene file's path, as ``--scene``) run as CJ and as CL at the payloads [kg] of ``payloads`` (as ``--payloads``:
    ``"FROM:TO"`` with ``points`` of them, or ``"FROM:TO:N:log"``), log-spaced, with MCAP logs
    of three of them. ``table``: ``payload_kg``,
    ``cj_peak_n``, ``cl_peak_n``, ``ratio``; ``figures``: payload.svg.
    """
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.payload(
            o.path, _word("scene", os.fspath(scene) if isinstance(scene, os.PathLike) else scene),
            _word("payloads", payloads), _count("points", points),
            size, formats, dpi,
        )
        return _report("payload", data, "rows", o)


def prb(
    *,
    out: Optional[PathLike] = None,
    elements: int = 32,
    model: str = "ancf",
    criterion: str = "deflection",
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
) -> Report:
    """The Pseudo-Rigid-Body model (γ, K_Θ) against the large-deflection FE cantilever, as
    ``flexrig prb``: ``elements`` (4 to 256), ``model`` ancf or corotational, ``criterion``
    deflection or length. ``data``: ``gamma``, ``k_theta``, ``theta_max_deg``, the other
    criterion's fit, the published values, the spring stiffness and the effective mass;
    ``figures``: prb.svg.
    """
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.prb(
            o.path, _count("elements", elements), _word("model", model), _word("criterion", criterion),
            size, formats, dpi,
        )
        return _report("prb", data, None, o)


def fit(file: PathLike) -> Report:
    """The least-squares Hertz fit f = k δⁿ of compression data, as ``flexrig fit FILE``:
    ``file`` a CSV with the header ``indentation_m,force_n`` (m, N). ``data``: ``k`` [N/mⁿ],
    ``n``, ``r2``, ``k_stderr``, ``n_stderr``, ``rms_residual_n`` [N], ``points``, ``skipped``,
    ``iterations``.
    """
    data = _flexrig.fit(os.fspath(file))
    return Report(command="fit", data=data)


def _beam_args(scene: Any, length: Any, youngs: Any, density: Any, width: Any, thickness: Any,
               elements: Any, tip_mass: Any, root: Any, k_theta: Any) -> Tuple[Any, ...]:
    return (
        None if scene is None else os.fspath(scene),
        _number("length", length, True), _number("youngs", youngs, True),
        _number("density", density, True), _number("width", width, True),
        _number("thickness", thickness, True), _count("elements", elements, True),
        _number("tip_mass", tip_mass, True), _word("root", root), _number("k_theta", k_theta),
    )


def beam_modal(
    *,
    scene: Optional[PathLike] = None,
    length: Optional[float] = None,
    youngs: Optional[float] = None,
    density: Optional[float] = None,
    width: Optional[float] = None,
    thickness: Optional[float] = None,
    elements: Optional[int] = None,
    tip_mass: Optional[float] = None,
    root: str = "clamped",
    k_theta: float = 0.0,
    modes: int = 4,
) -> Report:
    """The natural frequencies of the FE Euler–Bernoulli cantilever, as ``flexrig beam modal``:
    ``length`` [m], ``youngs`` [Pa], ``density`` [kg/m³], ``width`` and ``thickness`` [m]
    (I = w t³/12), ``elements`` (default 16), ``tip_mass`` [kg] (default 0), ``root`` clamped or
    pinned (with ``k_theta`` [N·m/rad]), ``modes``. ``scene`` (a bundled scene's name or a scene
    file) takes the beam from the scene's robot link (length, E, ρ, section, its payload as the
    tip mass, its elements); the numbers given override it. ``data["frequencies_hz"]``
    (ascending), ``warnings``, ``scene``; ``table``: ``mode``, ``frequency_hz``.
    """
    import pandas as pd

    data = _flexrig.beam_modal(
        *_beam_args(scene, length, youngs, density, width, thickness, elements, tip_mass, root, k_theta),
        _count("modes", modes),
    )
    f = data["frequencies_hz"]
    table = pd.DataFrame({"mode": np.arange(1, len(f) + 1, dtype=np.int64), "frequency_hz": np.asarray(f, dtype=np.float64)})
    return Report(command="beam modal", data=data, table=table)


def beam_static(
    *,
    tip_load: float,
    scene: Optional[PathLike] = None,
    length: Optional[float] = None,
    youngs: Optional[float] = None,
    density: Optional[float] = None,
    width: Optional[float] = None,
    thickness: Optional[float] = None,
    elements: Optional[int] = None,
    tip_mass: Optional[float] = None,
    root: str = "clamped",
    k_theta: float = 0.0,
    tip_moment: float = 0.0,
    model: str = "linear",
    load_steps: int = 10,
    adaptive_steps: bool = False,
    yield_strength: Optional[float] = None,
) -> Report:
    """The tip displacement and largest stress of the FE cantilever under a dead tip load, as
    ``flexrig beam static``: the beam as :func:`beam_modal` (``density`` is not needed),
    ``tip_load`` [N] perpendicular to the undeformed beam, ``tip_moment`` [N·m], ``model``
    linear, corotational or ancf, ``load_steps``, ``adaptive_steps`` (the first increment
    1/``load_steps`` of the load, halved where Newton fails, doubled after each converged one;
    the same equilibrium in fewer iterations), ``yield_strength`` [Pa] (a warning when the
    largest stress exceeds it). ``data``: ``tip_u_m``, ``tip_v_m``, ``tip_angle_rad``,
    ``iterations``, ``residual_n``, ``load_level``, ``max_stress_pa`` and ``max_stress``
    (``stress_pa``, ``bending_pa``, ``axial_pa``, ``moment_nm``, ``axial_force_n``, ``at_m``:
    where, from the root), ``warnings``, ``scene``.
    """
    data = _flexrig.beam_static(
        *_beam_args(scene, length, youngs, density, width, thickness, elements, tip_mass, root, k_theta),
        _number("tip_load", tip_load), _number("tip_moment", tip_moment), _word("model", model),
        _count("load_steps", load_steps), _flag("adaptive_steps", adaptive_steps),
        _number("yield_strength", yield_strength, True),
    )
    return Report(command="beam static", data=data)


def validate(*, quick: bool = False, out: Optional[PathLike] = None) -> Report:
    """The verification suite against every reference, as ``flexrig validate`` (``quick``: without
    its slowest cases). ``table``: one row per case (``name``, ``value``, ``reference``,
    ``error``, ``tolerance``, ``pass``); failing cases are rows, not an exception (the CLI exits
    with code 1). Writes validation.md into ``out``.
    """
    if not isinstance(quick, (bool, np.bool_)):
        raise _input_error("quick", f"invalid argument quick = {quick!r}: must be True or False")
    with _Out(out) as o:
        data = _flexrig.validate(bool(quick), o.path)
        return _report("validate", data, "cases", o)


def bench(
    *,
    quick: bool = False,
    out: Optional[PathLike] = None,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
) -> Report:
    """The work–precision studies, as ``flexrig bench`` (``quick``: fewer settings and
    repetitions, well under a minute): the lumped impact's integrators (and the scipy peer when
    its interpreter has numpy and scipy: ``FLEXRIG_PYTHON``, else the project's ``.venv``, else
    ``python3``; ``data["peer_python"]`` names it), the beam, the rig, the driven strike and the
    safety maps.
    ``table``: one row per measured point — ``model``, ``method``, ``setting``, ``error`` against
    the study's reference (the same numbers as the CLI's), ``seconds`` (median run time on this
    machine: a timing, not a result) and ``evaluations`` (Int64, time integrations only).
    ``data["scipy_dop853_over_flexrig_at_1e_9"]``: the peer's run time over flexrig's (absent
    when the peer could not run). ``figures``: bench_lumped.svg, bench_beam.svg, bench_rig.svg.
    """
    if not isinstance(quick, (bool, np.bool_)):
        raise _input_error("quick", f"invalid argument quick = {quick!r}: must be True or False")
    size, formats, dpi = _figure_args(size, format, dpi)
    with _Out(out) as o:
        data = _flexrig.bench(bool(quick), o.path, size, formats, dpi)
        report = _report("bench", data, "rows", o)
    columns = ["model", "method", "setting", "error", "seconds", "evaluations"]
    table = report.table.reindex(columns=columns)
    table["evaluations"] = table["evaluations"].astype("Int64")
    return Report(command="bench", data=report.data, table=table, figures=report.figures, files=report.files)


#: The numbers of ``flexrig impact --json`` that :func:`impact` returns as arrays (or floats),
#: beyond the method's name and formulation.
IMPACT_FIELDS: Tuple[str, ...] = (
    "m_h_kg", "m_eff_kg", "mu_kg", "impact_energy_j", "f_max_n", "delta_max_m", "indentation_max_m",
    "link_deflection_max_m", "k_o_n_per_m", "t_peak_s", "contact_duration_s", "separation_speed_mps",
    "rtol", "rhs_evals", "steps", "rejected_steps",
)

_INTEGER_FIELDS = ("rhs_evals", "steps", "rejected_steps")


@dataclass(frozen=True, repr=False, eq=False)
class ImpactReport:
    """The lumped impact by any method, as ``flexrig impact --json``: one attribute per key of the
    report (floats for scalar inputs, arrays of the broadcast shape otherwise; counts as int or
    int64), ``None`` for what the method does not give (``k_o_n_per_m`` only for analytic,
    ``rhs_evals``/``steps``/``rejected_steps``/``separation_speed_mps``/``rtol`` only for ode).

    Units: masses [kg], energy [J], force [N], lengths [m], times [s], speed [m/s], k_o [N/m].
    """

    method: str
    #: The ode method's state variables used (``indentation`` or ``displacement``; per set for
    #: arrays, ``auto`` resolved), else None.
    formulation: Any
    m_h_kg: Any
    m_eff_kg: Any
    mu_kg: Any
    impact_energy_j: Any
    f_max_n: Any
    delta_max_m: Any
    indentation_max_m: Any
    link_deflection_max_m: Any
    k_o_n_per_m: Any = None
    t_peak_s: Any = None
    contact_duration_s: Any = None
    separation_speed_mps: Any = None
    rtol: Any = None
    rhs_evals: Any = None
    steps: Any = None
    rejected_steps: Any = None
    #: ode only: the severity of the impact (dict, or an object array of dicts per set).
    severity: Any = None

    def __repr__(self) -> str:
        return f"ImpactReport(method={self.method!r}, f_max_n={self.f_max_n!r})"


def impact_report(
    m_h: Any,
    m_eff: Any = None,
    k_delta: Any = None,
    k_c: Any = None,
    n: Any = None,
    v0: Any = None,
    *,
    gamma: Any = None,
    m_r: Any = None,
    m_e: Any = None,
    method: str = "exact",
    formulation: str = "auto",
    rtol: float = DEFAULT_RTOL,
    dome_radius: Optional[float] = None,
) -> ImpactReport:
    """The body of :func:`flexrig.impact` for PRB masses or the analytic/ode methods."""
    method = _word("method", method)
    formulation = _word("formulation", formulation)
    rtol_f = _number("rtol", rtol)
    dome = _number("dome_radius", dome_radius, optional=True)
    names = ["m_h", "m_eff", "gamma", "m_r", "m_e", "k_delta", "k_c", "n", "v0"]
    given = dict(zip(names, (m_h, m_eff, gamma, m_r, m_e, k_delta, k_c, n, v0)))
    for name in ("k_delta", "k_c", "n", "v0"):
        if given[name] is None:
            raise _input_error(name, f"{name}: missing (a number or an array of numbers)")
    arrays: Dict[str, np.ndarray] = {}
    for name, value in given.items():
        if value is None:
            continue
        try:
            arrays[name] = np.asarray(value, dtype=np.float64)
        except (TypeError, ValueError, OverflowError) as e:
            raise _input_error(name, f"{name}: not a number or an array of numbers ({e})") from None
    try:
        shaped = dict(zip(arrays, np.broadcast_arrays(*arrays.values())))
    except ValueError:
        shapes = ", ".join(f"{k} {a.shape}" for k, a in arrays.items())
        raise _input_error("m_h", f"the arguments do not broadcast to one shape: {shapes}") from None
    shape = next(iter(shaped.values())).shape
    flat = {k: np.ascontiguousarray(a).reshape(-1) for k, a in shaped.items()}
    size = int(np.prod(shape)) if shape else 1
    reports = []
    for i in range(size):
        x = {k: float(a[i]) for k, a in flat.items()}
        try:
            reports.append(
                _flexrig.impact_report(
                    x["m_h"], x.get("m_eff"), x.get("gamma"), x.get("m_r"), x.get("m_e"), x["k_delta"],
                    x["k_c"], x["n"], x["v0"], method, formulation, rtol_f, dome,
                )
            )
        except InputError as e:
            if shape == () or getattr(e, "field", "") in ("method", "formulation", "rtol", "m_eff", "dome_radius"):
                raise
            name = getattr(e, "field", "")
            raise _input_error(f"{name}[{i}]", str(e).replace(f"{name} =", f"{name}[{i}] =", 1)) from None
    first = reports[0]
    values: Dict[str, Any] = {"method": first["method"], "formulation": None}
    if "formulation" in first:
        used = [r["formulation"] for r in reports]
        values["formulation"] = used[0] if shape == () else np.asarray(used, dtype=object).reshape(shape)
    for key in IMPACT_FIELDS:
        if key not in first:
            continue
        column = [r[key] for r in reports]
        dtype = np.int64 if key in _INTEGER_FIELDS else np.float64
        if shape == ():
            values[key] = int(column[0]) if dtype is np.int64 else float(column[0])
        else:
            values[key] = np.asarray(column, dtype=dtype).reshape(shape)
    if "severity" in first:
        severities = [r["severity"] for r in reports]
        if shape == ():
            values["severity"] = severities[0]
        else:
            column = np.empty(size, dtype=object)
            column[:] = severities
            values["severity"] = column.reshape(shape)
    return ImpactReport(**values)
