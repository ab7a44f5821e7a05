//! Driven scenes: a scene file with a `[drive]` section is a driven robot striking a person
//! (docs/scenes.md, "Driven scenes"). Its fields are those of a strike description
//! ([`super::strike::StrikeDescription`]: `design`, `horizon_s`, `[link]`, `[drive]`,
//! `[person]`, `[placement]`, optional `[dome]` and `link_model`) plus the scene's `name`,
//! `description` and `[record] sample_rate_hz`; `flexrig run`, `flexrig sweep` and Python's
//! `flexrig.run` run it with flexrig-impact's driven solvers by the scene's link model and dome
//! ([`StrikeDescription::solve`]: exact by default, the CJ by DOP853 with the dome's geometry,
//! the CL as the corotational beam on the driven hub), not with the Rapier pendulum rig. Overrides (`--set
//! drive.command.profile.speed=3`) are applied to the text before it is parsed, so an overridden
//! value is checked like one in the file; every error names the scene's field path, the value
//! and what is allowed.
//!
//! The run returns a [`DrivenRun`]: the summary ([`DrivenSummary`], printed by `flexrig run`
//! and as JSON), the integrator's [`DrivenOutcome`] and the motion sampled along the run
//! ([`DrivenTraces`]: commanded and actual joint angle and speed, motor torque, the spring's or
//! the beam root's moment, tip deflection, contact force, indentation).

use flexrig_impact::drive::{Dome, Drive, DriveCommand, DriveSpec, HeadSupport, Person, Placement};
use flexrig_impact::{DriveNote, DrivenOutcome, ImpactError, LinkParams};
use flexrig_rig::{Override, RigError, overrides};
use serde::{Deserialize, Serialize};

use super::strike::{LinkModel, StrikeDescription, StrikeDesign, StrikeOptions};
use crate::{CancelToken, Error};

/// The sample rate of a driven scene's trace when `[record]` does not give one \[Hz\].
pub const DEFAULT_SAMPLE_RATE_HZ: f64 = 50_000.0;

/// The sample rate's range \[Hz\] (as the test bed's `record.sample_rate_hz`).
pub const SAMPLE_RATE_RANGE: (f64, f64) = (1.0, 1e8);

/// Most trace samples a driven run may keep (`horizon_s` × `record.sample_rate_hz`), as the
/// test bed's limit on sensor samples.
pub const MAX_SAMPLES: f64 = flexrig_rig::limits::MAX_SAMPLES;

/// The test bed's sections, which a driven scene does not have.
const RIG_SECTIONS: [&str; 6] = [
    "operator",
    "robot",
    "contact",
    "solver",
    "stop",
    "gravity_mps2",
];

/// `[record]` of a driven scene.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DrivenRecord {
    /// At most one trace sample per 1/rate seconds, taken at the integrator's steps (the onset
    /// and the separation always) \[Hz\], in [1, 1e8].
    pub sample_rate_hz: f64,
}

/// The file as written: the strike description's fields (their own types) and the scene's.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct DrivenSceneFile {
    name: String,
    #[serde(default)]
    description: String,
    record: Option<DrivenRecord>,
    design: StrikeDesign,
    horizon_s: f64,
    link: LinkParams,
    drive: DriveSpec,
    person: Person,
    placement: Placement,
    #[serde(default)]
    link_model: LinkModel,
    #[serde(default = "super::strike::test_bed_dome")]
    dome: Dome,
}

/// A validated driven scene.
#[derive(Debug, Clone, PartialEq)]
pub struct DrivenScene {
    /// The scene's name.
    pub name: String,
    /// Why the values were chosen.
    pub description: String,
    /// The strike (checked: every field in its range).
    pub strike: StrikeDescription,
    /// Trace sample rate \[Hz\].
    pub sample_rate_hz: f64,
}

/// True when the scene table has a `[drive]` section (a driven scene).
pub fn is_driven(table: &toml::Table) -> bool {
    table.contains_key("drive")
}

/// True when `text` parses as TOML with a `[drive]` section (a text that does not parse is not
/// driven: the test bed's loader then reports its error).
pub fn is_driven_text(text: &str) -> bool {
    toml::from_str::<toml::Table>(text).is_ok_and(|t| is_driven(&t))
}

/// An error of the scene's own validation as a scene-field error (`scene field link.m_r = …`):
/// the link's fields get their section.
fn scene_error(e: ImpactError) -> Error {
    match e {
        ImpactError::InvalidParameter {
            field,
            value,
            allowed,
        } => {
            let field = if ["m_r", "length", "k_delta", "m_e"].contains(&field.as_str()) {
                format!("link.{field}")
            } else {
                field
            };
            RigError::InvalidScene {
                field,
                value,
                allowed,
            }
            .into()
        }
        other => other.into(),
    }
}

/// The line and column of a byte offset.
fn line_of(text: &str, at: usize) -> (usize, &str) {
    let at = at.min(text.len());
    let start = text[..at].rfind('\n').map_or(0, |i| i + 1);
    let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    (
        text[..at].matches('\n').count() + 1,
        text[start..end].trim(),
    )
}

impl DrivenScene {
    /// Parses and checks a driven scene's text (no overrides).
    pub fn parse(text: &str) -> Result<DrivenScene, Error> {
        let table: toml::Table = toml::from_str(text).map_err(|e| syntax(text, &e))?;
        for section in RIG_SECTIONS {
            if table.contains_key(section) {
                return Err(RigError::InvalidScene {
                    field: section.into(),
                    value: "(present)".into(),
                    allowed: "not part of a driven scene: a scene with [drive] is the driven \
                              robot striking a person ([link], [drive], [person], [placement]); \
                              the test bed's sections belong to scenes without [drive]"
                        .into(),
                }
                .into());
            }
        }
        let file: DrivenSceneFile = toml::from_str(text).map_err(|e| syntax(text, &e))?;
        let drive = Drive::new(file.drive.motor, file.drive.command).map_err(scene_error)?;
        let strike = StrikeDescription {
            design: file.design,
            horizon_s: file.horizon_s,
            link: file.link,
            drive,
            person: file.person,
            placement: file.placement,
            link_model: file.link_model,
            dome: file.dome,
        };
        strike.strike().validate().map_err(scene_error)?;
        strike.dome.validate().map_err(scene_error)?;
        let sample_rate_hz = match file.record {
            Some(r) => {
                let (lo, hi) = SAMPLE_RATE_RANGE;
                if !(r.sample_rate_hz.is_finite() && (lo..=hi).contains(&r.sample_rate_hz)) {
                    return Err(invalid(
                        "record.sample_rate_hz",
                        r.sample_rate_hz,
                        format!("must lie in [{lo}, {hi:e}] Hz"),
                    ));
                }
                r.sample_rate_hz
            }
            None => DEFAULT_SAMPLE_RATE_HZ,
        };
        if strike.horizon_s * sample_rate_hz > MAX_SAMPLES {
            return Err(invalid(
                "record.sample_rate_hz",
                sample_rate_hz,
                format!(
                    "at most {MAX_SAMPLES:e} samples over horizon_s = {} s, i.e. at most {} Hz",
                    strike.horizon_s,
                    MAX_SAMPLES / strike.horizon_s
                ),
            ));
        }
        check_torque_limit(&strike)?;
        Ok(DrivenScene {
            name: file.name,
            description: file.description,
            strike,
            sample_rate_hz,
        })
    }

    /// Parses `text` with `overrides` applied; an error an override causes names its path and
    /// value.
    pub fn with_overrides(text: &str, overrides: &[Override]) -> Result<DrivenScene, Error> {
        if overrides.is_empty() {
            return DrivenScene::parse(text);
        }
        // the file itself first, so that its own errors carry its lines
        DrivenScene::parse(text)?;
        let applied = overrides::apply(text, overrides)?;
        match DrivenScene::parse(&applied) {
            Ok(scene) => Ok(scene),
            Err(e @ Error::Rig(RigError::InvalidScene { .. })) => Err(e),
            Err(e) => {
                // a format error (type, unknown field): name the first override that causes it
                for o in overrides {
                    let single = overrides::apply(text, std::slice::from_ref(o))?;
                    if let Err(Error::Rig(RigError::SceneSyntax(message))) =
                        DrivenScene::parse(&single)
                    {
                        return Err(RigError::InvalidScene {
                            field: o.path.clone(),
                            value: o.value.to_string(),
                            allowed: format!("not accepted by the driven scene format: {message}"),
                        }
                        .into());
                    }
                }
                Err(e)
            }
        }
    }

    /// The strike's run options: the trace at the scene's sample rate.
    fn options(&self) -> StrikeOptions {
        StrikeOptions {
            trace_every: Some(1.0 / self.sample_rate_hz),
            out: None,
            names: super::strike::FieldNames::File,
        }
    }
}

fn invalid(field: &str, value: f64, allowed: String) -> Error {
    RigError::InvalidScene {
        field: field.into(),
        value: flexrig_contact::validate::display(value),
        allowed,
    }
    .into()
}

/// A TOML error with its line (the driven scene's own positions).
fn syntax(text: &str, e: &toml::de::Error) -> Error {
    let message = flexrig_rig::format_message::plain(e.message().trim());
    let text_message = match e.span() {
        Some(span) => {
            let (line, quoted) = line_of(text, span.start);
            let quoted: String = quoted.chars().take(200).collect();
            format!("line {line}: {message} (at `{quoted}`)")
        }
        None => message,
    };
    RigError::SceneSyntax(text_message).into()
}

/// A controller's torque limit must cover the torque the commanded motion needs for the robot
/// as a rigid body, J α_cmd + c_j ω_cmd at the joint (J = J_m N² + (m_e + m_r/3) L²), over the
/// ramp and after it: a lower limit cannot follow the command, and the link reaches the person
/// late or never. `flexrig strike` runs such a drive and reports it; a scene refuses it.
fn check_torque_limit(strike: &StrikeDescription) -> Result<(), Error> {
    let DriveCommand::Controller {
        profile,
        torque_limit: Some(limit),
        ..
    } = strike.drive.command()
    else {
        return Ok(());
    };
    let motor = strike.drive.motor();
    let link = &strike.link;
    let j = motor.reflected_inertia() + (link.m_e + link.m_r / 3.0) * link.length * link.length;
    let c = motor.reflected_friction();
    let end = profile.ramp_end();
    const POINTS: usize = 2000;
    let need = (0..=POINTS)
        .map(|i| {
            let t = end * i as f64 / POINTS as f64;
            let (_, omega, alpha) = profile.at_in(t, t.min(end * (1.0 - 1e-12)));
            (j * alpha + c * omega).abs()
        })
        .chain(std::iter::once((c * profile.final_speed()).abs()))
        .fold(0.0f64, f64::max);
    let n = motor.gear_ratio;
    if limit * n < need {
        return Err(RigError::InvalidScene {
            field: "drive.command.torque_limit".into(),
            value: flexrig_contact::validate::display(*limit),
            allowed: format!(
                "at least {:.4e} N·m at the motor shaft: the commanded motion needs up to \
                 {need:.4e} N·m at the joint for the robot as a rigid body (J α + c ω with \
                 J = {j:.4e} kg·m², the rotor's J_m N² and the link's (m_e + m_r/3) L²), and a \
                 lower limit cannot follow the command",
                need / n
            ),
        }
        .into());
    }
    Ok(())
}

/// The summary of a driven run (`flexrig run` on a driven scene; its JSON). Times from the
/// drive's start.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DrivenSummary {
    /// Scene name.
    pub scene: String,
    /// Always `"driven"` (the test bed's summaries have no `kind`).
    pub kind: &'static str,
    /// CJ or CL.
    pub design: StrikeDesign,
    /// The head's support: `free`, `neck` or `wall`.
    pub head: &'static str,
    /// What moves the joint: `trajectory`, `controller` or `open_loop`.
    pub command: &'static str,
    /// Peak contact force \[N\].
    pub peak_force_n: f64,
    /// Time of the peak \[s\].
    pub time_of_peak_s: f64,
    /// Contact onset \[s\].
    pub onset_time_s: f64,
    /// Contact duration \[s\].
    pub contact_duration_s: f64,
    /// Approach speed δ̇ at the onset [m/s].
    pub impact_velocity_mps: f64,
    /// Commanded tip speed L ω_cmd at the onset [m/s] (absent under an open-loop torque).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub commanded_tip_speed_mps: Option<f64>,
    /// Relative speed at the separation, positive when parting [m/s].
    pub separation_velocity_mps: f64,
    /// The tip's deflection from the hub's line at the onset \[m\] (positive towards the
    /// person).
    pub pre_impact_deflection_m: f64,
    /// Joint torque τ_j at the onset [N·m].
    pub joint_torque_at_onset_nm: f64,
    /// Largest |τ_j| during the contact [N·m].
    pub peak_joint_torque_nm: f64,
    /// Largest |τ_m| at the motor shaft during the contact, τ_j / N [N·m].
    pub peak_motor_torque_nm: f64,
    /// The joint's speed at the onset [rad/s] (the motor's, after the gear).
    pub joint_speed_at_contact_rad_s: f64,
    /// Largest indentation \[m\]: (f_max/k_c)^{1/n} for an undamped contact (Eq. 4, exact at
    /// the peak); with damping the largest among the trace's samples.
    pub max_indentation_m: f64,
    /// Impulse ∫ f dt over the contact [N·s] (trapezoidal over the trace's samples).
    pub impulse_n_s: f64,
    /// Work of the motor on the joint over the contact \[J\].
    pub motor_work_j: f64,
    /// Work of the contact force while the indentation grows \[J\].
    pub impact_energy_j: f64,
    /// Dissipated over the contact (friction, neck, contact damping) \[J\].
    pub dissipated_j: f64,
    /// Energy balance residual over the contact (motor work − dissipated − change of the
    /// mechanical energy) \[J\].
    pub energy_residual_j: f64,
    /// What the drive did, in words (empty: it followed its command).
    pub notes: Vec<String>,
    /// Right-hand-side evaluations (CJ) or steps (CL).
    pub steps: usize,
    /// Simulated time, to the separation \[s\].
    pub duration_s: f64,
    /// Trace samples.
    pub samples: usize,
    /// Plausibility warnings of the scene's values (the shared rule for masses, lengths and
    /// speeds, [`crate::shared::plausibility`]; empty: none), each naming its field.
    pub warnings: Vec<crate::shared::plausibility::Warning>,
    /// Severity of the contact ([`crate::shared::severity::of_driven`] over the trace: peak force,
    /// pressure under both dome area models, energy transferred, and for a head that moves
    /// its peak acceleration, HIC15 and HIC36; the struck body is the person's head).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub severity: Option<crate::shared::severity::Severity>,
}

/// The motion of a driven run, one entry per trace sample (at the integrator's steps, at most
/// one per 1/`record.sample_rate_hz`, the onset and the separation always).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DrivenTraces {
    /// Time from the drive's start \[s\].
    pub time_s: Vec<f64>,
    /// Commanded joint angle \[rad\] (empty under an open-loop torque).
    pub commanded_angle_rad: Vec<f64>,
    /// Commanded joint speed [rad/s] (empty under an open-loop torque).
    pub commanded_speed_rad_s: Vec<f64>,
    /// Joint angle (the motor's, after the gear) \[rad\].
    pub joint_angle_rad: Vec<f64>,
    /// Joint speed [rad/s].
    pub joint_speed_rad_s: Vec<f64>,
    /// Motor torque at the joint, τ_j = N τ_m [N·m].
    pub joint_torque_nm: Vec<f64>,
    /// Motor torque at the motor shaft, τ_m [N·m].
    pub motor_torque_nm: Vec<f64>,
    /// The torsion spring's moment (CJ) or the beam's root moment (CL) [N·m].
    pub link_moment_nm: Vec<f64>,
    /// Tip deflection from the hub's line \[m\].
    pub tip_deflection_m: Vec<f64>,
    /// Contact force \[N\].
    pub force_n: Vec<f64>,
    /// Indentation \[m\] (negative: the gap before the contact).
    pub indentation_m: Vec<f64>,
    /// The head's acceleration along the tip's path [m/s²] (positive away from the link; 0
    /// against a wall).
    pub head_acceleration_mps2: Vec<f64>,
}

impl DrivenTraces {
    /// The named columns, in order (for a table or a dict); the commanded columns only with a
    /// commanded motion.
    pub fn columns(&self) -> Vec<(&'static str, &Vec<f64>)> {
        let mut out = vec![("time_s", &self.time_s)];
        if !self.commanded_angle_rad.is_empty() {
            out.push(("commanded_angle_rad", &self.commanded_angle_rad));
            out.push(("commanded_speed_rad_s", &self.commanded_speed_rad_s));
        }
        out.extend([
            ("joint_angle_rad", &self.joint_angle_rad),
            ("joint_speed_rad_s", &self.joint_speed_rad_s),
            ("joint_torque_nm", &self.joint_torque_nm),
            ("motor_torque_nm", &self.motor_torque_nm),
            ("link_moment_nm", &self.link_moment_nm),
            ("tip_deflection_m", &self.tip_deflection_m),
            ("force_n", &self.force_n),
            ("indentation_m", &self.indentation_m),
            ("head_acceleration_mps2", &self.head_acceleration_mps2),
        ]);
        out
    }
}

/// A driven run: its summary, the integrator's outcome and the traces.
#[derive(Debug, Clone)]
pub struct DrivenRun {
    /// The summary.
    pub summary: DrivenSummary,
    /// The integrator's result (its own trace included).
    pub outcome: DrivenOutcome,
    /// The motion as columns.
    pub traces: DrivenTraces,
}

/// The drive's note in words.
pub fn note_text(note: &DriveNote) -> String {
    note.to_string()
}

/// The samples `trace` of a run of `scene` as columns (the commanded motion from the
/// scene's profile, the motor's torque through its gear).
pub fn traces_of(scene: &DrivenScene, trace: &[flexrig_impact::TraceSample]) -> DrivenTraces {
    let s = &scene.strike;
    let n = s.drive.motor().gear_ratio;
    let profile = s.drive.profile();
    let mut traces = DrivenTraces::default();
    for sample in trace {
        traces.time_s.push(sample.t);
        if let Some(p) = profile {
            let (phi, omega, _) = p.at(sample.t);
            traces.commanded_angle_rad.push(phi);
            traces.commanded_speed_rad_s.push(omega);
        }
        traces.joint_angle_rad.push(sample.hub_angle_rad);
        traces.joint_speed_rad_s.push(sample.hub_speed_rad_s);
        traces.joint_torque_nm.push(sample.joint_torque_nm);
        traces.motor_torque_nm.push(sample.joint_torque_nm / n);
        traces.link_moment_nm.push(sample.moment_nm);
        traces.tip_deflection_m.push(sample.tip_deflection_m);
        traces.force_n.push(sample.force_n);
        traces.indentation_m.push(sample.indentation_m);
        traces
            .head_acceleration_mps2
            .push(sample.head_acceleration_mps2);
    }
    traces
}

/// Runs a driven scene (the strike with its trace at the scene's sample rate).
pub fn run(scene: &DrivenScene, cancel: &CancelToken) -> Result<DrivenRun, Error> {
    let result = super::strike::run(&scene.strike, &scene.options(), cancel)?;
    let outcome = result.outcome;
    let s = &scene.strike;
    let n = s.drive.motor().gear_ratio;
    let traces = traces_of(scene, &outcome.trace);
    let c = outcome.contact;
    let end = c.onset_s + c.duration_s;
    let in_contact = |t: f64| t >= c.onset_s && t <= end;
    let contact: Vec<_> = outcome.trace.iter().filter(|x| in_contact(x.t)).collect();
    let impulse = contact
        .windows(2)
        .map(|w| 0.5 * (w[0].force_n + w[1].force_n) * (w[1].t - w[0].t))
        .sum();
    let hertz = s.person.contact;
    let max_indentation = if s.person.damping == flexrig_contact::DampingSpec::NONE {
        (c.peak_force_n / hertz.k()).powf(1.0 / hertz.n())
    } else {
        contact
            .iter()
            .map(|x| x.indentation_m)
            .fold(0.0f64, f64::max)
    };
    let head_moves = s.person.support != HeadSupport::Wall;
    let severity = if contact.len() >= 2 {
        Some(crate::shared::severity::of_driven(
            &traces.time_s,
            &traces.force_n,
            &traces.indentation_m,
            head_moves.then_some(traces.head_acceleration_mps2.as_slice()),
            (c.onset_s, end),
            s.dome.radius_m,
            hertz.n(),
        )?)
    } else {
        None
    };
    let joint_speed_at_contact = outcome
        .trace
        .iter()
        .find(|x| x.t >= c.onset_s)
        .map_or(f64::NAN, |x| x.hub_speed_rad_s);
    let summary = DrivenSummary {
        scene: scene.name.clone(),
        kind: "driven",
        design: s.design,
        head: match s.person.support {
            HeadSupport::Free => "free",
            HeadSupport::Neck { .. } => "neck",
            HeadSupport::Wall => "wall",
        },
        command: match s.drive.command() {
            DriveCommand::Trajectory { .. } => "trajectory",
            DriveCommand::Controller { .. } => "controller",
            DriveCommand::OpenLoop { .. } => "open_loop",
        },
        peak_force_n: c.peak_force_n,
        time_of_peak_s: c.time_of_peak_s,
        onset_time_s: c.onset_s,
        contact_duration_s: c.duration_s,
        impact_velocity_mps: outcome.approach_speed_mps,
        commanded_tip_speed_mps: outcome.commanded_tip_speed_mps,
        separation_velocity_mps: -outcome.separation_rate_mps,
        pre_impact_deflection_m: outcome.pre_impact_deflection_m,
        joint_torque_at_onset_nm: outcome.joint_torque_at_onset_nm,
        peak_joint_torque_nm: outcome.peak_joint_torque_nm,
        peak_motor_torque_nm: outcome.peak_joint_torque_nm / n,
        joint_speed_at_contact_rad_s: joint_speed_at_contact,
        max_indentation_m: max_indentation,
        impulse_n_s: impulse,
        motor_work_j: outcome.energy.motor_work_j,
        impact_energy_j: outcome.energy.impact_energy_j,
        dissipated_j: outcome.energy.dissipated_j,
        energy_residual_j: outcome.energy.residual_j,
        notes: outcome.notes.iter().map(note_text).collect(),
        steps: outcome.work,
        duration_s: end,
        samples: outcome.trace.len(),
        warnings: result.warnings,
        severity,
    };
    Ok(DrivenRun {
        summary,
        outcome,
        traces,
    })
}

/// The summary as `flexrig run --json` prints it.
pub fn summary_json(s: &DrivenSummary) -> serde_json::Value {
    let mut value = serde_json::to_value(s).expect("a driven summary serialises");
    if let Some(map) = value.as_object_mut() {
        map.retain(|_, v| !v.is_null());
    }
    value
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::driven::strike::{self, StrikeOptions};
    use crate::testbed::run::{LogRequest, run_driven_text};

    const CJ_FREE: &str = include_str!("../../../../assets/scenes/driven_cj_free_head.toml");
    const CJ_WALL: &str = include_str!("../../../../assets/scenes/driven_cj_wall.toml");
    const CL_FREE: &str = include_str!("../../../../assets/scenes/driven_cl_free_head.toml");
    const CL_WALL: &str = include_str!("../../../../assets/scenes/driven_cl_wall.toml");

    fn set(path: &str, value: &str) -> Override {
        Override::parse(&format!("{path}={value}")).unwrap()
    }

    fn no_log() -> LogRequest<'static> {
        LogRequest {
            out: None,
            force: false,
            rates: crate::log::mcap::LogRates::DECIMATED,
            deformation_scale: 1.0,
        }
    }

    #[test]
    fn the_bundled_driven_scenes_are_their_drive_files() {
        for (scene, drive) in [
            (
                CJ_FREE,
                include_str!("../../../../assets/drives/cj_free_head.toml"),
            ),
            (
                CJ_WALL,
                include_str!("../../../../assets/drives/cj_wall.toml"),
            ),
            (
                CL_FREE,
                include_str!("../../../../assets/drives/cl_free_head.toml"),
            ),
            (
                CL_WALL,
                include_str!("../../../../assets/drives/cl_wall.toml"),
            ),
        ] {
            let s = DrivenScene::parse(scene).unwrap();
            assert_eq!(s.strike, StrikeDescription::parse(drive, "drive").unwrap());
            assert!(is_driven_text(scene));
            assert_eq!(s.sample_rate_hz, 50_000.0);
        }
        for (name, text) in crate::testbed::scenes::BUNDLED_SCENES {
            assert_eq!(is_driven_text(text), name.starts_with("driven_"), "{name}");
        }
    }

    #[test]
    fn a_driven_cj_scene_run_gives_the_strike_bit_for_bit() {
        for text in [CJ_FREE, CJ_WALL] {
            let scene = DrivenScene::parse(text).unwrap();
            let direct = strike::run(
                &scene.strike,
                &StrikeOptions {
                    trace_every: None,
                    out: None,
                    names: crate::driven::strike::FieldNames::File,
                },
                &CancelToken::new(),
            )
            .unwrap();
            let run = run_driven_text(text, &[], no_log(), &CancelToken::new()).unwrap();
            let c = direct.outcome.contact;
            assert_eq!(run.summary.peak_force_n, c.peak_force_n);
            assert_eq!(run.summary.time_of_peak_s, c.time_of_peak_s);
            assert_eq!(run.summary.contact_duration_s, c.duration_s);
            assert_eq!(
                run.summary.pre_impact_deflection_m,
                direct.outcome.pre_impact_deflection_m
            );
            assert_eq!(
                run.summary.peak_motor_torque_nm * 50.0,
                direct.outcome.peak_joint_torque_nm
            );
        }
    }

    /// Trapezoidal ∫ y dt over the samples with t in [a, b].
    fn integral(t: &[f64], y: &[f64], a: f64, b: f64) -> f64 {
        (1..t.len())
            .filter(|&i| t[i - 1] >= a && t[i] <= b)
            .map(|i| 0.5 * (y[i - 1] + y[i]) * (t[i] - t[i - 1]))
            .sum()
    }

    #[test]
    fn the_logged_channels_balance_the_rotor_and_the_motor_work() {
        // every integrator step sampled
        let o = [
            set("record.sample_rate_hz", "1e8"),
            set("horizon_s", "0.09"),
        ];
        let scene = DrivenScene::with_overrides(CJ_FREE, &o);
        // 0.09 s is too short for the link to arrive: refused up front, naming the placement
        let e = scene.unwrap_err();
        assert!(e.to_string().contains("placement"), "{e}");
        let o = [set("record.sample_rate_hz", "1e6")];
        let run = run_driven_text(CJ_FREE, &o, no_log(), &CancelToken::new()).unwrap();
        let (s, tr) = (&run.summary, &run.traces);
        let (a, b) = (s.onset_time_s, s.onset_time_s + s.contact_duration_s);
        // the motor's work over the contact: ∫ τ_j ω dt against the integrator's own integral
        let power: Vec<f64> = (0..tr.time_s.len())
            .map(|i| tr.joint_torque_nm[i] * tr.joint_speed_rad_s[i])
            .collect();
        let work = integral(&tr.time_s, &power, a, b);
        assert!(
            (work - s.motor_work_j).abs() <= 2e-3 * s.motor_work_j.abs(),
            "{work} vs {}",
            s.motor_work_j
        );
        // the rotor's momentum: ∫ (τ_j − c_j ω − M_spring) dt = J_m N² Δω over the contact,
        // M_spring from the logged deflection (k_θr (φ_m − φ_l))
        let motor = scene_motor(CJ_FREE);
        let (j, c) = (motor.reflected_inertia(), motor.reflected_friction());
        let net: Vec<f64> = (0..tr.time_s.len())
            .map(|i| tr.joint_torque_nm[i] - c * tr.joint_speed_rad_s[i] - tr.link_moment_nm[i])
            .collect();
        let ia = tr.time_s.iter().position(|&t| t >= a).unwrap();
        let ib = tr.time_s.iter().rposition(|&t| t <= b).unwrap();
        let change = j * (tr.joint_speed_rad_s[ib] - tr.joint_speed_rad_s[ia]);
        let impulse = integral(&tr.time_s, &net, tr.time_s[ia], tr.time_s[ib]);
        let scale = integral(
            &tr.time_s,
            &tr.link_moment_nm
                .iter()
                .map(|m| m.abs())
                .collect::<Vec<_>>(),
            a,
            b,
        );
        assert!(
            (impulse - change).abs() <= 2e-3 * scale,
            "{impulse} vs {change} (scale {scale})"
        );
        // the spring moment is k_θr (φ_m − φ_l) = −k_δ L × the tip deflection
        for i in 0..tr.time_s.len() {
            let expected = -1e8 * 1.0 * tr.tip_deflection_m[i];
            assert!((tr.link_moment_nm[i] - expected).abs() <= 1e-9 * expected.abs().max(1.0));
        }
        // the logged force peaks just below the located peak
        let logged = tr.force_n.iter().fold(0.0f64, |m, &f| m.max(f));
        assert!(logged <= s.peak_force_n && logged >= (1.0 - 1e-3) * s.peak_force_n);
        // commanded speed reaches the ramp's 2 rad/s
        let last = tr.commanded_speed_rad_s.last().unwrap();
        assert_eq!(*last, 2.0);
    }

    fn scene_motor(text: &str) -> flexrig_impact::drive::Motor {
        *DrivenScene::parse(text).unwrap().strike.drive.motor()
    }

    fn expect_input(text: &str, o: &[Override], field: &str, value: &str) {
        let e = DrivenScene::with_overrides(text, o).unwrap_err();
        assert_eq!(e.kind(), crate::ErrorKind::Input, "{e}");
        let m = e.to_string();
        assert!(m.contains(field) && m.contains(value), "{m}");
    }

    #[test]
    fn bad_values_name_the_scene_field_its_value_and_range() {
        expect_input(
            CJ_FREE,
            &[set("drive.motor.rotor_inertia", "-1e-4")],
            "drive.motor.rotor_inertia",
            "[0, 1e9]",
        );
        expect_input(
            CL_FREE,
            &[set("drive.motor.gear_ratio", "0")],
            "drive.motor.gear_ratio",
            "(0, 1e6]",
        );
        expect_input(
            CJ_WALL,
            &[set("drive.command.torque_limit", "0.1")],
            "drive.command.torque_limit",
            "at least",
        );
        // a commanded motion that turns away from the person never reaches it
        expect_input(
            CJ_FREE,
            &[set("placement", "{ placement = \"angle\", angle = -0.5 }")],
            "placement",
            "-0.5",
        );
        expect_input(
            CJ_FREE,
            &[set("drive.command.gains.kp", "-1")],
            "drive.command.gains.kp",
            "-1",
        );
        expect_input(CJ_FREE, &[set("link.m_r", "0")], "link.m_r", "0");
        expect_input(
            CJ_FREE,
            &[set("record.sample_rate_hz", "0")],
            "record.sample_rate_hz",
            "[1, 1e8]",
        );
        // a value of the wrong type names the override
        expect_input(
            CJ_FREE,
            &[set("drive.motor.gear_ratio", "fast")],
            "drive.motor.gear_ratio",
            "fast",
        );
        // the test bed's sections do not belong to a driven scene
        expect_input(
            CJ_FREE,
            &[set("robot.payload_kg", "0.2")],
            "robot",
            "driven scene",
        );
        // a field the format does not know
        let e =
            DrivenScene::parse(&CJ_FREE.replace("ramp_time = 0.5", "ramp_time = 0.5\nramp = 1"))
                .unwrap_err();
        assert!(
            e.to_string().contains("ramp") && e.to_string().contains("line"),
            "{e}"
        );
    }

    #[test]
    fn an_override_of_the_speed_changes_the_strike() {
        let slow = run_driven_text(
            CJ_WALL,
            &[set("drive.command.profile.speed", "1.0")],
            no_log(),
            &CancelToken::new(),
        )
        .unwrap();
        let base = run_driven_text(CJ_WALL, &[], no_log(), &CancelToken::new()).unwrap();
        // the link arrives near the commanded tip speed; against a wall with n = 2 the peak
        // grows as v^(2n/(n+1)) = v^(4/3) (Eq. 13's energy argument)
        let ratio = base.summary.peak_force_n / slow.summary.peak_force_n;
        let v_ratio = base.summary.impact_velocity_mps / slow.summary.impact_velocity_mps;
        assert!((v_ratio - 2.0).abs() < 0.1, "{v_ratio}");
        assert!(ratio > 1.5 && ratio < 3.0, "{ratio}");
        assert_eq!(slow.summary.commanded_tip_speed_mps, Some(1.0));
    }

    /// A driven CJ held at constant speed (an ideal position source in steady motion), a link
    /// 1e5 times stiffer than the contact, n = 1, a free head of 4 kg.
    const HELD_CJ_LINEAR: &str = r#"
name = "held_cj_linear"
design = "cj"
horizon_s = 1.0
# the contact along the tip's path (the half-sine's 1-D model; the exact model's dome turns
# with the link by 0.04 rad over the pulse)
link_model = "linear"
[link]
m_r = 1.0
length = 1.0
k_delta = 1e10
m_e = 0.1
[drive.motor]
rotor_inertia = 1e-4
gear_ratio = 50.0
friction = 0.0
[drive.command]
command = "trajectory"
[drive.command.profile]
profile = "steady"
speed = 2.0
[person]
m_h = 4.0
speed = 0.0
[person.support]
support = "free"
[person.contact]
k = 1e5
n = 1.0
[placement]
placement = "angle"
angle = 0.01
[record]
sample_rate_hz = 1e6
"#;

    #[test]
    fn the_hic_of_a_held_linear_strike_is_the_half_sine_s() {
        // A link moved at a constant tip speed v that the contact cannot slow (held joint,
        // link 1e5 × stiffer than the contact) into a free head m_h on a linear contact k_c:
        // the head's acceleration is the half-sine a = v ω sin ωt, ω = √(k_c/m_h), for
        // T = π/ω. Its HIC (window w centred on the pulse, x = π w/(2T)):
        // HIC = (2T/π) (v ω/g₀)^2.5 sin^2.5 x / x^1.5, largest at tan x = 5x/3 (w < 15 ms here,
        // so HIC15 = HIC36). Departures: the link's compliance k_c/k_δ = 1e-5 (HIC ∝ ω^1.5:
        // 7.5e-6), its vibration ((ω/ω_link)² ≈ 1e-6), and the trace's linear interpolant at
        // 1 µs ((π Δt/T)²/12 ≈ 2e-9): tolerance 1e-4.
        let run = run_driven_text(HELD_CJ_LINEAR, &[], no_log(), &CancelToken::new()).unwrap();
        let s = &run.summary;
        let (v, k_c, m_h) = (2.0, 1e5, 4.0_f64);
        let omega = (k_c / m_h).sqrt();
        let t_c = std::f64::consts::PI / omega;
        let a_g = v * omega / crate::shared::severity::STANDARD_GRAVITY;
        // tan x = 5x/3 by Newton from 1
        let mut x: f64 = 1.0;
        for _ in 0..50 {
            let g = x.tan() - 5.0 * x / 3.0;
            let dg = 1.0 / x.cos().powi(2) - 5.0 / 3.0;
            x -= g / dg;
        }
        let window = 2.0 * t_c * x / std::f64::consts::PI;
        assert!(window < 0.015, "{window}");
        let hic =
            2.0 * t_c / std::f64::consts::PI * a_g.powf(2.5) * x.sin().powf(2.5) / x.powf(1.5);
        let sev = s.severity.as_ref().expect("a severity");
        for (name, h) in [("HIC15", sev.hic15), ("HIC36", sev.hic36)] {
            let h = h.expect("a HIC for a free head");
            eprintln!(
                "{name} {} vs half-sine {hic} (window {} s, closed form {window} s)",
                h.hic,
                h.t2_s - h.t1_s
            );
            assert!(
                (h.hic - hic).abs() <= 1e-4 * hic,
                "{name} {} vs {hic}",
                h.hic
            );
            assert!(((h.t2_s - h.t1_s) - window).abs() <= 1e-3 * window);
        }
        // the pulse itself: peak m_h v ω, duration π/ω, peak acceleration v ω
        let peak = m_h * v * omega;
        assert!(
            (s.peak_force_n - peak).abs() <= 1e-4 * peak,
            "{}",
            s.peak_force_n
        );
        assert!((s.contact_duration_s - t_c).abs() <= 1e-4 * t_c);
        let a_peak = sev.peak_acceleration_mps2.unwrap();
        assert!((a_peak - v * omega).abs() <= 1e-4 * v * omega, "{a_peak}");
        // energy transferred: the contact's energy at the peak, ½ m_h v² (the striker does
        // not slow)
        let e = 0.5 * m_h * v * v;
        assert!((sev.energy_transferred_j - e).abs() <= 1e-4 * e);
        // the sweep row carries the severity and the driven columns
        let row = crate::study::sweep::driven_values(s);
        let col = |name: &str| {
            let i = crate::study::sweep::SUMMARY_COLUMNS
                .iter()
                .position(|c| *c == name)
                .unwrap();
            row[i]
        };
        assert_eq!(col("hic15"), Some(sev.hic15.unwrap().hic));
        assert_eq!(col("severity_peak_force_n"), Some(sev.peak_force_n));
        assert_eq!(col("peak_motor_torque_nm"), Some(s.peak_motor_torque_nm));
        assert_eq!(col("joint_speed_at_contact_rad_s"), Some(2.0));
        assert_eq!(col("commanded_tip_speed_mps"), Some(2.0));
        assert_eq!(
            col("pre_impact_deflection_m"),
            Some(s.pre_impact_deflection_m)
        );
    }

    #[test]
    fn a_head_against_a_wall_has_a_severity_without_acceleration() {
        let run = run_driven_text(CJ_WALL, &[], no_log(), &CancelToken::new()).unwrap();
        let sev = run.summary.severity.as_ref().expect("a severity");
        assert!(sev.hic15.is_none() && sev.peak_acceleration_mps2.is_none());
        // the logged force peaks just below the located peak: so does the severity's
        let p = run.summary.peak_force_n;
        assert!(sev.peak_force_n <= p && sev.peak_force_n >= (1.0 - 1e-3) * p);
        // the energy transferred is the contact's work while the indentation grows (the
        // integrator's impact energy), to the trace's trapezoid
        let e = run.summary.impact_energy_j;
        assert!(
            (sev.energy_transferred_j - e).abs() <= 1e-3 * e,
            "{} vs {e}",
            sev.energy_transferred_j
        );
        let row = crate::study::sweep::driven_values(&run.summary);
        let hic = crate::study::sweep::SUMMARY_COLUMNS
            .iter()
            .position(|c| *c == "hic15")
            .unwrap();
        assert_eq!(row[hic], None);
    }

    #[test]
    fn a_cancelled_driven_run_stops() {
        let cancel = CancelToken::new();
        cancel.cancel();
        let e = run_driven_text(CL_WALL, &[], no_log(), &cancel).unwrap_err();
        assert_eq!(e.kind(), crate::ErrorKind::Interrupted);
    }
}
