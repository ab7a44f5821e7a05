//! The library's error type: every failure names what went wrong (for bad input: the field,
//! the value and what is allowed) and says what kind of failure it is ([`ErrorKind`]: bad input,
//! a run that failed, I/O, interrupted), from which the command line takes its exit code.

use std::path::PathBuf;

/// Everything a flexrig computation can fail with.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// An argument (a field of an input, or its command-line flag) is outside its allowed range.
    #[error("invalid argument {arg} = {value}: {allowed}")]
    InvalidArgument {
        /// The field or flag, e.g. `--m-h`.
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
    /// An error from the free-mass impact at finite-element fidelity.
    #[error(transparent)]
    Impact(#[from] flexrig_impact::ImpactError),
    /// An error from the test rig (scene, simulation).
    #[error(transparent)]
    Rig(#[from] flexrig_rig::RigError),
    /// An error from the safety crate (body model, limits, a contact the standard forbids).
    #[error(transparent)]
    Safety(#[from] flexrig_safety::SafetyError),
    /// An error from the robot crate (a URDF, a trajectory CSV, a contact point, a joint
    /// vector): it names the file and line or the field.
    #[error(transparent)]
    Robot(#[from] flexrig_robot::RobotError),
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
    /// A sweep stopped (Ctrl-C) before every point ran; the rows done are kept.
    #[error(
        "the sweep was interrupted with {done} of {points} runs in {}; run the same command again \
         to resume it (the runs done are kept)",
        table.display()
    )]
    SweepInterrupted {
        /// Rows in the table (done now or earlier).
        done: usize,
        /// Points of the sweep (or of its shard).
        points: usize,
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

/// What kind of failure an [`Error`] is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ErrorKind {
    /// Bad input: an argument, a parameter, a scene field, a data file's content (the message
    /// names the field); changing the input is the cure.
    Input,
    /// A file could not be read or written.
    Io,
    /// A run or a check failed on valid input (unstable, a budget exhausted, failed cases).
    Failed,
    /// Stopped by a [`crate::CancelToken`].
    Interrupted,
}

impl Error {
    /// The kind of failure.
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::Rig(flexrig_rig::RigError::Interrupted { .. })
            | Error::SweepInterrupted { .. } => ErrorKind::Interrupted,
            Error::Impact(e) if matches!(e.root(), flexrig_impact::ImpactError::Interrupted) => {
                ErrorKind::Interrupted
            }
            Error::Read { .. } | Error::Write { .. } => ErrorKind::Io,
            Error::InvalidArgument { .. } | Error::NonFinite { .. } => ErrorKind::Input,
            Error::Contact(e) if e.is_input_error() => ErrorKind::Input,
            Error::Lumped(e) if e.is_input_error() => ErrorKind::Input,
            Error::Beam(e) if e.is_input_error() => ErrorKind::Input,
            Error::Rig(e) if e.is_input_error() => ErrorKind::Input,
            Error::Impact(e) if e.is_input_error() => ErrorKind::Input,
            Error::Safety(e) if e.is_input_error() => ErrorKind::Input,
            Error::Robot(flexrig_robot::RobotError::Io { .. }) => ErrorKind::Io,
            Error::Robot(_) => ErrorKind::Input,
            _ => ErrorKind::Failed,
        }
    }

    /// Process exit code: 2 for bad input (arguments, parameters, data files, an input file
    /// that cannot be read), 130 for a run stopped by Ctrl-C (the shell's code for SIGINT), 1
    /// otherwise.
    pub fn exit_code(&self) -> i32 {
        match self.kind() {
            ErrorKind::Interrupted => 130,
            ErrorKind::Input => 2,
            ErrorKind::Io
                if matches!(
                    self,
                    Error::Read { .. } | Error::Robot(flexrig_robot::RobotError::Io { .. })
                ) =>
            {
                2
            }
            _ => 1,
        }
    }

    /// True for a report that could not be written because its reader went away (`flexrig … |
    /// head`): the front then stops quietly, as a pipeline expects.
    pub fn is_broken_pipe(&self) -> bool {
        matches!(self, Error::Write { source, .. } if source.kind() == std::io::ErrorKind::BrokenPipe)
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
        Error::Write {
            path: path.into(),
            source,
        }
    }
}
