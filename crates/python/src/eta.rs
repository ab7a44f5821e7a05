//! The FE impact studies (`flexrig eta`, `eta-map`, `eta-rotor`): the keyword arguments checked
//! by the same library functions as the flags ([`flexrig::fronts`]), the study run with the GIL
//! released (Ctrl-C stops it), and the report the command prints with `--json`.

use std::path::PathBuf;

use flexrig::CancelToken;
use flexrig::fronts::{self, DampingModel, EtaInputs, JointKind};
use pyo3::prelude::*;

use crate::convert::json_to_py;
use crate::{detached, flag_error};

/// The contact's damping of the keyword arguments `damping`, `restitution`, `c_max`, `depth`.
fn damping(
    model: &str,
    restitution: Option<f64>,
    c_max: Option<f64>,
    depth: Option<f64>,
) -> PyResult<flexrig::fe::eta::DampingSpec> {
    let model = DampingModel::parse(model).map_err(flag_error)?;
    fronts::damping_spec(model, restitution, c_max, depth).map_err(flag_error)
}

/// The design held fixed (`m_r` [kg], `k_c` [N/mⁿ], `v0` [m/s]), checked by the library.
fn design_of((m_r, k_c, v0): (f64, f64, f64)) -> flexrig::lumped::fig6::Fig6Design {
    flexrig::lumped::fig6::Fig6Design { m_r, k_c, v0 }
}

/// The cases (`m_h`, `k_delta`, `m_e`: every combination), checked by the library.
fn grid_of((m_h, k_delta, m_e): (Vec<f64>, Vec<f64>, Vec<f64>)) -> flexrig::lumped::fig6::Fig6Grid {
    flexrig::lumped::fig6::Fig6Grid { m_h, k_delta, m_e }
}

/// `flexrig eta --json` for the same inputs; writes eta.csv and the figures into `out`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, joint, rotor_inertia, method, tol, zone_elements, window_periods, elements, steps_per_contact, modes, length, damping_model, restitution, c_max, depth, size, format, dpi, design, grid))]
pub fn eta<'py>(
    py: Python<'py>,
    out: PathBuf,
    joint: &str,
    rotor_inertia: Option<f64>,
    method: &str,
    tol: Option<f64>,
    zone_elements: Option<f64>,
    window_periods: Option<f64>,
    elements: Option<usize>,
    steps_per_contact: Option<usize>,
    modes: Option<usize>,
    length: f64,
    damping_model: &str,
    restitution: Option<f64>,
    c_max: Option<f64>,
    depth: Option<f64>,
    size: &str,
    format: Vec<String>,
    dpi: f64,
    design: (f64, f64, f64),
    grid: (Vec<f64>, Vec<f64>, Vec<f64>),
) -> PyResult<Bound<'py, PyAny>> {
    let alpha = match method {
        "modal" => false,
        "alpha" => true,
        other => {
            return Err(flag_error(flexrig::Error::InvalidArgument {
                arg: "--method".into(),
                value: other.into(),
                allowed: "one of modal, alpha".into(),
            }));
        }
    };
    let settings = fronts::eta_settings(&EtaInputs {
        joint: JointKind::parse(joint).map_err(flag_error)?,
        rotor_inertia,
        alpha,
        tol,
        zone_elements,
        window_periods,
        elements,
        steps_per_contact,
        modes,
        length,
        damping: damping(damping_model, restitution, c_max, depth)?,
        design: design_of(design),
    })
    .map_err(flag_error)?;
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let cancel = CancelToken::new();
    let r = detached(py, &cancel, || {
        flexrig::fe::eta::run(&settings, &grid_of(grid), &out, &figures, &cancel)
    })?
    .map_err(|e| flag_error(fronts::impact_as_flag(e)))?;
    json_to_py(py, &fronts::eta_report(&settings, &r))
}

/// `flexrig eta-map --json` for the same inputs; writes eta_map.csv and the figures into `out`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, m_h, n, mass_ratio, stiffness_ratio, points, joint, rotor_inertia, tol, damping_model, restitution, c_max, depth, size, format, dpi, design, length))]
pub fn eta_map<'py>(
    py: Python<'py>,
    out: PathBuf,
    m_h: Vec<f64>,
    n: f64,
    mass_ratio: &str,
    stiffness_ratio: &str,
    points: usize,
    joint: &str,
    rotor_inertia: Option<f64>,
    tol: f64,
    damping_model: &str,
    restitution: Option<f64>,
    c_max: Option<f64>,
    depth: Option<f64>,
    size: &str,
    format: Vec<String>,
    dpi: f64,
    design: (f64, f64, f64),
    length: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let joint = fronts::joint(JointKind::parse(joint).map_err(flag_error)?, rotor_inertia)
        .map_err(flag_error)?;
    let specs =
        fronts::eta_map_specs(&m_h, n, mass_ratio, stiffness_ratio, points).map_err(flag_error)?;
    let settings = fronts::eta_map_settings(
        joint,
        tol,
        damping(damping_model, restitution, c_max, depth)?,
        design_of(design),
        length,
    )
    .map_err(flag_error)?;
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let options = flexrig::fe::eta_map::EtaMapOptions {
        out,
        specs,
        settings,
        figures,
    };
    let cancel = CancelToken::new();
    let r = detached(py, &cancel, || flexrig::fe::eta_map::run(&options, &cancel))?
        .map_err(|e| flag_error(fronts::impact_as_flag(e)))?;
    json_to_py(py, &fronts::eta_map_report(&options.settings, &r))
}

/// `flexrig eta-rotor --json` for the same inputs; writes eta_rotor.csv and the figures into
/// `out`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, ratio, points, n, tol, damping_model, restitution, c_max, depth, size, format, dpi, design, length, grid))]
pub fn eta_rotor<'py>(
    py: Python<'py>,
    out: PathBuf,
    ratio: &str,
    points: usize,
    n: Vec<f64>,
    tol: f64,
    damping_model: &str,
    restitution: Option<f64>,
    c_max: Option<f64>,
    depth: Option<f64>,
    size: &str,
    format: Vec<String>,
    dpi: f64,
    design: (f64, f64, f64),
    length: f64,
    grid: (Vec<f64>, Vec<f64>, Vec<f64>),
) -> PyResult<Bound<'py, PyAny>> {
    let ratios = fronts::eta_rotor_inputs(ratio, points, &n).map_err(flag_error)?;
    let settings = fronts::eta_rotor_settings(
        tol,
        damping(damping_model, restitution, c_max, depth)?,
        design_of(design),
        length,
    )
    .map_err(flag_error)?;
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let options = flexrig::fe::eta_rotor::EtaRotorOptions {
        out,
        ratios,
        n,
        settings,
        grid: grid_of(grid),
        figures,
    };
    let cancel = CancelToken::new();
    let r = detached(py, &cancel, || {
        flexrig::fe::eta_rotor::run(&options, &cancel)
    })?
    .map_err(|e| flag_error(fronts::eta_rotor_error(e, ratio)))?;
    json_to_py(py, &fronts::eta_rotor_report(&settings, &r))
}
