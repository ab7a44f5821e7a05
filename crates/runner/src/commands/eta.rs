//! `flexrig eta`: the paper's Fig. 6 design cases at finite-element fidelity (issue 14): the
//! free-mass impact on the FE compliant link and the rigid compliant joint, η_FE beside the
//! lumped η(2/3), and the effective γ of the lumped model.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use flexrig_contact::DampingSpec;
use flexrig_impact::eta::{ClMethod, EffectiveGamma, EtaRow, EtaSettings, eta_table};
use flexrig_impact::graded::GradedMesh;
use flexrig_impact::{ClSolver, Joint};
use serde_json::json;

use crate::CliError;
use crate::output::{ensure_dir, line, positive_arg, print_json, write_atomic};

/// The joint during the impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum JointArg {
    /// Driven at constant speed: the robot at rest in the joint's frame, struck at v0.
    Held,
    /// A free hub with the rotor inertia --rotor-inertia; the robot moves at v0 into the head.
    FreeHub,
}

/// How the CL link is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The FE link's modes on a mesh graded towards the tip, integrated exactly between force
    /// samples (fast; --tol, --zone-elements).
    Modal,
    /// The FE link on a uniform mesh by generalized-α (the reference; --elements,
    /// --steps-per-contact, --modes).
    Alpha,
}

/// Damping added to the Hertz contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DampingArg {
    /// The paper's elastic contact f = k_c δⁿ.
    None,
    /// Hunt–Crossley, f = k_c δⁿ (1 + χ δ̇), χ = 3(1 − e)/(2 v0) (--restitution).
    HuntCrossley,
    /// Lankarani–Nikravesh, χ = 3(1 − e²)/(4 v0) (--restitution).
    LankaraniNikravesh,
    /// ADAMS IMPACT: damping ramped from 0 at first touch to --c-max at --depth.
    AdamsImpact,
}

/// The contact's damping flags (shared by `flexrig eta` and `flexrig eta-map`).
#[derive(Debug, Args)]
pub struct DampingArgs {
    /// Damping added to the Hertz contact (the lumped columns then come from the lumped model
    /// integrated with the same law).
    #[arg(long, value_enum, default_value = "none")]
    pub damping: DampingArg,
    /// Coefficient of restitution e in [0, 1] (with --damping hunt-crossley or
    /// lankarani-nikravesh).
    #[arg(long, value_name = "E")]
    pub restitution: Option<f64>,
    /// Largest damping coefficient, N·s/m in [0, 1e9] (with --damping adams-impact).
    #[arg(long, value_name = "N_S_PER_M")]
    pub c_max: Option<f64>,
    /// Indentation at which the damping reaches --c-max, m in [1e-9, 1] (with --damping
    /// adams-impact).
    #[arg(long, value_name = "M")]
    pub depth: Option<f64>,
}

impl DampingArgs {
    /// The damping the flags ask for; a missing, stray or out-of-range flag is named.
    pub fn spec(&self) -> Result<DampingSpec, CliError> {
        let bad = |arg: &str, value: String, allowed: &str| CliError::InvalidArgument {
            arg: arg.into(),
            value,
            allowed: allowed.into(),
        };
        let in_range = |arg: &str, value: Option<f64>, lo: f64, hi: f64, what: &str| {
            let v = value.ok_or_else(|| {
                bad(
                    "--damping",
                    self.damping
                        .to_possible_value()
                        .map_or(String::new(), |v| v.get_name().to_string()),
                    &format!("needs {arg} ({what})"),
                )
            })?;
            if v.is_finite() && (lo..=hi).contains(&v) {
                Ok(v)
            } else {
                Err(bad(
                    arg,
                    v.to_string(),
                    &format!("must lie in [{lo:e}, {hi:e}]"),
                ))
            }
        };
        let stray = |arg: &str, value: Option<f64>, with: &str| match value {
            Some(v) => Err(bad(
                arg,
                v.to_string(),
                &format!("only with --damping {with}"),
            )),
            None => Ok(()),
        };
        let restitution_models = "hunt-crossley or lankarani-nikravesh";
        match self.damping {
            DampingArg::None | DampingArg::AdamsImpact => {
                stray("--restitution", self.restitution, restitution_models)?
            }
            _ => {}
        }
        if self.damping != DampingArg::AdamsImpact {
            stray("--c-max", self.c_max, "adams-impact")?;
            stray("--depth", self.depth, "adams-impact")?;
        }
        let restitution = || in_range("--restitution", self.restitution, 0.0, 1.0, "e in [0, 1]");
        Ok(match self.damping {
            DampingArg::None => DampingSpec::NONE,
            DampingArg::HuntCrossley => DampingSpec::HuntCrossley {
                restitution: restitution()?,
            },
            DampingArg::LankaraniNikravesh => DampingSpec::LankaraniNikravesh {
                restitution: restitution()?,
            },
            DampingArg::AdamsImpact => DampingSpec::AdamsImpact {
                c_max_n_s_per_m: in_range("--c-max", self.c_max, 0.0, 1e9, "N·s/m")?,
                depth_m: in_range("--depth", self.depth, 1e-9, 1.0, "m")?,
            },
        })
    }
}

/// The contact as the table's title says it.
pub fn contact_text(damping: &DampingSpec) -> String {
    match *damping {
        DampingSpec::None {} => "elastic Hertz contact".into(),
        DampingSpec::HuntCrossley { restitution } => {
            format!("Hunt–Crossley contact, e = {restitution}")
        }
        DampingSpec::LankaraniNikravesh { restitution } => {
            format!("Lankarani–Nikravesh contact, e = {restitution}")
        }
        DampingSpec::AdamsImpact {
            c_max_n_s_per_m,
            depth_m,
        } => format!("ADAMS IMPACT contact, c_max = {c_max_n_s_per_m} N·s/m at {depth_m} m"),
    }
}

/// Arguments of `flexrig eta`.
#[derive(Debug, Args)]
pub struct EtaArgs {
    /// Directory for eta.csv and eta.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// The joint during the impact.
    #[arg(long, value_enum, default_value = "held")]
    pub joint: JointArg,
    /// Rotor inertia J_R of the free hub, kg·m² (with --joint free-hub).
    #[arg(long, value_name = "KG_M2")]
    pub rotor_inertia: Option<f64>,
    /// How the CL link is solved.
    #[arg(long, value_enum, default_value = "modal")]
    pub method: MethodArg,
    /// Modal method: tolerance of the force's linear hold per step (1e-14 to 0.1; default 1e-6).
    #[arg(long, value_name = "TOL")]
    pub tol: Option<f64>,
    /// Modal method: elements across the tip zone (EI/ρA)^¼ √t_c of the graded mesh (0.5 to
    /// 1000; default 8).
    #[arg(long, value_name = "N")]
    pub zone_elements: Option<f64>,
    /// Modal method: also follow every contact for this many first-mode periods of the CJ link
    /// (0.01 to 1000), run at --tol and --tol/10 to find how long the contacts are converged.
    #[arg(long, value_name = "P")]
    pub window_periods: Option<f64>,
    /// Alpha method: Hermite-cubic elements of the CL beam (2 to 4096; default 256).
    #[arg(long, value_name = "N")]
    pub elements: Option<usize>,
    /// Alpha method: time steps over the shortest possible contact (head against the payload;
    /// 20 to 1e6; default 800).
    #[arg(long, value_name = "N")]
    pub steps_per_contact: Option<usize>,
    /// Alpha method: the CL beam reduced to its lowest N modes plus the tip's static correction
    /// shape (at most 1000 elements); without it, the full FE model.
    #[arg(long, value_name = "N")]
    pub modes: Option<usize>,
    /// Link length L, m (the transverse impact does not depend on it).
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    pub length: f64,
    /// The contact's damping.
    #[command(flatten)]
    pub contact: DampingArgs,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// The joint from --joint and --rotor-inertia.
pub fn joint_from_args(joint: JointArg, rotor_inertia: Option<f64>) -> Result<Joint, CliError> {
    Ok(match (joint, rotor_inertia) {
        (JointArg::Held, None) => Joint::Held,
        (JointArg::Held, Some(j)) => {
            return Err(CliError::InvalidArgument {
                arg: "--rotor-inertia".into(),
                value: j.to_string(),
                allowed: "only with --joint free-hub".into(),
            });
        }
        (JointArg::FreeHub, None) => {
            return Err(CliError::InvalidArgument {
                arg: "--joint".into(),
                value: "free-hub".into(),
                allowed: "needs --rotor-inertia (kg·m², > 0)".into(),
            });
        }
        (JointArg::FreeHub, Some(j)) => Joint::FreeHub {
            rotor_inertia: positive_arg("--rotor-inertia", j)?,
        },
    })
}

/// An impact parameter error as the flag the user typed (`zone_elements` → `--zone-elements`).
pub fn as_flag(e: flexrig_impact::ImpactError) -> CliError {
    match e {
        flexrig_impact::ImpactError::InvalidParameter {
            field,
            value,
            allowed,
        } => CliError::InvalidArgument {
            arg: format!("--{}", field.replace('_', "-")),
            value,
            allowed,
        },
        other => CliError::Impact(other),
    }
}

fn settings(args: &EtaArgs) -> Result<EtaSettings, CliError> {
    let joint = joint_from_args(args.joint, args.rotor_inertia)?;
    let only = |flag: &str, given: bool, method: &str| {
        if given {
            Err(CliError::InvalidArgument {
                arg: flag.into(),
                value: "given".into(),
                allowed: format!("only with --method {method}"),
            })
        } else {
            Ok(())
        }
    };
    let method = match args.method {
        MethodArg::Alpha => {
            only("--tol", args.tol.is_some(), "modal")?;
            only("--zone-elements", args.zone_elements.is_some(), "modal")?;
            ClMethod::Alpha(ClSolver {
                elements: args.elements.unwrap_or(ClSolver::DEFAULT.elements),
                steps_per_contact: args
                    .steps_per_contact
                    .unwrap_or(ClSolver::DEFAULT.steps_per_contact),
                modes: args.modes,
            })
        }
        MethodArg::Modal => {
            only("--elements", args.elements.is_some(), "alpha")?;
            only(
                "--steps-per-contact",
                args.steps_per_contact.is_some(),
                "alpha",
            )?;
            only("--modes", args.modes.is_some(), "alpha")?;
            ClMethod::Modal {
                mesh: GradedMesh {
                    zone_elements: args
                        .zone_elements
                        .unwrap_or(GradedMesh::DEFAULT.zone_elements),
                    ..GradedMesh::DEFAULT
                },
                tol: args.tol.unwrap_or(1e-6),
            }
        }
    };
    if !(args.length.is_finite() && (1e-3..=1e3).contains(&args.length)) {
        return Err(CliError::InvalidArgument {
            arg: "--length".into(),
            value: args.length.to_string(),
            allowed: "must lie in [1e-3, 1e3] m".into(),
        });
    }
    let settings = EtaSettings {
        length: args.length,
        joint,
        method,
        window_periods: args.window_periods,
        damping: args.contact.spec()?,
        ..EtaSettings::DEFAULT
    };
    settings.validate().map_err(as_flag)?;
    Ok(settings)
}

fn gamma_text(g: &EffectiveGamma) -> String {
    match g {
        EffectiveGamma::Fits(g) => format!("{g:.6}"),
        EffectiveGamma::AboveGammaOne => "> 1".into(),
        EffectiveGamma::BelowPayloadOnly => "< 0".into(),
    }
}

fn csv(rows: &[EtaRow]) -> String {
    let mut s = String::from(
        "m_h_kg,k_delta_n_per_m,m_e_kg,n,f_cj_n,f_cl_n,eta_fe,eta_lumped_2_3,f_cj_lumped_n,gamma_eff,gamma_eff_note,f_placed_n,placed_error,window_s,cj_contacts,cl_contacts,cj_horizon_s,cl_horizon_s,cj_overall_n,cl_overall_n,eta_overall\n",
    );
    for r in rows {
        let (gamma, note) = match r.gamma_eff {
            EffectiveGamma::Fits(g) => (format!("{g}"), ""),
            EffectiveGamma::AboveGammaOne => {
                (String::new(), "FE CL peak above the lumped CJ (gamma = 1)")
            }
            EffectiveGamma::BelowPayloadOnly => (
                String::new(),
                "FE CL peak below the lumped payload-only peak",
            ),
        };
        let window = match &r.window {
            Some(w) => {
                let (cj, cl) = (&w.cj, &w.cl);
                format!(
                    "{},{},{},{},{},{},{},{}",
                    w.window_s,
                    cj.converged_contacts,
                    cl.converged_contacts,
                    cj.horizon_s,
                    cl.horizon_s,
                    cj.overall_converged.peak_force_n,
                    cl.overall_converged.peak_force_n,
                    cl.overall_converged.peak_force_n / cj.overall_converged.peak_force_n
                )
            }
            None => ",,,,,,,".to_string(),
        };
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.case.m_h,
            r.case.k_delta,
            r.case.m_e,
            r.n,
            r.f_cj_n,
            r.f_cl_n,
            r.eta_fe,
            r.eta_lumped_2_3,
            r.f_cj_lumped_n,
            gamma,
            note,
            r.f_placed_n,
            r.f_placed_n / r.f_cl_n - 1.0,
            window
        );
    }
    s
}

fn method_text(method: &ClMethod) -> String {
    match method {
        ClMethod::Modal { mesh, tol } => format!(
            "CL: FE modes on a graded mesh, {} elements per tip zone, exact modal integration, tol {tol:e}",
            mesh.zone_elements
        ),
        ClMethod::Alpha(s) => format!(
            "CL: {} elements, generalized-α, {} steps per contact",
            s.elements, s.steps_per_contact
        ),
    }
}

/// The paper's Fig. 6 curves with each row's η_FE placed where its lumped curve takes that value.
fn fig6_with_fe_points(rows: &[EtaRow]) -> Result<String, String> {
    let curves = flexrig_lumped::fig6::fig6(41).map_err(|e| e.to_string())?;
    let points = rows
        .iter()
        .map(|r| {
            Ok(crate::plots::Fig6Point {
                case: r.case,
                n: r.n,
                eta_fe: r.eta_fe,
                gamma: flexrig_impact::eta::gamma_on_curve(&r.case, r.n, r.eta_fe)
                    .map_err(|e| e.to_string())?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    crate::plots::fig6_with_points_svg(&curves, &points)
}

/// Runs `flexrig eta`.
pub fn run(args: &EtaArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let settings = settings(args)?;
    let rows = eta_table(&settings)?;
    ensure_dir(&args.out)?;
    let csv_path = args.out.join("eta.csv");
    let svg_path = args.out.join("eta.svg");
    let fig6_path = args.out.join("eta_fig6.svg");
    let fig6_svg = fig6_with_fe_points(&rows).map_err(|message| CliError::Plot {
        path: fig6_path.clone(),
        message,
    })?;
    let joint = match settings.joint {
        Joint::Held => "held".to_string(),
        Joint::FreeHub { rotor_inertia } => format!("free-hub (J_R = {rotor_inertia} kg·m²)"),
    };
    let svg = crate::plots::eta_svg(&rows, &joint).map_err(|message| CliError::Plot {
        path: svg_path.clone(),
        message,
    })?;
    write_atomic(&csv_path, csv(&rows).as_bytes())?;
    write_atomic(&svg_path, svg.as_bytes())?;
    write_atomic(&fig6_path, fig6_svg.as_bytes())?;
    if args.json {
        return print_json(
            out,
            &json!({ "settings": settings, "rows": rows, "csv": csv_path, "svg": svg_path, "fig6_svg": fig6_path }),
        );
    }
    line(
        out,
        format!(
            "Fig. 6 cases at FE fidelity (free head, {joint} joint; m_r = 10 kg, k_c = 1e8, v0 = 2 m/s, {}; {})",
            contact_text(&settings.damping),
            method_text(&settings.method)
        ),
    )?;
    line(
        out,
        format!(
            "{:>7} {:>8} {:>6} {:>3} {:>12} {:>12} {:>9} {:>11} {:>12} {:>9} {:>12}",
            "m_h[kg]",
            "k_δ[N/m]",
            "m_e[kg]",
            "n",
            "f_CJ[N]",
            "f_CL[N]",
            "η_FE",
            "η_lump(2/3)",
            "f_CJ,lump[N]",
            "γ_eff",
            "f_placed[N]"
        ),
    )?;
    for r in &rows {
        line(
            out,
            format!(
                "{:>7} {:>8.0e} {:>6} {:>3} {:>12.1} {:>12.1} {:>9.5} {:>11.5} {:>12.1} {:>9} {:>12.1}",
                r.case.m_h,
                r.case.k_delta,
                r.case.m_e,
                r.n,
                r.f_cj_n,
                r.f_cl_n,
                r.eta_fe,
                r.eta_lumped_2_3,
                r.f_cj_lumped_n,
                gamma_text(&r.gamma_eff),
                r.f_placed_n
            ),
        )?;
    }
    if rows.iter().any(|r| r.window.is_some()) {
        line(
            out,
            "Every contact in the window (runs at --tol and --tol/10; the horizon is where they part):",
        )?;
        line(
            out,
            format!(
                "{:>7} {:>8} {:>6} {:>3} {:>10} {:>14} {:>14} {:>12} {:>12} {:>9}",
                "m_h[kg]",
                "k_δ[N/m]",
                "m_e[kg]",
                "n",
                "window[s]",
                "CJ contacts/s",
                "CL contacts/s",
                "f_CJ,all[N]",
                "f_CL,all[N]",
                "η_all"
            ),
        )?;
        for r in &rows {
            let Some(w) = &r.window else { continue };
            let contacts = |x: &flexrig_impact::horizon::WindowReport| {
                format!(
                    "{}/{}@{:.3}",
                    x.converged_contacts,
                    x.outcome.contacts.len(),
                    x.horizon_s
                )
            };
            line(
                out,
                format!(
                    "{:>7} {:>8.0e} {:>6} {:>3} {:>10.4} {:>14} {:>14} {:>12.1} {:>12.1} {:>9.5}",
                    r.case.m_h,
                    r.case.k_delta,
                    r.case.m_e,
                    r.n,
                    w.window_s,
                    contacts(&w.cj),
                    contacts(&w.cl),
                    w.cj.overall_converged.peak_force_n,
                    w.cl.overall_converged.peak_force_n,
                    w.cl.overall_converged.peak_force_n / w.cj.overall_converged.peak_force_n
                ),
            )?;
        }
    }
    line(
        out,
        format!(
            "Wrote {}, {} and {} (the FE points on the Fig. 6 curves)",
            csv_path.display(),
            svg_path.display(),
            fig6_path.display()
        ),
    )
}
