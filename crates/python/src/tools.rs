//! The model checks and tools (`flexrig fit`, `beam modal`, `beam static`, `prb`, `validate`,
//! `bench`):
//! the inputs checked by the same library functions as the flags ([`flexrig::fronts`]), the
//! computation with the GIL released, and the report the command prints with `--json`.

use std::path::PathBuf;

use flexrig::fronts;
use pyo3::prelude::*;

use crate::convert::json_to_py;
use crate::flag_error;

/// `flexrig fit FILE --json`: the Hertz fit f = k δⁿ of the compression data in `file`.
#[pyfunction]
pub fn fit(py: Python<'_>, file: PathBuf) -> PyResult<Bound<'_, PyAny>> {
    let (fit, warnings) = py
        .detach(|| flexrig::lumped::fit::fit_file_with_warnings(&file))
        .map_err(flag_error)?;
    json_to_py(py, &fronts::fit_report(&fit, &warnings))
}

/// The beam of `flexrig beam`'s flags (each number optional when `scene` gives the link).
#[allow(clippy::too_many_arguments)]
fn beam(
    scene: Option<PathBuf>,
    length: Option<f64>,
    youngs: Option<f64>,
    density: Option<f64>,
    width: Option<f64>,
    thickness: Option<f64>,
    elements: Option<usize>,
    tip_mass: Option<f64>,
    root: &str,
    k_theta: f64,
) -> PyResult<(flexrig::fe::beam::BeamInput, Option<String>)> {
    fronts::beam_input(&fronts::BeamFlags {
        scene,
        length,
        youngs,
        density,
        width,
        thickness,
        elements,
        tip_mass,
        root: root.to_string(),
        k_theta,
    })
    .map_err(flag_error)
}

/// `flexrig beam modal --json`: the natural frequencies [Hz].
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (scene, length, youngs, density, width, thickness, elements, tip_mass, root, k_theta, modes))]
pub fn beam_modal<'py>(
    py: Python<'py>,
    scene: Option<PathBuf>,
    length: Option<f64>,
    youngs: Option<f64>,
    density: Option<f64>,
    width: Option<f64>,
    thickness: Option<f64>,
    elements: Option<usize>,
    tip_mass: Option<f64>,
    root: &str,
    k_theta: f64,
    modes: usize,
) -> PyResult<Bound<'py, PyAny>> {
    if let Some(elements) = elements {
        flexrig::fe::beam::check_modal_elements(elements).map_err(flag_error)?;
    }
    let (input, origin) = beam(
        scene, length, youngs, density, width, thickness, elements, tip_mass, root, k_theta,
    )?;
    let frequencies = py
        .detach(|| fronts::beam_modal(&input, modes))
        .map_err(flag_error)?;
    let mut warnings = flexrig::fe::beam::beam_warnings(&input);
    crate::keyword_beam_warnings(&mut warnings);
    json_to_py(
        py,
        &fronts::beam_modal_report(&frequencies, &warnings, origin.as_deref()),
    )
}

/// `flexrig beam static --json`: the tip displacement and the largest stress under a dead tip
/// load.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (scene, length, youngs, density, width, thickness, elements, tip_mass, root, k_theta, tip_load, tip_moment, model, load_steps, adaptive_steps, yield_strength))]
pub fn beam_static<'py>(
    py: Python<'py>,
    scene: Option<PathBuf>,
    length: Option<f64>,
    youngs: Option<f64>,
    density: Option<f64>,
    width: Option<f64>,
    thickness: Option<f64>,
    elements: Option<usize>,
    tip_mass: Option<f64>,
    root: &str,
    k_theta: f64,
    tip_load: f64,
    tip_moment: f64,
    model: &str,
    load_steps: usize,
    adaptive_steps: bool,
    yield_strength: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let load = fronts::beam_tip_load(tip_load, tip_moment, model, load_steps, adaptive_steps)
        .map_err(flag_error)?;
    let (input, origin) = beam(
        scene, length, youngs, density, width, thickness, elements, tip_mass, root, k_theta,
    )?;
    let (sol, mut warnings) = py
        .detach(|| fronts::beam_static(&input, &load, yield_strength))
        .map_err(flag_error)?;
    crate::keyword_beam_warnings(&mut warnings);
    json_to_py(
        py,
        &fronts::beam_static_report(&sol, model, &warnings, origin.as_deref(), yield_strength),
    )
}

/// `flexrig prb --json`: the PRB model against the large-deflection FE beam; writes prb.svg
/// into `out`.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
#[pyo3(signature = (out, elements, model, criterion, size, format, dpi))]
pub fn prb<'py>(
    py: Python<'py>,
    out: PathBuf,
    elements: usize,
    model: &str,
    criterion: &str,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let options =
        fronts::prb_options(elements, model, criterion, out, figures).map_err(flag_error)?;
    let r = py
        .detach(|| flexrig::fe::prb::run(&options))
        .map_err(flag_error)?;
    json_to_py(py, &fronts::prb_report(&options, &r))
}

/// `flexrig validate --json`: every verification case (failures are reported, not raised);
/// writes validation.md into `out`.
#[pyfunction]
pub fn validate(py: Python<'_>, quick: bool, out: PathBuf) -> PyResult<Bound<'_, PyAny>> {
    let r = py
        .detach(|| flexrig::quality::validation::run(quick, &out))
        .map_err(flag_error)?;
    json_to_py(py, &fronts::validation_report(&r))
}

/// `flexrig bench --json`: the work–precision studies (each row's error against its reference
/// and its median run time on this machine); writes the bench_*.svg plots into `out`.
#[pyfunction]
#[pyo3(signature = (quick, out, size, format, dpi))]
pub fn bench<'py>(
    py: Python<'py>,
    quick: bool,
    out: PathBuf,
    size: &str,
    format: Vec<String>,
    dpi: f64,
) -> PyResult<Bound<'py, PyAny>> {
    let figures = fronts::figure_options(size, &format, dpi).map_err(flag_error)?;
    let cancel = flexrig::CancelToken::new();
    let r = crate::detached(py, &cancel, || {
        flexrig::quality::bench::run_cancellable(quick, &out, &figures, &cancel)
    })?
    .map_err(flag_error)?;
    json_to_py(py, &fronts::bench_report(&r))
}
