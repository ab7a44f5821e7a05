//! `flexrig safety`: the permissible speed of a design near a body region by the standard's
//! formula, the paper's energy method and the simulated finite-element impact, see
//! [`flexrig::safety`].

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use flexrig::safety::{
    ContactAreaModel, ContactKind, FeLink, MethodResult, RobotEffectiveMass, SafetyInput,
    SafetyMethod, SafetyReport, SimulationSettings, Speed, safety_cancellable,
};
use flexrig::{CancelToken, Error};

use super::safety_args::{ContactArg, ContactLawArgs, map_joint, missing};
use crate::print::{line, print_json};

/// Permissible-speed method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The standard's formula (ISO/TS 15066 Annex A, Eq. A.1–A.6).
    Standard,
    /// The paper's lumped energy balance (Eq. 13 with the Hertz law and k_δ).
    Energy,
    /// The finite-element impact (the safe-speed map's) and a root search on the speed.
    Simulation,
}

/// The finite-element link of the simulation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LinkArg {
    /// The compliant joint: a rigid link on a torsion spring.
    Cj,
    /// The compliant link: the Euler–Bernoulli beam.
    Cl,
}

/// Arguments of `flexrig safety`.
#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct SafetyArgs {
    /// Body region key of the body model, e.g. chest, hands_and_fingers.
    #[arg(long, value_name = "REGION")]
    pub region: String,
    /// Specific area of the region for the pressure limit (default: its most sensitive area).
    #[arg(long, value_name = "NAME")]
    pub area: Option<String>,
    /// Contact kind.
    #[arg(long, value_enum, default_value = "transient")]
    pub contact: ContactArg,
    /// Effective robot mass m_eff [kg] for the energy and simulation methods.
    #[arg(long = "m-eff", value_name = "KG", conflicts_with_all = ["gamma", "m_r", "m_e"])]
    pub m_eff: Option<f64>,
    /// Link mass m_r [kg], for m_eff = m_e + γ m_r/3 (with --m-e, and --gamma or --link).
    #[arg(long = "m-r", value_name = "KG", requires = "m_e")]
    pub m_r: Option<f64>,
    /// End mass m_e [kg] (with --m-r).
    #[arg(long = "m-e", value_name = "KG", requires = "m_r")]
    pub m_e: Option<f64>,
    /// PRB characteristic radius γ ∈ (0, 1] (with --m-r, --m-e; default with --link: 1 for cj,
    /// 2/3 for cl).
    #[arg(long, value_name = "G", requires_all = ["m_r", "m_e"])]
    pub gamma: Option<f64>,
    /// The simulation method's finite-element link: cj (rigid link on a torsion spring) or cl
    /// (Euler–Bernoulli beam); default: cj for γ = 1, cl for γ = 2/3.
    #[arg(long, value_enum, requires_all = ["m_r", "m_e"])]
    pub link: Option<LinkArg>,
    /// The joint during the simulated impact: held (driven at constant speed, the body region
    /// arriving at v) or a free hub (with --rotor-inertia; needed for quasi-static contact).
    #[arg(long, value_enum, default_value = "held")]
    pub joint: super::impact_args::JointArg,
    /// Rotor inertia J_R of the free hub [kg·m²] (with --joint free-hub).
    #[arg(long = "rotor-inertia", value_name = "KG_M2")]
    pub rotor_inertia: Option<f64>,
    /// Link length L [m] of the simulated link: required with --joint free-hub (the rotor's
    /// inertia acts at the contact as J_R/L²); with a held joint the impact depends on m_r and
    /// k_δ only and the length is not needed.
    #[arg(long, value_name = "M")]
    pub length: Option<f64>,
    /// Tolerance of the simulated CL's modal integrator (1e-10 to 1e-3).
    #[arg(long, value_name = "TOL", default_value = "1e-6")]
    pub tol: f64,
    /// Relative tolerance of the simulation's root search on the speed (1e-13 to 1e-4).
    #[arg(long = "root-rtol", value_name = "RTOL", default_value = "1e-6")]
    pub root_rtol: f64,
    /// Link lateral stiffness k_δ [N/m] (default: a rigid link).
    #[arg(long = "k-delta", value_name = "N_PER_M")]
    pub k_delta: Option<f64>,
    /// The contact law and the contact-area model.
    #[command(flatten)]
    pub law: ContactLawArgs,
    /// The robot's total moving mass M [kg] for the standard's m_R = M/2 + m_L (default: m_R = m_eff).
    #[arg(long = "moving-mass", value_name = "KG")]
    pub moving_mass: Option<f64>,
    /// Payload m_L [kg] for the standard's m_R.
    #[arg(long, value_name = "KG", default_value_t = 0.0)]
    pub payload: f64,
    /// Relative speed [m/s] to judge.
    #[arg(long, value_name = "M_PER_S")]
    pub speed: Option<f64>,
    /// A body-model TOML file in the format of assets/safety/iso_ts_15066_2016.toml.
    #[arg(long = "body-model", value_name = "FILE")]
    pub body_model: Option<PathBuf>,
    /// A scene as the design: a driven scene (driven_cj_free_head, driven_cj_wall,
    /// driven_cl_free_head, driven_cl_wall, or a scene file with a [drive] section: the link,
    /// the skin's law and the contact, a wall quasi-static and a free head transient; the
    /// simulation method searches its commanded speed) or a test-bed scene (cj_aluminium,
    /// cl_iron, …: the robot link and the operator block's skin, transient contact; the
    /// simulation method searches the operator's speed at contact through its release angle,
    /// up to 170°).
    #[arg(
        long,
        value_name = "NAME|FILE",
        conflicts_with_all = ["m_eff", "m_r", "m_e", "gamma", "link", "k_delta", "k_c", "n", "material", "contact"]
    )]
    pub scene: Option<String>,
    /// Methods, comma-separated (default: all three whenever the design is known — a scene, or
    /// --m-r --m-e with --link or --gamma 1 or 2/3 — else standard,energy). The overall verdict
    /// is the most restrictive of the methods run.
    #[arg(long, value_enum, value_delimiter = ',')]
    pub method: Vec<MethodArg>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// A measured impact to judge instead of a design: a CSV file with a header naming each
    /// column with its unit — time and force, optionally the struck body's acceleration and
    /// the indentation (e.g. `t [s], F [N], a [m/s^2], delta [mm]`, or flexrig's `t_s,
    /// force_n, head_acceleration_mps2, indentation_m`; docs/safety.md) — and one sample per
    /// line: its peak force, pressure (with an area model), transferred energy, HIC15/HIC36
    /// and the verdict against the region's limits.
    #[arg(
        long,
        value_name = "FILE.csv",
        conflicts_with_all = ["m_eff", "m_r", "m_e", "gamma", "link", "k_delta", "k_c", "n", "material", "scene", "method", "speed", "moving_mass", "report", "rotor_inertia"]
    )]
    pub trace: Option<PathBuf>,
    /// Also write a report for a risk assessment: FILE.md (Markdown) or FILE.html (HTML), with
    /// the inputs, every limit and its source, each method's calculation trace, a figure
    /// (FILE_peak_force.svg beside it), the verdict and the ISO/PAS 5672 caveat.
    #[arg(long, value_name = "FILE")]
    pub report: Option<PathBuf>,
    /// Overwrite an existing report and its figure.
    #[arg(long, requires = "report")]
    pub force: bool,
}

impl SafetyArgs {
    /// The library's input.
    pub fn input(&self) -> Result<SafetyInput, Error> {
        let link = self.link.map(|l| match l {
            LinkArg::Cj => FeLink::CompliantJoint,
            LinkArg::Cl => FeLink::CompliantLink,
        });
        let implied = link.map(|l| match l {
            FeLink::CompliantJoint => flexrig::safety::map::GAMMA_CJ,
            FeLink::CompliantLink => flexrig::safety::map::GAMMA_CL,
        });
        let m_eff = match (self.m_eff, self.gamma.or(implied), self.m_r, self.m_e) {
            (Some(m), ..) => Some(RobotEffectiveMass::Given(m)),
            (None, Some(gamma), Some(m_r), Some(m_e)) => {
                Some(RobotEffectiveMass::Prb { gamma, m_r, m_e })
            }
            (None, None, Some(_), _) => {
                return Err(missing("--gamma", "--m-r and --m-e need --gamma or --link"));
            }
            _ => None,
        };
        let simulation = SimulationSettings {
            joint: map_joint(self.joint, self.rotor_inertia)?,
            length: self.length,
            tol: self.tol,
            root_rtol: self.root_rtol,
            ..SimulationSettings::DEFAULT
        };
        let (law, area_model) = (self.law.law(), self.law.area_model()?);
        Ok(SafetyInput {
            region: self.region.clone(),
            area: self.area.clone(),
            contact: match self.contact {
                ContactArg::Transient => ContactKind::Transient,
                ContactArg::QuasiStatic => ContactKind::QuasiStatic,
            },
            m_eff,
            k_delta: self.k_delta,
            law,
            area_model,
            moving_mass: self.moving_mass,
            payload: self.payload,
            speed: self.speed,
            methods: self
                .methods()
                .iter()
                .map(|m| match m {
                    MethodArg::Standard => SafetyMethod::Standard,
                    MethodArg::Energy => SafetyMethod::Energy,
                    MethodArg::Simulation => SafetyMethod::Simulation,
                })
                .collect(),
            link,
            simulation: Some(simulation),
            scene: self.scene.clone(),
        })
    }

    /// `--method` as given (empty: the library's default, [`flexrig::safety::default_methods`]).
    fn methods(&self) -> Vec<MethodArg> {
        self.method.clone()
    }
}

pub use flexrig::safety::load_body_model;

/// Runs `flexrig safety`.
pub fn run(args: &SafetyArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let model = load_body_model(args.body_model.as_deref())?;
    flexrig::safety::check_region(&args.region, model.as_ref())?;
    if let Some(trace) = &args.trace {
        let input = flexrig::safety::measured::TraceInput {
            trace: trace.clone(),
            region: args.region.clone(),
            area: args.area.clone(),
            contact: match args.contact {
                ContactArg::Transient => ContactKind::Transient,
                ContactArg::QuasiStatic => ContactKind::QuasiStatic,
            },
            area_model: args.law.area_model()?,
        };
        return super::safety_trace::run(&input, model.as_ref(), args.json, out);
    }
    let input = args.input()?;
    let (report, written) = match &args.report {
        Some(path) => {
            flexrig::safety::report::write_report(&input, model.as_ref(), path, args.force, cancel)?
        }
        None => (
            safety_cancellable(&input, model.as_ref(), cancel)?,
            Vec::new(),
        ),
    };
    for w in &report.warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        let mut value = serde_json::to_value(&report).expect("the report serialises");
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
    print_text(out, &report)?;
    for p in &written {
        line(out, format!("wrote {}", p.display()))?;
    }
    Ok(())
}

fn speed(s: &Speed) -> String {
    match s {
        Speed::Finite(v) => fixed(*v, 6),
        Speed::Unlimited(_) => "unlimited".into(),
    }
}

/// `v` with `digits` decimals for ordinary magnitudes, in the one formatter's exponent form
/// outside them (never hundreds of digits).
fn fixed(v: f64, digits: usize) -> String {
    if v == 0.0 || (1e-3..1e9).contains(&v.abs()) {
        format!("{v:.digits$}")
    } else {
        n(v)
    }
}

/// A number as the messages write it (the one formatter: 1e300, not 301 digits).
fn n(v: f64) -> String {
    flexrig::shared::output::display_number(v)
}

fn print_text(out: &mut dyn Write, r: &SafetyReport) -> Result<(), Error> {
    print_overall(out, &r.overall)?;
    line(
        out,
        format!("body region        {} ({})", r.region_name, r.region),
    )?;
    line(out, format!("area               {}", r.area))?;
    let contact = match r.contact {
        ContactKind::Transient => "transient (the body free to recoil)",
        ContactKind::QuasiStatic => "quasi-static (clamped against a support)",
    };
    line(out, format!("contact            {contact}"))?;
    line(
        out,
        format!(
            "limits             force {} N, pressure {} N/cm²",
            n(r.force_limit_n),
            n(r.pressure_limit_pa / 1e4)
        ),
    )?;
    let area = match &r.area_model {
        Some(ContactAreaModel::HertzSphere { radius_m }) => {
            format!("Hertz sphere, A = π R δ, R = {} mm", n(radius_m * 1e3))
        }
        Some(ContactAreaModel::ThinLayer { radius_m }) => format!(
            "thin layer on a rigid backing, A = π(2Rδ − δ²), R = {} mm",
            n(radius_m * 1e3)
        ),
        Some(ContactAreaModel::Fixed { area_m2 }) => {
            format!("fixed area, A = {} cm²", n(area_m2 * 1e4))
        }
        None => "none (pressure not assessed)".into(),
    };
    line(out, format!("contact-area model {area}"))?;
    line(
        out,
        format!(
            "{:<11} {:>12} {:>12} {:>12} {:>12} {:>9}",
            "method", "robot kg", "v_max m/s", "by force", "by pressure", "governs"
        ),
    )?;
    for m in &r.methods {
        print_method(out, m)?;
    }
    if let Some(sc) = &r.scene {
        if let Some(angle) = sc.release_angle_at_root_deg {
            return print_test_bed(out, sc, angle);
        }
        line(
            out,
            format!(
                "scene              {} ({}, {} link, the {} {}): commanded tip speed {} m/s \
                 as written",
                sc.name,
                sc.scene,
                format!("{:?}", sc.design).to_uppercase(),
                r.region_name.to_lowercase(),
                match sc.support {
                    "wall" => "against a wall",
                    "neck" => "on a neck",
                    _ => "free",
                },
                n(sc.scene_tip_speed_mps)
            ),
        )?;
        line(
            out,
            format!(
                "  at the force limit: commanded {:.6} m/s, arriving at {:.6} m/s, peak {:.3} N \
                 ({} driven runs, run tolerance {}, root tolerance {})",
                sc.by_force_mps,
                sc.approach_speed_at_root_mps,
                sc.peak_force_at_root_n,
                sc.runs,
                n(sc.run_tol),
                n(sc.root_rtol)
            ),
        )?;
        if let Some(c) = &sc.contacts_at_root {
            line(
                out,
                format!(
                    "  contacts           {}",
                    flexrig::safety::scene::contacts_words(c)
                ),
            )?;
        }
        for note in &sc.notes {
            line(out, format!("  note: {note}"))?;
        }
    }
    Ok(())
}

/// The overall verdict first: the governing method, its speed, and the verdict at the speed.
fn print_overall(
    out: &mut dyn Write,
    o: &flexrig::safety::overall::OverallVerdict,
) -> Result<(), Error> {
    use flexrig::safety::overall::method_name;
    line(
        out,
        format!(
            "permissible speed  {}, governed by {} ({} limit)",
            match o.v_max_mps {
                Speed::Finite(v) => format!("{v:.6} m/s"),
                Speed::Unlimited(_) => "unlimited".into(),
            },
            method_name(o.method),
            format!("{:?}", o.governing).to_lowercase()
        ),
    )?;
    line(out, format!("                   {}", o.reason))?;
    if let Some(pass) = o.pass {
        let verdict = if pass {
            "pass by every method".to_string()
        } else {
            format!(
                "FAIL (failed by {})",
                o.failed_by
                    .iter()
                    .map(|m| method_name(*m))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        let head = format!(
            "verdict{}",
            o.speed_mps
                .map_or(String::new(), |v| format!(" at {} m/s", n(v)))
        );
        line(out, format!("{head:<18} {verdict}"))?;
    }
    Ok(())
}

/// The test bed's search: the operator's speed at contact and its release angle.
fn print_test_bed(
    out: &mut dyn Write,
    sc: &flexrig::safety::simulation::SceneSimulation,
    angle: f64,
) -> Result<(), Error> {
    line(
        out,
        format!(
            "scene              {} ({}, {} link, operator pendulum): operator speed at contact \
             {} m/s as written",
            sc.name,
            sc.scene,
            format!("{:?}", sc.design).to_uppercase(),
            n(sc.scene_tip_speed_mps)
        ),
    )?;
    line(
        out,
        format!(
            "  {}: operator speed {:.6} m/s (released from {:.4}°), run's impact speed {:.6} \
             m/s, peak {:.3} N ({} runs of {}, root tolerance {})",
            if sc.limit_reached {
                "at the force limit"
            } else {
                "limit NOT reached up to"
            },
            sc.by_force_mps,
            angle,
            sc.approach_speed_at_root_mps,
            sc.peak_force_at_root_n,
            sc.runs,
            sc.link_model,
            n(sc.root_rtol)
        ),
    )?;
    if let Some(c) = &sc.contacts_at_root {
        line(
            out,
            format!(
                "  contacts           {}",
                flexrig::safety::scene::contacts_words(c)
            ),
        )?;
    }
    for note in &sc.notes {
        line(out, format!("  note: {note}"))?;
    }
    Ok(())
}

fn print_method(out: &mut dyn Write, m: &MethodResult) -> Result<(), Error> {
    let by_p = m.by_pressure_mps.as_ref().map_or("—".into(), speed);
    // without a pressure assessment no limit "governs": only the force was judged
    let governs = if m.pressure_assessed {
        format!("{:?}", m.governing).to_lowercase()
    } else {
        "force only".into()
    };
    line(
        out,
        format!(
            "{:<11} {:>12} {:>12} {:>12} {:>12} {:>9}",
            format!("{:?}", m.method).to_lowercase(),
            fixed(m.robot_mass_kg, 6),
            speed(&m.v_max_mps),
            speed(&m.by_force_mps),
            by_p,
            governs
        ),
    )?;
    if !m.pressure_assessed {
        line(
            out,
            format!("  pressure not assessed: {}", not_assessed_reason(m)),
        )?;
    }
    if let Some(v) = &m.verdict {
        line(
            out,
            format!(
                "  at {} m/s: {} (peak force {} N, force margin {})",
                n(v.speed_mps),
                if v.pass { "pass" } else { "FAIL" },
                fixed(v.peak_force_n, 3),
                fixed(v.force_margin, 4)
            ),
        )?;
        if let Some(c) = &v.governing_contact {
            line(out, format!("    {}", contact_words(c)))?;
        }
    }
    if let Some(c) = &m.governing_contact {
        line(out, format!("  at v_max: {}", contact_words(c)))?;
    }
    Ok(())
}

/// Why a method did not judge the pressure.
fn not_assessed_reason(m: &MethodResult) -> &'static str {
    match m.method {
        flexrig::safety::SafetyMethod::Standard => {
            "the standard's formula judges a pressure over a fixed area only (Eq. A.6; \
             --contact-area, e.g. 1cm2)"
        }
        _ => {
            "no contact geometry (give --radius of the dome, --contact-area, or --material \
             with its dome)"
        }
    }
}

/// Which contact holds the peak of a simulated impact, in words.
fn contact_words(c: &flexrig::safety::simulation::SimulatedPeak) -> String {
    format!(
        "peak {:.3} N in contact {} of {} at {:.4} ms (the bodies part for good at {:.4} ms)",
        c.peak_force_n,
        c.contact,
        c.contacts,
        c.time_of_peak_s * 1e3,
        c.parted_at_s * 1e3
    )
}
