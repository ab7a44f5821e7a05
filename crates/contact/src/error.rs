//! Errors of the contact crate. Every variant names the field (or CSV line), the value and what
//! is allowed, so a user can fix the input without reading the source.

/// Everything the contact crate can fail with.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ContactError {
    /// A parameter is outside its allowed range (or not finite).
    #[error("invalid {field} = {value}: {allowed}")]
    InvalidParameter {
        /// Name of the parameter, e.g. `k_c` or `material.abs.n`.
        field: String,
        /// The rejected value, as given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A line of a compression-data CSV file could not be read.
    #[error("CSV line {line}: {reason} (found {content:?})")]
    Csv {
        /// 1-based line number.
        line: usize,
        /// The offending line, trimmed.
        content: String,
        /// What was expected.
        reason: String,
    },
    /// Too few usable data points for a fit.
    #[error("compression data has {found} usable points (indentation > 0): {needed}")]
    NotEnoughData {
        /// Usable points found.
        found: usize,
        /// What is needed.
        needed: String,
    },
    /// The materials file could not be parsed.
    #[error("materials file: {0}")]
    MaterialsSyntax(String),
    /// A material name is not in the materials file.
    #[error("unknown material {name:?}: known materials are {known}")]
    UnknownMaterial {
        /// The requested name.
        name: String,
        /// Comma-separated known names.
        known: String,
    },
    /// The least-squares fit did not converge.
    #[error("Hertz fit did not converge after {iterations} iterations: {reason}")]
    FitDidNotConverge {
        /// Iterations done.
        iterations: usize,
        /// Why it stopped.
        reason: String,
    },
}

impl ContactError {
    /// True when the error is caused by bad input (the CLI exits with code 2).
    pub fn is_input_error(&self) -> bool {
        !matches!(self, ContactError::FitDidNotConverge { .. })
    }
}
