//! A real arm from its URDF along a trajectory, judged by the safety methods (docs/arm.md): at
//! every sample and every candidate contact point, the point's speed, its contact direction (the
//! velocity's), the arm's reflected mass there (flexrig-robot: m_u = 1/(uᵀ J M⁻¹ Jᵀ u)), and the
//! permissible speed of the compliant impact of that mass into a body region by the methods of
//! [`crate::safety`] — the same function `flexrig safety` calls, so the same rules (every contact,
//! one person, the overall verdict the most restrictive method, named) — then the ratio of each
//! point's speed to it, the speed-scaling factor of the whole trajectory and the verdict
//! ([`judge`]). Its fronts' pieces: the figure ([`plot`]), the Foxglove log ([`log`]) and the
//! report for a risk assessment ([`report`]). The bundled UR5 and its swing are in [`bundled`].
//!
//! May use: `shared`, `plots`, `log`, `safety`.

pub mod bundled;
pub mod judge;
pub mod log;
pub mod plot;
pub mod report;

pub use flexrig_robot::{Robot, Trajectory};
pub use judge::{
    ArmDrive, ArmInput, ArmJoints, ArmPoint, ArmReport, Governing, MassAnswer, PointResult,
    SampleResult, effective_mass_node, judge, judge_cancellable, simulation_settings,
};
