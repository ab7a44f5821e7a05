//! The CLI's error type: every failure names what went wrong and maps to an exit code
//! (2 for bad input, 1 for a failure while running or writing).

use std::path::PathBuf;

/// Everything a `flexrig` command can fail with.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// A command-line argument is outside its allowed range.
    #[error("invalid argument {arg} = {value}: {allowed}")]
    InvalidArgument {
        /// The flag, e.g. `--m-h`.
        arg: String,
        /// The rejected value, as given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// An error from the contact crate (parameters, CSV data, fitting).
    #[error(transparent)]
    Contact(#[from] flexrig_contact::ContactError),
    /// An error from the lumped impact model.
    #[error(transparent)]
    Lumped(#[from] flexrig_lumped::LumpedError),
    /// An error from the beam crate.
    #[error(transparent)]
    Beam(#[from] flexrig_beam::BeamError),
    /// An error from the free-mass impact (issue 14).
    #[error(transparent)]
    Impact(#[from] flexrig_impact::ImpactError),
    /// An error from the test rig (scene, simulation).
    #[error(transparent)]
    Rig(#[from] flexrig_rig::RigError),
    /// An input file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// An output file or directory could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file or directory.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A result is not a finite number for the given arguments.
    #[error("the {what} is {value} for these arguments: {advice}")]
    NonFinite {
        /// The quantity.
        what: String,
        /// Its (non-finite) value.
        value: String,
        /// Which arguments to change.
        advice: String,
    },
    /// Some runs of a sweep failed (their rows say why).
    #[error("{failed} of {total} runs failed; see the status and error columns of {}", table.display())]
    SweepFailed {
        /// Failed runs.
        failed: usize,
        /// Runs of the sweep (or shard).
        total: usize,
        /// The table.
        table: PathBuf,
    },
    /// `flexrig validate` found failing cases.
    #[error("verification failed: {failed}")]
    ValidationFailed {
        /// Names of the failing cases.
        failed: String,
    },
    /// A figure could not be drawn.
    #[error("cannot draw {path}: {message}")]
    Plot {
        /// The SVG file.
        path: PathBuf,
        /// What the plotting backend reported.
        message: String,
    },
}

impl CliError {
    /// Process exit code: 2 for bad input (arguments, parameters, data files), 130 for a run
    /// stopped by Ctrl-C (the shell's code for SIGINT), 1 otherwise.
    pub fn exit_code(&self) -> i32 {
        match self {
            CliError::Rig(flexrig_rig::RigError::Interrupted { .. }) => 130,
            CliError::InvalidArgument { .. }
            | CliError::Read { .. }
            | CliError::NonFinite { .. } => 2,
            CliError::Contact(e) if e.is_input_error() => 2,
            CliError::Lumped(e) if e.is_input_error() => 2,
            CliError::Beam(e) if e.is_input_error() => 2,
            CliError::Rig(e) if e.is_input_error() => 2,
            CliError::Impact(e) if e.is_input_error() => 2,
            _ => 1,
        }
    }

    /// Wraps an I/O error of writing `path`; a full disk says so in words.
    pub fn write(path: impl Into<PathBuf>, source: std::io::Error) -> Self {
        let source = if source.kind() == std::io::ErrorKind::StorageFull {
            std::io::Error::new(
                std::io::ErrorKind::StorageFull,
                format!("the disk is full ({source}); free some space or write elsewhere"),
            )
        } else {
            source
        };
        CliError::Write {
            path: path.into(),
            source,
        }
    }
}
