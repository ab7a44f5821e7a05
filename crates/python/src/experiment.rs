//! The test-bed studies (`flexrig experiment`, `flexrig payload`): the options checked by the
//! library as for the flags, the runs with the GIL released (Ctrl-C stops them), and the report
//! the command prints with `--json`.

use std::path::PathBuf;

use flexrig::fe::payload::PayloadOptions;
use flexrig::testbed::experiment::ExperimentOptions;
use flexrig::{CancelToken, NoProgress, fronts};
use pyo3::prelude::*;

use crate::convert::json_to_py;
use crate::{detached, flag_error};

/// `flexrig experiment --json` for the same inputs (`overrides` as `--set`); writes an MCAP log
/// per run, experiment.csv and fig9 into `out`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, repeats, jitter_deg, seed, scenes, overrides, size, format, dpi))]
pub fn experiment<'py>(
    py: Python<'py>,
    out: PathBuf,
    repeats: usize,
    jitter_deg: f64,
    seed: u64,
    scenes: Option<PathBuf>,
    overrides: Vec<(String, Bound<'py, PyAny>)>,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let mut options = ExperimentOptions {
        repeats,
        jitter_deg,
        seed,
        out,
        scenes,
        overrides: Vec::new(),
        figures: fronts::figure_options(size, &format, dpi).map_err(flag_error)?,
    };
    options.validate().map_err(flag_error)?;
    options.overrides = crate::run::overrides(&overrides)?;
    let cancel = CancelToken::new();
    let r = detached(py, &cancel, || {
        flexrig::testbed::experiment::run(&options, &cancel, &NoProgress)
    })?
    .map_err(flag_error)?;
    json_to_py(py, &fronts::experiment_report(&r))
}

/// `flexrig payload --json` for the same inputs; writes payload.csv, the figure and three
/// points' MCAP logs into `out`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, scene, payloads, points, size, format, dpi))]
pub fn payload<'py>(
    py: Python<'py>,
    out: PathBuf,
    scene: String,
    payloads: &str,
    points: usize,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let (from, to, points) =
        flexrig::fe::payload::parse_payloads(payloads, points).map_err(flag_error)?;
    let options = PayloadOptions {
        scene,
        from,
        to,
        points,
        out,
        figures: fronts::figure_options(size, &format, dpi).map_err(flag_error)?,
    };
    let cancel = CancelToken::new();
    let r = detached(py, &cancel, || flexrig::fe::payload::run(&options, &cancel))?
        .map_err(flag_error)?;
    json_to_py(py, &fronts::payload_report(&r))
}
