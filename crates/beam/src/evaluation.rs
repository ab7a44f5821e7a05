//! The inputs of one evaluation of the beam's residual and Jacobian, shared by the Hermite
//! ([`crate::assembly`]) and the ANCF ([`crate::assembly_ancf`]) assembly.

/// Weights of the Jacobian J = c_k ∂r/∂q + c_v ∂r/∂q̇ + c_a ∂r/∂q̈.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobianWeights {
    /// Weight of ∂r/∂q.
    pub stiffness: f64,
    /// Weight of ∂r/∂q̇.
    pub velocity: f64,
    /// Weight of ∂r/∂q̈.
    pub acceleration: f64,
}

/// Kinematic input of an evaluation: displacements, and for dynamics velocities and
/// accelerations (all with one entry per DOF).
#[derive(Debug, Clone, Copy)]
pub struct Kinematic<'a> {
    /// q [m, rad].
    pub q: &'a [f64],
    /// q̇, or `None` in statics.
    pub v: Option<&'a [f64]>,
    /// q̈, or `None` in statics.
    pub a: Option<&'a [f64]>,
}
