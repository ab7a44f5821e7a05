//! `flexrig payload`: the test bed's CL/CJ peak ratio over the payload, see [`flexrig::fe::payload`].

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::fe::payload::PayloadOptions;
use flexrig::{CancelToken, Error};

use crate::print::{line, print_json};

/// Arguments of `flexrig payload`.
#[derive(Debug, Args)]
pub struct PayloadArgs {
    /// Scene to vary (its `robot.design` is set to cj and to cl): a bundled scene's name
    /// (cl_light_load: the aluminium operator of the paper's light-load study; `flexrig scenes`
    /// lists them) or a scene file's path.
    #[arg(long, default_value = "cl_light_load")]
    pub scene: String,
    /// Payloads [kg], log-spaced: FROM:TO:N:log, or FROM:TO with N from --points (within
    /// [0.0001, 10] kg; see "Ranges" in docs/cli.md).
    #[arg(long, value_name = "FROM:TO[:N:log]", default_value = "0.01:1")]
    pub payloads: String,
    /// Payloads given as FROM:TO (2 to 1000).
    #[arg(long, value_name = "N", default_value_t = 25)]
    pub points: usize,
    /// Directory for payload.csv and the MCAP logs of three points (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Size and formats of payload.svg.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
}

/// Runs `flexrig payload`.
pub fn run(args: &PayloadArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let (from, to, points) = flexrig::fe::payload::parse_payloads(&args.payloads, args.points)?;
    let result = flexrig::fe::payload::run(
        &PayloadOptions {
            scene: args.scene.clone(),
            from,
            to,
            points,
            out: args.out.clone(),
            figures: args.figure.options()?,
        },
        cancel,
    )?;
    let (rows, csv_path, logs) = (&result.rows, &result.csv, &result.logs);
    if args.json {
        return print_json(out, &flexrig::fronts::payload_report(&result));
    }
    line(
        out,
        format!(
            "Test bed ({}): CL/CJ peak over the payload, release to separation",
            args.scene
        ),
    )?;
    line(
        out,
        format!(
            "{:>10} {:>12} {:>12} {:>8}",
            "m_e[kg]", "CJ[N]", "CL[N]", "CL/CJ"
        ),
    )?;
    for r in rows {
        line(
            out,
            format!(
                "{:>10.4} {:>12.3} {:>12.3} {:>8.4}",
                r.payload_kg, r.cj_peak_n, r.cl_peak_n, r.ratio
            ),
        )?;
    }
    line(
        out,
        format!(
            "Wrote {}, {} and {} logs in {}",
            csv_path.display(),
            result
                .figures
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", "),
            logs.len(),
            args.out.display()
        ),
    )
}
