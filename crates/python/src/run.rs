//! One run: the scene as TOML text (from a path, a bundled name, TOML text or a dict), the run
//! with overrides and its traces.

use std::path::PathBuf;

use flexrig::CancelToken;
use flexrig::testbed::run::summary_json;
use flexrig::testbed::traces::run_traced_logged;
use flexrig_rig::Override;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyMapping, PyString};

use crate::convert::{json_to_py, to_toml};
use crate::{detached, input_error, to_py};

/// The names of the bundled scenes (`flexrig.run("cj_aluminium")`).
#[pyfunction]
pub fn bundled_scenes() -> Vec<&'static str> {
    flexrig::testbed::scenes::bundled_names()
}

/// The bundled scenes as `flexrig scenes` lists them: (name, one-line description) pairs.
#[pyfunction]
pub fn scene_descriptions() -> Vec<(&'static str, String)> {
    flexrig::testbed::scenes::list_bundled()
        .into_iter()
        .map(|s| (s.name, s.summary))
        .collect()
}

/// Writes bundled scene `name` to `path` to edit it (`flexrig scenes --write NAME --out
/// PATH`); an existing file is kept unless `force` (InputError naming it).
#[pyfunction]
#[pyo3(signature = (name, path, force=false))]
pub fn write_scene(name: &str, path: PathBuf, force: bool) -> PyResult<()> {
    flexrig::testbed::scenes::write_bundled(name, &path, force).map_err(to_py)
}

/// The TOML text of `scene`: a path (str or os.PathLike) to a scene file, the name of a bundled
/// scene, TOML text, or a dict of the scene's tables. Returns (text, directory of the file or
/// None).
#[pyfunction]
pub fn scene_text(scene: &Bound<'_, PyAny>) -> PyResult<(String, Option<PathBuf>)> {
    if let Ok(mapping) = scene.cast::<PyMapping>() {
        let toml::Value::Table(table) = to_toml("", mapping.as_any())? else {
            unreachable!("a mapping converts to a table")
        };
        return Ok((
            toml::to_string(&table).map_err(|e| {
                input_error(
                    "scene",
                    format!("scene: cannot write the dict as TOML: {e}"),
                )
            })?,
            None,
        ));
    }
    if scene.is_instance_of::<PyString>() {
        let text: String = scene.extract()?;
        // TOML text has a key = value line; a path or a name has none
        if text.contains('=') || text.contains('\n') {
            return Ok((text, None));
        }
        return resolve(PathBuf::from(text));
    }
    // os.PathLike
    if let Ok(path) = scene.extract::<PathBuf>() {
        return resolve(path);
    }
    Err(input_error(
        "scene",
        format!(
            "scene: {} is not a scene: give a path, the name of a bundled scene ({}), TOML text \
             or a dict",
            scene.get_type().name()?,
            bundled_scenes().join(", ")
        ),
    ))
}

/// A bundled name or a file, resolved as the command line does (a near miss of a bundled name
/// is an InputError with "did you mean").
fn resolve(path: PathBuf) -> PyResult<(String, Option<PathBuf>)> {
    let source = flexrig::testbed::scenes::resolve("scene", &path).map_err(to_py)?;
    let Some(path) = source.path else {
        return Ok((source.text, None));
    };
    let text = source.text;
    let dir = path
        .canonicalize()
        .ok()
        .and_then(|p| p.parent().map(PathBuf::from));
    Ok((text, dir))
}

/// The overrides of a list of (dotted path, value) pairs; a malformed path or a value that is
/// not a scene value raises InputError naming it.
pub fn overrides(pairs: &[(String, Bound<'_, PyAny>)]) -> PyResult<Vec<Override>> {
    pairs
        .iter()
        .map(|(path, value)| {
            // the path is checked like a CLI override (a long path is quoted shortened)
            let shown: String = match path.char_indices().nth(80) {
                Some((end, _)) => format!("{}…", &path[..end]),
                None => path.clone(),
            };
            let levels = path.split('.').count();
            let checked = Override::parse(&format!("{path}=0")).map_err(|_| {
                let deep = if levels > flexrig_rig::overrides::MAX_PATH_DEPTH
                    || path.len() > flexrig_rig::overrides::MAX_PATH_LENGTH
                {
                    format!(
                        " at most {} levels and {} characters long (this one has {levels} \
                         levels),",
                        flexrig_rig::overrides::MAX_PATH_DEPTH,
                        flexrig_rig::overrides::MAX_PATH_LENGTH
                    )
                } else {
                    String::new()
                };
                input_error(
                    &shown,
                    format!(
                        "override {shown:?}: the path must be dotted field names,{deep} e.g. \
                         robot.payload_kg or operator.start.release_angle_deg"
                    ),
                )
            })?;
            Ok(Override::new(&checked.path, to_toml(&checked.path, value)?))
        })
        .collect()
}

/// The scene `text` with `overrides` applied, validated like the file (an error names the
/// field): the scene as a run with these overrides would run it.
#[pyfunction]
pub fn apply_overrides(text: &str, overrides: Vec<(String, Bound<'_, PyAny>)>) -> PyResult<String> {
    let overrides = self::overrides(&overrides)?;
    let materials = flexrig_contact::Materials::bundled().map_err(|e| to_py(e.into()))?;
    flexrig_rig::scene_with_overrides(text, &overrides, &materials).map_err(|e| to_py(e.into()))?;
    flexrig_rig::overrides::apply(text, &overrides).map_err(|e| to_py(e.into()))
}

fn array<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyAny> {
    PyArray1::from_vec(py, v).into_any()
}

/// Runs the scene `text` with `overrides` (GIL released; Ctrl-C stops it), logging it to the
/// MCAP file `out` with its Foxglove layout beside it if given (as `flexrig run --out`, with
/// `force`, `log_every_step` and `deformation_scale` as the flags). Returns (summary, sample
/// traces, step traces): the summary as `flexrig run --json` prints it (the link quantities
/// included), the traces as dicts of NumPy arrays.
#[pyfunction]
#[pyo3(signature = (text, overrides, out=None, force=false, log_every_step=false, deformation_scale=flexrig::log::mcap::DEFAULT_DEFORMATION_SCALE))]
pub fn run<'py>(
    py: Python<'py>,
    text: &str,
    overrides: Vec<(String, Bound<'py, PyAny>)>,
    out: Option<PathBuf>,
    force: bool,
    log_every_step: bool,
    deformation_scale: f64,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyDict>, Bound<'py, PyDict>)> {
    let overrides = self::overrides(&overrides)?;
    let deformation_scale =
        flexrig::shared::output::positive_arg("--deformation-scale", deformation_scale)
            .map_err(crate::flag_error)?;
    let log = flexrig::testbed::run::LogRequest {
        out: out.as_ref(),
        force,
        rates: if log_every_step {
            flexrig::log::mcap::LogRates::EVERY_STEP
        } else {
            flexrig::log::mcap::LogRates::DECIMATED
        },
        deformation_scale,
    };
    let cancel = CancelToken::new();
    if flexrig::driven::scene::is_driven_text(text) {
        // a driven scene: the strike's summary and its traces (no steps of a rig), its log
        // written as `flexrig run --out` writes it
        let (run, link) = detached(py, &cancel, || {
            let run = flexrig::testbed::run::run_driven_text(text, &overrides, log, &cancel)?;
            Ok::<_, flexrig::Error>((run, flexrig::testbed::link::of_text(text, &overrides)?))
        })?
        .map_err(crate::flag_error)?;
        let samples = PyDict::new(py);
        for (name, column) in run.traces.columns() {
            samples.set_item(name, array(py, column.clone()))?;
        }
        let summary = flexrig::testbed::run::driven_summary_json(&run.summary, &link);
        return Ok((json_to_py(py, &summary)?, samples, PyDict::new(py)));
    }
    let (summary, traces, link) = detached(py, &cancel, || {
        let (summary, traces) = run_traced_logged(text, &overrides, log, &cancel)?;
        Ok::<_, flexrig::Error>((
            summary,
            traces,
            flexrig::testbed::link::of_text(text, &overrides)?,
        ))
    })?
    .map_err(crate::flag_error)?;
    let s = traces.samples;
    let samples = PyDict::new(py);
    for (name, column) in [
        ("time_s", s.time_s),
        ("force_n", s.force_n),
        ("indentation_m", s.indentation_m),
        ("operator_accel_mps2", s.operator_accel_mps2),
        ("load_accel_mps2", s.load_accel_mps2),
        ("operator_angle_rad", s.operator_angle_rad),
        ("robot_angle_rad", s.robot_angle_rad),
        ("link_tip_deflection_m", s.link_tip_deflection_m),
    ] {
        samples.set_item(name, array(py, column))?;
    }
    let st = traces.steps;
    let steps = PyDict::new(py);
    for (name, column) in [
        ("time_s", st.time_s),
        ("dt_s", st.dt_s),
        ("force_n", st.force_n),
        ("indentation_m", st.indentation_m),
        ("energy_j", st.energy_j),
    ] {
        steps.set_item(name, array(py, column))?;
    }
    Ok((
        json_to_py(py, &summary_json(&summary, &link))?,
        samples,
        steps,
    ))
}
