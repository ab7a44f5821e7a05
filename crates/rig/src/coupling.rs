//! How the parts of the rig exchange the contact force within a step, second order and stable.
//!
//! **Time levels.** Rapier's symplectic Euler (kick, then drift) keeps the hinge rates half a
//! step behind the angles. The rig keeps a *synchronised* state instead — angle, rate and
//! acceleration of each hinge at the same instant t_n — and turns each Rapier step into a
//! velocity-Verlet step: the torque applied over a step h after a step h_prev makes Rapier's kick
//! ω_{n−½} + h a_n (h_prev + h)/(2h) = ω_n + (h/2) a_n, so its drift gives
//! φ_{n+1} = φ_n + h ω_n + (h²/2) a_n (second order for any sequence of steps), and
//! ω_{n+1} = ω_{n+½} + (h/2) a_{n+1} once the forces at t_{n+1} are known ([`HingeMotion`]). A
//! velocity-dependent (damped) contact force at t_{n+1} needs ω_{n+1}, which needs the force:
//! one predictor–corrector pass, exact for an undamped law.
//!
//! **Compliant link.** The beam is integrated by generalized-α with the contact force at the end
//! of the step *implicit*: [`TipContact`] evaluates the dome–block contact at the tip's unknown
//! displacement and velocity (the operator at its exactly predicted angle) inside the beam's
//! Newton iteration and hands it the contact stiffness ∂f/∂δ and damping ∂f/∂δ̇ through the tip
//! section's rigid map. The operator, a single heavy hinge resolved by the contact step, stays
//! explicit (velocity Verlet). An explicit tip prediction (the earlier scheme) lost stability
//! once a fine mesh put fast tip modes against the Hertz spring.

use flexrig_beam::{NodeForce, NodeLoad};
use flexrig_contact::math::{Pose, Vector};
use flexrig_contact::{BodyKinematics, ContactCallback, DomeBlockContact};
use rapier3d_f64::glamx::DQuat;

use crate::hinge::HingeState;
use crate::world::RapierRig;

/// A hinge over one step from its synchronised state at `t0`: the angle of the velocity-Verlet
/// step, φ(t) = φ₀ + ω₀ τ + ½ a₀ τ² with τ = t − t₀ (exact at the step's end), and the rate
/// ω₀ + a₀ τ (first order in τ; it enters only damping forces, whose effect stays second order).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HingeMotion {
    /// Start of the step \[s\].
    pub t0: f64,
    /// Angle \[rad\] and rate [rad/s] at `t0`.
    pub start: HingeState,
    /// Angular acceleration at `t0` [rad/s²].
    pub accel: f64,
}

impl HingeMotion {
    /// The hinge state at time `t` \[s\].
    pub fn at(&self, t: f64) -> HingeState {
        let tau = t - self.t0;
        HingeState {
            angle: self.start.angle + tau * (self.start.rate + 0.5 * tau * self.accel),
            rate: self.start.rate + tau * self.accel,
        }
    }
}

/// Pose and velocity of the beam section at undeformed position x = `x0` \[m\] along the link
/// (world x; the link bends in the world xy plane) with nodal displacement `q` = (u \[m\], v \[m\],
/// θ \[rad\]) and velocity `v`: frame origin at the deformed node, turned by θ about z.
pub fn section_kinematics(x0: f64, q: [f64; 3], v: [f64; 3]) -> BodyKinematics {
    let position = Vector::new(x0 + q[0], q[1], 0.0);
    BodyKinematics {
        pose: Pose::from_parts(position, DQuat::from_rotation_z(q[2])),
        reference_point: position,
        linvel: Vector::new(v[0], v[1], 0.0),
        angvel: Vector::new(0.0, 0.0, v[2]),
    }
}

/// The dome–block contact as a load on the beam's tip node, for the implicit coupling.
#[derive(Debug)]
pub struct TipContact<'a> {
    /// The contact (geometry and law).
    pub contact: &'a DomeBlockContact,
    /// The operator's hinge geometry.
    pub rapier: &'a RapierRig,
    /// The operator over the step.
    pub operator: HingeMotion,
    /// Undeformed x of the tip node \[m\] (the link length).
    pub tip_x: f64,
    /// The tip node's index.
    pub tip: usize,
}

impl NodeLoad for TipContact<'_> {
    fn node(&self) -> usize {
        self.tip
    }

    /// With n the contact normal (dome → block), r the arm from the tip node to the dome's
    /// centre and g = (n_x, n_y, (e_z × r)·n) the rate of the indentation per unit tip motion
    /// (δ̇ = g·q̇ + block terms), the load on (u, v, θ) is Q = −f g, and
    /// ∂Q/∂q = −(∂f/∂δ) g gᵀ plus the turn of the arm: ∂g_θ/∂θ = −r·n, which adds f (r·n) on
    /// θθ and, through δ̇, (∂f/∂δ̇) θ̇ (r·n) g on the θ column; ∂Q/∂q̇ = −(∂f/∂δ̇) g gᵀ. Exact for a
    /// dome on a face of the block apart from the block's own rotation under the moving
    /// contact point (checked against finite differences in the tests).
    fn evaluate(&mut self, t: f64, q: [f64; 3], v: [f64; 3]) -> NodeForce {
        let tip = section_kinematics(self.tip_x, q, v);
        let block = self.rapier.operator_kinematics_at(self.operator.at(t));
        let Some(c) = self.contact.evaluate(&tip, &block) else {
            return NodeForce::ZERO;
        };
        let n = c.normal;
        let r = self.contact.dome_center(&tip.pose) - tip.pose.translation;
        let g = [n.x, n.y, r.x * n.y - r.y * n.x];
        let r_n = r.x * n.x + r.y * n.y;
        let law = self.contact.law();
        let stiffness = law.stiffness(c.indentation, c.rate);
        let damping = law.damping(c.indentation, c.rate);
        let mut out = NodeForce::ZERO;
        for i in 0..3 {
            out.force[i] = -c.force * g[i];
            for j in 0..3 {
                out.d_dq[i][j] = -stiffness * g[i] * g[j];
                out.d_dv[i][j] = -damping * g[i] * g[j];
            }
            out.d_dq[i][2] += damping * v[2] * r_n * g[i];
        }
        out.d_dq[2][2] += c.force * r_n;
        out
    }
}
