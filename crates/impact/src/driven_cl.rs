//! The driven compliant link striking a person: the FE beam (flexrig-beam's Hermite cubics on
//! the mesh graded towards the tip, [`crate::graded`]) clamped to the motor's hub, by its modes
//! and an exact modal integrator with **two ports**: the tip (the contact force, −f) and the
//! drive.
//!
//! * **Controller or open-loop torque**: the hub is a free DOF θ₀ with the rotor's inertia
//!   J_m N² (the free hub's matrices; its modes from the rigid rotation and the clamped beam's
//!   modes by the secular equation, [`crate::hub_modes`], so the rigid or the loop's mode is
//!   exact on any mesh); every mode obeys q̈ᵢ + ωᵢ² qᵢ = −bᵢ f + cᵢ u with
//!   bᵢ = φᵢ(tip), cᵢ = φᵢ(θ₀), u = τ_j − c_j θ̇₀ the net hub torque (τ_j from the controller
//!   of [`crate::drive`] at the hub's θ₀ = Σ cᵢ qᵢ, θ̇₀, or N τ_m(t); c_j = c_m N²), tip
//!   w = Σ bᵢ qᵢ.
//! * **Prescribed trajectory**: the beam is clamped to a hub at θ(t); in the clamped modes
//!   q̈ᵢ + ωᵢ² qᵢ = −bᵢ f − gᵢ θ̈(t), gᵢ = φᵢᵀ M ι (ι: the rigid rotation, x on v and 1 on θ),
//!   tip w = L θ(t) + Σ bᵢ qᵢ; the hub takes τ_j = (J_m N² + ιᵀMι) θ̈ + Σ gᵢ q̈ᵢ + L f + c_j θ̇.
//!
//! Over a step both port loads are held linear in time and every mode is integrated exactly
//! (Nigam–Jennings, as in [`crate::modal_run`]); the head (free, on a neck, or a wall) too. The
//! end-of-step force and drive load solve two coupled equations: for a given f₁ the drive's u₁ is
//! explicit (its law is piecewise linear in θ₀, θ̇₀), leaving one monotone scalar equation for
//! f₁ (Illinois). The step follows the curvature of f and of u (h² |f″|/8 ≤ tol · f_max, the same
//! for u), lands on the drive's corners, and in free flight is bounded by the gap over the
//! fastest the gap can close, so no contact is skipped; the onset and the separation are located
//! on the exact motion. With [`ClDriveSettings::every_contact`] the run goes on after a
//! separation — the link and the head fly on with the drive acting, by the same free-flight
//! steps, to the next onset — until the window closes (the run is split into its flights,
//! [`Run::fly`], and its contacts, [`Run::contact`]). Motor work, friction, damping and impact
//! work over the first contact by Simpson's rule on each step (mid-step state exact). The
//! controller's integral ∫e_φ dt by the trapezoidal rule.
//!
//! **One file, one concept** (about 1 400 lines): the driven compliant link's two-port modal
//! integrator — the drive's law, the exact modal steps, the contact's force solve, the events and
//! the energy terms of one step loop.

use faer::Mat;
use flexrig_beam::modal::ShiftedPencil;
use flexrig_contact::ContactLaw;
use nalgebra::{Matrix4, Vector4};

use crate::ImpactError;
use crate::drive::{DriveCommand, HeadSupport, Profile, TorqueProfile};
use crate::graded::{GradedMesh, LinkMatrices, cl_matrices};
use crate::hub_modes::{ClampedModes, hub_modes};
use crate::setup::{ContactEvent, FreeMassImpact, Joint};
use crate::strike::{DriveNote, DrivenOutcome, DrivenStrike, EnergyBalance, TraceSample, Tracer};

/// How the driven CL is solved.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ClDriveSettings {
    /// The mesh (`mode_cut` is ignored: every mode is kept, the exact integrator does not mind
    /// their frequency).
    pub mesh: GradedMesh,
    /// Relative deviation of the linear holds per step in the contact.
    pub tol: f64,
    /// The same before the contact (the drive's torque against its largest value so far).
    pub approach_tol: f64,
    /// Most steps, approach and contact.
    pub max_steps: usize,
    /// `Some(dt)`: sample the motion at the integrator's steps, at most every dt \[s\].
    pub trace_every: Option<f64>,
    /// `false`: stop at the first separation; `true`: follow every contact, the drive keeping
    /// its command, until the window (`horizon_s`) closes. Along the linear model's path (the
    /// tip and the head on one line) the tip can always come back, so no parting for good is
    /// declared before the window.
    pub every_contact: bool,
}

impl ClDriveSettings {
    /// The default graded mesh with at most L/48 elements (a long push of the whole link needs
    /// the body resolved too), tol 1e-6 in the contact and 1e-5 before it, 10⁶ steps.
    pub const DEFAULT: ClDriveSettings = ClDriveSettings {
        mesh: GradedMesh {
            min_elements: 48,
            ..GradedMesh::DEFAULT
        },
        tol: 1e-6,
        approach_tol: 1e-5,
        max_steps: 1_000_000,
        trace_every: None,
        every_contact: false,
    };
}

/// The structure's modes at its two ports.
struct Modes {
    omegas: Vec<f64>,
    /// bᵢ at the tip.
    tip: Vec<f64>,
    /// cᵢ at the drive port.
    port: Vec<f64>,
}

/// Mode coefficients over one step h: [cos x, sin x/ω, ω sin x, α, β, α_v, β_v] (x = ωh).
fn coefficients(omega: f64, h: f64) -> [f64; 7] {
    let x = omega * h;
    let (sin, cos) = x.sin_cos();
    let (one_minus_cos, x_minus_sin, sinc) = if x < 1e-2 {
        let x2 = x * x;
        (
            0.5 - x2 / 24.0 + x2 * x2 / 720.0,
            1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0,
            1.0 - x2 / 6.0 + x2 * x2 / 120.0,
        )
    } else {
        ((1.0 - cos) / (x * x), (x - sin) / (x * x * x), sin / x)
    };
    let h2 = h * h;
    let beta = h2 * x_minus_sin;
    let alpha = h2 * one_minus_cos - beta;
    let beta_v = h * one_minus_cos;
    let alpha_v = h * sinc - beta_v;
    [cos, h * sinc, omega * sin, alpha, beta, alpha_v, beta_v]
}

/// Every per-step coefficient for one step length.
struct StepCoef {
    h: f64,
    modes: Vec<[f64; 7]>,
    /// The head's exact map over the step (neck), or `None` (free head: closed form; wall).
    head: Option<Matrix4<f64>>,
}

/// Coefficients of the step lengths h_ref 2^{k/4}, computed once each.
struct Levels {
    h_ref: f64,
    levels: std::collections::HashMap<i32, std::rc::Rc<StepCoef>>,
}

impl Levels {
    /// The level at or below `h`.
    fn level_for(&self, h: f64) -> i32 {
        (4.0 * (h / self.h_ref).log2()).floor() as i32
    }

    fn get(&mut self, int: &Integrator<'_>, level: i32) -> std::rc::Rc<StepCoef> {
        let h_ref = self.h_ref;
        self.levels
            .entry(level)
            .or_insert_with(|| {
                std::rc::Rc::new(int.coefficients_for(h_ref * 2f64.powf(level as f64 / 4.0)))
            })
            .clone()
    }
}

/// The drive port's law in the integrator.
enum Port<'a> {
    /// u = θ̈_cmd(t) (clamped modes, cᵢ = −gᵢ).
    Prescribed {
        profile: &'a Profile,
        g: Vec<f64>,
        j_total: f64,
    },
    /// u = sat(K_p e_φ + K_d e_ω + K_i z) − c θ̇.
    Feedback {
        profile: &'a Profile,
        kp: f64,
        kd: f64,
        ki: f64,
        limit: f64,
    },
    /// u = N τ_m(t) − c θ̇.
    OpenLoop {
        torque: &'a TorqueProfile,
        gear: f64,
    },
}

/// What the drive's torque and the powers need at an instant.
#[derive(Debug, Clone, Copy)]
struct Ports {
    /// Tip position and rate.
    w: f64,
    wv: f64,
    /// Hub angle, rate and (prescribed) acceleration.
    hub: f64,
    hub_rate: f64,
    hub_acc: f64,
    /// Σ cᵢ ωᵢ² qᵢ.
    cwq: f64,
    xh: f64,
    vh: f64,
    f: f64,
    u: f64,
}

/// Everything at one instant.
#[derive(Debug, Clone)]
struct Point {
    t: f64,
    q: Vec<f64>,
    qd: Vec<f64>,
    xh: f64,
    vh: f64,
    f: f64,
    u: f64,
    z: f64,
    /// Drive torque τ_j and whether it is at its limit.
    torque: f64,
    saturated: bool,
}

struct Integrator<'a> {
    modes: Modes,
    port: Port<'a>,
    /// The contact's law (set at each onset for its closing speed).
    law: Option<Box<dyn ContactLaw>>,
    /// c_j = c_m N² [N·m·s/rad].
    friction: f64,
    l: f64,
    /// Head: 1/m_h (0: wall), neck k and c, rest position.
    m_h: f64,
    wall: bool,
    k_n: f64,
    c_n: f64,
    x_rest: f64,
    /// Breakpoint branch (a time inside the current segment).
    branch: f64,
    /// The controller's K_p, folded into the structure's stiffness on θ₀ (its spring is then
    /// integrated exactly; the port carries the rest of the law) [N·m/rad].
    folded: f64,
    /// (Σ gᵢ bᵢ, Σ gᵢ²) of a prescribed hub (gᵢ = −cᵢ).
    port_sums: (f64, f64),
    /// (Σ cᵢ bᵢ, Σ cᵢ²) of a free hub (its acceleration θ̈₀ = −Σ cᵢ ωᵢ² qᵢ − f Σ cᵢ bᵢ + u Σ cᵢ²).
    hub_sums: (f64, f64),
    /// The rotor's inertia at the joint J_m N² [kg·m²].
    rotor_inertia: f64,
}

/// The linear parts of one step: end values = constant + slope × (f₁, u₁).
struct Linear {
    h: f64,
    q: Vec<f64>,
    qd: Vec<f64>,
    // w = w0 − sbb f + sbc u, ẇ likewise with _v; θ = t0 − sbc f + scc u
    w0: f64,
    wv0: f64,
    th0: f64,
    tv0: f64,
    sbb: f64,
    sbc: f64,
    scc: f64,
    sbb_v: f64,
    sbc_v: f64,
    scc_v: f64,
    // head x = x0 + xf f, v = v0 + vf f
    x0: f64,
    xf: f64,
    v0: f64,
    vf: f64,
}

impl Integrator<'_> {
    fn command(&self, t: f64) -> Option<(f64, f64, f64)> {
        let p = match &self.port {
            Port::Prescribed { profile, .. } | Port::Feedback { profile, .. } => profile,
            Port::OpenLoop { .. } => return None,
        };
        Some(p.at_in(t, self.branch))
    }

    /// Hub angle and rate (free-hub modes).
    fn hub(&self, q: &[f64], qd: &[f64]) -> (f64, f64) {
        let m = &self.modes;
        let th = m.port.iter().zip(q).map(|(c, x)| c * x).sum();
        let tv = m.port.iter().zip(qd).map(|(c, x)| c * x).sum();
        (th, tv)
    }

    /// Tip position and rate.
    fn tip(&self, t: f64, q: &[f64], qd: &[f64]) -> (f64, f64) {
        let m = &self.modes;
        let mut w: f64 = m.tip.iter().zip(q).map(|(b, x)| b * x).sum();
        let mut wv: f64 = m.tip.iter().zip(qd).map(|(b, x)| b * x).sum();
        if let Port::Prescribed { .. } = self.port {
            let (th, om, _) = self.command(t).expect("a profile");
            w += self.l * th;
            wv += self.l * om;
        }
        (w, wv)
    }

    fn coefficients_for(&self, h: f64) -> StepCoef {
        StepCoef {
            h,
            modes: self
                .modes
                .omegas
                .iter()
                .map(|&w| coefficients(w, h))
                .collect(),
            head: if self.wall || (self.k_n == 0.0 && self.c_n == 0.0) {
                None
            } else {
                Some(self.head_coefficients(h))
            },
        }
    }

    fn head_coefficients(&self, h: f64) -> Matrix4<f64> {
        // z = (x − x_rest, v, f(τ), f₁ − f₀): ż = A z over the step (f linear in τ)
        let (k, c, inv) = (self.k_n, self.c_n, 1.0 / self.m_h);
        let a = Matrix4::new(
            0.0,
            1.0,
            0.0,
            0.0,
            -k * inv,
            -c * inv,
            inv,
            0.0,
            0.0,
            0.0,
            0.0,
            1.0 / h,
            0.0,
            0.0,
            0.0,
            0.0,
        );
        (a * h).exp()
    }

    fn linear(&self, s: &Point, sc: &StepCoef) -> Linear {
        let h = sc.h;
        let n = self.modes.omegas.len();
        let mut lin = Linear {
            h,
            q: Vec::with_capacity(n),
            qd: Vec::with_capacity(n),
            w0: 0.0,
            wv0: 0.0,
            th0: 0.0,
            tv0: 0.0,
            sbb: 0.0,
            sbc: 0.0,
            scc: 0.0,
            sbb_v: 0.0,
            sbc_v: 0.0,
            scc_v: 0.0,
            x0: s.xh,
            xf: 0.0,
            v0: 0.0,
            vf: 0.0,
        };
        for i in 0..n {
            let k = &sc.modes[i];
            let (b, c) = (self.modes.tip[i], self.modes.port[i]);
            let p0 = -b * s.f + c * s.u;
            let qi = k[0] * s.q[i] + k[1] * s.qd[i] + k[3] * p0;
            let vi = -k[2] * s.q[i] + k[0] * s.qd[i] + k[5] * p0;
            lin.w0 += b * qi;
            lin.wv0 += b * vi;
            lin.th0 += c * qi;
            lin.tv0 += c * vi;
            lin.sbb += b * b * k[4];
            lin.sbc += b * c * k[4];
            lin.scc += c * c * k[4];
            lin.sbb_v += b * b * k[6];
            lin.sbc_v += b * c * k[6];
            lin.scc_v += c * c * k[6];
            lin.q.push(qi);
            lin.qd.push(vi);
        }
        if let Port::Prescribed { .. } = self.port {
            let (th, om, _) = self.command(s.t + h).expect("a profile");
            lin.w0 += self.l * th;
            lin.wv0 += self.l * om;
        }
        (lin.x0, lin.xf, lin.v0, lin.vf) = self.head_map(s, sc);
        lin
    }

    /// The head at the step's end: x = x0 + xf f₁, v = v0 + vf f₁.
    fn head_map(&self, s: &Point, sc: &StepCoef) -> (f64, f64, f64, f64) {
        let h = sc.h;
        if self.wall {
            (s.xh, 0.0, 0.0, 0.0)
        } else if let Some(e) = &sc.head {
            let z = Vector4::new(s.xh - self.x_rest, s.vh, s.f, -s.f);
            let end = e * z;
            (end[0] + self.x_rest, e[(0, 3)], end[1], e[(1, 3)])
        } else {
            // a free head under f linear in τ: x₁ = x + h v + h² (f₀/3 + f₁/6)/m
            let inv = 1.0 / self.m_h;
            (
                s.xh + h * s.vh + h * h * s.f * inv / 3.0,
                h * h * inv / 6.0,
                s.vh + 0.5 * h * s.f * inv,
                0.5 * h * inv,
            )
        }
    }

    /// The drive load u₁ and the drive torque for a given f₁ (and whether at the limit).
    fn port_load(&self, s: &Point, lin: &Linear, f: f64) -> (f64, f64, bool) {
        let t1 = s.t + lin.h;
        let c = self.friction;
        // θ = a_t + s_t u, θ̇ = a_v + s_v u for this f
        let (a_t, s_t) = (lin.th0 - lin.sbc * f, lin.scc);
        let (a_v, s_v) = (lin.tv0 - lin.sbc_v * f, lin.scc_v);
        match &self.port {
            Port::Prescribed { .. } => {
                let (_, _, al) = self.command(t1).expect("a profile");
                (al, 0.0, false)
            }
            Port::OpenLoop { torque, gear } => {
                let tau = gear * torque.at_in(t1, self.branch);
                // u = τ − c (a_v + s_v u)
                ((tau - c * a_v) / (1.0 + c * s_v), tau, false)
            }
            Port::Feedback {
                kp, kd, ki, limit, ..
            } => {
                let (pc, wc, _) = self.command(t1).expect("a profile");
                let (pc0, _, _) = self.command(s.t).expect("a profile");
                let (th_s, _) = self.hub(&s.q, &s.qd);
                let e0 = pc0 - th_s;
                // z₁ = z₀ + h/2 (e₀ + pc − θ₁); τ = kp (pc − θ) + kd (wc − θ̇) + ki z₁
                let z_part = s.z + 0.5 * lin.h * (e0 + pc);
                let raw0 = kp * (pc - a_t) + kd * (wc - a_v) + ki * (z_part - 0.5 * lin.h * a_t);
                let raw_u = -(kp * s_t + kd * s_v + ki * 0.5 * lin.h * s_t);
                // unsaturated: u = raw0 + raw_u u − c (a_v + s_v u)
                // u = τ − c θ̇ + K_p θ (K_p θ₀'s spring is in the structure)
                let kf = self.folded;
                let u = (raw0 - c * a_v + kf * a_t) / (1.0 - raw_u + c * s_v - kf * s_t);
                let tau = raw0 + raw_u * u;
                if tau.abs() <= *limit {
                    (u, tau, false)
                } else {
                    let tau = limit * tau.signum();
                    (
                        (tau - c * a_v + kf * a_t) / (1.0 + c * s_v - kf * s_t),
                        tau,
                        true,
                    )
                }
            }
        }
    }

    /// (δ₁, δ̇₁) for (f₁, u₁).
    fn gap(&self, lin: &Linear, f: f64, u: f64) -> (f64, f64) {
        let w = lin.w0 - lin.sbb * f + lin.sbc * u;
        let wv = lin.wv0 - lin.sbb_v * f + lin.sbc_v * u;
        let (x, v) = (lin.x0 + lin.xf * f, lin.v0 + lin.vf * f);
        (w - x, wv - v)
    }

    /// f₁ (0 when `unloaded` or out of contact).
    fn solve_force(&self, s: &Point, lin: &Linear, unloaded: bool) -> f64 {
        let Some(law) = self.law.as_deref() else {
            return 0.0;
        };
        if unloaded {
            return 0.0;
        }
        let r = |f: f64| {
            let (u, _, _) = self.port_load(s, lin, f);
            let (d, dv) = self.gap(lin, f, u);
            f - law.force(d, dv)
        };
        let r0 = r(0.0);
        if r0 >= 0.0 {
            return 0.0;
        }
        // bracket: the force that closes the gap on the linear slope, doubled as needed
        let (u0, _, _) = self.port_load(s, lin, 0.0);
        let (d0, _) = self.gap(lin, 0.0, u0);
        let slope = lin.sbb + lin.xf.abs().max(0.0) + 1e-300;
        let mut hi = (d0 / slope).max(s.f).max(1e-300);
        let mut r_hi = r(hi);
        let mut guard = 0;
        while r_hi <= 0.0 && guard < 200 {
            hi *= 2.0;
            r_hi = r(hi);
            guard += 1;
        }
        illinois(r, 0.0, r0, hi, r_hi, 1e-15 * hi)
    }

    fn finish(&self, s: &Point, sc: &StepCoef, lin: Linear, f: f64) -> Point {
        let (u, torque, saturated) = self.port_load(s, &lin, f);
        let (x_end, v_end) = (lin.x0 + lin.xf * f, lin.v0 + lin.vf * f);
        let h = lin.h;
        let mut q = lin.q;
        let mut qd = lin.qd;
        for i in 0..q.len() {
            let p1 = -self.modes.tip[i] * f + self.modes.port[i] * u;
            q[i] += sc.modes[i][4] * p1;
            qd[i] += sc.modes[i][6] * p1;
        }
        let z = match &self.port {
            Port::Feedback { .. } => {
                let (pc0, _, _) = self.command(s.t).expect("a profile");
                let (pc1, _, _) = self.command(s.t + h).expect("a profile");
                let (th0, _) = self.hub(&s.q, &s.qd);
                let (th1, _) = self.hub(&q, &qd);
                s.z + 0.5 * h * (pc0 - th0 + pc1 - th1)
            }
            _ => 0.0,
        };
        Point {
            t: s.t + h,
            q,
            qd,
            xh: x_end,
            vh: v_end,
            f,
            u,
            z,
            torque,
            saturated,
        }
    }

    fn step(&self, s: &Point, sc: &StepCoef, unloaded: bool) -> Point {
        let lin = self.linear(s, sc);
        let f = self.solve_force(s, &lin, unloaded);
        self.finish(s, sc, lin, f)
    }

    /// A step of any length (coefficients computed for it).
    fn step_any(&self, s: &Point, h: f64, unloaded: bool) -> Point {
        self.step(s, &self.coefficients_for(h), unloaded)
    }

    /// The ports at a point: one pass over the modes.
    fn ports(&self, p: &Point) -> Ports {
        let m = &self.modes;
        let (mut w, mut wv, mut th, mut tv, mut cwq) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for i in 0..p.q.len() {
            let (b, c, om) = (m.tip[i], m.port[i], m.omegas[i]);
            w += b * p.q[i];
            wv += b * p.qd[i];
            th += c * p.q[i];
            tv += c * p.qd[i];
            cwq += c * om * om * p.q[i];
        }
        self.ports_from(p.t, [w, wv, th, tv, cwq], p.xh, p.vh, p.f, p.u)
    }

    /// The ports half-way through the step s → e of coefficients `half` (h/2), the holds at
    /// their midpoints (one pass, nothing stored).
    fn mid_ports(&self, s: &Point, e: &Point, half: &StepCoef) -> Ports {
        let m = &self.modes;
        let (f, u) = (0.5 * (s.f + e.f), 0.5 * (s.u + e.u));
        let (mut w, mut wv, mut th, mut tv, mut cwq) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for i in 0..s.q.len() {
            let k = &half.modes[i];
            let (b, c, om) = (m.tip[i], m.port[i], m.omegas[i]);
            let p0 = -b * s.f + c * s.u;
            let p1 = -b * f + c * u;
            let q = k[0] * s.q[i] + k[1] * s.qd[i] + k[3] * p0 + k[4] * p1;
            let qd = -k[2] * s.q[i] + k[0] * s.qd[i] + k[5] * p0 + k[6] * p1;
            w += b * q;
            wv += b * qd;
            th += c * q;
            tv += c * qd;
            cwq += c * om * om * q;
        }
        let (x0, xf, v0, vf) = self.head_map(s, half);
        self.ports_from(
            s.t + half.h,
            [w, wv, th, tv, cwq],
            x0 + xf * f,
            v0 + vf * f,
            f,
            u,
        )
    }

    fn ports_from(&self, t: f64, sums: [f64; 5], xh: f64, vh: f64, f: f64, u: f64) -> Ports {
        let [mut w, mut wv, th, tv, cwq] = sums;
        let (hub, hub_rate, hub_acc) = match &self.port {
            Port::Prescribed { .. } => {
                let (a, b, c) = self.command(t).expect("a profile");
                w += self.l * a;
                wv += self.l * b;
                (a, b, c)
            }
            _ => (th, tv, 0.0),
        };
        Ports {
            w,
            wv,
            hub,
            hub_rate,
            hub_acc,
            cwq,
            xh,
            vh,
            f,
            u,
        }
    }

    fn sample(&self, p: &Point) -> TraceSample {
        let ports = self.ports(p);
        TraceSample {
            t: p.t,
            hub_angle_rad: ports.hub,
            hub_speed_rad_s: ports.hub_rate,
            tip_deflection_m: ports.w - self.l * ports.hub,
            indentation_m: ports.w - ports.xh,
            force_n: p.f,
            joint_torque_nm: self.torque(&ports),
            head_position_m: ports.xh,
            moment_nm: self.root_moment(&ports),
            head_acceleration_mps2: if self.wall {
                0.0
            } else {
                (p.f - self.k_n * (ports.xh - self.x_rest) - self.c_n * ports.vh) / self.m_h
            },
        }
    }

    /// The beam's root moment [N·m]: what the hub passes on to the clamped beam, from the hub's
    /// balance J_m N² θ̈ = τ_j − c_j θ̇ − M_root.
    fn root_moment(&self, p: &Ports) -> f64 {
        let acc = match self.port {
            Port::Prescribed { .. } => p.hub_acc,
            _ => -p.cwq - p.f * self.hub_sums.0 + p.u * self.hub_sums.1,
        };
        self.torque(p) - self.friction * p.hub_rate - self.rotor_inertia * acc
    }

    /// (motor power, friction power, damping power, impact power) \[W\].
    fn powers(&self, p: &Ports) -> [f64; 4] {
        let (delta, rate) = (p.w - p.xh, p.wv - p.vh);
        let contact = match self.law.as_deref() {
            Some(law) if delta > 0.0 => (p.f - law.elastic().force(delta, 0.0)) * rate,
            _ => 0.0,
        };
        let neck = if self.wall {
            0.0
        } else {
            self.c_n * p.vh * p.vh
        };
        let impact = p.f * rate.max(0.0);
        let speed = p.hub_rate;
        [
            self.torque(p) * speed,
            self.friction * speed * speed,
            neck + contact,
            impact,
        ]
    }

    /// Drive torque τ_j [N·m]: prescribed, what the hub takes,
    /// τ = J θ̈ + Σ gᵢ q̈ᵢ + L f + c θ̇ with q̈ᵢ = −ωᵢ² qᵢ − bᵢ f − gᵢ θ̈ (gᵢ = −cᵢ); otherwise
    /// consistent with the hold, τ = u − K_p θ + c θ̇.
    fn torque(&self, p: &Ports) -> f64 {
        match &self.port {
            Port::Prescribed { j_total, .. } => {
                let (gb, gg) = self.port_sums;
                j_total * p.hub_acc + self.l * p.f + self.friction * p.hub_rate + p.cwq
                    - p.f * gb
                    - p.hub_acc * gg
            }
            _ => p.u - self.folded * p.hub + self.friction * p.hub_rate,
        }
    }

    fn energy(&self, p: &Point) -> f64 {
        let modal: f64 = (0..p.q.len())
            .map(|i| {
                let w = self.modes.omegas[i];
                0.5 * (p.qd[i] * p.qd[i] + w * w * p.q[i] * p.q[i])
            })
            .sum();
        let rigid = match &self.port {
            Port::Prescribed { g, j_total, .. } => {
                let (_, om, _) = self.command(p.t).expect("a profile");
                0.5 * j_total * om * om + om * g.iter().zip(&p.qd).map(|(a, b)| a * b).sum::<f64>()
            }
            _ => 0.0,
        };
        let (w, _) = self.tip(p.t, &p.q, &p.qd);
        let contact = self
            .law
            .as_deref()
            .map_or(0.0, |law| law.elastic_energy((w - p.xh).max(0.0)));
        let head = if self.wall {
            0.0
        } else {
            0.5 * self.m_h * p.vh * p.vh + 0.5 * self.k_n * (p.xh - self.x_rest).powi(2)
        };
        // the folded controller spring is not the robot's: its work is the motor's
        let folded = match &self.port {
            Port::Feedback { .. } => 0.5 * self.folded * self.hub(&p.q, &p.qd).0.powi(2),
            _ => 0.0,
        };
        modal + rigid + contact + head - folded
    }

    /// The gap δ = w − x_h at a point.
    /// The drive's torque scale at `p` for the approach's step control \[N·m\]: a controller's
    /// torque (its port load carries K_p φ_cmd, which grows with the angle and says nothing of
    /// the torque's accuracy), otherwise the port's load.
    fn torque_scale(&self, p: &Point) -> f64 {
        match self.port {
            Port::Feedback { .. } => p.torque.abs(),
            _ => p.u.abs(),
        }
    }

    fn delta(&self, p: &Point) -> (f64, f64) {
        let (w, wv) = self.tip(p.t, &p.q, &p.qd);
        (w - p.xh, wv - p.vh)
    }

    /// The fastest the gap can close from `p` [m/s] (rigid and port-driven parts at their current
    /// rate plus every flexible mode at its amplitude's top speed), for the free-flight bound.
    fn closing_speed_bound(&self, p: &Point) -> f64 {
        let mut speed = p.vh.abs();
        let (_, wv) = self.tip(p.t, &p.q, &p.qd);
        speed += wv.abs();
        for i in 0..p.q.len() {
            let w = self.modes.omegas[i];
            if w > 0.0 {
                let amp = (p.q[i] * p.q[i] + (p.qd[i] / w).powi(2)).sqrt();
                speed += self.modes.tip[i].abs() * amp * w;
            }
        }
        speed
    }
}

/// Root of g in [a, b] (Illinois regula falsi).
fn illinois(
    g: impl Fn(f64) -> f64,
    mut a: f64,
    mut ga: f64,
    mut b: f64,
    mut gb: f64,
    tol: f64,
) -> f64 {
    if ga == 0.0 {
        return a;
    }
    if gb == 0.0 || ga * gb > 0.0 {
        return b;
    }
    for _ in 0..200 {
        let c = (a * gb - b * ga) / (gb - ga);
        let gc = g(c);
        if gc == 0.0 {
            return c;
        }
        let moved = (c - b).abs();
        if gc * gb < 0.0 {
            a = b;
            ga = gb;
        } else {
            ga *= 0.5;
        }
        b = c;
        gb = gc;
        if moved <= tol || (b - a).abs() <= tol {
            return b;
        }
    }
    b
}

/// Modes of (K, M) with gains at `tip` and along the port vector `port` (cᵢ = φᵢᵀ port), the
/// initial modal displacements and rates for the displacement `x0` and velocity `v0`.
fn port_modes(
    mats: &LinkMatrices,
    port: &[f64],
    x0: &[f64],
    v0: &[f64],
    shift: f64,
) -> Result<(Modes, Vec<f64>, Vec<f64>), ImpactError> {
    let n = mats.k.nrows();
    let pencil = ShiftedPencil::solve(&mats.k, &mats.m, shift)?;
    let lambda_max = pencil.lambda.iter().copied().fold(0.0_f64, f64::max);
    let mx0: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|j| mats.m[(i, j)] * x0[j]).sum())
        .collect();
    let mv0: Vec<f64> = (0..n)
        .map(|i| (0..n).map(|j| mats.m[(i, j)] * v0[j]).sum())
        .collect();
    let mut modes = Modes {
        omegas: Vec::new(),
        tip: Vec::new(),
        port: Vec::new(),
    };
    let (mut q0, mut qd0) = (Vec::new(), Vec::new());
    for i in (0..n).rev() {
        let lambda = pencil.lambda[i];
        if lambda <= 1e-14 * lambda_max {
            break;
        }
        let phi = pencil.vector(i);
        let w2 = 1.0 / lambda - shift;
        let w2 = if w2.abs() <= 1e-8 * shift {
            0.0
        } else {
            w2.max(0.0)
        };
        let scale = 1.0 / lambda.sqrt();
        let dot = |v: &[f64]| (0..n).map(|j| phi[(j, 0)] * v[j]).sum::<f64>() * scale;
        modes.omegas.push(w2.sqrt());
        modes.tip.push(phi[(mats.tip, 0)] * scale);
        modes.port.push(dot(port));
        q0.push(dot(&mx0));
        qd0.push(dot(&mv0));
    }
    Ok((modes, q0, qd0))
}

/// The rigid rotation's shape on the free DOFs of `mats` (x on v, 1 on θ), for node positions
/// from `lengths`; `with_hub`: the hub's θ₀ is the first free DOF.
fn rigid_shape(lengths: &[f64], with_hub: bool) -> Vec<f64> {
    let mut out = Vec::new();
    if with_hub {
        out.push(1.0);
    }
    let mut x = 0.0;
    for le in lengths {
        x += le;
        out.push(x);
        out.push(1.0);
    }
    out
}

/// Runs the driven CL strike from the drive's start to the separation of the first contact,
/// with the **linear** link and the contact along the tip's path — the faster option. Its
/// error against the geometrically exact link ([`crate::exact_link::run_exact_cl`], the
/// default, [`DrivenStrike::run_cl`]) on the test bed's link (51 g, 0.338 m, 412 g payload,
/// free 4 kg head, tip speed 1 m/s commanded): peak force 1.1e-3 low on a steady approach,
/// 1.4e-2 high after a 1 s ramp that leaves the link ringing, 2.5e-2 high after a 0.5 s ramp
/// that bends it by 0.11 m, 1.5e-2 under a PD loop; contact duration 0.8 %, 1.2 %, 9 % and
/// 1.3 % (crates/impact/tests/exact_link.rs `linear_model_error`). It misses the centrifugal
/// stiffening, the large deflection and the dome's moment on the tip section.
pub fn run_driven_cl(
    strike: &DrivenStrike,
    settings: &ClDriveSettings,
) -> Result<DrivenOutcome, ImpactError> {
    run_driven_cl_until(strike, settings, &std::sync::atomic::AtomicBool::new(false))
}

/// [`run_driven_cl`], stopping with [`ImpactError::Interrupted`] within a step once `stop` is
/// set.
pub fn run_driven_cl_until(
    strike: &DrivenStrike,
    settings: &ClDriveSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<DrivenOutcome, ImpactError> {
    let mut tracer = Tracer::new(settings.trace_every);
    run_driven_cl_traced(strike, settings, stop, &mut tracer)
        .map_err(|e| ImpactError::with_trace(e, std::mem::take(&mut tracer.samples)))
}

/// [`run_driven_cl_until`], its samples going to `tracer` (kept there when the run fails
/// midway).
fn run_driven_cl_traced(
    strike: &DrivenStrike,
    settings: &ClDriveSettings,
    stop: &std::sync::atomic::AtomicBool,
    tracer: &mut Tracer,
) -> Result<DrivenOutcome, ImpactError> {
    strike.validate()?;
    settings.mesh.validate()?;
    for (field, tol) in [
        ("tol", settings.tol),
        ("approach_tol", settings.approach_tol),
    ] {
        if !(tol.is_finite() && (1e-14..=1e-2).contains(&tol)) {
            return Err(ImpactError::invalid(
                field,
                tol,
                "must lie in [1e-14, 1e-2]",
            ));
        }
    }
    if !(100..=100_000_000).contains(&settings.max_steps) {
        return Err(ImpactError::invalid(
            "max_steps",
            settings.max_steps,
            "must lie in [100, 1e8]",
        ));
    }
    let link = strike.link;
    let l = link.length;
    let motor = *strike.drive.motor();
    let (z0, lag0, speed0) = strike.drive.steady_preload()?;
    // the mesh's tip zone from the expected approach speed
    let v_expect = strike
        .drive
        .profile()
        .map_or(l * speed0.abs(), |p| l * p.final_speed().abs())
        .max(strike.person.speed)
        .max(1e-3);
    let prescribed = matches!(strike.drive.command(), DriveCommand::Trajectory { .. });
    let folded = match strike.drive.command() {
        DriveCommand::Controller { gains, .. } => gains.kp,
        _ => 0.0,
    };
    let (m_h, support) = (strike.person.m_h, strike.person.support);
    let setup = FreeMassImpact {
        m_h: if support == HeadSupport::Wall {
            1e9
        } else {
            m_h
        },
        v0: v_expect,
        link,
        joint: if prescribed {
            Joint::Held
        } else {
            Joint::FreeHub {
                rotor_inertia: motor.reflected_inertia(),
            }
        },
        contact: strike.person.contact,
        damping: flexrig_contact::DampingSpec::NONE,
    };
    setup.validate()?;
    let lengths = settings.mesh.element_lengths(&setup)?;
    let mats = cl_matrices(&setup, &lengths)?;
    let n = mats.k.nrows();
    let shape = rigid_shape(&lengths, !prescribed);
    let shift = link.ei() / (link.rho_a() * l.powi(4));
    let (modes, q0, qd0, port) = if prescribed {
        // cᵢ = −gᵢ = −φᵢᵀ M ι
        let m_iota: Vec<f64> = (0..n)
            .map(|i| -(0..n).map(|j| mats.m[(i, j)] * shape[j]).sum::<f64>())
            .collect();
        let zeros = vec![0.0; n];
        let (modes, q0, qd0) = port_modes(&mats, &m_iota, &zeros, &zeros, shift)?;
        let g: Vec<f64> = modes.port.iter().map(|c| -c).collect();
        let j_beam: f64 = (0..n)
            .map(|i| shape[i] * (0..n).map(|j| mats.m[(i, j)] * shape[j]).sum::<f64>())
            .sum();
        let DriveCommand::Trajectory { profile } = strike.drive.command() else {
            unreachable!()
        };
        let port = Port::Prescribed {
            profile,
            g,
            j_total: j_beam + motor.reflected_inertia(),
        };
        (modes, q0, qd0, port)
    } else {
        // the rigid rotation by the hub's angle and the clamped beam's modes, coupled by the
        // secular equation (crate::hub_modes: the hub's mode keeps its digits on a fine mesh)
        let clamped_mats = LinkMatrices {
            k: Mat::from_fn(n - 1, n - 1, |i, j| mats.k[(i + 1, j + 1)]),
            m: Mat::from_fn(n - 1, n - 1, |i, j| mats.m[(i + 1, j + 1)]),
            tip: mats.tip - 1,
            v0: Vec::new(),
        };
        let m_iota: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| mats.m[(i, j)] * shape[j]).sum::<f64>())
            .collect();
        let j_total: f64 = shape.iter().zip(&m_iota).map(|(a, b)| a * b).sum();
        let zeros = vec![0.0; n - 1];
        let (clamped, _, _) = port_modes(&clamped_mats, &m_iota[1..], &zeros, &zeros, shift)?;
        let coupled = hub_modes(
            &ClampedModes {
                omegas: &clamped.omegas,
                coupling: &clamped.port,
                tip: &clamped.tip,
            },
            j_total,
            folded,
            l,
        );
        // the steady start: rigid rotation at speed0, the hub lagging by lag0
        let q0: Vec<f64> = coupled.rigid.iter().map(|r| -r * lag0).collect();
        let qd0: Vec<f64> = coupled.rigid.iter().map(|r| r * speed0).collect();
        let modes = Modes {
            omegas: coupled.omegas,
            tip: coupled.tip,
            port: coupled.hub,
        };
        let port = match strike.drive.command() {
            DriveCommand::Controller { profile, gains, .. } => Port::Feedback {
                profile,
                kp: gains.kp,
                kd: gains.kd,
                ki: gains.ki,
                limit: strike.drive.joint_torque_limit(),
            },
            DriveCommand::OpenLoop { torque, .. } => Port::OpenLoop {
                torque,
                gear: motor.gear_ratio,
            },
            DriveCommand::Trajectory { .. } => unreachable!(),
        };
        (modes, q0, qd0, port)
    };
    let port_sums = match port {
        Port::Prescribed { .. } => (
            -modes
                .port
                .iter()
                .zip(&modes.tip)
                .map(|(c, b)| c * b)
                .sum::<f64>(),
            modes.port.iter().map(|c| c * c).sum::<f64>(),
        ),
        _ => (0.0, 0.0),
    };
    let hub_sums = match port {
        Port::Prescribed { .. } => (0.0, 0.0),
        _ => (
            modes
                .port
                .iter()
                .zip(&modes.tip)
                .map(|(c, b)| c * b)
                .sum::<f64>(),
            modes.port.iter().map(|c| c * c).sum::<f64>(),
        ),
    };
    let (k_n, c_n) = match support {
        HeadSupport::Neck { stiffness, damping } => (stiffness, damping),
        _ => (0.0, 0.0),
    };
    let x_contact = l * strike.placement.angle(&strike.drive)?;
    let mut int = Integrator {
        modes,
        port,
        law: None,
        friction: motor.reflected_friction(),
        folded,
        port_sums,
        hub_sums,
        rotor_inertia: motor.reflected_inertia(),
        l,
        m_h,
        wall: support == HeadSupport::Wall,
        k_n,
        c_n,
        x_rest: x_contact,
        branch: 0.0,
    };
    let mut s = Point {
        t: 0.0,
        q: q0,
        qd: qd0,
        xh: x_contact,
        vh: -strike.person.speed,
        f: 0.0,
        u: 0.0,
        z: z0,
        torque: 0.0,
        saturated: false,
    };
    let t_link = 2.0 * std::f64::consts::PI * (link.cj_tip_mass() / link.k_delta).sqrt();
    // the drive's load at t = 0 (a vanishing step)
    {
        let probe = int.step_any(&s, t_link * 1e-12, true);
        s.u = probe.u;
        s.torque = probe.torque;
        s.saturated = probe.saturated;
    }
    if let Some(dt) = settings.trace_every
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(ImpactError::invalid("trace_every", dt, "a time > 0 s"));
    }
    tracer.offer(0.0, true, || int.sample(&s));
    let mut breaks = strike.drive.breakpoints();
    breaks.push(strike.horizon_s);
    breaks.sort_by(f64::total_cmp);
    let mut run = Run {
        tracer,
        stop,
        steps: 0,
        max_steps: settings.max_steps,
        horizon: strike.horizon_s,
        breaks,
        t_link,
        tol: settings.tol,
        approach_tol: settings.approach_tol,
        saturation_at: None,
        u_ref: int.torque_scale(&s),
    };
    // ---- approach ----
    let (delta0, rate0) = int.delta(&s);
    if delta0 > 0.0 {
        return Err(ImpactError::invalid(
            "placement",
            format!("{} rad", x_contact / l),
            "a person the link has not yet reached at t = 0",
        ));
    }
    let onset_reached = delta0 == 0.0 && rate0 > 0.0;
    if !onset_reached {
        s = match run.fly(&mut int, s)? {
            Flight::Onset(p) => p,
            Flight::OutOfSteps(p) => {
                return Err(ImpactError::NotFinished {
                    design: "driven CL",
                    reason: format!(
                        "the step budget ({}) ran out in the approach at t = {:.6e} s",
                        settings.max_steps, p.t
                    ),
                });
            }
            Flight::Window(p) => {
                let mut reason = format!(
                    "the link did not reach the person within horizon_s = {} s (gap {:.6e} m \
                     at the end)",
                    strike.horizon_s,
                    -int.delta(&p).0
                );
                if let Some(ts) = run.saturation_at {
                    reason.push_str(&format!(
                        "; the torque limit was reached at {ts:.6e} s and cannot hold the speed"
                    ));
                }
                return Err(ImpactError::NotFinished {
                    design: "driven CL",
                    reason,
                });
            }
        };
    }
    // ---- the first contact ----
    let t_on = s.t;
    let (_, approach) = int.delta(&s);
    if !(approach > 0.0) {
        return Err(ImpactError::NotFinished {
            design: "driven CL",
            reason: format!("the link touched the person without approaching (δ̇ = {approach})"),
        });
    }
    int.law = Some(strike.person.damping.law(strike.person.contact, approach)?);
    int.branch = t_on;
    let (w_on, _) = int.tip(s.t, &s.q, &s.qd);
    let hub_on = match &int.port {
        Port::Prescribed { .. } => int.command(t_on).expect("a profile").0,
        _ => int.hub(&s.q, &s.qd).0,
    };
    let deflection = w_on - l * hub_on;
    let (_, tip_speed_on) = int.tip(t_on, &s.q, &s.qd);
    let torque_on = int.torque(&int.ports(&s));
    let e0 = int.energy(&s);
    run.tracer.offer(s.t, true, || int.sample(&s));
    let t_c = setup.payload_contact_time() * v_expect / approach;
    let first = run.contact(&mut int, s, t_c, 1)?;
    let s = first.end;
    let e1 = int.energy(&s);
    let [motor_work, friction, damping, impact] = first.acc;
    let dissipated = friction + damping;
    let energy = EnergyBalance {
        impact_energy_j: impact,
        motor_work_j: motor_work,
        dissipated_j: dissipated,
        mechanical_change_j: e1 - e0,
        residual_j: motor_work - dissipated - (e1 - e0),
    };
    let separation_rate = int.delta(&s).1;
    let mut peak_torque = first.peak_torque.max(torque_on.abs());
    let mut contacts = vec![first.event];
    let mut pressing_at_window = first.window_closed;
    // ---- every later contact, until the window closes ----
    let ended = if first.window_closed {
        crate::RunEnd::Window(strike.horizon_s)
    } else if !settings.every_contact {
        crate::RunEnd::FirstSeparation
    } else {
        let mut s = s;
        loop {
            match run.fly(&mut int, s)? {
                Flight::Window(p) => break crate::RunEnd::Window(p.t),
                Flight::OutOfSteps(p) => {
                    return Err(ImpactError::NotFinished {
                        design: "driven CL",
                        reason: format!(
                            "the step budget ({}) ran out between contacts at t = {:.6e} s",
                            settings.max_steps, p.t
                        ),
                    });
                }
                Flight::Onset(p) => {
                    // a later onset may graze (its located closing speed a rounding error)
                    let rate = int.delta(&p).1.max(1e-9);
                    int.law = Some(strike.person.damping.law(strike.person.contact, rate)?);
                    int.branch = p.t;
                    run.tracer.offer(p.t, true, || int.sample(&p));
                    // the first contact's time scale starts the step control (a later contact
                    // comes slower, so lasts longer)
                    let c = run.contact(&mut int, p, t_c, contacts.len() + 1)?;
                    peak_torque = peak_torque.max(c.peak_torque);
                    if c.event.peak_force_n > 0.0 {
                        contacts.push(c.event);
                    }
                    if c.window_closed {
                        pressing_at_window = true;
                        break crate::RunEnd::Window(strike.horizon_s);
                    }
                    s = c.end;
                }
            }
        }
    };
    let commanded = int.command(t_on).map(|c| l * c.1);
    let mut notes = Vec::new();
    if pressing_at_window {
        notes.push(DriveNote::StillPressing {
            window_s: strike.horizon_s,
        });
    }
    if let Some(ts) = run.saturation_at {
        notes.push(DriveNote::TorqueLimitReached { first_s: ts });
    }
    if let Some(c) = commanded {
        notes.extend(DriveNote::arrival(c, tip_speed_on));
    }
    let outcome = DrivenOutcome {
        contact: contacts[0],
        approach_speed_mps: approach,
        commanded_tip_speed_mps: commanded,
        pre_impact_deflection_m: deflection,
        joint_torque_at_onset_nm: torque_on,
        peak_joint_torque_nm: peak_torque,
        energy,
        separation_rate_mps: separation_rate,
        notes,
        work: run.steps,
        trace: std::mem::take(&mut run.tracer.samples),
        contacts,
        ended,
    };
    crate::driven_cj::finite(outcome)
}

/// What the phases of one linear CL run share: the trace, the work done, the window, the
/// drive's breakpoints, the tolerances, the stop flag.
struct Run<'r> {
    tracer: &'r mut Tracer,
    stop: &'r std::sync::atomic::AtomicBool,
    steps: usize,
    max_steps: usize,
    /// The window's end \[s\].
    horizon: f64,
    /// The drive's breakpoints and the window's end, sorted \[s\].
    breaks: Vec<f64>,
    /// The lumped link's period 2π √(m_e/k_δ) \[s\] (the free flight's step scale).
    t_link: f64,
    /// Relative deviation of the force's hold in a contact, and of the drive's torque out of it.
    tol: f64,
    approach_tol: f64,
    /// When the drive's torque first reached its limit \[s\].
    saturation_at: Option<f64>,
    /// The drive's largest torque scale so far (the approach's step control) \[N·m\].
    u_ref: f64,
}

/// How a flight of the link without contact ended.
enum Flight {
    /// The next contact's onset, located on the motion (the point there).
    Onset(Point),
    /// The window closed (the point at its end).
    Window(Point),
    /// The step budget ran out (the last point).
    OutOfSteps(Point),
}

/// One contact from its onset to its separation (or the window).
struct Pressed {
    event: ContactEvent,
    /// The point at the separation (or the window's end).
    end: Point,
    /// ∫ power dt over the contact: motor, friction, damping, impact \[J\].
    acc: [f64; 4],
    peak_torque: f64,
    window_closed: bool,
}

impl Run<'_> {
    fn check_stop(&self) -> Result<(), ImpactError> {
        if self.stop.load(std::sync::atomic::Ordering::Relaxed) {
            Err(ImpactError::Interrupted)
        } else {
            Ok(())
        }
    }

    /// The link and the head without contact from `s` until the tip touches the head (the onset
    /// located on the exact motion), the window closes or the steps run out. The step follows
    /// the drive's torque (its linear hold within `approach_tol`, the structure being exact for
    /// any step) and never passes the time the gap could close at the fastest it can close
    /// ([`Integrator::closing_speed_bound`]), so no contact is stepped over.
    fn fly(&mut self, int: &mut Integrator<'_>, mut s: Point) -> Result<Flight, ImpactError> {
        let t_link = self.t_link;
        let mut levels = Levels {
            h_ref: t_link * 1e-4,
            levels: std::collections::HashMap::new(),
        };
        let mut level = 0_i32;
        let mut history: Vec<(f64, f64)> = vec![(s.t, s.u)];
        loop {
            self.check_stop()?;
            if self.steps >= self.max_steps {
                return Ok(Flight::OutOfSteps(s));
            }
            if s.t >= self.horizon {
                return Ok(Flight::Window(s));
            }
            self.steps += 1;
            let next_break = self
                .breaks
                .iter()
                .copied()
                .find(|b| *b > s.t * (1.0 + 1e-15))
                .unwrap_or(self.horizon);
            let last_break = self
                .breaks
                .iter()
                .copied()
                .filter(|b| *b <= s.t * (1.0 + 1e-15))
                .fold(0.0, f64::max);
            int.branch = 0.5 * (last_break + next_break);
            // after a separation the located gap may be a rounding error inside the face
            let d0 = int.delta(&s).0.min(-f64::MIN_POSITIVE);
            let gap = -d0;
            let bound = (gap / int.closing_speed_bound(&s).max(1e-300)).max(t_link * 1e-6);
            let limit = bound.min(next_break - s.t);
            let h_level = levels.h_ref * 2f64.powf(level as f64 / 4.0);
            let (sc, h_try) = if h_level <= limit {
                (levels.get(int, level), h_level)
            } else {
                (std::rc::Rc::new(int.coefficients_for(limit)), limit)
            };
            let next = int.step(&s, &sc, true);
            // the torque's curvature
            if history.len() >= 2 {
                let (ta, ua) = history[history.len() - 2];
                let (tb, ub) = history[history.len() - 1];
                let (h0, h1) = (tb - ta, h_try);
                let u2 = 2.0 * ((next.u - ub) / h1 - (ub - ua) / h0) / (h0 + h1);
                let allowed =
                    self.approach_tol * self.u_ref.max(int.torque_scale(&next)).max(1e-300);
                if h1 * h1 * u2.abs() / 8.0 > 4.0 * allowed && h_try > t_link * 1e-9 {
                    level = levels.level_for(h_try) - 4;
                    self.steps -= 1;
                    continue;
                }
                let ideal = if u2 == 0.0 {
                    2.0 * h1
                } else {
                    0.9 * (8.0 * allowed / u2.abs()).sqrt()
                };
                let target = ideal.clamp(0.5 * h1, 2.0 * h1).max(t_link * 1e-9);
                level = levels.level_for(target).min(level + 4);
            } else {
                level += 4;
            }
            if int.delta(&next).0 >= 0.0 {
                // the onset within this step
                let g = |hh: f64| int.delta(&int.step_any(&s, hh, true)).0;
                let h_on = illinois(g, 0.0, d0, h_try, int.delta(&next).0, 1e-14 * h_try);
                return Ok(Flight::Onset(int.step_any(&s, h_on, true)));
            }
            if next.saturated && self.saturation_at.is_none() {
                self.saturation_at = Some(next.t);
            }
            self.u_ref = self.u_ref.max(int.torque_scale(&next));
            s = next;
            self.tracer.offer(s.t, false, || int.sample(&s));
            history.push((s.t, s.u));
            if history.len() > 4 {
                history.remove(0);
            }
        }
    }

    /// Contact `number` (from 1) from its onset `s` (the law set for its closing speed) to its
    /// separation, located where the gap closes with the force gone, or to the window's end.
    /// The step keeps the force's linear hold within `tol` of the largest force so far,
    /// starting from 1e-4 of the contact time scale `t_c` \[s\].
    fn contact(
        &mut self,
        int: &mut Integrator<'_>,
        mut s: Point,
        t_c: f64,
        number: usize,
    ) -> Result<Pressed, ImpactError> {
        let t_on = s.t;
        let tol = self.tol;
        let mut levels = Levels {
            h_ref: t_c * 1e-4,
            levels: std::collections::HashMap::new(),
        };
        let mut level = 0_i32;
        let mut samples: Vec<(f64, f64)> = vec![(s.t, 0.0)];
        let mut peak = (0.0_f64, s.t);
        let mut f_ref = 0.0_f64;
        let mut acc = [0.0_f64; 4];
        // the powers at the step's start (the last step's end)
        let mut p_start = int.powers(&int.ports(&s));
        let mut peak_torque = 0.0_f64;
        let h_min = t_c * 1e-9;
        let mut window_closed = false;
        loop {
            self.check_stop()?;
            if s.t >= self.horizon {
                // the window closed with the contact on (the drive pressing the person): the
                // force there counts as well
                if s.f > peak.0 {
                    peak = (s.f, s.t);
                }
                window_closed = true;
                self.tracer.offer(s.t, true, || int.sample(&s));
                break;
            }
            if self.steps >= self.max_steps {
                let mut reason = format!(
                    "the step budget ({}) ran out {:.3e} s into contact {number}",
                    self.max_steps,
                    s.t - t_on
                );
                if number > 1 {
                    // a later contact that lasts: the drive pressing the person, the link
                    // ringing against them
                    reason.push_str(
                        ": the linear model resolves every period of the link's ringing in a \
                         long press; the exact link model (link_model = \"exact\") follows a \
                         press at the drive's pace",
                    );
                }
                return Err(ImpactError::NotFinished {
                    design: "driven CL",
                    reason,
                });
            }
            self.steps += 1;
            let sc = levels.get(int, level);
            let h = sc.h;
            let next = int.step(&s, &sc, false);
            // reject a step whose force bends far beyond the tolerance
            if samples.len() >= 2 && h > h_min {
                let (ta, fa) = samples[samples.len() - 2];
                let (tb, fb) = samples[samples.len() - 1];
                let (h0, h1) = (tb - ta, h);
                let f2 = 2.0 * ((next.f - fb) / h1 - (fb - fa) / h0) / (h0 + h1);
                if h1 * h1 * f2.abs() / 8.0 > 4.0 * tol * f_ref.max(next.f) {
                    level -= 4;
                    continue;
                }
            }
            let (finished, e, half) = if next.f == 0.0 && int.delta(&next).0 <= 0.0 {
                // separation within the step: shorten it to where the gap closes under f → 0
                let g = |hh: f64| {
                    let lin = int.linear(&s, &int.coefficients_for(hh));
                    let (u, _, _) = int.port_load(&s, &lin, 0.0);
                    int.gap(&lin, 0.0, u).0
                };
                let h_sep = illinois(g, 0.0, int.delta(&s).0, h, g(h), 1e-14 * h);
                (
                    true,
                    int.step_any(&s, h_sep, true),
                    std::rc::Rc::new(int.coefficients_for(0.5 * h_sep)),
                )
            } else {
                (false, next, levels.get(int, level - 4))
            };
            let mid = int.mid_ports(&s, &e, &half);
            let end = int.ports(&e);
            let (p0, pm, p1) = (p_start, int.powers(&mid), int.powers(&end));
            p_start = p1;
            let dt = e.t - s.t;
            for k in 0..4 {
                acc[k] += dt / 6.0 * (p0[k] + 4.0 * pm[k] + p1[k]);
            }
            if e.saturated && self.saturation_at.is_none() {
                self.saturation_at = Some(e.t);
            }
            peak_torque = peak_torque.max(int.torque(&end).abs());
            s = e;
            self.tracer.offer(s.t, finished, || int.sample(&s));
            samples.push((s.t, s.f));
            f_ref = f_ref.max(s.f);
            if samples.len() >= 3 {
                let m = samples.len();
                let (a, b, c) = (samples[m - 3], samples[m - 2], samples[m - 1]);
                if b.1 > a.1 && b.1 >= c.1 {
                    let v = vertex(a, b, c);
                    if v.1 > peak.0 {
                        peak = (v.1, v.0);
                    }
                }
                let (h0, h1) = (b.0 - a.0, c.0 - b.0);
                let f2 = 2.0 * ((c.1 - b.1) / h1 - (b.1 - a.1) / h0) / (h0 + h1);
                let ideal = if f2 == 0.0 {
                    2.0 * h1
                } else {
                    0.9 * (8.0 * tol * f_ref / f2.abs()).sqrt()
                };
                let target = ideal.clamp(0.5 * h1, 2.0 * h1).max(h_min);
                level = levels.level_for(target).min(level + 4);
            }
            if samples.len() > 8 {
                samples.drain(..samples.len() - 3);
            }
            if finished {
                break;
            }
        }
        Ok(Pressed {
            event: ContactEvent {
                onset_s: t_on,
                peak_force_n: peak.0,
                time_of_peak_s: peak.1,
                duration_s: s.t - t_on,
            },
            end: s,
            acc,
            peak_torque,
            window_closed,
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
