//! `flexrig payload`: the test bed's CL/CJ peak ratio over the payload m_e (issue 14; the paper's
//! Fig. 9b light-load study generalised from one point to a curve). The bundled rig (a scene
//! with `robot.design` set to `cj` and to `cl`, everything else equal) runs for each payload from
//! release to separation, in parallel through the sweep machinery; three chosen points keep an
//! MCAP log of each design.

use std::fmt::Write as _;
use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig_rig::overrides::Override;
use flexrig_rig::{RunOptions, Simulation};
use serde::Serialize;
use serde_json::json;

use crate::CliError;
use crate::cli::Interrupt;
use crate::commands::experiment::BUNDLED_SCENES;
use crate::mcap_log::{LogRates, LogTarget, run_logged};
use crate::output::{ensure_dir, line, print_json, write_atomic};
use crate::study::spec::Dimension;
use crate::study::sweep::{Sweep, SweepOptions};

/// Arguments of `flexrig payload`.
#[derive(Debug, Args)]
pub struct PayloadArgs {
    /// Bundled scene to vary (its `robot.design` is set to cj and to cl): cl_light_load (the
    /// aluminium operator of the paper's light-load study) or any other bundled name.
    #[arg(long, default_value = "cl_light_load")]
    pub scene: String,
    /// Smallest payload, kg.
    #[arg(long, value_name = "KG", default_value_t = 0.01)]
    pub from: f64,
    /// Largest payload, kg.
    #[arg(long, value_name = "KG", default_value_t = 1.0)]
    pub to: f64,
    /// Payloads, log-spaced (2 to 1000).
    #[arg(long, value_name = "N", default_value_t = 25)]
    pub points: usize,
    /// Directory for payload.csv and the MCAP logs of three points (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// One payload: both designs' peaks and their ratio.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PayloadRow {
    /// Payload m_e \[kg\].
    pub payload_kg: f64,
    /// CJ peak \[N\].
    pub cj_peak_n: f64,
    /// CL peak \[N\].
    pub cl_peak_n: f64,
    /// CL/CJ.
    pub ratio: f64,
}

fn check(args: &PayloadArgs) -> Result<String, CliError> {
    let bad = |arg: &str, value: String, allowed: &str| CliError::InvalidArgument {
        arg: arg.into(),
        value,
        allowed: allowed.into(),
    };
    let text = BUNDLED_SCENES
        .iter()
        .find(|(n, _)| *n == args.scene)
        .map(|(_, t)| t.to_string())
        .ok_or_else(|| {
            let names: Vec<&str> = BUNDLED_SCENES.iter().map(|(n, _)| *n).collect();
            bad(
                "--scene",
                args.scene.clone(),
                &format!("one of {}", names.join(", ")),
            )
        })?;
    for (flag, v) in [("--from", args.from), ("--to", args.to)] {
        if !(v.is_finite() && (1e-4..=10.0).contains(&v)) {
            return Err(bad(flag, v.to_string(), "must lie in [1e-4, 10] kg"));
        }
    }
    if args.from >= args.to {
        return Err(bad(
            "--to",
            args.to.to_string(),
            "must be larger than --from",
        ));
    }
    if !(2..=1000).contains(&args.points) {
        return Err(bad(
            "--points",
            args.points.to_string(),
            "must lie in [2, 1000]",
        ));
    }
    Ok(text)
}

/// The payloads, log-spaced from `from` to `to` (both exactly).
fn payloads(args: &PayloadArgs) -> Vec<f64> {
    let (a, b) = (args.from.ln(), args.to.ln());
    let last = args.points - 1;
    (0..args.points)
        .map(|i| match i {
            0 => args.from,
            i if i == last => args.to,
            i => (a + (b - a) * i as f64 / last as f64).exp(),
        })
        .collect()
}

/// Runs the curve: both designs at every payload.
pub fn payload_curve(
    base_text: &str,
    payloads: &[f64],
    interrupt: &Interrupt,
) -> Result<Vec<PayloadRow>, CliError> {
    let dimensions = vec![
        Dimension {
            path: "robot.payload_kg".into(),
            values: payloads.iter().map(|&p| toml::Value::Float(p)).collect(),
        },
        Dimension {
            path: "robot.design".into(),
            values: vec!["cj".into(), "cl".into()],
        },
    ];
    let sweep = Sweep::new(base_text, dimensions, false)?;
    let options = SweepOptions {
        interrupt: interrupt.0.clone(),
        ..SweepOptions::default()
    };
    let indices: Vec<usize> = (0..sweep.len()).collect();
    let rows = sweep.run(&indices, &options, &|_| ());
    if rows.len() != sweep.len() {
        return Err(CliError::Rig(flexrig_rig::RigError::Interrupted { t: 0.0 }));
    }
    let peak = |i: usize| -> Result<f64, CliError> {
        let r = &rows[i];
        match r.summary.first().copied().flatten() {
            Some(p) if r.status == "ok" => Ok(p),
            _ => Err(CliError::InvalidArgument {
                arg: "--from/--to".into(),
                value: format!("payload {}", r.values[0]),
                allowed: format!("a payload the rig can run: {}", r.error),
            }),
        }
    };
    payloads
        .iter()
        .enumerate()
        .map(|(i, &p)| {
            let (cj, cl) = (peak(2 * i)?, peak(2 * i + 1)?);
            Ok(PayloadRow {
                payload_kg: p,
                cj_peak_n: cj,
                cl_peak_n: cl,
                ratio: cl / cj,
            })
        })
        .collect()
}

/// Logs both designs at the smallest, the middle and the largest payload.
fn log_three(
    base_text: &str,
    payloads: &[f64],
    dir: &std::path::Path,
    interrupt: &Interrupt,
) -> Result<Vec<PathBuf>, CliError> {
    let materials = flexrig_contact::Materials::bundled()?;
    let base: toml::Table = toml::from_str(base_text)
        .map_err(|e| flexrig_rig::RigError::SceneSyntax(e.message().to_string()))?;
    let chosen = [
        payloads[0],
        payloads[payloads.len() / 2],
        payloads[payloads.len() - 1],
    ];
    let mut paths = Vec::new();
    for p in chosen {
        for design in ["cj", "cl"] {
            let overrides = [
                Override::new("robot.payload_kg", toml::Value::Float(p)),
                Override::new("robot.design", design.into()),
            ];
            let scene = flexrig_rig::scene_from_table(&base, &overrides, &materials)?;
            let text = flexrig_rig::overrides::apply(base_text, &overrides)?;
            let path = dir.join(format!("payload_{design}_{p:.4}kg.mcap"));
            run_logged(
                Simulation::new(&scene, RunOptions::default())?,
                &scene,
                &LogTarget {
                    path: &path,
                    force: true,
                    scene_text: &text,
                    interrupt: interrupt.0.clone(),
                    rates: LogRates::DECIMATED,
                    deformation_scale: crate::mcap_log::DEFAULT_DEFORMATION_SCALE,
                },
            )?;
            paths.push(path);
        }
    }
    Ok(paths)
}

fn csv(rows: &[PayloadRow]) -> String {
    let mut s = String::from("payload_kg,cj_peak_n,cl_peak_n,cl_over_cj\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{}",
            r.payload_kg, r.cj_peak_n, r.cl_peak_n, r.ratio
        );
    }
    s
}

/// Runs `flexrig payload`.
pub fn run(args: &PayloadArgs, out: &mut dyn Write, interrupt: &Interrupt) -> Result<(), CliError> {
    let text = check(args)?;
    let payloads = payloads(args);
    let rows = payload_curve(&text, &payloads, interrupt)?;
    ensure_dir(&args.out)?;
    let logs = log_three(&text, &payloads, &args.out, interrupt)?;
    let csv_path = args.out.join("payload.csv");
    write_atomic(&csv_path, csv(&rows).as_bytes())?;
    if args.json {
        return print_json(out, &json!({ "rows": rows, "csv": csv_path, "logs": logs }));
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
    for r in &rows {
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
            "Wrote {} and {} logs in {}",
            csv_path.display(),
            logs.len(),
            args.out.display()
        ),
    )
}
