//! `flexrig arm`: a real arm from its URDF along a trajectory — at every sample and contact point
//! the point's speed, the reflected mass along its velocity and the permissible speed of the
//! compliant impact into a body region, the speed-scaling factor and the verdict; see
//! [`flexrig::arm`].

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use flexrig::arm::{ArmDrive, ArmInput, ArmJoints, ArmPoint, ArmReport, simulation_settings};
use flexrig::safety::overall::method_name;
use flexrig::safety::{ContactKind, FeLink, SafetyMethod, Speed};
use flexrig::{CancelToken, Error};

use super::safety::{LinkArg, MethodArg};
use super::safety_args::{ContactArg, ContactLawArgs, missing};
use crate::print::{line, print_json};

/// How the joints behave on the impact's time scale.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum JointsArg {
    /// Rigid joints: the links' inertias only.
    Rigid,
    /// Rigid joints with the rotors' inertia reflected through the gear (--armature).
    Armature,
    /// Elastic joints (series elastic actuators): the rotors decoupled during the impact.
    Elastic,
}

/// The drive during the impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DriveArg {
    /// A stiff drive carries the joint on at its speed (flexrig safety's held joint).
    Held,
    /// The drive exerts no torque: the reflected mass coasts into the person.
    Free,
}

/// Arguments of `flexrig arm`.
#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct ArmArgs {
    /// The arm's URDF (with --trajectory; default: the bundled UR5, assets/robots/ur5.urdf).
    #[arg(long, value_name = "FILE.urdf")]
    pub urdf: Option<PathBuf>,
    /// The trajectory: a CSV with a header `time_s,JOINT,…` naming every moving joint, one
    /// sample per line, positions in rad (m for prismatic joints) (default: the UR5's bundled
    /// swing, assets/robots/ur5_swing.csv).
    #[arg(long, value_name = "FILE.csv")]
    pub trajectory: Option<PathBuf>,
    /// A candidate contact point LINK:x,y,z (m, in the link's frame), or LINK for its origin;
    /// repeat for several (default for the bundled UR5: a tool tip tool0:0,0,0.1, the wrist
    /// wrist_2_link, the mid-forearm forearm_link:0,0,0.2 and the elbow forearm_link).
    #[arg(long = "point", value_name = "LINK:X,Y,Z")]
    pub points: Vec<String>,
    /// The joints during the impact: rigid, armature (rigid with the rotors, --armature) or
    /// elastic (series elastic: the rotors decoupled).
    #[arg(long, value_enum, default_value = "rigid")]
    pub joints: JointsArg,
    /// The rotor inertia reflected through each gear, J_m N² [kg·m²], one per moving joint in
    /// the URDF's order, comma-separated (with --joints armature).
    #[arg(long, value_name = "KG_M2,…", value_delimiter = ',')]
    pub armature: Vec<f64>,
    /// Run the trajectory at this multiple of its speed (2: twice as fast).
    #[arg(long = "speed-scale", value_name = "S", default_value_t = 1.0)]
    pub speed_scale: f64,
    /// Relative step of the mass grid: each reflected mass is rounded up to the next of the
    /// masses (1 + step)^k kg and judged there, once per distinct mass (0: every mass exactly;
    /// at most 0.25).
    #[arg(long = "mass-step", value_name = "STEP", default_value_t = 0.01)]
    pub mass_step: f64,
    /// Body region key of the body model, e.g. chest, hands_and_fingers.
    #[arg(long, value_name = "REGION", default_value = "chest")]
    pub region: String,
    /// Specific area of the region for the pressure limit (default: its most sensitive).
    #[arg(long, value_name = "NAME")]
    pub area: Option<String>,
    /// Contact kind.
    #[arg(long, value_enum, default_value = "transient")]
    pub contact: ContactArg,
    /// The compliance between the arm and the person: cj (a joint spring) or cl (a bending link).
    #[arg(long, value_enum, default_value = "cj")]
    pub link: LinkArg,
    /// Its lateral stiffness at the contact point, k_δ [N/m] (default: rigid).
    #[arg(long = "k-delta", value_name = "N_PER_M")]
    pub k_delta: Option<f64>,
    /// The compliant link's own mass m_r [kg] (default: the URDF mass of the link that carries
    /// the first point); the rest of the reflected mass rides at its tip.
    #[arg(long = "link-mass", value_name = "KG")]
    pub link_mass: Option<f64>,
    /// The contact law and the contact-area model.
    #[command(flatten)]
    pub law: ContactLawArgs,
    /// The drive during the simulated impact: free (the reflected mass coasts into the person,
    /// as the standard's free robot mass) or held (a stiff drive carries the joint on: the
    /// person meets the compliance moving at its speed).
    #[arg(long, value_enum, default_value = "free")]
    pub drive: DriveArg,
    /// Tolerance of the simulated link's integrator (1e-10 to 1e-3).
    #[arg(long, value_name = "TOL", default_value = "1e-6")]
    pub tol: f64,
    /// Relative tolerance of the simulation's root search on the speed (1e-13 to 1e-4).
    #[arg(long = "root-rtol", value_name = "RTOL", default_value = "1e-6")]
    pub root_rtol: f64,
    /// Methods, comma-separated (default: all three; the overall verdict is the most
    /// restrictive).
    #[arg(long, value_enum, value_delimiter = ',')]
    pub method: Vec<MethodArg>,
    /// A body-model TOML file in the format of assets/safety/iso_ts_15066_2016.toml.
    #[arg(long = "body-model", value_name = "FILE")]
    pub body_model: Option<PathBuf>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Also draw the figure (reflected mass, speed and permissible speed along the path, per
    /// point): FILE.svg (or .pdf, .png).
    #[arg(long, value_name = "FILE.svg")]
    pub figure: Option<PathBuf>,
    /// Also write an MCAP log of the arm along the path for Foxglove, with FILE.layout.json
    /// beside it.
    #[arg(long, value_name = "FILE.mcap")]
    pub log: Option<PathBuf>,
    /// Also write a report for a risk assessment: FILE.md or FILE.html (its figure beside it).
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Overwrite an existing figure, log or report.
    #[arg(long)]
    pub force: bool,
}

impl ArmArgs {
    /// The library's input, with `defaults` as the points when none are given.
    pub fn input(&self, defaults: Vec<ArmPoint>) -> Result<ArmInput, Error> {
        let points = if self.points.is_empty() {
            if defaults.is_empty() {
                return Err(missing(
                    "--point",
                    "give at least one contact point LINK:x,y,z (m, in the link's frame) on \
                     your arm, e.g. --point tool0:0,0,0.1",
                ));
            }
            defaults
        } else {
            self.points
                .iter()
                .map(|p| ArmPoint::parse(p))
                .collect::<Result<_, _>>()?
        };
        let joints = match (self.joints, self.armature.is_empty()) {
            (JointsArg::Armature, false) => ArmJoints::Armature(self.armature.clone()),
            (JointsArg::Armature, true) => {
                return Err(missing(
                    "--armature",
                    "--joints armature needs the rotor inertias J_m N² (kg·m²), one per moving \
                     joint, comma-separated",
                ));
            }
            (_, false) => {
                return Err(Error::InvalidArgument {
                    arg: "--armature".into(),
                    value: "(given)".into(),
                    allowed: "only with --joints armature".into(),
                });
            }
            (JointsArg::Rigid, true) => ArmJoints::Rigid,
            (JointsArg::Elastic, true) => ArmJoints::Elastic,
        };
        let drive = match self.drive {
            DriveArg::Held => ArmDrive::Held,
            DriveArg::Free => ArmDrive::Free,
        };
        Ok(ArmInput {
            points,
            joints,
            speed_scale: self.speed_scale,
            mass_step: self.mass_step,
            region: self.region.clone(),
            area: self.area.clone(),
            contact: match self.contact {
                ContactArg::Transient => ContactKind::Transient,
                ContactArg::QuasiStatic => ContactKind::QuasiStatic,
            },
            law: self.law.law(),
            area_model: self.law.area_model()?,
            link: match self.link {
                LinkArg::Cj => FeLink::CompliantJoint,
                LinkArg::Cl => FeLink::CompliantLink,
            },
            k_delta: self.k_delta,
            link_mass: self.link_mass,
            simulation: simulation_settings(drive, self.tol, self.root_rtol),
            methods: self
                .method
                .iter()
                .map(|m| match m {
                    MethodArg::Standard => SafetyMethod::Standard,
                    MethodArg::Energy => SafetyMethod::Energy,
                    MethodArg::Simulation => SafetyMethod::Simulation,
                })
                .collect(),
        })
    }
}

/// Runs `flexrig arm`.
pub fn run(args: &ArmArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let model = flexrig::safety::load_body_model(args.body_model.as_deref())?;
    flexrig::safety::check_region(&args.region, model.as_ref())?;
    let (robot, trajectory, defaults, urdf_name, trajectory_name) =
        flexrig::arm::bundled::load(args.urdf.as_deref(), args.trajectory.as_deref())?;
    let input = args.input(defaults)?;
    let outputs = flexrig::arm::report::Outputs {
        figure: args.figure.clone(),
        log: args.log.clone(),
        report: args.report.clone(),
        force: args.force,
    };
    outputs.check()?;
    let report =
        flexrig::arm::judge_cancellable(&robot, &trajectory, &input, model.as_ref(), cancel)?;
    let sources = flexrig::arm::report::Sources {
        urdf: urdf_name,
        trajectory: trajectory_name,
    };
    let written = outputs.write(&robot, &report, &sources, model.as_ref())?;
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        let mut value = serde_json::to_value(&report).expect("the report serialises");
        value["urdf"] = serde_json::json!(sources.urdf);
        value["trajectory"] = serde_json::json!(sources.trajectory);
        if !written.is_empty() {
            value["files"] = serde_json::json!(
                written
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
            );
        }
        return print_json(out, &value);
    }
    print_text(out, &report, &sources)?;
    for p in &written {
        line(out, format!("wrote {}", p.display()))?;
    }
    Ok(())
}

fn n(v: f64) -> String {
    flexrig::shared::output::display_number(v)
}

fn speed(s: &Speed) -> String {
    match s {
        Speed::Finite(v) => format!("{v:.4}"),
        Speed::Unlimited(_) => "unlimited".into(),
    }
}

fn print_text(
    out: &mut dyn Write,
    r: &ArmReport,
    sources: &flexrig::arm::report::Sources,
) -> Result<(), Error> {
    for l in flexrig::arm::report::summary_lines(r, sources) {
        line(out, l)?;
    }
    line(
        out,
        format!(
            "{:<28} {:>9} {:>15} {:>10} {:>9} {:>9}  {}",
            "point", "max m/s", "m_u kg", "min v_max", "max ratio", "at t s", "method there"
        ),
    )?;
    for (p, point) in r.points.iter().enumerate() {
        let mut vmax = f64::INFINITY;
        let (mut lo, mut hi, mut top) = (f64::INFINITY, 0.0f64, 0.0f64);
        let mut worst: Option<(f64, f64, Option<SafetyMethod>)> = None;
        for s in &r.samples {
            let pr = &s.points[p];
            top = top.max(pr.speed_mps);
            if let Some(m) = pr.reflected_mass_kg {
                lo = lo.min(m);
                hi = hi.max(m);
            }
            if let Some(v) = pr.v_max_mps {
                vmax = vmax.min(v.value());
            }
            if worst.is_none_or(|w| pr.ratio > w.0) {
                worst = Some((pr.ratio, s.time_s, pr.method));
            }
        }
        let (ratio, t, method) = worst.unwrap_or((0.0, 0.0, None));
        line(
            out,
            format!(
                "{:<28} {:>9.4} {:>15} {:>10} {:>9.4} {:>9.3}  {}",
                point.label(),
                top,
                if lo.is_finite() {
                    format!("{lo:.3}–{hi:.3}")
                } else {
                    "at rest".into()
                },
                speed(&Speed::from_f64(vmax)),
                ratio,
                t,
                method.map_or("—", method_name)
            ),
        )?;
    }
    if let Some(g) = &r.governing {
        line(
            out,
            format!(
                "at the governing sample ({} at t = {} s, {} m/s, m = {} kg), each method:",
                g.label,
                n(g.time_s),
                n(g.speed_mps),
                n(g.effective_mass_kg)
            ),
        )?;
        for m in &g.safety.methods {
            let v = m.verdict.as_ref();
            line(
                out,
                format!(
                    "  {:<22} v_max {:>10} m/s{}",
                    method_name(m.method),
                    speed(&m.v_max_mps),
                    v.map_or(String::new(), |v| format!(
                        ", at {} m/s: {} (peak force {:.1} N)",
                        n(v.speed_mps),
                        if v.pass { "pass" } else { "FAIL" },
                        v.peak_force_n
                    ))
                ),
            )?;
        }
    }
    Ok(())
}
