//! Loading a scene: the TOML parsed, every quantity checked against its physical range
//! ([`crate::limits`]), the derived quantities, then the run's work budget. Above
//! [`crate::scene`] (the data) so that the checks may use the rig's geometry.

use flexrig_contact::{Hertz, Materials};

use crate::RigError;
use crate::error::invalid;
use crate::limits;
use crate::scene::{
    BeamSolverSpec, ContactPolicy, DampingSpec, Design, Scene, SceneFile, Start, StopSpec,
    SwingPolicy,
};

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
                // With a drive the robot may come to the block: it may hang at the bottom.
                let driven = file.robot.drive.is_some();
                if !(angle_deg.is_finite()
                    && ((-170.0..0.0).contains(&angle_deg) || (driven && angle_deg == 0.0)))
                {
                    return Err(invalid(
                        "operator.start.angle_deg",
                        angle_deg,
                        if driven {
                            "must lie in [-170, 0] degrees (the block before the dome or hanging \
                             at the bottom)"
                        } else {
                            "must lie in [-170, 0) degrees (the block before the dome)"
                        },
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
        limits::check_beam_mass_conditioning(
            r.beam_elements,
            r.density_kg_m3 * r.width_m * r.thickness_m,
            r.length_m,
            r.payload_kg,
        )?;
        let link_mass_kg = r.density_kg_m3 * r.width_m * r.thickness_m * r.length_m;
        let link_ei = r.youngs_modulus_pa * r.width_m * r.thickness_m.powi(3) / 12.0;
        let torsion_spring = match r.torsion_spring_nm_per_rad.and_then(|k| k.value()) {
            Some(k) => limits::TORSION_SPRING.check("robot.torsion_spring_nm_per_rad", k)?,
            None => 3.0 * link_ei / r.length_m,
        };

        let drive = match &r.drive {
            Some(spec) => Some(crate::joint_drive::JointDrive::new(spec)?),
            None => None,
        };
        if drive.is_some() && r.design == crate::scene::Design::Cl {
            match file.solver.beam {
                crate::scene::BeamSolverSpec::Auto {}
                | crate::scene::BeamSolverSpec::Corotational {} => {}
                other => {
                    return Err(invalid(
                        "solver.beam",
                        format!("{other:?}").to_lowercase().replace(" {}", ""),
                        "\"auto\" or \"corotational\" for a compliant link on a drive (the \
                         motor turns the link through large angles, which the linear and modal \
                         beams cannot follow and the ANCF beam's clamp does not turn)",
                    ));
                }
            }
        }

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
        if let Some(rtol) = s.contact_rtol {
            limits::CONTACT_RTOL.check("solver.contact_rtol", rtol)?;
        }
        if s.contact == ContactPolicy::Adaptive {
            if file.robot.design != Design::Cj {
                return Err(invalid(
                    "solver.contact",
                    "\"adaptive\"",
                    "\"adaptive\" integrates the two hinges of robot.design = \"cj\" only; \
                     the compliant link needs \"fixed\"",
                ));
            }
            if s.swing != SwingPolicy::Adaptive {
                return Err(invalid(
                    "solver.contact",
                    "\"adaptive\"",
                    "\"adaptive\" starts at the onset located by solver.swing = \"adaptive\"; \
                     with solver.swing = \"fixed\" use \"fixed\"",
                ));
            }
            if file.robot.drive.is_some() {
                return Err(invalid(
                    "solver.contact",
                    "\"adaptive\"",
                    "\"adaptive\" integrates the unforced hinges; with robot.drive use \"fixed\"",
                ));
            }
        }
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

        let mut scene = Scene {
            block_mass_kg,
            hertz,
            link_mass_kg,
            link_ei,
            torsion_spring,
            file,
            warnings: Vec::new(),
            drive,
        };
        limits::check_budget(&scene)?;
        scene.warnings = crate::plausibility::warnings(&scene, materials);
        Ok(scene)
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
