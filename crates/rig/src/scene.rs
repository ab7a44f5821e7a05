//! Scene files (TOML): one run of the drop-pendulum test bed. See `docs/scenes.md`.
//!
//! A [`SceneFile`] is what the TOML holds; [`Scene::from_file`] validates it against the
//! materials file and derives every physical quantity once ([`Scene`] is immutable). Errors name
//! the field path (`robot.thickness_m`), the value and what is allowed.

pub use flexrig_contact::DampingSpec;
use flexrig_contact::{ContactLaw, Hertz};
use serde::{Deserialize, Serialize};

use crate::RigError;
pub use crate::free_flight::{ContactPolicy, SwingPolicy};
pub use crate::joint_drive::RobotDriveSpec;

/// Compliant joint (rigid link on a torsion spring) or compliant link (flexible beam).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Design {
    /// Rigid link on a torsion spring k_θr (paper Fig. 1a).
    Cj,
    /// Flexible beam clamped at the robot axis (paper Fig. 1b).
    Cl,
}

impl std::fmt::Display for Design {
    /// The paper's abbreviation: "CJ" or "CL".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Design::Cj => "CJ",
            Design::Cl => "CL",
        })
    }
}

/// How the run starts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "from", deny_unknown_fields)]
pub enum Start {
    /// Released at rest from `release_angle_deg` (from the vertical, away from the robot).
    Release {
        /// Release angle \[deg\], in (0, 170].
        release_angle_deg: f64,
    },
    /// At the instant of contact, with the swing speed of a release from `release_angle_deg`
    /// (energy of the compound pendulum): the swing is not integrated.
    Contact {
        /// Release angle \[deg\] whose swing speed is used, in (0, 170].
        release_angle_deg: f64,
    },
    /// At any angle with any angular velocity (the general initial condition).
    Moving {
        /// Angle from the vertical \[deg\], in [−170, 170]; negative on the side away from the robot.
        angle_deg: f64,
        /// Angular velocity [rad/s], positive towards the robot.
        angular_velocity_rad_s: f64,
    },
}

/// Angular speed [rad/s] at the bottom of the swing of a compound pendulum (mass \[kg\], centre of
/// mass `com_distance` \[m\] below the pivot, `inertia` [kg·m²] about it) that is at `angle` \[rad\]
/// with `rate` [rad/s]: ½ J ω_b² = ½ J ω² + M g l_c (1 − cos φ).
pub fn rate_at_bottom(
    mass: f64,
    com_distance: f64,
    inertia: f64,
    g: f64,
    angle: f64,
    rate: f64,
) -> f64 {
    (rate * rate + 2.0 * mass * g * com_distance * (1.0 - angle.cos()) / inertia).sqrt()
}

/// The operator's initial hinge state and the angular speed it will have at the contact (the
/// bottom of the swing), from the energy of the compound pendulum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InitialSwing {
    /// Angle \[rad\] from the vertical, positive towards the robot.
    pub angle: f64,
    /// Angular velocity [rad/s].
    pub rate: f64,
    /// Angular speed at the bottom of the swing [rad/s].
    pub rate_at_contact: f64,
    /// True when the run starts touching.
    pub starts_in_contact: bool,
}

impl Start {
    /// The initial swing of a pendulum of mass `mass` \[kg\], centre of mass `com_distance` \[m\]
    /// below the pivot and inertia `inertia` [kg·m²] about it, under gravity `g` [m/s²]:
    /// ½ J ω_b² = ½ J ω₀² + M g l_c (1 − cos φ₀).
    pub fn initial_swing(
        &self,
        mass: f64,
        com_distance: f64,
        inertia: f64,
        g: f64,
    ) -> InitialSwing {
        let bottom =
            |angle: f64, rate: f64| rate_at_bottom(mass, com_distance, inertia, g, angle, rate);
        match *self {
            Start::Release { release_angle_deg } => {
                let angle = -release_angle_deg.to_radians();
                InitialSwing {
                    angle,
                    rate: 0.0,
                    rate_at_contact: bottom(angle, 0.0),
                    starts_in_contact: false,
                }
            }
            Start::Contact { release_angle_deg } => {
                let rate = bottom(release_angle_deg.to_radians(), 0.0);
                InitialSwing {
                    angle: 0.0,
                    rate,
                    rate_at_contact: rate,
                    starts_in_contact: true,
                }
            }
            Start::Moving {
                angle_deg,
                angular_velocity_rad_s,
            } => {
                let angle = angle_deg.to_radians();
                InitialSwing {
                    angle,
                    rate: angular_velocity_rad_s,
                    rate_at_contact: bottom(angle, angular_velocity_rad_s),
                    starts_in_contact: false,
                }
            }
        }
    }
}

/// The operator pendulum: a light arm with the skinned block at its end.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OperatorSpec {
    /// Pivot to block centre \[m\].
    pub arm_length_m: f64,
    /// Mass of the arm, a uniform rod from the pivot to the block centre \[kg\].
    pub arm_mass_kg: f64,
    /// Block material in the materials file (sets its Hertz law and, by default, its mass).
    pub block_material: String,
    /// Block mass \[kg\]; default: the material's block mass.
    #[serde(default)]
    pub block_mass_kg: Option<f64>,
    /// Block size \[m\]: along the arm's swing axis (x), the strike direction (y), vertical (z).
    pub block_size_m: [f64; 3],
    /// How the run starts.
    pub start: Start,
}

/// The robot link with its payload, force sensor and dome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSpec {
    /// CJ or CL.
    pub design: Design,
    /// Link length, axis to payload \[m\].
    pub length_m: f64,
    /// Link width (in the plane of the strike for CJ) \[m\].
    pub width_m: f64,
    /// Link thickness (the bending direction of the CL) \[m\].
    pub thickness_m: f64,
    /// Young's modulus of the link \[Pa\].
    pub youngs_modulus_pa: f64,
    /// Density of the link [kg/m³].
    pub density_kg_m3: f64,
    /// Payload at the tip, including force sensor and dome \[kg\].
    pub payload_kg: f64,
    /// Dome radius \[m\].
    pub dome_radius_m: f64,
    /// Distance from the link axis to the dome apex, towards the operator \[m\].
    pub dome_standoff_m: f64,
    /// CJ torsion spring k_θr [N·m/rad], or `"matched"`: 3EI/L of this link (Eq. 3), the
    /// default; `"matched"` follows the link when a sweep changes it.
    #[serde(default)]
    pub torsion_spring_nm_per_rad: Option<TorsionSpring>,
    /// CL: number of beam elements.
    #[serde(default = "default_beam_elements")]
    pub beam_elements: usize,
    /// A motor on the robot joint (`[robot.drive]`); absent: the link at rest on a fixed axis
    /// (the paper's test bed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub drive: Option<RobotDriveSpec>,
}

/// The CJ torsion spring as a scene gives it: a stiffness, or the link's own 3EI/L.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TorsionSpring {
    /// k_θr [N·m/rad].
    Value(f64),
    /// 3EI/L of the link (Eq. 3): the CJ as stiff as the CL link it stands for.
    Matched,
}

impl TorsionSpring {
    /// The stiffness [N·m/rad] given, `None` for the matched spring.
    pub fn value(self) -> Option<f64> {
        match self {
            TorsionSpring::Value(k) => Some(k),
            TorsionSpring::Matched => None,
        }
    }
}

impl Serialize for TorsionSpring {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            TorsionSpring::Value(k) => serializer.serialize_f64(*k),
            TorsionSpring::Matched => serializer.serialize_str("matched"),
        }
    }
}

impl<'de> Deserialize<'de> for TorsionSpring {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = TorsionSpring;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a stiffness in N·m/rad or \"matched\" (3EI/L of the link)")
            }
            fn visit_f64<E: serde::de::Error>(self, v: f64) -> Result<TorsionSpring, E> {
                Ok(TorsionSpring::Value(v))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<TorsionSpring, E> {
                Ok(TorsionSpring::Value(v as f64))
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<TorsionSpring, E> {
                Ok(TorsionSpring::Value(v as f64))
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<TorsionSpring, E> {
                if v == "matched" {
                    Ok(TorsionSpring::Matched)
                } else {
                    Err(E::invalid_value(serde::de::Unexpected::Str(v), &self))
                }
            }
        }
        deserializer.deserialize_any(Visitor)
    }
}

fn default_beam_elements() -> usize {
    16
}

/// The contact law between dome and block.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    /// Hertz stiffness [N/m^n]; default: the block material's fit.
    #[serde(default)]
    pub k: Option<f64>,
    /// Hertz exponent; default: the block material's fit.
    #[serde(default)]
    pub n: Option<f64>,
    /// Damping.
    #[serde(default = "no_damping")]
    pub damping: DampingSpec,
}

fn no_damping() -> DampingSpec {
    DampingSpec::None {}
}

/// Step policy.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverSpec {
    /// Step during the free swing \[s\].
    pub swing_step_s: f64,
    /// Steps per estimated contact duration.
    pub contact_steps: usize,
    /// Cap on the number of steps.
    #[serde(default = "default_max_steps")]
    pub max_steps: usize,
    /// How the CL beam is solved (default: the full corotational FE beam).
    #[serde(default)]
    pub beam: BeamSolverSpec,
    /// How the rig moves out of contact: `"adaptive"` (default; DOP853 with the onset located
    /// as an event) or `"fixed"` (Rapier steps of `swing_step_s`).
    #[serde(default)]
    pub swing: SwingPolicy,
    /// How the contact is integrated: `"auto"` (default: `"adaptive"` for a CJ without a drive
    /// on its robot joint and with the adaptive swing, whatever the stop; `"fixed"` otherwise),
    /// `"fixed"` (Rapier's steps, `contact_steps` per contact) or `"adaptive"` (the CJ's two
    /// hinges with the contact force by DOP853 at `contact_rtol`, peak and separation located
    /// on its dense output). [`crate::RunSummary::contact_integration`] says which ran.
    #[serde(default, skip_serializing_if = "ContactPolicy::is_auto")]
    pub contact: ContactPolicy,
    /// Relative tolerance of the adaptive contact (of the indentation and the approach speed;
    /// default [`crate::free_flight::CONTACT_RTOL`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_rtol: Option<f64>,
}

/// How the finite-element link is solved (design `cl`; ignored for `cj`). (Struct variants, so
/// that a field a model does not take, e.g. `modes` with `linear`, is an error.)
///
/// The default, `auto`, takes the element that is cheapest at equal error for the run: the
/// corotational beam for a run that stops at the peak or at separation (the two elements agree
/// on the bundled peaks within 5e-7 and converge alike in the mesh; the corotational one costs
/// less per step), the ANCF beam with the energy-conserving step for a run to a duration (its
/// free vibration keeps the energy to 1e-9 where the corotational beam drifts or blows up).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "model", deny_unknown_fields)]
pub enum BeamSolverSpec {
    /// Corotational for a run to the peak or to separation, ANCF for a run to a duration.
    Auto {},
    /// Every FE degree of freedom, corotational (large deflection): the reference.
    Corotational {},
    /// Every FE degree of freedom, linear kinematics (small deflection).
    Linear {},
    /// Every FE degree of freedom, the ANCF cable element (positions and slopes, constant
    /// consistent mass, fourth order in the mesh); at ρ∞ = 1 stepped by the energy-conserving
    /// midpoint rule, which keeps the energy of long runs to the Newton tolerance.
    Ancf {},
    /// The shortcut for small deflections: the linear beam reduced to its lowest `modes` modes
    /// plus static correction shapes for the tip force and moment (flexrig_beam::reduced).
    Modal {
        /// Number of kept modes, ≥ 1 (and at most the beam's DOFs).
        modes: usize,
    },
}

impl Default for BeamSolverSpec {
    fn default() -> Self {
        BeamSolverSpec::Auto {}
    }
}

impl BeamSolverSpec {
    /// The concrete solver of `auto` for a run that stops at `stop` (a compliant link on a
    /// drive takes the corotational beam whatever the stop: it turns through large angles).
    pub fn resolve(self, stop: StopSpec) -> BeamSolverSpec {
        match (self, stop) {
            (BeamSolverSpec::Auto {}, StopSpec::Duration { .. }) => BeamSolverSpec::Ancf {},
            (BeamSolverSpec::Auto {}, _) => BeamSolverSpec::Corotational {},
            (other, _) => other,
        }
    }
}

fn default_max_steps() -> usize {
    10_000_000
}

/// When the run stops.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "at", deny_unknown_fields)]
pub enum StopSpec {
    /// At the peak contact force.
    Peak,
    /// When the dome and the block separate.
    Separation,
    /// Every contact of the swing: after the last separation, when the operator's block,
    /// having moved away from the dome, turns back at the apex of its rebound (a later contact
    /// would be the return swing under gravity, a new strike of the test bed).
    Rebound,
    /// After a fixed simulated time.
    Duration {
        /// Simulated time \[s\].
        duration_s: f64,
    },
}

impl StopSpec {
    /// The stop in words, for messages ("the separation of the first contact",
    /// "t = 5 s (stop.duration_s)").
    pub fn describe(&self) -> String {
        match *self {
            StopSpec::Peak => "the peak of the first contact (stop.at = \"peak\")".into(),
            StopSpec::Separation => {
                "the separation of the first contact (stop.at = \"separation\")".into()
            }
            StopSpec::Rebound => {
                "the operator's turn at the apex of its rebound (stop.at = \"rebound\")".into()
            }
            StopSpec::Duration { duration_s } => format!(
                "t = {} s (stop.duration_s)",
                flexrig_contact::validate::display(duration_s)
            ),
        }
    }
}

/// What is recorded.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RecordSpec {
    /// Sensor sampling rate \[Hz\], independent of the step.
    pub sample_rate_hz: f64,
}

/// The scene file as written in TOML.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneFile {
    /// Short name.
    pub name: String,
    /// What the scene is and why its values were chosen.
    #[serde(default)]
    pub description: String,
    /// Gravitational acceleration [m/s²] (acts along −z).
    pub gravity_mps2: f64,
    /// The operator pendulum.
    pub operator: OperatorSpec,
    /// The robot link.
    pub robot: RobotSpec,
    /// The contact law.
    pub contact: ContactSpec,
    /// Step policy.
    pub solver: SolverSpec,
    /// Stop condition.
    pub stop: StopSpec,
    /// Sensors.
    pub record: RecordSpec,
}

/// One plausibility warning about a scene field: valid, but it looks like a mistake (the
/// checks are in [`crate::plausibility`]).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Warning {
    /// The scene field it is about (dotted path).
    pub field: String,
    /// What looks wrong and what to do.
    pub message: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.field, self.message)
    }
}

/// A validated scene with its derived quantities.
#[derive(Debug, Clone)]
pub struct Scene {
    /// The file it came from.
    pub file: SceneFile,
    /// Block mass \[kg\].
    pub block_mass_kg: f64,
    /// Elastic Hertz law of the contact.
    pub hertz: Hertz,
    /// Link mass m_r = ρ w t L \[kg\].
    pub link_mass_kg: f64,
    /// Bending stiffness of the link in its compliant direction, EI = E w t³/12 [N·m²].
    pub link_ei: f64,
    /// CJ torsion spring k_θr [N·m/rad].
    pub torsion_spring: f64,
    /// Plausibility warnings: what is valid but looks like a mistake
    /// ([`crate::plausibility`]).
    pub warnings: Vec<Warning>,
    /// The validated motor on the robot joint (`robot.drive`), if any.
    pub drive: Option<crate::joint_drive::JointDrive>,
}

impl Scene {
    /// The contact law for an impact at approach speed `v0` [m/s] (damping models need it).
    pub fn contact_law(&self, v0: f64) -> Result<Box<dyn ContactLaw>, RigError> {
        Ok(self.file.contact.damping.law(self.hertz, v0)?)
    }

    /// How the contact of this scene is integrated: `solver.contact` resolved
    /// ([`ContactPolicy::resolved`]), [`ContactPolicy::Adaptive`] or [`ContactPolicy::Fixed`].
    pub fn contact_integration(&self) -> ContactPolicy {
        let s = &self.file.solver;
        s.contact.resolved(
            self.file.robot.design == Design::Cj,
            s.swing,
            self.drive.is_some(),
        )
    }
}
