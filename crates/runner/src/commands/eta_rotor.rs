//! `flexrig eta-rotor`: the rotor-inertia sweep of issue 14 — η_FE of the Fig. 6 cases as the
//! free hub's rotor inertia J_R grows from a freely pivoting link to the held joint.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig_impact::eta::{ClMethod, EtaSettings};
use flexrig_impact::graded::GradedMesh;
use flexrig_impact::rotor::{RotorPoint, rotor_sweep};
use serde_json::json;

use super::eta::{DampingArgs, as_flag, contact_text};
use super::eta_map::parse_range;
use crate::CliError;
use crate::output::{ensure_dir, line, print_json, write_atomic};
use crate::plots::{Curve, CurvePanel, log_x_curves_svg};

/// Arguments of `flexrig eta-rotor`.
#[derive(Debug, Args)]
pub struct EtaRotorArgs {
    /// Directory for eta_rotor.csv and eta_rotor.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Rotor over link inertia J_R/(m_r L²/3), FROM:TO (log-spaced; within [1e-9, 1e9]).
    #[arg(long, value_name = "FROM:TO", default_value = "1e-4:1e6")]
    pub ratio: String,
    /// Points along the ratio (2 to 200); the held joint is added as the limit.
    #[arg(long, value_name = "N", default_value_t = 21)]
    pub points: usize,
    /// Hertz exponents n, comma-separated (1 to 3 each).
    #[arg(long, value_name = "N,...", value_delimiter = ',', default_values_t = [1.0, 2.0])]
    pub n: Vec<f64>,
    /// Tolerance of the force's linear hold per step (1e-14 to 0.1).
    #[arg(long, value_name = "TOL", default_value_t = 1e-6)]
    pub tol: f64,
    /// The contact's damping.
    #[command(flatten)]
    pub contact: DampingArgs,
    /// Print JSON instead of the summary.
    #[arg(long)]
    pub json: bool,
}

fn csv(points: &[RotorPoint]) -> String {
    let mut s =
        String::from("m_h_kg,k_delta_n_per_m,m_e_kg,n,inertia_ratio,f_cj_n,f_cl_n,eta_fe\n");
    for p in points {
        let ratio = p
            .inertia_ratio
            .map_or("held".to_string(), |r| r.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}",
            p.case.m_h, p.case.k_delta, p.case.m_e, p.n, ratio, p.f_cj_n, p.f_cl_n, p.eta_fe
        );
    }
    s
}

/// One panel per head mass, one curve per (k_δ, m_e, n), the held η as its limit.
fn panels(points: &[RotorPoint]) -> Vec<CurvePanel> {
    let mut panels: Vec<CurvePanel> = Vec::new();
    for p in points {
        let title = format!("m_h = {} kg", p.case.m_h);
        if panels.last().is_none_or(|panel| panel.title != title) {
            panels.push(CurvePanel {
                title,
                curves: Vec::new(),
            });
        }
        let panel = panels.last_mut().expect("pushed above");
        let label = format!(
            "k_δ = {:.0e} N/m, m_e = {} kg, n = {}",
            p.case.k_delta, p.case.m_e, p.n
        );
        if panel.curves.last().is_none_or(|c| c.label != label) {
            panel.curves.push(Curve {
                label,
                points: Vec::new(),
                limit: None,
            });
        }
        let curve = panel.curves.last_mut().expect("pushed above");
        match p.inertia_ratio {
            Some(r) => curve.points.push((r, p.eta_fe)),
            None => curve.limit = Some(p.eta_fe),
        }
    }
    panels
}

/// Runs `flexrig eta-rotor`.
pub fn run(args: &EtaRotorArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if !(2..=200).contains(&args.points) {
        return Err(CliError::InvalidArgument {
            arg: "--points".into(),
            value: args.points.to_string(),
            allowed: "must lie in [2, 200]".into(),
        });
    }
    let ratios = parse_range("--ratio", &args.ratio, args.points)?;
    if args.n.is_empty()
        || args
            .n
            .iter()
            .any(|n| !(n.is_finite() && (1.0..=3.0).contains(n)))
    {
        return Err(CliError::InvalidArgument {
            arg: "--n".into(),
            value: format!("{:?}", args.n),
            allowed: "one or more exponents in [1, 3]".into(),
        });
    }
    let settings = EtaSettings {
        method: ClMethod::Modal {
            mesh: GradedMesh::DEFAULT,
            tol: args.tol,
        },
        damping: args.contact.spec()?,
        ..EtaSettings::DEFAULT
    };
    let points = rotor_sweep(&ratios, &args.n, &settings).map_err(|e| match e {
        flexrig_impact::ImpactError::InvalidParameter { field, .. } if field == "inertia_ratio" => {
            CliError::InvalidArgument {
                arg: "--ratio".into(),
                value: args.ratio.clone(),
                allowed: "FROM:TO with 1e-9 ≤ FROM < TO ≤ 1e9".into(),
            }
        }
        other => as_flag(other),
    })?;
    let title = format!(
        "η_FE from a freely pivoting link (J_R → 0) to the held joint (dashed), {} (m_r = 10 kg, k_c = 1e8, v0 = 2 m/s)",
        contact_text(&settings.damping)
    );
    let svg_path = args.out.join("eta_rotor.svg");
    let csv_path = args.out.join("eta_rotor.csv");
    let svg = log_x_curves_svg(
        &title,
        "rotor over link inertia J_R/(m_r L²/3)",
        "η_FE = f_CL/f_CJ",
        &panels(&points),
    )
    .map_err(|message| CliError::Plot {
        path: svg_path.clone(),
        message,
    })?;
    ensure_dir(&args.out)?;
    write_atomic(&csv_path, csv(&points).as_bytes())?;
    write_atomic(&svg_path, svg.as_bytes())?;
    if args.json {
        return print_json(
            out,
            &json!({ "settings": settings, "points": points, "csv": csv_path, "svg": svg_path }),
        );
    }
    line(
        out,
        format!(
            "η_FE along J_R/(m_r L²/3) = {} ({} points), n = {:?}, {}: free pivot → held",
            args.ratio,
            args.points,
            args.n,
            contact_text(&settings.damping)
        ),
    )?;
    for curve in points.chunk_by(|a, b| a.case == b.case && a.n == b.n) {
        let (first, last) = (curve[0], curve[curve.len() - 1]);
        let lowest = curve
            .iter()
            .min_by(|a, b| a.eta_fe.total_cmp(&b.eta_fe))
            .expect("non-empty");
        line(
            out,
            format!(
                "m_h {:>6} kg, k_δ {:>5.0e}, m_e {:>4} kg, n {}: η_FE {:.4} (ρ = {:.1e}) … {:.4} (held), lowest {:.4} at {}",
                first.case.m_h,
                first.case.k_delta,
                first.case.m_e,
                first.n,
                first.eta_fe,
                first.inertia_ratio.unwrap_or(f64::NAN),
                last.eta_fe,
                lowest.eta_fe,
                lowest
                    .inertia_ratio
                    .map_or("held".to_string(), |r| format!("ρ = {r:.2e}"))
            ),
        )?;
    }
    line(
        out,
        format!("Wrote {} and {}", csv_path.display(), svg_path.display()),
    )
}
