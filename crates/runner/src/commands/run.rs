//! `flexrig run SCENE`: one run of the drop-pendulum test rig.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig_contact::Materials;
use flexrig_rig::overrides;
use flexrig_rig::{
    Interruptible, Override, RunOptions, RunSummary, Simulation, scene_with_overrides,
};
use serde_json::json;

use crate::CliError;
use crate::cli::Interrupt;
use crate::mcap_log::{DEFAULT_DEFORMATION_SCALE, LogRates, LogTarget, run_logged};
use crate::output::{line, positive_arg, print_json};

/// Arguments of `flexrig run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// Scene file (TOML), e.g. assets/scenes/cj_aluminium.toml; see docs/scenes.md.
    #[arg(value_name = "SCENE")]
    pub scene: PathBuf,
    /// Write the run's traces to this MCAP file (opens in Foxglove; see docs/foxglove.md).
    #[arg(long, value_name = "FILE.mcap")]
    pub out: Option<PathBuf>,
    /// Overwrite the --out file if it exists.
    #[arg(long)]
    pub force: bool,
    /// Log every step and sensor sample on every channel (default: the 3D view at 60 Hz and the
    /// sensors at 250 Hz outside contact; inside contact everything is logged either way).
    #[arg(long, requires = "out")]
    pub log_every_step: bool,
    /// Factor on the CL beam's deflection in the log's 3D view (FE post-processing style,
    /// labelled in the view and recorded in the log; 1 = true scale; the CJ link is rigid).
    #[arg(long, requires = "out", value_name = "FACTOR", default_value_t = DEFAULT_DEFORMATION_SCALE)]
    pub deformation_scale: f64,
    /// Override a scene field, e.g. `--set robot.payload_kg=0.2` or
    /// `--set operator.start.release_angle_deg=45` (repeatable; validated like the file).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// How `flexrig run` logs: where, whether it may overwrite, how often, how the 3D view draws.
#[derive(Debug, Clone, Copy)]
pub struct LogRequest<'a> {
    /// The MCAP file (`--out`); none: no log.
    pub out: Option<&'a PathBuf>,
    /// Overwrite the log and its layout (`--force`).
    pub force: bool,
    /// What is logged how often.
    pub rates: LogRates,
    /// Factor on the CL beam's deflection in the 3D view (`--deformation-scale`).
    pub deformation_scale: f64,
}

/// Loads, validates and runs a scene file, logging as `log` asks (MCAP and its Foxglove
/// layout). The log is always finished, with an `error` metadata record if the run failed.
pub fn run_scene_file(
    path: &std::path::Path,
    overrides: &[Override],
    log: LogRequest<'_>,
    interrupt: &Interrupt,
) -> Result<RunSummary, CliError> {
    let text = crate::output::read_text(path)?;
    let scene = scene_with_overrides(&text, overrides, &Materials::bundled()?)?;
    // the log records the scene as run
    let text = overrides::apply(&text, overrides)?;
    let simulation = Simulation::new(&scene, RunOptions::default())?;
    let Some(out) = log.out else {
        return Ok(simulation.run(&mut Interruptible(interrupt.0.clone()))?);
    };
    run_logged(
        simulation,
        &scene,
        &LogTarget {
            path: out,
            force: log.force,
            scene_text: &text,
            interrupt: interrupt.0.clone(),
            rates: log.rates,
            deformation_scale: log.deformation_scale,
        },
    )
}

/// The run summary as `flexrig run --json` prints it: every field of [`RunSummary`] (absent
/// when it does not apply, e.g. `contact_duration_s` for a run stopped at the peak) and the
/// number of sensor `samples`.
pub fn summary_json(s: &RunSummary) -> serde_json::Value {
    let mut value = serde_json::to_value(s).expect("a run summary serialises");
    if let Some(map) = value.as_object_mut() {
        map.retain(|_, v| !v.is_null());
        map.insert("samples".into(), json!(s.samples.len()));
    }
    value
}

/// Runs `flexrig run`.
pub fn run(args: &RunArgs, out: &mut dyn Write, interrupt: &Interrupt) -> Result<(), CliError> {
    let rates = if args.log_every_step {
        LogRates::EVERY_STEP
    } else {
        LogRates::DECIMATED
    };
    let overrides = args
        .set
        .iter()
        .map(|s| Override::parse(s))
        .collect::<Result<Vec<_>, _>>()?;
    let deformation_scale = positive_arg("--deformation-scale", args.deformation_scale)?;
    let s = run_scene_file(
        &args.scene,
        &overrides,
        LogRequest {
            out: args.out.as_ref(),
            force: args.force,
            rates,
            deformation_scale,
        },
        interrupt,
    )?;
    if args.json {
        return print_json(out, &summary_json(&s));
    }
    line(out, format!("scene {} ({})", s.scene, s.design))?;
    if let Some(path) = &args.out {
        line(out, format!("  log                 {}", path.display()))?;
    }
    line(
        out,
        format!(
            "  peak force          {:.6} N at t = {:.6} s",
            s.peak_force_n, s.time_of_peak_s
        ),
    )?;
    line(
        out,
        format!(
            "  impact velocity     {:.6} m/s (onset at {:.6} s)",
            s.impact_velocity_mps, s.onset_time_s
        ),
    )?;
    match s.contact_duration_s {
        Some(d) => line(out, format!("  contact duration    {:.6e} s", d))?,
        None => line(out, "  contact duration    (stopped before separation)")?,
    }
    line(
        out,
        format!("  max indentation     {:.6e} m", s.max_indentation_m),
    )?;
    line(
        out,
        format!("  impulse             {:.6e} N·s", s.impulse_n_s),
    )?;
    line(
        out,
        format!(
            "  steps               {} ({} in contact at {:.3e} s), {} sensor samples",
            s.steps,
            s.contact_steps,
            s.contact_step_s,
            s.samples.len()
        ),
    )
}
