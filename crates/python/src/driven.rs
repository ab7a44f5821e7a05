//! The driven robot (docs/driven.md): the spin-up beam benchmark, one driven strike and the
//! role-switch table, over [`flexrig::driven`]; results as the library's serialised structs (the
//! Python wrappers in `flexrig/__init__.py` turn them into NumPy arrays and DataFrames).

use std::path::PathBuf;

use flexrig::driven::role_switch::{RoleSwitchOptions, run_with_figures as run_role_switch};
use flexrig::driven::spin_up::{SpinUpCase, SpinUpFlags, run_with_figures as run_spin_up};
use flexrig::driven::strike::{
    FieldNames, LinkModel, StrikeDescription, StrikeDesign, StrikeFlags, StrikeOptions,
    parse_support, run as run_strike,
};
use flexrig::{CancelToken, Error, fronts};
use flexrig_impact::ImpactError;
use pyo3::prelude::*;
use serde::Serialize;

use crate::convert::json_to_py;
use crate::{detached, flag_error, input_error, to_py};

/// A library error as a Python exception; a drive field's error names it (`drive.motor.gear_ratio`).
fn py_error(e: Error) -> PyErr {
    match &e {
        Error::Impact(ImpactError::InvalidParameter { field, .. }) => {
            input_error(field, e.to_string())
        }
        // the command's flags (`--omega-s`) written as the keyword arguments (`omega_s`)
        Error::InvalidArgument { .. } => flag_error(e),
        _ => to_py(e),
    }
}

fn to_object<'py>(py: Python<'py>, value: &impl Serialize) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    json_to_py(py, &v)
}

/// The spin-up benchmark as `flexrig spin-up` runs it: the beam `case` (`simo-vu-quoc` or
/// `kane`) with each beam or spin-up number given in place of the case's; writes into `out` (the
/// figure at the printed width `size`, in `format`s, PNG at `dpi`, as `--size`, `--format`,
/// `--dpi`); returns the serialised `SpinUpResult` (a dict). Errors name the keyword argument.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, case, length, area, second_moment, youngs_modulus, density, t_s, omega_s, elements, duration, sample_every, max_step, modes, size, format, dpi))]
pub fn spin_up<'py>(
    py: Python<'py>,
    out: PathBuf,
    case: &str,
    length: Option<f64>,
    area: Option<f64>,
    second_moment: Option<f64>,
    youngs_modulus: Option<f64>,
    density: Option<f64>,
    t_s: Option<f64>,
    omega_s: Option<f64>,
    elements: usize,
    duration: Option<f64>,
    sample_every: f64,
    max_step: f64,
    modes: usize,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let flags = SpinUpFlags {
        case: SpinUpCase::parse("--case", case).map_err(flag_error)?,
        length,
        area,
        second_moment,
        youngs_modulus,
        density,
        t_s,
        omega_s,
        elements,
        duration,
        sample_every,
        max_step,
        modes,
    };
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let cancel = CancelToken::new();
    let result = detached(py, &cancel, || {
        run_spin_up(&flags.options(), &out, &figures, &cancel)
    })?
    .map_err(py_error)?;
    to_object(py, &result)
}

/// One driven strike from a drive description's TOML `text` (`source` names it in errors), as
/// `flexrig strike FILE` runs it; returns the serialised `StrikeResult` (a dict).
#[pyfunction]
#[pyo3(signature = (text, source, trace_every, out))]
pub fn strike<'py>(
    py: Python<'py>,
    text: &str,
    source: &str,
    trace_every: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let description = StrikeDescription::parse(text, source).map_err(py_error)?;
    let options = StrikeOptions {
        trace_every,
        out,
        names: FieldNames::File,
    };
    run_described(py, &description, options)
}

/// One driven strike from the numbers of `flexrig strike`'s flags (the library's
/// [`StrikeFlags`]: `design` cj or cl, `support` free or wall, SI units); returns the
/// serialised `StrikeResult` (a dict). Errors name the keyword argument.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (design, support, m_r, length, k_delta, m_e, rotor_inertia, gear_ratio, friction, speed, ramp_time, kp, kd, torque_limit, m_h, k_c, n, settle, horizon, dome_radius, dome_standoff, link_model, trace_every, out))]
pub fn strike_flags<'py>(
    py: Python<'py>,
    design: &str,
    support: &str,
    m_r: f64,
    length: f64,
    k_delta: f64,
    m_e: f64,
    rotor_inertia: f64,
    gear_ratio: f64,
    friction: f64,
    speed: f64,
    ramp_time: f64,
    kp: f64,
    kd: f64,
    torque_limit: f64,
    m_h: f64,
    k_c: f64,
    n: f64,
    settle: f64,
    horizon: f64,
    dome_radius: f64,
    dome_standoff: f64,
    link_model: &str,
    trace_every: Option<f64>,
    out: Option<PathBuf>,
) -> PyResult<Bound<'py, PyAny>> {
    let flags = StrikeFlags {
        design: StrikeDesign::parse("--design", design).map_err(flag_error)?,
        m_r,
        length,
        k_delta,
        m_e,
        rotor_inertia,
        gear_ratio,
        friction,
        speed,
        ramp_time,
        kp,
        kd,
        torque_limit,
        m_h,
        support: parse_support("--support", support).map_err(flag_error)?,
        k_c,
        n,
        settle,
        horizon,
        dome_radius,
        dome_standoff,
        link_model: LinkModel::parse("--link-model", link_model).map_err(flag_error)?,
    };
    let description = flags.description().map_err(|e| match e {
        Error::InvalidArgument { .. } => flag_error(e),
        _ => py_error(e),
    })?;
    let options = StrikeOptions {
        trace_every,
        out,
        names: FieldNames::Flags,
    };
    run_described(py, &description, options)
}

/// Runs a described strike with the GIL released (cancellable by Ctrl-C) and returns its
/// serialised result.
fn run_described<'py>(
    py: Python<'py>,
    description: &StrikeDescription,
    options: StrikeOptions,
) -> PyResult<Bound<'py, PyAny>> {
    let cancel = CancelToken::new();
    let mut result =
        detached(py, &cancel, || run_strike(description, &options, &cancel))?.map_err(py_error)?;
    // the flags' warnings name the keyword arguments (`m_r`, not `--m-r`)
    crate::keyword_warnings(&mut result.warnings);
    to_object(py, &result)
}

/// The defaults of `flexrig strike`'s flags ([`StrikeFlags::DEFAULT`]) by keyword argument.
#[pyfunction]
pub fn strike_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let d = StrikeFlags::DEFAULT;
    let design = match d.design {
        StrikeDesign::Cj => "cj",
        StrikeDesign::Cl => "cl",
    };
    let support = match d.support {
        flexrig::driven::drive::HeadSupport::Wall => "wall",
        _ => "free",
    };
    let v = serde_json::json!({
        "design": design, "support": support, "m_r": d.m_r, "length": d.length,
        "k_delta": d.k_delta, "m_e": d.m_e, "rotor_inertia": d.rotor_inertia,
        "gear_ratio": d.gear_ratio, "friction": d.friction, "speed": d.speed,
        "ramp_time": d.ramp_time, "kp": d.kp, "kd": d.kd, "torque_limit": d.torque_limit,
        "m_h": d.m_h, "k_c": d.k_c, "n": d.n, "settle": d.settle, "horizon": d.horizon,
        "dome_radius": d.dome_radius, "dome_standoff": d.dome_standoff,
        "link_model": match d.link_model {
            LinkModel::Exact => "exact",
            LinkModel::Linear => "linear",
        },
    });
    json_to_py(py, &v)
}

/// The defaults of `flexrig spin-up`'s flags ([`SpinUpFlags::DEFAULT`]: Simo & Vu-Quoc's
/// beam, its numbers `None` for the case's) by keyword argument.
#[pyfunction]
pub fn spin_up_defaults(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    let d = SpinUpFlags::DEFAULT;
    let v = serde_json::json!({
        "case": d.case.name(), "length": d.length, "area": d.area,
        "second_moment": d.second_moment, "youngs_modulus": d.youngs_modulus,
        "density": d.density, "t_s": d.t_s, "omega_s": d.omega_s, "elements": d.elements,
        "duration": d.duration, "sample_every": d.sample_every, "max_step": d.max_step,
        "modes": d.modes,
    });
    json_to_py(py, &v)
}

/// The role-switch table as `flexrig role-switch` runs it; writes into `out` (the figure at the
/// printed width `size`, in `format`s, PNG at `dpi`, as `--size`, `--format`, `--dpi`); returns
/// (rows as a list of dicts, csv path, the figures' paths).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, kappa, rotor_ratio, damping_ratio, fig6, size, format, dpi, link_model))]
pub fn role_switch<'py>(
    py: Python<'py>,
    out: PathBuf,
    kappa: Vec<f64>,
    rotor_ratio: f64,
    damping_ratio: f64,
    fig6: bool,
    size: &str,
    format: Vec<String>,
    dpi: f64,
    link_model: &str,
) -> PyResult<(Bound<'py, PyAny>, PathBuf, Vec<PathBuf>)> {
    let options = RoleSwitchOptions {
        kappas: kappa,
        rotor_ratio,
        damping_ratio,
        fig6,
        link_model: LinkModel::parse("--link-model", link_model).map_err(flag_error)?,
    };
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let cancel = CancelToken::new();
    let result = detached(py, &cancel, || {
        run_role_switch(&options, &out, &figures, &cancel)
    })?
    .map_err(py_error)?;
    Ok((to_object(py, &result.rows)?, result.csv, result.figures))
}
