//! flexrig-beam: a planar finite-element Euler–Bernoulli beam that replaces the ADAMS flexible
//! link of the paper (§VI).
//!
//! * [`section`]: the cross-section (EA, EI, ρA) from a material and a rectangle or given directly.
//! * [`model`]: the validated, serialisable [`BeamModel`] (mesh, root support, point masses,
//!   kinematics, mass lumping, Rayleigh damping) and the [`NodalLoads`] applied to it.
//! * [`element`]: the linear two-node Hermite-cubic element (stiffness) and the element inertia
//!   (consistent, rotation-invariant, or lumped mass).
//! * [`corotational`]: the corotational element for large displacement and rotation with its
//!   analytic tangent.
//! * [`ancf`]: the ANCF cable element (positions and slopes, constant mass, exact for rigid
//!   motion, O(h⁴) accurate in large deflection) and [`assembly_ancf`] its assembly
//!   ([`Kinematics::Ancf`]: 4 DOFs per node, loads and node queries still in (u, v, θ)).
//! * [`banded`]: a banded LU factorisation (partial pivoting), O(N) per solve.
//! * [`statics`], [`modal`], [`dynamics`] (generalized-α), [`energy`]: the solvers;
//!   [`energy_conserving`]: the energy-conserving midpoint step (discrete gradient) for the
//!   ANCF and linear models ([`GeneralizedAlpha::energy_conserving`]).
//! * [`reduced`]: the modal-reduced linear beam (lowest modes plus static correction shapes),
//!   stepped by the same generalized-α scheme — the shortcut for small deflections.
//! * [`prb`]: the Pseudo-Rigid-Body (γ, K_Θ) fit to the corotational or ANCF tip path (Howell's
//!   method).
//! * [`rotating_clamp`]: a beam clamped to a hub whose angle is prescribed (the spin-up
//!   benchmark), tip in the hub frame.
//! * [`canonical`]: canonical problems and their published references, shared by tests, benches
//!   and the CLI.
//!
//! ```
//! use flexrig_beam::{canonical, Kinematics, ModalDirection, modal_analysis};
//! // First bending frequency of a unit cantilever (EI = ρA = L = 1) with 16 elements against
//! // ω₁ = (1.8751040687)² √(EI/(ρA L⁴)).
//! let model = canonical::unit_cantilever(16, Kinematics::Linear)?;
//! let modes = modal_analysis(&model, 1, ModalDirection::Transverse)?;
//! let exact = 1.8751040687f64.powi(2);
//! assert!((modes.omegas[0] / exact - 1.0).abs() < 1e-6);
//! # Ok::<(), flexrig_beam::BeamError>(())
//! ```
//!
//! Every length is in m, force in N, moment in N·m, mass in kg, time in s, angle in rad.
//! Degrees of freedom: node `i` (0 at the root, `N` at the tip) carries `(u, v, θ)` at indices
//! `3i, 3i+1, 3i+2`; u is along the undeformed beam axis (x), v transverse (y), θ the section
//! rotation (counter-clockwise). The ANCF model carries `(u, v, r′ᵧ, r′ₓ − 1)` at `4i … 4i+3`
//! (see [`Kinematics::Ancf`]); use [`State::node`], [`State::node_velocity`],
//! [`State::node_acceleration`] and [`StaticSolution::node`] for (u, v, θ) with either layout.

// Index loops mirror the equations (DOF i, node j) in the numerics.
#![allow(clippy::needless_range_loop)]

pub mod ancf;
pub mod assembly;
pub mod assembly_ancf;
pub mod banded;
pub mod canonical;
pub mod corotational;
pub mod counters;
pub mod dynamics;
pub mod element;
pub mod energy;
pub mod energy_conserving;
mod error;
pub mod evaluation;
mod lanes;
pub mod modal;
pub mod model;
pub mod node_load;
pub mod prb;
pub mod reduced;
pub mod rotating_clamp;
pub mod section;
pub mod statics;

pub use counters::StepCounters;
pub use dynamics::{
    GeneralizedAlpha, MAX_STEP_HALVINGS, NewtonMethod, State, StepMemory, StepReport, Workspace,
    root_reaction,
};
pub use error::BeamError;
pub use modal::{ModalAnalysis, ModalDirection, modal_analysis};
pub use model::{
    BeamModel, BeamSpec, Kinematics, MassMatrix, NodalLoads, PointMass, Rayleigh, RootSupport,
};
pub use node_load::{NodeForce, NodeLoad};
pub use reduced::{ReducedModel, ReducedState};
pub use section::{Material, Section};
pub use statics::{StaticOptions, StaticSolution, solve_static};
