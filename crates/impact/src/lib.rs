//! The paper's Fig. 5 impact at finite-element fidelity (issue 14): a free head of mass m_h
//! arriving at speed v0 strikes the tip payload m_e of a robot link, either a **compliant joint**
//! (CJ: a rigid uniform link of mass m_r and length L on a torsion spring k_θr = 3EI/L, Eq. 3)
//! or a **compliant link** (CL: a clamped Euler–Bernoulli beam with the same m_r, L and EI, meshed
//! with flexrig-beam's Hermite-cubic elements). Both links have the same lateral tip stiffness
//! k_δ = 3EI/L³. No pendulum, no gravity, no Rapier: only what the impact needs.
//!
//! **The joint during the impact** ([`Joint`]): held (driven at constant speed; in the joint's
//! frame the robot is at rest and the head arrives at v0), or a free hub with the motor's rotor
//! inertia J_R behind the torsion spring (CJ) or under the clamped beam (CL), the robot moving at
//! v0 into a head at rest. An infinite rotor is the held joint.
//!
//! The CJ is integrated by the 8th-order DOP853 of flexrig-lumped with the separation located on
//! its dense output; the CL by generalized-α at ρ∞ = 1 (energy-conserving for the linear beam)
//! with the contact implicit in the beam's Newton and the head stepped by velocity Verlet.
//! [`eta`] turns the paper's Fig. 6 design cases into η_FE = f_max(CL)/f_max(CJ) and the
//! effective γ of the lumped model.

pub mod chain;
pub mod cj;
pub mod cl;
pub mod cl_modal;
pub mod drive;
pub mod driven_cj;
pub mod driven_cl;
mod error;
pub mod eta;
pub mod exact_link;
pub mod graded;
pub mod horizon;
pub mod hub_modes;
pub mod map;
pub mod modal_run;
pub mod role_switch;
pub mod rotor;
pub mod setup;
pub mod severity;
pub mod spin_up;
pub mod strike;
pub mod tip_modes;

pub use drive::{
    Drive, DriveCommand, Gains, HeadSupport, Motor, Person, Placement, Profile, TorqueProfile,
};
pub use error::ImpactError;
pub use setup::{ClSolver, FreeMassImpact, ImpactOutcome, Joint, LinkParams, RunEnd};
pub use strike::{DriveNote, DrivenOutcome, DrivenStrike, EnergyBalance, TraceSample};
