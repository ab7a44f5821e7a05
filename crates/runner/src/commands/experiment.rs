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
    /// Standard deviation of the release-angle jitter (degrees).
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
    /// Override a scene field in every scene of the experiment, as in `flexrig run --set`
    /// (dotted path, e.g. robot.payload_kg=0.2; repeatable). The jitter is added to the
    /// release angle that results.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
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
    /// Half-width of the 95 % confidence interval of the mean \[N\] (Student t); none with one
    /// run (absent from the JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci95_n: Option<f64>,
}

/// The CJ/CL pairs of the experiment: case name, CJ scene, CL scene.
pub const PAIRS: [(&str, &str, &str); 3] = [
    ("aluminium", "cj_aluminium", "cl_aluminium"),
    ("iron", "cj_iron", "cl_iron"),
    ("light_load", "cj_light_load", "cl_light_load"),
];

/// CL/CJ peak-force ratio of one case, paired by repeat (the same release angle for CJ and CL):
/// mean of the per-repeat ratios and its 95 % confidence interval.
#[derive(Debug, Clone, Serialize)]
pub struct RatioStats {
    /// Case: `aluminium`, `iron` or `light_load`.
    pub case: String,
    /// Pairs (repeats run for both CJ and CL).
    pub pairs: usize,
    /// Mean of the per-repeat ratios CL/CJ.
    pub mean_cl_over_cj: f64,
    /// Half-width of the 95 % confidence interval of the mean ratio (Student t); none with one
    /// pair (absent from the JSON).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ci95: Option<f64>,
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

/// Mean and 95 % CI half-width (Student t) of `values`; no interval from fewer than two values.
pub fn mean_ci95(values: &[f64]) -> (f64, Option<f64>) {
    let n = values.len();
    let mean = values.iter().sum::<f64>() / n as f64;
    if n < 2 {
        return (mean, None);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    (mean, Some(t_quantile_975(n - 1) * (var / n as f64).sqrt()))
}

/// Per-repeat CL/CJ ratios of `case` (see [`PAIRS`]): `(repeat, ratio)` for every repeat run
/// with both designs, in repeat order.
pub fn paired_ratios(records: &[RunRecord], cj: &str, cl: &str) -> Vec<(usize, f64)> {
    let mut ratios: Vec<(usize, f64)> = records
        .iter()
        .filter(|r| r.scene == cl)
        .filter_map(|r_cl| {
            records
                .iter()
                .find(|r| r.scene == cj && r.repeat == r_cl.repeat)
                .map(|r_cj| (r_cl.repeat, r_cl.peak_force_n / r_cj.peak_force_n))
        })
        .collect();
    ratios.sort_by_key(|(repeat, _)| *repeat);
    ratios
}

/// The paired CL/CJ ratio of every case of [`PAIRS`] that was run.
pub fn ratio_stats(records: &[RunRecord]) -> Vec<RatioStats> {
    PAIRS
        .iter()
        .filter_map(|(case, cj, cl)| {
            let ratios: Vec<f64> = paired_ratios(records, cj, cl)
                .into_iter()
                .map(|(_, r)| r)
                .collect();
            if ratios.is_empty() {
                return None;
            }
            let (mean, ci) = mean_ci95(&ratios);
            Some(RatioStats {
                case: case.to_string(),
                pairs: ratios.len(),
                mean_cl_over_cj: mean,
                ci95: ci,
            })
        })
        .collect()
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

    let groups = group_stats(&records);
    let ratios = ratio_stats(&records);
    let csv_path = args.out.join("experiment.csv");
    let svg_path = args.out.join("fig9.svg");
    write_atomic(&csv_path, csv(&records, &ratios).as_bytes())?;
    let svg = crate::plots::fig9_svg(&groups, &ratios).map_err(|message| CliError::Plot {
        path: svg_path.clone(),
        message,
    })?;
    write_atomic(&svg_path, svg.as_bytes())?;

    if args.json {
        return print_json(
            out,
            &json!({"groups": groups, "ratios": ratios, "runs": records, "csv": csv_path, "svg": svg_path}),
        );
    }
    print_table(out, &groups, &ratios)?;
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

/// Mean peak force and its 95 % CI of every scene of the experiment that was run.
fn group_stats(records: &[RunRecord]) -> Vec<GroupStats> {
    FIG9A_SCENES
        .iter()
        .chain(FIG9B_SCENES.iter())
        .filter_map(|name| {
            let peaks: Vec<f64> = records
                .iter()
                .filter(|r| r.scene == *name)
                .map(|r| r.peak_force_n)
                .collect();
            if peaks.is_empty() {
                return None;
            }
            let (mean, ci) = mean_ci95(&peaks);
            Some(GroupStats {
                scene: name.to_string(),
                n: peaks.len(),
                mean_peak_force_n: mean,
                ci95_n: ci,
            })
        })
        .collect()
}

/// `mean ± ci` of a ratio: the interval to two significant digits (in e-notation when tiny), the
/// mean to the interval's last digit (3 to 6 decimals); the mean to 4 decimals without interval.
pub fn mean_pm_ci(mean: f64, ci: Option<f64>) -> String {
    let Some(ci) = ci.filter(|c| c.is_finite() && *c > 0.0) else {
        return format!("{mean:.4}");
    };
    let last = (1.0 - ci.log10().floor()).max(0.0) as usize;
    let d = last.clamp(3, 6);
    if last > 6 {
        format!("{mean:.d$} ± {ci:.1e}")
    } else {
        format!("{mean:.d$} ± {ci:.last$}")
    }
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
) -> Result<(), CliError> {
    line(
        out,
        "Paper §VI replayed: peak impact force, mean ± 95 % CI (Student t; none from one run)",
    )?;
    line(
        out,
        format!(
            "{:<16} {:>4} {:>14} {:>10}",
            "scene", "runs", "peak [N]", "CI [N]"
        ),
    )?;
    for g in groups {
        line(
            out,
            format!(
                "{:<16} {:>4} {:>14.3} {:>10}",
                g.scene,
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
    line(
        out,
        "The paper: CL slightly below CJ with the 412 g payload, clearly below with the light load.",
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
    let overrides = args
        .set
        .iter()
        .map(|s| flexrig_rig::overrides::Override::parse(s))
        .collect::<Result<Vec<_>, _>>()?;
    let mut jobs = Vec::new();
    for (names, repeats) in [(&FIG9A_SCENES[..], args.repeats), (&FIG9B_SCENES[..], 1)] {
        for name in names {
            let (text, origin) = scene_text(name, args.scenes.as_ref())?;
            let text = flexrig_rig::overrides::apply(&text, &overrides)?;
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

/// One row per run; the CL rows also carry the paired CL/CJ ratio of their repeat and their
/// case's mean ratio with its 95 % CI half-width (empty with one pair).
fn csv(records: &[RunRecord], ratios: &[RatioStats]) -> String {
    let mut text = String::from(
        "scene,repeat,release_angle_deg,peak_force_n,impact_velocity_mps,contact_duration_s,max_indentation_m,mcap,cl_over_cj,cl_over_cj_mean,cl_over_cj_ci95\n",
    );
    let optional = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.9e}"));
    for r in records {
        let (pair, stats) = pair_columns(records, ratios, r);
        let _ = writeln!(
            text,
            "{},{},{:.6},{:.9e},{:.9e},{},{:.9e},{},{},{},{}",
            r.scene,
            r.repeat,
            r.release_angle_deg,
            r.peak_force_n,
            r.impact_velocity_mps,
            optional(r.contact_duration_s),
            r.max_indentation_m,
            r.mcap.display(),
            optional(pair),
            optional(stats.map(|s| s.mean_cl_over_cj)),
            optional(stats.and_then(|s| s.ci95)),
        );
    }
    text
}

/// For a CL run: its repeat's paired CL/CJ ratio and its case's statistics.
fn pair_columns<'a>(
    records: &[RunRecord],
    ratios: &'a [RatioStats],
    run: &RunRecord,
) -> (Option<f64>, Option<&'a RatioStats>) {
    let Some((case, cj, cl)) = PAIRS.iter().find(|(_, _, cl)| *cl == run.scene) else {
        return (None, None);
    };
    let pair = paired_ratios(records, cj, cl)
        .into_iter()
        .find(|(repeat, _)| *repeat == run.repeat)
        .map(|(_, ratio)| ratio);
    (pair, ratios.iter().find(|r| r.case == *case))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn confidence_interval_of_a_known_sample() {
        // 1..5: mean 3, s = √2.5, t(0.975, 4) = 2.776 (tables) → 2.776 √2.5/√5 = 1.96293.
        let (mean, ci) = mean_ci95(&[1.0, 2.0, 3.0, 4.0, 5.0]);
        assert_eq!(mean, 3.0);
        assert!((ci.unwrap() - 2.776 * (2.5f64 / 5.0).sqrt()).abs() < 1e-12);
        // The large-sample limit is the normal quantile 1.95996.
        assert!((t_quantile_975(100_000) - 1.959964).abs() < 1e-4);
        assert!(
            t_quantile_975(31) > t_quantile_975(100) && t_quantile_975(30) > t_quantile_975(31)
        );
        // One value: a mean but no interval (was 0.0).
        assert_eq!(mean_ci95(&[7.0]), (7.0, None));
    }

    fn record(scene: &str, repeat: usize, peak: f64) -> RunRecord {
        RunRecord {
            scene: scene.into(),
            repeat,
            release_angle_deg: 30.0 + repeat as f64,
            peak_force_n: peak,
            impact_velocity_mps: 1.0,
            contact_duration_s: None,
            max_indentation_m: 1e-3,
            mcap: PathBuf::from("x.mcap"),
        }
    }

    #[test]
    fn paired_ratio_and_its_interval_match_a_hand_computation() {
        // CJ 100, 110, 120, 130; CL 99, 108, 119, 130 → ratios 0.99, 0.981818…, 0.991666…, 1.
        let cj = [100.0, 110.0, 120.0, 130.0];
        let cl = [99.0, 108.0, 119.0, 130.0];
        let mut records: Vec<RunRecord> = Vec::new();
        // Out of order, as the parallel runs may finish.
        for i in [2, 0, 3, 1] {
            records.push(record("cl_iron", i, cl[i]));
            records.push(record("cj_iron", i, cj[i]));
        }
        let stats = ratio_stats(&records);
        assert_eq!(stats.len(), 1);
        let r = &stats[0];
        assert_eq!((r.case.as_str(), r.pairs), ("iron", 4));
        // Independently: mean and sample standard deviation written out, t(0.975, 3) = 3.182.
        let ratios = [0.99, 108.0 / 110.0, 119.0 / 120.0, 1.0];
        let mean = (ratios[0] + ratios[1] + ratios[2] + ratios[3]) / 4.0;
        let ss: f64 = ratios.iter().map(|x| (x - mean) * (x - mean)).sum();
        let half = 3.182 * (ss / 3.0).sqrt() / 2.0;
        assert!((r.mean_cl_over_cj - mean).abs() < 1e-15);
        assert!(
            (r.ci95.unwrap() - half).abs() < 1e-15,
            "{:?} vs {half}",
            r.ci95
        );
        // Pairs are by repeat: a pair's ratio is its own CL over its own CJ.
        let pairs = paired_ratios(&records, "cj_iron", "cl_iron");
        assert_eq!(pairs.iter().map(|p| p.0).collect::<Vec<_>>(), [0, 1, 2, 3]);
        assert_eq!(pairs[1].1, 108.0 / 110.0);
    }

    #[test]
    fn one_pair_gives_a_ratio_without_interval() {
        let records = [
            record("cj_light_load", 0, 100.0),
            record("cl_light_load", 0, 93.0),
        ];
        let stats = ratio_stats(&records);
        assert_eq!(stats.len(), 1);
        assert_eq!(stats[0].mean_cl_over_cj, 0.93);
        assert_eq!(stats[0].ci95, None);
        let json = serde_json::to_value(&stats[0]).unwrap();
        assert!(json.get("ci95").is_none(), "{json}");
        let groups = group_stats(&records);
        let json = serde_json::to_value(&groups).unwrap().to_string();
        assert!(!json.contains("ci95_n") && !json.contains("null"), "{json}");
        // experiment.csv: the CL row has its ratio and mean; the interval field is empty.
        let text = csv(&records, &stats);
        let cl_row = text
            .lines()
            .find(|l| l.starts_with("cl_light_load"))
            .unwrap();
        assert!(
            cl_row.ends_with(",9.300000000e-1,9.300000000e-1,"),
            "{cl_row}"
        );
        let cj_row = text
            .lines()
            .find(|l| l.starts_with("cj_light_load"))
            .unwrap();
        assert!(cj_row.ends_with(",,,"), "{cj_row}");
    }

    #[test]
    fn mean_and_interval_are_written_to_the_intervals_digits() {
        assert_eq!(mean_pm_ci(0.990008, Some(3.3e-7)), "0.990008 ± 3.3e-7");
        assert_eq!(mean_pm_ci(0.98249, Some(0.0123)), "0.982 ± 0.012");
        assert_eq!(mean_pm_ci(0.93566, None), "0.9357");
    }
}
