//! Loads that depend on the motion of a node: a contact spring to a body that moves on its own
//! (the rig's dome against the operator's block), a follower or a grounded spring.
//!
//! The time integrators treat such a load implicitly: it enters the Newton residual at the end of
//! the step, evaluated at the node's unknown displacement and velocity, and its derivatives enter
//! the iteration matrix, S ← S − (c_q ∂F/∂q + c_v ∂F/∂q̇) on the node's three DOFs. A stiff load
//! (a Hertz contact on a finely meshed tip) is then as stable as the beam's own stiffness, where
//! a load computed from a predicted node motion (explicit) loses stability once the contact
//! stiffness meets the fast tip modes of a fine mesh.
//!
//! The beam crate knows nothing of contact: the caller implements [`NodeLoad`].

/// Force on a node and its derivatives with respect to the node's motion.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct NodeForce {
    /// (F_x \[N\], F_y \[N\], M [N·m]) on the node's (u, v, θ), in the global frame.
    pub force: [f64; 3],
    /// ∂F_i/∂q_j with q = (u \[m\], v \[m\], θ \[rad\]) of the node.
    pub d_dq: [[f64; 3]; 3],
    /// ∂F_i/∂q̇_j with q̇ = (u̇ [m/s], v̇ [m/s], θ̇ [rad/s]) of the node.
    pub d_dv: [[f64; 3]; 3],
}

impl NodeForce {
    /// No force.
    pub const ZERO: NodeForce = NodeForce {
        force: [0.0; 3],
        d_dq: [[0.0; 3]; 3],
        d_dv: [[0.0; 3]; 3],
    };

    /// True when the force and both derivatives are finite.
    pub fn is_finite(&self) -> bool {
        self.force.iter().all(|x| x.is_finite())
            && self.d_dq.iter().flatten().all(|x| x.is_finite())
            && self.d_dv.iter().flatten().all(|x| x.is_finite())
    }
}

/// A load on one node that depends on the node's displacement and velocity and on time.
///
/// The derivatives need not be exact (they only set Newton's rate of convergence, not the
/// solution), but the stiffness part must be there for stability: leave out nothing of the
/// order of the load's own stiffness.
pub trait NodeLoad {
    /// The loaded node (0 at the root, N at the tip).
    fn node(&self) -> usize;

    /// The force at time `t` \[s\] (within the step being taken) for the node displacement `q`
    /// (u \[m\], v \[m\], θ \[rad\]) and velocity `v` ([m/s], [m/s], [rad/s]).
    fn evaluate(&mut self, t: f64, q: [f64; 3], v: [f64; 3]) -> NodeForce;
}
