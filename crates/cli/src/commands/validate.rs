//! `flexrig validate`: the verification report against every reference
//! ([`flexrig::quality::validation`]).

use std::io::Write;
use std::path::PathBuf;

use crate::print::{line, print_json};
use clap::Args;
use flexrig::Error;

/// Arguments of `flexrig validate`.
#[derive(Debug, Args)]
pub struct ValidateArgs {
    /// Skip the slowest cases (the PRB fit path, the rig convergence study).
    #[arg(long)]
    pub quick: bool,
    /// Directory for validation.md (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Runs `flexrig validate`; fails (exit code 1) if any case fails.
pub fn run(args: &ValidateArgs, out: &mut dyn Write) -> Result<(), Error> {
    let result = flexrig::quality::validation::run(args.quick, &args.out)?;
    let (cases, report) = (&result.cases, &result.report);
    if args.json {
        print_json(out, &flexrig::fronts::validation_report(&result))?;
    } else {
        for c in cases {
            line(
                out,
                format!(
                    "{} {:<58} value {:>16.9e}  ref {:>16.9e}  err {:.1e} ≤ {:.0e}",
                    if c.pass { "pass" } else { "FAIL" },
                    c.name,
                    c.value,
                    c.reference,
                    c.error,
                    c.tolerance
                ),
            )?;
        }
        line(
            out,
            format!(
                "{} of {} passed, {} failed",
                cases.iter().filter(|c| c.pass).count(),
                cases.len(),
                cases.iter().filter(|c| !c.pass).count()
            ),
        )?;
        line(out, format!("Wrote {}", report.display()))?;
    }
    result.check()
}
