//! The adaptive contact (`solver.contact = "adaptive"`, CJ): the two hinges in reduced
//! coordinates with the dome–block force in the right-hand side, integrated by the free
//! flight's DOP853 from the located onset to the located separation. Equations (y = (φ, φ̇, ψ,
//! ψ̇, sin φ, cos φ)):
//!
//! J_op φ̈ = −M g l_c sin φ + ((p − p_pivot) × f n)·e_x,
//! J_rob ψ̈ = −k_θr ψ + (p × (−f n))·e_z,
//!
//! with f = f(δ, δ̇) the contact law, n the normal from the dome into the block and p the
//! contact point (flexrig-contact's dome–block callback), the same forces as the Rapier path's
//! synchronised accelerations. The peak is the largest force on the dense output (Brent's
//! search next to the largest of the sampled values), the impulse Simpson's rule on the sampled
//! forces of each step.

use flexrig_contact::math::Vector;
use flexrig_contact::{ContactSample, DomeBlockContact};
use flexrig_lumped::ode::dop853::{DenseOutput, OdeSystem};

use crate::free_flight::{DIM, EVENT_SUBINTERVALS, FreeHinges};
use crate::hinge::HingeState;
use crate::sensors::SensorSample;
use crate::world::RapierRig;

/// The CJ's hinges with the contact force.
#[derive(Debug, Clone, Copy)]
pub struct HingesInContact<'a> {
    /// The motion without the contact (gravity, the torsion spring); `robot` must be set.
    pub free: FreeHinges,
    /// The contact (geometry and law).
    pub contact: &'a DomeBlockContact,
    /// The hinges' axes (poses and velocities of the bodies at a hinge state).
    pub rapier: &'a RapierRig,
    /// The operator's pivot [m, world].
    pub pivot: Vector,
}

impl HingesInContact<'_> {
    /// The contact in state `y`, if touching.
    pub fn sample(&self, y: &[f64; DIM]) -> Option<ContactSample> {
        let (dome, block) = self.bodies(y);
        self.contact.evaluate_direct(&dome, &block)
    }

    /// The signed dome–block gap \[m\] in state `y` (negative in contact).
    pub fn gap(&self, y: &[f64; DIM]) -> f64 {
        let (dome, block) = self.bodies(y);
        self.contact.gap_direct(&dome.pose, &block.pose)
    }

    /// The gap \[m\] and the approach rate [m/s] (> 0 closing) in state `y`.
    pub fn approach(&self, y: &[f64; DIM]) -> (f64, f64) {
        let (dome, block) = self.bodies(y);
        self.contact
            .approach_direct(&dome, &block)
            .unwrap_or((f64::INFINITY, 0.0))
    }

    fn bodies(
        &self,
        y: &[f64; DIM],
    ) -> (
        flexrig_contact::BodyKinematics,
        flexrig_contact::BodyKinematics,
    ) {
        let block = self.rapier.operator_kinematics_at(HingeState {
            angle: y[0],
            rate: y[1],
        });
        let dome = self.rapier.robot_kinematics_at(HingeState {
            angle: y[2],
            rate: y[3],
        });
        (dome, block)
    }

    /// The torques [N·m] of the contact `c` about the operator's pivot axis (x) and the robot
    /// axis (z through the origin).
    pub fn torques(&self, c: &ContactSample) -> (f64, f64) {
        (
            (c.point - self.pivot).cross(c.force_on_block()).x,
            c.point.cross(c.force_on_dome()).z,
        )
    }

    /// Every sensor at time `t` \[s\] in state `y`: as [`crate::free_flight::FlightSensors`]
    /// with the accelerations of the equations of motion above and the contact force;
    /// `arm_length` l and `link_length` L \[m\].
    pub fn sensors(
        &self,
        t: f64,
        y: &[f64; DIM],
        arm_length: f64,
        link_length: f64,
    ) -> SensorSample {
        let c = self.sample(y);
        let d = self.derivative(y, c.as_ref());
        let (sin, cos) = (y[4], y[5]);
        let (s, co) = y[2].sin_cos();
        SensorSample {
            t,
            operator_angle_rad: y[0],
            robot_angle_rad: y[2],
            link_tip_deflection_m: link_length * s,
            operator_accel_mps2: arm_length * (cos * d[1] - sin * y[1] * y[1]),
            load_accel_mps2: link_length * (co * d[3] - s * y[3] * y[3]),
            force_n: c.map_or(0.0, |c| c.force),
            indentation_m: c.map_or(0.0, |c| c.indentation),
        }
    }

    fn derivative(&self, y: &[f64; DIM], c: Option<&ContactSample>) -> [f64; DIM] {
        let mut d = self.free.rhs(0.0, y);
        if let Some(c) = c {
            let (operator, robot) = self.torques(c);
            d[1] += operator / self.free.operator_inertia;
            if let Some((inertia, _)) = self.free.robot {
                d[3] += robot / inertia;
            }
        }
        d
    }
}

impl OdeSystem<DIM> for HingesInContact<'_> {
    fn rhs(&self, _t: f64, y: &[f64; DIM]) -> [f64; DIM] {
        self.derivative(y, self.sample(y).as_ref())
    }
}

/// Bracket of the search left when it stops, relative to the bracket it starts
/// with (one or two sub-intervals of a step, ω Δt ≲ 0.3 for a step of a third of the contact):
/// at a smooth maximum f(t* + Δt) = f(t*) (1 − O((ω Δt)²)), so the value is found to ~1e-13,
/// its time to ~1e-10 s on the bundled scenes.
const MAX_SEARCH_RESOLUTION: f64 = 1e-6;

/// The largest value of `f` on `[a, b]` by Brent's method (golden section with parabolic
/// steps through the last three points: a handful of evaluations for a smooth maximum), `f`
/// unimodal there (at a monotone end, that end). Returns (t, f(t)).
pub fn search_max(a: f64, b: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let g = |t: f64| -f(t);
    let golden = 0.5 * (3.0 - 5f64.sqrt());
    let (mut lo, mut hi) = (a, b);
    let tol = (MAX_SEARCH_RESOLUTION * (b - a)).max(4.0 * f64::EPSILON * b.abs());
    let mut x = lo + golden * (hi - lo);
    let (mut w, mut v) = (x, x);
    let mut fx = g(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        let tol1 = 0.5 * tol;
        let tol2 = 2.0 * tol1;
        if (x - mid).abs() <= tol2 - 0.5 * (hi - lo) {
            break;
        }
        let mut golden_step = true;
        if e.abs() > tol1 {
            // parabola through (x, fx), (w, fw), (v, fv)
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let e_prev = e;
            if p.abs() < (0.5 * q * e_prev).abs() && p > q * (lo - x) && p < q * (hi - x) {
                e = d;
                d = p / q;
                let u = x + d;
                if u - lo < tol2 || hi - u < tol2 {
                    d = if mid >= x { tol1 } else { -tol1 };
                }
                golden_step = false;
            }
        }
        if golden_step {
            e = if x >= mid { lo - x } else { hi - x };
            d = golden * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else if d > 0.0 {
            x + tol1
        } else {
            x - tol1
        };
        let fu = g(u);
        if fu <= fx {
            if u >= x {
                lo = x;
            } else {
                hi = x;
            }
            (v, fv) = (w, fw);
            (w, fw) = (x, fx);
            (x, fx) = (u, fu);
        } else {
            if u < x {
                lo = u;
            } else {
                hi = u;
            }
            if fu <= fw || w == x {
                (v, fv) = (w, fw);
                (w, fw) = (u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    let mut best = (x, -fx);
    for t in [a, b] {
        let ft = f(t);
        if ft > best.1 {
            best = (t, ft);
        }
    }
    best
}

/// The sample times of a step of `dense` (its start, the ends of its [`EVENT_SUBINTERVALS`]
/// sub-intervals up to `t_end`, which may end it early at an event).
pub fn sample_times(dense: &DenseOutput<DIM>, t_end: f64) -> [f64; EVENT_SUBINTERVALS + 1] {
    let a = dense.t_start();
    std::array::from_fn(|k| {
        if k == EVENT_SUBINTERVALS {
            t_end
        } else {
            a + (t_end - a) * k as f64 / EVENT_SUBINTERVALS as f64
        }
    })
}

/// Composite Simpson's rule over the equally spaced `values` on `[t_a, t_b]` (an even number of
/// sub-intervals).
pub fn simpson(t_a: f64, t_b: f64, values: &[f64]) -> f64 {
    let n = values.len() - 1;
    let h = (t_b - t_a) / n as f64;
    let inner: f64 = values[1..n]
        .iter()
        .enumerate()
        .map(|(i, v)| if i % 2 == 0 { 4.0 * v } else { 2.0 * v })
        .sum();
    h / 3.0 * (values[0] + inner + values[n])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_search_finds_a_smooth_maximum_and_a_monotone_end() {
        // f = cos(3 (t − 0.3)) on [0, 1]: maximum 1 at t = 0.3 (analytic)
        let (t, f) = search_max(0.0, 1.0, |t| (3.0 * (t - 0.3)).cos());
        assert!((t - 0.3).abs() < 2e-6, "{t}");
        assert!((f - 1.0).abs() < 1e-12, "{f}");
        // a Hertz-like pulse sin(t)^1.5 on [1.2, 2.0]: maximum at π/2
        let (t, _) = search_max(1.2, 2.0, |t: f64| t.sin().powf(1.5));
        assert!((t - std::f64::consts::FRAC_PI_2).abs() < 2e-6, "{t}");
        // rising throughout: the right end, exactly
        assert_eq!(search_max(0.0, 0.5, |t| t * t), (0.5, 0.25));
    }

    #[test]
    fn simpsons_rule_is_exact_for_cubics() {
        let t: Vec<f64> = (0..=8).map(|k| 0.25 * k as f64).collect();
        let v: Vec<f64> = t.iter().map(|t| t * t * t - 2.0 * t + 1.0).collect();
        // ∫₀² (t³ − 2t + 1) dt = 4 − 4 + 2
        assert!((simpson(0.0, 2.0, &v) - 2.0).abs() < 1e-14);
    }
}
