//! One run of a scene file with its overrides, logged to MCAP (with its Foxglove layout) or not,
//! and its summary as JSON. See also [`crate::traces`] (a run that keeps its traces in memory).

use std::path::{Path, PathBuf};

use flexrig_contact::Materials;
use flexrig_rig::overrides;
use flexrig_rig::{Interruptible, RunOptions, Simulation, scene_with_overrides};
use serde_json::json;

use crate::Error;
use crate::cancel::CancelToken;
use crate::mcap_log::{LogRates, LogTarget, run_logged};

/// The scene-edit and summary types of a run (flexrig-rig's), for callers of this module.
pub use flexrig_rig::{Override, RunSummary};

/// How a run logs: where, whether it may overwrite, how often, how the 3D view draws.
#[derive(Debug, Clone, Copy)]
pub struct LogRequest<'a> {
    /// The MCAP file (`--out`); none: no log.
    pub out: Option<&'a PathBuf>,
    /// Overwrite the log and its layout (`--force`).
    pub force: bool,
    /// What is logged how often.
    pub rates: LogRates,
    /// Factor on the CL beam's deflection in the 3D view (`--deformation-scale`).
    pub deformation_scale: f64,
}

/// Loads, validates and runs a scene (a bundled name or a scene file's path, see
/// [`crate::scenes::resolve`]; errors name `SCENE`), logging as `log` asks (MCAP and its Foxglove
/// layout). The log is always finished, with an `error` metadata record if the run failed.
pub fn run_scene_file(
    path: &Path,
    overrides: &[Override],
    log: LogRequest<'_>,
    cancel: &CancelToken,
) -> Result<RunSummary, Error> {
    let text = crate::scenes::resolve("SCENE", path)?.text;
    let scene = scene_with_overrides(&text, overrides, &Materials::bundled()?)?;
    // the log records the scene as run
    let text = overrides::apply(&text, overrides)?;
    let simulation = Simulation::new(&scene, RunOptions::default())?;
    let Some(out) = log.out else {
        return Ok(simulation.run(&mut Interruptible(cancel.flag()))?);
    };
    run_logged(
        simulation,
        &scene,
        &LogTarget {
            path: out,
            force: log.force,
            scene_text: &text,
            cancel: cancel.clone(),
            rates: log.rates,
            deformation_scale: log.deformation_scale,
        },
    )
}

/// The plausibility warnings of a scene (a bundled name or a file) with its overrides (what is valid but looks like a
/// mistake, [`flexrig_rig::plausibility`]), for a front to show before the run starts; none if
/// the scene cannot be loaded (the run itself then says why).
pub fn scene_warnings(
    path: &Path,
    overrides: &[Override],
) -> Vec<flexrig_rig::plausibility::Warning> {
    let Ok(crate::scenes::SceneSource { text, .. }) = crate::scenes::resolve("SCENE", path) else {
        return Vec::new();
    };
    let Ok(materials) = Materials::bundled() else {
        return Vec::new();
    };
    scene_with_overrides(&text, overrides, &materials)
        .map(|scene| scene.warnings)
        .unwrap_or_default()
}

/// The run summary as `flexrig run --json` prints it: every field of [`RunSummary`] (absent
/// when it does not apply, e.g. `contact_duration_s` for a run stopped at the peak), the number
/// of sensor `samples` and the plausibility `warnings` (a list, empty when there are none).
pub fn summary_json(s: &RunSummary) -> serde_json::Value {
    let mut value = serde_json::to_value(s).expect("a run summary serialises");
    if let Some(map) = value.as_object_mut() {
        map.retain(|_, v| !v.is_null());
        map.insert("samples".into(), json!(s.samples.len()));
    }
    value
}
