//! Errors of the lumped impact model.

use flexrig_contact::ContactError;

/// Everything the lumped crate can fail with.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LumpedError {
    /// A parameter is invalid (names the field, the value and what is allowed).
    #[error(transparent)]
    Parameter(#[from] ContactError),
    /// The requested method does not apply to this model.
    #[error("method {method} does not apply: {reason}")]
    NotApplicable {
        /// The method, e.g. `analytic`.
        method: &'static str,
        /// Why, and what to use instead.
        reason: String,
    },
    /// The time integration failed.
    #[error("time integration failed at t = {t:e} s: {reason}")]
    IntegrationFailed {
        /// Time reached \[s\].
        t: f64,
        /// What happened and what to try.
        reason: String,
    },
}

impl LumpedError {
    /// True when the error is caused by bad input (the CLI exits with code 2).
    pub fn is_input_error(&self) -> bool {
        match self {
            LumpedError::Parameter(e) => e.is_input_error(),
            LumpedError::NotApplicable { .. } => true,
            LumpedError::IntegrationFailed { .. } => false,
        }
    }
}
