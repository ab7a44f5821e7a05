//! A run logged to a file: the log written under a temporary name and moved into place only when
//! finished, never replacing a file without `--force`, with its Foxglove layout beside it.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use flexrig_rig::{Recorder, RigError, RunSummary, Scene, Simulation, SwingSamples};

use crate::Error;
use crate::log::mcap::{LogRates, McapRecorder};
use crate::shared::cancel::CancelToken;

/// Where and how [`run_logged`] writes a run's MCAP log.
#[derive(Debug, Clone)]
pub struct LogTarget<'a> {
    /// The log file the user asked for.
    pub path: &'a Path,
    /// Replace an existing file at `path` (otherwise an existing file is an error).
    pub force: bool,
    /// The scene text as run (attached to the log).
    pub scene_text: &'a str,
    /// Cancelled (e.g. by Ctrl-C), the run stops and its log is finished.
    pub cancel: CancelToken,
    /// What is logged how often.
    pub rates: LogRates,
    /// Factor on the FE beam's displacements in the 3D view (1: true scale; see
    /// [`McapRecorder::with_deformation_scale`]).
    pub deformation_scale: f64,
}

/// Runs `simulation` of `scene` while logging it to `target.path`, with its Foxglove layout
/// beside it (`run.layout.json` beside `run.mcap`, see [`crate::log::layout::for_log`]: the
/// plots over the first contact; over the whole log when the run had none or failed).
///
/// The log is written under a temporary name in the same directory and moved into place only
/// when finished, so the requested name never holds an unfinished file; the layout, which
/// belongs to the log, is then written (replaced) atomically. A run that fails (or is stopped by Ctrl-C) still leaves its finished
/// log, with an `error` metadata record, and returns the run's error; a write that fails (e.g.
/// a full disk) leaves no log and returns the write error, naming the file.
pub fn run_logged(
    simulation: Simulation,
    scene: &Scene,
    target: &LogTarget<'_>,
) -> Result<RunSummary, Error> {
    run_logged_also(simulation, scene, target, &mut flexrig_rig::NoRecorder)
}

/// Both recorders of a logged run: the log first, then `also`.
struct Both<'a, A, B: ?Sized>(&'a mut A, &'a mut B);

impl<A: Recorder, B: Recorder + ?Sized> Recorder for Both<'_, A, B> {
    fn frame(&mut self, f: &flexrig_rig::Frame<'_>) -> Result<(), RigError> {
        self.0.frame(f)?;
        self.1.frame(f)
    }

    /// The log's period (the poses between free-swing steps are for its 3D view).
    fn pose_period(&self) -> Option<f64> {
        self.0.pose_period()
    }

    fn between(&mut self, f: &flexrig_rig::Frame<'_>) -> Result<(), RigError> {
        self.0.between(f)?;
        if self.1.pose_period().is_some() {
            self.1.between(f)?;
        }
        Ok(())
    }

    /// The samples either wants (each filters what it gets, so a superset is harmless).
    fn swing_samples(&self) -> SwingSamples {
        match (self.0.swing_samples(), self.1.swing_samples()) {
            (SwingSamples::Every, _) | (_, SwingSamples::Every) => SwingSamples::Every,
            (SwingSamples::None, SwingSamples::None) => SwingSamples::None,
            _ => SwingSamples::Chosen,
        }
    }

    fn wants_swing_sample(&mut self, t: f64) -> bool {
        // both are asked (each keeps count of what it chose)
        let a = self.0.swing_samples() == SwingSamples::Chosen && self.0.wants_swing_sample(t);
        let b = self.1.swing_samples() == SwingSamples::Chosen && self.1.wants_swing_sample(t);
        a || b
    }
}

/// [`run_logged`], with every step also handed to `also` (e.g. a
/// [`crate::testbed::traces::TraceRecorder`], for a front that returns the traces and writes the log).
pub fn run_logged_also(
    simulation: Simulation,
    scene: &Scene,
    target: &LogTarget<'_>,
    also: &mut dyn Recorder,
) -> Result<RunSummary, Error> {
    let path = target.path;
    let layout = crate::log::layout::path_beside(path);
    crate::shared::output::check_output_target(path)?;
    crate::shared::output::check_output_target(&layout)?;
    if !target.force {
        // neither the log nor the layout written beside it replaces a file without --force
        for existing in [path, layout.as_path()] {
            if existing.exists() {
                return Err(refuse_overwrite(existing));
            }
        }
    }
    if let Some(parent) = path.parent().filter(|p| !p.as_os_str().is_empty()) {
        crate::shared::output::ensure_dir(parent)?;
    }
    let pending = PendingFile::new(path);
    let file = File::create(&pending.tmp).map_err(|e| Error::write(path, e))?;
    let write_error = |e: mcap::McapError| Error::write(path, io_of(e));
    let mut log = McapRecorder::new(BufWriter::new(file), scene, target.scene_text)
        .map_err(write_error)?
        .with_cancel(target.cancel.clone())
        .with_rates(target.rates)
        .with_deformation_scale(target.deformation_scale);
    let outcome = simulation.run(&mut Both(&mut log, also));
    let finished = match &outcome {
        Ok(summary) => log
            .write_summary(summary)
            .and_then(|()| log.write_severity(summary))
            .and_then(|()| log.finish_into_inner()),
        Err(e) => log.finish_with_error(&e.to_string()),
    };
    let writer = finished.map_err(write_error)?;
    let file = writer
        .into_inner()
        .map_err(|e| Error::write(path, e.into_error()))?;
    drop(file);
    pending.commit(target.force)?;
    crate::log::layout::write_beside(path, outcome.as_ref().ok())?;
    Ok(outcome?)
}

pub(crate) fn refuse_overwrite(path: &Path) -> Error {
    Error::InvalidArgument {
        arg: "--out".into(),
        value: path.display().to_string(),
        allowed: "a file that does not exist yet, nor its layout beside it (or add --force to \
                  overwrite both)"
            .into(),
    }
}

/// The I/O error inside an MCAP error (kept, so a full disk still reads as one).
pub(crate) fn io_of(e: mcap::McapError) -> std::io::Error {
    match e {
        mcap::McapError::Io(e) => e,
        other => std::io::Error::other(other.to_string()),
    }
}

/// A file written under a temporary sibling name, removed unless committed.
pub(crate) struct PendingFile {
    pub(crate) tmp: PathBuf,
    path: PathBuf,
    committed: bool,
}

impl PendingFile {
    pub(crate) fn new(path: &Path) -> Self {
        PendingFile {
            tmp: crate::shared::output::temporary_sibling(path),
            path: path.to_path_buf(),
            committed: false,
        }
    }

    /// Moves the finished file into place; without `force` an existing file is not replaced.
    pub(crate) fn commit(mut self, force: bool) -> Result<(), Error> {
        let placed = if force {
            std::fs::rename(&self.tmp, &self.path)
        } else {
            // a hard link fails if the name was taken meanwhile; then the temporary is removed
            std::fs::hard_link(&self.tmp, &self.path)
                .or_else(|e| match e.kind() {
                    std::io::ErrorKind::AlreadyExists => Err(e),
                    // file systems without hard links
                    _ => std::fs::rename(&self.tmp, &self.path),
                })
                .map(|()| {
                    let _ = std::fs::remove_file(&self.tmp);
                })
        };
        placed.map_err(|e| {
            if e.kind() == std::io::ErrorKind::AlreadyExists {
                refuse_overwrite(&self.path)
            } else {
                Error::write(&self.path, e)
            }
        })?;
        self.committed = true;
        Ok(())
    }
}

impl Drop for PendingFile {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
