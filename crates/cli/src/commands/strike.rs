//! `flexrig strike`: one driven CJ or CL strike from a drive description (TOML, see
//! assets/drives/) or from flags, see [`flexrig::driven::strike`]; a summary or JSON.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use flexrig::driven::drive::HeadSupport;
use flexrig::driven::scene::note_text;
use flexrig::driven::strike::{
    FieldNames, LinkModel, StrikeDescription, StrikeDesign, StrikeFlags, StrikeOptions,
    run as run_strike,
};
use flexrig::{CancelToken, Error};

use crate::print::{line, print_json};

/// The link design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DesignArg {
    /// Rigid link on a torsion spring.
    Cj,
    /// Beam clamped to the hub.
    Cl,
}

/// How the head is held.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum SupportArg {
    /// A free head.
    Free,
    /// Against a wall.
    Wall,
}

/// The link's model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LinkModelArg {
    /// Geometrically exact, with the dome (the default).
    Exact,
    /// The faster linear option: within 1.1e-4 of the exact peak on the bundled stiff-link
    /// drives, up to 2.5 % off in the peak and 9 % in the duration on a soft link that bends.
    Linear,
}

/// The flags' defaults: the library's (assets/drives/cl_free_head.toml).
const D: StrikeFlags = StrikeFlags::DEFAULT;

/// Arguments of `flexrig strike`. Without FILE the flags describe the strike (their defaults:
/// assets/drives/cl_free_head.toml, [`StrikeFlags::DEFAULT`]); with FILE they may not be given.
#[derive(Debug, Args)]
pub struct StrikeArgs {
    /// Drive description (TOML: design, horizon_s, [link], [drive], [person], [placement]).
    #[arg(value_name = "FILE")]
    pub file: Option<PathBuf>,
    /// Link design.
    #[arg(long, value_enum, default_value_t = DesignArg::of(D.design), conflicts_with = "file")]
    pub design: DesignArg,
    /// Link mass m_r [kg].
    #[arg(
        long,
        value_name = "KG",
        default_value_t = D.m_r,
        conflicts_with = "file"
    )]
    pub m_r: f64,
    /// Link length L [m].
    #[arg(long, value_name = "M", default_value_t = D.length, conflicts_with = "file")]
    pub length: f64,
    /// Lateral tip stiffness k_δ [N/m].
    #[arg(
        long,
        value_name = "N_M",
        default_value_t = D.k_delta,
        conflicts_with = "file"
    )]
    pub k_delta: f64,
    /// Tip payload m_e [kg].
    #[arg(
        long,
        value_name = "KG",
        default_value_t = D.m_e,
        conflicts_with = "file"
    )]
    pub m_e: f64,
    /// Rotor inertia at the motor shaft J_m [kg·m²].
    #[arg(
        long,
        value_name = "KG_M2",
        default_value_t = D.rotor_inertia,
        conflicts_with = "file"
    )]
    pub rotor_inertia: f64,
    /// Gear ratio N (> 0).
    #[arg(
        long,
        value_name = "N",
        default_value_t = D.gear_ratio,
        conflicts_with = "file"
    )]
    pub gear_ratio: f64,
    /// Viscous friction at the motor shaft [N·m·s/rad].
    #[arg(
        long,
        value_name = "NMS",
        default_value_t = D.friction,
        conflicts_with = "file"
    )]
    pub friction: f64,
    /// Commanded joint speed after the ramp [rad/s].
    #[arg(
        long,
        value_name = "RAD_S",
        default_value_t = D.speed,
        conflicts_with = "file"
    )]
    pub speed: f64,
    /// Duration of the smooth (quintic) speed ramp [s].
    #[arg(long, value_name = "S", default_value_t = D.ramp_time, conflicts_with = "file")]
    pub ramp_time: f64,
    /// PD gain on the joint angle K_p [N·m/rad].
    #[arg(
        long,
        value_name = "NM_RAD",
        default_value_t = D.kp,
        conflicts_with = "file"
    )]
    pub kp: f64,
    /// PD gain on the joint speed K_d [N·m·s/rad].
    #[arg(
        long,
        value_name = "NMS_RAD",
        default_value_t = D.kd,
        conflicts_with = "file"
    )]
    pub kd: f64,
    /// Largest motor-shaft torque [N·m] (> 0).
    #[arg(
        long,
        value_name = "NM",
        default_value_t = D.torque_limit,
        conflicts_with = "file"
    )]
    pub torque_limit: f64,
    /// Head mass m_h [kg].
    #[arg(
        long,
        value_name = "KG",
        default_value_t = D.m_h,
        conflicts_with = "file"
    )]
    pub m_h: f64,
    /// How the head is held.
    #[arg(long, value_enum, default_value_t = SupportArg::Free, conflicts_with = "file")]
    pub support: SupportArg,
    /// Contact stiffness k_c [N/mⁿ].
    #[arg(long, value_name = "K", default_value_t = D.k_c, conflicts_with = "file")]
    pub k_c: f64,
    /// Hertz exponent n.
    #[arg(long, value_name = "N", default_value_t = D.n, conflicts_with = "file")]
    pub n: f64,
    /// The person stands where the commanded motion is this long after the ramp [s].
    #[arg(long, value_name = "S", default_value_t = D.settle, conflicts_with = "file")]
    pub settle: f64,
    /// Longest wait for the link to arrive [s].
    #[arg(long, value_name = "S", default_value_t = D.horizon, conflicts_with = "file")]
    pub horizon: f64,
    /// Radius of the dome on the link's tip [m].
    #[arg(long, value_name = "M", default_value_t = D.dome_radius, conflicts_with = "file")]
    pub dome_radius: f64,
    /// How far the dome's apex sits ahead of the link's axis, towards the person [m] (at most
    /// twice the radius).
    #[arg(long, value_name = "M", default_value_t = D.dome_standoff, conflicts_with = "file")]
    pub dome_standoff: f64,
    /// The link's model: exact (the link bends and turns geometrically exactly, the dome's
    /// geometry in the contact) or linear (faster: within 1.1e-4 of the exact peak on the
    /// default stiff link, but up to 2.5 % off in the peak and 9 % in the contact's duration on
    /// a soft link that bends; docs/driven.md).
    #[arg(long, value_enum, default_value_t = LinkModelArg::Exact, conflicts_with = "file")]
    pub link_model: LinkModelArg,
    /// Sample the motion every this many seconds and write strike_trace.csv into --out.
    #[arg(long, value_name = "S")]
    pub trace_every: Option<f64>,
    /// Directory for strike_trace.csv (with --trace-every).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON instead of the summary.
    #[arg(long)]
    pub json: bool,
}

impl LinkModelArg {
    /// The library's model.
    pub fn model(self) -> LinkModel {
        match self {
            LinkModelArg::Exact => LinkModel::Exact,
            LinkModelArg::Linear => LinkModel::Linear,
        }
    }
}

impl DesignArg {
    fn of(design: StrikeDesign) -> Self {
        match design {
            StrikeDesign::Cj => DesignArg::Cj,
            StrikeDesign::Cl => DesignArg::Cl,
        }
    }
}

impl StrikeArgs {
    /// The description from FILE or from the flags (errors name the flag or the file's field).
    fn description(&self) -> Result<StrikeDescription, Error> {
        if let Some(file) = &self.file {
            return StrikeDescription::read(file);
        }
        StrikeFlags {
            design: match self.design {
                DesignArg::Cj => StrikeDesign::Cj,
                DesignArg::Cl => StrikeDesign::Cl,
            },
            m_r: self.m_r,
            length: self.length,
            k_delta: self.k_delta,
            m_e: self.m_e,
            rotor_inertia: self.rotor_inertia,
            gear_ratio: self.gear_ratio,
            friction: self.friction,
            speed: self.speed,
            ramp_time: self.ramp_time,
            kp: self.kp,
            kd: self.kd,
            torque_limit: self.torque_limit,
            m_h: self.m_h,
            support: match self.support {
                SupportArg::Free => HeadSupport::Free,
                SupportArg::Wall => HeadSupport::Wall,
            },
            k_c: self.k_c,
            n: self.n,
            settle: self.settle,
            horizon: self.horizon,
            dome_radius: self.dome_radius,
            dome_standoff: self.dome_standoff,
            link_model: self.link_model.model(),
        }
        .description()
    }
}

/// Runs `flexrig strike`.
pub fn run(args: &StrikeArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let description = args.description()?;
    let names = if args.file.is_some() {
        FieldNames::File
    } else {
        FieldNames::Flags
    };
    // plausibility warnings before the run (on standard error; the JSON lists them too)
    for w in description.warnings(names) {
        eprintln!("warning: {w}");
    }
    let r = run_strike(
        &description,
        &StrikeOptions {
            trace_every: args.trace_every,
            out: Some(args.out.clone()),
            names,
        },
        cancel,
    )?;
    if args.json {
        let v = serde_json::to_value(&r).map_err(|e| Error::NonFinite {
            what: "strike result".into(),
            value: e.to_string(),
            advice: "a non-finite value cannot be printed as JSON".into(),
        })?;
        return print_json(out, &v);
    }
    let o = &r.outcome;
    let c = &o.contact;
    line(
        out,
        format!(
            "Driven {} strike: peak {:.6e} N at t = {:.6} s (onset {:.6} s, duration {:.6e} s)",
            if r.design == StrikeDesign::Cj {
                "CJ"
            } else {
                "CL"
            },
            c.peak_force_n,
            c.time_of_peak_s,
            c.onset_s,
            c.duration_s
        ),
    )?;
    line(
        out,
        format!(
            "  approach speed {:.6} m/s (commanded tip speed {}), pre-impact deflection {:.6e} m",
            o.approach_speed_mps,
            o.commanded_tip_speed_mps
                .map_or("none".to_string(), |v| format!("{v:.6} m/s")),
            o.pre_impact_deflection_m
        ),
    )?;
    line(
        out,
        format!(
            "  joint torque at the onset {:.4} N·m, largest in the contact {:.4} N·m",
            o.joint_torque_at_onset_nm, o.peak_joint_torque_nm
        ),
    )?;
    let e = &o.energy;
    line(
        out,
        format!(
            "  energy [J]: impact {:.6e}, motor work {:.6e}, dissipated {:.6e}, mechanical change {:.6e}, residual {:.1e}",
            e.impact_energy_j, e.motor_work_j, e.dissipated_j, e.mechanical_change_j, e.residual_j
        ),
    )?;
    for note in &o.notes {
        line(out, format!("  note: {}", note_text(note)))?;
    }
    if let Some(path) = &r.trace_csv {
        line(out, format!("Wrote {}", path.display()))?;
    }
    Ok(())
}
