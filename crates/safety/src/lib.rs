//! flexrig-safety: severity measures and permissible speeds for human–robot contact.
//!
//! Pure functions, no simulation inside:
//!
//! - [`BodyModel`]: the ISO/TS 15066:2016 Annex A body model as data with provenance
//!   (`assets/safety/iso_ts_15066_2016.toml`: Table A.2 force and pressure limits of the 29 body
//!   areas in 12 regions, Table A.3 K and m_H, the transient factor and the head/face
//!   prohibition). User tables in the same format load with [`BodyModel::from_toml_str`].
//! - Severity over sampled traces: [`hic`] (exact for the piecewise-linear interpolant; HIC15,
//!   HIC36), [`hic_half_sine`] (closed form), [`peak_force`], [`peak_pressure`] with a
//!   [`ContactAreaModel`] (Hertz sphere, thin layer, fixed area), [`loading_work`] and
//!   [`relative_kinetic_energy`]; all of them at once for a run summary with [`severity`] (the
//!   one function the test bed, the lumped and FE impacts, sweeps and logs use).
//! - Permissible speed: [`StandardContact`] (the standard's formula, Eq. A.1–A.6) and
//!   [`EnergyContact`] (the paper's energy method with a Hertz skin law and the link's series
//!   compliance, Eq. 4–13), each giving a [`PermissibleSpeed`] (which limit governs) and a
//!   [`Verdict`] at a speed; [`speed_map`] over robot masses × link stiffnesses. Transient
//!   contact with head or face is refused with [`SafetyError::ContactNotPermitted`] citing the
//!   clause.
//!
//! Units are SI (m, kg, s, N, Pa, J) except where a name says otherwise (`*_n_per_mm`,
//! `*_n_per_cm2` are the table's own units; HIC uses g₀).
//!
//! ```
//! use flexrig_safety::{BodyModel, ContactKind, RobotMass, StandardContact};
//! let model = BodyModel::iso_ts_15066_2016()?;
//! let hand = model.region("hands_and_fingers")?;
//! let m_r = RobotMass { total_moving_mass: 20.0, payload: 1.0 }.effective()?;
//! let contact = StandardContact { region: hand, area: None, robot_mass: m_r, kind: ContactKind::Transient };
//! let v = contact.permissible_speed()?;
//! // F_T = 2 × 140 N, k = 75 N/mm, μ = (1/0.6 + 1/11)⁻¹ kg.
//! let mu: f64 = 1.0 / (1.0 / 0.6 + 1.0 / 11.0);
//! assert!((v.v_max - 280.0 / (mu * 75.0e3).sqrt()).abs() < 1e-12);
//! # Ok::<(), flexrig_safety::SafetyError>(())
//! ```

mod body_model;
mod body_model_file;
mod contact_area;
mod energy;
mod energy_method;
mod error;
mod hic;
mod severity;
mod speed;
mod standard;
mod trace;

pub use body_model::{
    BUNDLED_BODY_MODEL_TOML, BodyArea, BodyModel, BodyRegion, ContactKind, Limits,
    N_PER_M_PER_N_PER_MM, PA_PER_N_PER_CM2, Provenance, TransientRule,
};
pub use contact_area::{ContactAreaModel, peak_pressure};
pub use energy::{loading_work, peak_force, relative_kinetic_energy, spring_energy_at_force};
pub use energy_method::{EnergyContact, LinkStiffness, PressureCrossing, speed_map};
pub use error::SafetyError;

/// A name as a message quotes it: in double quotes, control and invisible format characters
/// written as their code point (U+202E), never as Rust escapes; at most 120 characters.
pub fn quoted_name(name: &str) -> String {
    body_model_file::quoted(name)
}
pub use hic::{
    HicResult, HicWindow, STANDARD_GRAVITY, half_sine_optimal_phase, hic, hic_half_sine,
};
pub use severity::{
    ContactTraces, HIC_METHOD, HicSeverity, PressureSeverity, Severity, contact_work, severity,
};
pub use speed::{GoverningLimit, PermissibleSpeed, Verdict};
pub use standard::{RobotMass, StandardContact, reduced_mass};
