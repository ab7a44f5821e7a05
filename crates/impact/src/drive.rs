//! The robot joint's drive (the paper's Fig. 5a: "driven by a torque controller τ(t)"): a motor
//! with rotor inertia J_m behind a gear of ratio N, optional viscous friction, and what moves it —
//! a prescribed joint trajectory (an ideal position source), a feedback controller with a torque
//! limit, or an open-loop torque.
//!
//! **Units and sides.** Angles and speeds are the *joint's* (after the gear: the motor shaft turns
//! N times as far). The rotor's inertia J_m and friction c_m are given at the motor shaft and act
//! at the joint as J_m N² and c_m N². Controller gains act on joint-side errors and give a
//! joint-side torque τ_j = N τ_m; the torque limit and an open-loop torque are given at the motor
//! shaft (a motor's datasheet), so the joint sees at most N τ_m,max.
//!
//! **Controller** ([`Gains`]): τ_j = sat(K_p e_φ + K_d e_ω + K_i ∫e_φ dt), e_φ = φ_cmd − φ_m,
//! e_ω = ω_cmd − φ̇_m, |τ_j| ≤ N τ_m,max (sat clips; the integral keeps running). A PI loop on
//! the joint velocity, τ_j = K_v e_ω + K_I ∫e_ω dt, is the same law with K_p = K_I, K_d = K_v,
//! K_i = 0, because ∫e_ω dt = e_φ − e_φ(0) exactly ([`Gains::velocity_pi`]).
//!
//! **Profiles** ([`Profile`]): the commanded joint angle φ_cmd(t), speed ω_cmd(t) and
//! acceleration α_cmd(t). A steady profile starts the whole robot in steady motion at t = 0
//! (springs unloaded, the controller holding the speed); every other profile starts at rest.
//! The spin-up profile is Kane, Ryan & Banerjee's (1987):
//! φ(t) = (ω_s/T_s)[t²/2 + (T_s/2π)²(cos(2πt/T_s) − 1)] for t < T_s, then ω_s(t − T_s/2).

use std::f64::consts::PI;

use serde::{Deserialize, Serialize};

use crate::ImpactError;

/// The motor and gear.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Motor {
    /// Rotor inertia J_m at the motor shaft [kg·m²], ≥ 0 (0 only with a prescribed trajectory).
    pub rotor_inertia: f64,
    /// Gear ratio N (motor turns per joint turn), > 0.
    pub gear_ratio: f64,
    /// Viscous friction c_m at the motor shaft [N·m·s/rad], ≥ 0.
    #[serde(default)]
    pub friction: f64,
}

impl Motor {
    /// A validated motor; the error names the field.
    pub fn new(rotor_inertia: f64, gear_ratio: f64, friction: f64) -> Result<Motor, ImpactError> {
        let m = Motor {
            rotor_inertia,
            gear_ratio,
            friction,
        };
        m.validate()?;
        Ok(m)
    }

    /// Checks the fields.
    pub fn validate(&self) -> Result<(), ImpactError> {
        non_negative(
            "drive.motor.rotor_inertia",
            self.rotor_inertia,
            1e9,
            "kg·m²",
        )?;
        if !(self.gear_ratio.is_finite() && self.gear_ratio > 0.0 && self.gear_ratio <= 1e6) {
            return Err(ImpactError::invalid(
                "drive.motor.gear_ratio",
                self.gear_ratio,
                "must lie in (0, 1e6]",
            ));
        }
        non_negative("drive.motor.friction", self.friction, 1e9, "N·m·s/rad")?;
        // the joint sees J_m N²: the free hub's range [1e-12, 1e12] kg·m² (or no rotor at all)
        let reflected = self.reflected_inertia();
        if self.rotor_inertia > 0.0 && !(1e-12..=1e12).contains(&reflected) {
            let n2 = self.gear_ratio * self.gear_ratio;
            return Err(ImpactError::invalid(
                "drive.motor.rotor_inertia",
                self.rotor_inertia,
                format!(
                    "0, or an inertia the joint sees (times gear_ratio² = {}) within \
                     [1e-12, 1e12] kg·m²: [{}, {}] kg·m² at this gear",
                    flexrig_contact::validate::display(n2),
                    flexrig_contact::validate::display(1e-12 / n2),
                    flexrig_contact::validate::display(1e12 / n2)
                ),
            ));
        }
        Ok(())
    }

    /// The rotor's inertia seen at the joint, J_m N² [kg·m²].
    pub fn reflected_inertia(&self) -> f64 {
        self.rotor_inertia * self.gear_ratio * self.gear_ratio
    }

    /// The friction seen at the joint, c_m N² [N·m·s/rad].
    pub fn reflected_friction(&self) -> f64 {
        self.friction * self.gear_ratio * self.gear_ratio
    }
}

/// A commanded joint motion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "profile", deny_unknown_fields)]
pub enum Profile {
    /// Constant joint speed from t = 0, the robot already in steady motion (springs unloaded, the
    /// controller holding the speed).
    Steady {
        /// Joint speed ω [rad/s].
        speed: f64,
    },
    /// From rest to `speed` by a smooth ramp of duration `ramp_time`: ω = ω_c s(t/T_r) with the
    /// quintic s(u) = 10u³ − 15u⁴ + 6u⁵ (zero acceleration and jerk at both ends).
    SmoothRamp {
        /// Final joint speed ω_c [rad/s].
        speed: f64,
        /// Ramp duration T_r \[s\], > 0.
        ramp_time: f64,
    },
    /// Trapezoidal velocity: constant acceleration from rest to `speed`, then constant speed.
    Trapezoid {
        /// Final joint speed [rad/s].
        speed: f64,
        /// Acceleration [rad/s²], > 0.
        acceleration: f64,
    },
    /// Kane, Ryan & Banerjee's spin-up (module docs), from rest to ω_s at T_s.
    SpinUp {
        /// Final speed ω_s [rad/s].
        speed: f64,
        /// Spin-up time T_s \[s\], > 0.
        time: f64,
    },
}

impl Profile {
    /// Checks the fields (`field` is the profile's name in the user's input).
    pub fn validate(&self, field: &str) -> Result<(), ImpactError> {
        let speed = self.final_speed();
        if !(speed.is_finite() && speed.abs() <= 1e4) {
            return Err(ImpactError::invalid(
                format!("{field}.speed"),
                speed,
                "a finite joint speed within ±1e4 rad/s",
            ));
        }
        match *self {
            Profile::Steady { .. } => Ok(()),
            Profile::SmoothRamp { ramp_time, .. } => {
                positive(&format!("{field}.ramp_time"), ramp_time, 1e6, "s")
            }
            Profile::Trapezoid { acceleration, .. } => positive(
                &format!("{field}.acceleration"),
                acceleration,
                1e9,
                "rad/s²",
            ),
            Profile::SpinUp { time, .. } => positive(&format!("{field}.time"), time, 1e6, "s"),
        }
    }

    /// The speed reached [rad/s].
    pub fn final_speed(&self) -> f64 {
        match *self {
            Profile::Steady { speed }
            | Profile::SmoothRamp { speed, .. }
            | Profile::Trapezoid { speed, .. }
            | Profile::SpinUp { speed, .. } => speed,
        }
    }

    /// True when the robot starts in steady motion.
    pub fn is_steady(&self) -> bool {
        matches!(self, Profile::Steady { .. })
    }

    /// Time \[s\] at which the speed is reached (0 for a steady profile).
    pub fn ramp_end(&self) -> f64 {
        match *self {
            Profile::Steady { .. } => 0.0,
            Profile::SmoothRamp { ramp_time, .. } => ramp_time,
            Profile::Trapezoid {
                speed,
                acceleration,
            } => speed.abs() / acceleration,
            Profile::SpinUp { time, .. } => time,
        }
    }

    /// (φ \[rad\], ω [rad/s], α [rad/s²]) commanded at time `t` ≥ 0.
    pub fn at(&self, t: f64) -> (f64, f64, f64) {
        self.at_in(t, t)
    }

    /// As [`Profile::at`], on the branch that holds at `branch` (an integrator's step evaluates
    /// its end stages on the step's own side of a corner: pass the step's midpoint).
    pub fn at_in(&self, t: f64, branch: f64) -> (f64, f64, f64) {
        match *self {
            Profile::Steady { speed } => (speed * t, speed, 0.0),
            Profile::SmoothRamp { speed, ramp_time } => {
                if t >= ramp_time {
                    // ∫₀¹ s = 1/2
                    (speed * (t - 0.5 * ramp_time), speed, 0.0)
                } else {
                    let u = t / ramp_time;
                    let (u2, u3) = (u * u, u * u * u);
                    let s = u3 * (10.0 - 15.0 * u + 6.0 * u2);
                    let ds = 30.0 * u2 * (1.0 - 2.0 * u + u2);
                    let int = u2 * u2 * (2.5 - 3.0 * u + u2);
                    (speed * ramp_time * int, speed * s, speed * ds / ramp_time)
                }
            }
            Profile::Trapezoid {
                speed,
                acceleration,
            } => {
                let a = acceleration * speed.signum();
                let t1 = speed.abs() / acceleration;
                if branch >= t1 {
                    (speed * (t - 0.5 * t1), speed, 0.0)
                } else {
                    (0.5 * a * t * t, a * t, a)
                }
            }
            Profile::SpinUp { speed, time } => spin_up(speed, time, t),
        }
    }
}

/// Kane, Ryan & Banerjee's spin-up: (θ, θ̇, θ̈) at `t` for final speed `omega_s` [rad/s] reached
/// at `t_s` \[s\].
pub fn spin_up(omega_s: f64, t_s: f64, t: f64) -> (f64, f64, f64) {
    if t >= t_s {
        return (omega_s * (t - 0.5 * t_s), omega_s, 0.0);
    }
    let c = omega_s / t_s;
    let w = 2.0 * PI / t_s;
    let (sin, cos) = (w * t).sin_cos();
    (
        c * (0.5 * t * t + (cos - 1.0) / (w * w)),
        c * (t - sin / w),
        c * (1.0 - cos),
    )
}

/// Feedback gains on the joint (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Gains {
    /// K_p on the angle error [N·m/rad], ≥ 0.
    pub kp: f64,
    /// K_d on the speed error [N·m·s/rad], ≥ 0.
    pub kd: f64,
    /// K_i on the integral of the angle error [N·m/(rad·s)], ≥ 0.
    #[serde(default)]
    pub ki: f64,
}

impl Gains {
    /// A position PD loop.
    pub fn position_pd(kp: f64, kd: f64) -> Gains {
        Gains { kp, kd, ki: 0.0 }
    }

    /// A velocity PI loop τ = K_v e_ω + K_I ∫e_ω dt (= K_I e_φ + K_v e_ω, module docs).
    pub fn velocity_pi(kv: f64, k_int: f64) -> Gains {
        Gains {
            kp: k_int,
            kd: kv,
            ki: 0.0,
        }
    }

    /// Checks the fields.
    pub fn validate(&self) -> Result<(), ImpactError> {
        non_negative("drive.command.gains.kp", self.kp, 1e15, "N·m/rad")?;
        non_negative("drive.command.gains.kd", self.kd, 1e15, "N·m·s/rad")?;
        non_negative("drive.command.gains.ki", self.ki, 1e18, "N·m/(rad·s)")?;
        if self.kp == 0.0 && self.kd == 0.0 && self.ki == 0.0 {
            return Err(ImpactError::invalid(
                "drive.command.gains",
                "all zero",
                "at least one gain > 0 (a torque-free drive is an open-loop torque of 0)",
            ));
        }
        Ok(())
    }
}

/// An open-loop motor torque τ_m(t) at the motor shaft [N·m].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "shape", deny_unknown_fields)]
pub enum TorqueProfile {
    /// Constant torque (0: a torque-free drive, the free hub).
    Constant {
        /// τ_m [N·m].
        torque: f64,
    },
    /// `torque` for `duration`, then 0 (accelerate, then coast).
    Pulse {
        /// τ_m [N·m].
        torque: f64,
        /// Duration \[s\], > 0.
        duration: f64,
    },
    /// Piecewise linear through (times, torques), constant beyond the ends.
    Table {
        /// Times \[s\], strictly increasing.
        times: Vec<f64>,
        /// Torques [N·m], one per time.
        torques: Vec<f64>,
    },
}

impl TorqueProfile {
    /// Checks the fields.
    pub fn validate(&self) -> Result<(), ImpactError> {
        let finite = |f: &str, v: f64| {
            if v.is_finite() && v.abs() <= 1e9 {
                Ok(())
            } else {
                Err(ImpactError::invalid(
                    f,
                    v,
                    "a finite torque within ±1e9 N·m",
                ))
            }
        };
        match self {
            TorqueProfile::Constant { torque } => finite("drive.command.torque.torque", *torque),
            TorqueProfile::Pulse { torque, duration } => {
                finite("drive.command.torque.torque", *torque)?;
                positive("drive.command.torque.duration", *duration, 1e6, "s")
            }
            TorqueProfile::Table { times, torques } => {
                if times.is_empty() || times.len() != torques.len() {
                    return Err(ImpactError::invalid(
                        "drive.command.torque.times",
                        format!("{} times, {} torques", times.len(), torques.len()),
                        "as many times as torques, at least one",
                    ));
                }
                for (i, w) in times.windows(2).enumerate() {
                    if !(w[1] > w[0]) {
                        return Err(ImpactError::invalid(
                            format!("drive.command.torque.times[{}]", i + 1),
                            w[1],
                            "strictly increasing times",
                        ));
                    }
                }
                for (i, &t) in times.iter().enumerate() {
                    if !t.is_finite() {
                        return Err(ImpactError::invalid(
                            format!("drive.command.torque.times[{i}]"),
                            t,
                            "a finite time",
                        ));
                    }
                }
                for (i, &q) in torques.iter().enumerate() {
                    finite(&format!("drive.command.torque.torques[{i}]"), q)?;
                }
                Ok(())
            }
        }
    }

    /// τ_m(t) [N·m].
    pub fn at(&self, t: f64) -> f64 {
        self.at_in(t, t)
    }

    /// As [`TorqueProfile::at`], on the branch that holds at `branch` (see [`Profile::at_in`]).
    pub fn at_in(&self, t: f64, branch: f64) -> f64 {
        match self {
            TorqueProfile::Constant { torque } => *torque,
            TorqueProfile::Pulse { torque, duration } => {
                if branch < *duration {
                    *torque
                } else {
                    0.0
                }
            }
            TorqueProfile::Table { times, torques } => {
                let i = times.partition_point(|&x| x <= t);
                if i == 0 {
                    torques[0]
                } else if i == times.len() {
                    torques[i - 1]
                } else {
                    let s = (t - times[i - 1]) / (times[i] - times[i - 1]);
                    torques[i - 1] + s * (torques[i] - torques[i - 1])
                }
            }
        }
    }
}

/// What moves the joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "command", deny_unknown_fields)]
pub enum DriveCommand {
    /// The joint (after the gear) follows the profile exactly: an infinitely stiff drive whose
    /// motor delivers whatever torque that takes (reported).
    Trajectory {
        /// The commanded motion.
        profile: Profile,
    },
    /// A feedback loop on the motor's joint-side angle and speed (collocated), with a limit.
    Controller {
        /// The commanded motion.
        profile: Profile,
        /// The gains.
        gains: Gains,
        /// Largest motor-shaft torque |τ_m| [N·m] (`None`: unlimited).
        #[serde(default)]
        torque_limit: Option<f64>,
    },
    /// An open-loop motor torque.
    OpenLoop {
        /// τ_m(t).
        torque: TorqueProfile,
        /// Joint speed [rad/s] of everything at t = 0 (steady motion if the torque balances the
        /// friction; 0: from rest).
        #[serde(default)]
        initial_speed: f64,
    },
}

/// The validated drive.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "DriveSpec", into = "DriveSpec")]
pub struct Drive {
    spec: DriveSpec,
}

/// The serialised form of [`Drive`] (a scene's `[drive]` table).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveSpec {
    /// Motor and gear.
    pub motor: Motor,
    /// What moves it.
    pub command: DriveCommand,
}

impl TryFrom<DriveSpec> for Drive {
    type Error = ImpactError;
    fn try_from(spec: DriveSpec) -> Result<Self, ImpactError> {
        Drive::new(spec.motor, spec.command)
    }
}

impl From<Drive> for DriveSpec {
    fn from(d: Drive) -> Self {
        d.spec
    }
}

impl Drive {
    /// A validated drive; the error names the field, the value and what is allowed.
    pub fn new(motor: Motor, command: DriveCommand) -> Result<Drive, ImpactError> {
        motor.validate()?;
        match &command {
            DriveCommand::Trajectory { profile } => profile.validate("drive.command.profile")?,
            DriveCommand::Controller {
                profile,
                gains,
                torque_limit,
            } => {
                profile.validate("drive.command.profile")?;
                gains.validate()?;
                if let Some(limit) = torque_limit {
                    positive("drive.command.torque_limit", *limit, 1e9, "N·m")?;
                }
                if motor.rotor_inertia == 0.0 {
                    return Err(ImpactError::invalid(
                        "drive.motor.rotor_inertia",
                        0.0,
                        "> 0 kg·m² under a controller (a massless rotor is a prescribed trajectory)",
                    ));
                }
            }
            DriveCommand::OpenLoop {
                torque,
                initial_speed,
            } => {
                torque.validate()?;
                if !(initial_speed.is_finite() && initial_speed.abs() <= 1e4) {
                    return Err(ImpactError::invalid(
                        "drive.command.initial_speed",
                        initial_speed,
                        "a finite joint speed within ±1e4 rad/s",
                    ));
                }
                if motor.rotor_inertia == 0.0 {
                    return Err(ImpactError::invalid(
                        "drive.motor.rotor_inertia",
                        0.0,
                        "> 0 kg·m² under an open-loop torque",
                    ));
                }
            }
        }
        Ok(Drive {
            spec: DriveSpec { motor, command },
        })
    }

    /// An ideal position source along `profile` (motor irrelevant but for the torque it takes).
    pub fn trajectory(motor: Motor, profile: Profile) -> Result<Drive, ImpactError> {
        Drive::new(motor, DriveCommand::Trajectory { profile })
    }

    /// A feedback loop.
    pub fn controller(
        motor: Motor,
        profile: Profile,
        gains: Gains,
        torque_limit: Option<f64>,
    ) -> Result<Drive, ImpactError> {
        Drive::new(
            motor,
            DriveCommand::Controller {
                profile,
                gains,
                torque_limit,
            },
        )
    }

    /// A torque-free drive (τ_m ≡ 0) turning at `speed` [rad/s] at t = 0: the free hub.
    pub fn torque_free(motor: Motor, speed: f64) -> Result<Drive, ImpactError> {
        Drive::new(
            motor,
            DriveCommand::OpenLoop {
                torque: TorqueProfile::Constant { torque: 0.0 },
                initial_speed: speed,
            },
        )
    }

    /// The motor.
    pub fn motor(&self) -> &Motor {
        &self.spec.motor
    }

    /// The command.
    pub fn command(&self) -> &DriveCommand {
        &self.spec.command
    }

    /// The commanded profile (none for an open-loop torque).
    pub fn profile(&self) -> Option<&Profile> {
        match &self.spec.command {
            DriveCommand::Trajectory { profile } | DriveCommand::Controller { profile, .. } => {
                Some(profile)
            }
            DriveCommand::OpenLoop { .. } => None,
        }
    }

    /// Joint speed of everything at t = 0 [rad/s].
    pub fn initial_speed(&self) -> f64 {
        match &self.spec.command {
            DriveCommand::OpenLoop { initial_speed, .. } => *initial_speed,
            _ => match self.profile() {
                Some(Profile::Steady { speed }) => *speed,
                _ => 0.0,
            },
        }
    }

    /// Times \[s\] at which the drive's command is not smooth (a ramp's end, a trapezoid's
    /// corner, a pulse's end, a table's points): integrators land on them.
    pub fn breakpoints(&self) -> Vec<f64> {
        let mut out = match &self.spec.command {
            DriveCommand::OpenLoop { torque, .. } => match torque {
                TorqueProfile::Constant { .. } => Vec::new(),
                TorqueProfile::Pulse { duration, .. } => vec![*duration],
                TorqueProfile::Table { times, .. } => times.clone(),
            },
            _ => match self.profile() {
                Some(p) if !p.is_steady() => vec![p.ramp_end()],
                _ => Vec::new(),
            },
        };
        out.retain(|t| *t > 0.0);
        out
    }

    /// Largest joint-side torque N τ_m,max [N·m] (∞ when unlimited).
    pub fn joint_torque_limit(&self) -> f64 {
        match &self.spec.command {
            DriveCommand::Controller {
                torque_limit: Some(l),
                ..
            } => l * self.spec.motor.gear_ratio,
            _ => f64::INFINITY,
        }
    }

    /// The controller's preload (∫e_φ dt, e_φ) at t = 0 that holds a steady start against the
    /// friction: the joint torque c_j ω from the integral if K_i > 0, else from a lag of the
    /// angle if K_p > 0, else from a lag of the speed (then the robot moves at the speed the loop
    /// settles at: returned as the third value, the joint speed at t = 0).
    pub fn steady_preload(&self) -> Result<(f64, f64, f64), ImpactError> {
        let c = self.spec.motor.reflected_friction();
        let speed = self.initial_speed();
        let DriveCommand::Controller { profile, gains, .. } = &self.spec.command else {
            return Ok((0.0, 0.0, speed));
        };
        if !profile.is_steady() || c == 0.0 {
            return Ok((0.0, 0.0, speed));
        }
        let torque = c * speed;
        if torque.abs() > self.joint_torque_limit() {
            return Err(ImpactError::invalid(
                "drive.command.torque_limit",
                self.joint_torque_limit() / self.spec.motor.gear_ratio,
                format!(
                    "at least the friction torque at the steady speed, {:.6e} N·m at the motor",
                    torque.abs() / self.spec.motor.gear_ratio
                ),
            ));
        }
        if gains.ki > 0.0 {
            Ok((torque / gains.ki, 0.0, speed))
        } else if gains.kp > 0.0 {
            Ok((0.0, torque / gains.kp, speed))
        } else {
            // K_d (ω_cmd − ω) = c ω
            Ok((0.0, 0.0, gains.kd * speed / (gains.kd + c)))
        }
    }
}

/// How the struck person is held.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "support", deny_unknown_fields)]
pub enum HeadSupport {
    /// A free head (unconstrained impact).
    Free,
    /// The head on a neck: a spring k_n [N/m] and damper c_n [N·s/m] to the ground.
    Neck {
        /// k_n [N/m], ≥ 0.
        stiffness: f64,
        /// c_n [N·s/m], ≥ 0.
        damping: f64,
    },
    /// The head against a wall (constrained impact): the skin's surface cannot move; the paper's
    /// m_h = 1000 kg case as a support.
    Wall,
}

/// The struck person: head mass, support, and the dome–skin contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Person {
    /// Head mass m_h \[kg\] (ignored against a wall).
    pub m_h: f64,
    /// The support.
    pub support: HeadSupport,
    /// The elastic contact law f = k_c δ^n (Eq. 4).
    pub contact: flexrig_contact::Hertz,
    /// Damping added to it (restitution laws set χ from the approach speed at the onset).
    #[serde(default)]
    pub damping: flexrig_contact::DampingSpec,
    /// The head's speed towards the link at t = 0 [m/s], ≥ 0 (0: at rest, struck by the robot;
    /// > 0: the test bed's roles, the operator striking).
    #[serde(default)]
    pub speed: f64,
}

impl Person {
    /// Checks the fields.
    pub fn validate(&self) -> Result<(), ImpactError> {
        if self.support != HeadSupport::Wall {
            positive("person.m_h", self.m_h, 1e9, "kg")?;
        }
        non_negative("person.speed", self.speed, 1e3, "m/s")?;
        if self.support == HeadSupport::Wall && self.speed != 0.0 {
            return Err(ImpactError::invalid(
                "person.speed",
                self.speed,
                "0 against a wall (the skin cannot move)",
            ));
        }
        if let HeadSupport::Neck { stiffness, damping } = self.support {
            non_negative("person.support.stiffness", stiffness, 1e12, "N/m")?;
            non_negative("person.support.damping", damping, 1e9, "N·s/m")?;
        }
        Ok(())
    }
}

/// The dome rigid with the link's tip section (the rig's `dome_radius_m`, `dome_standoff_m`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Dome {
    /// Sphere radius R \[m\], > 0.
    pub radius_m: f64,
    /// How far the dome's apex sits ahead of the link's axis, towards the person, s \[m\]
    /// (0 < s ≤ 2R; the centre sits R − s behind the axis).
    pub standoff_m: f64,
}

impl Dome {
    /// The test bed's skinned-aluminium dome (§III-B): R = 71.5 mm, apex 30 mm ahead of the
    /// axis (its centre 41.5 mm behind it), as in the bundled rig scenes.
    pub const TEST_BED: Dome = Dome {
        radius_m: 0.0715,
        standoff_m: 0.030,
    };

    /// Checks the fields; the error names them.
    pub fn validate(&self) -> Result<(), ImpactError> {
        positive("dome.radius_m", self.radius_m, 10.0, "m")?;
        positive("dome.standoff_m", self.standoff_m, 2.0 * self.radius_m, "m")?;
        Ok(())
    }

    /// The centre's distance behind the axis d_c = R − s \[m\].
    pub fn centre_offset(&self) -> f64 {
        self.radius_m - self.standoff_m
    }
}

/// Where the person stands.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "placement", deny_unknown_fields)]
pub enum Placement {
    /// The undeformed link's tip touches the skin at this joint angle \[rad\] (0: in contact at
    /// t = 0, with a steady profile the held/free-hub set-up).
    Angle {
        /// φ_c \[rad\].
        angle: f64,
    },
    /// Where the commanded trajectory is at `settle` seconds after its ramp ends (the drive has
    /// settled at the commanded speed when the link arrives).
    AfterRamp {
        /// Time after the ramp's end \[s\], ≥ 0.
        settle: f64,
    },
}

impl Placement {
    /// The contact angle for `drive` \[rad\].
    pub fn angle(&self, drive: &Drive) -> Result<f64, ImpactError> {
        match *self {
            Placement::Angle { angle } => {
                if angle.is_finite() && angle.abs() <= 1e6 {
                    Ok(angle)
                } else {
                    Err(ImpactError::invalid(
                        "placement.angle",
                        angle,
                        "a finite angle within ±1e6 rad",
                    ))
                }
            }
            Placement::AfterRamp { settle } => {
                non_negative("placement.settle", settle, 1e6, "s")?;
                let Some(profile) = drive.profile() else {
                    return Err(ImpactError::invalid(
                        "placement",
                        "after_ramp",
                        "an angle under an open-loop torque (no commanded trajectory)",
                    ));
                };
                Ok(profile.at(profile.ramp_end() + settle).0)
            }
        }
    }
}

pub(crate) fn positive(field: &str, v: f64, max: f64, unit: &str) -> Result<(), ImpactError> {
    if v.is_finite() && v > 0.0 && v <= max {
        Ok(())
    } else {
        Err(ImpactError::invalid(
            field,
            v,
            format!("must lie in (0, {max:e}] {unit}"),
        ))
    }
}

pub(crate) fn non_negative(field: &str, v: f64, max: f64, unit: &str) -> Result<(), ImpactError> {
    if v.is_finite() && (0.0..=max).contains(&v) {
        Ok(())
    } else {
        Err(ImpactError::invalid(
            field,
            v,
            format!("must lie in [0, {max:e}] {unit}"),
        ))
    }
}
