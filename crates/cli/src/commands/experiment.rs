//! `flexrig experiment`: the paper's §VI experiment replayed (Fig. 9), see
//! [`flexrig::testbed::experiment`]; a progress bar while the runs go, then the table.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::testbed::experiment::{self, ExperimentOptions, GroupStats, RatioStats, mean_pm_ci};
use flexrig::{CancelToken, Error};

use super::figure_args::FigureArgs;
use crate::print::{Bar, line, parse_overrides, print_json};

/// Arguments of `flexrig experiment`.
#[derive(Debug, Args)]
pub struct ExperimentArgs {
    /// Repeats of each Fig. 9a configuration (the paper: 5).
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Standard deviation of the release-angle jitter [deg].
    #[arg(long, value_name = "DEG", default_value_t = 0.5)]
    pub jitter_deg: f64,
    /// Seed of the jitter RNG.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Directory for an MCAP log per run, fig9.svg and experiment.csv (created if missing; its
    /// files are overwritten).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Directory with scene files to use instead of the bundled ones of the same names
    /// (cj_aluminium.toml, …; any subset: the others stay bundled). `flexrig scenes --write
    /// NAME --out DIR/NAME.toml` writes one to edit.
    #[arg(long, value_name = "DIR")]
    pub scenes: Option<PathBuf>,
    /// Override a scene field in every scene of the experiment, as in `flexrig run --set`
    /// (dotted path, e.g. robot.payload_kg=0.2; repeatable). The jitter is added to the
    /// release angle that results.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Size and formats of fig9.
    #[command(flatten)]
    pub figure: FigureArgs,
}

impl ExperimentArgs {
    /// The library's options; errors name the flag.
    pub fn options(&self) -> Result<ExperimentOptions, Error> {
        let mut options = ExperimentOptions {
            repeats: self.repeats,
            jitter_deg: self.jitter_deg,
            seed: self.seed,
            out: self.out.clone(),
            scenes: self.scenes.clone(),
            overrides: Vec::new(),
            figures: self.figure.options()?,
        };
        options.validate()?;
        options.overrides = parse_overrides(&self.set)?;
        Ok(options)
    }
}

/// Runs `flexrig experiment`.
pub fn run(args: &ExperimentArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    report(&args.options()?, args.json, out, cancel)
}

/// Runs the experiment of `options` with a progress bar and prints its table (or JSON).
pub fn report(
    options: &ExperimentOptions,
    json: bool,
    out: &mut dyn Write,
    cancel: &CancelToken,
) -> Result<(), Error> {
    let result = experiment::run(
        options,
        cancel,
        &Bar::new("{bar:30} {pos}/{len} runs {msg}"),
    )?;
    if json {
        return print_json(out, &flexrig::fronts::experiment_report(&result));
    }
    print_table(out, &result.groups, &result.ratios)?;
    for note in &result.notes {
        line(out, note)?;
    }
    let figures: Vec<String> = result
        .figures
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    line(
        out,
        format!(
            "Wrote {} MCAP logs, {} and {} in {}",
            result.runs.len(),
            result.csv.display(),
            figures.join(", "),
            options.out.display()
        ),
    )?;
    line(
        out,
        "Open a log in Foxglove with the layout written beside it (NAME.layout.json beside \
         NAME.mcap: the plots over its contact; see docs/foxglove.md).",
    )
}

/// `± ci` with `decimals`, or blank when there is no interval.
fn plus_minus(ci: Option<f64>, decimals: usize) -> String {
    ci.map_or(String::new(), |c| format!("± {c:.decimals$}"))
}

/// The printed table: peak force per scene, then the paired CL/CJ ratios.
fn print_table(
    out: &mut dyn Write,
    groups: &[GroupStats],
    ratios: &[RatioStats],
) -> Result<(), Error> {
    line(
        out,
        "Paper §VI replayed: peak impact force, mean ± 95 % CI (Student t; none from one run)",
    )?;
    line(
        out,
        format!(
            "{:<16} {:>6} {:>18} {:>9} {:>9} {:>4} {:>14} {:>10}",
            "scene file", "design", "operator", "m_h [g]", "m_e [g]", "runs", "peak [N]", "CI [N]"
        ),
    )?;
    for g in groups {
        line(
            out,
            format!(
                "{:<16} {:>6} {:>18} {:>9.1} {:>9.1} {:>4} {:>14.3} {:>10}",
                g.scene,
                g.inputs.design.to_uppercase(),
                g.inputs.block_material,
                g.inputs.block_mass_kg * 1e3,
                g.inputs.payload_kg * 1e3,
                g.n,
                g.mean_peak_force_n,
                plus_minus(g.ci95_n, 3)
            ),
        )?;
    }
    line(
        out,
        "CL/CJ peak-force ratio, paired by repeat (same release angle), mean ± 95 % CI:",
    )?;
    line(out, format!("{:<16} {:>5}   {}", "case", "pairs", "CL/CJ"))?;
    for r in ratios {
        line(
            out,
            format!(
                "{:<16} {:>5}   {}",
                r.case,
                r.pairs,
                mean_pm_ci(r.mean_cl_over_cj, r.ci95)
            ),
        )?;
    }
    Ok(())
}
