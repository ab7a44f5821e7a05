//! `flexrig run SCENE`: one run of the drop-pendulum test rig ([`flexrig::run`]).

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::mcap_log::{DEFAULT_DEFORMATION_SCALE, LogRates};
use flexrig::output::positive_arg;
use flexrig::run::{LogRequest, run_scene_file, scene_warnings, summary_json};
use flexrig::{CancelToken, Error};

use crate::print::{line, parse_overrides, print_json};

/// Arguments of `flexrig run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// A bundled scene's name (e.g. cj_aluminium; `flexrig scenes` lists them) or a scene
    /// file's path (TOML, see docs/scenes.md).
    #[arg(value_name = "SCENE")]
    pub scene: PathBuf,
    /// File (MCAP) to write the run's traces to; it opens in Foxglove (see docs/foxglove.md).
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

/// Runs `flexrig run`.
pub fn run(args: &RunArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let rates = if args.log_every_step {
        LogRates::EVERY_STEP
    } else {
        LogRates::DECIMATED
    };
    let overrides = parse_overrides(&args.set)?;
    let deformation_scale = positive_arg("--deformation-scale", args.deformation_scale)?;
    // plausibility warnings before the run (on standard error; the JSON lists them too)
    for w in scene_warnings(&args.scene, &overrides) {
        eprintln!("warning: {w}");
    }
    let s = run_scene_file(
        &args.scene,
        &overrides,
        LogRequest {
            out: args.out.as_ref(),
            force: args.force,
            rates,
            deformation_scale,
        },
        cancel,
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
