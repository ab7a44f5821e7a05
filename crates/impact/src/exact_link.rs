//! The geometrically exact driven CL link: the compliant link as flexrig-beam's corotational
//! beam clamped to the driven hub, the dome rigid with the tip section, the person's face a
//! plane — the default model of the driven strike ([`crate::DrivenStrike::run_cl`]).
//!
//! **The link.** Hermite/corotational elements (flexrig-beam, [`Kinematics::Corotational`]) of
//! EI = k_δ L³/3 (Eq. 3), ρA = m_r/L and EA = [`AXIAL_SLENDERNESS`] EI/L² (the test bed's
//! section, EA L²/EI = 12 L²/t² ≈ 2.05e5), consistent mass, the payload m_e a point mass at the
//! tip node. Large rotation is exact, so the centrifugal tension of a turning link stiffens its
//! bending (the test bed's link turning at 2.96 rad/s: first frequency 5.21 rad/s instead of the
//! linear 5.05). The corotational element is chosen over the ANCF element although ANCF
//! converges faster per element in large static deflection (docs/performance-beam.md): only the
//! corotational beam has the rotating clamp ([`GeneralizedAlpha::step_with_root`]) and the hub
//! root. Its mesh error falls as 1/N² when the link bends far (the test bed's link bent by a
//! third of its length: 2.2e-4 in peak at 16 elements, 4.4e-5 at 32) and as 1/N⁴ in small
//! deflection (a stiff link: 4 elements within 2e-7 of 32), so the mesh is checked per strike
//! ([`ExactSettings::mesh_tolerance`]): a stiff link stops at 4 elements, a bent one at 64–128.
//!
//! **The hub.** A prescribed trajectory turns the clamped root (rotating clamp); the motor's
//! joint torque is the root's reaction plus J_m N² θ̈ + c_m N² θ̇. A controller or an
//! open-loop torque drives a free hub of the rotor's inertia J_m N² (`RootSupport::Hub`): over a
//! step the law τ = K_p (φ_c − θ) + K_d (ω_c − θ̇) + K_i z (trapezoidal z) is the hub's spring
//! K_p + K_i h/2, its damper K_d + c_m N² and a moment; at the torque limit the constant
//! moment ±N τ_m,max (the step is taken again on the other branch when its end says so).
//!
//! **The dome and the person.** The dome is a sphere of radius R rigid with the tip section,
//! its centre at d_c = R − s behind the link's axis (s the standoff: the apex sits s ahead of
//! the axis, towards the person): c = p_tip − d_c n(θ_tip), n = (−sin θ, cos θ). The face is a
//! plane with normal e = (−sin φ_c, cos φ_c) (the undeformed tip's direction of motion at the
//! placement angle φ_c), placed where the undeformed link at φ_c touches it with its apex; the
//! head moves along e by x_h (free: m_h ẍ_h = f; neck: − k_n x_h − c_n ẋ_h; a wall: x_h ≡ 0).
//! Indentation δ = e·c + d_c − x_h, force f(δ, δ̇) of the person's law, on the dome −f e
//! through the sphere's centre: on the tip node's (u, v, θ) the load −f g with
//! g = (e_x, e_y, d_c e·(cos θ, sin θ)) — the moment f (R − s) sin α that turns the tip section
//! when it meets the face at an angle α.
//!
//! **Integration.** Generalized-α at ρ∞ = 1 (the trapezoidal rule; second order, no numerical
//! dissipation) for the beam with the contact implicit in its Newton iteration
//! ([`flexrig_beam::NodeLoad`]); the head by the same trapezoidal rule, solved with the force
//! inside the node load (its position is affine in f over the step), so beam, contact and head
//! advance as one implicit system. Before the contact the step is [`ExactSettings::approach_steps`]
//! per the drive's shortest time scale or a tenth of the link's first period, whichever is
//! longer (landing on the drive's corners); the onset is located by
//! the secant method on the step length (the gap of the contact-free step from the last state);
//! the contact is taken in [`ExactSettings::contact_steps`] steps per the expected contact
//! duration, the separation located the same way; the peak is the vertex of the parabola
//! through the three samples around the largest force. Motor work, friction, neck and contact
//! damping and the impact work are integrated by the trapezoidal rule over the contact.

use flexrig_beam::{
    BeamModel, BeamSpec, GeneralizedAlpha, Kinematics, NewtonMethod, NodalLoads, NodeForce,
    NodeLoad, PointMass, RootSupport, Section, State, Workspace,
};
use flexrig_contact::ContactLaw;
use serde::Serialize;

use crate::ImpactError;
use crate::drive::{DriveCommand, HeadSupport, Profile, TorqueProfile};
use crate::driven_cj::{CjSettings, run_exact_cj};
use crate::setup::{ContactEvent, hertz_time_integral};
use crate::strike::{DriveNote, DrivenOutcome, DrivenStrike, EnergyBalance, TraceSample, Tracer};

/// EA L²/EI of the exact link's beam: the test bed's polypropylene section (t = 2.58 mm,
/// L = 0.338 m: 12 L²/t² = 2.05e5). The reference elastica is inextensible; the axial strain of
/// the strike (≤ f/EA ≈ 4e-4 at 100 N) changes its peak by less than 1e-6.
pub const AXIAL_SLENDERNESS: f64 = 2.05e5;

pub use crate::drive::Dome;

/// How the exact link is solved.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ExactSettings {
    /// Corotational elements along the link, 2..=512 (with a
    /// [`ExactSettings::mesh_tolerance`], the first mesh of the check).
    pub elements: usize,
    /// The dome.
    pub dome: Dome,
    /// Steps before the contact per the drive's shortest time scale (ramp, loop period,
    /// arrival) or per a tenth of the link's first bending period if that is longer,
    /// 20..=1e6.
    pub approach_steps: usize,
    /// Steps over the expected contact duration (the head against the payload alone), 20..=1e6.
    pub contact_steps: usize,
    /// EA L²/EI of the beam (≥ 1e3; [`AXIAL_SLENDERNESS`] by default).
    pub axial_slenderness: f64,
    /// How the beam's Newton iterates (flexrig-beam's [`NewtonMethod`]: full Newton by default;
    /// modified Newton keeps the iteration matrix while it contracts).
    pub newton: NewtonMethod,
    /// `Some(tol)`: the mesh is checked: the strike is solved on `elements`, 2×, 4×, …
    /// elements until two successive meshes N and 2N differ by at most 3 tol (relative: peak,
    /// time of peak after the onset against the duration, duration, onset), the 2N solution's
    /// mesh error then being at most tol (the corotational beam converges as 1/N² or faster:
    /// 1/N² when the link bends far, 1/N⁴ in small deflection); at most 512 elements. `None`:
    /// `elements` as they are. In [1e-9, 1e-2].
    pub mesh_tolerance: Option<f64>,
    /// Most steps in all (of each mesh).
    pub max_steps: usize,
    /// `Some(dt)`: sample the motion at the steps, at most every dt \[s\].
    pub trace_every: Option<f64>,
    /// Follow every contact: after a separation the motion goes on, the drive keeping its
    /// command, until the next onset, until a free head moving away is beyond the farthest the
    /// dome can reach (the bodies parted for good), or until the strike's window (`horizon_s`)
    /// closes. `false`: the run ends at the first separation.
    pub every_contact: bool,
}

impl ExactSettings {
    /// The mesh checked from 4 elements up ([`ExactSettings::mesh_tolerance`] 5e-6), 500 steps
    /// per period before the contact and 400 over it, modified Newton, the test bed's dome:
    /// converged to ≤ 1e-5 in peak, time of peak, duration and onset against 2× the elements and
    /// 4× the steps on the bundled driven scenes and the test bed's cases
    /// (crates/impact/tests/exact_link.rs). A stiff link (the bundled scenes) stops at 8
    /// elements: about 15 ms per strike from rest on one core; a link bent by a third of its
    /// length needs 128 (docs/performance.md).
    pub const DEFAULT: ExactSettings = ExactSettings {
        elements: 2,
        dome: Dome::TEST_BED,
        approach_steps: 1000,
        contact_steps: 400,
        axial_slenderness: AXIAL_SLENDERNESS,
        newton: NewtonMethod::Modified,
        mesh_tolerance: Some(5e-6),
        max_steps: 10_000_000,
        trace_every: None,
        every_contact: false,
    };

    /// 8 elements, unchecked, 250 steps per period before the contact and 200 over it: within
    /// 2e-5 of converged on the bundled (stiff-link) scenes, but up to 1e-3 on a link bent by a
    /// third of its length (the mesh; 3e-5 on a link bent by 1 %), for quick looks.
    pub const FAST: ExactSettings = ExactSettings {
        elements: 8,
        approach_steps: 250,
        contact_steps: 200,
        mesh_tolerance: None,
        ..ExactSettings::DEFAULT
    };

    fn validate(&self) -> Result<(), ImpactError> {
        self.dome.validate()?;
        if !(2..=512).contains(&self.elements) {
            return Err(ImpactError::invalid(
                "elements",
                self.elements,
                "must lie in [2, 512]",
            ));
        }
        for (field, v) in [
            ("approach_steps", self.approach_steps),
            ("contact_steps", self.contact_steps),
        ] {
            if !(20..=1_000_000).contains(&v) {
                return Err(ImpactError::invalid(field, v, "must lie in [20, 1e6]"));
            }
        }
        if !(self.axial_slenderness.is_finite() && (1e3..=1e12).contains(&self.axial_slenderness)) {
            return Err(ImpactError::invalid(
                "axial_slenderness",
                self.axial_slenderness,
                "must lie in [1e3, 1e12]",
            ));
        }
        if let Some(tol) = self.mesh_tolerance
            && !(tol.is_finite() && (1e-9..=1e-2).contains(&tol))
        {
            return Err(ImpactError::invalid(
                "mesh_tolerance",
                tol,
                "must lie in [1e-9, 1e-2]",
            ));
        }
        if !(100..=100_000_000).contains(&self.max_steps) {
            return Err(ImpactError::invalid(
                "max_steps",
                self.max_steps,
                "must lie in [100, 1e8]",
            ));
        }
        Ok(())
    }
}

/// The head over one step from its state at t₀, by the trapezoidal rule: its position and rate
/// at t₀ + h are affine in the contact force there, x₁ = x_b + B f, ẋ₁ = v_b + C f.
#[derive(Debug, Clone, Copy)]
struct HeadStep {
    x_b: f64,
    b: f64,
    v_b: f64,
    c: f64,
}

/// The person's head along the face normal e (x_h > 0 away from the link).
#[derive(Debug, Clone, Copy)]
struct Head {
    x: f64,
    v: f64,
    a: f64,
    m: f64,
    k_n: f64,
    c_n: f64,
    wall: bool,
}

impl Head {
    fn over(&self, h: f64) -> HeadStep {
        if self.wall {
            return HeadStep {
                x_b: 0.0,
                b: 0.0,
                v_b: 0.0,
                c: 0.0,
            };
        }
        let xs = self.x + h * self.v + 0.25 * h * h * self.a;
        let vs = self.v + 0.5 * h * self.a;
        let d = self.m + 0.25 * h * h * self.k_n + 0.5 * h * self.c_n;
        // a₁ = (f − k_n xs − c_n vs)/d
        let a_b = -(self.k_n * xs + self.c_n * vs) / d;
        HeadStep {
            x_b: xs + 0.25 * h * h * a_b,
            b: 0.25 * h * h / d,
            v_b: vs + 0.5 * h * a_b,
            c: 0.5 * h / d,
        }
    }

    fn energy(&self) -> f64 {
        if self.wall {
            0.0
        } else {
            0.5 * self.m * self.v * self.v + 0.5 * self.k_n * self.x * self.x
        }
    }
}

/// The dome's geometry against the face for a tip node state.
#[derive(Debug, Clone, Copy)]
struct Geometry {
    length: f64,
    d_c: f64,
    e: [f64; 2],
}

impl Geometry {
    /// (e·c + d_c, g = ∂/∂(u, v, θ), ġ·… : the rate e·ċ) for the tip's q, q̇.
    fn gap(&self, q: [f64; 3], v: [f64; 3]) -> (f64, [f64; 3], f64) {
        let (s, c) = q[2].sin_cos();
        let [ex, ey] = self.e;
        let px = self.length + q[0];
        let py = q[1];
        // c = p − d_c (−sin θ, cos θ)
        let cx = px + self.d_c * s;
        let cy = py - self.d_c * c;
        let g = [ex, ey, self.d_c * (ex * c + ey * s)];
        let depth = ex * cx + ey * cy + self.d_c;
        let rate = g[0] * v[0] + g[1] * v[1] + g[2] * v[2];
        (depth, g, rate)
    }

    /// ∂g_θ/∂θ = d_c e·(−sin θ, cos θ).
    fn dg_dtheta(&self, theta: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        self.d_c * (-self.e[0] * s + self.e[1] * c)
    }
}

/// The contact's solution at a tip state: force, indentation and rate, the head's end state.
#[derive(Debug, Clone, Copy, Default)]
struct ContactState {
    f: f64,
    delta: f64,
    rate: f64,
    x_h: f64,
    v_h: f64,
    /// The law's damping part f(δ, δ̇) − f(δ, 0) \[N\] (0 for an elastic law).
    f_damping: f64,
}

/// The contact with the head as a node load on the tip (implicit in the beam's Newton).
struct DomeLoad<'a> {
    geometry: Geometry,
    law: &'a dyn ContactLaw,
    head: HeadStep,
    tip: usize,
    active: bool,
    last: ContactState,
}

impl DomeLoad<'_> {
    /// Solves f = law(δ, δ̇) with δ = G − x_b − B f, δ̇ = Ġ − v_b − C f (scalar Newton, the
    /// force monotone in the head's response) and returns the state with (∂f/∂δ, ∂f/∂δ̇, D)
    /// where D = 1 + F_δ B + F_v C.
    fn solve(&self, q: [f64; 3], v: [f64; 3]) -> (ContactState, [f64; 3], f64, f64, f64) {
        let (depth, g, rate_g) = self.geometry.gap(q, v);
        let hs = self.head;
        let at = |f: f64| (depth - hs.x_b - hs.b * f, rate_g - hs.v_b - hs.c * f);
        let (d0, r0) = at(0.0);
        if !self.active || d0 <= 0.0 {
            let st = ContactState {
                f: 0.0,
                delta: d0,
                rate: r0,
                x_h: hs.x_b,
                v_h: hs.v_b,
                f_damping: 0.0,
            };
            return (st, g, 0.0, 0.0, 1.0);
        }
        // the force at the head's free response, then Newton on r(f) = f − law(δ(f), δ̇(f))
        let mut f = self.law.force(d0, r0);
        let (mut lo, mut hi) = (0.0_f64, f.max(0.0));
        for _ in 0..100 {
            let (d, r) = at(f);
            let (fl, kd, kv) = if d > 0.0 {
                (
                    self.law.force(d, r),
                    self.law.stiffness(d, r),
                    self.law.damping(d, r),
                )
            } else {
                (0.0, 0.0, 0.0)
            };
            let res = f - fl;
            if res > 0.0 {
                hi = hi.min(f);
            } else {
                lo = lo.max(f);
            }
            let jac = 1.0 + kd * hs.b + kv * hs.c;
            let mut next = f - res / jac;
            if !(next > lo && next < hi) && hi > lo {
                next = 0.5 * (lo + hi);
            }
            let done = (next - f).abs() <= 1e-15 * f.abs().max(1e-300);
            f = next;
            if done {
                break;
            }
        }
        let (d, r) = at(f);
        let (kd, kv) = if d > 0.0 {
            (self.law.stiffness(d, r), self.law.damping(d, r))
        } else {
            (0.0, 0.0)
        };
        let st = ContactState {
            f,
            delta: d,
            rate: r,
            x_h: hs.x_b + hs.b * f,
            v_h: hs.v_b + hs.c * f,
            // the law's damping part at the same (δ, δ̇): exactly 0 for an elastic law
            f_damping: if d > 0.0 {
                self.law.force(d, r) - self.law.force(d, 0.0)
            } else {
                0.0
            },
        };
        (st, g, kd, kv, 1.0 + kd * hs.b + kv * hs.c)
    }
}

impl NodeLoad for DomeLoad<'_> {
    fn node(&self) -> usize {
        self.tip
    }

    /// Q = −f g on (u, v, θ); ∂Q/∂q = −g (∂f/∂q)ᵀ − f ∂g/∂q with ∂f/∂q = (F_δ g + F_v θ̇ ∂g/∂θ
    /// on θ)/D and ∂f/∂q̇ = F_v g/D (the head's response inside D).
    fn evaluate(&mut self, _t: f64, q: [f64; 3], v: [f64; 3]) -> NodeForce {
        let (st, g, kd, kv, d) = self.solve(q, v);
        self.last = st;
        if st.f == 0.0 {
            return NodeForce::ZERO;
        }
        let dg = self.geometry.dg_dtheta(q[2]);
        let mut df_dq = [kd * g[0] / d, kd * g[1] / d, kd * g[2] / d];
        df_dq[2] += kv * v[2] * dg / d;
        let df_dv = [kv * g[0] / d, kv * g[1] / d, kv * g[2] / d];
        let mut out = NodeForce::ZERO;
        for i in 0..3 {
            out.force[i] = -st.f * g[i];
            for j in 0..3 {
                out.d_dq[i][j] = -g[i] * df_dq[j];
                out.d_dv[i][j] = -g[i] * df_dv[j];
            }
        }
        out.d_dq[2][2] -= st.f * dg;
        out
    }
}

/// The drive on the hub.
#[derive(Debug, Clone, Copy)]
enum Hub<'a> {
    Prescribed(&'a Profile),
    Controller {
        profile: &'a Profile,
        kp: f64,
        kd: f64,
        ki: f64,
        limit: f64,
    },
    OpenLoop {
        torque: &'a TorqueProfile,
        gear: f64,
    },
}

/// A free hub's law over one step: τ = moment − k θ₁ − c θ̇₁ (friction not included).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Law {
    k: f64,
    c: f64,
    moment: f64,
    saturated: bool,
}

/// Everything a step changes (to take it again).
#[derive(Debug, Clone)]
struct Snapshot {
    state: State,
    head: Head,
    z: f64,
}

struct Solver<'a> {
    model: BeamModel,
    spec: BeamSpec,
    ga: GeneralizedAlpha,
    ws: Workspace,
    loads: NodalLoads,
    state: State,
    head: Head,
    hub: Hub<'a>,
    /// ∫ e_φ dt of the controller.
    z: f64,
    j_rotor: f64,
    c_rotor: f64,
    geometry: Geometry,
    law: Box<dyn ContactLaw>,
    tip: usize,
    saturated_at: Option<f64>,
    /// The last step's law (free hub).
    law_used: Option<Law>,
}

impl<'a> Solver<'a> {
    fn snapshot(&self) -> Snapshot {
        Snapshot {
            state: self.state.clone(),
            head: self.head,
            z: self.z,
        }
    }

    fn restore(&mut self, s: &Snapshot) {
        self.state.clone_from(&s.state);
        self.head = s.head;
        self.z = s.z;
    }

    fn hub_motion(&self) -> (f64, f64, f64) {
        (self.state.q[2], self.state.v[2], self.state.a[2])
    }

    fn tip_qv(&self) -> ([f64; 3], [f64; 3]) {
        let i = 3 * self.tip;
        (
            [self.state.q[i], self.state.q[i + 1], self.state.q[i + 2]],
            [self.state.v[i], self.state.v[i + 1], self.state.v[i + 2]],
        )
    }

    /// The free hub's law for a step to t₁ of length h (unsaturated unless `saturated`).
    fn law_for(&self, t1: f64, h: f64, saturated: Option<f64>) -> Law {
        match self.hub {
            Hub::Prescribed(_) => unreachable!("a prescribed hub has no law"),
            Hub::OpenLoop { torque, gear } => Law {
                k: 0.0,
                c: 0.0,
                moment: gear * torque.at_in(t1, t1 - 0.5 * h),
                saturated: false,
            },
            Hub::Controller {
                profile,
                kp,
                kd,
                ki,
                ..
            } => {
                if let Some(sign_limit) = saturated {
                    return Law {
                        k: 0.0,
                        c: 0.0,
                        moment: sign_limit,
                        saturated: true,
                    };
                }
                let (p1, w1, _) = profile.at_in(t1, t1 - 0.5 * h);
                let (p0, ..) = profile.at_in(self.state.t, t1 - 0.5 * h);
                let e0 = p0 - self.state.q[2];
                // z₁ = z₀ + h/2 (e₀ + p₁ − θ₁)
                let zb = self.z + 0.5 * h * (e0 + p1);
                Law {
                    k: kp + ki * 0.5 * h,
                    c: kd,
                    moment: kp * p1 + kd * w1 + ki * zb,
                    saturated: false,
                }
            }
        }
    }

    fn set_law(&mut self, law: Law) -> Result<(), ImpactError> {
        let root = RootSupport::Hub {
            inertia: self.j_rotor,
            k_theta: law.k,
            c_theta: law.c + self.c_rotor,
        };
        if self.spec.root != root {
            self.spec.root = root;
            self.model = BeamModel::new(self.spec.clone())?;
        }
        self.loads.set_moment(0, law.moment)?;
        Ok(())
    }

    /// The controller's unsaturated torque at the current state (after a step to it).
    fn controller_torque(&self) -> Option<(f64, f64)> {
        let Hub::Controller {
            profile,
            kp,
            kd,
            ki,
            limit,
        } = self.hub
        else {
            return None;
        };
        let (p, w, _) = profile.at(self.state.t);
        let (th, om, _) = self.hub_motion();
        Some((kp * (p - th) + kd * (w - om) + ki * self.z, limit))
    }

    /// One step of `h` with the contact on or off; returns the contact's state at its end.
    fn step(&mut self, h: f64, contact: bool) -> Result<ContactState, ImpactError> {
        let cs = self.step_on_branch(h, contact)?;
        if self.saturated_at.is_none() && self.law_used.is_some_and(|l| l.saturated) {
            self.saturated_at = Some(self.state.t);
        }
        Ok(cs)
    }

    /// [`Solver::step`] on the controller's branch (free or at its limit) that its end confirms.
    fn step_on_branch(&mut self, h: f64, contact: bool) -> Result<ContactState, ImpactError> {
        let t1 = self.state.t + h;
        let start = self.snapshot();
        let mut saturated: Option<f64> = self.law_used.filter(|l| l.saturated).map(|l| l.moment);
        for attempt in 0..3 {
            let cs = self.try_step(h, contact, t1, saturated)?;
            let Some((tau, limit)) = self.controller_torque() else {
                return Ok(cs);
            };
            if attempt == 2 {
                return Ok(cs);
            }
            match saturated {
                None if tau.abs() > limit => {
                    saturated = Some(limit.copysign(tau));
                    self.restore(&start);
                }
                Some(m) if tau.abs() < limit || tau.signum() != m.signum() => {
                    saturated = None;
                    self.restore(&start);
                }
                _ => return Ok(cs),
            }
        }
        unreachable!("returns within three attempts")
    }

    fn try_step(
        &mut self,
        h: f64,
        contact: bool,
        t1: f64,
        saturated: Option<f64>,
    ) -> Result<ContactState, ImpactError> {
        let head = self.head.over(h);
        let theta0 = self.state.q[2];
        if !matches!(self.hub, Hub::Prescribed(_)) {
            let law = self.law_for(t1, h, saturated);
            self.set_law(law)?;
            self.law_used = Some(law);
        }
        let mut load = DomeLoad {
            geometry: self.geometry,
            law: self.law.as_ref(),
            head,
            tip: self.tip,
            active: contact,
            last: ContactState::default(),
        };
        let report = match self.hub {
            Hub::Prescribed(profile) => {
                let branch = t1 - 0.5 * h;
                let root = move |t: f64| {
                    let (p, w, a) = profile.at_in(t, branch);
                    [p, w, a]
                };
                self.ga.step_with_root(
                    &self.model,
                    &mut self.state,
                    &mut self.ws,
                    h,
                    &self.loads,
                    Some(&mut load),
                    &root,
                )?
            }
            _ => self.ga.step_with(
                &self.model,
                &mut self.state,
                &mut self.ws,
                h,
                &self.loads,
                Some(&mut load),
            )?,
        };
        if report.substeps > 1 {
            return Err(ImpactError::NotFinished {
                design: "exact driven CL",
                reason: format!(
                    "the beam's Newton needed a split step at t = {:.6e} s (h = {h:.3e} s): \
                     raise approach_steps or contact_steps",
                    self.state.t
                ),
            });
        }
        let (q, v) = self.tip_qv();
        let (cs, ..) = load.solve(q, v);
        // the head's end state
        if !self.head.wall {
            let a1 = (cs.f - self.head.k_n * cs.x_h - self.head.c_n * cs.v_h) / self.head.m;
            self.head.x = cs.x_h;
            self.head.v = cs.v_h;
            self.head.a = a1;
        }
        if let Hub::Controller { profile, .. } = self.hub {
            let (p1, ..) = profile.at_in(t1, t1 - 0.5 * h);
            let (p0, ..) = profile.at_in(t1 - h, t1 - 0.5 * h);
            let e1 = p1 - self.state.q[2];
            let e0 = p0 - theta0;
            self.z += 0.5 * h * (e0 + e1);
        }
        Ok(cs)
    }
}

/// Power terms at one instant [W]: motor, friction, neck damper, contact damping, impact.
fn powers(s: &Solver<'_>, cs: &ContactState, torque: f64) -> [f64; 5] {
    let (_, om, _) = s.hub_motion();
    let head_damper = if s.head.wall {
        0.0
    } else {
        s.head.c_n * s.head.v * s.head.v
    };
    [
        torque * om,
        s.c_rotor * om * om,
        head_damper,
        cs.f_damping * cs.rate,
        if cs.rate > 0.0 { cs.f * cs.rate } else { 0.0 },
    ]
}

impl Solver<'_> {
    /// The joint torque τ_j [N·m] the motor applies (after the gear) at the current state.
    fn joint_torque(&self) -> f64 {
        let (th, om, al) = self.hub_motion();
        match self.hub {
            Hub::Prescribed(_) => {
                flexrig_beam::root_reaction(&self.model, &self.state, &self.loads)[2]
                    + self.j_rotor * al
                    + self.c_rotor * om
            }
            _ => self
                .law_used
                .map_or(0.0, |l| l.moment - l.k * th - l.c * om),
        }
    }

    /// The link's elastic moment at the root [N·m]: what the hub passes on to the beam.
    fn root_moment(&self) -> f64 {
        let (_, om, al) = self.hub_motion();
        self.joint_torque() - self.c_rotor * om - self.j_rotor * al
    }

    /// Mechanical energy \[J\]: the beam (with a free hub's rotor), a prescribed hub's rotor,
    /// the head and its neck, the contact's elastic energy at `cs`.
    fn energy(&self, cs: &ContactState) -> f64 {
        let e = self.state.energy(&self.model);
        let (k_root, _, _) = self.model.root().spring_damper_inertia();
        let (th, om, _) = self.hub_motion();
        let rotor = match self.hub {
            Hub::Prescribed(_) => 0.5 * self.j_rotor * om * om,
            _ => 0.0,
        };
        let contact = if cs.delta > 0.0 {
            self.law.elastic_energy(cs.delta)
        } else {
            0.0
        };
        e.kinetic + e.strain - 0.5 * k_root * th * th + rotor + self.head.energy() + contact
    }

    /// The tip's deflection from the hub's line \[m\] and its rate there relative to the hub's
    /// rotation [m/s] (positive towards the person).
    fn tip_deflection(&self) -> (f64, f64) {
        let (th, om, _) = self.hub_motion();
        let (q, v) = self.tip_qv();
        let (s, c) = th.sin_cos();
        let (px, py) = (self.geometry.length + q[0], q[1]);
        let d = -s * px + c * py;
        let rate = -s * v[0] + c * v[1] - om * (c * px + s * py);
        (d, rate)
    }

    fn sample(&self, cs: &ContactState) -> TraceSample {
        let (th, om, _) = self.hub_motion();
        TraceSample {
            t: self.state.t,
            hub_angle_rad: th,
            hub_speed_rad_s: om,
            tip_deflection_m: self.tip_deflection().0,
            indentation_m: cs.delta,
            force_n: cs.f,
            joint_torque_nm: self.joint_torque(),
            head_position_m: if self.head.wall { 0.0 } else { self.head.x },
            moment_nm: self.root_moment(),
            head_acceleration_mps2: if self.head.wall { 0.0 } else { self.head.a },
        }
    }

    /// Retakes the step from `from` with length `h` and returns the contact's state.
    fn retake(
        &mut self,
        from: &Snapshot,
        h: f64,
        contact: bool,
    ) -> Result<ContactState, ImpactError> {
        self.restore(from);
        self.step(h, contact)
    }

    /// From `from` the step length in (0, h] at which `what` (of the contact's state) is 0,
    /// given its values `d0` there and `dh` after the whole step (of opposite signs), by the
    /// Illinois method; leaves the solver there.
    fn locate(
        &mut self,
        from: &Snapshot,
        (d0, h, dh): (f64, f64, f64),
        contact: bool,
        what: fn(&ContactState) -> f64,
        scale: f64,
    ) -> Result<ContactState, ImpactError> {
        let (mut a, mut fa, mut b, mut fb) = (0.0, d0, h, dh);
        let mut side = 0;
        let mut best = None;
        for _ in 0..60 {
            let x = b - fb * (b - a) / (fb - fa);
            let x = if x > a && x < b { x } else { 0.5 * (a + b) };
            let cs = self.retake(from, x, contact)?;
            let fx = what(&cs);
            best = Some(cs);
            if fx.abs() <= 1e-15 * scale || (b - a) <= 1e-15 * h.max(1e-300) {
                break;
            }
            if (fx > 0.0) == (fb > 0.0) {
                b = x;
                fb = fx;
                if side == 1 {
                    fa *= 0.5;
                }
                side = 1;
            } else {
                a = x;
                fa = fx;
                if side == -1 {
                    fb *= 0.5;
                }
                side = -1;
            }
        }
        Ok(best.expect("at least one iteration"))
    }
}

/// The link's first bending frequency estimate √(k_δ/(m_e + 0.2357 m_r)) [rad/s] (Rayleigh,
/// the static shape), for the approach's step.
fn first_frequency(link: &crate::LinkParams) -> f64 {
    (link.k_delta / (link.m_e + 0.2357 * link.m_r)).sqrt()
}

/// Runs the exact driven CL strike from the drive's start to the separation of the first
/// contact (on the mesh [`ExactSettings::mesh_tolerance`] asks for: see
/// [`run_exact_cl_meshed`]).
pub fn run_exact_cl(
    strike: &DrivenStrike,
    settings: &ExactSettings,
) -> Result<DrivenOutcome, ImpactError> {
    run_exact_cl_until(strike, settings, &std::sync::atomic::AtomicBool::new(false))
}

/// [`run_exact_cl`], stopping with [`ImpactError::Interrupted`] within a step once `stop` is
/// set.
pub fn run_exact_cl_until(
    strike: &DrivenStrike,
    settings: &ExactSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<DrivenOutcome, ImpactError> {
    run_exact_cl_meshed_until(strike, settings, stop).map(|(o, _)| o)
}

/// Largest relative change between the strikes on two meshes: the first contact's peak force,
/// time of peak after the onset (against the duration), duration and onset, and the largest
/// peak over every contact (the first's when the run ends at the first separation).
fn mesh_change(a: &DrivenOutcome, b: &DrivenOutcome) -> f64 {
    let rel = |p: f64, q: f64| (p - q).abs() / q.abs().max(f64::MIN_POSITIVE);
    let change = |x: &ContactEvent, y: &ContactEvent| {
        [
            rel(x.peak_force_n, y.peak_force_n),
            ((x.time_of_peak_s - x.onset_s) - (y.time_of_peak_s - y.onset_s)).abs()
                / y.duration_s.max(f64::MIN_POSITIVE),
            rel(x.duration_s, y.duration_s),
            rel(x.onset_s, y.onset_s),
        ]
        .into_iter()
        .fold(0.0, f64::max)
    };
    change(&a.contact, &b.contact).max(rel(
        a.largest_contact().1.peak_force_n,
        b.largest_contact().1.peak_force_n,
    ))
}

/// [`run_exact_cl`] and the number of elements of the mesh it was solved on. With a
/// [`ExactSettings::mesh_tolerance`] the strike is solved on `elements`, 2×, 4×, … elements
/// until two successive meshes agree to 3 tol (Richardson's estimate for a 1/N² error: the
/// finer mesh is then within tol); the finer one's outcome is returned, its `work` the steps of
/// every mesh.
pub fn run_exact_cl_meshed(
    strike: &DrivenStrike,
    settings: &ExactSettings,
) -> Result<(DrivenOutcome, usize), ImpactError> {
    run_exact_cl_meshed_until(strike, settings, &std::sync::atomic::AtomicBool::new(false))
}

/// [`run_exact_cl_meshed`], stopping with [`ImpactError::Interrupted`] within a step once
/// `stop` is set.
pub fn run_exact_cl_meshed_until(
    strike: &DrivenStrike,
    settings: &ExactSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<(DrivenOutcome, usize), ImpactError> {
    strike.validate()?;
    settings.validate()?;
    let Some(tol) = settings.mesh_tolerance else {
        return Ok((run_on_mesh(strike, settings, stop)?, settings.elements));
    };
    let mut n = settings.elements;
    // traced as well: a run stopped or failed on this mesh keeps what it computed
    let mut coarse = run_on_mesh(strike, settings, stop)?;
    let mut work = coarse.work;
    let mut change = f64::INFINITY;
    loop {
        let m = 2 * n;
        if m > 512 {
            return Err(ImpactError::NotFinished {
                design: "exact driven CL",
                reason: format!(
                    "the link's mesh did not converge to {tol:e} by 512 elements ({n} and {} \
                     elements differ by {change:.2e})",
                    n / 2
                ),
            });
        }
        let mut fine = run_on_mesh(
            strike,
            &ExactSettings {
                elements: m,
                ..*settings
            },
            stop,
        )?;
        work += fine.work;
        change = mesh_change(&coarse, &fine);
        if change <= 3.0 * tol {
            fine.work = work;
            return Ok((fine, m));
        }
        fine.trace.clear();
        coarse = fine;
        n = m;
    }
}

/// The strike on `settings.elements` elements.
fn run_on_mesh(
    strike: &DrivenStrike,
    settings: &ExactSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<DrivenOutcome, ImpactError> {
    let mut tracer = Tracer::new(settings.trace_every);
    run_on_mesh_traced(strike, settings, stop, &mut tracer)
        .map_err(|e| ImpactError::with_trace(e, std::mem::take(&mut tracer.samples)))
}

/// [`run_on_mesh`], its samples going to `tracer` (kept there when the run fails midway).
fn run_on_mesh_traced(
    strike: &DrivenStrike,
    settings: &ExactSettings,
    stop: &std::sync::atomic::AtomicBool,
    tracer: &mut Tracer,
) -> Result<DrivenOutcome, ImpactError> {
    let link = strike.link;
    let l = link.length;
    let ei = link.ei();
    let section =
        Section::from_stiffness(settings.axial_slenderness * ei / (l * l), ei, link.rho_a())?;
    let mut spec = BeamSpec::cantilever(l, section, settings.elements, Kinematics::Corotational);
    if link.m_e > 0.0 {
        spec.point_masses.push(PointMass {
            node: settings.elements,
            mass: link.m_e,
            inertia: 0.0,
        });
    }
    let motor = *strike.drive.motor();
    let j_rotor = motor.reflected_inertia();
    let c_rotor = motor.reflected_friction();
    let (z0, lag0, speed0) = strike.drive.steady_preload()?;
    let hub = match strike.drive.command() {
        DriveCommand::Trajectory { profile } => Hub::Prescribed(profile),
        DriveCommand::Controller { profile, gains, .. } => Hub::Controller {
            profile,
            kp: gains.kp,
            kd: gains.kd,
            ki: gains.ki,
            limit: strike.drive.joint_torque_limit(),
        },
        DriveCommand::OpenLoop { torque, .. } => Hub::OpenLoop {
            torque,
            gear: motor.gear_ratio,
        },
    };
    let (angle0, rate0, accel0) = match hub {
        Hub::Prescribed(p) => p.at(0.0),
        Hub::Controller { profile, .. } => (profile.at(0.0).0 - lag0, speed0, 0.0),
        Hub::OpenLoop { .. } => (0.0, strike.drive.initial_speed(), 0.0),
    };
    if !matches!(hub, Hub::Prescribed(_)) {
        spec.root = RootSupport::Hub {
            inertia: j_rotor,
            k_theta: 0.0,
            c_theta: c_rotor,
        };
    }
    let model = BeamModel::new(spec.clone())?;
    let loads = NodalLoads::zeros(&model);
    let phi_c = strike.placement.angle(&strike.drive)?;
    let (head_m, k_n, c_n, wall) = match strike.person.support {
        HeadSupport::Free => (strike.person.m_h, 0.0, 0.0, false),
        HeadSupport::Neck { stiffness, damping } => (strike.person.m_h, stiffness, damping, false),
        HeadSupport::Wall => (f64::INFINITY, 0.0, 0.0, true),
    };
    let steady = strike.drive.profile().is_some_and(|p| p.is_steady())
        || matches!(strike.drive.command(), DriveCommand::OpenLoop { .. });
    let state = if steady {
        State::in_steady_rotation(&model, [angle0, rate0], 0.0, &loads)?
    } else {
        State::in_rigid_rotation(&model, [angle0, rate0, accel0], 0.0, &loads)?
    };
    let ga = GeneralizedAlpha::new(1.0)?
        .with_newton(30, 1e-12)?
        .with_newton_method(settings.newton);
    let law0 = strike.person.damping.law(strike.person.contact, 1.0)?;
    let mut s = Solver {
        ws: Workspace::new(&model),
        model,
        spec,
        ga,
        loads,
        state,
        head: Head {
            x: 0.0,
            v: -strike.person.speed,
            a: 0.0,
            m: head_m,
            k_n,
            c_n,
            wall,
        },
        hub,
        z: z0,
        j_rotor,
        c_rotor,
        geometry: Geometry {
            length: l,
            d_c: settings.dome.centre_offset(),
            e: [-phi_c.sin(), phi_c.cos()],
        },
        law: law0,
        tip: settings.elements,
        saturated_at: None,
        law_used: None,
    };
    if !matches!(hub, Hub::Prescribed(_)) {
        // the drive's law at t = 0 and the start's accelerations under it
        let law = s.law_for(0.0, 0.0, None);
        let law = match s.controller_torque() {
            Some((tau, limit)) if tau.abs() > limit => Law {
                k: 0.0,
                c: 0.0,
                moment: limit.copysign(tau),
                saturated: true,
            },
            _ => law,
        };
        s.set_law(law)?;
        s.law_used = Some(law);
        s.state = if steady {
            State::in_steady_rotation(&s.model, [angle0, rate0], 0.0, &s.loads)?
        } else {
            State::in_rigid_rotation(&s.model, [angle0, rate0, 0.0], 0.0, &s.loads)?
        };
    }
    let mut pass = Pass {
        tracer,
        steps: 0,
        max_steps: settings.max_steps,
        horizon: strike.horizon_s,
        corners: Vec::new(),
        stop,
        length: l,
    };
    let (mut cs, ..) = {
        let (q, v) = s.tip_qv();
        let load = DomeLoad {
            geometry: s.geometry,
            law: s.law.as_ref(),
            head: s.head.over(0.0),
            tip: s.tip,
            active: false,
            last: ContactState::default(),
        };
        load.solve(q, v)
    };
    if cs.delta > 0.0 {
        return Err(ImpactError::invalid(
            "placement",
            format!("{phi_c} rad"),
            "an angle the dome has not yet passed at t = 0 (it already indents the face)",
        ));
    }
    pass.tracer.offer(0.0, true, || s.sample(&cs));
    // the approach: approach_steps per the drive's shortest time scale (a ramp, the loop's
    // period with the rigid link, the arrival) or per a tenth of the link's first period if
    // that is longer: the drive's motion and a soft link's ringing (its period longer than the
    // drive's scale) are resolved, a stiff link's fast, small ringing is not chased (measured:
    // the test bed's link bent by a 0.5 s ramp, per 0.5 s instead of per its 1.24 s period,
    // 1000 steps: 2e-5 instead of 6e-5 in peak)
    let period = std::f64::consts::TAU / first_frequency(&link);
    let j_link = j_rotor + (link.m_r / 3.0 + link.m_e) * l * l;
    let mut drive_scale = strike.horizon_s;
    if let Some(p) = strike.drive.profile()
        && !p.is_steady()
    {
        drive_scale = drive_scale.min(p.ramp_end());
    }
    if let Hub::Controller { kp, .. } = hub
        && kp > 0.0
    {
        drive_scale = drive_scale.min(std::f64::consts::TAU * (j_link / kp).sqrt());
    }
    let speed_scale = strike
        .drive
        .profile()
        .map_or(strike.drive.initial_speed(), |p| p.final_speed())
        .abs();
    if speed_scale > 0.0 {
        drive_scale = drive_scale.min((phi_c - angle0).abs().max(1e-3) / speed_scale);
    }
    let h_a = drive_scale.max(0.1 * period) / settings.approach_steps as f64;
    pass.corners = strike.drive.breakpoints();
    pass.corners.sort_by(f64::total_cmp);
    match pass.fly(&mut s, &mut cs, h_a, None)? {
        Flight::Onset => {}
        Flight::Window(_) | Flight::Parted(_) => {
            return Err(ImpactError::NotFinished {
                design: "exact driven CL",
                reason: format!(
                    "the link did not reach the person within horizon_s = {} s (the drive's \
                     torque limit or command may not carry it there)",
                    strike.horizon_s
                ),
            });
        }
        Flight::OutOfSteps => {
            return Err(ImpactError::NotFinished {
                design: "exact driven CL",
                reason: format!(
                    "max_steps = {} ran out before the onset",
                    settings.max_steps
                ),
            });
        }
    }
    // the onset
    let t_on = s.state.t;
    let approach = cs.rate;
    let dome_speed = cs.rate + cs.v_h;
    s.law = strike
        .person
        .damping
        .law(strike.person.contact, approach.max(1e-9))?;
    let (deflection, vibration) = s.tip_deflection();
    let torque_on = s.joint_torque();
    let commanded = strike.drive.profile().map(|p| l * p.at(t_on).1);
    let e0 = s.energy(&cs);
    pass.tracer.offer(t_on, true, || s.sample(&cs));
    // the contact
    let setup = Impact {
        mu: if wall {
            link.m_e.max(link.m_r / 100.0)
        } else {
            let m = link.m_e.max(link.m_r / 100.0);
            head_m * m / (head_m + m)
        },
        k: strike.person.contact.k(),
        n: strike.person.contact.n(),
        contact_steps: settings.contact_steps,
        h_a,
    };
    let first = pass.contact(&mut s, &mut cs, &setup, torque_on.abs())?;
    let e1 = s.energy(&cs);
    let [motor_work, friction, neck, damping, impact] = first.acc;
    let dissipated = friction + neck + damping;
    let energy = EnergyBalance {
        impact_energy_j: impact,
        motor_work_j: motor_work,
        dissipated_j: dissipated,
        mechanical_change_j: e1 - e0,
        residual_j: motor_work - dissipated - (e1 - e0),
    };
    let separation_rate = cs.rate;
    let mut contacts = vec![first.event];
    let mut peak_torque = first.peak_torque;
    let mut pressing_at_window = first.window_closed;
    // ---- every later contact, until the bodies part for good or the window closes ----
    let ended = if first.window_closed {
        crate::RunEnd::Window(strike.horizon_s)
    } else if !settings.every_contact {
        crate::RunEnd::FirstSeparation
    } else {
        // between contacts the step resolves a contact as short as an eighth of the first one's
        // expected duration (a re-contact comes at a closing speed the drive and the link's
        // ringing give; one shorter than a step could be stepped over)
        let h_free = h_a.min(first.expected_duration_s / 8.0);
        let reach = (!wall && s.head.k_n == 0.0 && s.head.c_n == 0.0)
            .then(|| farthest_reach(l, settings.dome.centre_offset()));
        loop {
            match pass.fly(&mut s, &mut cs, h_free, reach)? {
                Flight::Parted(t) => break crate::RunEnd::PartedForGood(t),
                Flight::Window(t) => break crate::RunEnd::Window(t),
                Flight::OutOfSteps => {
                    return Err(ImpactError::NotFinished {
                        design: "exact driven CL",
                        reason: format!(
                            "max_steps = {} ran out between contacts",
                            settings.max_steps
                        ),
                    });
                }
                Flight::Onset => {
                    s.law = strike
                        .person
                        .damping
                        .law(strike.person.contact, cs.rate.max(1e-9))?;
                    let torque = s.joint_torque().abs();
                    pass.tracer.offer(s.state.t, true, || s.sample(&cs));
                    let c = pass.contact(&mut s, &mut cs, &setup, torque)?;
                    peak_torque = peak_torque.max(c.peak_torque);
                    contacts.push(c.event);
                    if c.window_closed {
                        pressing_at_window = true;
                        break crate::RunEnd::Window(strike.horizon_s);
                    }
                }
            }
        }
    };
    let mut notes = Vec::new();
    if pressing_at_window {
        notes.push(DriveNote::StillPressing {
            window_s: strike.horizon_s,
        });
    }
    if let Some(first_s) = s.saturated_at {
        notes.push(DriveNote::TorqueLimitReached { first_s });
    }
    if let Some(c) = commanded {
        notes.extend(DriveNote::arrival(c, dome_speed));
    }
    notes.extend(DriveNote::vibration(vibration, approach));
    let outcome = DrivenOutcome {
        contact: first.event,
        approach_speed_mps: approach,
        commanded_tip_speed_mps: commanded,
        pre_impact_deflection_m: deflection,
        joint_torque_at_onset_nm: torque_on,
        peak_joint_torque_nm: peak_torque,
        energy,
        separation_rate_mps: separation_rate,
        notes,
        work: pass.steps,
        trace: std::mem::take(&mut pass.tracer.samples),
        contacts,
        ended,
    };
    finite(outcome)
}

/// The farthest the dome's surface can reach along the face's normal from where it first
/// touches, over every pose of the link \[m\]: the dome's centre lies within |p| + |d_c| of the
/// hub, the tip's distance |p| within the link's length stretched by [`STRETCH_BOUND`], and
/// the face at the first touch lies d_c beyond the centre's projection, so
/// e·c + d_c ≤ (1 + ε) L + |d_c| + d_c.
fn farthest_reach(length: f64, d_c: f64) -> f64 {
    (1.0 + STRETCH_BOUND) * length + d_c.abs() + d_c
}

/// Bound on the link's stretch between contacts used by [`farthest_reach`]: 5 %, far beyond
/// the elastic strain of any link material (metals yield below 1 %; the beam's axial strain in
/// a strike is f/EA ≈ 4e-4 at 100 N on the test bed's section).
const STRETCH_BOUND: f64 = 0.05;

/// What the phases of one exact CL run share: the trace, the work done, the window, the
/// drive's corners, the stop flag.
struct Pass<'r> {
    tracer: &'r mut Tracer,
    steps: usize,
    max_steps: usize,
    horizon: f64,
    corners: Vec<f64>,
    stop: &'r std::sync::atomic::AtomicBool,
    /// The link's length L \[m\] (the onset's location scale).
    length: f64,
}

/// How a flight of the link without contact ended.
enum Flight {
    /// The next contact's onset (the solver stands there).
    Onset,
    /// A free head moving away beyond [`farthest_reach`] at this time \[s\].
    Parted(f64),
    /// The window closed at this time \[s\].
    Window(f64),
    /// The step budget ran out.
    OutOfSteps,
}

/// The contact's constants: the reduced mass of the impact time estimate, the law's k and n,
/// the steps per contact and the approach's step.
struct Impact {
    /// m_e (or m_r/100) in series with the head \[kg\].
    mu: f64,
    k: f64,
    n: f64,
    contact_steps: usize,
    /// The approach's step \[s\] (the largest step of a long press).
    h_a: f64,
}

/// One contact from its onset to its separation (or the window).
struct Struck {
    event: ContactEvent,
    /// ∫ power dt over the contact: motor, friction, neck damper, contact damping, impact \[J\].
    acc: [f64; 5],
    peak_torque: f64,
    window_closed: bool,
    /// The contact duration expected from the onset's closing speed \[s\].
    expected_duration_s: f64,
}

impl Pass<'_> {
    fn check_stop(&self) -> Result<(), ImpactError> {
        if self.stop.load(std::sync::atomic::Ordering::Relaxed) {
            Err(ImpactError::Interrupted)
        } else {
            Ok(())
        }
    }

    /// The link and the head without contact by steps of `h_a` (cut at the drive's corners)
    /// until the dome touches the face (the onset located on the motion; the solver and `cs`
    /// left there), the head parts for good (`reach`: a free head moving away beyond it), the
    /// window closes or the steps run out.
    fn fly(
        &mut self,
        s: &mut Solver<'_>,
        cs: &mut ContactState,
        h_a: f64,
        reach: Option<f64>,
    ) -> Result<Flight, ImpactError> {
        loop {
            self.check_stop()?;
            if s.state.t >= self.horizon {
                return Ok(Flight::Window(s.state.t));
            }
            if self.steps >= self.max_steps {
                return Ok(Flight::OutOfSteps);
            }
            if let Some(r) = reach
                && s.head.v >= 0.0
                && s.head.x > r
            {
                return Ok(Flight::Parted(s.state.t));
            }
            let t = s.state.t;
            let mut h = h_a;
            if let Some(c) = self
                .corners
                .iter()
                .find(|c| **c > t * (1.0 + 1e-14) + 1e-15)
            {
                if t + h > *c - 1e-3 * h_a {
                    h = c - t;
                } else if t + 2.0 * h > *c {
                    h = 0.5 * (c - t);
                }
            }
            let from = s.snapshot();
            // after a separation the located gap may be a rounding error inside the face
            let d0 = if cs.delta > 0.0 {
                -f64::MIN_POSITIVE
            } else {
                cs.delta
            };
            let next = s.step(h, false)?;
            self.steps += 1;
            if next.delta > 0.0 {
                *cs = s.locate(&from, (d0, h, next.delta), false, |c| c.delta, self.length)?;
                self.steps += 1;
                return Ok(Flight::Onset);
            }
            *cs = next;
            self.tracer.offer(s.state.t, false, || s.sample(cs));
        }
    }

    /// The contact from its onset (the solver and `cs` there, the law set for the onset's
    /// closing speed) to its separation, located on the motion, or to the window's end.
    fn contact(
        &mut self,
        s: &mut Solver<'_>,
        cs: &mut ContactState,
        im: &Impact,
        torque_on: f64,
    ) -> Result<Struck, ImpactError> {
        let t_on = s.state.t;
        let v = cs.rate.max(1e-6);
        let delta_max = ((im.n + 1.0) * im.mu * v * v / (2.0 * im.k)).powf(1.0 / (im.n + 1.0));
        let t_c = 2.0 * delta_max / v * hertz_time_integral(im.n);
        let h_c = t_c / im.contact_steps as f64;
        // the step: h_c through the impact; a contact that outlasts fifty impact times is the
        // drive pressing the person, a slow, quasi-static motion: there the step grows by 1.5
        // while the force changes by less than 1e-4 of its peak per step, halves (not below
        // h_c) when it changes by more than 1e-3, and never passes the approach's step or the
        // window's end
        let mut h = h_c;
        let h_press = im.h_a.max(h_c);
        let mut acc = [0.0; 5];
        let mut p0 = powers(s, cs, s.joint_torque());
        let mut samples: Vec<(f64, f64)> = vec![(t_on, 0.0)];
        let mut peak = (0.0_f64, t_on);
        let mut peak_torque = torque_on;
        // an elastic law (no damping part at the onset's rate): the peak is at δ̇ = 0
        let elastic = s.law.damping(1e-3 * delta_max, v) == 0.0;
        let mut located_peak: Option<(f64, f64)> = None;
        let mut window_closed = false;
        let l = self.length;
        loop {
            self.check_stop()?;
            if self.steps >= self.max_steps {
                return Err(ImpactError::NotFinished {
                    design: "exact driven CL",
                    reason: format!("max_steps = {} ran out in the contact", self.max_steps),
                });
            }
            if s.state.t >= self.horizon {
                // the window closed with the contact on (the drive pressing the person): the
                // force there counts as well
                if cs.f > peak.0 {
                    peak = (cs.f, s.state.t);
                }
                window_closed = true;
                self.tracer.offer(s.state.t, true, || s.sample(cs));
                break;
            }
            let from = s.snapshot();
            let (d0, rate0) = (cs.delta, cs.rate);
            let t0 = s.state.t;
            let mut next = s.step(h, true)?;
            self.steps += 1;
            let finished = next.delta <= 0.0 && s.state.t > t_on + 0.05 * t_c;
            if finished {
                next = s.locate(&from, (d0.max(1e-300), h, next.delta), true, |c| c.delta, l)?;
                self.steps += 1;
            } else if elastic && located_peak.is_none() && rate0 > 0.0 && next.rate <= 0.0 {
                // an elastic law peaks where δ̇ = 0: located on the motion, not interpolated
                next = s.locate(&from, (rate0, h, next.rate), true, |c| c.rate, v)?;
                self.steps += 1;
                located_peak = Some((next.f, s.state.t));
            }
            *cs = next;
            let tau = s.joint_torque();
            let p1 = powers(s, cs, tau);
            let dt = s.state.t - t0;
            for i in 0..5 {
                acc[i] += 0.5 * dt * (p0[i] + p1[i]);
            }
            p0 = p1;
            peak_torque = peak_torque.max(tau.abs());
            samples.push((s.state.t, cs.f));
            let m = samples.len();
            if m >= 3 {
                let (a, b, c) = (samples[m - 3], samples[m - 2], samples[m - 1]);
                if b.1 > a.1 && b.1 >= c.1 {
                    let v = vertex(a, b, c);
                    if v.1 > peak.0 {
                        peak = (v.1, v.0);
                    }
                }
            }
            if s.state.t - t_on > 50.0 * t_c && samples.len() >= 2 {
                let df = (cs.f - samples[samples.len() - 2].1).abs();
                let scale = peak.0.max(cs.f).max(f64::MIN_POSITIVE);
                if df < 1e-4 * scale {
                    h = (1.5 * h).min(h_press);
                } else if df > 1e-3 * scale {
                    h = (0.5 * h).max(h_c);
                }
                let left = self.horizon - s.state.t;
                if left > 0.0 && h > left {
                    h = left;
                }
            }
            if samples.len() > 8 {
                samples.drain(..samples.len() - 3);
            }
            self.tracer.offer(s.state.t, finished, || s.sample(cs));
            if finished {
                break;
            }
        }
        if let Some(p) = located_peak
            && p.0 >= peak.0
        {
            peak = p;
        }
        if peak.0 == 0.0 {
            // a single-step contact: the largest sample
            peak = samples
                .iter()
                .fold((0.0, t_on), |m, x| if x.1 > m.0 { (x.1, x.0) } else { m });
        }
        Ok(Struck {
            event: ContactEvent {
                onset_s: t_on,
                peak_force_n: peak.0,
                time_of_peak_s: peak.1,
                duration_s: s.state.t - t_on,
            },
            acc,
            peak_torque,
            window_closed,
            expected_duration_s: t_c,
        })
    }
}

/// Vertex (t, f) of the parabola through three samples, kept within [a, c].
fn vertex(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> (f64, f64) {
    let (h0, h1) = (b.0 - a.0, c.0 - b.0);
    let d0 = (b.1 - a.1) / h0;
    let d1 = (c.1 - b.1) / h1;
    let curvature = (d1 - d0) / (h0 + h1);
    if curvature >= 0.0 {
        return b;
    }
    let slope = d0 + curvature * h0;
    let tau = (-slope / (2.0 * curvature)).clamp(-h0, h1);
    (b.0 + tau, b.1 + slope * tau + curvature * tau * tau)
}

/// The outcome if every number is finite.
fn finite(o: DrivenOutcome) -> Result<DrivenOutcome, ImpactError> {
    let values = [
        o.contact.peak_force_n,
        o.contact.time_of_peak_s,
        o.contact.duration_s,
        o.pre_impact_deflection_m,
        o.energy.residual_j,
        o.separation_rate_mps,
        o.peak_joint_torque_nm,
    ];
    if values.iter().all(|v| v.is_finite()) {
        Ok(o)
    } else {
        Err(ImpactError::NotFinished {
            design: "exact driven CL",
            reason: "the integration lost finiteness".into(),
        })
    }
}

impl DrivenStrike {
    /// The CL strike by the default model: the geometrically exact link
    /// ([`run_exact_cl`] at [`ExactSettings::DEFAULT`], the test bed's dome). The linear modal
    /// link ([`crate::driven_cl::run_driven_cl`]) stays as the faster option; its error against
    /// this one is in its rustdoc.
    pub fn run_cl(&self) -> Result<DrivenOutcome, ImpactError> {
        run_exact_cl(self, &ExactSettings::DEFAULT)
    }

    /// The CJ strike by the default model: the rigid link on its torsion spring with the exact
    /// dome geometry ([`run_exact_cj`] at [`CjSettings::DEFAULT`], the test bed's dome).
    pub fn run_cj(&self) -> Result<DrivenOutcome, ImpactError> {
        run_exact_cj(self, &CjSettings::DEFAULT, &Dome::TEST_BED)
    }
}
