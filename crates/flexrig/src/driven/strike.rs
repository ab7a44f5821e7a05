//! One driven strike: a CJ or CL robot link moved by its drive (motor, gear, trajectory or
//! controller) into a person (free head, neck or wall), from a TOML description
//! (assets/drives/*.toml) or built in code; returns flexrig-impact's
//! [`DrivenOutcome`] (peak, time of peak, duration, pre-impact deflection, joint torque, energy
//! balance, notes) and optionally writes the motion sampled along the run as a CSV.
//!
//! The description holds flexrig-impact's [`DrivenStrike`] fields (`horizon_s`, `[link]`,
//! `[drive]`, `[person]`, `[placement]`) and the `design` (`"cj"` or `"cl"`); every field is checked, and
//! an error names it as written in the file (`drive.motor.gear_ratio`, `person.m_h`, …).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexrig_impact::drive::{Drive, Person, Placement};
use flexrig_impact::driven_cj::{CjSettings, run_driven_cj};
use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl};
use flexrig_impact::{DrivenOutcome, DrivenStrike, LinkParams, TraceSample};
use serde::{Deserialize, Serialize};

use super::{check, num};
use crate::output::{ensure_dir, positive_arg, read_text, write_atomic};
use crate::{CancelToken, Error};

/// The link design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StrikeDesign {
    /// Rigid link on a torsion spring (series elastic actuator).
    Cj,
    /// FE beam clamped to the motor hub.
    Cl,
}

/// A drive description: the design and the strike.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StrikeDescription {
    /// CJ or CL.
    pub design: StrikeDesign,
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
}

impl StrikeDescription {
    /// Parses and checks a description; `source` (the file's path) names it in errors.
    pub fn parse(text: &str, source: &str) -> Result<StrikeDescription, Error> {
        let d: StrikeDescription = toml::from_str(text).map_err(|e| Error::InvalidArgument {
            arg: source.into(),
            value: "(drive description)".into(),
            allowed: e.message().trim().to_string(),
        })?;
        d.strike().validate()?;
        Ok(d)
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

    /// Reads, parses and checks the file at `path`.
    pub fn read(path: &Path) -> Result<StrikeDescription, Error> {
        StrikeDescription::parse(&read_text(path)?, &path.display().to_string())
    }
}

/// How the strike is run and what it writes.
#[derive(Debug, Clone, PartialEq)]
pub struct StrikeOptions {
    /// Trace sampling interval \[s\] (`--trace-every`; `None`: no trace).
    pub trace_every: Option<f64>,
    /// Directory for strike_trace.csv (`--out`; only with a trace).
    pub out: Option<PathBuf>,
}

/// The outcome and the file written.
#[derive(Debug, Clone, Serialize)]
pub struct StrikeResult {
    /// The design.
    pub design: StrikeDesign,
    /// The integrator's result.
    pub outcome: DrivenOutcome,
    /// strike_trace.csv, if written.
    pub trace_csv: Option<PathBuf>,
}

/// Runs the strike (the default integrator settings of flexrig-impact: CJ DOP853 rtol 1e-10, CL
/// tol 1e-6 on the graded mesh up to L/48).
pub fn run(
    description: &StrikeDescription,
    options: &StrikeOptions,
    cancel: &CancelToken,
) -> Result<StrikeResult, Error> {
    let trace_every = options
        .trace_every
        .map(|t| positive_arg("--trace-every", t))
        .transpose()?;
    check(cancel)?;
    let strike = description.strike();
    let outcome = match description.design {
        StrikeDesign::Cj => run_driven_cj(
            &strike,
            &CjSettings {
                trace_every,
                ..CjSettings::DEFAULT
            },
        )?,
        StrikeDesign::Cl => run_driven_cl(
            &strike,
            &ClDriveSettings {
                trace_every,
                ..ClDriveSettings::DEFAULT
            },
        )?,
    };
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
    })
}

/// The trace's CSV header (SI units in the names).
pub const TRACE_HEADER: &str = "t_s,hub_angle_rad,hub_speed_rad_s,tip_deflection_m,indentation_m,force_n,joint_torque_nm,head_position_m";

/// One row per trace sample, each number in its shortest exact form.
pub fn trace_text(trace: &[TraceSample]) -> String {
    let mut text = format!("{TRACE_HEADER}\n");
    for s in trace {
        let _ = writeln!(
            text,
            "{},{},{},{},{},{},{},{}",
            num(s.t),
            num(s.hub_angle_rad),
            num(s.hub_speed_rad_s),
            num(s.tip_deflection_m),
            num(s.indentation_m),
            num(s.force_n),
            num(s.joint_torque_nm),
            num(s.head_position_m)
        );
    }
    text
}
