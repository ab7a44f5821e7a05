"""flexrig: the drop-pendulum impact test bed (compliant joint vs compliant link) from Python.

A run, its summary as attributes and its traces as NumPy arrays::

    import flexrig
    r = flexrig.run("cj_aluminium", **{"robot.payload_kg": 0.2})
    print(r.peak_force_n, r.time_s.shape, r.force_n.max())

A sweep into a pandas DataFrame (one row per run, the same table as ``flexrig sweep``)::

    df = flexrig.sweep("cj_iron", {"operator.start.release_angle_deg": "10:60:11",
                                   "robot.design": ["cj", "cl"]})
    df.to_parquet("sweep.parquet")        # needs pyarrow

The same sweep farmed out to a Dask cluster (``dask.distributed.Client``; dask-jobqueue reaches
Slurm/PBS)::

    df = flexrig.sweep(base, grid, client=client)

The lumped two-mass impact, vectorised over NumPy arrays (exact energy method), and the paper's
Fig. 6::

    peaks = flexrig.impact(4.0, m_eff, 1e8, 1e8, 2.0, np.linspace(0.5, 3, 1000))
    fig = flexrig.fig6()

Scenes are given as a path (str or os.PathLike), the name of a bundled scene
(``flexrig.bundled_scenes()``), TOML text, or a dict of the scene's tables (docs/scenes.md).

Overrides set scene fields by dotted path, exactly like ``flexrig run --set PATH=VALUE``; the
value is checked like one in the file. Give them as keyword arguments whose name is the path,
either spelled out with ``**{"robot.payload_kg": 0.2}`` or with ``__`` for each dot
(``robot__payload_kg=0.2``), or as a mapping ``overrides={"robot.payload_kg": 0.2}``; a keyword
wins over the same path in the mapping. A value is a bool, int, float, str, dict (a TOML table)
or list (a TOML array). A dict value replaces the whole table at its path.

Bad input (an unknown override path, a value of the wrong type or out of range, an empty grid)
raises :class:`InputError`, a ``ValueError`` whose message names the field and whose ``field``
attribute holds it. A run that cannot finish raises :class:`SimulationError` (a
``RuntimeError``); inside a sweep it is a row with status ``error`` and its message instead.
Runs release the GIL; Ctrl-C stops them.
"""

from __future__ import annotations

import os
import warnings as _warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Dict, List, Mapping, NamedTuple, Optional, Sequence, Tuple, Union

import numpy as np

from . import _flexrig
from ._commands import (
    DEFAULT_RTOL,
    IMPACT_FIELDS,
    ImpactReport,
    Report,
    beam_modal,
    bench,
    beam_static,
    eta,
    eta_map,
    eta_rotor,
    experiment,
    fit,
    payload,
    prb,
    validate,
)
from ._checks import _check_count, _count, _input_error, _number, _word
from ._commands import impact_report as _impact_report
from ._safety import safety, safety_map
from ._arm import ARM_COLUMNS, arm
from ._flexrig import (
    INTEGER_SUMMARY_COLUMNS as _INTEGER_SUMMARY_COLUMNS,
    LINK_COLUMNS as _LINK_COLUMNS,
    SUMMARY_COLUMNS,
    InputError,
    SimulationError,
    Sweep,
    bundled_scenes,
    scene_descriptions,
    write_scene,
)

if TYPE_CHECKING:  # pragma: no cover
    import pandas

__version__: str = _flexrig.__version__

__all__ = [
    "ARM_COLUMNS",
    "DEFAULT_RTOL",
    "arm",
    "IMPACT_FIELDS",
    "ImpactPeaks",
    "ImpactReport",
    "INTEGER_SUMMARY_COLUMNS",
    "LINK_COLUMNS",
    "Report",
    "STRIKE_TRACE_COLUMNS",
    "beam_modal",
    "bench",
    "beam_static",
    "eta",
    "eta_map",
    "eta_rotor",
    "experiment",
    "fit",
    "payload",
    "prb",
    "validate",
    "InputError",
    "PlausibilityWarning",
    "RunResult",
    "SUMMARY_COLUMNS",
    "SimulationError",
    "Sweep",
    "TRACE_NAMES",
    "bundled_scenes",
    "fig6",
    "role_switch",
    "spin_up",
    "strike",
    "impact",
    "run",
    "safety",
    "safety_map",
    "scene_descriptions",
    "scene_text",
    "sweep",
    "write_scene",
]

#: The summary columns of a sweep that count (contacts, steps): pandas' nullable ``Int64``
#: (``<NA>`` for a failed run); the others are float64.
INTEGER_SUMMARY_COLUMNS: Tuple[str, ...] = tuple(_INTEGER_SUMMARY_COLUMNS)

#: The link quantities of a run's summary and a sweep's table (paper Eq. 1–3, 5): link mass
#: ``m_r_kg`` [kg], bending stiffness ``ei_n_m2`` [N·m²], lateral tip stiffness
#: ``k_delta_n_per_m`` [N/m], joint stiffness ``k_theta_r_nm_per_rad`` [N·m/rad] (the CL's
#: equivalent 3EI/L) and the mass ratio ``m_e_over_m_r``.
LINK_COLUMNS: Tuple[str, ...] = tuple(_LINK_COLUMNS)

#: A scene: a path, the name of a bundled scene, TOML text, or a dict of the scene's tables.
Scene = Union[str, "os.PathLike[str]", Mapping[str, Any]]

#: The names of the sample-rate traces (the virtual sensors), in order.
TRACE_NAMES: Tuple[str, ...] = (
    "time_s",
    "force_n",
    "indentation_m",
    "operator_accel_mps2",
    "load_accel_mps2",
    "operator_angle_rad",
    "robot_angle_rad",
    "link_tip_deflection_m",
)


class PlausibilityWarning(UserWarning):
    """A scene that is valid but looks like a mistake (a unit that looks wrong, a contact law
    outside its fit, a joint spring left behind by the link): the run goes on; the summary's
    ``warnings`` lists them (``field``, ``message``)."""


def _overrides(overrides: Optional[Mapping[str, Any]], keywords: Mapping[str, Any]) -> List[Tuple[str, Any]]:
    merged: Dict[str, Any] = {}
    if overrides is not None:
        if not isinstance(overrides, Mapping):
            raise _input_error(
                "overrides",
                f"overrides: must be a mapping of dotted scene path to value, not {type(overrides).__name__}",
            )
        for path, value in overrides.items():
            if not isinstance(path, str):
                raise _input_error("overrides", f"overrides: the path {path!r} is not a str")
            merged[path] = value
    for name, value in keywords.items():
        merged[name.replace("__", ".")] = value
    return list(merged.items())


def scene_text(scene: Scene, /, overrides: Optional[Mapping[str, Any]] = None, **kwargs: Any) -> str:
    """The TOML text of ``scene`` (a path, a bundled scene name, TOML text or a dict).

    With overrides, the text is validated and returned with them applied (as ``flexrig run
    --set`` would run it); an unknown path or a bad value raises :class:`InputError`.
    """
    text, _ = _flexrig.scene_text(scene)
    pairs = _overrides(overrides, kwargs)
    if not pairs:
        return text
    return _flexrig.apply_overrides(text, pairs)


@dataclass(frozen=True, repr=False, eq=False)
class RunResult:
    """The result of :func:`run`: the summary as attributes, the traces as NumPy arrays.

    The summary attributes are those of ``flexrig run --json`` (``summary`` holds that dict
    itself); quantities of the first contact; ``None`` where they do not apply (e.g.
    ``contact_duration_s`` for a run stopped at the peak). Units are in the names.

    The traces have two time bases:

    - ``traces`` (also as attributes ``time_s``, ``force_n``, ``indentation_m``,
      ``operator_accel_mps2``, ``load_accel_mps2``, ``operator_angle_rad``, ``robot_angle_rad``,
      ``link_tip_deflection_m``): the virtual sensors at the scene's ``record.sample_rate_hz``
      (force sensor, accelerometers along the strike direction, encoders; the indentation
      interpolated between step ends like the force), one float64 array each, all of one
      length, ``time_s`` strictly increasing from 0;
    - ``step_traces`` (``time_s``, ``dt_s``, ``force_n``, ``indentation_m``, ``energy_j``): one
      entry per integration step, contact values at the step end (0 outside contact), total
      mechanical energy.

    ``pandas.DataFrame(r.traces)`` makes a table of the sensor traces.

    A driven scene (one with a ``[drive]`` section, docs/scenes.md) has the driven strike's
    summary (``summary["kind"] == "driven"``: also ``pre_impact_deflection_m``,
    ``peak_motor_torque_nm``, ``motor_work_j``, ``notes``, …; the test bed's step counts and
    energies are ``None``) and its traces in ``traces``: ``time_s``, ``commanded_angle_rad`` and
    ``commanded_speed_rad_s`` (with a commanded motion), ``joint_angle_rad``,
    ``joint_speed_rad_s``, ``joint_torque_nm``, ``motor_torque_nm``, ``link_moment_nm``,
    ``tip_deflection_m``, ``force_n``, ``indentation_m`` (at the integrator's steps, at most one
    per 1/``record.sample_rate_hz``); ``step_traces`` is empty.
    """

    scene: str
    design: str
    peak_force_n: float
    time_of_peak_s: float
    impact_velocity_mps: float
    separation_velocity_mps: Optional[float]
    onset_time_s: float
    contact_duration_s: Optional[float]
    max_indentation_m: float
    impulse_n_s: float
    steps: int
    contact_steps: int
    #: How the contact was integrated: ``"adaptive"`` or ``"fixed"`` (Rapier's steps); the
    #: scene's ``solver.contact`` resolved (``"auto"``, the default, is adaptive for a CJ without
    #: a drive). ``None`` for a driven run.
    contact_integration: Optional[str]
    contact_step_s: float
    energy_initial_j: float
    energy_final_j: float
    energy_through_contact_j: Optional[Tuple[float, float]]
    contacts: List[Dict[str, Any]]
    duration_s: float
    samples: int
    warnings: List[Dict[str, str]]
    #: Severity of the first contact (peak force, pressure under both dome models, energy
    #: transferred, peak acceleration, HIC15/HIC36; docs/safety.md), ``None`` for a driven run.
    severity: Optional[Dict[str, Any]]
    #: Link mass m_r [kg].
    m_r_kg: float
    #: Bending stiffness EI of the link in its compliant direction [N·m²].
    ei_n_m2: float
    #: Lateral tip stiffness k_δ [N/m]: k_θr/L² for the CJ (Eq. 1), 3EI/L³ for the CL (Eq. 2).
    k_delta_n_per_m: float
    #: Joint stiffness k_θr [N·m/rad]: the CJ's torsion spring, the CL's equivalent 3EI/L (Eq. 3).
    k_theta_r_nm_per_rad: float
    #: Payload over link mass m_e/m_r (Eq. 5).
    m_e_over_m_r: float
    summary: Dict[str, Any]
    traces: Dict[str, np.ndarray]
    step_traces: Dict[str, np.ndarray]

    @classmethod
    def _from_native(
        cls, summary: Dict[str, Any], traces: Dict[str, np.ndarray], step_traces: Dict[str, np.ndarray]
    ) -> "RunResult":
        through = summary.get("energy_through_contact_j")
        for array in list(traces.values()) + list(step_traces.values()):
            array.setflags(write=False)
        return cls(
            scene=summary["scene"],
            design=summary["design"],
            peak_force_n=summary["peak_force_n"],
            time_of_peak_s=summary["time_of_peak_s"],
            impact_velocity_mps=summary["impact_velocity_mps"],
            separation_velocity_mps=summary.get("separation_velocity_mps"),
            onset_time_s=summary["onset_time_s"],
            contact_duration_s=summary.get("contact_duration_s"),
            max_indentation_m=summary["max_indentation_m"],
            impulse_n_s=summary["impulse_n_s"],
            steps=summary["steps"],
            contact_steps=summary.get("contact_steps"),
            contact_integration=summary.get("contact_integration"),
            contact_step_s=summary.get("contact_step_s"),
            energy_initial_j=summary.get("energy_initial_j"),
            energy_final_j=summary.get("energy_final_j"),
            energy_through_contact_j=None if through is None else (through[0], through[1]),
            contacts=summary.get("contacts", []),
            duration_s=summary["duration_s"],
            samples=summary["samples"],
            warnings=summary["warnings"],
            severity=summary.get("severity"),
            **{name: summary[name] for name in LINK_COLUMNS},
            summary=summary,
            traces=traces,
            step_traces=step_traces,
        )

    @property
    def time_s(self) -> np.ndarray:
        """Sample time [s]."""
        return self.traces["time_s"]

    @property
    def force_n(self) -> np.ndarray:
        """Force sensor between load and dome [N], per sample."""
        return self.traces["force_n"]

    @property
    def indentation_m(self) -> np.ndarray:
        """Contact indentation [m], per sample (0 outside contact)."""
        return self.traces["indentation_m"]

    @property
    def operator_accel_mps2(self) -> np.ndarray:
        """Operator block accelerometer along the strike direction [m/s²], per sample."""
        return self.traces["operator_accel_mps2"]

    @property
    def load_accel_mps2(self) -> np.ndarray:
        """Load accelerometer along the strike direction [m/s²], per sample."""
        return self.traces["load_accel_mps2"]

    @property
    def operator_angle_rad(self) -> np.ndarray:
        """Operator encoder: pendulum angle from the vertical [rad], per sample."""
        return self.traces["operator_angle_rad"]

    @property
    def robot_angle_rad(self) -> np.ndarray:
        """Robot encoder: angle of the robot axis [rad] (0 for CL), per sample."""
        return self.traces["robot_angle_rad"]

    @property
    def link_tip_deflection_m(self) -> np.ndarray:
        """Lateral tip deflection of the link [m], per sample."""
        return self.traces["link_tip_deflection_m"]

    def __repr__(self) -> str:
        return (
            f"RunResult(scene={self.scene!r}, design={self.design!r}, "
            f"peak_force_n={self.peak_force_n:.6g}, impact_velocity_mps={self.impact_velocity_mps:.6g}, "
            f"samples={self.samples}, steps={self.steps})"
        )


def run(
    scene: Scene,
    /,
    overrides: Optional[Mapping[str, Any]] = None,
    *,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    force: bool = False,
    log_every_step: bool = False,
    deformation_scale: float = 30.0,
    **kwargs: Any,
) -> RunResult:
    """Runs one scene of the test rig and returns its summary and traces.

    ``scene``: a path (str or os.PathLike), the name of a bundled scene
    (:func:`bundled_scenes`), TOML text, or a dict of the scene's tables.

    Overrides by dotted path (see the module documentation): ``run(s, **{"robot.payload_kg":
    0.2})``, ``run(s, robot__payload_kg=0.2)`` or ``run(s, overrides={"robot.payload_kg": 0.2})``.

    ``out``: also write the run's MCAP log there (FILE.mcap, with its Foxglove layout
    FILE.layout.json beside it), as ``flexrig run --out``; ``force`` overwrites both,
    ``log_every_step`` logs every step and sample on every channel, ``deformation_scale`` is the
    factor on the CL beam's deflection in the log's 3D view (the flags of the same names). The
    log is finished (with an error record) even when the run fails.

    Raises :class:`InputError` (a ValueError naming the field) for bad input, FileNotFoundError
    for a missing scene file, :class:`SimulationError` for a run that cannot finish. The GIL is
    released while the simulation runs.
    """
    for name, flag in (("force", force), ("log_every_step", log_every_step)):
        if not isinstance(flag, (bool, np.bool_)):
            raise _input_error(name, f"invalid argument {name} = {flag!r}: must be True or False")
    if log_every_step and out is None:
        raise _input_error("log_every_step", "invalid argument log_every_step = True: only with out (the MCAP log)")
    if isinstance(deformation_scale, bool) or not isinstance(deformation_scale, (int, float, np.integer, np.floating)):
        raise _input_error("deformation_scale", f"invalid argument deformation_scale = {deformation_scale!r}: must be a number > 0")
    text, _ = _flexrig.scene_text(scene)
    summary, traces, step_traces = _flexrig.run(
        text, _overrides(overrides, kwargs), None if out is None else os.fspath(out), bool(force),
        bool(log_every_step), float(deformation_scale),
    )
    for w in summary["warnings"]:
        _warnings.warn(f"{w['field']}: {w['message']}", PlausibilityWarning, stacklevel=2)
    return RunResult._from_native(summary, traces, step_traces)


class ImpactPeaks(NamedTuple):
    """The peak of the lumped two-mass impact (paper Eq. 10–14), one array (or float) each."""

    #: Peak contact force f_max [N].
    f_max_n: Any
    #: Peak displacement δ_max = f/k_δ + δ_c [m].
    delta_max_m: Any
    #: Contact indentation at the peak δ_c = (f/k_c)^(1/n) [m].
    indentation_max_m: Any
    #: Link deflection at the peak f/k_δ [m].
    link_deflection_max_m: Any
    #: Reduced mass μ = m_h m_eff / (m_h + m_eff) [kg].
    mu_kg: Any
    #: Impact energy ½ μ v0² [J].
    impact_energy_j: Any


_IMPACT_ARGS = ("m_h", "m_eff", "k_delta", "k_c", "n", "v0")


def impact(
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
) -> Union[ImpactPeaks, ImpactReport]:
    """The peak of the lumped two-mass impact for every parameter set, as ``flexrig impact``.

    With ``m_eff`` and the default ``method="exact"``: the vectorised exact peak below, as
    :class:`ImpactPeaks`. Otherwise — the effective mass from ``gamma`` (PRB characteristic
    radius, 1: compliant joint, 2/3: compliant link), ``m_r`` (link mass, kg) and ``m_e``
    (payload, kg) as m_eff = m_e + γ m_r/3 (paper Eq. 5), or ``method="analytic"`` (the n = 1
    closed form, Eq. 13: also ``k_o_n_per_m``, ``t_peak_s``, ``contact_duration_s``) or
    ``method="ode"`` (time integration with ``formulation`` auto, indentation or displacement
    and relative tolerance ``rtol``: also time to peak, duration, separation speed, right-hand-side
    evaluations, steps and the ``severity``, whose contact pressure takes the dome radius
    ``dome_radius`` [m], default the paper's dome) — an :class:`ImpactReport` with every key of ``flexrig impact --json``
    (the same numbers), arrays over broadcast inputs.

    The exact (energy) method of ``flexrig impact``: ½ μ v0² = f²/(2 k_δ) + f δ_c/(n + 1) with
    δ_c = (f/k_c)^(1/n), for any Hertz exponent n; the same numbers as ``flexrig impact
    --method exact --json``.

    Arguments (floats or NumPy arrays, broadcast together): human mass ``m_h`` [kg], effective
    robot mass ``m_eff`` [kg], link stiffness ``k_delta`` [N/m], contact stiffness ``k_c``
    [N/m^n], Hertz exponent ``n``, approach speed ``v0`` [m/s]. Returns :class:`ImpactPeaks`
    with arrays of the broadcast shape (floats when every argument is a scalar). Parallel over
    the sets with the GIL released; the first set out of range raises :class:`InputError` naming
    the argument and its flat index, e.g. ``m_h[3]``.
    """
    if m_eff is None or gamma is not None or m_r is not None or m_e is not None or dome_radius is not None or not (
        isinstance(method, str) and method == "exact"
    ):
        return _impact_report(
            m_h, m_eff, k_delta, k_c, n, v0, gamma=gamma, m_r=m_r, m_e=m_e, method=method,
            formulation=formulation, rtol=rtol, dome_radius=dome_radius,
        )
    values = (m_h, m_eff, k_delta, k_c, n, v0)
    arrays = []
    for name, value in zip(_IMPACT_ARGS, values):
        try:
            arrays.append(np.asarray(value, dtype=np.float64))
        except (TypeError, ValueError, OverflowError) as e:
            raise _input_error(name, f"{name}: not a number or an array of numbers ({e})") from None
    try:
        arrays = np.broadcast_arrays(*arrays)
    except ValueError:
        shapes = ", ".join(f"{name} {a.shape}" for name, a in zip(_IMPACT_ARGS, arrays))
        raise _input_error("m_h", f"the arguments do not broadcast to one shape: {shapes}") from None
    shape = arrays[0].shape
    flat = [np.ascontiguousarray(a).reshape(-1) for a in arrays]
    out = _flexrig.impact_exact(*flat)
    if shape == ():
        return ImpactPeaks(*(float(o[0]) for o in out))
    return ImpactPeaks(*(o.reshape(shape) for o in out))


def fig6(
    points: int = 101,
    *,
    m_r: float = 10.0,
    k_c: float = 1e8,
    v0: float = 2.0,
    m_h: Union[float, List[float], Tuple[float, ...]] = (4.0, 1000.0),
    k_delta: Union[float, List[float], Tuple[float, ...]] = (1e8, 2e2),
    m_e: Union[float, List[float], Tuple[float, ...]] = (0.1, 10.0),
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    size: Union[str, int] = "2",
    format: Union[str, List[str], Tuple[str, ...]] = ("svg",),
    dpi: float = 300.0,
) -> "pandas.DataFrame":
    """The paper's Fig. 6 (§V, Eq. 15) for any design: η(γ) = f_max(γ)/f_max(γ = 1), as
    ``flexrig fig6``.

    The design held fixed: link mass ``m_r`` [kg], contact stiffness ``k_c`` [N/mⁿ], approach
    speed ``v0`` [m/s]; the cases: every combination of head masses ``m_h`` [kg], link lateral
    stiffnesses ``k_delta`` [N/m] and payloads ``m_e`` [kg] (one to four values each). The
    defaults are the paper's: m_r = 10 kg, k_c = 1e8, v0 = 2 m/s and its eight cases. Bad values
    raise :class:`InputError` naming the keyword. With ``out`` (a directory), fig6.csv and the
    figure (``size``, ``format``, ``dpi`` as :func:`eta`) are written there as ``flexrig fig6
    --out`` writes them.

    One row per (case, n, γ): columns ``m_h_kg``, ``k_delta_n_per_m``, ``m_e_kg``, ``n`` (1 and
    2), ``gamma`` (``points`` samples over [0.5, 1]), ``eta`` and ``eta_at_2_3`` (η at γ = 2/3,
    the uniform compliant link, the same on every row of a curve) — the columns of ``flexrig
    fig6``'s fig6.csv plus the last. ``attrs["design"]`` holds the design.
    """
    import pandas as pd

    from ._commands import _cases, _design, _figure_args

    if isinstance(points, bool) or not isinstance(points, (int, np.integer)) or not 2 <= points <= 1_000_000:
        raise _input_error("points", f"points = {points!r}: must be a whole number from 2 to 1000000")
    design = _design(m_r, k_c, v0)
    size, formats, dpi = _figure_args(size, format, dpi)
    curves = _flexrig.fig6(
        int(points), *design, *_cases(m_h, k_delta, m_e), None if out is None else os.path.abspath(os.fspath(out)),
        size, formats, dpi,
    )
    frames = []
    for c in curves:
        size = len(c["gamma"])
        frames.append(
            pd.DataFrame(
                {
                    "m_h_kg": np.full(size, c["m_h"]),
                    "k_delta_n_per_m": np.full(size, c["k_delta"]),
                    "m_e_kg": np.full(size, c["m_e"]),
                    "n": np.full(size, c["n"]),
                    "gamma": c["gamma"],
                    "eta": c["eta"],
                    "eta_at_2_3": np.full(size, c["eta_at_2_3"]),
                }
            )
        )
    frame = pd.concat(frames, ignore_index=True)
    frame.attrs["design"] = dict(zip(("m_r", "k_c", "v0"), design))
    return frame


def sweep(
    base: Scene,
    grid: Mapping[str, Any],
    *,
    zip: bool = False,
    client: Any = None,
    threads: Optional[int] = None,
    chunk_size: Optional[int] = None,
) -> "pandas.DataFrame":
    """Runs ``base`` over a grid of scene fields, in parallel, into a pandas DataFrame.

    ``grid`` maps a dotted scene path to its values: a list, tuple, range or NumPy array (its
    items), a str in the CLI's SPEC syntax (``"0.1,0.2,0.5"``, ``"cj,cl"``, ``"10:60:11"`` with
    both ends, ``"1e-3:1:25:log"``, ``"@values.txt"``), or a single value. The points are the
    full grid (the first path varies slowest) or, with ``zip=True``, the lists side by side.

    The table is the one ``flexrig sweep`` writes to sweep.csv, one row per point in point
    order: ``index``, one column per path (tables and arrays as TOML text), ``status`` (``ok``
    or ``error``), ``error`` (the message of a failed run, else empty) and every summary
    quantity of :data:`SUMMARY_COLUMNS` (float64, NaN where absent, e.g. for a failed run; the
    counts of :data:`INTEGER_SUMMARY_COLUMNS` as nullable Int64, ``<NA>`` where absent), then
    ``notes``: what the run's drive did that the numbers do not say, as ``flexrig run`` notes it
    (the torque limit reached, an arrival off the commanded speed; ``"; "`` between two; empty
    for a run without notes). ``df.to_parquet(path)`` writes it (with pyarrow installed).

    ``client``: a ``dask.distributed.Client``; the points are then run on its workers in chunks
    of ``chunk_size`` (default: about four chunks per worker thread), each chunk in one thread,
    with results identical to the local sweep. Without it the sweep runs here on ``threads``
    threads (default: every core), GIL released.

    Raises :class:`InputError` naming the path for an unknown path or a value of the wrong type
    (before anything runs), naming ``grid`` for an empty grid; a run that fails (e.g. a value out
    of its range, an unstable run) is a row with its error.
    """
    if not isinstance(grid, Mapping):
        raise _input_error("grid", f"grid: must be a mapping of dotted scene path to values, not {type(grid).__name__}")
    if len(grid) == 0:
        raise _input_error(
            "grid",
            'grid: the grid is empty; give at least one scene path and its values, e.g. {"robot.payload_kg": [0.1, 0.2]}',
        )
    if not isinstance(zip, (bool, np.bool_)):
        raise _input_error("zip", f"zip = {zip!r}: must be True or False")
    _check_count("threads", threads, "None for every core")
    _check_count("chunk_size", chunk_size, "None for about four chunks per worker thread")
    if client is not None:
        missing = [m for m in ("nthreads", "scatter", "map", "gather") if not callable(getattr(client, m, None))]
        if missing:
            raise _input_error(
                "client",
                f"client: a {type(client).__name__} is not a Dask client (it has no {', '.join(missing)}); "
                "give a dask.distributed.Client, or None to run here",
            )
    text, base_dir = _flexrig.scene_text(base)
    native = Sweep(text, [(str(path), values) for path, values in grid.items()], zip, base_dir)
    if client is None:
        parts = [native.run(None, threads)]
    else:
        parts = _run_on_dask(native, client, chunk_size)
    return _frame(native.paths, parts)


def _run_chunk(indices: List[int], sweep: Sweep) -> Dict[str, Any]:
    """A Dask task: the points ``indices`` of ``sweep``, in the worker's thread."""
    return sweep.run(indices, 1)


def _run_on_dask(native: Sweep, client: Any, chunk_size: Optional[int]) -> List[Dict[str, Any]]:
    points = len(native)
    threads = max(1, sum(client.nthreads().values()))
    size = chunk_size if chunk_size else max(1, -(-points // (4 * threads)))
    if size < 1:
        raise _input_error("chunk_size", f"chunk_size = {chunk_size}: must be at least 1")
    chunks = [list(range(i, min(i + size, points))) for i in range(0, points, size)]
    # a key of its own (hash=False): the same sweep scattered again right after an earlier call
    # released it would otherwise share that call's content-hash key, and the scheduler could be
    # deleting it while it replicates ("Key lost during replication", the chunks cancelled)
    [remote] = client.scatter([native], broadcast=True, hash=False)
    futures = client.map(_run_chunk, chunks, sweep=remote, pure=False)
    return client.gather(futures)


def _frame(paths: List[str], parts: List[Dict[str, Any]]) -> "pandas.DataFrame":
    import pandas as pd

    index = np.concatenate([p["index"] for p in parts]) if parts else np.zeros(0, dtype=np.int64)
    order = np.argsort(index, kind="stable")
    columns: Dict[str, Any] = {"index": index[order]}
    for k, path in enumerate(paths):
        values = [v for p in parts for v in p["values"][k]]
        columns[path] = [values[i] for i in order]
    for name in ("status", "error"):
        values = [v for p in parts for v in p[name]]
        columns[name] = [values[i] for i in order]
    summary = np.concatenate([p["summary"] for p in parts])[order]
    for j, name in enumerate(SUMMARY_COLUMNS):
        if name in INTEGER_SUMMARY_COLUMNS:
            # counts as integers; pandas' nullable Int64 keeps a failed run's row missing (<NA>)
            columns[name] = pd.array([None if np.isnan(x) else int(x) for x in summary[:, j]], dtype="Int64")
        else:
            columns[name] = summary[:, j]
    notes = [v for p in parts for v in p["notes"]]
    columns["notes"] = [notes[i] for i in order]
    return pd.DataFrame(columns)


def _out_dir(out: Optional[Union[str, "os.PathLike[str]"]]):
    """(directory, temporary-directory object or None): ``out`` or a fresh temporary directory."""
    import tempfile

    if out is not None:
        return os.fspath(out), None
    tmp = tempfile.TemporaryDirectory(prefix="flexrig-")
    return tmp.name, tmp


def spin_up(
    *,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    case: str = "simo-vu-quoc",
    length: Optional[float] = None,
    area: Optional[float] = None,
    second_moment: Optional[float] = None,
    youngs_modulus: Optional[float] = None,
    density: Optional[float] = None,
    t_s: Optional[float] = None,
    omega_s: Optional[float] = None,
    elements: int = 16,
    duration: Optional[float] = None,
    sample_every: float = 0.1,
    max_step: float = 5e-3,
    modes: int = 5,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
) -> "pandas.DataFrame":
    """The spin-up beam benchmark, as ``flexrig spin-up``: the tip's deflection in the hub frame
    [m] by the corotational FE beam (``fe``), the independent elastica reference (``reference``)
    and the linear rotating-frame beam (``linear``, which diverges), one row per reported time
    ``t`` [s] — the columns of spin_up.csv. Keyword arguments are the command's flags (SI units;
    run to T_s + 5 s unless ``duration`` is given): ``case`` names the beam and its spin-up,
    ``"simo-vu-quoc"`` (Simo & Vu-Quoc's 10 m beam to 6 rad/s, the default) or ``"kane"`` (Kane,
    Ryan & Banerjee's 8 m aluminium beam to 4 rad/s); ``length``, ``area``, ``second_moment``,
    ``youngs_modulus``, ``density``, ``t_s`` and ``omega_s`` left at None are the case's. ``size``,
    ``format`` and ``dpi`` are the figure's printed width (``"1"``, ``"2"`` or e.g. ``"5in"``),
    formats (svg, pdf, png) and PNG resolution, as ``--size``, ``--format``, ``--dpi``. With
    ``out`` the CSV, JSON and the figure are written there. ``df.attrs`` holds
    ``fe_error_of_max``, ``reference_max_m`` and the options (and, with ``out``, the files:
    ``csv``, ``json``, ``svg``, ``figures``).
    """
    import pandas as pd

    from ._commands import _figure_args

    size, formats, dpi = _figure_args(size, format, dpi)
    directory, tmp = _out_dir(out)
    try:
        r = _flexrig.spin_up(
            directory, _word("case", case), _number("length", length, True), _number("area", area, True),
            _number("second_moment", second_moment, True),
            _number("youngs_modulus", youngs_modulus, True), _number("density", density, True),
            _number("t_s", t_s, True), _number("omega_s", omega_s, True),
            _count("elements", elements), _number("duration", duration, True),
            _number("sample_every", sample_every), _number("max_step", max_step),
            _count("modes", modes), size, formats, dpi,
        )
    finally:
        if tmp is not None:
            tmp.cleanup()
    df = pd.DataFrame({k: np.asarray(r[k], dtype=np.float64) for k in ("t", "fe", "reference", "linear")})
    df.attrs.update(
        fe_error_of_max=r["fe_error_of_max"], reference_max_m=r["reference_max_m"], options=r["options"]
    )
    if out is not None:
        df.attrs.update(csv=r["csv"], json=r["json"], svg=r["svg"], figures=r["figures"])
    return df


#: The columns of a strike's trace (strike_trace.csv).
STRIKE_TRACE_COLUMNS: Tuple[str, ...] = (
    "t_s", "hub_angle_rad", "hub_speed_rad_s", "tip_deflection_m", "indentation_m", "force_n",
    "joint_torque_nm", "head_position_m", "head_acceleration_mps2",
)

_TRACE_KEYS = (
    "t", "hub_angle_rad", "hub_speed_rad_s", "tip_deflection_m", "indentation_m", "force_n",
    "joint_torque_nm", "head_position_m", "head_acceleration_mps2",
)


def strike(
    file: Optional[Union[str, "os.PathLike[str]"]] = None,
    *,
    design: str = "cl",
    m_r: float = 10.0,
    length: float = 1.0,
    k_delta: float = 1e8,
    m_e: float = 0.1,
    rotor_inertia: float = 1e-4,
    gear_ratio: float = 50.0,
    friction: float = 1e-5,
    speed: float = 2.0,
    ramp_time: float = 0.5,
    kp: float = 500.0,
    kd: float = 40.0,
    torque_limit: float = 1.0,
    m_h: float = 4.0,
    support: str = "free",
    k_c: float = 1e8,
    n: float = 2.0,
    settle: float = 0.3,
    horizon: float = 5.0,
    dome_radius: float = 0.0715,
    dome_standoff: float = 0.030,
    link_model: str = "exact",
    trace_every: Optional[float] = None,
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
) -> Dict[str, Any]:
    """One driven CJ or CL strike, as ``flexrig strike``: from a drive description ``file`` (a
    path to TOML, see assets/drives/) or from the keyword arguments (the command's flags; their
    defaults are assets/drives/cl_free_head.toml). Returns the outcome as a dict (``contact``:
    onset_time_s, peak_force_n, time_of_peak_s, duration_s; approach speed, pre-impact deflection,
    joint torques, ``energy``, ``notes``, ``steps``, ``warnings``: the plausibility warnings,
    each a dict of ``field`` and ``message``, also raised as :class:`PlausibilityWarning`, e.g. a
    link heavier than 200 kg) and, with ``trace_every`` [s], ``trace``: a
    DataFrame of the motion (columns :data:`STRIKE_TRACE_COLUMNS`; written as strike_trace.csv
    into ``out`` if given). ``link_model`` "exact" (the default: the link bends and turns
    geometrically exactly, the dome of ``dome_radius`` [m] with its apex ``dome_standoff`` [m]
    ahead of the link's axis in the contact) or "linear" (faster: within 1.1e-4 of the exact
    peak on the default stiff link, up to 2.5 % off in the peak and 9 % in the duration on a
    soft link that bends). A bad field raises :class:`InputError` naming it
    (``drive.motor.gear_ratio``).
    """
    import pandas as pd

    every = None if trace_every is None else float(trace_every)
    directory = None if out is None else os.fspath(out)
    if file is not None:
        path = os.fspath(file)
        with open(path, encoding="utf-8") as fh:
            text = fh.read()
        r = _flexrig.strike(text, path, every, directory)
    else:
        r = _flexrig.strike_flags(
            design, support, float(m_r), float(length), float(k_delta), float(m_e), float(rotor_inertia),
            float(gear_ratio), float(friction), float(speed), float(ramp_time), float(kp), float(kd),
            float(torque_limit), float(m_h), float(k_c), float(n), float(settle), float(horizon),
            float(dome_radius), float(dome_standoff), link_model, every, directory,
        )
    outcome = dict(r["outcome"])
    trace = outcome.pop("trace")
    if trace_every is not None:
        outcome["trace"] = pd.DataFrame(
            {c: np.asarray([s[k] for s in trace], dtype=np.float64) for c, k in zip(STRIKE_TRACE_COLUMNS, _TRACE_KEYS)}
        )
    outcome["design"] = r["design"]
    if r.get("trace_csv") is not None:
        outcome["trace_csv"] = r["trace_csv"]
    outcome["warnings"] = r["warnings"]
    for w in r["warnings"]:
        _warnings.warn(f"{w['field']}: {w['message']}", PlausibilityWarning, stacklevel=2)
    return outcome


def role_switch(
    *,
    kappa: Any = (1e4, 1e2, 1.0, 1e-2),
    rotor_ratio: float = 1.0,
    damping_ratio: float = 0.7,
    no_fig6: bool = False,
    link_model: str = "exact",
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    size: Union[str, int] = "2",
    format: Union[str, Sequence[str]] = ("svg",),
    dpi: float = 300.0,
) -> "pandas.DataFrame":
    """The role-switch table, as ``flexrig role-switch``: one row per (case, design, drive) with
    the columns of role_switch.csv — ``case``, ``design`` (cj, cl), ``drive`` (prescribed, pd,
    torque_free), ``kappa`` (K_p/k_θr; inf for the ideal position source, 0 torque-free),
    ``f_test_bed_n``, ``f_driven_n``, ``ratio``, ``f_switched_same_drive_n``. Keyword arguments
    are the command's flags (``size``, ``format``, ``dpi``: the figure's printed width, formats
    and PNG resolution, as ``--size``, ``--format``, ``--dpi``; ``link_model`` "exact", the
    default, or "linear": seconds instead of minutes, every ratio within 4.3e-3 of the exact
    one); with ``out`` the CSV and the figure are written there (``df.attrs``: ``csv``,
    ``svg``, ``figures``).
    """
    import pandas as pd

    from ._commands import _figure_args

    size, formats, dpi = _figure_args(size, format, dpi)
    directory, tmp = _out_dir(out)
    try:
        rows, csv, figures = _flexrig.role_switch(
            directory, [float(k) for k in np.atleast_1d(kappa)], float(rotor_ratio),
            float(damping_ratio), not no_fig6, size, formats, dpi, link_model,
        )
    finally:
        if tmp is not None:
            tmp.cleanup()
    kappas = {"prescribed": np.inf, "torque_free": 0.0}
    df = pd.DataFrame(
        {
            "case": [r["case"] for r in rows],
            "design": [r["design"] for r in rows],
            "drive": [r["level"]["drive"] for r in rows],
            "kappa": np.asarray(
                [r["level"].get("kappa", kappas.get(r["level"]["drive"])) for r in rows], dtype=np.float64
            ),
            **{
                k: np.asarray([r[k] for r in rows], dtype=np.float64)
                for k in ("f_test_bed_n", "f_driven_n", "ratio", "f_switched_same_drive_n")
            },
        }
    )
    if out is not None:
        df.attrs.update(
            csv=str(csv), svg=str(os.path.join(directory, "role_switch.svg")), figures=[str(f) for f in figures]
        )
    return df
