//! Errors of the free-mass impact.

/// Everything a free-mass impact can fail with.
#[derive(Debug, thiserror::Error)]
pub enum ImpactError {
    /// A parameter outside its allowed range.
    #[error("invalid {field} = {value}: {allowed}")]
    InvalidParameter {
        /// The parameter, as the user names it.
        field: String,
        /// The rejected value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// The contact law rejected its parameters.
    #[error(transparent)]
    Contact(#[from] flexrig_contact::ContactError),
    /// The lumped model rejected its parameters.
    #[error(transparent)]
    Lumped(#[from] flexrig_lumped::LumpedError),
    /// The beam failed (parameters or a step).
    #[error(transparent)]
    Beam(#[from] flexrig_beam::BeamError),
    /// The integration did not reach the separation.
    #[error("the {design} impact did not finish: {reason}")]
    NotFinished {
        /// "CJ" or "CL".
        design: &'static str,
        /// What happened, and what to change.
        reason: String,
    },
    /// Stopped on request (Ctrl-C) before every case was computed.
    #[error("stopped on request before every case was computed")]
    Interrupted,
}

impl ImpactError {
    /// True for bad input (exit code 2 in the CLI).
    pub fn is_input_error(&self) -> bool {
        match self {
            ImpactError::InvalidParameter { .. } => true,
            ImpactError::Contact(e) => e.is_input_error(),
            ImpactError::Lumped(e) => e.is_input_error(),
            ImpactError::Beam(e) => e.is_input_error(),
            ImpactError::NotFinished { .. } | ImpactError::Interrupted => false,
        }
    }

    pub(crate) fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        ImpactError::InvalidParameter {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}
