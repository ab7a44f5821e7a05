//! `flexrig bench`: work–precision studies — run time against error — for the lumped impact,
//! the beam and the rig ([`flexrig::quality::bench`]), as a table or JSON rows, with log–log SVG plots.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::{CancelToken, Error};

use crate::print::{line, print_json};

/// Arguments of `flexrig bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Fewer settings and repetitions (well under a minute).
    #[arg(long)]
    pub quick: bool,
    /// Directory for the SVG plots (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON rows instead of the tables.
    #[arg(long)]
    pub json: bool,
    /// Size and formats of the bench_*.svg figures.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
}

/// Runs `flexrig bench`.
pub fn run(args: &BenchArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let report = flexrig::quality::bench::run_cancellable(
        args.quick,
        &args.out,
        &args.figure.options()?,
        cancel,
    )?;
    let (rows, files, peer_ratio) = (
        &report.rows,
        &report.plots,
        report.scipy_dop853_over_flexrig_at_1e_9,
    );
    if args.json {
        return print_json(out, &flexrig::fronts::bench_report(&report));
    }
    line(
        out,
        format!(
            "{:<7} {:<34} {:<14} {:>10} {:>12}",
            "model", "method", "setting", "error", "time [s]"
        ),
    )?;
    for r in rows {
        line(
            out,
            format!(
                "{:<7} {:<34} {:<14} {:>10.2e} {:>12.3e}",
                r.model, r.method, r.setting, r.error, r.seconds
            ),
        )?;
    }
    match peer_ratio {
        Some(r) => line(
            out,
            format!(
                "scipy DOP853 / flexrig run time at a peak error <= 1e-9: {r:.0}x (scipy run by {})",
                report.peer_python
            ),
        )?,
        None => line(
            out,
            flexrig::quality::bench::peer_missing_note(&report.peer_python),
        )?,
    }
    line(
        out,
        format!(
            "Plots: {}",
            files
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )
}
