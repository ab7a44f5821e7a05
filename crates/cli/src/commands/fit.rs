//! `flexrig fit`: least-squares Hertz fit f = k δ^n of compression data (paper §III-B), see
//! [`flexrig::fit`].

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use serde_json::json;

use crate::print::{line, print_json};
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
    let (fit, warnings) = flexrig::fit::fit_file_with_warnings(&args.file)?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    if args.json {
        return print_json(
            out,
            &json!({
                "k": fit.k,
                "n": fit.n,
                "r2": fit.r2,
                "k_stderr": fit.k_stderr,
                "n_stderr": fit.n_stderr,
                "rms_residual_n": fit.rms_residual_n,
                "points": fit.points,
                "skipped": fit.skipped,
                "iterations": fit.iterations,
                "warnings": warnings,
            }),
        );
    }
    line(
        out,
        format!("Hertz fit f = k δ^n of {}", args.file.display()),
    )?;
    line(
        out,
        format!("  k  = {:.6e} ± {:.2e} N/m^n", fit.k, fit.k_stderr),
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
