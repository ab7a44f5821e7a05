//! One driven strike: a CJ or CL robot link moved by its drive (motor, gear, trajectory or
//! controller) into a person (free head, neck or wall), from a TOML description
//! (assets/drives/*.toml) or built in code; returns flexrig-impact's
//! [`DrivenOutcome`] (peak, time of peak, duration, pre-impact deflection, joint torque, energy
//! balance, notes) and optionally writes the motion sampled along the run as a CSV.
//!
//! The description holds flexrig-impact's [`DrivenStrike`] fields (`horizon_s`, `[link]`,
//! `[drive]`, `[person]`, `[placement]`), the `design` (`"cj"` or `"cl"`), the dome on the
//! link's tip (`[dome]`: `radius_m`, `standoff_m`; absent: the test bed's) and the link's model
//! (`link_model`: `"exact"`, the default, or `"linear"`); every field is checked, and an error
//! names it as written in the file (`drive.motor.gear_ratio`, `person.m_h`, …).
//!
//! **The models.** `exact` (the default): the CL link is flexrig-impact's geometrically exact
//! corotational beam on the driven hub ([`run_exact_cl`], its mesh checked to 5e-6), the CJ link
//! the rigid link on its spring with the dome's exact geometry ([`run_exact_cj`]), both with the
//! description's dome. `linear`: the linear modal CL ([`run_driven_cl`]) and the
//! arc-coordinate CJ ([`run_driven_cj`]), the contact along the tip's path, no dome: faster,
//! within 1.1e-4 of the exact peak on the bundled stiff-link drives but 1.1e-3 to 2.5e-2 off in
//! the peak and up to 9 % in the contact's duration on the test bed's soft link turning at
//! 3 rad/s (docs/driven.md, "The linear option's error").

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Dome, Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::driven_cj::{CjSettings, run_driven_cj_until, run_exact_cj_until};
use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl_until};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl_until};
use flexrig_impact::{DrivenOutcome, DrivenStrike, LinkParams, TraceSample};
use serde::{Deserialize, Serialize};

// Most trace samples over the wait (a driven scene's `horizon_s` × `record.sample_rate_hz`
// budget, the rig's, as the scene's `MAX_SAMPLES`; taken from the rig so that this file and the
// scene's do not import each other); flexrig-impact thins a trace beyond its own cap.
use super::{check, num};
use crate::shared::output::{ensure_dir, positive_arg, read_text, write_atomic};
use crate::{CancelToken, Error};
use flexrig_rig::limits::MAX_SAMPLES;

/// The link design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StrikeDesign {
    /// Rigid link on a torsion spring (series elastic actuator).
    Cj,
    /// FE beam clamped to the motor hub.
    Cl,
}

/// How the link is modelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LinkModel {
    /// Geometrically exact, with the dome (the default): the CL link a corotational beam on the
    /// driven hub, the CJ link rigid on its spring.
    #[default]
    Exact,
    /// The faster linear option: the linear modal CL beam, the CJ in the tip's arc coordinate,
    /// the contact along the tip's path (its error against the exact model: the module's doc).
    Linear,
}

impl LinkModel {
    /// `exact` or `linear` as the model; an error names `flag`.
    pub fn parse(flag: &str, word: &str) -> Result<LinkModel, Error> {
        match word {
            "exact" => Ok(LinkModel::Exact),
            "linear" => Ok(LinkModel::Linear),
            _ => Err(Error::InvalidArgument {
                arg: flag.into(),
                value: word.into(),
                allowed: "one of exact, linear".into(),
            }),
        }
    }
}

/// The test bed's dome, a description's dome when it gives none.
pub fn test_bed_dome() -> Dome {
    Dome::TEST_BED
}

/// A drive description: the design and the strike.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrikeDescription {
    /// CJ or CL.
    pub design: StrikeDesign,
    /// The link's model (`link_model`; absent: exact).
    #[serde(default)]
    pub link_model: LinkModel,
    /// Longest time to wait for the link to arrive \[s\].
    pub horizon_s: f64,
    /// The link (m_r, length, k_delta, m_e).
    pub link: LinkParams,
    /// The joint's drive (`[drive.motor]`, `[drive.command]`).
    pub drive: Drive,
    /// The person (`m_h`, `speed`, `[person.support]`, `[person.contact]`, `[person.damping]`).
    pub person: Person,
    /// Where the person stands (`[placement]`).
    pub placement: Placement,
    /// The dome on the link's tip (`[dome]`: `radius_m`, `standoff_m`; absent: the test bed's,
    /// R = 71.5 mm with its apex 30 mm ahead of the link's axis).
    #[serde(default = "test_bed_dome")]
    pub dome: Dome,
}

impl StrikeDescription {
    /// Parses and checks a description; `source` (the file's path) names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<StrikeDescription, Error> {
        let d: StrikeDescription = toml::from_str(text).map_err(|e| {
            // the line of the offending value, and serde's Rust terms in the file's words
            let at = e
                .span()
                .map(|r| {
                    format!(
                        "line {}: ",
                        text[..r.start.min(text.len())].matches('\n').count() + 1
                    )
                })
                .unwrap_or_default();
            Error::InvalidArgument {
                arg: source.into(),
                value: "(drive description)".into(),
                allowed: format!(
                    "{at}{}",
                    flexrig_rig::format_message::plain(e.message().trim())
                ),
            }
        })?;
        d.validate()?;
        Ok(d)
    }

    /// Checks every field (the strike's and the dome's).
    pub fn validate(&self) -> Result<(), Error> {
        self.strike().validate()?;
        self.dome.validate()?;
        Ok(())
    }

    /// Solves the strike by the description's link model with the description's dome,
    /// sampling the motion every `trace_every` seconds if given (the integrators' default
    /// settings otherwise: [`ExactSettings::DEFAULT`], [`CjSettings::DEFAULT`],
    /// [`ClDriveSettings::DEFAULT`]).
    pub fn solve(
        &self,
        trace_every: Option<f64>,
        stop: &std::sync::atomic::AtomicBool,
    ) -> Result<DrivenOutcome, Error> {
        let strike = self.strike();
        let cj = CjSettings {
            trace_every,
            ..CjSettings::DEFAULT
        };
        Ok(match (self.design, self.link_model) {
            (StrikeDesign::Cl, LinkModel::Exact) => run_exact_cl_until(
                &strike,
                &ExactSettings {
                    trace_every,
                    dome: self.dome,
                    ..ExactSettings::DEFAULT
                },
                stop,
            )?,
            (StrikeDesign::Cj, LinkModel::Exact) => {
                run_exact_cj_until(&strike, &cj, &self.dome, stop)?
            }
            (StrikeDesign::Cl, LinkModel::Linear) => run_driven_cl_until(
                &strike,
                &ClDriveSettings {
                    trace_every,
                    ..ClDriveSettings::DEFAULT
                },
                stop,
            )?,
            (StrikeDesign::Cj, LinkModel::Linear) => run_driven_cj_until(&strike, &cj, stop)?,
        })
    }

    /// The physics crate's set-up.
    pub fn strike(&self) -> DrivenStrike {
        DrivenStrike {
            link: self.link,
            drive: self.drive.clone(),
            person: self.person,
            placement: self.placement,
            horizon_s: self.horizon_s,
        }
    }

    /// What looks wrong though it is allowed, by the shared rule of
    /// [`crate::shared::plausibility`]: a link or payload heavier than 200 kg (grams typed for
    /// kilograms), a link longer than 5 m (millimetres for metres), a commanded tip speed beyond
    /// 10 m/s (degrees per second for radians per second), a person approaching faster than
    /// 10 m/s. Each names the value as the user gave it (`names`: the file's fields or the
    /// flags).
    pub fn warnings(&self, names: FieldNames) -> Vec<crate::shared::plausibility::Warning> {
        use crate::shared::plausibility::{joint_speed, length, mass, speed};
        let name = |field: &str| names.of(field);
        let mut out: Vec<_> = [
            mass(&name("link.m_r"), self.link.m_r),
            mass(&name("link.m_e"), self.link.m_e),
            length(&name("link.length"), self.link.length),
        ]
        .into_iter()
        .flatten()
        .collect();
        if let Some(profile) = self.drive.profile() {
            out.extend(joint_speed(
                &name("drive.command.profile.speed"),
                profile.final_speed(),
                self.link.length,
            ));
        }
        out.extend(speed(&name("person.speed"), self.person.speed));
        out
    }

    /// Reads, parses and checks the file at `path`.
    pub fn read(path: &Path) -> Result<StrikeDescription, Error> {
        StrikeDescription::parse(&read_text(path)?, &path.display().to_string())
    }
}

/// How the user named a description's values: the drive file's fields (`link.m_r`) or
/// `flexrig strike`'s flags (`--m-r`; Python's keyword arguments are the flags' names).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FieldNames {
    /// The fields of a drive description or a driven scene file.
    #[default]
    File,
    /// The flags of [`StrikeFlags`].
    Flags,
}

impl FieldNames {
    /// The file field `field` (dotted path) as the user typed it.
    pub fn of(self, field: &str) -> String {
        match self {
            FieldNames::File => field.to_string(),
            FieldNames::Flags => match field {
                "link.m_r" => "--m-r",
                "link.m_e" => "--m-e",
                "link.length" => "--length",
                "link.k_delta" => "--k-delta",
                "drive.command.profile.speed" => "--speed",
                "person.m_h" => "--m-h",
                other => other,
            }
            .to_string(),
        }
    }
}

/// A strike described by a few numbers instead of a file: the flags of `flexrig strike` and the
/// keyword arguments of its Python twin. A position PD controller drives the joint on a smooth
/// (quintic) speed ramp, the person stands where the commanded motion arrives `settle` seconds
/// after the ramp, and the contact is elastic Hertz. [`StrikeFlags::DEFAULT`] is the
/// description assets/drives/cl_free_head.toml.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrikeFlags {
    /// Link design (`--design`).
    pub design: StrikeDesign,
    /// Link mass m_r \[kg\] (`--m-r`).
    pub m_r: f64,
    /// Link length L \[m\] (`--length`).
    pub length: f64,
    /// Lateral tip stiffness k_δ \[N/m\] (`--k-delta`).
    pub k_delta: f64,
    /// Tip payload m_e \[kg\] (`--m-e`).
    pub m_e: f64,
    /// Rotor inertia at the motor shaft J_m \[kg·m²\] (`--rotor-inertia`).
    pub rotor_inertia: f64,
    /// Gear ratio N, > 0 (`--gear-ratio`).
    pub gear_ratio: f64,
    /// Viscous friction at the motor shaft \[N·m·s/rad\] (`--friction`).
    pub friction: f64,
    /// Commanded joint speed after the ramp \[rad/s\] (`--speed`).
    pub speed: f64,
    /// Duration of the smooth speed ramp \[s\] (`--ramp-time`).
    pub ramp_time: f64,
    /// PD gain on the joint angle K_p \[N·m/rad\] (`--kp`).
    pub kp: f64,
    /// PD gain on the joint speed K_d \[N·m·s/rad\] (`--kd`).
    pub kd: f64,
    /// Largest motor-shaft torque \[N·m\], > 0 (`--torque-limit`).
    pub torque_limit: f64,
    /// Head mass m_h \[kg\] (`--m-h`).
    pub m_h: f64,
    /// How the head is held: free or against a wall (`--support`).
    pub support: HeadSupport,
    /// Contact stiffness k_c \[N/mⁿ\] (`--k-c`).
    pub k_c: f64,
    /// Hertz exponent n (`--n`).
    pub n: f64,
    /// The person stands where the commanded motion is this long after the ramp \[s\]
    /// (`--settle`).
    pub settle: f64,
    /// Longest wait for the link to arrive \[s\] (`--horizon`).
    pub horizon: f64,
    /// The dome's radius R \[m\] (`--dome-radius`).
    pub dome_radius: f64,
    /// How far the dome's apex sits ahead of the link's axis \[m\] (`--dome-standoff`).
    pub dome_standoff: f64,
    /// The link's model (`--link-model`).
    pub link_model: LinkModel,
}

impl StrikeFlags {
    /// The defaults of the flags: assets/drives/cl_free_head.toml (a 10 kg, 1 m CL link with a
    /// 0.1 kg payload, geared 50:1, ramped to 2 rad/s in 0.5 s, into a free 4 kg head).
    pub const DEFAULT: StrikeFlags = StrikeFlags {
        design: StrikeDesign::Cl,
        m_r: 10.0,
        length: 1.0,
        k_delta: 1e8,
        m_e: 0.1,
        rotor_inertia: 1e-4,
        gear_ratio: 50.0,
        friction: 1e-5,
        speed: 2.0,
        ramp_time: 0.5,
        kp: 500.0,
        kd: 40.0,
        torque_limit: 1.0,
        m_h: 4.0,
        support: HeadSupport::Free,
        k_c: 1e8,
        n: 2.0,
        settle: 0.3,
        horizon: 5.0,
        dome_radius: Dome::TEST_BED.radius_m,
        dome_standoff: Dome::TEST_BED.standoff_m,
        link_model: LinkModel::Exact,
    };

    /// The drive description these numbers make, checked; an error names the flag
    /// (`--k-c/--n`) or the description's field (`drive.motor.gear_ratio`).
    pub fn description(&self) -> Result<StrikeDescription, Error> {
        self.checked_description()
            .map_err(|e| self.named_by_flag(e))
    }

    /// The flag of a description's field, and the value the user gave it.
    fn flag_of(&self, field: &str) -> Option<(&'static str, f64)> {
        let leaf = field.rsplit('.').next().unwrap_or(field);
        Some(match leaf {
            "m_r" => ("--m-r", self.m_r),
            "length" => ("--length", self.length),
            "k_delta" => ("--k-delta", self.k_delta),
            "m_e" => ("--m-e", self.m_e),
            "rotor_inertia" => ("--rotor-inertia", self.rotor_inertia),
            "gear_ratio" => ("--gear-ratio", self.gear_ratio),
            "friction" => ("--friction", self.friction),
            "speed" if field.starts_with("drive") => ("--speed", self.speed),
            "ramp_time" => ("--ramp-time", self.ramp_time),
            "kp" => ("--kp", self.kp),
            "kd" => ("--kd", self.kd),
            "torque_limit" => ("--torque-limit", self.torque_limit),
            "m_h" => ("--m-h", self.m_h),
            "k" | "k_c" if !field.starts_with("drive") => ("--k-c", self.k_c),
            "n" if !field.starts_with("drive") => ("--n", self.n),
            "settle" | "placement" => ("--settle", self.settle),
            "horizon_s" => ("--horizon", self.horizon),
            "radius_m" => ("--dome-radius", self.dome_radius),
            "standoff_m" => ("--dome-standoff", self.dome_standoff),
            _ => return None,
        })
    }

    /// The error with the description's field replaced by the flag the user typed, and its
    /// value by the flag's value (the fields' own words would name a file the user never saw).
    fn named_by_flag(&self, e: Error) -> Error {
        use flexrig_impact::ImpactError;
        let (field, allowed) = match &e {
            Error::Impact(ImpactError::InvalidParameter { field, allowed, .. }) => {
                (field.clone(), allowed.clone())
            }
            Error::Impact(ImpactError::Contact(
                flexrig_contact::ContactError::InvalidParameter { field, allowed, .. },
            ))
            | Error::Contact(flexrig_contact::ContactError::InvalidParameter {
                field,
                allowed,
                ..
            }) => (field.clone(), allowed.clone()),
            Error::InvalidArgument { arg, allowed, .. } => (arg.clone(), allowed.clone()),
            _ => return e,
        };
        let Some((flag, value)) = self.flag_of(&field) else {
            return e;
        };
        Error::InvalidArgument {
            arg: flag.into(),
            value: flexrig_contact::validate::display(value),
            allowed: rename_fields(&allowed),
        }
    }

    fn checked_description(&self) -> Result<StrikeDescription, Error> {
        let contact = Hertz::named(self.k_c, self.n, "person.contact.k", "person.contact.n")?;
        let motor = Motor::new(self.rotor_inertia, self.gear_ratio, self.friction)?;
        let drive = Drive::controller(
            motor,
            Profile::SmoothRamp {
                speed: self.speed,
                ramp_time: self.ramp_time,
            },
            Gains::position_pd(self.kp, self.kd),
            Some(self.torque_limit),
        )?;
        let d = StrikeDescription {
            design: self.design,
            link_model: self.link_model,
            dome: Dome {
                radius_m: self.dome_radius,
                standoff_m: self.dome_standoff,
            },
            horizon_s: self.horizon,
            link: LinkParams {
                m_r: self.m_r,
                length: self.length,
                k_delta: self.k_delta,
                m_e: self.m_e,
            },
            drive,
            person: Person {
                m_h: self.m_h,
                support: self.support,
                contact,
                damping: DampingSpec::NONE,
                speed: 0.0,
            },
            placement: Placement::AfterRamp {
                settle: self.settle,
            },
        };
        d.validate()?;
        Ok(d)
    }
}

/// An explanation written in the description's words, in the flags' words.
fn rename_fields(text: &str) -> String {
    const WORDS: &[(&str, &str)] = &[
        ("drive.command.profile.speed", "--speed"),
        ("drive.command.profile.ramp_time", "--ramp-time"),
        ("drive.command.gains.kp", "--kp"),
        ("drive.command.gains.kd", "--kd"),
        ("drive.motor.rotor_inertia", "--rotor-inertia"),
        ("drive.command.torque_limit", "--torque-limit"),
        ("placement.settle", "--settle"),
        ("link.m_r", "--m-r"),
        ("person.contact.k", "--k-c"),
        ("person.contact.n", "--n"),
        ("person.speed", "the person's speed (0)"),
        ("link.length", "--length"),
        ("horizon_s", "--horizon"),
        ("gear_ratio²", "--gear-ratio²"),
        ("dome.radius_m", "--dome-radius"),
        ("dome.standoff_m", "--dome-standoff"),
    ];
    let mut out = text.to_string();
    for (from, to) in WORDS {
        out = out.replace(from, to);
    }
    out
}

impl StrikeDesign {
    /// `cj` or `cl` as the design; an error names `flag`.
    pub fn parse(flag: &str, word: &str) -> Result<StrikeDesign, Error> {
        match word {
            "cj" => Ok(StrikeDesign::Cj),
            "cl" => Ok(StrikeDesign::Cl),
            _ => Err(Error::InvalidArgument {
                arg: flag.into(),
                value: word.into(),
                allowed: "one of cj, cl".into(),
            }),
        }
    }
}

/// `free` or `wall` as the head's support (the flags' choices; a neck needs a description
/// file); an error names `flag`.
pub fn parse_support(flag: &str, word: &str) -> Result<HeadSupport, Error> {
    match word {
        "free" => Ok(HeadSupport::Free),
        "wall" => Ok(HeadSupport::Wall),
        _ => Err(Error::InvalidArgument {
            arg: flag.into(),
            value: word.into(),
            allowed: "one of free, wall".into(),
        }),
    }
}

/// How the strike is run and what it writes.
#[derive(Debug, Clone, PartialEq)]
pub struct StrikeOptions {
    /// Trace sampling interval \[s\] (`--trace-every`; `None`: no trace).
    pub trace_every: Option<f64>,
    /// Directory for strike_trace.csv (`--out`; only with a trace).
    pub out: Option<PathBuf>,
    /// How the user named the description's values: the warnings name them so.
    pub names: FieldNames,
}

/// The outcome and the file written.
#[derive(Debug, Clone, Serialize)]
pub struct StrikeResult {
    /// The design.
    pub design: StrikeDesign,
    /// The integrator's result.
    pub outcome: DrivenOutcome,
    /// strike_trace.csv, if written (absent from the JSON otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trace_csv: Option<PathBuf>,
    /// The description's plausibility warnings ([`StrikeDescription::warnings`]; empty: none).
    pub warnings: Vec<crate::shared::plausibility::Warning>,
}

/// Runs the strike by the description's link model and dome
/// ([`StrikeDescription::solve`]).
pub fn run(
    description: &StrikeDescription,
    options: &StrikeOptions,
    cancel: &CancelToken,
) -> Result<StrikeResult, Error> {
    let trace_every = options
        .trace_every
        .map(|t| positive_arg("--trace-every", t))
        .transpose()?;
    if let Some(every) = trace_every {
        // the samples over the wait and a contact as long (checked to fit in the horizon)
        let samples = description.horizon_s / every;
        if !(samples <= MAX_SAMPLES) {
            return Err(Error::InvalidArgument {
                arg: "--trace-every".into(),
                value: flexrig_contact::validate::display(every),
                allowed: format!(
                    "at least {} s: the trace keeps one sample per interval over the wait of \
                     {} s (at most {} samples)",
                    flexrig_contact::validate::display(description.horizon_s / MAX_SAMPLES),
                    flexrig_contact::validate::display(description.horizon_s),
                    flexrig_contact::validate::display(MAX_SAMPLES)
                ),
            });
        }
    }
    check(cancel)?;
    let flag = cancel.flag();
    let outcome = description.solve(trace_every, &flag)?;
    check(cancel)?;
    let trace_csv = match (&options.out, trace_every) {
        (Some(dir), Some(_)) => {
            ensure_dir(dir)?;
            let path = dir.join("strike_trace.csv");
            write_atomic(&path, trace_text(&outcome.trace).as_bytes())?;
            Some(path)
        }
        _ => None,
    };
    Ok(StrikeResult {
        design: description.design,
        outcome,
        trace_csv,
        warnings: description.warnings(options.names),
    })
}

/// The trace's CSV header (SI units in the names; `flexrig safety --trace` reads it as it is:
/// time, force, indentation and the head's acceleration).
pub const TRACE_HEADER: &str = "t_s,hub_angle_rad,hub_speed_rad_s,tip_deflection_m,indentation_m,force_n,joint_torque_nm,head_position_m,head_acceleration_mps2";

/// One row per trace sample, each number in its shortest exact form.
pub fn trace_text(trace: &[TraceSample]) -> String {
    let mut text = format!("{TRACE_HEADER}\n");
    for s in trace {
        let _ = writeln!(
            text,
            "{},{},{},{},{},{},{},{},{}",
            num(s.t),
            num(s.hub_angle_rad),
            num(s.hub_speed_rad_s),
            num(s.tip_deflection_m),
            num(s.indentation_m),
            num(s.force_n),
            num(s.joint_torque_nm),
            num(s.head_position_m),
            num(s.head_acceleration_mps2)
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_flags_are_the_cl_free_head_description() {
        let file = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../assets/drives/cl_free_head.toml"
        );
        let from_file = StrikeDescription::read(Path::new(file)).unwrap();
        assert_eq!(StrikeFlags::DEFAULT.description().unwrap(), from_file);
    }

    #[test]
    fn a_bad_flag_is_named() {
        let bad = StrikeFlags {
            n: -1.0,
            ..StrikeFlags::DEFAULT
        };
        let e = bad.description().unwrap_err().to_string();
        assert!(e.contains("--n = -1"), "{e}");
        let e = StrikeDesign::parse("--design", "cx")
            .unwrap_err()
            .to_string();
        assert!(e.contains("--design") && e.contains("cj, cl"), "{e}");
        let e = parse_support("--support", "neck").unwrap_err().to_string();
        assert!(e.contains("--support") && e.contains("free, wall"), "{e}");
    }
}
