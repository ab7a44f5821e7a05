//! Errors of the safety crate. Every variant names the field (and the body region where there is
//! one), the value and what is allowed, or the clause of the standard that forbids the request.

use flexrig_contact::ContactError;

/// Everything the safety crate can fail with.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SafetyError {
    /// A numeric parameter is outside its allowed range (names the field, value, allowed range).
    #[error(transparent)]
    Parameter(#[from] ContactError),
    /// The body-model file is not valid TOML or has the wrong shape.
    #[error("body-model file: {0}")]
    BodyModelSyntax(String),
    /// A required field of a body region (or of one of its areas) is missing.
    #[error("body-model file: region {region:?}: missing field {field} ({allowed})")]
    MissingField {
        /// Region key (or `[document]`).
        region: String,
        /// Field path, e.g. `max_force_n` or `area[2].max_pressure_n_per_cm2`.
        field: String,
        /// What the field must hold.
        allowed: String,
    },
    /// A field of a body region holds a value that is not allowed.
    #[error("body-model file: region {region:?}: invalid {field} = {value}: {allowed}")]
    InvalidField {
        /// Region key.
        region: String,
        /// Field path.
        field: String,
        /// The rejected value as given.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A body region or area name is not in the model.
    #[error(
        "unknown {what} {}: known are {known}",
        crate::body_model_file::quoted(name)
    )]
    Unknown {
        /// `body region` or `body area`.
        what: &'static str,
        /// The requested name.
        name: String,
        /// Comma-separated known names.
        known: String,
    },
    /// The standard forbids the requested contact (transient contact with head or face).
    #[error(
        "transient contact with {region} is not permitted ({clause}); evaluate quasi-static \
         contact or protect this body region"
    )]
    ContactNotPermitted {
        /// Region name.
        region: String,
        /// The clause of the standard, as given in the body-model file.
        clause: String,
    },
    /// A sampled trace is unusable (names the trace, the sample and the reason).
    #[error("trace {trace}: {reason}")]
    InvalidTrace {
        /// Which trace, e.g. `acceleration` or `force`.
        trace: String,
        /// What is wrong and what is needed.
        reason: String,
    },
}

impl SafetyError {
    /// True when the error is caused by bad input (the CLI exits with code 2). Every variant is.
    pub fn is_input_error(&self) -> bool {
        match self {
            SafetyError::Parameter(e) => e.is_input_error(),
            _ => true,
        }
    }
}
