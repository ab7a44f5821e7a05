//! `flexrig experiment`: the paper's §VI experiment replayed (Fig. 9). CJ and CL against the
//! aluminium (398 g) and the iron (4008 g) operator, each repeated with a release-angle jitter
//! drawn from a seeded RNG and reported as mean and 95 % confidence interval (Fig. 9a); and the
//! light-load case m_e = 0.1 kg (Fig. 9b, the paper's ADAMS study, here the FE beam). Every run
//! writes an MCAP log; the runs go in parallel across cores (rayon), with a progress bar.

use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use flexrig_contact::Materials;
use flexrig_rig::{RunOptions, Scene, Simulation, scene::Start};
use indicatif::{ProgressBar, ProgressStyle};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;
use serde::Serialize;
use serde_json::json;

use crate::CliError;
use crate::cli::Interrupt;
use crate::mcap_log::{LogRates, LogTarget, run_logged};
use crate::output::{ensure_dir, line, print_json, write_atomic};

/// The bundled scenes of the experiment (paper §VI, Fig. 9), relative to the assets directory.
pub const FIG9A_SCENES: [&str; 4] = ["cj_aluminium", "cl_aluminium", "cj_iron", "cl_iron"];
/// The light-load scenes (Fig. 9b).
pub const FIG9B_SCENES: [&str; 2] = ["cj_light_load", "cl_light_load"];

/// Arguments of `flexrig experiment`.
#[derive(Debug, Args)]
pub struct ExperimentArgs {
    /// Repeats of each Fig. 9a configuration (the paper: 5).
    #[arg(long, default_value_t = 5)]
    pub repeats: usize,
    /// Standard deviation of the release-angle jitter \[deg\].
    #[arg(long, value_name = "DEG", default_value_t = 0.5)]
    pub jitter_deg: f64,
    /// Seed of the jitter RNG.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output directory (MCAP per run, fig9.svg, experiment.csv); its files are overwritten.
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Directory with the scene files to use instead of the bundled ones (same names).
    #[arg(long, value_name = "DIR")]
    pub scenes: Option<PathBuf>,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// The bundled scene files, compiled in (the binary needs no assets directory).
pub const BUNDLED_SCENES: [(&str, &str); 6] = [
    (
        "cj_aluminium",
        include_str!("../../../../assets/scenes/cj_aluminium.toml"),
    ),
    (
        "cl_aluminium",
        include_str!("../../../../assets/scenes/cl_aluminium.toml"),
    ),
    (
        "cj_iron",
        include_str!("../../../../assets/scenes/cj_iron.toml"),
    ),
    (
        "cl_iron",
        include_str!("../../../../assets/scenes/cl_iron.toml"),
    ),
    (
        "cj_light_load",
        include_str!("../../../../assets/scenes/cj_light_load.toml"),
    ),
    (
        "cl_light_load",
        include_str!("../../../../assets/scenes/cl_light_load.toml"),
    ),
];

/// Bundled scene `name` with text replacements applied (for studies that vary one setting:
/// `flexrig validate`, `flexrig bench`).
pub fn bundled_scene(name: &str, edits: &[(&str, &str)]) -> Result<Scene, CliError> {
    let (mut text, _) = scene_text(name, None)?;
    for (from, to) in edits {
        text = text.replace(from, to);
    }
    Ok(Scene::from_toml_str(&text, &Materials::bundled()?)?)
}

/// The text of scene `name`: from `dir` if given, else the bundled copy.
fn scene_text(name: &str, dir: Option<&PathBuf>) -> Result<(String, String), CliError> {
    match dir {
        Some(dir) => {
            let path = dir.join(format!("{name}.toml"));
            let text = crate::output::read_text(&path)?;
            Ok((text, path.display().to_string()))
        }
        None => {
            let text = BUNDLED_SCENES
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, t)| t.to_string())
                .expect("every experiment scene is bundled");
            Ok((text, format!("bundled {name}.toml")))
        }
    }
}

/// One run of the experiment.
#[derive(Debug, Clone, Serialize)]
pub struct RunRecord {
    /// Scene name.
    pub scene: String,
    /// Repeat index.
    pub repeat: usize,
    /// Release angle used \[deg\].
    pub release_angle_deg: f64,
    /// Peak contact force \[N\].
    pub peak_force_n: f64,
    /// Impact speed [m/s].
    pub impact_velocity_mps: f64,
    /// Contact duration \[s\].
    pub contact_duration_s: Option<f64>,
    /// Largest indentation \[m\].
    pub max_indentation_m: f64,
    /// The MCAP log.
    pub mcap: PathBuf,
}

/// Mean and 95 % confidence interval of one configuration.
#[derive(Debug, Clone, Serialize)]
pub struct GroupStats {
    /// Scene name.
    pub scene: String,
    /// Runs.
    pub n: usize,
    /// Mean peak force \[N\].
    pub mean_peak_force_n: f64,
    /// Half-width of the 95 % confidence interval of the mean \[N\] (Student t).
    pub ci95_n: f64,
}

/// Two-sided 95 % Student t quantile for `df` degrees of freedom.
pub fn t_quantile_975(df: usize) -> f64 {
    const TABLE: [f64; 30] = [
        12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
        2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
        2.052, 2.048, 2.045, 2.042,
    ];
    match df {
        0 => f64::INFINITY,
        1..=30 => TABLE[df - 1],
        _ => 1.959964 + 2.37 / df as f64,
    }
}

/// Mean and 95 % CI half-width of `values`.
pub fn mean_ci95(values: &[f64]) -> (f64, f64) {
    let n = values.len();
    let mean = values.iter().sum::<f64>() / n as f64;
    if n < 2 {
        return (mean, 0.0);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    (mean, t_quantile_975(n - 1) * (var / n as f64).sqrt())
}

struct Job {
    scene: String,
    repeat: usize,
    angle_deg: f64,
    text: String,
}

/// Runs `flexrig experiment`.
pub fn run(
    args: &ExperimentArgs,
    out: &mut dyn Write,
    interrupt: &Interrupt,
) -> Result<(), CliError> {
    if args.repeats == 0 || args.repeats > 1000 {
        return Err(CliError::InvalidArgument {
            arg: "--repeats".into(),
            value: args.repeats.to_string(),
            allowed: "must lie in [1, 1000]".into(),
        });
    }
    if !(args.jitter_deg.is_finite() && (0.0..=10.0).contains(&args.jitter_deg)) {
        return Err(CliError::InvalidArgument {
            arg: "--jitter-deg".into(),
            value: args.jitter_deg.to_string(),
            allowed: "must lie in [0, 10] degrees".into(),
        });
    }
    let materials = Materials::bundled()?;
    let jobs = plan(args, &materials)?;
    ensure_dir(&args.out)?;
    let progress = ProgressBar::new(jobs.len() as u64).with_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} runs {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let records = jobs
        .par_iter()
        .map(|job| {
            let r = run_job(job, &materials, &args.out, interrupt);
            progress.inc(1);
            r
        })
        .collect::<Result<Vec<RunRecord>, CliError>>()?;
    progress.finish_and_clear();

    let groups: Vec<GroupStats> = FIG9A_SCENES
        .iter()
        .chain(FIG9B_SCENES.iter())
        .map(|name| {
            let peaks: Vec<f64> = records
                .iter()
                .filter(|r| r.scene == *name)
                .map(|r| r.peak_force_n)
                .collect();
            let (mean, ci) = mean_ci95(&peaks);
            GroupStats {
                scene: name.to_string(),
                n: peaks.len(),
                mean_peak_force_n: mean,
                ci95_n: ci,
            }
        })
        .collect();
    let csv_path = args.out.join("experiment.csv");
    let svg_path = args.out.join("fig9.svg");
    write_atomic(&csv_path, csv(&records).as_bytes())?;
    let svg = crate::plots::fig9_svg(&groups).map_err(|message| CliError::Plot {
        path: svg_path.clone(),
        message,
    })?;
    write_atomic(&svg_path, svg.as_bytes())?;

    if args.json {
        return print_json(
            out,
            &json!({"groups": groups, "runs": records, "csv": csv_path, "svg": svg_path}),
        );
    }
    line(
        out,
        "Paper §VI replayed: peak impact force, mean ± 95 % CI (Student t)",
    )?;
    line(
        out,
        format!(
            "{:<16} {:>4} {:>14} {:>10}",
            "scene", "runs", "peak [N]", "± CI [N]"
        ),
    )?;
    for g in &groups {
        line(
            out,
            format!(
                "{:<16} {:>4} {:>14.3} {:>10.3}",
                g.scene, g.n, g.mean_peak_force_n, g.ci95_n
            ),
        )?;
    }
    let ratio = |cl: &str, cj: &str| {
        let find = |s: &str| {
            groups
                .iter()
                .find(|g| g.scene == s)
                .map_or(f64::NAN, |g| g.mean_peak_force_n)
        };
        find(cl) / find(cj)
    };
    line(
        out,
        format!(
            "CL/CJ: aluminium {:.4}, iron {:.4}, light load {:.4} (the paper: CL slightly below CJ; clearly below with the light load)",
            ratio("cl_aluminium", "cj_aluminium"),
            ratio("cl_iron", "cj_iron"),
            ratio("cl_light_load", "cj_light_load")
        ),
    )?;
    line(
        out,
        format!(
            "Wrote {} MCAP logs, {} and {} in {}",
            records.len(),
            csv_path.display(),
            svg_path.display(),
            args.out.display()
        ),
    )?;
    line(
        out,
        "Open a log in Foxglove with the layout written beside it (NAME.layout.json beside \
         NAME.mcap: the plots over its contact; see docs/foxglove.md).",
    )
}

/// The runs: each Fig. 9a scene `repeats` times with jittered release angles (the same angles
/// for CJ and CL, as on the physical rig), then the two light-load scenes once.
fn plan(args: &ExperimentArgs, materials: &Materials) -> Result<Vec<Job>, CliError> {
    let mut rng = StdRng::seed_from_u64(args.seed);
    let jitter = Normal::new(0.0, args.jitter_deg).map_err(|_| CliError::InvalidArgument {
        arg: "--jitter-deg".into(),
        value: args.jitter_deg.to_string(),
        allowed: "a finite standard deviation >= 0".into(),
    })?;
    let offsets: Vec<f64> = (0..args.repeats).map(|_| jitter.sample(&mut rng)).collect();
    let mut jobs = Vec::new();
    for (names, repeats) in [(&FIG9A_SCENES[..], args.repeats), (&FIG9B_SCENES[..], 1)] {
        for name in names {
            let (text, origin) = scene_text(name, args.scenes.as_ref())?;
            let scene = Scene::from_toml_str(&text, materials)?;
            let base = match scene.file.operator.start {
                Start::Release { release_angle_deg } => release_angle_deg,
                other => {
                    return Err(CliError::InvalidArgument {
                        arg: "--scenes".into(),
                        value: format!("{origin}: {other:?}"),
                        allowed: "experiment scenes start from a release".into(),
                    });
                }
            };
            for (repeat, offset) in offsets.iter().take(repeats).enumerate() {
                let offset = if repeats == 1 { 0.0 } else { *offset };
                jobs.push(Job {
                    scene: name.to_string(),
                    repeat,
                    angle_deg: base + offset,
                    text: text.clone(),
                });
            }
        }
    }
    Ok(jobs)
}

fn run_job(
    job: &Job,
    materials: &Materials,
    dir: &Path,
    interrupt: &Interrupt,
) -> Result<RunRecord, CliError> {
    let mut scene = Scene::from_toml_str(&job.text, materials)?;
    scene.file.operator.start = Start::Release {
        release_angle_deg: job.angle_deg,
    };
    let scene = Scene::from_file(scene.file, materials)?;
    let path = dir.join(format!("{}_{}.mcap", job.scene, job.repeat));
    let target = LogTarget {
        path: &path,
        force: true,
        scene_text: &job.text,
        interrupt: interrupt.0.clone(),
        rates: LogRates::DECIMATED,
        deformation_scale: crate::mcap_log::DEFAULT_DEFORMATION_SCALE,
    };
    let summary = run_logged(
        Simulation::new(&scene, RunOptions::default())?,
        &scene,
        &target,
    )?;
    Ok(RunRecord {
        scene: job.scene.clone(),
        repeat: job.repeat,
        release_angle_deg: job.angle_deg,
        peak_force_n: summary.peak_force_n,
        impact_velocity_mps: summary.impact_velocity_mps,
        contact_duration_s: summary.contact_duration_s,
        max_indentation_m: summary.max_indentation_m,
        mcap: path,
    })
}

fn csv(records: &[RunRecord]) -> String {
    let mut text = String::from(
        "scene,repeat,release_angle_deg,peak_force_n,impact_velocity_mps,contact_duration_s,max_indentation_m,mcap\n",
    );
    for r in records {
        let _ = writeln!(
            text,
            "{},{},{:.6},{:.9e},{:.9e},{},{:.9e},{}",
            r.scene,
            r.repeat,
            r.release_angle_deg,
            r.peak_force_n,
            r.impact_velocity_mps,
            r.contact_duration_s
                .map_or(String::new(), |d| format!("{d:.9e}")),
            r.max_indentation_m,
            r.mcap.display()
        );
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn confidence_interval_of_a_known_sample() {
        // 1..5: mean 3, s = √2.5, t(0.975, 4) = 2.776 (tables) → 2.776 √2.5/√5 = 1.96293.
        let (mean, ci) = mean_ci95(&[1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(mean, 3.0);
        assert!((ci - 2.776 * (2.5f64 / 5.0).sqrt()).abs() < 1e-12);
        // The large-sample limit is the normal quantile 1.95996.
        assert!((t_quantile_975(100_000) - 1.959964).abs() < 1e-4);
        assert!(
            t_quantile_975(31) > t_quantile_975(100) && t_quantile_975(30) > t_quantile_975(31)
        );
        assert_eq!(mean_ci95(&[7.0]), (7.0, 0.0));
    }
}
