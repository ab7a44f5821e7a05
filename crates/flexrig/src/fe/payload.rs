//! The test bed's CL/CJ peak ratio over the payload m_e (the paper's Fig. 9b light-load study
//! generalised from one point to a curve). The bundled rig (a scene with `robot.design` set to
//! `cj` and to `cl`, everything else equal) runs for each payload from release to separation, in
//! parallel through the sweep machinery ([`crate::study`]); three chosen points keep an MCAP log
//! of each design.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexrig_rig::overrides::Override;
use flexrig_rig::{RunOptions, Simulation};
use serde::Serialize;

use crate::Error;
use crate::log::file::{LogTarget, run_logged};
use crate::log::mcap::LogRates;
use crate::shared::cancel::CancelToken;
use crate::shared::output::{ensure_dir, write_atomic};
use crate::study::spec::Dimension;
use crate::study::sweep::{Sweep, SweepOptions};

/// The figure of the payload study.
pub mod figure;

/// What the study varies and where it writes (the flags of `flexrig payload`).
#[derive(Debug, Clone, PartialEq)]
pub struct PayloadOptions {
    /// Scene to vary: a bundled name, e.g. `cl_light_load`, or a scene file's path (`--scene`,
    /// see [`crate::testbed::scenes::resolve`]); its `robot.design` is set to cj and to cl.
    pub scene: String,
    /// Smallest payload \[kg\], in [1e-4, 10] (`--payloads FROM:…`).
    pub from: f64,
    /// Largest payload \[kg\], in [1e-4, 10] and above `from` (`--payloads …:TO`).
    pub to: f64,
    /// Payloads, log-spaced, in [2, 1000] (`--payloads FROM:TO:N:log`, or `--points`).
    pub points: usize,
    /// Directory for payload.csv, the figure and the MCAP logs of three points (created if
    /// missing; `--out`).
    pub out: PathBuf,
    /// Printed size and formats of the figure payload.svg (`--size`, `--format`, `--dpi`).
    pub figures: crate::plots::FigureOptions,
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

/// What [`run`] produced.
#[derive(Debug, Clone, Serialize)]
pub struct PayloadResult {
    /// One row per payload.
    pub rows: Vec<PayloadRow>,
    /// payload.csv.
    pub csv: PathBuf,
    /// The MCAP logs (CJ and CL at the smallest, the middle and the largest payload).
    pub logs: Vec<PathBuf>,
    /// The figure in every format asked for (payload.svg, …).
    pub figures: Vec<PathBuf>,
}

/// The payloads of `--payloads`: `FROM:TO` \[kg\] with N from `points` (`--points`), or
/// `FROM:TO:N:log` (the command line's one range syntax; the payloads are log-spaced, so a
/// linear `FROM:TO:N` is refused naming the flag). Returns (from, to, N); the values are
/// checked by [`run`].
pub fn parse_payloads(text: &str, points: usize) -> Result<(f64, f64, usize), Error> {
    let r = crate::fe::eta_map::parse_log_range("--payloads", text, points)?;
    // N given in the range is the range's: named as --payloads (N from --points is checked,
    // and named, by `run`)
    if text.split(':').count() == 4 && !(2..=1000).contains(&r.points) {
        return Err(Error::InvalidArgument {
            arg: "--payloads".into(),
            value: text.into(),
            allowed: format!("N = {} must lie in [2, 1000]", r.points),
        });
    }
    Ok((r.from, r.to, r.points))
}

/// The scene's text, and the ranges checked (errors name the flag).
fn check(args: &PayloadOptions) -> Result<String, Error> {
    let bad = |arg: &str, value: String, allowed: &str| Error::InvalidArgument {
        arg: arg.into(),
        value,
        allowed: allowed.into(),
    };
    // a file that cannot be read, or is no valid scene, is the flag's fault: named
    let text = crate::testbed::scenes::resolve("--scene", Path::new(&args.scene))
        .map_err(|e| match e {
            Error::Read { source, .. } => bad(
                "--scene",
                args.scene.clone(),
                &format!("cannot be read ({source}): give a bundled scene's name or a scene file"),
            ),
            other => other,
        })?
        .text;
    flexrig_rig::Scene::from_toml_str(&text, &flexrig_contact::Materials::bundled()?).map_err(
        |e| {
            bad(
                "--scene",
                args.scene.clone(),
                &format!("is not a valid scene: {e}"),
            )
        },
    )?;
    use crate::shared::output::display_number;
    let range = || format!("{}:{}", display_number(args.from), display_number(args.to));
    for v in [args.from, args.to] {
        if !(v.is_finite() && (1e-4..=10.0).contains(&v)) {
            return Err(bad(
                "--payloads",
                range(),
                &format!(
                    "FROM and TO must lie in [0.0001, 10] kg: {} does not{}",
                    display_number(v),
                    flexrig_contact::validate::unit_hint_in("kg", v, 1e-4, 10.0)
                ),
            ));
        }
    }
    if args.from >= args.to {
        return Err(bad(
            "--payloads",
            range(),
            "FROM must be smaller than TO (e.g. 0.01:1)",
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
fn payloads(args: &PayloadOptions) -> Vec<f64> {
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
    cancel: &CancelToken,
) -> Result<Vec<PayloadRow>, Error> {
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
        cancel: cancel.clone(),
        ..SweepOptions::default()
    };
    let indices: Vec<usize> = (0..sweep.len()).collect();
    let rows = sweep.run(&indices, &options, &|_| ());
    if rows.len() != sweep.len() {
        return Err(Error::Rig(flexrig_rig::RigError::Interrupted { t: 0.0 }));
    }
    let peak = |i: usize| -> Result<f64, Error> {
        let r = &rows[i];
        match r.summary.first().copied().flatten() {
            Some(p) if r.status == "ok" => Ok(p),
            _ => Err(Error::InvalidArgument {
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
    dir: &Path,
    cancel: &CancelToken,
) -> Result<Vec<PathBuf>, Error> {
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
                Simulation::new(&scene, RunOptions::default())?.with_lean_samples(),
                &scene,
                &LogTarget {
                    path: &path,
                    force: true,
                    scene_text: &text,
                    cancel: cancel.clone(),
                    rates: LogRates::DECIMATED,
                    deformation_scale: crate::log::mcap::DEFAULT_DEFORMATION_SCALE,
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

/// Runs the study: the curve, the three logged points, payload.csv.
pub fn run(options: &PayloadOptions, cancel: &CancelToken) -> Result<PayloadResult, Error> {
    let text = check(options)?;
    options.figures.validate()?;
    let payloads = payloads(options);
    let rows = payload_curve(&text, &payloads, cancel)?;
    ensure_dir(&options.out)?;
    let logs = log_three(&text, &payloads, &options.out, cancel)?;
    let csv_path = options.out.join("payload.csv");
    write_atomic(&csv_path, csv(&rows).as_bytes())?;
    let scene = flexrig_rig::Scene::from_toml_str(&text, &flexrig_contact::Materials::bundled()?)?;
    let operator = format!(
        "{} operator, m_h = {} ({}): CJ and CL, release to separation",
        scene.file.operator.block_material.replace('_', " "),
        crate::plots::grams(scene.block_mass_kg),
        options.scene
    );
    let svg =
        figure::payload_svg(&rows, &operator, options.figures.width_pt()).map_err(|message| {
            Error::Plot {
                path: options.out.join("payload.svg"),
                message,
            }
        })?;
    let figures = crate::plots::write_figure(&options.out, "payload", &svg, &options.figures)?;
    Ok(PayloadResult {
        rows,
        csv: csv_path,
        logs,
        figures,
    })
}
