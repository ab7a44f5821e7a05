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
                    format!("{angle} rad"),
                    format!(
                        "an angle the commanded trajectory reaches within horizon_s = {} s \
                         (it reaches {reach:.6} rad)",
                        self.horizon_s
                    ),
                ));
            }
        }
        Ok(())
    }
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
            self.samples.push(sample());
        }
    }
}
