"""Type stubs of the native module ``flexrig._flexrig`` (PyO3). Use the ``flexrig`` package:
its functions wrap these with the documented conveniences (scene forms, keyword overrides,
broadcasting, DataFrames, Dask)."""

import os
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

#: The default relative tolerance of the lumped impact's ode method (``flexrig impact --rtol``).
DEFAULT_RTOL: float

#: The summary quantities of a sweep row, in column order (as in ``flexrig sweep``'s CSV).
SUMMARY_COLUMNS: List[str]
INTEGER_SUMMARY_COLUMNS: List[str]
LINK_COLUMNS: List[str]

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
    text: str,
    overrides: Sequence[Tuple[str, Any]],
    out: Optional[Union[str, "os.PathLike[str]"]] = None,
    force: bool = False,
    log_every_step: bool = False,
    deformation_scale: float = 30.0,
) -> Tuple[Dict[str, Any], Dict[str, npt.NDArray[np.float64]], Dict[str, npt.NDArray[np.float64]]]:
    """Runs the scene text with overrides: (summary as ``flexrig run --json``, sample traces,
    step traces); with ``out`` also the MCAP log and its layout as ``flexrig run --out``. GIL
    released; Ctrl-C raises KeyboardInterrupt."""

_Path = Union[str, "os.PathLike[str]"]

def impact_report(
    m_h: float,
    m_eff: Optional[float],
    gamma: Optional[float],
    m_r: Optional[float],
    m_e: Optional[float],
    k_delta: float,
    k_c: float,
    n: float,
    v0: float,
    method: str,
    formulation: str,
    rtol: float,
    dome_radius: Optional[float] = None,
) -> Dict[str, Any]:
    """``flexrig impact --json`` for one set (masses kg, k_delta N/m, k_c N/m^n, v0 m/s; the
    severity's dome radius m, ode only)."""

def eta(
    out: _Path, joint: str, rotor_inertia: Optional[float], method: str, tol: Optional[float],
    zone_elements: Optional[float], window_periods: Optional[float], elements: Optional[int],
    steps_per_contact: Optional[int], modes: Optional[int], length: float, damping_model: str,
    restitution: Optional[float], c_max: Optional[float], depth: Optional[float], size: str,
    format: Sequence[str], dpi: float, design: Tuple[float, float, float],
    grid: Tuple[Sequence[float], Sequence[float], Sequence[float]],
) -> Dict[str, Any]:
    """``flexrig eta --json`` for the same inputs; writes into ``out``."""

def eta_map(
    out: _Path, m_h: Sequence[float], n: float, mass_ratio: str, stiffness_ratio: str, points: int,
    joint: str, rotor_inertia: Optional[float], tol: float, damping_model: str,
    restitution: Optional[float], c_max: Optional[float], depth: Optional[float], size: str,
    format: Sequence[str], dpi: float, design: Tuple[float, float, float], length: float,
) -> Dict[str, Any]:
    """``flexrig eta-map --json`` for the same inputs; writes into ``out``."""

def eta_rotor(
    out: _Path, ratio: str, points: int, n: Sequence[float], tol: float, damping_model: str,
    restitution: Optional[float], c_max: Optional[float], depth: Optional[float], size: str,
    format: Sequence[str], dpi: float, design: Tuple[float, float, float], length: float,
    grid: Tuple[Sequence[float], Sequence[float], Sequence[float]],
) -> Dict[str, Any]:
    """``flexrig eta-rotor --json`` for the same inputs; writes into ``out``."""

def experiment(
    out: _Path, repeats: int, jitter_deg: float, seed: int, scenes: Optional[_Path],
    overrides: Sequence[Tuple[str, Any]], size: str, format: Sequence[str], dpi: float,
) -> Dict[str, Any]:
    """``flexrig experiment --json`` for the same inputs; writes into ``out``."""

def payload(
    out: _Path, scene: str, payloads: str, points: int, size: str, format: Sequence[str],
    dpi: float,
) -> Dict[str, Any]:
    """``flexrig payload --json`` for the same inputs; writes into ``out``."""

def fit(file: _Path) -> Dict[str, Any]:
    """``flexrig fit FILE --json``."""

def beam_modal(
    scene: Optional[_Path], length: Optional[float], youngs: Optional[float],
    density: Optional[float], width: Optional[float], thickness: Optional[float],
    elements: Optional[int], tip_mass: Optional[float], root: str, k_theta: float, modes: int,
) -> Dict[str, Any]:
    """``flexrig beam modal --json`` (SI units)."""

def beam_static(
    scene: Optional[_Path], length: Optional[float], youngs: Optional[float],
    density: Optional[float], width: Optional[float], thickness: Optional[float],
    elements: Optional[int], tip_mass: Optional[float], root: str, k_theta: float,
    tip_load: float, tip_moment: float, model: str, load_steps: int,
    yield_strength: Optional[float],
) -> Dict[str, Any]:
    """``flexrig beam static --json`` (SI units)."""

def prb(
    out: _Path, elements: int, model: str, criterion: str, size: str, format: Sequence[str], dpi: float
) -> Dict[str, Any]:
    """``flexrig prb --json`` for the same inputs; writes prb.svg into ``out``."""

def validate(quick: bool, out: _Path) -> Dict[str, Any]:
    """``flexrig validate --json``; writes validation.md into ``out``."""

def bench(quick: bool, out: _Path, size: str, format: Sequence[str], dpi: float) -> Dict[str, Any]:
    """``flexrig bench --json``; writes the bench_*.svg plots into ``out``."""

def strike_flags(
    design: str, support: str, m_r: float, length: float, k_delta: float, m_e: float,
    rotor_inertia: float, gear_ratio: float, friction: float, speed: float, ramp_time: float,
    kp: float, kd: float, torque_limit: float, m_h: float, k_c: float, n: float, settle: float,
    horizon: float, dome_radius: float, dome_standoff: float, link_model: str,
    trace_every: Optional[float], out: Optional[_Path],
) -> Dict[str, Any]:
    """``flexrig strike --json`` from the flags' numbers (SI units; errors name the keyword)."""

def strike_defaults() -> Dict[str, Any]:
    """The defaults of ``flexrig strike``'s flags by keyword (assets/drives/cl_free_head.toml)."""

def spin_up_defaults() -> Dict[str, Any]:
    """The defaults of ``flexrig spin-up``'s flags by keyword (``case`` Simo & Vu-Quoc's beam;
    the beam's numbers None: the case's)."""

def arm_json(
    input_json: str,
    urdf: Optional[str] = None,
    trajectory: Optional[str] = None,
    times: Optional[List[float]] = None,
    positions: Optional[List[List[float]]] = None,
    body_model_toml: Optional[str] = None,
) -> str: ...
def safety_json(input_json: str, body_model_toml: Optional[str] = None) -> str:
    """The report of ``flexrig safety --json`` for a safety input given as JSON (see
    ``flexrig.safety``)."""

def safety_trace_json(input_json: str, body_model_toml: Optional[str] = None) -> str:
    """The report of ``flexrig safety --trace FILE --json`` for a trace input given as JSON (see
    ``flexrig.safety`` with ``trace``)."""

def parse_area(text: str) -> float:
    """An area with its unit (``"1cm2"``, ``"1e-4m2"``, ``"100mm2"``) in m², as
    ``--contact-area`` reads it; a bare number is refused."""

def safety_map_json(input_json: str, body_model_toml: Optional[str] = None) -> str:
    """The safe-speed map of ``flexrig safety-map`` (its safety_map.json) for a map input given
    as JSON; an axis may be ``{"text": "PARAM=START:STOP:COUNT[:log]"}`` (see
    ``flexrig.safety_map``)."""

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

def fig6(
    points: int, m_r: float, k_c: float, v0: float, m_h: Sequence[float], k_delta: Sequence[float],
    m_e: Sequence[float], out: Optional[_Path], size: str, format: Sequence[str], dpi: float,
) -> List[Dict[str, Any]]:
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
