//! `flexrig fig6`: the paper's Fig. 6 η(γ) study (§V, Eq. 15), as a CSV, an SVG and a table.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig_lumped::fig6::{self, EtaCurve};
use serde_json::json;

use crate::CliError;
use crate::output::{ensure_dir, line, print_json, write_atomic};
use crate::plots::fig6_svg;

/// Default number of γ samples over [0.5, 1].
pub const DEFAULT_POINTS: usize = 101;
/// Fewest γ samples the figure is drawn from (the CSV keeps `--points`).
pub const PLOT_POINTS: usize = 201;

/// Arguments of `flexrig fig6`.
#[derive(Debug, Args)]
pub struct Fig6Args {
    /// Directory for fig6.csv and fig6.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Number of γ samples over [0.5, 1] (≥ 2).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_POINTS)]
    pub points: usize,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `flexrig fig6`.
pub fn run(args: &Fig6Args, out: &mut dyn Write) -> Result<(), CliError> {
    if args.points < 2 {
        return Err(CliError::InvalidArgument {
            arg: "--points".into(),
            value: args.points.to_string(),
            allowed: "must be at least 2".into(),
        });
    }
    let curves = fig6::fig6(args.points)?;
    ensure_dir(&args.out)?;
    let csv_path = args.out.join("fig6.csv");
    let svg_path = args.out.join("fig6.svg");
    write_atomic(&csv_path, csv(&curves).as_bytes())?;
    // The figure is drawn from at least PLOT_POINTS samples, so that its curves are smooth.
    let dense;
    let plotted = if args.points >= PLOT_POINTS {
        &curves
    } else {
        dense = fig6::fig6(PLOT_POINTS)?;
        &dense
    };
    let svg = fig6_svg(plotted).map_err(|message| CliError::Plot {
        path: svg_path.clone(),
        message,
    })?;
    write_atomic(&svg_path, svg.as_bytes())?;

    if args.json {
        let cases: Vec<_> = curves
            .iter()
            .map(|c| {
                json!({
                    "m_h": c.case.m_h,
                    "k_delta": c.case.k_delta,
                    "m_e": c.case.m_e,
                    "n": c.n,
                    "eta_at_2_3": c.eta_at_2_3,
                    "gamma": c.gamma,
                    "eta": c.eta,
                })
            })
            .collect();
        return print_json(
            out,
            &json!({"cases": cases, "csv": csv_path, "svg": svg_path}),
        );
    }
    line(
        out,
        "Fig. 6 (paper §V): η(2/3) = f_max(γ = 2/3)/f_max(γ = 1), m_r = 10 kg, k_c = 1e8, v0 = 2 m/s",
    )?;
    line(
        out,
        format!(
            "{:>8} {:>10} {:>6} {:>10} {:>10}",
            "m_h[kg]", "k_δ[N/m]", "m_e[kg]", "η n=1", "η n=2"
        ),
    )?;
    for pair in curves.chunks(2) {
        let case = pair[0].case;
        line(
            out,
            format!(
                "{:>8} {:>10.0e} {:>6} {:>10.6} {:>10.6}",
                case.m_h, case.k_delta, case.m_e, pair[0].eta_at_2_3, pair[1].eta_at_2_3
            ),
        )?;
    }
    line(
        out,
        "The paper quotes η = 0.89 (m_h = 4 kg) and 0.82 (m_h = 1000 kg) for m_e = 0.1 kg: the n = 1 values.",
    )?;
    line(
        out,
        format!("Wrote {} and {}", csv_path.display(), svg_path.display()),
    )
}

/// One row per (case, n, γ): `m_h_kg,k_delta_n_per_m,m_e_kg,n,gamma,eta`.
fn csv(curves: &[EtaCurve]) -> String {
    let mut text = String::from("m_h_kg,k_delta_n_per_m,m_e_kg,n,gamma,eta\n");
    for c in curves {
        for (g, e) in c.gamma.iter().zip(&c.eta) {
            let _ = writeln!(
                text,
                "{},{:e},{},{},{:.17},{:.17}",
                c.case.m_h, c.case.k_delta, c.case.m_e, c.n, g, e
            );
        }
    }
    text
}
