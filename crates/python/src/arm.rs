//! A real arm along its trajectory ([`flexrig::arm`]): the input and the report cross as JSON,
//! so the Python result holds exactly the numbers of `flexrig arm --json`; the trajectory comes
//! as a CSV file or as arrays of times and joint positions (the Python wrapper `flexrig.arm`
//! takes NumPy arrays and returns a pandas DataFrame beside the report).

use flexrig::arm::{ArmDrive, ArmInput, Robot, Trajectory, bundled, simulation_settings};
use pyo3::prelude::*;

use crate::{flag_error, input_error, to_py};

/// The report of [`flexrig::arm::judge`] as JSON. `input_json` is [`ArmInput`]'s serde form
/// without `simulation`, plus `drive` (`"free"` or `"held"`), `tol` and `root_rtol`; the arm is
/// the URDF file `urdf` (absent: the bundled UR5), the trajectory the CSV file `trajectory` or
/// `times` (s) with `positions` (one row per sample, rad or m, the URDF's joint order; absent:
/// the UR5's bundled swing); the points default to the UR5's when the arm is bundled.
#[pyfunction]
#[pyo3(signature = (input_json, urdf=None, trajectory=None, times=None, positions=None, body_model_toml=None))]
pub fn arm_json(
    py: Python<'_>,
    input_json: &str,
    urdf: Option<&str>,
    trajectory: Option<&str>,
    times: Option<Vec<f64>>,
    positions: Option<Vec<Vec<f64>>>,
    body_model_toml: Option<&str>,
) -> PyResult<String> {
    let mut value: serde_json::Value = serde_json::from_str(input_json)
        .map_err(|e| input_error("input", format!("invalid arm input: {e}")))?;
    let drive: ArmDrive = serde_json::from_value(value["drive"].take())
        .map_err(|_| input_error("drive", "invalid argument drive: 'free' or 'held'".into()))?;
    let tol = value["tol"].as_f64().unwrap_or(1e-6);
    let root_rtol = value["root_rtol"].as_f64().unwrap_or(1e-6);
    value["simulation"] = serde_json::to_value(simulation_settings(drive, tol, root_rtol))
        .map_err(|e| input_error("input", e.to_string()))?;
    let (robot, defaults): (Robot, _) = match urdf {
        Some(path) => (
            Robot::from_urdf_file(path).map_err(|e| to_py(e.into()))?,
            Vec::new(),
        ),
        None => (bundled::ur5().map_err(to_py)?, bundled::ur5_points()),
    };
    if let Some(items) = value["points"].as_array().cloned() {
        let mut parsed = Vec::with_capacity(items.len());
        for item in items {
            parsed.push(match item.as_str() {
                Some(text) => flexrig::arm::ArmPoint::parse(text).map_err(flag_error)?,
                None => serde_json::from_value(item)
                    .map_err(|e| input_error("points", format!("invalid argument points: {e}")))?,
            });
        }
        value["points"] = serde_json::to_value(&parsed).expect("points serialise");
    }
    if value["points"].as_array().is_none_or(|p| p.is_empty()) {
        if defaults.is_empty() {
            return Err(input_error(
                "points",
                "invalid argument points: give at least one contact point 'LINK:x,y,z' (m, in \
                 the link's frame) on your arm, e.g. points=['tool0:0,0,0.1']"
                    .into(),
            ));
        }
        value["points"] = serde_json::to_value(&defaults).expect("points serialise");
    }
    let input: ArmInput = serde_json::from_value(value)
        .map_err(|e| input_error("input", format!("invalid arm input: {e}")))?;
    let traj = match (trajectory, times, positions) {
        (Some(path), None, None) => {
            Trajectory::from_csv_file(&robot, path).map_err(|e| to_py(e.into()))?
        }
        (None, Some(t), Some(q)) => Trajectory::new(&robot, t, q).map_err(|e| to_py(e.into()))?,
        (None, None, None) if urdf.is_none() => bundled::ur5_swing(&robot).map_err(to_py)?,
        (None, None, None) => {
            return Err(input_error(
                "trajectory",
                "invalid argument trajectory: your arm needs a trajectory (a CSV file, or times \
                 and positions)"
                    .into(),
            ));
        }
        _ => {
            return Err(input_error(
                "trajectory",
                "invalid argument trajectory: give either a CSV file or times with positions \
                 (both arrays)"
                    .into(),
            ));
        }
    };
    let model = body_model_toml
        .map(|t| {
            flexrig::safety::body_model_from_text(t, "body_model")
                .map_err(|e| input_error("body_model", e.to_string()))
        })
        .transpose()?;
    let cancel = flexrig::CancelToken::new();
    let report = crate::detached(py, &cancel, || {
        flexrig::arm::judge_cancellable(&robot, &traj, &input, model.as_ref(), &cancel)
    })?
    .map_err(flag_error)?;
    serde_json::to_string(&report)
        .map_err(|e| input_error("input", format!("the report does not serialise: {e}")))
}
