//! `flexrig eta-map`: η_FE, the lumped model's error, the effective γ and the placed model's
//! error over m_e/m_r × k_δ/k_c (issue 14, "maps beyond the paper"), with the region where the
//! CL beats the CJ by more than 5 %.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use flexrig_impact::eta::{ClMethod, EffectiveGamma, EtaSettings};
use flexrig_impact::graded::GradedMesh;
use flexrig_impact::map::{LogRange, MapPoint, MapSpec, eta_map};
use serde_json::json;

use super::eta::{DampingArgs, JointArg, as_flag, contact_text, joint_from_args};
use crate::CliError;
use crate::output::{ensure_dir, line, print_json, write_atomic};
use crate::plots::{ColorScale, HeatMap, heatmaps_svg};

/// η_FE below this: the CL beats the CJ by more than 5 %.
const BEATS: f64 = 0.95;

/// Arguments of `flexrig eta-map`.
#[derive(Debug, Args)]
pub struct EtaMapArgs {
    /// Directory for eta_map.csv and one eta_map_mh<M>.svg per head mass (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Head masses m_h, kg, comma-separated (one map each).
    #[arg(long = "m-h", value_name = "KG,...", value_delimiter = ',', default_values_t = [4.0, 1000.0])]
    pub m_h: Vec<f64>,
    /// Hertz exponent n (1 to 3).
    #[arg(long, value_name = "N", default_value_t = 2.0)]
    pub n: f64,
    /// Payload over link mass m_e/m_r along x, FROM:TO (log-spaced; within [1e-6, 1e5]).
    #[arg(long, value_name = "FROM:TO", default_value = "1e-3:1e2")]
    pub mass_ratio: String,
    /// Link over contact stiffness k_δ/k_c along y, FROM:TO (log-spaced; within [1e-11, 1e4]).
    #[arg(long, value_name = "FROM:TO", default_value = "1e-7:1")]
    pub stiffness_ratio: String,
    /// Points along each axis (2 to 200).
    #[arg(long, value_name = "N", default_value_t = 30)]
    pub points: usize,
    /// The joint during the impact.
    #[arg(long, value_enum, default_value = "held")]
    pub joint: JointArg,
    /// Rotor inertia J_R of the free hub, kg·m² (with --joint free-hub).
    #[arg(long, value_name = "KG_M2")]
    pub rotor_inertia: Option<f64>,
    /// Tolerance of the force's linear hold per step (1e-14 to 0.1); 1e-5 keeps each peak
    /// within 5e-5 of the converged one (tested).
    #[arg(long, value_name = "TOL", default_value_t = 1e-5)]
    pub tol: f64,
    /// The contact's damping.
    #[command(flatten)]
    pub contact: DampingArgs,
    /// Print JSON instead of the summary.
    #[arg(long)]
    pub json: bool,
}

/// Parses FROM:TO for `flag`.
pub(crate) fn parse_range(flag: &str, text: &str, points: usize) -> Result<LogRange, CliError> {
    let bad = || CliError::InvalidArgument {
        arg: flag.into(),
        value: text.into(),
        allowed: "FROM:TO, two numbers > 0 with FROM < TO (e.g. 1e-3:1e2)".into(),
    };
    let (a, b) = text.split_once(':').ok_or_else(bad)?;
    let from: f64 = a.trim().parse().map_err(|_| bad())?;
    let to: f64 = b.trim().parse().map_err(|_| bad())?;
    Ok(LogRange { from, to, points })
}

/// The map's ranges and exponent, checked, with the error named by flag.
fn spec_for(args: &EtaMapArgs, m_h: f64) -> Result<MapSpec, CliError> {
    if !(2..=200).contains(&args.points) {
        return Err(CliError::InvalidArgument {
            arg: "--points".into(),
            value: args.points.to_string(),
            allowed: "must lie in [2, 200]".into(),
        });
    }
    let spec = MapSpec {
        m_h,
        n: args.n,
        mass_ratio: parse_range("--mass-ratio", &args.mass_ratio, args.points)?,
        stiffness_ratio: parse_range("--stiffness-ratio", &args.stiffness_ratio, args.points)?,
    };
    spec.validate().map_err(as_flag)?;
    Ok(spec)
}

/// One computed map.
struct Computed {
    spec: MapSpec,
    points: Vec<MapPoint>,
    seconds: f64,
}

fn csv(maps: &[Computed]) -> String {
    let mut s = String::from(
        "m_h_kg,n,mass_ratio,stiffness_ratio,m_e_kg,k_delta_n_per_m,f_cj_n,f_cl_n,eta_fe,eta_lumped_2_3,lumped_error,gamma_eff,gamma_eff_note,f_placed_n,placed_error,error\n",
    );
    for m in maps {
        for p in &m.points {
            let head = format!(
                "{},{},{},{}",
                m.spec.m_h, m.spec.n, p.mass_ratio, p.stiffness_ratio
            );
            match &p.row {
                Ok(r) => {
                    let (gamma, note) = match r.gamma_eff {
                        EffectiveGamma::Fits(g) => (format!("{g}"), ""),
                        EffectiveGamma::AboveGammaOne => (String::new(), "above gamma = 1"),
                        EffectiveGamma::BelowPayloadOnly => {
                            (String::new(), "below the payload alone")
                        }
                    };
                    let _ = writeln!(
                        s,
                        "{head},{},{},{},{},{},{},{},{gamma},{note},{},{},",
                        r.case.m_e,
                        r.case.k_delta,
                        r.f_cj_n,
                        r.f_cl_n,
                        r.eta_fe,
                        r.eta_lumped_2_3,
                        r.eta_lumped_2_3 / r.eta_fe - 1.0,
                        r.f_placed_n,
                        r.f_placed_n / r.f_cl_n - 1.0
                    );
                }
                Err(e) => {
                    let _ = writeln!(s, "{head},,,,,,,,,,,,\"{}\"", e.replace('"', "'"));
                }
            }
        }
    }
    s
}

/// The four panels of one head mass.
fn svg(m: &Computed, joint: &str) -> Result<String, String> {
    let xs = m.spec.mass_ratio.values();
    let ys = m.spec.stiffness_ratio.values();
    let value = |f: &dyn Fn(&flexrig_impact::eta::EtaRow) -> Option<f64>| -> Vec<Option<f64>> {
        m.points
            .iter()
            .map(|p| p.row.as_ref().ok().and_then(f))
            .collect()
    };
    let eta = value(&|r| Some(r.eta_fe));
    let lumped = value(&|r| Some(r.eta_lumped_2_3 / r.eta_fe - 1.0));
    let gamma = value(&|r| match r.gamma_eff {
        EffectiveGamma::Fits(g) => Some(g),
        _ => None,
    });
    let placed = value(&|r| Some(r.f_placed_n / r.f_cl_n - 1.0));
    let beats: Vec<bool> = eta.iter().map(|e| e.is_some_and(|e| e < BEATS)).collect();
    // both error maps on one scale, clamped at ±100 % so the region near 0 keeps its detail
    let (lumped_span, placed_span) = (1.0, 1.0);
    let maps = [
        HeatMap {
            title: "η_FE = f_max(CL)/f_max(CJ)",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &eta,
            scale: ColorScale::Sequential { lo: 0.0, hi: 1.0 },
            value_label: "η_FE",
            outline: Some((&beats, "CL beats CJ by > 5 % (η_FE < 0.95)")),
        },
        HeatMap {
            title: "lumped model's error η(2/3)/η_FE − 1",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &lumped,
            scale: ColorScale::Diverging {
                centre: 0.0,
                span: lumped_span,
            },
            value_label: "η(2/3)/η_FE − 1",
            outline: None,
        },
        HeatMap {
            title: "effective γ (blank: none in (0, 1] fits)",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &gamma,
            scale: ColorScale::Sequential { lo: 0.0, hi: 1.0 },
            value_label: "γ_eff",
            outline: None,
        },
        HeatMap {
            title: "placed model's error f_placed/f_CL − 1",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &placed,
            scale: ColorScale::Diverging {
                centre: 0.0,
                span: placed_span,
            },
            value_label: "f_placed/f_CL − 1",
            outline: None,
        },
    ];
    let title = format!(
        "Free head m_h = {} kg on the CL (FE) and CJ links, n = {}, {joint} (m_r = 10 kg, k_c = 1e8, v0 = 2 m/s)",
        m.spec.m_h, m.spec.n
    );
    heatmaps_svg(&title, &maps)
}

/// Summary numbers of one map: points, failures, CL-beats-CJ count and the largest errors.
fn summary(m: &Computed) -> serde_json::Value {
    let rows: Vec<_> = m
        .points
        .iter()
        .filter_map(|p| p.row.as_ref().ok())
        .collect();
    let beats = rows.iter().filter(|r| r.eta_fe < BEATS).count();
    let fits = rows
        .iter()
        .filter(|r| matches!(r.gamma_eff, EffectiveGamma::Fits(_)))
        .count();
    let worst = |f: &dyn Fn(&&flexrig_impact::eta::EtaRow) -> f64| {
        rows.iter().map(f).fold(0.0_f64, |a, b| a.max(b.abs()))
    };
    let within = |f: &dyn Fn(&&flexrig_impact::eta::EtaRow) -> f64, limit: f64| {
        rows.iter().filter(|r| f(r).abs() <= limit).count()
    };
    let lumped = |r: &&flexrig_impact::eta::EtaRow| r.eta_lumped_2_3 / r.eta_fe - 1.0;
    let placed = |r: &&flexrig_impact::eta::EtaRow| r.f_placed_n / r.f_cl_n - 1.0;
    json!({
        "m_h_kg": m.spec.m_h,
        "points": m.points.len(),
        "failed": m.points.len() - rows.len(),
        "cl_beats_cj_by_5_percent": beats,
        "gamma_eff_fits": fits,
        "lumped_error_max": worst(&lumped),
        "lumped_within_5_percent": within(&lumped, 0.05),
        "placed_error_max": worst(&placed),
        "placed_within_5_percent": within(&placed, 0.05),
        "seconds": m.seconds,
    })
}

/// Runs `flexrig eta-map`.
pub fn run(args: &EtaMapArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let joint = joint_from_args(args.joint, args.rotor_inertia)?;
    if args.m_h.is_empty() {
        return Err(CliError::InvalidArgument {
            arg: "--m-h".into(),
            value: String::new(),
            allowed: "one or more head masses in (0, 1e9] kg".into(),
        });
    }
    let specs = args
        .m_h
        .iter()
        .map(|&m_h| spec_for(args, m_h))
        .collect::<Result<Vec<_>, _>>()?;
    let settings = EtaSettings {
        joint,
        method: ClMethod::Modal {
            mesh: GradedMesh::DEFAULT,
            tol: args.tol,
        },
        damping: args.contact.spec()?,
        ..EtaSettings::DEFAULT
    };
    settings.method.validate().map_err(as_flag)?;
    let joint_text = match joint {
        flexrig_impact::Joint::Held => "held".to_string(),
        flexrig_impact::Joint::FreeHub { rotor_inertia } => {
            format!("free-hub (J_R = {rotor_inertia} kg·m²)")
        }
    };
    let joint_text = format!("{joint_text} joint, {}", contact_text(&settings.damping));
    let mut maps = Vec::new();
    for spec in specs {
        let start = Instant::now();
        let points = eta_map(&spec, &settings).map_err(as_flag)?;
        maps.push(Computed {
            spec,
            points,
            seconds: start.elapsed().as_secs_f64(),
        });
    }
    // render everything before writing anything: no partial output
    let mut files = vec![(args.out.join("eta_map.csv"), csv(&maps))];
    for m in &maps {
        let path = args.out.join(format!("eta_map_mh{}.svg", m.spec.m_h));
        let text = svg(m, &joint_text).map_err(|message| CliError::Plot {
            path: path.clone(),
            message,
        })?;
        files.push((path, text));
    }
    ensure_dir(&args.out)?;
    for (path, text) in &files {
        write_atomic(path, text.as_bytes())?;
    }
    let summaries: Vec<_> = maps.iter().map(summary).collect();
    let paths: Vec<_> = files.iter().map(|(p, _)| p.display().to_string()).collect();
    if args.json {
        return print_json(
            out,
            &json!({ "settings": settings, "maps": summaries, "files": paths }),
        );
    }
    line(
        out,
        format!(
            "η over m_e/m_r {} × k_δ/k_c {} ({} × {} points, n = {}, {joint_text}, tol {:e})",
            args.mass_ratio, args.stiffness_ratio, args.points, args.points, args.n, args.tol
        ),
    )?;
    for s in &summaries {
        line(
            out,
            format!(
                "m_h = {} kg: {} points in {:.1} s ({} failed); CL beats CJ by > 5 % at {}; \
                 lumped η(2/3) within 5 % of η_FE at {}, worst {:.3}; placed model within 5 % \
                 at {}, worst {:.3}; γ_eff in (0, 1] at {}",
                s["m_h_kg"],
                s["points"],
                s["seconds"].as_f64().unwrap_or(0.0),
                s["failed"],
                s["cl_beats_cj_by_5_percent"],
                s["lumped_within_5_percent"],
                s["lumped_error_max"].as_f64().unwrap_or(0.0),
                s["placed_within_5_percent"],
                s["placed_error_max"].as_f64().unwrap_or(0.0),
                s["gamma_eff_fits"],
            ),
        )?;
    }
    line(out, format!("Wrote {}", paths.join(", ")))
}
