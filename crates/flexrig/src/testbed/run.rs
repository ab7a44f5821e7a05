//! One run of a scene file with its overrides, logged to MCAP (with its Foxglove layout) or not,
//! and its summary as JSON. See also [`crate::testbed::traces`] (a run that keeps its traces in memory).
//!
//! A scene with a `[drive]` section is a driven scene ([`crate::driven::scene`]): it runs the
//! driven strike of flexrig-impact instead of the test bed's pendulum rig, and its run is a
//! [`SceneRun::Driven`].

use std::path::{Path, PathBuf};

use flexrig_contact::Materials;
use flexrig_rig::overrides;
use flexrig_rig::{Interruptible, RunOptions, Simulation, scene_with_overrides};
use serde_json::json;

use crate::Error;
use crate::driven::scene::{DrivenRun, DrivenScene, is_driven_text};
use crate::log::file::{LogTarget, run_logged};
use crate::log::mcap::LogRates;
use crate::shared::cancel::CancelToken;
use crate::testbed::link::LinkQuantities;

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

/// What a scene file's run returns: the test bed's summary, or a driven strike's run; each with
/// the scene's link quantities ([`crate::testbed::link`]).
#[derive(Debug, Clone)]
// one value per run, returned once: the test bed's summary is kept inline as before
#[allow(clippy::large_enum_variant)]
pub enum SceneRun {
    /// The drop-pendulum test bed (a scene without `[drive]`).
    Rig(RunSummary, LinkQuantities),
    /// A driven scene (with `[drive]`): summary, outcome and traces.
    Driven(Box<DrivenRun>, LinkQuantities),
}

impl SceneRun {
    /// The summary as `flexrig run --json` prints it, the link quantities included.
    pub fn summary_json(&self) -> serde_json::Value {
        match self {
            SceneRun::Rig(s, link) => summary_json(s, link),
            SceneRun::Driven(d, link) => driven_summary_json(&d.summary, link),
        }
    }

    /// The scene's link quantities.
    pub fn link(&self) -> &LinkQuantities {
        match self {
            SceneRun::Rig(_, link) | SceneRun::Driven(_, link) => link,
        }
    }
}

/// Loads, validates and runs a scene (a bundled name or a scene file's path, see
/// [`crate::testbed::scenes::resolve`]; errors name `SCENE`), logging as `log` asks (MCAP and its Foxglove
/// layout). The log is always finished, with an `error` metadata record if the run failed.
pub fn run_scene_file(
    path: &Path,
    overrides: &[Override],
    log: LogRequest<'_>,
    cancel: &CancelToken,
) -> Result<SceneRun, Error> {
    let text = crate::testbed::scenes::resolve("SCENE", path)?.text;
    if is_driven_text(&text) {
        let run = run_driven_text(&text, overrides, log, cancel)?;
        let link = crate::testbed::link::of_text(&text, overrides)?;
        return Ok(SceneRun::Driven(Box::new(run), link));
    }
    let summary = run_rig_text(&text, overrides, log, cancel)?;
    Ok(SceneRun::Rig(
        summary,
        crate::testbed::link::of_text(&text, overrides)?,
    ))
}

/// Runs a driven scene's `text` with `overrides`, logged as `log` asks.
pub fn run_driven_text(
    text: &str,
    overrides: &[Override],
    log: LogRequest<'_>,
    cancel: &CancelToken,
) -> Result<DrivenRun, Error> {
    let scene = DrivenScene::with_overrides(text, overrides)?;
    let Some(out) = log.out else {
        return crate::driven::scene::run(&scene, cancel);
    };
    let text = overrides::apply(text, overrides)?;
    crate::driven::log::run_logged(
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

fn run_rig_text(
    text: &str,
    overrides: &[Override],
    log: LogRequest<'_>,
    cancel: &CancelToken,
) -> Result<RunSummary, Error> {
    let text = text.to_string();
    let scene = scene_with_overrides(&text, overrides, &Materials::bundled()?)?;
    // the log records the scene as run
    let text = overrides::apply(&text, overrides)?;
    // without a log nothing reads the samples (the summary counts them): a lean run; a logged
    // run samples in full, as Python's `run(out=…)` does, so the two logs stay byte for byte equal
    let simulation = Simulation::new(&scene, RunOptions::default())?;
    let Some(out) = log.out else {
        return Ok(simulation
            .with_lean_samples()
            .run(&mut Interruptible(cancel.flag()))?);
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

/// The plausibility warnings of a scene (a bundled name or a file, the test bed's or a driven
/// one) with its overrides (what is valid but looks like a mistake, [`flexrig_rig::plausibility`]
/// and its shared rule for masses, lengths and speeds), for a front to show before the run
/// starts; none if the scene cannot be loaded (the run itself then says why).
pub fn scene_warnings(
    path: &Path,
    overrides: &[Override],
) -> Vec<flexrig_rig::plausibility::Warning> {
    let Ok(crate::testbed::scenes::SceneSource { text, .. }) =
        crate::testbed::scenes::resolve("SCENE", path)
    else {
        return Vec::new();
    };
    if is_driven_text(&text) {
        return DrivenScene::with_overrides(&text, overrides)
            .map(|scene| {
                scene
                    .strike
                    .warnings(crate::driven::strike::FieldNames::File)
            })
            .unwrap_or_default();
    }
    let Ok(materials) = Materials::bundled() else {
        return Vec::new();
    };
    scene_with_overrides(&text, overrides, &materials)
        .map(|scene| scene.warnings)
        .unwrap_or_default()
}

/// The run summary as `flexrig run --json` prints it: every field of [`RunSummary`] (absent
/// when it does not apply, e.g. `contact_duration_s` for a run stopped at the peak), the number
/// of sensor `samples`, the plausibility `warnings` (a list, empty when there are none) and the
/// scene's link quantities ([`crate::testbed::link::COLUMNS`]).
pub fn summary_json(s: &RunSummary, link: &LinkQuantities) -> serde_json::Value {
    let mut value = serde_json::to_value(s).expect("a run summary serialises");
    if let Some(map) = value.as_object_mut() {
        map.retain(|_, v| !v.is_null());
        map.insert("samples".into(), json!(s.sample_count));
    }
    link.insert_into(&mut value);
    value
}

/// The notes of a test-bed run with a motor on the robot joint, in words, as `flexrig run` and
/// a sweep's `notes` column give them: the time the controller spent at its torque limit (the
/// link then follows its command only where the limit allows). None without a drive or when the
/// limit was never reached.
pub fn drive_notes(s: &RunSummary) -> Vec<String> {
    let Some(d) = &s.drive else {
        return Vec::new();
    };
    let mut notes = Vec::new();
    if d.time_at_torque_limit_s > 0.0 {
        notes.push(format!(
            "the controller was at its torque limit for {:.6} s: the link follows its command \
             only where the limit allows",
            d.time_at_torque_limit_s
        ));
    }
    notes
}

/// A driven run's summary as `flexrig run --json` prints it: the strike's summary
/// ([`crate::driven::scene::summary_json`]) and the link quantities ([`crate::testbed::link::COLUMNS`]).
pub fn driven_summary_json(
    s: &crate::driven::scene::DrivenSummary,
    link: &LinkQuantities,
) -> serde_json::Value {
    let mut value = crate::driven::scene::summary_json(s);
    link.insert_into(&mut value);
    value
}
