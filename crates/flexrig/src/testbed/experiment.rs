//! The paper's §VI experiment replayed (Fig. 9): CJ and CL against the aluminium (398 g) and the
//! iron (4008 g) operator, each repeated with a release-angle jitter drawn from a seeded RNG and
//! reported as mean and 95 % confidence interval (Fig. 9a); and the light-load case
//! m_e = 0.1 kg (Fig. 9b, the paper's ADAMS study, here the FE beam). Every run writes an MCAP
//! log; the runs go in parallel across cores (rayon). [`plan`] lays the runs out, [`run`] runs
//! them and writes the table and the figure, the statistics ([`group_stats`], [`ratio_stats`])
//! are plain functions of the records.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexrig_contact::Materials;
use flexrig_rig::overrides::Override;
use flexrig_rig::{RunOptions, Scene, Simulation, scene::Start};
use rand::SeedableRng;
use rand::rngs::StdRng;
use rand_distr::{Distribution, Normal};
use rayon::prelude::*;
use serde::Serialize;

use crate::Error;
use crate::log::file::{LogTarget, run_logged};
use crate::log::mcap::LogRates;
use crate::plots::{FigureOptions, write_figure};
use crate::shared::cancel::CancelToken;
use crate::shared::output::{ensure_dir, write_atomic};
use crate::shared::progress::Progress;
use crate::testbed::scenes::scene_text;

/// The experiment's figure (Fig. 9): peaks by design and operator, and the CL/CJ ratio.
pub mod fig9;

/// The bundled scenes of the experiment (paper §VI, Fig. 9), relative to the assets directory.
pub const FIG9A_SCENES: [&str; 4] = ["cj_aluminium", "cl_aluminium", "cj_iron", "cl_iron"];
/// The light-load scenes (Fig. 9b).
pub const FIG9B_SCENES: [&str; 2] = ["cj_light_load", "cl_light_load"];

/// What the experiment runs and where it writes (the CLI's `flexrig experiment` flags).
#[derive(Debug, Clone, PartialEq)]
pub struct ExperimentOptions {
    /// Repeats of each Fig. 9a configuration, in [1, 1000] (the paper: 5; `--repeats`).
    pub repeats: usize,
    /// Standard deviation of the release-angle jitter \[deg\], in [0, 10] (`--jitter-deg`).
    pub jitter_deg: f64,
    /// Seed of the jitter RNG (`--seed`).
    pub seed: u64,
    /// Output directory: an MCAP log per run, fig9.svg, experiment.csv; its files are
    /// overwritten (`--out`).
    pub out: PathBuf,
    /// Directory with scene files to use instead of the bundled ones, same names (`--scenes`);
    /// it may hold any subset of them (the others are the bundled ones), at least one.
    pub scenes: Option<PathBuf>,
    /// Overrides of every scene of the experiment (`--set`); the jitter is added to the release
    /// angle that results.
    pub overrides: Vec<Override>,
    /// Printed size and formats of fig9 (`--size`, `--format`, `--dpi`).
    pub figures: FigureOptions,
}

impl ExperimentOptions {
    /// The main job's experiment on bundled defaults (the paper's 5 repeats, 0.5° jitter,
    /// seed 1) into `out`.
    pub fn defaults(out: PathBuf) -> Self {
        ExperimentOptions {
            repeats: 5,
            jitter_deg: 0.5,
            seed: 1,
            out,
            scenes: None,
            overrides: Vec::new(),
            figures: FigureOptions::two_column_svg(),
        }
    }

    /// Checks the ranges; errors name the flag.
    pub fn validate(&self) -> Result<(), Error> {
        if self.repeats == 0 || self.repeats > 1000 {
            return Err(Error::InvalidArgument {
                arg: "--repeats".into(),
                value: self.repeats.to_string(),
                allowed: "must lie in [1, 1000]".into(),
            });
        }
        if !(self.jitter_deg.is_finite() && (0.0..=10.0).contains(&self.jitter_deg)) {
            return Err(Error::InvalidArgument {
                arg: "--jitter-deg".into(),
                value: flexrig_contact::validate::display(self.jitter_deg),
                allowed: "must lie in [0, 10] degrees".into(),
            });
        }
        if let Some(dir) = &self.scenes {
            let names = FIG9A_SCENES.iter().chain(&FIG9B_SCENES);
            if !dir.is_dir() {
                return Err(Error::InvalidArgument {
                    arg: "--scenes".into(),
                    value: dir.display().to_string(),
                    allowed: "must be a directory of scene files".into(),
                });
            }
            if !names
                .clone()
                .any(|n| dir.join(format!("{n}.toml")).exists())
            {
                return Err(Error::InvalidArgument {
                    arg: "--scenes".into(),
                    value: dir.display().to_string(),
                    allowed: format!(
                        "holds none of the experiment's scene files; give a directory with any \
                         of {}",
                        names
                            .map(|n| format!("{n}.toml"))
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                });
            }
        }
        self.figures.validate()
    }
}

/// What a run of the experiment ran with (read from the scene after the overrides), for the
/// labels of its table and figure.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunInputs {
    /// The robot's design as run: `cj` or `cl`.
    pub design: String,
    /// The operator block's material as run (e.g. `skinned_aluminium`).
    pub block_material: String,
    /// The operator block's mass m_h as run \[kg\].
    pub block_mass_kg: f64,
    /// The payload m_e as run \[kg\].
    pub payload_kg: f64,
}

impl RunInputs {
    /// The inputs of `scene` (overrides applied).
    pub fn of(scene: &Scene) -> Self {
        RunInputs {
            design: design_key(scene.file.robot.design).into(),
            block_material: scene.file.operator.block_material.clone(),
            block_mass_kg: scene.block_mass_kg,
            payload_kg: scene.file.robot.payload_kg,
        }
    }
}

/// `cj` or `cl`.
pub fn design_key(design: flexrig_rig::scene::Design) -> &'static str {
    match design {
        flexrig_rig::scene::Design::Cj => "cj",
        flexrig_rig::scene::Design::Cl => "cl",
    }
}

/// One run of the experiment.
#[derive(Debug, Clone, Serialize)]
pub struct RunRecord {
    /// Scene name (of the scene file; what ran is in `inputs`).
    pub scene: String,
    /// What the run ran with.
    #[serde(flatten)]
    pub inputs: RunInputs,
    /// Repeat index.
    pub repeat: usize,
    /// Release angle used \[deg\].
    pub release_angle_deg: f64,
    /// Peak contact force \[N\].
    pub peak_force_n: f64,
    /// Time of the peak, from the release \[s\] (the log's time).
    pub time_of_peak_s: f64,
    /// Impact speed [m/s].
    pub impact_velocity_mps: f64,
    /// Contact duration \[s\] (absent from the JSON for a run stopped before separation, as in
    /// `flexrig run --json`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_duration_s: Option<f64>,
    /// Largest indentation \[m\].
    pub max_indentation_m: f64,
    /// The MCAP log.
    pub mcap: PathBuf,
    /// Severity of the run ([`crate::shared::severity`]; absent when the run took fewer than two
    /// samples).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub severity: Option<crate::shared::severity::Severity>,
}

/// Mean and 95 % confidence interval of one configuration.
#[derive(Debug, Clone, Serialize)]
pub struct GroupStats {
    /// Scene name (of the scene file; what ran is in `inputs`).
    pub scene: String,
    /// What the runs ran with (those of the first run: the repeats differ only in the release
    /// angle).
    #[serde(flatten)]
    pub inputs: RunInputs,
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
/// One planned run: a scene (its text, overrides applied) and the release angle to use.
#[derive(Debug, Clone)]
pub struct Job {
    /// Scene name.
    pub scene: String,
    /// Repeat index.
    pub repeat: usize,
    /// Release angle \[deg\].
    pub angle_deg: f64,
    /// The scene's text as run.
    pub text: String,
}

/// What [`run`] produced: the statistics, every run, and the files written.
#[derive(Debug, Clone, Serialize)]
pub struct ExperimentResult {
    /// Mean peak force per scene.
    pub groups: Vec<GroupStats>,
    /// Paired CL/CJ ratios per case.
    pub ratios: Vec<RatioStats>,
    /// Every run.
    pub runs: Vec<RunRecord>,
    /// experiment.csv.
    pub csv: PathBuf,
    /// fig9 in the first format asked for (fig9.svg by default).
    pub svg: PathBuf,
    /// fig9 in every format asked for.
    pub figures: Vec<PathBuf>,
    /// What to read the table with ([`notes`]): a scene that ran as the other design, and
    /// whether the paper's finding applies to these runs.
    pub notes: Vec<String>,
}

/// Runs the experiment: the runs of [`plan`] in parallel (each writes its MCAP log into
/// `options.out`; `progress` hears of each), then experiment.csv and fig9.svg. Stops when
/// `cancel` is set.
pub fn run(
    options: &ExperimentOptions,
    cancel: &CancelToken,
    progress: &dyn Progress,
) -> Result<ExperimentResult, Error> {
    options.validate()?;
    let materials = Materials::bundled()?;
    let jobs = plan(options, &materials)?;
    ensure_dir(&options.out)?;
    progress.start(jobs.len());
    let records = jobs
        .par_iter()
        .map(|job| {
            let r = run_job(job, &materials, &options.out, cancel);
            progress.advance();
            r
        })
        .collect::<Result<Vec<RunRecord>, Error>>();
    progress.finish();
    let records = records?;
    let groups = group_stats(&records);
    let ratios = ratio_stats(&records);
    let csv_path = options.out.join("experiment.csv");
    write_atomic(&csv_path, csv(&records, &ratios).as_bytes())?;
    let jitter = fig9::Jitter {
        sd_deg: options.jitter_deg,
        seed: options.seed,
    };
    let svg = fig9::fig9_svg(&groups, &ratios, jitter, options.figures.width_pt()).map_err(
        |message| Error::Plot {
            path: options.out.join("fig9.svg"),
            message,
        },
    )?;
    let figures = write_figure(&options.out, "fig9", &svg, &options.figures)?;
    let notes = notes(&groups);
    Ok(ExperimentResult {
        notes,
        groups,
        ratios,
        runs: records,
        csv: csv_path,
        svg: figures[0].clone(),
        figures,
    })
}

/// Mean peak force and its 95 % CI of every scene of the experiment that was run.
pub fn group_stats(records: &[RunRecord]) -> Vec<GroupStats> {
    FIG9A_SCENES
        .iter()
        .chain(FIG9B_SCENES.iter())
        .filter_map(|name| {
            let runs: Vec<&RunRecord> = records.iter().filter(|r| r.scene == *name).collect();
            let peaks: Vec<f64> = runs.iter().map(|r| r.peak_force_n).collect();
            let first = runs.first()?;
            let (mean, ci) = mean_ci95(&peaks);
            Some(GroupStats {
                scene: name.to_string(),
                inputs: first.inputs.clone(),
                n: peaks.len(),
                mean_peak_force_n: mean,
                ci95_n: ci,
            })
        })
        .collect()
}

/// The notes to the experiment's table: one for each scene whose file name says one design and
/// whose run (after the overrides) was the other ([`design_notes`]), then the paper's finding
/// or why it does not apply ([`paper_comparison`]).
pub fn notes(groups: &[GroupStats]) -> Vec<String> {
    let mut notes = design_notes(groups);
    notes.push(paper_comparison(groups));
    notes
}

/// A note for each scene whose file name says one design (`cj_…`, `cl_…`) and whose run (after
/// `--set`) was the other.
pub fn design_notes(groups: &[GroupStats]) -> Vec<String> {
    groups
        .iter()
        .filter(|g| {
            let named = &g.scene[..2.min(g.scene.len())];
            (named == "cj" || named == "cl") && named != g.inputs.design
        })
        .map(|g| {
            format!(
                "Note: scene file {} ran as {} (the overrides set robot.design).",
                g.scene,
                g.inputs.design.to_uppercase()
            )
        })
        .collect()
}

/// The payload of the paper's runs of `scene` \[kg\]: 100 g for the light load (Fig. 9b), the
/// test bed's 412 g otherwise (Fig. 9a).
fn paper_payload_kg(scene: &str) -> f64 {
    if scene.ends_with("light_load") {
        0.1
    } else {
        0.412
    }
}

/// The paper's finding for comparison, only when the runs had the paper's designs and payloads
/// (CJ and CL, 412 g on the test bed, 100 g light load); otherwise why it does not apply.
pub fn paper_comparison(groups: &[GroupStats]) -> String {
    let as_paper = groups.iter().all(|g| {
        g.scene.starts_with(&g.inputs.design)
            && (g.inputs.payload_kg - paper_payload_kg(&g.scene)).abs() < 1e-9
    });
    if as_paper {
        "The paper: CL slightly below CJ with the 412 g payload, clearly below with the light load."
            .into()
    } else {
        "The paper's comparison (CJ vs CL, 412 g payload, 100 g light load) does not apply: \
         these runs changed the design or the payload."
            .into()
    }
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

/// The runs: each Fig. 9a scene `repeats` times with jittered release angles (the same angles
/// for CJ and CL, as on the physical rig), then the two light-load scenes once.
pub fn plan(options: &ExperimentOptions, materials: &Materials) -> Result<Vec<Job>, Error> {
    let mut rng = StdRng::seed_from_u64(options.seed);
    let jitter = Normal::new(0.0, options.jitter_deg).map_err(|_| Error::InvalidArgument {
        arg: "--jitter-deg".into(),
        value: flexrig_contact::validate::display(options.jitter_deg),
        allowed: "a finite standard deviation >= 0".into(),
    })?;
    let offsets: Vec<f64> = (0..options.repeats)
        .map(|_| jitter.sample(&mut rng))
        .collect();
    check_compared_fields(&options.overrides)?;
    let mut jobs = Vec::new();
    for (names, repeats) in [(&FIG9A_SCENES[..], options.repeats), (&FIG9B_SCENES[..], 1)] {
        for name in names {
            let (original, origin) = scene_text(name, options.scenes.as_deref())?;
            // validated from the scene's own text, so an error names the override (or the
            // file's line), never a line of the text the overrides produce
            let scene =
                flexrig_rig::scene_with_overrides(&original, &options.overrides, materials)?;
            let text = flexrig_rig::overrides::apply(&original, &options.overrides)?;
            let base = match scene.file.operator.start {
                Start::Release { release_angle_deg } => release_angle_deg,
                Start::Contact { .. } | Start::Moving { .. } => {
                    return Err(Error::InvalidArgument {
                        arg: "--scenes".into(),
                        value: format!("{origin}: operator.start.from is not \"release\""),
                        allowed: "experiment scenes start from a release (the repeats jitter \
                                  the release angle)"
                            .into(),
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

/// The fields the experiment compares (CJ against CL, the aluminium against the iron operator)
/// or names its scenes by: an override of one would make every pair compare a thing with
/// itself while the table and the figure still name two.
const COMPARED_FIELDS: [&str; 3] = ["robot.design", "operator.block_material", "name"];

/// Refuses an override of a compared field (or of a table holding one), naming it.
fn check_compared_fields(overrides: &[Override]) -> Result<(), Error> {
    for o in overrides {
        let hit = COMPARED_FIELDS.iter().find(|f| {
            **f == o.path
                || f.strip_prefix(o.path.as_str())
                    .is_some_and(|rest| rest.starts_with('.'))
        });
        if let Some(field) = hit {
            return Err(Error::InvalidArgument {
                arg: format!("--set {}", o.path),
                value: o.value.to_string(),
                allowed: format!(
                    "{field} is what the experiment compares (CJ against CL, the aluminium \
                     against the iron operator): it cannot be set for every scene; use flexrig \
                     run or flexrig sweep to vary it"
                ),
            });
        }
    }
    Ok(())
}

fn run_job(
    job: &Job,
    materials: &Materials,
    dir: &Path,
    cancel: &CancelToken,
) -> Result<RunRecord, Error> {
    let mut scene = Scene::from_toml_str(&job.text, materials)?;
    scene.file.operator.start = Start::Release {
        release_angle_deg: job.angle_deg,
    };
    let scene = Scene::from_file(scene.file, materials)?;
    let inputs = RunInputs::of(&scene);
    let path = dir.join(format!("{}_{}.mcap", job.scene, job.repeat));
    let target = LogTarget {
        path: &path,
        force: true,
        scene_text: &job.text,
        cancel: cancel.clone(),
        rates: LogRates::DECIMATED,
        deformation_scale: crate::log::mcap::DEFAULT_DEFORMATION_SCALE,
    };
    let summary = run_logged(
        Simulation::new(&scene, RunOptions::default())?.with_lean_samples(),
        &scene,
        &target,
    )?;
    Ok(RunRecord {
        scene: job.scene.clone(),
        inputs,
        repeat: job.repeat,
        release_angle_deg: job.angle_deg,
        peak_force_n: summary.peak_force_n,
        time_of_peak_s: summary.time_of_peak_s,
        impact_velocity_mps: summary.impact_velocity_mps,
        contact_duration_s: summary.contact_duration_s,
        max_indentation_m: summary.max_indentation_m,
        mcap: path,
        severity: summary.severity,
    })
}

/// One row per run; the CL rows also carry the paired CL/CJ ratio of their repeat and their
/// case's mean ratio with its 95 % CI half-width (empty with one pair), then the severity
/// columns ([`crate::shared::severity::SEVERITY_COLUMNS`]).
pub fn csv(records: &[RunRecord], ratios: &[RatioStats]) -> String {
    let mut text = String::from(
        "scene,design,block_material,block_mass_kg,payload_kg,repeat,release_angle_deg,peak_force_n,time_of_peak_s,impact_velocity_mps,contact_duration_s,max_indentation_m,mcap,cl_over_cj,cl_over_cj_mean,cl_over_cj_ci95",
    );
    for column in crate::shared::severity::SEVERITY_COLUMNS {
        text.push(',');
        text.push_str(column);
    }
    text.push('\n');
    let optional = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:.9e}"));
    for r in records {
        let (pair, stats) = pair_columns(records, ratios, r);
        let _ = writeln!(
            text,
            "{},{},{},{},{},{},{:.6},{:.9e},{:.9e},{:.9e},{},{:.9e},{},{},{},{},{}",
            r.scene,
            r.inputs.design,
            r.inputs.block_material,
            r.inputs.block_mass_kg,
            r.inputs.payload_kg,
            r.repeat,
            r.release_angle_deg,
            r.peak_force_n,
            r.time_of_peak_s,
            r.impact_velocity_mps,
            optional(r.contact_duration_s),
            r.max_indentation_m,
            r.mcap.display(),
            optional(pair),
            optional(stats.map(|s| s.mean_cl_over_cj)),
            optional(stats.and_then(|s| s.ci95)),
            crate::shared::severity::severity_values(r.severity.as_ref())
                .map(optional)
                .join(","),
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
            inputs: RunInputs {
                design: scene[..2].into(),
                block_material: "skinned_aluminium".into(),
                block_mass_kg: 0.398,
                payload_kg: 0.412,
            },
            repeat,
            release_angle_deg: 30.0 + repeat as f64,
            peak_force_n: peak,
            time_of_peak_s: 0.28,
            impact_velocity_mps: 1.0,
            contact_duration_s: None,
            max_indentation_m: 1e-3,
            mcap: PathBuf::from("x.mcap"),
            severity: None,
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
        let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
        let column = |row: &str, name: &str| {
            let i = header.iter().position(|h| *h == name).unwrap();
            row.split(',').nth(i).unwrap().to_string()
        };
        let cl_row = text
            .lines()
            .find(|l| l.starts_with("cl_light_load"))
            .unwrap();
        assert_eq!(column(cl_row, "cl_over_cj"), "9.300000000e-1", "{cl_row}");
        assert_eq!(column(cl_row, "cl_over_cj_mean"), "9.300000000e-1");
        assert_eq!(column(cl_row, "cl_over_cj_ci95"), "", "{cl_row}");
        let cj_row = text
            .lines()
            .find(|l| l.starts_with("cj_light_load"))
            .unwrap();
        for name in ["cl_over_cj", "cl_over_cj_mean", "cl_over_cj_ci95"] {
            assert_eq!(column(cj_row, name), "", "{cj_row}");
        }
    }

    fn group(scene: &str, design: &str, payload_kg: f64) -> GroupStats {
        GroupStats {
            scene: scene.into(),
            inputs: RunInputs {
                design: design.into(),
                block_material: "skinned_aluminium".into(),
                block_mass_kg: 0.398,
                payload_kg,
            },
            n: 5,
            mean_peak_force_n: 180.0,
            ci95_n: Some(1.0),
        }
    }

    #[test]
    fn the_notes_name_a_scene_run_as_the_other_design_and_when_the_paper_applies() {
        let paper = [
            group("cj_aluminium", "cj", 0.412),
            group("cl_aluminium", "cl", 0.412),
            group("cj_light_load", "cj", 0.1),
            group("cl_light_load", "cl", 0.1),
        ];
        let n = notes(&paper);
        assert_eq!(n.len(), 1, "{n:?}");
        assert!(n[0].starts_with("The paper: CL slightly below CJ"), "{n:?}");
        // the CL file run as CJ: a note naming it, and the paper does not apply
        let mut swapped = paper.clone();
        swapped[1].inputs.design = "cj".into();
        let n = notes(&swapped);
        assert_eq!(n.len(), 2, "{n:?}");
        assert_eq!(
            n[0],
            "Note: scene file cl_aluminium ran as CJ (the overrides set robot.design)."
        );
        assert!(n[1].contains("does not apply"), "{n:?}");
        // another payload: no design note, the paper does not apply
        let mut heavier = paper.clone();
        heavier[0].inputs.payload_kg = 0.2;
        let n = notes(&heavier);
        assert_eq!(n.len(), 1);
        assert!(n[0].contains("does not apply"), "{n:?}");
    }

    #[test]
    fn mean_and_interval_are_written_to_the_intervals_digits() {
        assert_eq!(mean_pm_ci(0.990008, Some(3.3e-7)), "0.990008 ± 3.3e-7");
        assert_eq!(mean_pm_ci(0.98249, Some(0.0123)), "0.982 ± 0.012");
        assert_eq!(mean_pm_ci(0.93566, None), "0.9357");
    }
}
