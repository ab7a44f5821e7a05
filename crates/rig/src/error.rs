//! Errors of the rig: scene validation names the field path, the value and what is allowed.

/// Everything the rig can fail with.
#[derive(Debug, thiserror::Error)]
pub enum RigError {
    /// A scene field is outside its allowed range.
    #[error("scene field {field} = {value}: {allowed}")]
    InvalidScene {
        /// Dotted path, e.g. `operator.release_angle_deg`.
        field: String,
        /// The rejected value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// The scene file is not valid TOML for the scene format.
    #[error("scene file: {0}")]
    SceneSyntax(String),
    /// An error from the contact crate (materials, laws).
    #[error(transparent)]
    Contact(#[from] flexrig_contact::ContactError),
    /// An error from the beam crate.
    #[error(transparent)]
    Beam(#[from] flexrig_beam::BeamError),
    /// The simulation became unstable or non-finite.
    #[error("simulation stopped at t = {t:.6e} s: {quantity} {reason}; try {suggestion}")]
    Unstable {
        /// Time reached \[s\].
        t: f64,
        /// The quantity that failed.
        quantity: String,
        /// What happened.
        reason: String,
        /// Which setting to reduce.
        suggestion: String,
    },
    /// The recorder failed (e.g. a log could not be written); the run stops.
    #[error("recorder: {0}")]
    Recorder(String),
    /// The run was interrupted (e.g. Ctrl-C) by its recorder.
    #[error("the run was interrupted at t = {t:.6e} s")]
    Interrupted {
        /// Time reached \[s\].
        t: f64,
    },
    /// The run did not reach its stop condition.
    #[error("the run did not reach {what} within {limit}")]
    NotReached {
        /// The awaited event.
        what: String,
        /// The limit that stopped it.
        limit: String,
    },
}

impl RigError {
    /// True when the error is caused by bad input (the CLI exits with code 2).
    pub fn is_input_error(&self) -> bool {
        match self {
            RigError::InvalidScene { .. } | RigError::SceneSyntax(_) => true,
            RigError::Contact(e) => e.is_input_error(),
            RigError::Beam(e) => e.is_input_error(),
            RigError::Unstable { .. }
            | RigError::NotReached { .. }
            | RigError::Interrupted { .. }
            | RigError::Recorder(_) => false,
        }
    }
}

/// Shorthand for an [`RigError::InvalidScene`].
pub(crate) fn invalid(field: &str, value: impl std::fmt::Display, allowed: &str) -> RigError {
    RigError::InvalidScene {
        field: field.to_string(),
        value: compact(value.to_string()),
        allowed: allowed.to_string(),
    }
}

/// A number written out in full (1e300 as 301 digits) in the compact form of
/// [`flexrig_contact::validate::display`]; any other text unchanged.
fn compact(text: String) -> String {
    match text.parse::<f64>() {
        Ok(x) if text.len() > 20 => flexrig_contact::validate::display(x),
        _ => text,
    }
}
