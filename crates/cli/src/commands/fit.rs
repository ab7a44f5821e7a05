//! `flexrig fit`: least-squares Hertz fit f = k δ^n of compression data (paper §III-B), see
//! [`flexrig::lumped::fit`].

use std::io::Write;
use std::path::PathBuf;

use crate::print::{line, print_json};
use clap::Args;
use flexrig::Error;

/// Arguments of `flexrig fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// CSV file with a header `indentation_m,force_n` and one sample per line (indentation
    /// [m], force [N]).
    #[arg(value_name = "FILE.csv")]
    pub file: PathBuf,
    /// Print JSON (keys k, n, r2, k_stderr, n_stderr, ...) instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `flexrig fit`.
pub fn run(args: &FitArgs, out: &mut dyn Write) -> Result<(), Error> {
    let (fit, warnings) = flexrig::lumped::fit::fit_file_with_warnings(&args.file)?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        return print_json(out, &flexrig::fronts::fit_report(&fit, &warnings));
    }
    line(
        out,
        format!("Hertz fit f = k δ^n of {}", args.file.display()),
    )?;
    line(
        out,
        format!("  k  = {:.6e} ± {:.2e} N/mⁿ", fit.k, fit.k_stderr),
    )?;
    line(out, format!("  n  = {:.6} ± {:.2e}", fit.n, fit.n_stderr))?;
    line(out, format!("  R² = {:.8}", fit.r2))?;
    line(
        out,
        format!(
            "  {} points used ({} with indentation ≤ 0 skipped), RMS residual {:.3e} N",
            fit.points, fit.skipped, fit.rms_residual_n
        ),
    )
}
