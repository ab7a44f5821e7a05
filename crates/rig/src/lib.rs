//! flexrig-rig: the paper's drop-pendulum impact test bed (§VI, Fig. 7–8) replayed on
//! rapier3d-f64: an operator pendulum with a skinned block strikes the dome on the payload of a
//! robot link that is either a rigid link on a torsion spring (CJ) or a flexible finite-element
//! beam (CL, flexrig-beam). The contact force comes from the flexrig-contact callback each step;
//! virtual encoders, accelerometers and a force sensor sample the run.
//!
//! Units are SI; angles in rad unless a field name says `_deg`.

mod beam_link;
mod error;
pub mod geometry;
pub mod run;
pub mod scene;
pub mod sensors;
pub mod world;

pub use beam_link::{BeamLink, LinkVariant};
pub use error::RigError;
pub use run::{
    Frame, NoRecorder, Recorder, RunOptions, RunSummary, Simulation, StepOutcome, run_scene_text,
};
pub use scene::{Design, Scene, SceneFile};
