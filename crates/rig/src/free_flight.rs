//! The free flight: the rig's smooth motion out of contact (the pendulum swing; the CJ link on
//! its spring, at rest or moving freely) integrated by flexrig-lumped's adaptive 8th-order
//! Runge–Kutta method (DOP853) with dense output, and the contact onset located as an event —
//! the dome–block gap reaching zero — on that dense output. The number of steps before a contact
//! no longer grows with the length of the swing; at the onset the exact state is handed to
//! Rapier, which resolves the contact (see [`crate::run`]).
//!
//! Equations (reduced coordinates, y = (φ, φ̇, ψ, ψ̇)): the operator pendulum
//! J_op φ̈ = −M g l_c sin φ (compound pendulum, `docs/theory.md`), the CJ link
//! J_rob ψ̈ = −k_θr ψ (the torsion spring, Eq. 3; the link turns about the vertical axis, so
//! gravity does not load it). For the CL the beam is at rest before its first contact (nothing
//! loads it in its plane), ψ ≡ 0 and only the pendulum moves; after a CL contact the vibrating
//! beam is stepped with the fixed policy.

use flexrig_lumped::ode::dop853::{
    DenseOutput, Dop853, Dop853Options, OdeSystem, StepFailure, find_root,
};
use serde::{Deserialize, Serialize};

use crate::sensors::SensorSample;

/// How the rig is integrated out of contact (`solver.swing`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SwingPolicy {
    /// DOP853 at relative tolerance [`FREE_FLIGHT_RTOL`] on the hinges' smooth motion, the onset
    /// located as an event and handed to Rapier exactly (the default): a swing in a few tens of
    /// steps whatever its length.
    #[default]
    Adaptive,
    /// Rapier's fixed steps of `solver.swing_step_s` (velocity Verlet), shortened towards a
    /// predicted onset: the earlier policy, kept for comparison.
    Fixed,
}

/// How the CJ's contact is integrated (`solver.contact`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactPolicy {
    /// The adaptive contact wherever it applies — a CJ without a drive on its robot joint and
    /// with the adaptive swing, for every stop — and Rapier's fixed steps otherwise (a CL, a
    /// drive, the fixed swing): the cheaper and, on the CJ, the more accurate of the two (the
    /// default; [`ContactPolicy::resolved`]).
    #[default]
    Auto,
    /// Rapier's steps, `solver.contact_steps` per Hertz contact time, made velocity Verlet by
    /// the synchronised coupling.
    Fixed,
    /// The two hinges in reduced coordinates with the contact force in the right-hand side,
    /// integrated by DOP853 at `solver.contact_rtol` from the located onset to the located
    /// separation; the peak is the maximum of the force on the dense output
    /// ([`crate::contact_flight`]). Rapier does not step the contact.
    Adaptive,
}

impl ContactPolicy {
    /// True for the default.
    pub fn is_auto(&self) -> bool {
        *self == ContactPolicy::Auto
    }

    /// True for the adaptive contact.
    pub fn is_adaptive(&self) -> bool {
        *self == ContactPolicy::Adaptive
    }

    /// The integration that runs ([`ContactPolicy::Fixed`] or [`ContactPolicy::Adaptive`]) for
    /// a scene whose robot is a CJ (`cj`) or not, with the swing policy `swing`, with or without
    /// a drive on the robot joint (`driven`): "auto" takes the adaptive contact for an undriven
    /// CJ with the adaptive swing, the fixed steps otherwise; "fixed" and "adaptive" are taken
    /// as written (the scene's validation refuses "adaptive" where it does not apply).
    pub fn resolved(self, cj: bool, swing: SwingPolicy, driven: bool) -> Self {
        match self {
            ContactPolicy::Auto => {
                if cj && swing == SwingPolicy::Adaptive && !driven {
                    ContactPolicy::Adaptive
                } else {
                    ContactPolicy::Fixed
                }
            }
            written => written,
        }
    }

    /// The policy's name as written in a scene.
    pub fn name(&self) -> &'static str {
        match self {
            ContactPolicy::Auto => "auto",
            ContactPolicy::Fixed => "fixed",
            ContactPolicy::Adaptive => "adaptive",
        }
    }
}

/// Default relative tolerance of the adaptive contact (`solver.contact_rtol`): peak force within
/// about 1e-7 of the independent two-hinge reference on the bundled CJ scenes (tests/reference.rs).
pub const CONTACT_RTOL: f64 = 1e-8;

/// Relative tolerance of the free flight: onset time and impact speed within 1e-11 of the
/// elliptic-integral and energy references (tests/free_flight.rs).
pub const FREE_FLIGHT_RTOL: f64 = 1e-12;

/// Sub-intervals of each accepted step on which the gap is sampled for a sign change, so that a
/// grazing contact inside one step is not stepped over.
pub const EVENT_SUBINTERVALS: usize = 8;

/// Size of the free flight's state: y = (φ, φ̇, ψ, ψ̇, sin φ, cos φ).
pub const DIM: usize = 6;

/// The hinges out of contact as a first-order system, y = (φ \[rad\], φ̇ [rad/s], ψ \[rad\],
/// ψ̇ [rad/s], sin φ, cos φ): the sine and cosine of the pendulum angle ride along
/// (d sin φ/dt = φ̇ cos φ, d cos φ/dt = −φ̇ sin φ), so that neither the right-hand side nor a
/// sensor sample from the dense output needs a trigonometric function.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FreeHinges {
    /// Operator moment of inertia about its pivot J_op [kg·m²].
    pub operator_inertia: f64,
    /// Gravity moment M g l_c of the operator [N·m].
    pub gravity_moment: f64,
    /// CJ link: moment of inertia about the robot axis J_rob [kg·m²] and the torsion spring
    /// k_θr [N·m/rad]; `None` for the CL (ψ ≡ 0).
    pub robot: Option<(f64, f64)>,
}

impl OdeSystem<DIM> for FreeHinges {
    fn rhs(&self, _t: f64, y: &[f64; DIM]) -> [f64; DIM] {
        let psi_accel = self
            .robot
            .map_or(0.0, |(inertia, spring)| -spring * y[2] / inertia);
        [
            y[1],
            -self.gravity_moment * y[4] / self.operator_inertia,
            y[3],
            psi_accel,
            y[1] * y[5],
            -y[1] * y[4],
        ]
    }
}

/// The free flight in progress: the integrator and the system it integrates.
#[derive(Debug, Clone)]
pub struct FreeFlight {
    system: FreeHinges,
    solver: Dop853<DIM>,
}

/// Where an accepted free-flight step ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightStep {
    /// Start of the step \[s\].
    pub t_start: f64,
    /// End of the step \[s\]: the onset time if the step reached the contact.
    pub t_end: f64,
    /// The state at `t_end`.
    pub y: [f64; DIM],
    /// True when the step ends at its event: the contact onset (gap = 0) out of contact, the
    /// separation in contact.
    pub onset: bool,
}

impl FreeFlight {
    /// Starts at time `t0` \[s\] in state `y0`; `rate_scale` [rad/s] sets the absolute tolerance of
    /// the rates (e.g. the swing's speed at the bottom), `max_step` \[s\] the largest step.
    /// The state is y0 = (φ, φ̇, ψ, ψ̇) (its sine and cosine are added here).
    pub fn new(system: FreeHinges, t0: f64, y0: [f64; 4], rate_scale: f64, max_step: f64) -> Self {
        let (sin, cos) = y0[0].sin_cos();
        let y0 = [y0[0], y0[1], y0[2], y0[3], sin, cos];
        let rtol = FREE_FLIGHT_RTOL;
        // Angles to 1e-12 rad, rates to 1e-12 of the swing's speed.
        let rate_scale = rate_scale.max(1e-3);
        let options = Dop853Options {
            rtol,
            atol: [rtol, rtol * rate_scale, rtol, rtol * rate_scale, rtol, rtol],
            first_step: None,
            max_step,
            max_steps: usize::MAX,
        };
        FreeFlight {
            system,
            solver: Dop853::new(&system, t0, y0, options),
        }
    }

    /// The hinges in contact from time `t0` \[s\] in the full state `y0`, with `rhs` (the hinges
    /// and the contact force) at relative tolerance `rtol` and absolute tolerances `atol`, steps
    /// of at most `max_step` \[s\]; `system` is the motion without the contact.
    pub fn in_contact(
        system: FreeHinges,
        rhs: &impl OdeSystem<DIM>,
        t0: f64,
        y0: [f64; DIM],
        (rtol, atol): (f64, [f64; DIM]),
        max_step: f64,
    ) -> Self {
        let options = Dop853Options {
            rtol,
            atol,
            first_step: None,
            max_step,
            max_steps: usize::MAX,
        };
        FreeFlight {
            system,
            solver: Dop853::new(rhs, t0, y0, options),
        }
    }

    /// The system integrated (without the contact).
    pub fn system(&self) -> &FreeHinges {
        &self.system
    }

    /// One accepted step, not past `t_limit` (landing on it when within reach), ending at the
    /// first zero of `gap` (a signed distance \[m\], positive apart) if the step reaches it.
    pub fn step(
        &mut self,
        t_limit: Option<f64>,
        gap: impl Fn(&[f64; DIM]) -> f64,
    ) -> Result<FlightStep, StepFailure> {
        let system = self.system;
        self.step_with(&system, t_limit, gap)
    }

    /// [`FreeFlight::step`] with the right-hand side `rhs` (e.g. with the contact force),
    /// ending where `event` goes from positive to zero or negative.
    pub fn step_with(
        &mut self,
        rhs: &impl OdeSystem<DIM>,
        t_limit: Option<f64>,
        event: impl Fn(&[f64; DIM]) -> f64,
    ) -> Result<FlightStep, StepFailure> {
        match t_limit {
            Some(t_end) => self.solver.step_until(rhs, t_end)?,
            None => self.solver.step(rhs)?,
        }
        let t_start = self.solver.t_old();
        let dense = self.solver.dense_output(rhs);
        if let Some(t_onset) = first_zero(&dense, &event) {
            // The state at the event by a genuine step of the method (more accurate than the
            // interpolant).
            let y = self.solver.restep_to(rhs, t_onset);
            return Ok(FlightStep {
                t_start,
                t_end: t_onset,
                y,
                onset: true,
            });
        }
        Ok(FlightStep {
            t_start,
            t_end: self.solver.t(),
            y: *self.solver.y(),
            onset: false,
        })
    }

    /// The interpolant over the last accepted step (valid on [`FlightStep::t_start`],
    /// [`FlightStep::t_end`]).
    pub fn dense(&mut self) -> DenseOutput<DIM> {
        self.solver.dense_output(&self.system)
    }

    /// [`FreeFlight::dense`] of a step taken with the right-hand side `rhs`.
    pub fn dense_with(&mut self, rhs: &impl OdeSystem<DIM>) -> DenseOutput<DIM> {
        self.solver.dense_output(rhs)
    }

    /// Right-hand-side evaluations so far.
    pub fn evaluations(&self) -> usize {
        self.solver.stats().rhs_evals
    }
}

/// The first time in the step of `dense` at which `gap` goes from positive to zero or negative:
/// the gap is sampled on [`EVENT_SUBINTERVALS`] sub-intervals and the first bracket refined by
/// regula falsi (Illinois) to the resolution of t.
fn first_zero(dense: &DenseOutput<DIM>, gap: &impl Fn(&[f64; DIM]) -> f64) -> Option<f64> {
    let (a, b) = (dense.t_start(), dense.t_end());
    let g = |t: f64| gap(&dense.eval(t));
    let mut t0 = a;
    let mut g0 = g(a);
    for k in 1..=EVENT_SUBINTERVALS {
        let t1 = if k == EVENT_SUBINTERVALS {
            b
        } else {
            a + (b - a) * k as f64 / EVENT_SUBINTERVALS as f64
        };
        let g1 = g(t1);
        if g0 > 0.0 && g1 <= 0.0 {
            let t_tol = 4.0 * f64::EPSILON * t1.abs().max(b - a);
            return Some(find_root(g, t0, g0, t1, g1, t_tol));
        }
        (t0, g0) = (t1, g1);
    }
    None
}

/// The sensors of the free flight, read off its state exactly (no interpolation, accelerations
/// from the equations of motion): the constants of [`FreeHinges`] and the sensor geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightSensors {
    /// Operator pivot to block centre l \[m\] (the accelerometer's radius).
    pub arm_length: f64,
    /// CJ link length L \[m\]; `None` for the CL.
    pub link_length: Option<f64>,
    /// CL: tip deflection \[m\] and acceleration [m/s²] of the beam at rest.
    pub beam_tip: (f64, f64),
}

impl FlightSensors {
    /// Every sensor at time `t` \[s\] in state `y` of `system`: encoders φ and ψ, the link tip
    /// L sin ψ (CJ) or the beam's, the accelerations along the strike (world y) of the block,
    /// l (cos φ φ̈ − sin φ φ̇²), and of the load, L (cos ψ ψ̈ − sin ψ ψ̇²); no contact force.
    pub fn sample(&self, system: &FreeHinges, t: f64, y: &[f64; DIM]) -> SensorSample {
        let (sin, cos) = (y[4], y[5]);
        let phi_accel = -system.gravity_moment * sin / system.operator_inertia;
        let (robot_angle, tip, load_accel) = match (self.link_length, system.robot) {
            (Some(_), _) if y[2] == 0.0 && y[3] == 0.0 => (0.0, 0.0, 0.0),
            (Some(len), Some((inertia, spring))) => {
                let (s, c) = y[2].sin_cos();
                let psi_accel = -spring * y[2] / inertia;
                (y[2], len * s, len * (c * psi_accel - s * y[3] * y[3]))
            }
            _ => (0.0, self.beam_tip.0, self.beam_tip.1),
        };
        SensorSample {
            t,
            operator_angle_rad: y[0],
            robot_angle_rad: robot_angle,
            link_tip_deflection_m: tip,
            operator_accel_mps2: self.arm_length * (cos * phi_accel - sin * y[1] * y[1]),
            load_accel_mps2: load_accel,
            force_n: 0.0,
            indentation_m: 0.0,
        }
    }
}
