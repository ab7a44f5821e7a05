//! A sweep into a directory, as `flexrig sweep` runs it: the table (sweep.csv, or one per shard),
//! its manifest (sweep.json) and a journal that makes a rerun resume where the last one stopped;
//! optionally an MCAP log per run.

use std::path::{Path, PathBuf};

use crate::Error;
use crate::shared::cancel::CancelToken;
use crate::shared::output::{ensure_dir, read_text_limited, write_atomic};
use crate::shared::progress::Progress;
use crate::study::spec::MAX_VALUE_FILE_BYTES;
use crate::study::spec::{Dimension, parse_all};
use crate::study::sweep::{Journal, Sweep, SweepManifest, SweepOptions, rows_done, write_tables};

/// What to sweep and where.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRequest {
    /// The base scene: a bundled name or a scene file's path ([`crate::testbed::scenes::resolve`]).
    pub base: PathBuf,
    /// The varied fields.
    pub dimensions: Vec<Dimension>,
    /// Zip the dimensions (same length) instead of the full grid.
    pub zip: bool,
    /// Directory of the table, its manifest and journal; a rerun resumes.
    pub out: PathBuf,
    /// Also write JSON Lines (sweep.jsonl).
    pub jsonl: bool,
    /// Keep an MCAP log per run (out/runs/run-<index>.mcap, its Foxglove layout beside it).
    pub mcap: bool,
    /// Run only shard I of N (points with index ≡ I mod N).
    pub shard: Option<(usize, usize)>,
    /// Threads running points (`--threads`, 1 to [`MAX_THREADS`]); none: every core.
    pub threads: Option<usize>,
}

/// Most threads of one sweep.
pub const MAX_THREADS: usize = 4096;

/// What a sweep did.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepReport {
    /// The table written.
    pub table: PathBuf,
    /// Rows in the table (done now or earlier).
    pub rows: usize,
    /// Points of the sweep (or of its shard).
    pub points: usize,
    /// Rows from an earlier run (resumed).
    pub resumed: usize,
    /// Rows whose run failed.
    pub failed: usize,
    /// True if the sweep was cancelled before every point ran.
    pub interrupted: bool,
}

impl SweepReport {
    /// An error if the sweep was interrupted ([`Error::SweepInterrupted`]: a rerun resumes) or
    /// runs failed ([`Error::SweepFailed`]).
    pub fn check(&self) -> Result<(), Error> {
        if self.interrupted {
            return Err(Error::SweepInterrupted {
                done: self.rows,
                points: self.points,
                table: self.table.clone(),
            });
        }
        if self.failed > 0 {
            return Err(Error::SweepFailed {
                failed: self.failed,
                total: self.points,
                table: self.table.clone(),
            });
        }
        Ok(())
    }
}

/// The dimensions of `PATH=SPEC` texts (see [`Dimension::parse`]); a `@file` is read beside
/// `base` first, then as given.
pub fn parse_dimensions(set: &[String], base: &Path, zip: bool) -> Result<Vec<Dimension>, Error> {
    let base_dir = base.parent().map(PathBuf::from).unwrap_or_default();
    let read = |file: &str| {
        read_text_limited(&base_dir.join(file), MAX_VALUE_FILE_BYTES)
            .or_else(|_| read_text_limited(&PathBuf::from(file), MAX_VALUE_FILE_BYTES))
    };
    parse_all(set, &read, zip)
}

/// Runs the points of `request` not yet in its directory's table, in parallel; `progress` hears
/// of each. Rows of failed runs are in the table (their status and error columns say why): see
/// [`SweepReport::check`].
pub fn run_sweep(
    request: &SweepRequest,
    cancel: &CancelToken,
    progress: &dyn Progress,
) -> Result<SweepReport, Error> {
    let shard = request.shard;
    if let Some(k) = request.threads
        && !(1..=MAX_THREADS).contains(&k)
    {
        return Err(Error::InvalidArgument {
            arg: "--threads".into(),
            value: k.to_string(),
            allowed: format!("must be a whole number from 1 to {MAX_THREADS} (none: every core)"),
        });
    }
    let sweep = Sweep::new(
        &crate::testbed::scenes::resolve("BASE", &request.base)?.text,
        request.dimensions.clone(),
        request.zip,
    )?;
    let paths = sweep.paths();
    let manifest = SweepManifest {
        fingerprint: sweep.fingerprint(),
        paths: paths.iter().map(|p| p.to_string()).collect(),
        points: sweep.len(),
    };
    ensure_dir(&request.out)?;
    let mut rows = rows_done(&request.out, shard, &manifest)?;
    write_atomic(
        &request.out.join("sweep.json"),
        serde_json::to_string_pretty(&manifest)
            .expect("a manifest serialises")
            .as_bytes(),
    )?;
    crate::study::spec::check_process_points(
        if shard.is_some() { "--shard" } else { "--set" },
        sweep.indices(shard).len(),
    )?;
    let todo: Vec<usize> = sweep
        .indices(shard)
        .into_iter()
        .filter(|i| !rows.contains_key(i))
        .collect();
    let mcap_dir = request.out.join("runs");
    if request.mcap {
        ensure_dir(&mcap_dir)?;
    }
    let options = SweepOptions {
        shard,
        mcap_dir: request.mcap.then_some(mcap_dir),
        cancel: cancel.clone(),
    };
    progress.start(todo.len());
    let journal = Journal::open(&request.out, shard, &paths)?;
    let resumed = rows.len();
    let done = |row: &crate::study::sweep::SweepRow| {
        journal.append(row);
        progress.advance();
    };
    let new_rows = match request.threads {
        Some(k) => rayon::ThreadPoolBuilder::new()
            .num_threads(k)
            .build()
            .map_err(|e| Error::InvalidArgument {
                arg: "--threads".into(),
                value: k.to_string(),
                allowed: format!("cannot start that many threads ({e})"),
            })?
            .install(|| sweep.run(&todo, &options, &done)),
        None => sweep.run(&todo, &options, &done),
    };
    progress.finish();
    let interrupted = cancel.is_cancelled() || new_rows.iter().any(|r| r.status == "interrupted");
    rows.extend(
        new_rows
            .into_iter()
            .filter(|r| r.status != "interrupted")
            .map(|r| (r.index, r)),
    );
    let table = write_tables(&request.out, shard, &paths, &rows, request.jsonl)?;
    let points = sweep.indices(shard).len();
    if rows.len() == points {
        journal.remove();
    }
    let failed = rows.values().filter(|r| r.status != "ok").count();
    Ok(SweepReport {
        table,
        rows: rows.len(),
        points,
        resumed,
        failed,
        interrupted,
    })
}
