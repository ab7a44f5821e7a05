//! `flexrig fig6`: the paper's Fig. 6 η(γ) study (§V, Eq. 15), see [`flexrig::lumped::fig6`]; a table or
//! JSON.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::Error;
use flexrig::lumped::fig6::{DEFAULT_POINTS, Fig6Options};

use crate::print::{line, print_json};

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
    /// Size and formats of fig6.svg.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
    /// The design held fixed.
    #[command(flatten)]
    pub design: super::impact_args::DesignArgs,
    /// The cases.
    #[command(flatten)]
    pub cases: super::impact_args::CaseArgs,
}

/// Runs `flexrig fig6`.
pub fn run(args: &Fig6Args, out: &mut dyn Write) -> Result<(), Error> {
    let result = flexrig::lumped::fig6::run(&Fig6Options {
        out: args.out.clone(),
        points: args.points,
        figures: args.figure.options()?,
        design: args.design.design(),
        grid: args.cases.grid(),
    })?;
    if args.json {
        return print_json(out, &flexrig::fronts::fig6_report(&result));
    }
    let d = &result.design;
    line(
        out,
        format!(
            "Fig. 6 (paper §V): η(2/3) = f_max(γ = 2/3)/f_max(γ = 1), m_r = {} kg, k_c = {:e} N/mⁿ, v0 = {} m/s",
            d.m_r, d.k_c, d.v0
        ),
    )?;
    line(
        out,
        format!(
            "{:>8} {:>10} {:>6} {:>10} {:>10}",
            "m_h[kg]", "k_δ[N/m]", "m_e[kg]", "η n=1", "η n=2"
        ),
    )?;
    for pair in result.curves.chunks(2) {
        let case = pair[0].case;
        line(
            out,
            format!(
                "{:>8} {:>10.0e} {:>6} {:>10.6} {:>10.6}",
                case.m_h, case.k_delta, case.m_e, pair[0].eta_at_2_3, pair[1].eta_at_2_3
            ),
        )?;
    }
    if *d == flexrig::lumped::fig6::Fig6Design::PAPER {
        line(
            out,
            "The paper quotes η = 0.89 (m_h = 4 kg) and 0.82 (m_h = 1000 kg) for m_e = 0.1 kg: the n = 1 values.",
        )?;
    }
    line(
        out,
        format!(
            "Wrote {} and {}",
            result.csv.display(),
            result.svg.display()
        ),
    )
}
