//! Scene files (TOML): one run of the drop-pendulum test bed. See `docs/scenes.md`.
//!
//! A [`SceneFile`] is what the TOML holds; [`Scene::from_file`] validates it against the
//! materials file and derives every physical quantity once ([`Scene`] is immutable). Errors name
//! the field path (`robot.thickness_m`), the value and what is allowed.

pub use flexrig_contact::DampingSpec;
use flexrig_contact::{ContactLaw, Hertz, Materials};
use serde::{Deserialize, Serialize};

use crate::RigError;
use crate::error::invalid;
pub use crate::free_flight::SwingPolicy;
use crate::geometry::rate_at_bottom;
use crate::limits;

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
    /// CJ torsion spring k_θr [N·m/rad]; default 3EI/L (Eq. 3).
    #[serde(default)]
    pub torsion_spring_nm_per_rad: Option<f64>,
    /// CL: number of beam elements.
    #[serde(default = "default_beam_elements")]
    pub beam_elements: usize,
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
    /// The concrete solver of `auto` for a run that stops at `stop`.
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
    /// After a fixed simulated time.
    Duration {
        /// Simulated time \[s\].
        duration_s: f64,
    },
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
}

impl Scene {
    /// Parses a scene from TOML text and validates it.
    pub fn from_toml_str(text: &str, materials: &Materials) -> Result<Self, RigError> {
        let file: SceneFile =
            toml::from_str(text).map_err(|e| RigError::SceneSyntax(syntax_message(text, &e)))?;
        Self::from_file(file, materials)
    }

    /// Validates a parsed scene: every quantity in its physical range ([`crate::limits`]), then
    /// the run's work budget.
    pub fn from_file(file: SceneFile, materials: &Materials) -> Result<Self, RigError> {
        limits::GRAVITY.check("gravity_mps2", file.gravity_mps2)?;
        let op = &file.operator;
        limits::LENGTH.check("operator.arm_length_m", op.arm_length_m)?;
        limits::ARM_MASS.check("operator.arm_mass_kg", op.arm_mass_kg)?;
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            limits::SIZE.check(&format!("operator.block_size_m.{axis}"), op.block_size_m[i])?;
        }
        match op.start {
            Start::Release {
                release_angle_deg: a,
            }
            | Start::Contact {
                release_angle_deg: a,
            } => {
                if !(a.is_finite() && a > 0.0 && a <= 170.0) {
                    return Err(invalid(
                        "operator.start.release_angle_deg",
                        a,
                        "must lie in (0, 170] degrees",
                    ));
                }
            }
            Start::Moving {
                angle_deg,
                angular_velocity_rad_s,
            } => {
                if !(angle_deg.is_finite() && (-170.0..0.0).contains(&angle_deg)) {
                    return Err(invalid(
                        "operator.start.angle_deg",
                        angle_deg,
                        "must lie in [-170, 0) degrees (the block before the dome)",
                    ));
                }
                limits::ANGULAR_VELOCITY.check(
                    "operator.start.angular_velocity_rad_s",
                    angular_velocity_rad_s,
                )?;
            }
        }
        let material = materials.get(&op.block_material).map_err(|_| {
            invalid(
                "operator.block_material",
                &op.block_material,
                &format!(
                    "must be one of the materials file: {}",
                    materials
                        .all()
                        .iter()
                        .map(|m| m.name.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })?;
        let block_mass_kg = match op.block_mass_kg {
            Some(m) => limits::BLOCK_MASS.check("operator.block_mass_kg", m)?,
            None => material.block_mass_kg,
        };
        if op.block_size_m[2] * 0.5 >= op.arm_length_m {
            return Err(invalid(
                "operator.block_size_m.z",
                op.block_size_m[2],
                "half the block height must be less than operator.arm_length_m",
            ));
        }

        let r = &file.robot;
        limits::LENGTH.check("robot.length_m", r.length_m)?;
        limits::WIDTH.check("robot.width_m", r.width_m)?;
        limits::THICKNESS.check("robot.thickness_m", r.thickness_m)?;
        limits::YOUNGS_MODULUS.check("robot.youngs_modulus_pa", r.youngs_modulus_pa)?;
        limits::DENSITY.check("robot.density_kg_m3", r.density_kg_m3)?;
        limits::PAYLOAD.check("robot.payload_kg", r.payload_kg)?;
        limits::SIZE.check("robot.dome_radius_m", r.dome_radius_m)?;
        limits::SIZE.check("robot.dome_standoff_m", r.dome_standoff_m)?;
        limits::check_beam_mesh(r.beam_elements, file.solver.beam)?;
        let link_mass_kg = r.density_kg_m3 * r.width_m * r.thickness_m * r.length_m;
        let link_ei = r.youngs_modulus_pa * r.width_m * r.thickness_m.powi(3) / 12.0;
        let torsion_spring = match r.torsion_spring_nm_per_rad {
            Some(k) => limits::TORSION_SPRING.check("robot.torsion_spring_nm_per_rad", k)?,
            None => 3.0 * link_ei / r.length_m,
        };

        let c = &file.contact;
        let k = match c.k {
            Some(k) => limits::CONTACT_K.check("contact.k", k)?,
            None => material.hertz.k(),
        };
        let n = c.n.unwrap_or(material.hertz.n());
        let hertz = Hertz::named(k, n, "contact.k", "contact.n")?;
        match c.damping {
            DampingSpec::None {} => {}
            DampingSpec::HuntCrossley { restitution }
            | DampingSpec::LankaraniNikravesh { restitution } => {
                if !(0.0..=1.0).contains(&restitution) {
                    return Err(invalid(
                        "contact.damping.restitution",
                        restitution,
                        "must lie in [0, 1]",
                    ));
                }
            }
            DampingSpec::AdamsImpact {
                c_max_n_s_per_m,
                depth_m,
            } => {
                limits::DAMPING_C_MAX.check("contact.damping.c_max_n_s_per_m", c_max_n_s_per_m)?;
                limits::DAMPING_DEPTH.check("contact.damping.depth_m", depth_m)?;
            }
        }

        let s = &file.solver;
        limits::SWING_STEP.check("solver.swing_step_s", s.swing_step_s)?;
        limits::check_count(
            "solver.contact_steps",
            s.contact_steps,
            limits::CONTACT_STEPS,
        )?;
        limits::check_count("solver.max_steps", s.max_steps, limits::MAX_STEPS)?;
        if let BeamSolverSpec::Modal { modes } = s.beam {
            let dofs = 3 * file.robot.beam_elements;
            if modes == 0 || modes > dofs {
                return Err(invalid(
                    "solver.beam.modes",
                    modes,
                    &format!("must be from 1 to {dofs} (3 per beam element)"),
                ));
            }
        }
        if let StopSpec::Duration { duration_s } = file.stop {
            limits::DURATION.check("stop.duration_s", duration_s)?;
        }
        limits::SAMPLE_RATE.check("record.sample_rate_hz", file.record.sample_rate_hz)?;

        let scene = Scene {
            block_mass_kg,
            hertz,
            link_mass_kg,
            link_ei,
            torsion_spring,
            file,
        };
        limits::check_budget(&scene)?;
        Ok(scene)
    }

    /// The contact law for an impact at approach speed `v0` [m/s] (damping models need it).
    pub fn contact_law(&self, v0: f64) -> Result<Box<dyn ContactLaw>, RigError> {
        Ok(self.file.contact.damping.law(self.hertz, v0)?)
    }
}

/// Most characters of the offending line quoted in a syntax error.
const QUOTE_LIMIT: usize = 200;

/// A TOML error as the user should see it: line and column, the parser's message, and at most
/// [`QUOTE_LIMIT`] characters of the line around the error (a 10 MB field must not come back
/// as 20 MB of error text).
fn syntax_message(text: &str, e: &toml::de::Error) -> String {
    let message = crate::format_message::plain(e.message().trim());
    let message = message.as_str();
    let deep = nesting_too_deep(text).or_else(|| dotted_too_deep(text));
    let start = match (e.span(), deep) {
        (Some(span), _) => span.start.min(text.len()),
        // the parser's recursion limit carries no position: find the nesting ourselves
        (None, Some(at)) => {
            return located(
                text,
                at,
                &format!(
                    "arrays or tables nest more than {MAX_NESTING} levels deep here; a scene \
                     nests at most a few"
                ),
            );
        }
        (None, None) => return format!("{message} (position unknown)"),
    };
    located(text, start, message)
}

/// Nesting of `[` and `{` the scene parser is asked to follow at most.
const MAX_NESTING: usize = 32;

/// The byte offset where `[`/`{` nesting (outside strings and comments) first exceeds
/// [`MAX_NESTING`], if it does.
fn nesting_too_deep(text: &str) -> Option<usize> {
    let mut depth = 0usize;
    let mut in_string: Option<char> = None;
    let mut in_comment = false;
    let mut escaped = false;
    for (i, c) in text.char_indices() {
        if in_comment {
            in_comment = c != '\n';
            continue;
        }
        if let Some(quote) = in_string {
            if escaped {
                escaped = false;
            } else if c == '\\' && quote == '"' {
                escaped = true;
            } else if c == quote || c == '\n' {
                in_string = None;
            }
            continue;
        }
        match c {
            '#' => in_comment = true,
            '"' | '\'' => in_string = Some(c),
            '[' | '{' => {
                depth += 1;
                if depth > MAX_NESTING {
                    return Some(i);
                }
            }
            ']' | '}' => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    None
}

/// The byte offset of the first line whose key or table header has more than [`MAX_NESTING`]
/// dotted parts (`[a.b.c…]`, `a.b.c… = 1`), if one has.
fn dotted_too_deep(text: &str) -> Option<usize> {
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let key = match trimmed.strip_prefix('[') {
            Some(header) => header.split(']').next().unwrap_or(header),
            None => trimmed.split('=').next().unwrap_or(""),
        };
        if key.matches('.').count() >= MAX_NESTING {
            return Some(offset + (line.len() - trimmed.len()));
        }
        offset += line.len();
    }
    None
}

/// "line L, column C: message" and the line quoted (shortened around `start`, a byte offset).
fn located(text: &str, start: usize, message: &str) -> String {
    let start = (0..=start.min(text.len()))
        .rev()
        .find(|&i| text.is_char_boundary(i))
        .unwrap_or(0);
    let line_start = text[..start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[start..].find('\n').map_or(text.len(), |i| start + i);
    let line_number = text[..start].matches('\n').count() + 1;
    let column = text[line_start..start].chars().count() + 1;
    let line = &text[line_start..line_end];
    let before: Vec<char> = text[line_start..start].chars().collect();
    let after: Vec<char> = text[start..line_end].chars().collect();
    let quote = if line.chars().count() <= QUOTE_LIMIT {
        line.to_string()
    } else {
        let head = QUOTE_LIMIT / 2;
        let from = before.len().saturating_sub(head);
        let left: String = before[from..].iter().collect();
        let right: String = after
            .iter()
            .take(QUOTE_LIMIT - (before.len() - from))
            .collect();
        format!(
            "{}{left}{right}{}",
            if from > 0 { "…" } else { "" },
            if after.len() > QUOTE_LIMIT - (before.len() - from) {
                "…"
            } else {
                ""
            }
        )
    };
    format!("line {line_number}, column {column}: {message}\n    {quote}")
}
