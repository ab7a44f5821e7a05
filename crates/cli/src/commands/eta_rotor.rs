//! `flexrig eta-rotor`: η_FE of the Fig. 6 cases along the free hub's rotor inertia, see
//! [`flexrig::fe::eta_rotor`].

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::fe::eta::contact_text;
use flexrig::fe::eta_rotor::EtaRotorOptions;
use flexrig::{CancelToken, Error};

use super::impact_args::DampingArgs;
use crate::print::{line, print_json};

/// Arguments of `flexrig eta-rotor`.
#[derive(Debug, Args)]
pub struct EtaRotorArgs {
    /// Directory for eta_rotor.csv and eta_rotor.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Rotor over link inertia J_R/(m_r L²/3), log-spaced: FROM:TO:N:log, or FROM:TO with N
    /// from --points (within [1e-9, 1e9]; see "Ranges" in docs/cli.md).
    #[arg(long, value_name = "FROM:TO[:N:log]", default_value = "1e-4:1e6")]
    pub ratio: String,
    /// Points along a ratio given as FROM:TO (2 to 200); the held joint is added as the limit.
    #[arg(long, value_name = "N", default_value_t = 21)]
    pub points: usize,
    /// Hertz exponents n, comma-separated (1 to 3 each).
    #[arg(
        long,
        value_name = "N,...",
        value_delimiter = ',',
        default_value = "1,2"
    )]
    pub n: Vec<f64>,
    /// Tolerance of the force's linear hold per step (1e-10 to 0.1).
    #[arg(long, value_name = "TOL", default_value = "1e-6")]
    pub tol: f64,
    /// The contact's damping.
    #[command(flatten)]
    pub contact: DampingArgs,
    /// Print JSON instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Link length L [m], in [1e-3, 1e3] (with m_r it sets the link inertia m_r L²/3).
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    pub length: f64,
    /// Size and formats of eta_rotor.svg.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
    /// The design held fixed.
    #[command(flatten)]
    pub design: super::impact_args::DesignArgs,
    /// The cases.
    #[command(flatten)]
    pub cases: super::impact_args::CaseArgs,
}

/// Runs `flexrig eta-rotor`.
pub fn run(args: &EtaRotorArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let ratios = flexrig::fronts::eta_rotor_inputs(&args.ratio, args.points, &args.n)?;
    let settings = flexrig::fronts::eta_rotor_settings(
        args.tol,
        args.contact.spec()?,
        args.design.design(),
        args.length,
    )?;
    let r = flexrig::fe::eta_rotor::run(
        &EtaRotorOptions {
            out: args.out.clone(),
            ratios,
            n: args.n.clone(),
            settings,
            grid: args.cases.grid(),
            figures: args.figure.options()?,
        },
        cancel,
    )
    .map_err(|e| flexrig::fronts::eta_rotor_error(e, &args.ratio))?;
    let (points, csv_path, svg_path) = (&r.points, &r.csv, &r.svg);
    if args.json {
        return print_json(out, &flexrig::fronts::eta_rotor_report(&settings, &r));
    }
    line(
        out,
        format!(
            "η_FE along J_R/(m_r L²/3) = {} ({} points), n = {}, m_r = {} kg, k_c = {:e} N/mⁿ, v0 = {} m/s, L = {} m, {}: free pivot → held",
            args.ratio,
            args.points,
            args.n
                .iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            settings.design.m_r,
            settings.design.k_c,
            settings.design.v0,
            settings.length,
            contact_text(&settings.damping)
        ),
    )?;
    for curve in points.chunk_by(|a, b| a.case == b.case && a.n == b.n) {
        let (first, last) = (&curve[0], &curve[curve.len() - 1]);
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
