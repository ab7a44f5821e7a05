//! The driven robot (docs/driven.md): the spin-up beam benchmark, one driven strike and the
//! role-switch table, over [`flexrig::driven`]; results as the library's serialised structs (the
//! Python wrappers in `flexrig/__init__.py` turn them into NumPy arrays and DataFrames).

use std::path::PathBuf;

use flexrig::driven::role_switch::{RoleSwitchOptions, run_with_figures as run_role_switch};
use flexrig::driven::spin_up::{SpinUpOptions, run_with_figures as run_spin_up};
use flexrig::driven::strike::{StrikeDescription, StrikeOptions, run as run_strike};
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
        _ => to_py(e),
    }
}

fn to_object<'py>(py: Python<'py>, value: &impl Serialize) -> PyResult<Bound<'py, PyAny>> {
    let v = serde_json::to_value(value)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    json_to_py(py, &v)
}

/// The spin-up benchmark as `flexrig spin-up` runs it; writes into `out` (the figure at the
/// printed width `size`, in `format`s, PNG at `dpi`, as `--size`, `--format`, `--dpi`); returns
/// the serialised `SpinUpResult` (a dict).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, length, area, second_moment, youngs_modulus, density, t_s, omega_s, elements, duration, sample_every, max_step, modes, size, format, dpi))]
pub fn spin_up<'py>(
    py: Python<'py>,
    out: PathBuf,
    length: f64,
    area: f64,
    second_moment: f64,
    youngs_modulus: f64,
    density: f64,
    t_s: f64,
    omega_s: f64,
    elements: usize,
    duration: Option<f64>,
    sample_every: f64,
    max_step: f64,
    modes: usize,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let options = SpinUpOptions {
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
        run_spin_up(&options, &out, &figures, &cancel)
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
    let options = StrikeOptions { trace_every, out };
    let cancel = CancelToken::new();
    let result =
        detached(py, &cancel, || run_strike(&description, &options, &cancel))?.map_err(py_error)?;
    to_object(py, &result)
}

/// The role-switch table as `flexrig role-switch` runs it; writes into `out` (the figure at the
/// printed width `size`, in `format`s, PNG at `dpi`, as `--size`, `--format`, `--dpi`); returns
/// (rows as a list of dicts, csv path, the figures' paths).
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, kappa, rotor_ratio, damping_ratio, fig6, size, format, dpi))]
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
) -> PyResult<(Bound<'py, PyAny>, PathBuf, Vec<PathBuf>)> {
    let options = RoleSwitchOptions {
        kappas: kappa,
        rotor_ratio,
        damping_ratio,
        fig6,
    };
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let cancel = CancelToken::new();
    let result = detached(py, &cancel, || {
        run_role_switch(&options, &out, &figures, &cancel)
    })?
    .map_err(py_error)?;
    Ok((to_object(py, &result.rows)?, result.csv, result.figures))
}
