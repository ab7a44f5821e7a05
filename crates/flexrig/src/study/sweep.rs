//! A sweep: one base scene, its points (see [`super::spec`]), every point run in parallel, one
//! tidy table with a row per run — the varied values, the status (`ok`, or `error` with its
//! text: a failed run never stops the sweep) and every summary quantity.
//!
//! Deterministic (rows in point order, each run independent of the others), resumable (rows
//! already in the table or in its `.partial` journal are not run again), and divisible: shard
//! i of N runs the points with index ≡ i (mod N), and [`merge`] joins the shards' tables.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use flexrig_contact::Materials;
use flexrig_rig::{Interruptible, Override, RigError, RunOptions, RunSummary, Simulation};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::spec::{Dimension, point, point_count};
use crate::Error;
use crate::shared::cancel::CancelToken;
use crate::shared::output::write_atomic;

/// The summary quantities of a row, in column order: the run summary's, the severity's
/// ([`crate::shared::severity::SEVERITY_COLUMNS`]), the link's ([`crate::testbed::link::COLUMNS`]), then the
/// driven robot's ([`DRIVEN_COLUMNS`]).
pub const SUMMARY_COLUMNS: [&str; 33] = [
    "peak_force_n",
    "time_of_peak_s",
    "impact_velocity_mps",
    "separation_velocity_mps",
    "onset_time_s",
    "contact_duration_s",
    "max_indentation_m",
    "impulse_n_s",
    "contacts",
    "steps",
    "contact_steps",
    "contact_step_s",
    "energy_initial_j",
    "energy_final_j",
    "duration_s",
    "severity_peak_force_n",
    "peak_pressure_hertz_pa",
    "peak_pressure_thin_layer_pa",
    "energy_transferred_j",
    "contact_work_j",
    "peak_accel_mps2",
    "peak_accel_g",
    "hic15",
    "hic36",
    // the link quantities (crate::testbed::link::COLUMNS)
    "m_r_kg",
    "ei_n_m2",
    "k_delta_n_per_m",
    "k_theta_r_nm_per_rad",
    "m_e_over_m_r",
    // the driven robot's (scenes with [drive]; empty for the test bed): DRIVEN_COLUMNS
    "pre_impact_deflection_m",
    "peak_motor_torque_nm",
    "joint_speed_at_contact_rad_s",
    "commanded_tip_speed_mps",
];

/// The driven robot's columns (a scene with `[drive]`; empty for the test bed), the last block
/// of [`SUMMARY_COLUMNS`]: the tip's deflection from the hub's line at the onset \[m\] (the
/// drive's acceleration pre-bends a CL link), the largest motor-shaft torque during the
/// contact [N·m], the joint's speed at the onset [rad/s] and the commanded tip speed there
/// [m/s] (absent under an open-loop torque).
pub const DRIVEN_COLUMNS: [&str; 4] = [
    "pre_impact_deflection_m",
    "peak_motor_torque_nm",
    "joint_speed_at_contact_rad_s",
    "commanded_tip_speed_mps",
];

/// Index of the first driven column in [`SUMMARY_COLUMNS`].
pub const DRIVEN_START: usize = SUMMARY_COLUMNS.len() - DRIVEN_COLUMNS.len();

/// Index of the first severity column ([`crate::shared::severity::SEVERITY_COLUMNS`]) in
/// [`SUMMARY_COLUMNS`].
pub const SEVERITY_START: usize = 15;

/// The columns of [`SUMMARY_COLUMNS`] that hold counts: written as whole numbers (`3`, not
/// `3e0`) in the CSV and as integers in JSON Lines.
pub const INTEGER_COLUMNS: [&str; 3] = ["contacts", "steps", "contact_steps"];

/// Where the link quantities start in [`SUMMARY_COLUMNS`].
fn link_offset() -> usize {
    SUMMARY_COLUMNS
        .iter()
        .position(|c| *c == crate::testbed::link::COLUMNS[0])
        .expect("the link columns are summary columns")
}

/// `values` with the link quantities `link` in their columns.
pub fn with_link(
    mut values: [Option<f64>; SUMMARY_COLUMNS.len()],
    link: &crate::testbed::link::LinkQuantities,
) -> [Option<f64>; SUMMARY_COLUMNS.len()] {
    let at = link_offset();
    for (i, v) in link.values().into_iter().enumerate() {
        values[at + i] = Some(v);
    }
    values
}

/// The summary quantities of a run, as [`SUMMARY_COLUMNS`] (absent values: `None`), with the
/// scene's link quantities.
pub fn summary_values(
    s: &RunSummary,
    link: &crate::testbed::link::LinkQuantities,
) -> [Option<f64>; SUMMARY_COLUMNS.len()] {
    let run = [
        Some(s.peak_force_n),
        Some(s.time_of_peak_s),
        Some(s.impact_velocity_mps),
        s.separation_velocity_mps,
        Some(s.onset_time_s),
        s.contact_duration_s,
        Some(s.max_indentation_m),
        Some(s.impulse_n_s),
        Some(s.contacts.len() as f64),
        Some(s.steps as f64),
        Some(s.contact_steps as f64),
        Some(s.contact_step_s),
        Some(s.energy_initial_j),
        Some(s.energy_final_j),
        Some(s.duration_s),
    ];
    let severity = crate::shared::severity::severity_values(s.severity.as_ref());
    let mut values = [None; SUMMARY_COLUMNS.len()];
    values[..run.len()].copy_from_slice(&run);
    values[SEVERITY_START..SEVERITY_START + severity.len()].copy_from_slice(&severity);
    // a test-bed run with a motor on the robot joint: its pre-impact deflection and the link's
    // speed at the onset (its peak torque is the run's, not the contact's: left empty)
    if let Some(d) = &s.drive {
        values[DRIVEN_START] = d.pre_impact_deflection_m;
        values[DRIVEN_START + 2] = d.link_speed_at_onset_rad_s;
    }
    with_link(values, link)
}

/// The summary quantities of a sweep's row ([`SUMMARY_COLUMNS`]): what a
/// driven run has of them (the test bed's step counts and energies are absent).
pub fn driven_values(
    s: &crate::driven::scene::DrivenSummary,
) -> [Option<f64>; SUMMARY_COLUMNS.len()] {
    let mut values = [None; SUMMARY_COLUMNS.len()];
    let run = [
        Some(s.peak_force_n),
        Some(s.time_of_peak_s),
        Some(s.impact_velocity_mps),
        Some(s.separation_velocity_mps),
        Some(s.onset_time_s),
        Some(s.contact_duration_s),
        Some(s.max_indentation_m),
        Some(s.impulse_n_s),
        Some(1.0),
        Some(s.steps as f64),
        None,
        None,
        None,
        None,
        Some(s.duration_s),
    ];
    values[..run.len()].copy_from_slice(&run);
    let severity = crate::shared::severity::severity_values(s.severity.as_ref());
    let at = SEVERITY_START;
    values[at..at + severity.len()].copy_from_slice(&severity);
    let driven = [
        Some(s.pre_impact_deflection_m),
        Some(s.peak_motor_torque_nm),
        Some(s.joint_speed_at_contact_rad_s).filter(|v| v.is_finite()),
        s.commanded_tip_speed_mps,
    ];
    let at = DRIVEN_START;
    values[at..at + driven.len()].copy_from_slice(&driven);
    values
}

/// A summary value as a CSV cell of `column`: a count as a whole number, anything else in
/// Rust's shortest exponent form (`1.25e-3`), empty when absent.
fn summary_cell(column: &str, v: Option<f64>) -> String {
    match v {
        None => String::new(),
        Some(x) if INTEGER_COLUMNS.contains(&column) => format!("{}", x as i64),
        Some(x) => format!("{x:e}"),
    }
}

/// A format error of a sweep value that looks like a list typed with spaces or semicolons gets
/// the list syntax.
fn with_list_hint(e: RigError, value: &toml::Value) -> Error {
    match (e, value) {
        (
            RigError::InvalidScene {
                field,
                value: v,
                allowed,
            },
            toml::Value::String(text),
        ) if text.contains(' ') || text.contains(';') => RigError::InvalidScene {
            field,
            value: v,
            allowed: format!(
                "{allowed} (a list of values is comma-separated, e.g. 0.1,0.2,0.5; a range \
                     10:60:11)"
            ),
        }
        .into(),
        (e, _) => e.into(),
    }
}

/// A sweep: the base scene and what varies.
#[derive(Debug, Clone)]
pub struct Sweep {
    materials: Materials,
    base_text: String,
    base: toml::Table,
    dimensions: Vec<Dimension>,
    zip: bool,
    points: usize,
    /// A driven scene (with `[drive]`): its points run the driven strike.
    driven: bool,
}

/// Where and how a sweep runs.
#[derive(Debug, Clone, Default)]
pub struct SweepOptions {
    /// Shard (i, N): run the points with index ≡ i (mod N). `None`: every point.
    pub shard: Option<(usize, usize)>,
    /// Keep an MCAP log per run in this directory (`run-<index>.mcap`, with its Foxglove layout
    /// `run-<index>.layout.json`).
    pub mcap_dir: Option<PathBuf>,
    /// Stops the sweep (runs not yet started are left for a resume).
    pub cancel: CancelToken,
}

/// The outcome of one point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepRow {
    /// Point index.
    pub index: usize,
    /// The varied values, in dimension order, as TOML text.
    pub values: Vec<String>,
    /// `ok`, or `error`.
    pub status: String,
    /// The error of a failed run (empty when ok).
    pub error: String,
    /// [`SUMMARY_COLUMNS`] of an ok run.
    pub summary: Vec<Option<f64>>,
    /// What the run's drive did that its numbers do not say, as `flexrig run` notes it (the
    /// torque limit reached, an arrival off the commanded speed; [`NOTES_SEPARATOR`] between
    /// two), empty for a run without such notes: the table's last column, `notes`.
    #[serde(default)]
    pub notes: String,
}

/// Between two notes of a row's `notes` cell.
pub const NOTES_SEPARATOR: &str = "; ";

impl Sweep {
    /// A sweep of `base_text` over `dimensions` (grid, or zipped); the base must be a valid
    /// scene file (its errors name the field).
    pub fn new(base_text: &str, dimensions: Vec<Dimension>, zip: bool) -> Result<Self, Error> {
        let materials = Materials::bundled()?;
        let driven = crate::driven::scene::is_driven_text(base_text);
        if driven {
            return Sweep::new_driven(base_text, dimensions, zip, materials);
        }
        // the base alone is checked first, so that its own errors carry their line
        flexrig_rig::Scene::from_toml_str(base_text, &materials)?;
        let base: toml::Table = toml::from_str(base_text)
            .map_err(|e| RigError::SceneSyntax(e.message().trim().to_string()))?;
        // an unknown path or a value of the wrong type is refused before anything runs (a
        // value out of its range fails its runs, which become rows with the error)
        // counted first (cheap), then each field checked once per kind of value: a number of
        // each type, every distinct string, table and array
        let points = point_count(&dimensions, zip)?;
        super::spec::check_distinct(&dimensions)?;
        for d in &dimensions {
            let mut seen_float = false;
            let mut seen_integer = false;
            let mut seen = std::collections::HashSet::new();
            for v in &d.values {
                let check = match v {
                    toml::Value::Float(_) => !std::mem::replace(&mut seen_float, true),
                    toml::Value::Integer(_) => !std::mem::replace(&mut seen_integer, true),
                    other => seen.insert(other.to_string()),
                };
                if check {
                    flexrig_rig::overrides::check_format(&base, &Override::new(&d.path, v.clone()))
                        .map_err(|e| with_list_hint(e, v))?;
                }
            }
        }
        Ok(Sweep {
            materials,
            base_text: base_text.to_string(),
            base,
            dimensions,
            zip,
            points,
            driven: false,
        })
    }

    /// A sweep of a driven scene: the base and every distinct value of each dimension on its
    /// own are checked in full (format and range) before anything runs; a combination that
    /// fails becomes a row with its error.
    fn new_driven(
        base_text: &str,
        dimensions: Vec<Dimension>,
        zip: bool,
        materials: Materials,
    ) -> Result<Self, Error> {
        use crate::driven::scene::DrivenScene;
        DrivenScene::parse(base_text)?;
        let base: toml::Table = toml::from_str(base_text)
            .map_err(|e| RigError::SceneSyntax(e.message().trim().to_string()))?;
        let points = point_count(&dimensions, zip)?;
        super::spec::check_distinct(&dimensions)?;
        for d in &dimensions {
            let mut seen = std::collections::HashSet::new();
            for v in &d.values {
                if seen.insert(v.to_string()) {
                    DrivenScene::with_overrides(base_text, &[Override::new(&d.path, v.clone())])
                        .map_err(|e| match e {
                            Error::Rig(e) => with_list_hint(e, v),
                            other => other,
                        })?;
                }
            }
        }
        Ok(Sweep {
            materials,
            base_text: base_text.to_string(),
            base,
            dimensions,
            zip,
            points,
            driven: true,
        })
    }

    /// Runs the driven scene's point (with a log in `mcap_dir` if given).
    fn run_driven(
        &self,
        index: usize,
        overrides: &[Override],
        options: &SweepOptions,
    ) -> Result<([Option<f64>; SUMMARY_COLUMNS.len()], Vec<String>), Error> {
        let scene = crate::driven::scene::DrivenScene::with_overrides(&self.base_text, overrides)?;
        let run = match &options.mcap_dir {
            None => crate::driven::scene::run(&scene, &options.cancel)?,
            Some(dir) => {
                let text = flexrig_rig::overrides::apply(&self.base_text, overrides)?;
                let path = dir.join(format!("run-{index}.mcap"));
                crate::driven::log::run_logged(
                    &scene,
                    &crate::log::file::LogTarget {
                        path: &path,
                        force: true,
                        scene_text: &text,
                        cancel: options.cancel.clone(),
                        rates: crate::log::mcap::LogRates::DECIMATED,
                        deformation_scale: crate::log::mcap::DEFAULT_DEFORMATION_SCALE,
                    },
                )?
            }
        };
        Ok((
            with_link(
                driven_values(&run.summary),
                &crate::testbed::link::of_driven(&scene.strike.link),
            ),
            run.summary.notes,
        ))
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points
    }

    /// True when the sweep has no points (never: a sweep of no dimension has one).
    pub fn is_empty(&self) -> bool {
        self.points == 0
    }

    /// The varied paths (column names).
    pub fn paths(&self) -> Vec<&str> {
        self.dimensions.iter().map(|d| d.path.as_str()).collect()
    }

    /// The overrides of point `index`.
    pub fn point(&self, index: usize) -> Vec<Override> {
        point(&self.dimensions, self.zip, index)
    }

    /// A fingerprint of the sweep (base text, dimensions, grid or zip): tables of different
    /// sweeps are never mixed by a resume or a merge.
    pub fn fingerprint(&self) -> String {
        let mut text = self.base_text.clone();
        for d in &self.dimensions {
            text.push_str(&format!("\n{}={:?}", d.path, d.values));
        }
        text.push_str(if self.zip { "\nzip" } else { "\ngrid" });
        format!("{:016x}", fnv1a(text.as_bytes()))
    }

    /// The point indices of `shard` (all without one).
    pub fn indices(&self, shard: Option<(usize, usize)>) -> Vec<usize> {
        match shard {
            Some((i, n)) => (i..self.points).step_by(n).collect(),
            None => (0..self.points).collect(),
        }
    }

    /// Runs point `index` (with a log in `mcap_dir` if given).
    pub fn run_point(&self, index: usize, options: &SweepOptions) -> SweepRow {
        let overrides = self.point(index);
        let values = overrides.iter().map(|o| o.value.to_string()).collect();
        let result = if self.driven {
            self.run_driven(index, &overrides, options)
        } else {
            self.run_overrides(index, &overrides, options)
                .map(|(s, link)| {
                    (
                        summary_values(&s, &link),
                        crate::testbed::run::drive_notes(&s),
                    )
                })
        };
        match result {
            Ok((s, notes)) => SweepRow {
                index,
                values,
                status: "ok".into(),
                error: String::new(),
                summary: s.to_vec(),
                notes: notes.join(NOTES_SEPARATOR),
            },
            Err(e) => SweepRow {
                index,
                values,
                status: if matches!(
                    e,
                    Error::Rig(RigError::Interrupted { .. })
                        | Error::Impact(flexrig_impact::ImpactError::Interrupted)
                ) {
                    "interrupted".into()
                } else {
                    "error".into()
                },
                error: e.to_string(),
                summary: vec![None; SUMMARY_COLUMNS.len()],
                notes: String::new(),
            },
        }
    }

    fn run_overrides(
        &self,
        index: usize,
        overrides: &[Override],
        options: &SweepOptions,
    ) -> Result<(RunSummary, crate::testbed::link::LinkQuantities), Error> {
        let scene = flexrig_rig::scene_from_table(&self.base, overrides, &self.materials)?;
        let link = crate::testbed::link::of_scene(&scene);
        let simulation = Simulation::new(&scene, RunOptions::default())?.with_lean_samples();
        let Some(dir) = &options.mcap_dir else {
            return Ok((
                simulation.run(&mut Interruptible(options.cancel.flag()))?,
                link,
            ));
        };
        let text = flexrig_rig::overrides::apply(&self.base_text, overrides)?;
        let path = dir.join(format!("run-{index}.mcap"));
        let target = crate::log::file::LogTarget {
            path: &path,
            force: true,
            scene_text: &text,
            cancel: options.cancel.clone(),
            rates: crate::log::mcap::LogRates::DECIMATED,
            deformation_scale: crate::log::mcap::DEFAULT_DEFORMATION_SCALE,
        };
        Ok((
            crate::log::file::run_logged(simulation, &scene, &target)?,
            link,
        ))
    }

    /// Runs the points of `indices` in parallel, calling `done` after each (e.g. a progress bar
    /// or a journal); rows in index order. Points not started when the sweep is cancelled are
    /// left out.
    pub fn run(
        &self,
        indices: &[usize],
        options: &SweepOptions,
        done: &(dyn Fn(&SweepRow) + Sync),
    ) -> Vec<SweepRow> {
        let mut rows: Vec<SweepRow> = indices
            .par_iter()
            .filter_map(|&i| {
                if options.cancel.is_cancelled() {
                    return None;
                }
                let row = self.run_point(i, options);
                done(&row);
                Some(row)
            })
            .collect();
        rows.sort_by_key(|r| r.index);
        rows
    }
}

/// 64-bit FNV-1a.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf29ce484222325u64, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x100000001b3)
    })
}

/// A CSV field: quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_string()
    }
}

/// A varied value as a CSV cell: strings without their TOML quotes.
fn value_cell(toml_text: &str) -> String {
    match flexrig_rig::overrides::parse_value(toml_text) {
        toml::Value::String(s) => s,
        _ => toml_text.to_string(),
    }
}

/// The CSV header of a sweep over `paths`.
pub fn csv_header(paths: &[&str]) -> String {
    let mut columns = vec!["index".to_string()];
    columns.extend(paths.iter().map(|p| csv_field(p)));
    columns.extend(["status".to_string(), "error".to_string()]);
    columns.extend(SUMMARY_COLUMNS.iter().map(|c| c.to_string()));
    columns.push("notes".into());
    columns.join(",")
}

/// One CSV line of `row`.
pub fn csv_line(row: &SweepRow) -> String {
    let mut cells = vec![row.index.to_string()];
    cells.extend(row.values.iter().map(|v| csv_field(&value_cell(v))));
    cells.push(row.status.clone());
    cells.push(csv_field(&row.error));
    cells.extend(
        SUMMARY_COLUMNS
            .iter()
            .zip(&row.summary)
            .map(|(column, v)| summary_cell(column, *v)),
    );
    cells.push(csv_field(&row.notes));
    cells.join(",")
}

/// One JSON Lines object of `row` (varied values under their paths).
pub fn json_line(row: &SweepRow, paths: &[&str]) -> serde_json::Value {
    let mut map = serde_json::Map::new();
    map.insert("index".into(), row.index.into());
    for (path, value) in paths.iter().zip(&row.values) {
        let v = match flexrig_rig::overrides::parse_value(value) {
            toml::Value::String(s) => serde_json::Value::String(s),
            toml::Value::Integer(i) => i.into(),
            toml::Value::Float(f) => serde_json::json!(f),
            toml::Value::Boolean(b) => b.into(),
            other => serde_json::Value::String(other.to_string()),
        };
        map.insert((*path).into(), v);
    }
    map.insert("status".into(), row.status.clone().into());
    if !row.error.is_empty() {
        map.insert("error".into(), row.error.clone().into());
    }
    for (name, v) in SUMMARY_COLUMNS.iter().zip(&row.summary) {
        match v {
            Some(x) if INTEGER_COLUMNS.contains(name) => {
                map.insert((*name).into(), serde_json::json!(*x as i64));
            }
            Some(x) => {
                map.insert((*name).into(), serde_json::json!(x));
            }
            None => {}
        }
    }
    if !row.notes.is_empty() {
        map.insert("notes".into(), row.notes.clone().into());
    }
    serde_json::Value::Object(map)
}

/// Parses a table written by [`csv_line`] (header included): its rows, by index. Only rows
/// that ran to a result (`ok` or `error`) count as done; a row that failed only for a passing
/// cause (a write that failed, e.g. a full disk) does not, so a resume runs it again. Quoted
/// cells may hold commas, quotes and line breaks. Every record must be whole.
pub fn read_rows(text: &str, paths: usize) -> Result<BTreeMap<usize, SweepRow>, String> {
    read_records(text, paths, false)
}

/// [`read_rows`] for a journal: a record that is not whole (the torn last line of a run that
/// was killed, or bytes a crash left behind) is dropped, and its point runs again.
pub fn read_journal(text: &str, paths: usize) -> BTreeMap<usize, SweepRow> {
    read_records(text, paths, true).unwrap_or_default()
}

fn read_records(
    text: &str,
    paths: usize,
    lenient: bool,
) -> Result<BTreeMap<usize, SweepRow>, String> {
    let mut rows = BTreeMap::new();
    for (line, record, whole) in csv_records(text).into_iter().skip(1) {
        if record.iter().all(|c| c.trim().is_empty()) && whole {
            continue;
        }
        match parse_record(&record, paths, whole) {
            Ok(Some(row)) => {
                rows.insert(row.index, row);
            }
            Ok(None) => {}
            Err(reason) if lenient => {
                let _ = reason; // a torn or damaged journal record: the point runs again
            }
            Err(reason) => return Err(format!("line {line}: {reason}")),
        }
    }
    Ok(rows)
}

/// One record as a row: `None` for a row that did not run to a result or failed for a passing
/// cause.
fn parse_record(cells: &[String], paths: usize, whole: bool) -> Result<Option<SweepRow>, String> {
    // the notes, the last cell, came later: a table written before them has none
    let expected = 4 + paths + SUMMARY_COLUMNS.len();
    if !whole {
        return Err("the record is not terminated (a torn line)".into());
    }
    if cells.len() != expected && cells.len() != expected - 1 {
        return Err(format!("{} cells, expected {expected}", cells.len()));
    }
    let notes = cells.get(expected - 1).cloned().unwrap_or_default();
    let cells = &cells[..expected - 1];
    let index: usize = cells[0].parse().map_err(|_| {
        format!(
            "the index \u{201c}{}\u{201d} is not a whole number",
            cells[0]
        )
    })?;
    let status = cells[1 + paths].clone();
    if status != "ok" && status != "error" {
        return Ok(None);
    }
    let error = cells[2 + paths].clone();
    if status == "error" && failed_for_a_passing_cause(&error) {
        return Ok(None);
    }
    let summary = cells[3 + paths..]
        .iter()
        .map(|c| {
            if c.is_empty() {
                Ok(None)
            } else {
                c.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .map(Some)
                    .ok_or(())
            }
        })
        .collect::<Result<Vec<Option<f64>>, _>>()
        .map_err(|_| "a summary value is not a number".to_string())?;
    Ok(Some(SweepRow {
        index,
        values: cells[1..1 + paths]
            .iter()
            .map(|c| flexrig_rig::overrides::parse_value(c).to_string())
            .collect(),
        status,
        error,
        summary,
        notes,
    }))
}

/// True for the error of a run that failed because its output could not be written (a full
/// disk, a log that could not be finished): not the point's fault, worth running again.
pub fn failed_for_a_passing_cause(error: &str) -> bool {
    error.starts_with("cannot write ") || error.starts_with("recorder: ")
}

/// The records of CSV `text` with the line each starts on, and whether it ended with a line
/// break outside quotes (a whole record): quoted cells may hold commas, doubled quotes and line
/// breaks.
fn csv_records(text: &str) -> Vec<(usize, Vec<String>, bool)> {
    let mut records = Vec::new();
    let mut cells = Vec::new();
    let mut cell = String::new();
    let mut quoted = false;
    let mut line = 1;
    let mut start = 1;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                cell.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => cells.push(std::mem::take(&mut cell)),
            ('\r', false) if chars.peek() == Some(&'\n') => {}
            ('\n', false) => {
                cells.push(std::mem::take(&mut cell));
                records.push((start, std::mem::take(&mut cells), true));
                line += 1;
                start = line;
            }
            (c, _) => {
                if c == '\n' {
                    line += 1;
                }
                cell.push(c);
            }
        }
    }
    if !cell.is_empty() || !cells.is_empty() || quoted {
        cells.push(cell);
        records.push((start, cells, false));
    }
    records
}

/// The description of a sweep kept beside its tables (`sweep.json`): what a resume and a merge
/// check before they mix rows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepManifest {
    /// [`Sweep::fingerprint`].
    pub fingerprint: String,
    /// Varied paths.
    pub paths: Vec<String>,
    /// Number of points.
    pub points: usize,
}

/// The table file of a sweep in `dir` (of `shard`).
pub fn table_path(dir: &Path, shard: Option<(usize, usize)>, json: bool) -> PathBuf {
    let ext = if json { "jsonl" } else { "csv" };
    match shard {
        Some((i, n)) => dir.join(format!("sweep.shard-{i}-of-{n}.{ext}")),
        None => dir.join(format!("sweep.{ext}")),
    }
}

/// Writes the rows as CSV (and JSON Lines with `json`) atomically.
pub fn write_tables(
    dir: &Path,
    shard: Option<(usize, usize)>,
    paths: &[&str],
    rows: &BTreeMap<usize, SweepRow>,
    json: bool,
) -> Result<PathBuf, Error> {
    let mut csv = csv_header(paths);
    csv.push('\n');
    for row in rows.values() {
        csv.push_str(&csv_line(row));
        csv.push('\n');
    }
    let csv_path = table_path(dir, shard, false);
    write_atomic(&csv_path, csv.as_bytes())?;
    if json {
        let mut text = String::new();
        for row in rows.values() {
            text.push_str(&json_line(row, paths).to_string());
            text.push('\n');
        }
        write_atomic(&table_path(dir, shard, true), text.as_bytes())?;
    }
    Ok(csv_path)
}

/// The rows already done in `dir` for `shard` (table and journal), if the manifest matches.
pub fn rows_done(
    dir: &Path,
    shard: Option<(usize, usize)>,
    manifest: &SweepManifest,
) -> Result<BTreeMap<usize, SweepRow>, Error> {
    let manifest_path = dir.join("sweep.json");
    let Ok(text) = std::fs::read_to_string(&manifest_path) else {
        return Ok(BTreeMap::new());
    };
    let on_disk: SweepManifest =
        serde_json::from_str(&text).map_err(|e| Error::InvalidArgument {
            arg: "--out".into(),
            value: manifest_path.display().to_string(),
            allowed: format!("must hold this sweep's sweep.json (unreadable: {e})"),
        })?;
    if &on_disk != manifest {
        return Err(Error::InvalidArgument {
            arg: "--out".into(),
            value: dir.display().to_string(),
            allowed: "holds another sweep (its sweep.json differs): choose another directory"
                .into(),
        });
    }
    let mut rows = BTreeMap::new();
    let table = table_path(dir, shard, false);
    let journal = journal_path(dir, shard);
    if let Ok(text) = std::fs::read_to_string(&table) {
        let found =
            read_rows(&text, manifest.paths.len()).map_err(|reason| Error::InvalidArgument {
                arg: "--out".into(),
                value: table.display().to_string(),
                allowed: format!("must be a sweep table ({reason}): remove it to start over"),
            })?;
        rows.extend(found);
    }
    // the journal is a cache of finished rows: whatever of it is damaged runs again
    if let Ok(bytes) = std::fs::read(&journal) {
        rows.extend(read_journal(
            &String::from_utf8_lossy(&bytes),
            manifest.paths.len(),
        ));
    }
    rows.retain(|&i, _| i < manifest.points);
    Ok(rows)
}

/// The journal of finished rows written while a sweep runs (read by a resume).
pub fn journal_path(dir: &Path, shard: Option<(usize, usize)>) -> PathBuf {
    let mut p = table_path(dir, shard, false).into_os_string();
    p.push(".partial");
    PathBuf::from(p)
}

/// Appends rows to the journal as they finish (the header first).
pub struct Journal {
    file: Mutex<std::fs::File>,
    path: PathBuf,
}

impl Journal {
    /// Opens (creates or appends to) the journal of `dir`/`shard`.
    pub fn open(dir: &Path, shard: Option<(usize, usize)>, paths: &[&str]) -> Result<Self, Error> {
        let path = journal_path(dir, shard);
        let fresh = !path.exists();
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(|e| Error::write(&path, e))?;
        if fresh {
            writeln!(file, "{}", csv_header(paths)).map_err(|e| Error::write(&path, e))?;
        }
        Ok(Journal {
            file: Mutex::new(file),
            path,
        })
    }

    /// Appends `row` (rows that did not finish are not journalled).
    pub fn append(&self, row: &SweepRow) {
        if row.status == "interrupted" {
            return;
        }
        if let Ok(mut f) = self.file.lock() {
            // a journal write that fails only costs a rerun of the row on resume
            let _ = writeln!(f, "{}", csv_line(row));
        }
    }

    /// Removes the journal (its rows are in the table).
    pub fn remove(self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Joins the shard tables of `dir` into `sweep.csv`: every point exactly once.
pub fn merge(dir: &Path, json: bool) -> Result<(PathBuf, usize), Error> {
    let manifest_path = dir.join("sweep.json");
    let text = std::fs::read_to_string(&manifest_path).map_err(|source| Error::Read {
        path: manifest_path.clone(),
        source,
    })?;
    let manifest: SweepManifest =
        serde_json::from_str(&text).map_err(|e| Error::InvalidArgument {
            arg: "DIR".into(),
            value: manifest_path.display().to_string(),
            allowed: format!("must be a sweep manifest: {e}"),
        })?;
    let mut rows = BTreeMap::new();
    let mut shards = 0;
    let entries = std::fs::read_dir(dir).map_err(|source| Error::Read {
        path: dir.to_path_buf(),
        source,
    })?;
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        if !(name.starts_with("sweep.shard-") && name.ends_with(".csv")) {
            continue;
        }
        shards += 1;
        let text = std::fs::read_to_string(entry.path()).map_err(|source| Error::Read {
            path: entry.path(),
            source,
        })?;
        let found =
            read_rows(&text, manifest.paths.len()).map_err(|reason| Error::InvalidArgument {
                arg: "DIR".into(),
                value: entry.path().display().to_string(),
                allowed: format!("must hold sweep shard tables ({reason})"),
            })?;
        for (i, row) in found {
            if i >= manifest.points {
                return Err(Error::InvalidArgument {
                    arg: "DIR".into(),
                    value: entry.path().display().to_string(),
                    allowed: format!(
                        "holds point {i}, outside the sweep's {} points (0 to {}): a table of \
                         another sweep?",
                        manifest.points,
                        manifest.points.saturating_sub(1)
                    ),
                });
            }
            if rows.insert(i, row).is_some() {
                return Err(Error::InvalidArgument {
                    arg: "DIR".into(),
                    value: dir.display().to_string(),
                    allowed: format!("point {i} is in two shard tables"),
                });
            }
        }
    }
    let missing: Vec<usize> = (0..manifest.points)
        .filter(|i| !rows.contains_key(i))
        .collect();
    if shards == 0 || !missing.is_empty() {
        let first = match missing.first() {
            Some(i) => format!(", the first is point {i}"),
            None => String::new(),
        };
        let shard_tables = if shards == 0 {
            "it holds no shard table; run the shards with --shard I/N --out DIR \
             first"
                .to_string()
        } else {
            format!(
                "{} of {} points are missing{first}; run the missing shards with the same \
                 --out DIR (a rerun resumes)",
                missing.len(),
                manifest.points
            )
        };
        return Err(Error::InvalidArgument {
            arg: "DIR".into(),
            value: dir.display().to_string(),
            allowed: format!("must hold every shard of the sweep: {shard_tables}"),
        });
    }
    let paths: Vec<&str> = manifest.paths.iter().map(String::as_str).collect();
    let path = write_tables(dir, None, &paths, &rows, json)?;
    Ok((path, rows.len()))
}

#[cfg(test)]
mod tests;
