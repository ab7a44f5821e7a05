//! The error type of the beam crate.

/// Errors of the beam crate; every variant names the offending field or the failing solver step.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BeamError {
    /// A model parameter is out of its allowed range.
    #[error("invalid {field} = {value}: {allowed}")]
    InvalidParameter {
        /// Name of the parameter (the CLI flag or the struct field).
        field: String,
        /// The rejected value, as given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// Newton–Raphson did not converge.
    #[error(
        "{solver}: Newton did not converge after {iterations} iterations (residual \
         {residual:.3e}, load level reached {load_level:.4}); try more load steps or a smaller \
         time step"
    )]
    NotConverged {
        /// Which solver (e.g. "corotational static solve", "generalized-α step").
        solver: String,
        /// Fraction of the load reached (statics: the last converged load step, in [0, 1)) or 1
        /// (dynamics).
        load_level: f64,
        /// Iterations spent on the load step (or time step) that failed.
        iterations: usize,
        /// The last residual norm, in N.
        residual: f64,
    },
    /// A system matrix is singular (e.g. a static load on a pinned root without a spring).
    #[error("singular {what} at free degree of freedom {dof}: {hint}")]
    Singular {
        /// Which matrix.
        what: String,
        /// The free DOF index at which the zero pivot appeared.
        dof: usize,
        /// The likely cause.
        hint: String,
    },
    /// The state became non-finite (NaN or infinite).
    #[error("non-finite {what}: the solution diverged")]
    NonFinite {
        /// What became non-finite.
        what: String,
    },
    /// A time step failed even when taken in 2^`halvings` pieces.
    #[error(
        "time step at t = {t:.6e} s (h = {h:.3e} s) failed even split into {} pieces: {cause}",
        1u64 << *halvings
    )]
    StepFailed {
        /// Time at the start of the step \[s\].
        t: f64,
        /// The step \[s\].
        h: f64,
        /// How often the step was halved.
        halvings: u32,
        /// The failure of the smallest piece.
        cause: Box<BeamError>,
    },
    /// The eigen-solver failed.
    #[error("eigen-solver failed: {0}")]
    Eigen(String),
}

impl BeamError {
    /// True when the error is caused by bad input (exit code 2 in the CLI).
    pub fn is_input_error(&self) -> bool {
        matches!(self, BeamError::InvalidParameter { .. })
    }

    /// Shorthand for [`BeamError::InvalidParameter`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl ToString,
        allowed: impl Into<String>,
    ) -> Self {
        BeamError::InvalidParameter {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

/// A number as an error message should quote it: exponent form for very small or large
/// magnitudes.
pub(crate) fn display(value: f64) -> String {
    let a = value.abs();
    if a != 0.0 && a.is_finite() && !(1e-4..1e6).contains(&a) {
        format!("{value:e}")
    } else {
        format!("{value}")
    }
}

/// Checks that `value` is finite and > 0.
pub(crate) fn positive(field: &str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(BeamError::invalid(
            field,
            display(value),
            "a finite number > 0",
        ))
    }
}

/// Checks that `value` is finite and ≥ 0.
pub(crate) fn non_negative(field: &str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(BeamError::invalid(
            field,
            display(value),
            "a finite number ≥ 0",
        ))
    }
}

/// Checks that `value` is finite.
pub(crate) fn finite(field: &str, value: f64) -> Result<f64, BeamError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(BeamError::invalid(field, display(value), "a finite number"))
    }
}
