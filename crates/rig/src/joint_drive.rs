//! A motor on the robot joint of the test bed (`[robot.drive]`): flexrig-impact's drive
//! ([`flexrig_impact::drive`]: motor and gear, prescribed trajectory, controller with a torque
//! limit, open-loop torque) moving the rig's robot so that it swings into the operator's block —
//! the paper's §IV roles in the test bed, where the operator struck a robot at rest (§VI).
//!
//! **Where the motor lives.** CJ (a series elastic actuator): the rotor is a second body on the
//! robot axis in the Rapier multibody, a revolute joint of inertia J_m N² (the rotor as the
//! joint sees it); the torsion spring k_θr joins it to the rigid link,
//! J_r φ̈_m = τ_j − c_j φ̇_m − k_θr (φ_m − φ_l), J_l φ̈_l = k_θr (φ_m − φ_l) + M_contact
//! (J_r = J_m N², c_j = c_m N², Eq. 1–3). Rapier integrates both hinges with the rig's velocity
//! Verlet step ([`crate::coupling`]); the drive's torque is a load like the spring's. A
//! prescribed trajectory is an ideal position source: the rotor's angle is the command
//! φ_m ≡ φ_cmd(t) (no rotor body) and the motor delivers τ_j = J_r α_cmd + c_j ω_cmd +
//! k_θr (φ_m − φ_l). CL: the beam's root node is the hub (flexrig-beam's `RootSupport::Hub`,
//! inertia J_r, the beam clamped to it); the drive's torque is the hub's nodal moment.
//!
//! **Sides and signs.** The drive's joint angle θ and speed are positive towards the operator
//! and counted from the link's start (the driven scenes' convention); the rig's hinge angle φ
//! (about +z, the world's) is φ = A − θ, A the placement's angle, so that the undeformed link
//! touches the block hanging at rest at φ = 0. Torques: τ_φ = −τ_j.
//!
//! **Controller at the synchronised instant.** The rig keeps angles and rates at the same
//! instant; the rotor's rate after a step solves ω = ω_{n+½} + (h/2) a(ω) with the controller's
//! speed term and the friction in a(ω) — linear, solved exactly, on the limit's branch when the
//! unlimited torque exceeds it. The integral ∫e_φ dt is advanced by the trapezoidal rule.

use flexrig_impact::ImpactError;
use flexrig_impact::drive::{Drive, DriveCommand, Gains, Profile, TorqueProfile};
use serde::{Deserialize, Serialize};

use crate::RigError;
use crate::hinge::HingeState;

/// A motor on the robot joint, in the vocabulary of the driven scenes' `[drive]` and
/// `[placement]` sections (`docs/driven.md`): the motor and gear, what moves it, and where the
/// link starts. The joint angle and speed of the drive are positive towards the operator.
///
/// CJ: the torsion spring k_θr sits between the motor's output and the rigid link (a series
/// elastic actuator). CL: the beam is clamped to the motor's hub.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotDriveSpec {
    /// Rotor inertia J_m \[kg·m²\], gear ratio N and viscous friction c_m \[N·m·s/rad\] at the
    /// motor shaft.
    pub motor: flexrig_impact::drive::Motor,
    /// A prescribed trajectory, a controller with its profile, gains and torque limit, or an
    /// open-loop torque.
    pub command: flexrig_impact::drive::DriveCommand,
    /// Where the link starts: `angle` \[rad\] of joint travel before its undeformed tip touches
    /// the operator's block hanging at the bottom of its swing (0: touching, the test bed), or
    /// `after_ramp` with `settle` \[s\]: the commanded motion reaches the block `settle` seconds
    /// after its ramp.
    pub placement: flexrig_impact::drive::Placement,
}

/// Largest placement angle \[rad\]: the link starts at most a half turn from the block.
pub const MAX_PLACEMENT_RAD: f64 = std::f64::consts::PI;

/// The validated drive of a scene's robot joint.
#[derive(Debug, Clone, PartialEq)]
pub struct JointDrive {
    drive: Drive,
    /// Joint travel from the start to the touching configuration A \[rad\].
    start_angle: f64,
    /// J_m N² [kg·m²].
    inertia: f64,
    /// c_m N² [N·m·s/rad].
    friction: f64,
    /// N τ_m,max [N·m] (∞: unlimited).
    limit: f64,
    /// The controller's preload at t = 0 (∫e_φ dt, e_φ, joint speed), drive convention.
    preload: (f64, f64, f64),
}

/// The drive's state at one instant (rig convention: angles about +z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotorSync {
    /// Hub (motor output) angle \[rad\] and rate [rad/s].
    pub state: HingeState,
    /// Hub angular acceleration [rad/s²].
    pub accel: f64,
    /// Joint-side drive torque about +z [N·m] (what the motor applies after the gear).
    pub torque: f64,
    /// The controller's ∫(φ_cmd − φ) dt [rad·s] (0 without a controller).
    pub integral: f64,
}

/// The drive's channels at one instant, in the drive's convention (joint angle from the start,
/// positive towards the operator), for recorders.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DriveFrame {
    /// Commanded joint angle \[rad\] (NaN-free: the actual one under an open-loop torque).
    pub commanded_angle_rad: f64,
    /// Commanded joint speed [rad/s] (the actual one under an open-loop torque).
    pub commanded_speed_rad_s: f64,
    /// Motor-side (hub) joint angle \[rad\].
    pub motor_angle_rad: f64,
    /// Motor-side (hub) joint speed [rad/s].
    pub motor_speed_rad_s: f64,
    /// Link angle \[rad\] (CJ: the rigid link after the spring; CL: the hub's).
    pub link_angle_rad: f64,
    /// Link speed [rad/s].
    pub link_speed_rad_s: f64,
    /// Joint-side motor torque τ_j = N τ_m [N·m].
    pub joint_torque_nm: f64,
    /// Motor-shaft torque τ_m [N·m].
    pub motor_torque_nm: f64,
    /// Deflection of the link's tip from the hub's line \[m\], positive towards the operator
    /// (CJ: L sin(φ_m − φ_l) of the rigid link on its spring; CL: the beam's tip in the hub's
    /// frame).
    pub link_deflection_m: f64,
    /// Elastic moment of the link at the joint [N·m] (CJ: k_θr (φ_m − φ_l); CL: the beam's
    /// root moment).
    pub spring_moment_nm: f64,
    /// Work of the joint-side motor torque since the start, ∫ τ_j ω_m dt \[J\].
    pub motor_work_j: f64,
    /// Energy dissipated by the drive's friction since the start \[J\].
    pub friction_dissipated_j: f64,
}

/// What the drive did over a run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DriveSummary {
    /// Work of the motor's joint-side torque ∫ τ_j ω_m dt \[J\].
    pub motor_work_j: f64,
    /// Energy dissipated by the drive's friction ∫ c_j ω_m² dt \[J\].
    pub friction_dissipated_j: f64,
    /// Largest |τ_j| over the run [N·m].
    pub peak_joint_torque_nm: f64,
    /// Time \[s\] the controller spent at its torque limit (steps that end there); 0 without a
    /// limit or when the command never needed more.
    pub time_at_torque_limit_s: f64,
    /// Deflection of the link's tip from the hub's line at the contact onset \[m\], positive
    /// towards the operator (the drive's acceleration pre-bends the link; negative: the tip
    /// lags).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pre_impact_deflection_m: Option<f64>,
    /// Link speed at the contact onset [rad/s] (towards the operator).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub link_speed_at_onset_rad_s: Option<f64>,
    /// The commanded joint speed at the contact onset [rad/s] (none under an open-loop torque).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub commanded_speed_at_onset_rad_s: Option<f64>,
}

/// An impact error as a scene error: its field is under `robot.` in the scene file.
fn scene_error(e: ImpactError) -> RigError {
    match e {
        ImpactError::InvalidParameter {
            field,
            value,
            allowed,
        } => {
            let field = if field.starts_with("drive.") {
                format!("robot.{field}")
            } else {
                format!("robot.drive.{field}")
            };
            RigError::InvalidScene {
                field,
                value,
                allowed,
            }
        }
        other => RigError::InvalidScene {
            field: "robot.drive".into(),
            value: "(the drive)".into(),
            allowed: other.to_string(),
        },
    }
}

impl JointDrive {
    /// Validates `spec`; an error names the scene field (`robot.drive.motor.gear_ratio`, …).
    pub fn new(spec: &RobotDriveSpec) -> Result<Self, RigError> {
        let drive = Drive::new(spec.motor, spec.command.clone()).map_err(scene_error)?;
        let start_angle = spec.placement.angle(&drive).map_err(scene_error)?;
        let speed = match drive.command() {
            DriveCommand::OpenLoop { initial_speed, .. } => *initial_speed,
            _ => drive.profile().map_or(0.0, |p| p.final_speed()),
        };
        let after_ramp = matches!(
            spec.placement,
            flexrig_impact::drive::Placement::AfterRamp { .. }
        );
        if after_ramp && speed <= 0.0 && !matches!(drive.command(), DriveCommand::OpenLoop { .. }) {
            return Err(crate::error::invalid(
                "robot.drive.command.profile.speed",
                flexrig_contact::validate::display(speed),
                "must be > 0 rad/s (towards the operator) for placement = \"after_ramp\", \
                 which puts the block where the commanded motion arrives",
            ));
        }
        if !(0.0..=MAX_PLACEMENT_RAD).contains(&start_angle) {
            let field = match spec.placement {
                flexrig_impact::drive::Placement::Angle { .. } => "robot.drive.placement.angle",
                flexrig_impact::drive::Placement::AfterRamp { .. } => {
                    "robot.drive.placement.settle"
                }
            };
            return Err(crate::error::invalid(
                field,
                flexrig_contact::validate::display(start_angle),
                &format!(
                    "must place the link between 0 and {MAX_PLACEMENT_RAD:.6} rad of travel \
                     before the block (a positive commanded speed moves it towards the operator)"
                ),
            ));
        }
        let preload = drive.steady_preload().map_err(scene_error)?;
        let motor = drive.motor();
        if let DriveCommand::OpenLoop {
            torque: TorqueProfile::Constant { torque },
            initial_speed,
        } = drive.command()
            && *torque <= 0.0
            && *initial_speed <= 0.0
            && start_angle > 0.0
        {
            return Err(crate::error::invalid(
                "robot.drive.command.torque.torque",
                flexrig_contact::validate::display(*torque),
                "must move the link towards the operator (a positive torque or initial_speed) \
                 when it starts away from the block",
            ));
        }
        if start_angle > 0.0
            && speed <= 0.0
            && !matches!(drive.command(), DriveCommand::OpenLoop { .. })
        {
            return Err(crate::error::invalid(
                "robot.drive.command.profile.speed",
                flexrig_contact::validate::display(speed),
                "must be > 0 rad/s (towards the operator) when the link starts away from the \
                 block (robot.drive.placement)",
            ));
        }
        Ok(JointDrive {
            start_angle,
            inertia: motor.reflected_inertia(),
            friction: motor.reflected_friction(),
            limit: drive.joint_torque_limit(),
            preload,
            drive,
        })
    }

    /// The drive as flexrig-impact describes it.
    pub fn drive(&self) -> &Drive {
        &self.drive
    }

    /// Joint travel A \[rad\] from the start to the touching configuration.
    pub fn start_angle(&self) -> f64 {
        self.start_angle
    }

    /// Rotor inertia at the joint J_m N² [kg·m²].
    pub fn inertia(&self) -> f64 {
        self.inertia
    }

    /// Friction at the joint c_m N² [N·m·s/rad].
    pub fn friction(&self) -> f64 {
        self.friction
    }

    /// True for a prescribed trajectory (the hub follows the command exactly).
    pub fn is_prescribed(&self) -> bool {
        matches!(self.drive.command(), DriveCommand::Trajectory { .. })
    }

    /// Largest link tip speed [m/s] the drive aims at, for a link of `length` \[m\]: the
    /// profile's final speed, or the open-loop initial speed (an estimate for step sizes).
    pub fn tip_speed_estimate(&self, length: f64) -> f64 {
        let speed = match self.drive.command() {
            DriveCommand::OpenLoop { initial_speed, .. } => *initial_speed,
            _ => self.drive.profile().map_or(0.0, |p| p.final_speed()),
        };
        speed.abs() * length
    }

    /// Simulated time \[s\] the link takes to reach the block under its command (the ramp plus
    /// the travel left at the final speed); 1 s for an open-loop torque.
    pub fn approach_time_estimate(&self) -> f64 {
        match self.drive.profile() {
            Some(p) => {
                let speed = p.final_speed().abs();
                let (angle_at_ramp_end, _, _) = p.at(p.ramp_end());
                let rest = (self.start_angle - angle_at_ramp_end).max(0.0);
                p.ramp_end() + if speed > 0.0 { rest / speed } else { 0.0 }
            }
            None => 1.0,
        }
    }

    /// The commanded hub angle, rate and acceleration at `t` in the rig's convention, if the
    /// command has a profile.
    pub fn commanded(&self, t: f64) -> Option<(f64, f64, f64)> {
        self.drive.profile().map(|p: &Profile| {
            let (theta, omega, alpha) = p.at(t);
            (self.start_angle - theta, -omega, -alpha)
        })
    }

    /// The hub's and the link's state at t = 0 and the controller's integral (rig convention):
    /// steady profiles start everything turning at the speed, springs unloaded, the controller
    /// preloaded against the friction; the others at rest at the placement.
    pub fn initial(&self) -> (HingeState, HingeState, f64) {
        let (integral, error, speed) = self.preload;
        let angle = self.start_angle + error;
        // 0 − x, not −x: a drive at rest starts at +0 like the test bed's link
        let hub = HingeState {
            angle,
            rate: 0.0 - speed,
        };
        (hub, hub, 0.0 - integral)
    }

    /// The controller's angle error φ_cmd − φ at `t` for hub angle `angle` (0 otherwise).
    pub fn angle_error(&self, t: f64, angle: f64) -> f64 {
        match (self.drive.command(), self.commanded(t)) {
            (DriveCommand::Controller { .. }, Some((c, _, _))) => c - angle,
            _ => 0.0,
        }
    }

    /// The hub at `t` under a prescribed trajectory: its state and acceleration.
    pub fn prescribed(&self, t: f64) -> Option<(HingeState, f64)> {
        if !self.is_prescribed() {
            return None;
        }
        self.commanded(t)
            .map(|(angle, rate, accel)| (HingeState { angle, rate }, accel))
    }

    /// The drive's state after a step of `h` \[s\] ending at `t`: the hub at `angle` with the
    /// rate `lagging_rate` Rapier holds (half a step behind), the integral `integral` at `t`,
    /// and the elastic moment `spring` [N·m] the link puts on the hub (−k_θr (φ_m − φ_l) for
    /// the CJ). h = 0: the rate is already synchronised.
    pub fn synchronise(
        &self,
        t: f64,
        angle: f64,
        lagging_rate: f64,
        integral: f64,
        spring: f64,
        h: f64,
    ) -> RotorSync {
        if let Some((state, accel)) = self.prescribed(t) {
            let torque = self.inertia * accel + self.friction * state.rate - spring;
            return RotorSync {
                state,
                accel,
                torque,
                integral,
            };
        }
        let j = self.inertia;
        let c = self.friction;
        let half = 0.5 * h / j;
        let with_torque = |tau: f64, damping: f64| {
            (lagging_rate + half * (tau + spring)) / (1.0 + half * (damping + c))
        };
        let (rate, torque) = match self.drive.command() {
            DriveCommand::Controller { gains, .. } => {
                let Gains { kp, kd, ki } = *gains;
                let (c_angle, c_rate, _) = self.commanded(t).expect("a controller has a profile");
                let p = kp * (c_angle - angle) + kd * c_rate + ki * integral;
                let rate = with_torque(p, kd);
                let u = p - kd * rate;
                if u.abs() <= self.limit {
                    (rate, u)
                } else {
                    let tau = self.limit.copysign(u);
                    (with_torque(tau, 0.0), tau)
                }
            }
            DriveCommand::OpenLoop { torque, .. } => {
                let tau = -self.drive.motor().gear_ratio * torque.at(t);
                (with_torque(tau, 0.0), tau)
            }
            DriveCommand::Trajectory { .. } => unreachable!("handled above"),
        };
        RotorSync {
            state: HingeState { angle, rate },
            accel: (torque - c * rate + spring) / j,
            torque,
            integral,
        }
    }

    /// The drive's torque on the free hub of a compliant link over a step of `h` \[s\] from
    /// `start` at `t0` (rig convention), affine in the hub's angle and rate at the step's end
    /// t₁ = t₀ + h, so that the link's integrator takes it implicitly: a controller's
    /// τ = K_p (φ_cmd − φ) + K_d (ω_cmd − φ̇) + K_i z₁ with z₁ = z₀ + (h/2)(e₀ + φ_cmd − φ) is
    /// (K_p φ_cmd + K_d ω_cmd + K_i (z₀ + (h/2)(e₀ + φ_cmd))) − (K_p + K_i h/2) φ − K_d φ̇; an
    /// open-loop torque is the moment −N τ_m(t₁). Returns the unlimited law and the one to
    /// step with: at the torque limit (a constant moment) when the unlimited torque at the
    /// predicted end (φ₀ + h φ̇₀ + h² φ̈₀/2, φ̇₀ + h φ̈₀) exceeds it. `None` for a prescribed
    /// trajectory. h = 0: the law at t₀ itself.
    pub fn hub_law(&self, t0: f64, h: f64, start: &RotorSync) -> Option<(HubLaw, HubLaw)> {
        let t1 = t0 + h;
        let law = match self.drive.command() {
            DriveCommand::Trajectory { .. } => return None,
            DriveCommand::OpenLoop { torque, .. } => HubLaw {
                stiffness: 0.0,
                damping: 0.0,
                moment: -self.drive.motor().gear_ratio * torque.at(t1),
            },
            DriveCommand::Controller { gains, .. } => {
                let Gains { kp, kd, ki } = *gains;
                let (c_angle, c_rate, _) = self.commanded(t1).expect("a controller has a profile");
                let e0 = self.angle_error(t0, start.state.angle);
                HubLaw {
                    stiffness: kp + 0.5 * h * ki,
                    damping: kd,
                    moment: kp * c_angle
                        + kd * c_rate
                        + ki * (start.integral + 0.5 * h * (e0 + c_angle)),
                }
            }
        };
        let s = start.state;
        let predicted = law.torque(
            s.angle + h * (s.rate + 0.5 * h * start.accel),
            s.rate + h * start.accel,
        );
        Some((law, self.limited(law, predicted)))
    }

    /// True when the joint torque has a finite limit N τ_m,max.
    pub fn is_torque_limited(&self) -> bool {
        self.limit.is_finite()
    }

    /// `law`, or the constant torque at the limit when the unlimited torque `torque` [N·m]
    /// exceeds it.
    pub fn limited(&self, law: HubLaw, torque: f64) -> HubLaw {
        if torque.abs() <= self.limit {
            law
        } else {
            HubLaw {
                stiffness: 0.0,
                damping: 0.0,
                moment: self.limit.copysign(torque),
            }
        }
    }

    /// The channels of a frame: hub `hub`, link `link`, joint torque `torque` (rig convention),
    /// the elastic moment on the hub `spring` and the link's deflection \[m\] (towards the
    /// operator), at `t`; the motor's work and the friction's so far.
    pub fn frame(
        &self,
        t: f64,
        hub: HingeState,
        link: HingeState,
        torque: f64,
        (spring, link_deflection_m): (f64, f64),
        (motor_work_j, friction_dissipated_j): (f64, f64),
    ) -> DriveFrame {
        let a = self.start_angle;
        let (commanded_angle_rad, commanded_speed_rad_s) = match self.drive.profile() {
            Some(p) => {
                let (theta, omega, _) = p.at(t);
                (theta, omega)
            }
            None => (a - hub.angle, -hub.rate),
        };
        DriveFrame {
            commanded_angle_rad,
            commanded_speed_rad_s,
            motor_angle_rad: a - hub.angle,
            motor_speed_rad_s: -hub.rate,
            link_angle_rad: a - link.angle,
            link_speed_rad_s: -link.rate,
            joint_torque_nm: -torque,
            motor_torque_nm: -torque / self.drive.motor().gear_ratio,
            link_deflection_m,
            spring_moment_nm: spring,
            motor_work_j,
            friction_dissipated_j,
        }
    }
}

/// The drive's torque on a free hub over a step, affine in the hub's angle φ and rate φ̇ at
/// the step's end (rig convention, about +z): τ = `moment` − `stiffness` φ − `damping` φ̇.
/// The hub's root support takes the stiffness and the damping (with the friction) implicitly;
/// the moment is the root node's nodal moment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HubLaw {
    /// ∂τ/∂(−φ) [N·m/rad] (a position loop's K_p, plus K_i h/2 of its integral).
    pub stiffness: f64,
    /// ∂τ/∂(−φ̇) [N·m·s/rad] (the loop's K_d; the friction is added by the link).
    pub damping: f64,
    /// The rest [N·m].
    pub moment: f64,
}

impl HubLaw {
    /// The torque [N·m] at hub angle `angle` \[rad\] and rate `rate` [rad/s].
    pub fn torque(&self, angle: f64, rate: f64) -> f64 {
        self.moment - self.stiffness * angle - self.damping * rate
    }
}
