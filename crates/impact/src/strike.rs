//! The driven strike: a robot link moved by its [`Drive`] swings into a person at rest (the
//! paper's §IV question, Fig. 5a), and its result.
//!
//! **The default model** ([`DrivenStrike::run_cl`], [`DrivenStrike::run_cj`]) is geometrically
//! exact (crate::exact_link): the CL a corotational beam clamped to the driven hub (large
//! rotation, centrifugal stiffening, large deflection), the CJ a rigid link on its torsion
//! spring, both carrying the dome — a sphere rigid with the tip section, its centre off the
//! link's axis — against the plane of the person's face, so the contact's point, direction and
//! moment on the tip section follow from the geometry. Checked against an independent bar-chain
//! elastica (scripts/reference_driven_elastica.py, crates/impact/tests/exact_link.rs).
//!
//! **The linear option** (crate::driven_cl, crate::driven_cj::run_driven_cj) measures
//! everything along the tip's path (arc coordinate s = L φ), as in the free-mass impact
//! ([`crate::FreeMassImpact`]): the skin's surface sits at s = L φ_c (the [`Placement`]), the head
//! moves along the path's tangent there, and the indentation is δ = s_tip − s_head; the CL link
//! is linear (no centrifugal stiffening). It is exact for a link that turns little during the
//! contact and arrives unbent; on the test bed's link it is off by 1e-3 (steady approach) to
//! 2.5e-2 (a 0.5 s ramp that bends the link by a third of its length) in the peak force
//! (docs/driven.md).

use serde::{Deserialize, Serialize};

use crate::ImpactError;
use crate::drive::{Drive, Person, Placement, positive};

use crate::setup::{ContactEvent, LinkParams};

/// A driven robot link striking a person.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DrivenStrike {
    /// The link (the same m_r, L, k_δ, m_e for the CJ and the CL design).
    pub link: LinkParams,
    /// The joint's drive.
    pub drive: Drive,
    /// The person.
    pub person: Person,
    /// Where the person stands.
    pub placement: Placement,
    /// Longest time to wait for the link to arrive \[s\].
    pub horizon_s: f64,
}

impl DrivenStrike {
    /// Checks every field; the error names it.
    pub fn validate(&self) -> Result<(), ImpactError> {
        self.link.validate()?;
        self.person.validate()?;
        positive("horizon_s", self.horizon_s, 1e6, "s")?;
        let angle = self.placement.angle(&self.drive)?;
        if let Some(profile) = self.drive.profile()
            && profile.final_speed() < 0.0
        {
            // the models put the person on the positive side of the link
            return Err(ImpactError::invalid(
                "drive.command.profile.speed",
                profile.final_speed(),
                "a joint speed ≥ 0 rad/s (the person stands on the positive side of the link: \
                 for the other direction mirror the scene, the numbers are the same)",
            ));
        }
        if let (Some(profile), Placement::AfterRamp { settle }) =
            (self.drive.profile(), self.placement)
        {
            // the person stands where the command is `settle` after the ramp: that moment must
            // come within the horizon (the error names the horizon, the one field it depends
            // on that is not the placement itself)
            let at = profile.ramp_end() + settle;
            if !(at <= self.horizon_s) {
                return Err(ImpactError::invalid(
                    "horizon_s",
                    self.horizon_s,
                    format!(
                        "at least drive.command.profile.ramp_time + placement.settle = {} s (the \
                         person stands where the commanded motion is placement.settle after the \
                         ramp)",
                        flexrig_contact::validate::display(at)
                    ),
                ));
            }
        }
        if let Some(profile) = self.drive.profile() {
            // the commanded motion must pass the person within the horizon
            let reach = profile.at(self.horizon_s).0;
            let start = profile.at(0.0).0;
            let passes = if angle >= start {
                reach >= angle
            } else {
                reach <= angle
            };
            if !passes {
                return Err(ImpactError::invalid(
                    "placement",
                    format!("{} rad", flexrig_contact::validate::display(angle)),
                    format!(
                        "an angle the commanded trajectory reaches within horizon_s = {} s \
                         (it reaches {} rad)",
                        flexrig_contact::validate::display(self.horizon_s),
                        flexrig_contact::validate::display(reach)
                    ),
                ));
            }
        }
        self.check_payload()?;
        self.check_contact_range(angle)?;
        self.check_reachable(angle)?;
        self.check_loop_stability()
    }

    /// The contact law's range: the test bed's k_c ∈ [1e-3, 1e20] N/mⁿ and n ∈ [0.5, 10]
    /// (below n = 0.5 the law's stiffness dδ/df → ∞ at first touch and the integrators' energy
    /// balance breaks down), then what the integrators resolve: the peak indentation the link
    /// would make at its commanded arrival speed (estimated by energy, ½ μ v² = f²/(2k_δ) +
    /// f δ_c/(n+1), μ from the head and the rigid link's tip mass) must lie between
    /// [`MIN_INDENTATION_OF_LENGTH`] and [`MAX_INDENTATION_OF_LENGTH`] of the link's length:
    /// below, the indentation drowns in the rounding of the tip's position (a peak of 0 N and a
    /// tip passing through); above, the contact law and the linear link no longer hold (contacts
    /// of 1e96 s). An open-loop torque has no commanded speed: its arrival is not estimated.
    fn check_contact_range(&self, angle: f64) -> Result<(), ImpactError> {
        let (k, n) = (self.person.contact.k(), self.person.contact.n());
        if !(k.is_finite() && (CONTACT_K.0..=CONTACT_K.1).contains(&k)) {
            return Err(ImpactError::invalid(
                "person.contact.k",
                k,
                format!(
                    "must lie in [{:e}, {:e}] N/m^n (the test bed's range)",
                    CONTACT_K.0, CONTACT_K.1
                ),
            ));
        }
        if !(n.is_finite() && (CONTACT_N.0..=CONTACT_N.1).contains(&n)) {
            return Err(ImpactError::invalid(
                "person.contact.n",
                n,
                format!(
                    "must lie in [{}, {}] (below 0.5 the contact's stiffness is infinite at \
                     first touch and the energy balance is lost)",
                    CONTACT_N.0, CONTACT_N.1
                ),
            ));
        }
        let Some(profile) = self.drive.profile() else {
            return Ok(());
        };
        let omega = arrival_speed(profile, angle, self.horizon_s);
        let length = self.link.length;
        let tip_speed = omega.abs() * length + self.person.speed;
        if !(tip_speed <= MAX_APPROACH_SPEED) {
            return Err(ImpactError::invalid(
                "drive.command.profile.speed",
                profile.final_speed(),
                format!(
                    "a joint speed whose tip speed |speed| × link.length ({} m) + person.speed \
                     stays within {} m/s (here {} m/s), i.e. |speed| ≤ {} rad/s",
                    flexrig_contact::validate::display(length),
                    MAX_APPROACH_SPEED,
                    flexrig_contact::validate::display(tip_speed),
                    flexrig_contact::validate::display(
                        (MAX_APPROACH_SPEED - self.person.speed) / length
                    ),
                ),
            ));
        }
        let mu = self.reduced_mass();
        let k_delta = self.link.k_delta;
        let indent = |k: f64, v: f64| peak_indentation(mu, v, k, n, k_delta).0;
        // a Hertz contact lasts about 3 δ_max/v (π δ_max/v for n = 1, 2.94 δ_max/v for 3/2)
        let duration = |k: f64, v: f64| {
            if v > 0.0 {
                3.0 * peak_indentation(mu, v, k, n, k_delta).1 / v
            } else {
                f64::INFINITY
            }
        };
        let horizon = self.horizon_s;
        let (lo, hi) = (
            MIN_INDENTATION_OF_LENGTH * length,
            MAX_INDENTATION_OF_LENGTH * length,
        );
        let delta = indent(k, tip_speed);
        let lasts = duration(k, tip_speed);
        if delta >= lo && delta <= hi && lasts <= horizon {
            return Ok(());
        }
        if let Placement::Angle { angle: at } = self.placement
            && omega.abs() < 0.5 * profile.final_speed().abs()
            && (delta < lo || lasts > horizon)
        {
            let start = profile.at(0.0).0;
            return Err(ImpactError::invalid(
                "placement.angle",
                at,
                format!(
                    "an angle the commanded motion reaches moving: there it turns at {} rad/s, \
                     too slow to make a contact the integrators resolve (the tip would indent \
                     the skin by {} m, over about {} s); place the person beyond the start angle {} rad by more \
                     than the ramp's first instants, or use placement = \"after_ramp\"",
                    flexrig_contact::validate::display(omega),
                    flexrig_contact::validate::display(delta),
                    flexrig_contact::validate::display(lasts),
                    flexrig_contact::validate::display(start),
                ),
            ));
        }
        let speed = profile.final_speed();
        if (delta < lo || lasts > horizon) && delta <= hi && k <= DEFAULT_SCALE_K {
            // a physical contact law: the speed is too small
            let fits = |v: f64| indent(k, v) >= lo && duration(k, v) <= horizon;
            let v_min = solve_log(fits, 1e-300, MAX_APPROACH_SPEED);
            let w_min = (v_min - self.person.speed).max(0.0) / length;
            return Err(ImpactError::invalid(
                "drive.command.profile.speed",
                speed,
                format!(
                    "a joint speed whose tip arrives fast enough to make a contact the \
                     integrators resolve within horizon_s = {} s: at {} m/s the tip would indent \
                     the skin by {} m over about {} s (at least {:e} of the link's length, within \
                     the horizon); |speed| ≥ {} rad/s for this contact law",
                    flexrig_contact::validate::display(horizon),
                    flexrig_contact::validate::display(tip_speed),
                    flexrig_contact::validate::display(delta),
                    flexrig_contact::validate::display(lasts),
                    MIN_INDENTATION_OF_LENGTH,
                    flexrig_contact::validate::display(w_min),
                ),
            ));
        }
        // the contact law does not suit the speed: name k with the range that does
        // deeper and longer with a softer law: k_min from the upper bounds, k_max from the lower
        let deep_enough = |k: f64| indent(k, tip_speed) >= lo;
        let short_enough = |k: f64| indent(k, tip_speed) <= hi && duration(k, tip_speed) <= horizon;
        let k_max = if deep_enough(CONTACT_K.1) {
            CONTACT_K.1
        } else {
            solve_log(deep_enough, CONTACT_K.0, CONTACT_K.1)
        };
        let k_min = if short_enough(CONTACT_K.0) {
            CONTACT_K.0
        } else {
            solve_log(short_enough, CONTACT_K.0, CONTACT_K.1)
        };
        let why = if delta < lo {
            format!(
                "the tip, arriving at {} m/s, would indent the skin by {} m, below {:e} of the \
                 link's length, which the integrators do not resolve",
                flexrig_contact::validate::display(tip_speed),
                flexrig_contact::validate::display(delta),
                MIN_INDENTATION_OF_LENGTH
            )
        } else if delta > hi {
            format!(
                "the tip, arriving at {} m/s, would indent the skin by {} m, more than {} of \
                 the link's length, where the contact law and the linear link no longer hold",
                flexrig_contact::validate::display(tip_speed),
                flexrig_contact::validate::display(delta),
                MAX_INDENTATION_OF_LENGTH
            )
        } else {
            format!(
                "the tip, arriving at {} m/s, would stay in the skin for about {} s, longer than \
                 horizon_s = {} s",
                flexrig_contact::validate::display(tip_speed),
                flexrig_contact::validate::display(lasts),
                flexrig_contact::validate::display(horizon)
            )
        };
        if k_min > k_max {
            return Err(ImpactError::invalid(
                "person.contact.k",
                k,
                format!("{why}; no k in the test bed's range suits this speed and link"),
            ));
        }
        Err(ImpactError::invalid(
            "person.contact.k",
            k,
            format!(
                "{why}; for this speed and link k must lie in [{}, {}] N/m^n",
                flexrig_contact::validate::display(k_min),
                flexrig_contact::validate::display(k_max)
            ),
        ))
    }

    /// The reduced mass of the head and the rigid link's tip mass m_e + m_r/3 \[kg\] (against a
    /// wall, the link's alone).
    fn reduced_mass(&self) -> f64 {
        let m_link = self.link.cj_tip_mass();
        if self.person.support == crate::drive::HeadSupport::Wall {
            m_link
        } else {
            m_link * self.person.m_h / (m_link + self.person.m_h)
        }
    }

    /// A controller whose linear loop on the rigid joint is unstable is refused: with the
    /// joint-side inertia J = J_m N² + (m_r/3 + m_e) L² and friction c = c_m N², the loop's
    /// characteristic polynomial J s³ + (k_d + c) s² + k_p s + k_i is stable only when
    /// (k_d + c) k_p > J k_i (Routh–Hurwitz). An unstable loop grows until the torque limit
    /// clips it, and the peak then depends on the phase of that growth at the onset (peaks
    /// jumping 3× between the CJ and the CL).
    /// A payload is 0 or at least [`MIN_PAYLOAD_OF_LINK`] of the link's mass: a lighter one
    /// changes the peak by less than a millionth (measured: 1e-6 of m_r moves the test bed's
    /// peak by 1e-7), while a payload of 1e-15 kg on the compliant link makes a tip of no inertia
    /// whose contact the integrator cannot step through (the step budget runs out).
    fn check_payload(&self) -> Result<(), ImpactError> {
        let (m_e, m_r) = (self.link.m_e, self.link.m_r);
        if m_e == 0.0 || m_e >= MIN_PAYLOAD_OF_LINK * m_r {
            return Ok(());
        }
        Err(ImpactError::invalid(
            "link.m_e",
            m_e,
            format!(
                "0 (no payload) or at least {:e} of link.m_r, i.e. ≥ {} kg: a lighter payload \
                 changes nothing but the integrators' round-off",
                MIN_PAYLOAD_OF_LINK,
                flexrig_contact::validate::display(MIN_PAYLOAD_OF_LINK * m_r)
            ),
        ))
    }

    /// The drive can bring the link to the person within the horizon: with the whole joint
    /// torque limit N τ_max on the joint's rigid inertia J = J_m N² + m_r L²/3 + m_e L² and no
    /// friction, the link turns at most ω₀ T + ½ (N τ_max / J) T² in the horizon T (a bound the
    /// run never beats); a person farther away is never reached (the run would wait out the
    /// horizon and fail).
    fn check_reachable(&self, angle: f64) -> Result<(), ImpactError> {
        let (Some(profile), limit) = (self.drive.profile(), self.drive.joint_torque_limit()) else {
            return Ok(());
        };
        if !limit.is_finite() {
            return Ok(());
        }
        let motor = self.drive.motor();
        let l = self.link.length;
        let j = motor.reflected_inertia() + (self.link.m_r / 3.0 + self.link.m_e) * l * l;
        let (start, omega0) = (profile.at(0.0).0, profile.at(0.0).1.abs());
        let travel = (angle - start).abs();
        let t = self.horizon_s;
        let reach = omega0 * t + 0.5 * limit / j * t * t;
        if reach >= travel {
            return Ok(());
        }
        let needed = 2.0 * j * (travel - omega0 * t) / (t * t) / motor.gear_ratio;
        Err(ImpactError::invalid(
            "drive.command.torque_limit",
            limit / motor.gear_ratio,
            format!(
                "a torque limit that can turn the joint's inertia {} kg·m² (rotor through the \
                 gear, and link) through the {} rad to the person within horizon_s = {} s: \
                 at least {} N·m (or a lighter drive.motor.rotor_inertia, or a longer horizon_s)",
                flexrig_contact::validate::display(j),
                flexrig_contact::validate::display(travel),
                flexrig_contact::validate::display(t),
                flexrig_contact::validate::display(needed)
            ),
        ))
    }

    fn check_loop_stability(&self) -> Result<(), ImpactError> {
        let crate::drive::DriveCommand::Controller { gains, .. } = self.drive.command() else {
            return Ok(());
        };
        if gains.ki == 0.0 {
            return Ok(());
        }
        let motor = self.drive.motor();
        let j = motor.reflected_inertia() + self.link.cj_tip_mass() * self.link.length.powi(2);
        let damping = gains.kd + motor.reflected_friction();
        let ki_max = damping * gains.kp / j;
        if gains.ki < ki_max {
            return Ok(());
        }
        Err(ImpactError::invalid(
            "drive.command.gains.ki",
            gains.ki,
            format!(
                "a loop that is stable on the joint: with kp = {} and kd = {} on the joint's \
                 inertia {} kg·m² (rotor and link) the loop is unstable unless \
                 ki < (kd + friction) kp / J = {} N·m/(rad·s) (Routh–Hurwitz); raise kp or kd, \
                 or lower ki",
                flexrig_contact::validate::display(gains.kp),
                flexrig_contact::validate::display(gains.kd),
                flexrig_contact::validate::display(j),
                flexrig_contact::validate::display(ki_max)
            ),
        ))
    }
}

/// Smallest non-zero payload, as a fraction of the link's mass (see `check_payload`).
pub const MIN_PAYLOAD_OF_LINK: f64 = 1e-6;
/// The Hertz stiffness range \[N/mⁿ\] (the test bed's, flexrig-rig's `limits::CONTACT_K`).
pub const CONTACT_K: (f64, f64) = (1e-3, 1e20);
/// The Hertz exponent range of a driven strike.
pub const CONTACT_N: (f64, f64) = (0.5, 10.0);
/// Fastest approach \[m/s\] (the free-mass impact's v0 range).
pub const MAX_APPROACH_SPEED: f64 = 1e3;
/// Smallest peak indentation the integrators resolve, as a fraction of the link's length: the
/// tip's position is O(L) and carries ~1e-16 L of rounding; 1e-10 L keeps six digits.
pub const MIN_INDENTATION_OF_LENGTH: f64 = 1e-10;
/// Largest peak indentation, as a fraction of the link's length.
pub const MAX_INDENTATION_OF_LENGTH: f64 = 0.5;
/// Stiffnesses up to this are contact laws of tissue and materials (the paper's 1e7–1e8): a
/// contact too shallow to resolve with such a law is blamed on the speed, above it on k.
const DEFAULT_SCALE_K: f64 = 1e12;

/// The joint speed [rad/s] the commanded profile has where it reaches `angle` (bisection over
/// [0, horizon]; the profile turns one way, so its angle is monotone).
fn arrival_speed(profile: &crate::drive::Profile, angle: f64, horizon: f64) -> f64 {
    let start = profile.at(0.0).0;
    if angle == start {
        return profile.at(0.0).1;
    }
    let ahead = |t: f64| {
        let a = profile.at(t).0;
        if angle > start {
            a >= angle
        } else {
            a <= angle
        }
    };
    if !ahead(horizon) {
        return profile.at(horizon).1;
    }
    let (mut lo, mut hi) = (0.0, horizon);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if ahead(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    profile.at(hi).1
}

/// The peak total indentation \[m\] of a Hertz contact f = k δ_cⁿ in series with the link's
/// spring k_δ, struck by a reduced mass μ at speed v, from the energy ½ μ v² = f²/(2k_δ) +
/// f δ_c/(n+1) (exact for any n, docs/theory.md); the contact's own share δ_c is what the
/// integrators must resolve: (δ_c, δ_c + f/k_δ) are returned.
fn peak_indentation(mu: f64, v: f64, k: f64, n: f64, k_delta: f64) -> (f64, f64) {
    let energy = 0.5 * mu * v * v;
    if !(energy > 0.0) {
        return (0.0, 0.0);
    }
    let dc = |f: f64| (f / k).powf(1.0 / n);
    let u = |f: f64| f * f / (2.0 * k_delta) + f * dc(f) / (n + 1.0);
    // bisection on log f over the whole double range
    let (mut lo, mut hi) = (-700.0_f64, 700.0_f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if u(mid.exp()) < energy {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let f = hi.exp();
    (dc(f), dc(f) + f / k_delta)
}

/// The boundary of a monotone predicate over [lo, hi] on a log scale (`ok(lo)` and `!ok(hi)`
/// or the reverse; an end if it does not change).
fn solve_log(ok: impl Fn(f64) -> bool, lo: f64, hi: f64) -> f64 {
    let (mut a, mut b) = (lo.ln(), hi.ln());
    let at_lo = ok(lo);
    if at_lo == ok(hi) {
        return if at_lo { hi } else { lo };
    }
    for _ in 0..200 {
        let mid = 0.5 * (a + b);
        if ok(mid.exp()) == at_lo {
            a = mid;
        } else {
            b = mid;
        }
    }
    (0.5 * (a + b)).exp()
}

/// The energy balance over the contact, from its onset to the separation \[J\].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EnergyBalance {
    /// Work of the contact force on the approach while the indentation grows, ∫ f δ̇ dt over
    /// δ̇ > 0 (the elastic law: the contact energy at the peak).
    pub impact_energy_j: f64,
    /// Work of the motor on the joint, ∫ τ_j φ̇_m dt (the controller's torque included).
    pub motor_work_j: f64,
    /// Energy dissipated by the drive's friction, the neck's damper and the contact's damping.
    pub dissipated_j: f64,
    /// Change of the mechanical energy (kinetic + strain + contact + neck spring).
    pub mechanical_change_j: f64,
    /// motor work − dissipated − mechanical change: 0 up to the integration error.
    pub residual_j: f64,
}

/// Something the drive did that the reader should know (its `Display` says it in words).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "note")]
pub enum DriveNote {
    /// The controller's torque reached its limit (first at `first_s`): the commanded motion was
    /// not followed.
    TorqueLimitReached {
        /// First time at the limit \[s\].
        first_s: f64,
    },
    /// The link arrived faster or slower than commanded, by more than
    /// [`DriveNote::ARRIVAL_TOLERANCE`] of the commanded tip speed.
    ArrivalOffCommand {
        /// Commanded tip speed L ω_cmd at the onset [m/s].
        commanded_mps: f64,
        /// The link's actual speed towards the person at the onset [m/s] (the dome's, or the
        /// tip's along its path).
        actual_mps: f64,
    },
    /// The link still vibrated at the onset: the tip's speed relative to the hub's line (its
    /// vibration, CL: the beam's bending; CJ: L (φ̇_l − φ̇_m)) exceeded
    /// [`DriveNote::VIBRATION_THRESHOLD`] of the approach speed, so the impact speed depends
    /// on the vibration's phase at the onset. The rule fires for soft and stiff links alike.
    StillVibrating {
        /// The tip's vibration speed at the onset [m/s] (positive towards the person).
        vibration_speed_mps: f64,
        /// The approach speed at the onset [m/s].
        approach_speed_mps: f64,
    },
    /// A contact was still on when the strike's window (`horizon_s`) closed: the drive kept
    /// pressing the person; the largest force up to then counts.
    StillPressing {
        /// The window's end \[s\].
        window_s: f64,
    },
}

impl DriveNote {
    /// Relative deviation of the arrival speed from the command that earns a note (1 %).
    pub const ARRIVAL_TOLERANCE: f64 = 0.01;
    /// The tip's vibration speed over the approach speed that earns a note (2 %: the impact
    /// speed, and with it the peak force, then depends by as much on when the link arrives).
    pub const VIBRATION_THRESHOLD: f64 = 0.02;

    /// The arrival note, if `actual` [m/s] is off `commanded` [m/s] by more than the tolerance.
    pub fn arrival(commanded: f64, actual: f64) -> Option<DriveNote> {
        ((actual - commanded).abs() > DriveNote::ARRIVAL_TOLERANCE * commanded.abs()).then_some(
            DriveNote::ArrivalOffCommand {
                commanded_mps: commanded,
                actual_mps: actual,
            },
        )
    }

    /// The vibration note, if the tip's `vibration` speed [m/s] exceeds the threshold of the
    /// `approach` speed [m/s].
    pub fn vibration(vibration: f64, approach: f64) -> Option<DriveNote> {
        (vibration.abs() > DriveNote::VIBRATION_THRESHOLD * approach.abs()).then_some(
            DriveNote::StillVibrating {
                vibration_speed_mps: vibration,
                approach_speed_mps: approach,
            },
        )
    }
}

impl std::fmt::Display for DriveNote {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            DriveNote::TorqueLimitReached { first_s } => write!(
                f,
                "the controller's torque reached its limit at {first_s:.6} s: the commanded \
                 motion was not followed from then on"
            ),
            DriveNote::ArrivalOffCommand {
                commanded_mps,
                actual_mps,
            } => write!(
                f,
                "the link arrived at {actual_mps:.6} m/s, {} than the commanded \
                 {commanded_mps:.6} m/s ({:+.2} %)",
                if actual_mps > commanded_mps {
                    "faster"
                } else {
                    "slower"
                },
                100.0 * (actual_mps / commanded_mps - 1.0)
            ),
            DriveNote::StillVibrating {
                vibration_speed_mps,
                approach_speed_mps,
            } => write!(
                f,
                "the link still vibrated when it arrived: its tip moved at {:.4} m/s relative \
                 to the hub's line, {:.1} % of the approach speed {approach_speed_mps:.6} m/s \
                 (the impact depends on the vibration's phase)",
                vibration_speed_mps,
                100.0 * (vibration_speed_mps / approach_speed_mps).abs()
            ),
            DriveNote::StillPressing { window_s } => write!(
                f,
                "the contact was still on when the window closed at {window_s:.6} s (horizon_s): \
                 the drive kept pressing the person, and the force up to then counts"
            ),
        }
    }
}

/// The result of a driven strike (first contact, from onset to separation).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DrivenOutcome {
    /// The contact: onset, time of the peak and the duration, times from the drive's start.
    pub contact: ContactEvent,
    /// Relative approach speed δ̇ at the onset [m/s] (serialised as `impact_velocity_mps`, the
    /// test-bed run's name).
    #[serde(rename = "impact_velocity_mps")]
    pub approach_speed_mps: f64,
    /// The commanded tip speed L ω_cmd at the onset [m/s] (`None` for an open-loop torque).
    pub commanded_tip_speed_mps: Option<f64>,
    /// The tip's deflection from the hub's line at the onset \[m\] (CJ: L(φ_l − φ_m); CL: the
    /// beam's tip from the clamped hub's tangent), positive towards the person.
    pub pre_impact_deflection_m: f64,
    /// Joint torque τ_j at the onset [N·m].
    pub joint_torque_at_onset_nm: f64,
    /// Largest |τ_j| during the contact [N·m].
    pub peak_joint_torque_nm: f64,
    /// The energy balance over the contact.
    pub energy: EnergyBalance,
    /// Relative approach speed at the separation (negative: parting) [m/s]; serialised as the
    /// parting speed `separation_velocity_mps` (positive), the test-bed run's name.
    #[serde(
        rename = "separation_velocity_mps",
        serialize_with = "crate::setup::negated"
    )]
    pub separation_rate_mps: f64,
    /// What the drive did.
    pub notes: Vec<DriveNote>,
    /// Right-hand-side evaluations (CJ) or steps (CL) (serialised as `steps`, the test-bed
    /// run's name).
    #[serde(rename = "steps")]
    pub work: usize,
    /// The motion sampled at the integrator's steps, at most one sample per `trace_every` of
    /// the settings, the onset and the separation included (empty without `trace_every`).
    pub trace: Vec<TraceSample>,
    /// Every contact of the run in order, the first (`contact`) included: the first alone
    /// unless the settings ask for every contact.
    pub contacts: Vec<ContactEvent>,
    /// How the run ended: at the first separation, the bodies parted for good, or the window
    /// (`horizon_s`) closed — with a contact still on if the last one lasts to it.
    pub ended: crate::RunEnd,
}

impl DrivenOutcome {
    /// The contact with the largest peak force (the first of equal ones) and its number
    /// (1 = the first contact).
    pub fn largest_contact(&self) -> (usize, ContactEvent) {
        let (index, largest) =
            self.contacts
                .iter()
                .enumerate()
                .fold((0, self.contact), |(i, best), (j, c)| {
                    if c.peak_force_n > best.peak_force_n {
                        (j, *c)
                    } else {
                        (i, best)
                    }
                });
        (index + 1, largest)
    }
}

/// One sample of a driven strike's motion (for logs and figures).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TraceSample {
    /// Time from the drive's start \[s\].
    pub t: f64,
    /// Joint (motor, after the gear) angle \[rad\].
    pub hub_angle_rad: f64,
    /// Joint speed [rad/s].
    pub hub_speed_rad_s: f64,
    /// Tip deflection from the hub's line \[m\] (positive towards the person).
    pub tip_deflection_m: f64,
    /// Indentation δ \[m\] (negative: the gap before the contact).
    pub indentation_m: f64,
    /// Contact force \[N\].
    pub force_n: f64,
    /// Joint torque τ_j [N·m].
    pub joint_torque_nm: f64,
    /// The skin's position along the tip's path \[m\].
    pub head_position_m: f64,
    /// The link's elastic moment at the joint [N·m]: CJ the torsion spring's k_θr (φ_m − φ_l);
    /// CL the beam's root moment, what the hub passes on to the clamped beam (from the hub's
    /// balance J_m N² θ̈ = τ_j − c_j θ̇ − M_root).
    pub moment_nm: f64,
    /// The head's acceleration along the tip's path [m/s²] (positive away from the link):
    /// (f − k_n (x_h − x_rest) − c_n ẋ_h)/m_h; 0 against a wall (the skin does not move).
    pub head_acceleration_mps2: f64,
}

/// Keeps at most one sample per `every` seconds (the last one always replaceable by a
/// forced sample).
#[derive(Debug, Clone)]
pub(crate) struct Tracer {
    every: Option<f64>,
    pub(crate) samples: Vec<TraceSample>,
}

impl Tracer {
    pub(crate) fn new(every: Option<f64>) -> Tracer {
        Tracer {
            every,
            samples: Vec::new(),
        }
    }

    /// The next time a sample is due after the last one (`None`: no trace, or none yet).
    pub(crate) fn next_due(&self) -> Option<f64> {
        let every = self.every?;
        self.samples.last().map(|last| last.t + every)
    }

    /// Records `sample()` if due (or `force`d).
    pub(crate) fn offer(&mut self, t: f64, force: bool, sample: impl FnOnce() -> TraceSample) {
        let Some(every) = self.every else { return };
        let due = self.samples.last().is_none_or(|last| t - last.t >= every);
        if due || force {
            // a forced sample at the time of the last one replaces it
            if self.samples.last().is_some_and(|last| last.t >= t) {
                self.samples.pop();
            }
            // thinned before the push, so the vector never grows past its budget's capacity
            if self.samples.len() >= MAX_TRACE_SAMPLES {
                self.thin();
            }
            self.samples.push(sample());
        }
    }

    /// Halves the samples kept (every other one, the last kept) and doubles the interval: a
    /// contact that lasts far longer than foreseen keeps a bounded trace (at most
    /// [`MAX_TRACE_SAMPLES`]) at a coarser rate instead of growing without bound.
    fn thin(&mut self) {
        let last = self.samples.len() - 1;
        let mut i = 0;
        self.samples.retain(|_| {
            let keep = i % 2 == 0 || i == last;
            i += 1;
            keep
        });
        self.every = self.every.map(|e| 2.0 * e);
    }
}

/// Most trace samples a strike keeps (80 B each: 670 MB); beyond, the trace is thinned.
pub const MAX_TRACE_SAMPLES: usize = 1 << 23;
