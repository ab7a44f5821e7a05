//! The driven compliant joint (a series elastic actuator) striking a person: the motor's rotor
//! (joint-side inertia J_m N²) turns the torsion spring k_θr = k_δ L², which turns the rigid link
//! (inertia (m_e + m_r/3) L² about the joint) into the head. In tip units (arc coordinate along
//! the tip's path, module docs of [`crate::strike`]) with r = L φ_m, w = L φ_l:
//!
//! M_R r̈ = F − c_R ṙ − k_δ (r − w)          (rotor; M_R = J_m N²/L², c_R = c_m N²/L²)
//! M ẅ   = k_δ (r − w) − f                   (link; M = m_e + m_r/3)
//! m_h ẍ_h = f − k_n (x_h − x_c) − c_n ẋ_h   (head; a wall: x_h ≡ x_c)
//! f = f(δ, δ̇), δ = w − x_h                 (Eq. 4 or a damped law of flexrig-contact)
//!
//! with the drive's force F = τ_j/L: under a controller F = sat(K_p (r_c − r) + K_d (ṙ_c − ṙ) +
//! K_i z)/L², ż = r_c − r (r_c = L φ_cmd); under an open-loop torque F = N τ_m(t)/L; along a
//! prescribed trajectory r ≡ L φ_cmd(t) and F = M_R r̈ + c_R ṙ + k_δ (r − w) is the torque it
//! takes. The motor's work ∫ F ṙ dt, the friction's c_R ṙ², the damping's and the contact's
//! impact work are integrated with the motion.
//!
//! Two phases, both by DOP853 (flexrig-lumped): the approach from t = 0 to the onset, located on
//! the dense output and the state there recomputed by one step of the method; then the contact
//! from the onset (positions re-measured from the contact point, so the indentation keeps full
//! precision after a long swing) to the separation. Peaks where ḟ changes sign, as in
//! [`crate::cj`].

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_contact::ContactLaw;
use flexrig_lumped::ode::dop853::{Dop853, Dop853Options, OdeSystem, find_root};

use crate::ImpactError;
use crate::drive::{DriveCommand, HeadSupport, Profile, TorqueProfile};
use crate::setup::{ContactEvent, RunEnd, hertz_time_integral};
use crate::strike::{DriveNote, DrivenOutcome, DrivenStrike, EnergyBalance, TraceSample, Tracer};

const DIM: usize = 11;
type Y = [f64; DIM];
const XH: usize = 0;
const VH: usize = 1;
const W: usize = 2;
const WD: usize = 3;
const R: usize = 4;
const RD: usize = 5;
const Z: usize = 6;
const WORK: usize = 7;
const FRICTION: usize = 8;
const DAMPING: usize = 9;
const IMPACT: usize = 10;

/// The drive in tip units.
enum Source<'a> {
    Prescribed(&'a Profile),
    Feedback {
        profile: &'a Profile,
        kp: f64,
        kd: f64,
        ki: f64,
        limit: f64,
    },
    OpenLoop {
        torque: &'a TorqueProfile,
        /// N/L: motor-shaft torque to tip force.
        scale: f64,
    },
}

struct DrivenCj<'a> {
    l: f64,
    m_tip: f64,
    k: f64,
    m_rotor: f64,
    c_rotor: f64,
    /// 1/m_h (0 against a wall).
    inv_m_h: f64,
    m_h: f64,
    k_n: f64,
    c_n: f64,
    x_rest: f64,
    source: Source<'a>,
    /// Positions are measured from this point of the path \[m\].
    shift: f64,
    law: Option<Box<dyn ContactLaw>>,
    /// The dome's centre offset d_c = R − s behind the link's axis \[m\] for the exact
    /// contact geometry, or `None`: the arc coordinate (δ = w − x_h).
    dome_offset: Option<f64>,
    /// A time inside the current integration segment: the drive's command is evaluated on its
    /// branch there (a pulse's end, a trapezoid's corner lie on segment ends).
    branch: Cell<f64>,
}

impl DrivenCj<'_> {
    /// Commanded (r_c, ṙ_c, r̈_c) in tip units.
    fn command(&self, t: f64) -> Option<(f64, f64, f64)> {
        let profile = match &self.source {
            Source::Prescribed(p) => p,
            Source::Feedback { profile, .. } => profile,
            Source::OpenLoop { .. } => return None,
        };
        let (phi, omega, alpha) = profile.at_in(t, self.branch.get());
        Some((self.l * phi - self.shift, self.l * omega, self.l * alpha))
    }

    /// The rotor's (r, ṙ).
    fn rotor(&self, t: f64, y: &Y) -> (f64, f64) {
        match &self.source {
            Source::Prescribed(_) => {
                let (r, v, _) = self.command(t).expect("a profile");
                (r, v)
            }
            _ => (y[R], y[RD]),
        }
    }

    /// The drive's force on the rotor F = τ_j/L \[N\] and whether it is at its limit.
    fn drive_force(&self, t: f64, y: &Y) -> (f64, bool) {
        match &self.source {
            Source::Prescribed(_) => {
                let (r, v, a) = self.command(t).expect("a profile");
                (
                    self.m_rotor * a + self.c_rotor * v + self.k * (r - y[W]),
                    false,
                )
            }
            Source::Feedback {
                kp, kd, ki, limit, ..
            } => {
                let (rc, vc, _) = self.command(t).expect("a profile");
                let raw = kp * (rc - y[R]) + kd * (vc - y[RD]) + ki * y[Z];
                if raw.abs() > *limit {
                    (limit * raw.signum(), true)
                } else {
                    (raw, false)
                }
            }
            Source::OpenLoop { torque, scale } => {
                (scale * torque.at_in(t, self.branch.get()), false)
            }
        }
    }

    /// |raw torque| − limit of a limited controller (positive: saturated), `None` otherwise.
    fn saturation_margin(&self, t: f64, y: &Y) -> Option<f64> {
        let Source::Feedback {
            kp, kd, ki, limit, ..
        } = &self.source
        else {
            return None;
        };
        if !limit.is_finite() {
            return None;
        }
        let (rc, vc, _) = self.command(t).expect("a profile");
        Some((kp * (rc - y[R]) + kd * (vc - y[RD]) + ki * y[Z]).abs() - limit)
    }

    /// The time in (t0, t1) at which the controller enters or leaves its limit, if it does.
    fn saturation_switch(
        &self,
        ode: &mut Dop853<DIM>,
        (t0, t1): (f64, f64),
        (ya, yb): (&Y, &Y),
    ) -> Option<f64> {
        let (ga, gb) = (
            self.saturation_margin(t0, ya)?,
            self.saturation_margin(t1, yb)?,
        );
        if (ga > 0.0) == (gb > 0.0) || ga == 0.0 {
            return None;
        }
        let dense = ode.dense_output(self);
        let g = |t: f64| self.saturation_margin(t, &dense.eval(t)).unwrap_or(0.0);
        let t = find_root(g, t0, ga, t1, gb, 4.0 * f64::EPSILON * t1);
        (t > t0 + 8.0 * f64::EPSILON * t1 && t < t1).then_some(t)
    }

    /// The indentation δ \[m\], its rate δ̇ [m/s], the lever λ = ∂δ/∂w and its rate λ̇ \[1/s\].
    /// Exact geometry (module docs of [`crate::exact_link`]): with u = φ_l − φ_c =
    /// (w − x_rest)/L the link's turn past the placement and X = x_h − x_rest the head's
    /// displacement along the face normal, δ = L sin u + d_c (1 − cos u) − X,
    /// λ = cos u + (d_c/L) sin u; the arc coordinate: δ = w − x_h, λ = 1.
    fn contact_kinematics(&self, y: &Y) -> (f64, f64, f64, f64) {
        match self.dome_offset {
            None => (y[W] - y[XH], y[WD] - y[VH], 1.0, 0.0),
            Some(d_c) => {
                let u = (y[W] - self.x_rest) / self.l;
                let (s, c) = u.sin_cos();
                let lever = c + d_c / self.l * s;
                let lever_rate = (-s + d_c / self.l * c) * y[WD] / self.l;
                let delta = self.l * s + d_c * (1.0 - c) - (y[XH] - self.x_rest);
                (delta, lever * y[WD] - y[VH], lever, lever_rate)
            }
        }
    }

    /// The indentation δ \[m\] (negative: the gap).
    fn gap(&self, y: &Y) -> f64 {
        self.contact_kinematics(y).0
    }

    /// The bodies have parted for good: with the exact geometry, a free head (no neck, no wall)
    /// moving away (Ẋ ≥ 0, nothing acts on it any more) beyond the farthest the dome can ever
    /// reach along the face normal, max over u of L sin u + d_c (1 − cos u) = √(L² + d_c²) + d_c
    /// (the hub does not move; the link is rigid). Along the tip's path (the linear option) the
    /// path has no end: `false`, the run goes on to the window.
    fn parted_for_good(&self, y: &Y) -> bool {
        let Some(d_c) = self.dome_offset else {
            return false;
        };
        if self.inv_m_h == 0.0 || self.k_n != 0.0 || self.c_n != 0.0 {
            return false;
        }
        let reach = self.l.hypot(d_c) + d_c;
        y[VH] >= 0.0 && y[XH] - self.x_rest > reach
    }

    fn force(&self, y: &Y) -> f64 {
        let (delta, rate, ..) = self.contact_kinematics(y);
        self.law
            .as_deref()
            .map_or(0.0, |law| law.force(delta, rate))
    }

    /// ḟ along the motion.
    fn force_rate(&self, t: f64, y: &Y) -> f64 {
        let Some(law) = self.law.as_deref() else {
            return 0.0;
        };
        let (delta, rate, lever, lever_rate) = self.contact_kinematics(y);
        let dy = self.rhs(t, y);
        let accel = lever * dy[WD] + lever_rate * y[WD] - dy[VH];
        law.stiffness(delta, rate) * rate + law.damping(delta, rate) * accel
    }

    fn sample(&self, t: f64, y: &Y) -> TraceSample {
        let (r, rd) = self.rotor(t, y);
        TraceSample {
            t,
            hub_angle_rad: (r + self.shift) / self.l,
            hub_speed_rad_s: rd / self.l,
            tip_deflection_m: y[W] - r,
            indentation_m: self.gap(y),
            force_n: self.force(y),
            joint_torque_nm: self.drive_force(t, y).0 * self.l,
            head_position_m: y[XH] + self.shift,
            // k_θr (φ_m − φ_l) = k_δ L² (r − w)/L
            moment_nm: self.k * (r - y[W]) * self.l,
            head_acceleration_mps2: self.inv_m_h
                * (self.force(y) - self.k_n * (y[XH] - self.x_rest) - self.c_n * y[VH]),
        }
    }

    fn mechanical_energy(&self, t: f64, y: &Y) -> f64 {
        let (r, rd) = self.rotor(t, y);
        let spring = r - y[W];
        let neck = y[XH] - self.x_rest;
        let contact = self
            .law
            .as_deref()
            .map_or(0.0, |law| law.elastic_energy(self.gap(y).max(0.0)));
        let head = if self.inv_m_h > 0.0 {
            0.5 * self.m_h * y[VH] * y[VH]
        } else {
            0.0
        };
        head + 0.5 * self.m_tip * y[WD] * y[WD]
            + 0.5 * self.m_rotor * rd * rd
            + 0.5 * self.k * spring * spring
            + 0.5 * self.k_n * neck * neck
            + contact
    }
}

impl OdeSystem<DIM> for DrivenCj<'_> {
    fn rhs(&self, t: f64, y: &Y) -> Y {
        let f = self.force(y);
        let (r, rd) = self.rotor(t, y);
        let spring = self.k * (r - y[W]);
        let (drive, _) = self.drive_force(t, y);
        let head_acc = self.inv_m_h * (f - self.k_n * (y[XH] - self.x_rest) - self.c_n * y[VH]);
        let (rotor_acc, z_rate) = match &self.source {
            Source::Prescribed(_) => (0.0, 0.0),
            Source::Feedback { .. } => (
                (drive - self.c_rotor * rd - spring) / self.m_rotor,
                self.command(t).expect("a profile").0 - r,
            ),
            Source::OpenLoop { .. } => ((drive - self.c_rotor * rd - spring) / self.m_rotor, 0.0),
        };
        let (delta, rate, lever, _) = self.contact_kinematics(y);
        let damping_power = match self.law.as_deref() {
            Some(law) => (f - law.elastic().force(delta, 0.0)) * rate,
            None => 0.0,
        };
        let mut dy = [0.0; DIM];
        dy[XH] = y[VH];
        dy[VH] = head_acc;
        dy[W] = y[WD];
        dy[WD] = (spring - f * lever) / self.m_tip;
        if !matches!(self.source, Source::Prescribed(_)) {
            dy[R] = y[RD];
            dy[RD] = rotor_acc;
        }
        dy[Z] = z_rate;
        dy[WORK] = drive * rd;
        dy[FRICTION] = self.c_rotor * rd * rd;
        dy[DAMPING] = self.c_n * y[VH] * y[VH] + damping_power;
        dy[IMPACT] = f * rate.max(0.0);
        dy
    }
}

/// Integration settings of the driven CJ.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CjSettings {
    /// DOP853 relative tolerance, in [1e-14, 1e-3].
    pub rtol: f64,
    /// Most DOP853 steps per phase.
    pub max_steps: usize,
    /// `Some(dt)`: sample the motion at the integrator's steps, at most every dt \[s\].
    pub trace_every: Option<f64>,
    /// Follow every contact after the first, the drive acting, until the bodies part for good
    /// or the strike's window (`horizon_s` from the drive's start) closes; `false`: the run
    /// ends at the first separation.
    pub every_contact: bool,
}

impl CjSettings {
    /// rtol 1e-10, 10⁷ steps per phase.
    pub const DEFAULT: CjSettings = CjSettings {
        rtol: 1e-10,
        max_steps: 10_000_000,
        trace_every: None,
        every_contact: false,
    };
}

/// Runs the driven CJ strike from the drive's start (t = 0) to the separation of the first
/// contact.
pub fn run_driven_cj(
    strike: &DrivenStrike,
    settings: &CjSettings,
) -> Result<DrivenOutcome, ImpactError> {
    run_cj(strike, settings, None, &AtomicBool::new(false))
}

/// [`run_driven_cj`], stopping with [`ImpactError::Interrupted`] within a step once `stop` is
/// set.
pub fn run_driven_cj_until(
    strike: &DrivenStrike,
    settings: &CjSettings,
    stop: &AtomicBool,
) -> Result<DrivenOutcome, ImpactError> {
    run_cj(strike, settings, None, stop)
}

/// The driven CJ with the exact contact geometry of `dome` (the default model,
/// [`crate::DrivenStrike::run_cj`]): the rigid link's rotation was always exact; here the dome
/// is a sphere rigid with the link (its centre d_c = R − s behind the axis) against the face's
/// plane, so the indentation is δ = L sin u + d_c (1 − cos u) − X (u the link's turn past the
/// placement, X the head's displacement along the face normal) and the force acts on the link
/// through the lever λ = ∂δ/∂(L φ_l) = cos u + (d_c/L) sin u (its moment about the joint
/// included), where [`run_driven_cj`] measures δ along the tip's path (u ≪ 1).
pub fn run_exact_cj(
    strike: &DrivenStrike,
    settings: &CjSettings,
    dome: &crate::drive::Dome,
) -> Result<DrivenOutcome, ImpactError> {
    run_exact_cj_until(strike, settings, dome, &AtomicBool::new(false))
}

/// [`run_exact_cj`], stopping with [`ImpactError::Interrupted`] within a step once `stop` is
/// set.
pub fn run_exact_cj_until(
    strike: &DrivenStrike,
    settings: &CjSettings,
    dome: &crate::drive::Dome,
    stop: &AtomicBool,
) -> Result<DrivenOutcome, ImpactError> {
    dome.validate()?;
    run_cj(strike, settings, Some(dome.centre_offset()), stop)
}

fn run_cj(
    strike: &DrivenStrike,
    settings: &CjSettings,
    dome_offset: Option<f64>,
    stop: &AtomicBool,
) -> Result<DrivenOutcome, ImpactError> {
    let mut tracer = Tracer::new(settings.trace_every);
    run_cj_traced(strike, settings, dome_offset, stop, &mut tracer)
        .map_err(|e| ImpactError::with_trace(e, std::mem::take(&mut tracer.samples)))
}

/// [`run_cj`], its samples going to `tracer` (kept there when the run fails midway).
fn run_cj_traced(
    strike: &DrivenStrike,
    settings: &CjSettings,
    dome_offset: Option<f64>,
    stop: &AtomicBool,
    tracer: &mut Tracer,
) -> Result<DrivenOutcome, ImpactError> {
    strike.validate()?;
    if !(settings.rtol.is_finite() && (1e-14..=1e-3).contains(&settings.rtol)) {
        return Err(ImpactError::invalid(
            "rtol",
            settings.rtol,
            "must lie in [1e-14, 1e-3]",
        ));
    }
    if let Some(dt) = settings.trace_every
        && !(dt.is_finite() && dt > 0.0)
    {
        return Err(ImpactError::invalid("trace_every", dt, "a time > 0 s"));
    }
    let link = strike.link;
    let l = link.length;
    let motor = strike.drive.motor();
    let n_gear = motor.gear_ratio;
    let source = match strike.drive.command() {
        DriveCommand::Trajectory { profile } => Source::Prescribed(profile),
        DriveCommand::Controller { profile, gains, .. } => Source::Feedback {
            profile,
            kp: gains.kp / (l * l),
            kd: gains.kd / (l * l),
            ki: gains.ki / (l * l),
            limit: strike.drive.joint_torque_limit() / l,
        },
        DriveCommand::OpenLoop { torque, .. } => Source::OpenLoop {
            torque,
            scale: n_gear / l,
        },
    };
    let (inv_m_h, k_n, c_n) = match strike.person.support {
        HeadSupport::Free => (1.0 / strike.person.m_h, 0.0, 0.0),
        HeadSupport::Neck { stiffness, damping } => (1.0 / strike.person.m_h, stiffness, damping),
        HeadSupport::Wall => (0.0, 0.0, 0.0),
    };
    let x_contact = l * strike.placement.angle(&strike.drive)?;
    let mut system = DrivenCj {
        l,
        m_tip: link.cj_tip_mass(),
        k: link.k_delta,
        m_rotor: motor.reflected_inertia() / (l * l),
        c_rotor: motor.reflected_friction() / (l * l),
        inv_m_h,
        m_h: strike.person.m_h,
        k_n,
        c_n,
        x_rest: x_contact,
        source,
        shift: 0.0,
        law: None,
        dome_offset,
        branch: Cell::new(0.0),
    };
    // ---- t = 0 ----
    let (z0, lag0, speed0) = strike.drive.steady_preload()?;
    let r0 = -l * lag0;
    let mut y0 = [0.0; DIM];
    y0[XH] = x_contact;
    y0[VH] = -strike.person.speed;
    y0[W] = r0;
    y0[WD] = l * speed0;
    y0[R] = r0;
    y0[RD] = l * speed0;
    y0[Z] = l * z0;
    // scales: the link's own period for the approach
    let period = 2.0 * std::f64::consts::PI * (system.m_tip / system.k).sqrt();
    let opts = |rtol: f64, x: f64, v: f64, t: f64, e: f64, first: Option<f64>, max: f64| {
        let mut atol = [rtol * x; DIM];
        for i in [VH, WD, RD] {
            atol[i] = rtol * v;
        }
        atol[Z] = rtol * x * t;
        for i in [WORK, FRICTION, DAMPING, IMPACT] {
            atol[i] = rtol * e;
        }
        Dop853Options {
            rtol,
            atol,
            first_step: first,
            max_step: max,
            max_steps: settings.max_steps,
        }
    };
    let v_ref = strike
        .drive
        .profile()
        .map_or(l * speed0.abs(), |p| l * p.final_speed().abs())
        .max(strike.person.speed)
        .max(1e-6);
    let e_ref = 0.5 * system.m_tip * v_ref * v_ref;
    let free_options = opts(
        settings.rtol,
        l,
        v_ref,
        period,
        e_ref,
        None,
        (strike.horizon_s / 50.0).min(period / 4.0),
    );
    let mut run = Run {
        breaks: {
            let mut b = strike.drive.breakpoints();
            b.push(strike.horizon_s);
            b
        },
        horizon: strike.horizon_s,
        tracer,
        saturation_at: None,
        work: 0,
        stop,
        last_free: y0,
    };
    run.tracer.offer(0.0, true, || system.sample(0.0, &y0));
    let (t_on, y_on) = if system.gap(&y0) == 0.0 && y0[WD] - y0[VH] > 0.0 {
        (0.0, y0)
    } else if system.gap(&y0) > 0.0 {
        return Err(ImpactError::invalid(
            "placement",
            format!("{} rad", x_contact / l),
            "a person the link has not yet reached at t = 0",
        ));
    } else {
        match run.free_flight(&system, 0.0, y0, free_options, false)? {
            Flight::Onset(t, y) => (t, y),
            Flight::Parted(..) | Flight::Window(..) => {
                let yb = run.last_free;
                let speed = yb[WD] / l;
                let mut reason = format!(
                    "the link did not reach the person within horizon_s = {} s (gap {:.6e} m, \
                     joint speed {speed:.6e} rad/s at the end)",
                    strike.horizon_s,
                    -system.gap(&yb),
                );
                if let Some(ts) = run.saturation_at {
                    reason.push_str(&format!(
                        "; the torque limit was reached at {ts:.6e} s and cannot hold the speed"
                    ));
                }
                return Err(ImpactError::NotFinished {
                    design: "driven CJ",
                    reason,
                });
            }
        }
    };
    // ---- the first contact, positions from the contact point ----
    let approach = system.contact_kinematics(&y_on).1;
    if !(approach > 0.0) {
        return Err(ImpactError::NotFinished {
            design: "driven CJ",
            reason: format!("the link touched the person without approaching (δ̇ = {approach})"),
        });
    }
    let shift = y_on[XH];
    system.shift = shift;
    system.x_rest -= shift;
    let mut y = y_on;
    y[XH] = 0.0;
    y[W] -= shift;
    if !matches!(system.source, Source::Prescribed(_)) {
        y[R] -= shift;
    }
    for i in [WORK, FRICTION, DAMPING, IMPACT] {
        y[i] = 0.0;
    }
    let (torque_on, _) = system.drive_force(t_on, &y);
    let (r_on, rd_on) = system.rotor(t_on, &y);
    let deflection = y[W] - r_on;
    let first = run.contact(&mut system, strike, t_on, y, (settings.rtol, &opts))?;
    let e0 = first.energy_at_onset;
    let y_sep = first.y_end;
    let e1 = system.mechanical_energy(first.t_end, &y_sep);
    let dissipated = y_sep[FRICTION] + y_sep[DAMPING];
    let energy = EnergyBalance {
        impact_energy_j: y_sep[IMPACT],
        motor_work_j: y_sep[WORK],
        dissipated_j: dissipated,
        mechanical_change_j: e1 - e0,
        residual_j: y_sep[WORK] - dissipated - (e1 - e0),
    };
    let separation_rate = system.contact_kinematics(&y_sep).1;
    let mut peak_torque = first.peak_torque.max(torque_on.abs() * l);
    let mut contacts = vec![first.event];
    let mut pressing_at_window = first.window_closed;
    // ---- every later contact, until the bodies part for good or the window closes ----
    let ended = if first.window_closed {
        RunEnd::Window(strike.horizon_s)
    } else if !settings.every_contact {
        RunEnd::FirstSeparation
    } else {
        let (mut t, mut y) = (first.t_end, y_sep);
        loop {
            match run.free_flight(&system, t, y, free_options, true)? {
                Flight::Parted(tp) => break RunEnd::PartedForGood(tp),
                Flight::Window(tw) => break RunEnd::Window(tw),
                Flight::Onset(t_next, y_next) => {
                    let c =
                        run.contact(&mut system, strike, t_next, y_next, (settings.rtol, &opts))?;
                    peak_torque = peak_torque.max(c.peak_torque);
                    contacts.push(c.event);
                    if c.window_closed {
                        pressing_at_window = true;
                        break RunEnd::Window(strike.horizon_s);
                    }
                    (t, y) = (c.t_end, c.y_end);
                }
            }
        }
    };
    let mut notes = Vec::new();
    let commanded = system.command(t_on).map(|c| c.1);
    if let Some(ts) = run.saturation_at {
        notes.push(DriveNote::TorqueLimitReached { first_s: ts });
    }
    if let Some(c) = commanded {
        notes.extend(DriveNote::arrival(c, y_on[WD]));
    }
    if pressing_at_window {
        notes.push(DriveNote::StillPressing {
            window_s: strike.horizon_s,
        });
    }
    // the tip's vibration speed relative to the hub's line: L (φ̇_l − φ̇_m)
    notes.extend(DriveNote::vibration(y_on[WD] - rd_on, approach));
    let outcome = DrivenOutcome {
        contact: contacts[0],
        approach_speed_mps: approach,
        commanded_tip_speed_mps: commanded,
        pre_impact_deflection_m: deflection,
        joint_torque_at_onset_nm: torque_on * l,
        peak_joint_torque_nm: peak_torque,
        energy,
        separation_rate_mps: separation_rate,
        notes,
        work: run.work,
        trace: std::mem::take(&mut run.tracer.samples),
        contacts,
        ended,
    };
    finite(outcome)
}

/// How a free flight of the driven CJ ended.
enum Flight {
    /// The next contact's onset (time, state there).
    Onset(f64, Y),
    /// The bodies parted for good at this time \[s\] ([`DrivenCj::parted_for_good`]).
    Parted(f64),
    /// The window (the strike's `horizon_s`) closed at this time \[s\].
    Window(f64),
}

/// One contact of the driven CJ, from its onset to its separation (or the window's end).
struct ContactRun {
    event: ContactEvent,
    t_end: f64,
    y_end: Y,
    /// The mechanical energy at the onset \[J\].
    energy_at_onset: f64,
    /// Largest |τ_j| in the contact \[N·m\].
    peak_torque: f64,
    /// The contact was still on when the window closed.
    window_closed: bool,
}

/// What the phases of one driven CJ run share: the drive's corners, the window, the trace,
/// the first saturation, the work done, the stop flag.
struct Run<'s, 't> {
    breaks: Vec<f64>,
    horizon: f64,
    tracer: &'t mut Tracer,
    saturation_at: Option<f64>,
    work: usize,
    stop: &'s AtomicBool,
    /// The state where the last free flight that found no onset ended.
    last_free: Y,
}

impl Run<'_, '_> {
    /// The drive's segment around `t`: sets the branch on which the command is evaluated (the
    /// segment's middle) and returns the segment's end (a corner of the command or the window).
    fn segment(&self, system: &DrivenCj<'_>, t: f64) -> f64 {
        let end = self
            .breaks
            .iter()
            .copied()
            .filter(|b| *b > t)
            .fold(self.horizon, f64::min);
        let start = self
            .breaks
            .iter()
            .copied()
            .filter(|b| *b <= t)
            .fold(0.0, f64::max);
        system.branch.set(0.5 * (start + end));
        end
    }

    fn check_stop(&self) -> Result<(), ImpactError> {
        if self.stop.load(Ordering::Relaxed) {
            return Err(ImpactError::Interrupted);
        }
        Ok(())
    }

    /// Integrates the motion without contact from (`t`, `y`) to the next onset (the gap closing,
    /// located on the dense output and the state there recomputed by one step of the method),
    /// the bodies parting for good (`later`: after a contact), or the window's end.
    fn free_flight(
        &mut self,
        system: &DrivenCj<'_>,
        t: f64,
        y: Y,
        options: Dop853Options<DIM>,
        later: bool,
    ) -> Result<Flight, ImpactError> {
        let failed = |e| ImpactError::NotFinished {
            design: "driven CJ",
            reason: if later {
                format!("the motion between contacts failed: {e}")
            } else {
                format!("the approach failed: {e}")
            },
        };
        let mut ode = Dop853::new(system, t, y, options);
        loop {
            self.check_stop()?;
            let end = self.segment(system, ode.t());
            ode.step_until(system, end).map_err(failed)?;
            let (t0, t1) = (ode.t_old(), ode.t());
            let (ya, yb) = (*ode.y_old(), *ode.y());
            // the limit's corner: restart the integrator there (it keeps its order)
            if let Some(t_sw) = system.saturation_switch(&mut ode, (t0, t1), (&ya, &yb)) {
                let y_sw = ode.restep_to(system, t_sw);
                if system.gap(&y_sw) < 0.0 {
                    self.work += ode.stats().rhs_evals;
                    if self.saturation_at.is_none()
                        && system.saturation_margin(t1, &yb).unwrap_or(0.0) > 0.0
                    {
                        self.saturation_at = Some(t_sw);
                    }
                    ode = Dop853::new(system, t_sw, y_sw, options);
                    continue;
                }
            }
            if system.gap(&yb) < 0.0 {
                self.tracer.offer(t1, false, || system.sample(t1, &yb));
            }
            if self.saturation_at.is_none() && system.drive_force(t1, &yb).1 {
                self.saturation_at = Some(t1);
            }
            if system.gap(&ya) < 0.0 && system.gap(&yb) >= 0.0 {
                let dense = ode.dense_output(system);
                let t = find_root(
                    |t| system.gap(&dense.eval(t)),
                    t0,
                    system.gap(&ya),
                    t1,
                    system.gap(&yb),
                    4.0 * f64::EPSILON * t1.max(1e-300),
                );
                let y = if t < t1 { ode.restep_to(system, t) } else { yb };
                self.work += ode.stats().rhs_evals;
                return Ok(Flight::Onset(t, y));
            }
            if later && system.parted_for_good(&yb) {
                self.work += ode.stats().rhs_evals;
                self.tracer.offer(t1, true, || system.sample(t1, &yb));
                return Ok(Flight::Parted(t1));
            }
            if t1 >= self.horizon {
                self.work += ode.stats().rhs_evals;
                self.last_free = yb;
                if later {
                    self.tracer.offer(t1, true, || system.sample(t1, &yb));
                }
                return Ok(Flight::Window(t1));
            }
        }
    }

    /// One contact from its onset (`t_on`, `y`) to the separation, or to the window's end if it
    /// lasts that long (the drive pressing the person): the contact law made for this onset's
    /// approach speed, the peaks where ḟ changes sign.
    #[allow(clippy::type_complexity)]
    fn contact(
        &mut self,
        system: &mut DrivenCj<'_>,
        strike: &DrivenStrike,
        t_on: f64,
        y: Y,
        (rtol, opts): (
            f64,
            &dyn Fn(f64, f64, f64, f64, f64, Option<f64>, f64) -> Dop853Options<DIM>,
        ),
    ) -> Result<ContactRun, ImpactError> {
        let approach = system.contact_kinematics(&y).1;
        if !(approach > 0.0) {
            return Err(ImpactError::NotFinished {
                design: "driven CJ",
                reason: format!("the link touched the person without approaching (δ̇ = {approach})"),
            });
        }
        system.law = Some(strike.person.damping.law(strike.person.contact, approach)?);
        let m_struck = if system.inv_m_h > 0.0 {
            system.m_tip * strike.person.m_h / (system.m_tip + strike.person.m_h)
        } else {
            system.m_tip
        };
        let (kc, nc) = (strike.person.contact.k(), strike.person.contact.n());
        let d_max =
            ((nc + 1.0) * m_struck * approach * approach / (2.0 * kc)).powf(1.0 / (nc + 1.0));
        let t_c = 2.0 * d_max / approach * hertz_time_integral(nc);
        let x_c = approach * t_c;
        let e0 = system.mechanical_energy(t_on, &y);
        let options = opts(
            rtol,
            x_c,
            approach,
            t_c,
            0.5 * m_struck * approach * approach,
            Some(t_c * 1e-3),
            t_c * 0.5,
        );
        self.tracer.offer(t_on, true, || system.sample(t_on, &y));
        let system = &*system;
        let mut ode = Dop853::new(system, t_on, y, options);
        let mut peak = (0.0_f64, t_on);
        let mut peak_torque = 0.0_f64;
        let force_rate = |t: f64, y: &Y| system.force_rate(t, y);
        let failed = |e| ImpactError::NotFinished {
            design: "driven CJ",
            reason: format!("the contact failed: {e}"),
        };
        loop {
            self.check_stop()?;
            let end = self.segment(system, ode.t());
            ode.step_until(system, end).map_err(failed)?;
            let (t0, t1) = (ode.t_old(), ode.t());
            let (ya, yb) = (*ode.y_old(), *ode.y());
            if let Some(t_sw) = system.saturation_switch(&mut ode, (t0, t1), (&ya, &yb)) {
                let y_sw = ode.restep_to(system, t_sw);
                if system.gap(&y_sw) > 0.0 && force_rate(t0, &ya) * force_rate(t_sw, &y_sw) > 0.0 {
                    self.work += ode.stats().rhs_evals;
                    if self.saturation_at.is_none()
                        && system.saturation_margin(t1, &yb).unwrap_or(0.0) > 0.0
                    {
                        self.saturation_at = Some(t_sw);
                    }
                    ode = Dop853::new(system, t_sw, y_sw, options);
                    continue;
                }
            }
            let (fd, sat) = system.drive_force(t1, &yb);
            peak_torque = peak_torque.max(fd.abs() * system.l);
            // a step longer than the trace's interval: the samples between its ends from the
            // method's 7th-order interpolant (the contact's force and the head's acceleration
            // at the trace's rate, for the severity; the integration itself is unchanged)
            if let Some(mut due) = self.tracer.next_due()
                && due < t1
            {
                let dense = ode.dense_output(system);
                while due < t1 {
                    let yd = dense.eval(due);
                    if system.gap(&yd) <= 0.0 {
                        break;
                    }
                    self.tracer.offer(due, true, || system.sample(due, &yd));
                    due = match self.tracer.next_due() {
                        Some(next) if next > due => next,
                        _ => break,
                    };
                }
            }
            if system.gap(&yb) > 0.0 {
                self.tracer.offer(t1, false, || system.sample(t1, &yb));
            }
            if sat && self.saturation_at.is_none() {
                self.saturation_at = Some(t1);
            }
            if force_rate(t0, &ya) > 0.0 && force_rate(t1, &yb) <= 0.0 {
                let dense = ode.dense_output(system);
                let t = find_root(
                    |t| force_rate(t, &dense.eval(t)),
                    t0,
                    force_rate(t0, &ya),
                    t1,
                    force_rate(t1, &yb),
                    4.0 * f64::EPSILON * t1,
                );
                let f = system.force(&ode.restep_to(system, t));
                if f > peak.0 {
                    peak = (f, t);
                }
            }
            let separated = system.gap(&yb) <= 0.0 && t1 > t_on;
            if !separated && t1 >= self.horizon {
                // the window closed with the contact on (the drive pressing the person): the
                // force there counts as well
                let f = system.force(&yb);
                if f > peak.0 {
                    peak = (f, t1);
                }
                self.work += ode.stats().rhs_evals;
                self.tracer.offer(t1, true, || system.sample(t1, &yb));
                return Ok(ContactRun {
                    event: ContactEvent {
                        onset_s: t_on,
                        peak_force_n: peak.0,
                        time_of_peak_s: peak.1,
                        duration_s: t1 - t_on,
                    },
                    t_end: t1,
                    y_end: yb,
                    energy_at_onset: e0,
                    peak_torque,
                    window_closed: true,
                });
            }
            if separated {
                let dense = ode.dense_output(system);
                let t_sep = find_root(
                    |t| system.gap(&dense.eval(t)),
                    t0,
                    system.gap(&ya),
                    t1,
                    system.gap(&yb),
                    4.0 * f64::EPSILON * t1,
                );
                let y_sep = if t_sep < t1 {
                    ode.restep_to(system, t_sep)
                } else {
                    yb
                };
                self.work += ode.stats().rhs_evals;
                self.tracer
                    .offer(t_sep, true, || system.sample(t_sep, &y_sep));
                return Ok(ContactRun {
                    event: ContactEvent {
                        onset_s: t_on,
                        peak_force_n: peak.0,
                        time_of_peak_s: peak.1,
                        duration_s: t_sep - t_on,
                    },
                    t_end: t_sep,
                    y_end: y_sep,
                    energy_at_onset: e0,
                    peak_torque,
                    window_closed: false,
                });
            }
        }
    }
}

/// The outcome, or an error if anything in it is not finite.
pub(crate) fn finite(o: DrivenOutcome) -> Result<DrivenOutcome, ImpactError> {
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
            design: "driven strike",
            reason: "the integration lost finiteness".into(),
        })
    }
}
