//! The permissible speed near a body region ([`flexrig::safety`]): the input and the report
//! cross as JSON, so the Python result holds exactly the numbers of `flexrig safety --json`; its
//! warnings name the keyword arguments (`m_r`) where the command's name its flags (`--m-r`).

use flexrig::safety::{BodyModel, SafetyInput, safety_cancellable};
use pyo3::prelude::*;

use crate::{input_error, to_py};

/// The report of [`flexrig::safety::safety`] as JSON for a [`SafetyInput`] given as JSON (the
/// serde form; the Python wrapper `flexrig.safety` builds it from keyword arguments), with the
/// body model of the TOML text `body_model_toml` or the bundled ISO/TS 15066:2016 table.
#[pyfunction]
#[pyo3(signature = (input_json, body_model_toml=None))]
pub fn safety_json(
    py: Python<'_>,
    input_json: &str,
    body_model_toml: Option<&str>,
) -> PyResult<String> {
    let input: SafetyInput = serde_json::from_str(input_json)
        .map_err(|e| input_error("input", format!("invalid safety input: {e}")))?;
    let model = body_model_toml.map(body_model).transpose()?;
    let cancel = flexrig::CancelToken::new();
    let mut report = crate::detached(py, &cancel, || {
        safety_cancellable(&input, model.as_ref(), &cancel)
    })?
    .map_err(to_py)?;
    crate::keyword_warnings(&mut report.warnings);
    serde_json::to_string(&report)
        .map_err(|e| input_error("input", format!("the report does not serialise: {e}")))
}

/// The body model of the TOML `text` of the keyword argument `body_model` (an error names it).
fn body_model(text: &str) -> PyResult<BodyModel> {
    BodyModel::from_toml_str(text).map_err(|e| {
        let why = e.to_string();
        input_error(
            "body_model",
            format!(
                "invalid argument body_model: {}",
                flexrig_rig::format_message::plain(
                    why.strip_prefix("body-model file: ").unwrap_or(&why)
                )
            ),
        )
    })
}

/// The safe-speed map of [`flexrig::safety::map::safety_map`] as JSON (what `flexrig safety-map`
/// writes to safety_map.json) for a [`flexrig::safety::map::SafetyMapInput`] given as JSON; an
/// axis may also be `{"text": "PARAM=FROM:TO:N[:log]"}`, parsed as the command line
/// parses `--x`/`--y`. Ctrl-C stops it (KeyboardInterrupt).
#[pyfunction]
#[pyo3(signature = (input_json, body_model_toml=None))]
pub fn safety_map_json(
    py: Python<'_>,
    input_json: &str,
    body_model_toml: Option<&str>,
) -> PyResult<String> {
    let mut value: serde_json::Value = serde_json::from_str(input_json)
        .map_err(|e| input_error("input", format!("invalid safety map input: {e}")))?;
    for axis in ["x", "y"] {
        if let Some(text) = value[axis].get("text").and_then(|t| t.as_str()) {
            let parsed = flexrig::safety::map::parse_axis(axis, text).map_err(to_py)?;
            value[axis] = serde_json::to_value(parsed)
                .map_err(|e| input_error(axis, format!("{axis}: {e}")))?;
        }
    }
    let input: flexrig::safety::map::SafetyMapInput = serde_json::from_value(value)
        .map_err(|e| input_error("input", format!("invalid safety map input: {e}")))?;
    let model = body_model_toml.map(body_model).transpose()?;
    let cancel = flexrig::CancelToken::new();
    let mut map = crate::detached(py, &cancel, || {
        flexrig::safety::map::safety_map(&input, model.as_ref(), &cancel)
    })?
    .map_err(to_py)?;
    crate::keyword_warnings(&mut map.warnings);
    serde_json::to_string(&map)
        .map_err(|e| input_error("input", format!("the map does not serialise: {e}")))
}

/// The report of `flexrig safety --trace FILE --json` ([`flexrig::safety::measured::judge_trace`])
/// for a [`flexrig::safety::measured::TraceInput`] given as JSON (the Python wrapper
/// `flexrig.safety(region, trace=…)` builds it), with the body model of the TOML text
/// `body_model_toml` or the bundled ISO/TS 15066:2016 table.
#[pyfunction]
#[pyo3(signature = (input_json, body_model_toml=None))]
pub fn safety_trace_json(
    py: Python<'_>,
    input_json: &str,
    body_model_toml: Option<&str>,
) -> PyResult<String> {
    let input: flexrig::safety::measured::TraceInput = serde_json::from_str(input_json)
        .map_err(|e| input_error("input", format!("invalid trace input: {e}")))?;
    let model = body_model_toml
        .map(BodyModel::from_toml_str)
        .transpose()
        .map_err(|e| to_py(flexrig::Error::from(e)))?;
    let mut report = py
        .detach(|| flexrig::safety::measured::judge_trace(&input, model.as_ref()))
        .map_err(crate::flag_error)?;
    crate::keyword_warnings(&mut report.warnings);
    serde_json::to_string(&report)
        .map_err(|e| input_error("input", format!("the report does not serialise: {e}")))
}

/// An area with its unit (`"1cm2"`, `"1e-4m2"`, `"100mm2"`) in m², as `--contact-area` reads
/// it ([`flexrig::safety::measured::parse_area`]); a bare number is refused.
#[pyfunction]
pub fn parse_area(text: &str) -> PyResult<f64> {
    flexrig::safety::measured::parse_area("--contact-area", text).map_err(crate::flag_error)
}
