//! flexrig-rig: the paper's drop-pendulum impact test bed (§VI, Fig. 7–8) replayed on
//! rapier3d-f64: an operator pendulum with a skinned block strikes the dome on the payload of a
//! robot link that is either a rigid link on a torsion spring (CJ) or a flexible finite-element
//! beam (CL, flexrig-beam). The contact force comes from the flexrig-contact callback each step;
//! virtual encoders, accelerometers and a force sensor sample the run.
//!
//! Units are SI; angles in rad unless a field name says `_deg`.
//!
//! ```
//! use flexrig_contact::Materials;
//! use flexrig_rig::{NoRecorder, RunOptions, Scene, Simulation};
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/scenes/cj_aluminium.toml");
//! let scene = Scene::from_toml_str(&std::fs::read_to_string(path).unwrap(), &Materials::bundled()?)?;
//! let summary = Simulation::new(&scene, RunOptions::default())?.run(&mut NoRecorder)?;
//! // The 398 g aluminium operator released from 30° hits at 0.891 m/s with about 180 N.
//! assert!((summary.impact_velocity_mps - 0.8912).abs() < 1e-3);
//! assert!(summary.peak_force_n > 170.0 && summary.peak_force_n < 190.0);
//! # Ok::<(), flexrig_rig::RigError>(())
//! ```

mod beam_link;
pub mod canonical;
pub mod contact_flight;
pub mod coupling;
mod error;
pub mod format_message;
pub mod free_flight;
pub mod geometry;
pub mod hinge;
pub mod joint_drive;
pub mod limits;
pub mod overrides;
pub mod plausibility;
pub mod run;
pub mod scene;
mod scene_load;
pub mod sensors;
pub mod severity;
pub mod world;

pub use beam_link::{BeamLink, LinkCheckpoint, LinkVariant};
pub use error::RigError;
pub use joint_drive::{DriveFrame, DriveSummary, JointDrive};
pub use overrides::{Override, scene_from_table, scene_with_overrides};
pub use run::{
    ContactEvent, Frame, Interruptible, NoRecorder, Recorder, RunOptions, RunSummary, Simulation,
    StepOutcome, SwingSamples, run_scene_text,
};
pub use scene::{
    BeamSolverSpec, ContactPolicy, Design, RobotDriveSpec, Scene, SceneFile, SwingPolicy,
};
