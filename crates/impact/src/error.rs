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
    /// The severity measures of a run's traces could not be computed.
    #[error(transparent)]
    Severity(#[from] flexrig_safety::SafetyError),
    /// A time integration other than an impact's did not reach its end (e.g. the spin-up
    /// reference).
    #[error("the {what} did not finish: {reason}")]
    Unfinished {
        /// What was integrated, e.g. "spin-up reference".
        what: &'static str,
        /// What happened, and what to change.
        reason: String,
    },
    /// Stopped on request (Ctrl-C) before the run, search or map finished.
    #[error("stopped on request before the computation finished")]
    Interrupted,
    /// A traced run that failed or was stopped midway, with the trace it computed up to then
    /// (what its log keeps).
    #[error("{error}")]
    Partial {
        /// Why the run ended.
        error: Box<ImpactError>,
        /// The samples computed before it ended.
        trace: Vec<crate::strike::TraceSample>,
    },
}

impl ImpactError {
    /// `error` with the samples `trace` computed before it (unchanged without samples, and
    /// for bad input: that run never really ran).
    pub fn with_trace(error: ImpactError, trace: Vec<crate::strike::TraceSample>) -> ImpactError {
        if trace.is_empty()
            || error.is_input_error()
            || matches!(error, ImpactError::Partial { .. })
        {
            error
        } else {
            ImpactError::Partial {
                error: Box::new(error),
                trace,
            }
        }
    }

    /// The error itself, without the samples of a [`ImpactError::Partial`] run.
    pub fn root(&self) -> &ImpactError {
        match self {
            ImpactError::Partial { error, .. } => error.root(),
            other => other,
        }
    }

    /// The samples a run computed before it failed or was stopped (empty: none kept).
    pub fn partial_trace(&self) -> &[crate::strike::TraceSample] {
        match self {
            ImpactError::Partial { trace, .. } => trace,
            _ => &[],
        }
    }
}

impl ImpactError {
    /// True for bad input (exit code 2 in the CLI).
    pub fn is_input_error(&self) -> bool {
        match self {
            ImpactError::InvalidParameter { .. } => true,
            ImpactError::Contact(e) => e.is_input_error(),
            ImpactError::Lumped(e) => e.is_input_error(),
            ImpactError::Beam(e) => e.is_input_error(),
            ImpactError::Severity(e) => e.is_input_error(),
            ImpactError::Partial { error, .. } => error.is_input_error(),
            ImpactError::NotFinished { .. }
            | ImpactError::Unfinished { .. }
            | ImpactError::Interrupted => false,
        }
    }

    pub(crate) fn invalid(
        field: impl Into<String>,
        value: impl Quoted,
        allowed: impl Into<String>,
    ) -> Self {
        ImpactError::InvalidParameter {
            field: field.into(),
            value: value.quoted(),
            allowed: allowed.into(),
        }
    }
}

/// A rejected value as an error message quotes it: numbers as
/// [`flexrig_contact::validate::display`] writes them (1e20, not 21 digits), text as it is.
pub(crate) trait Quoted {
    /// The value as quoted in the message.
    fn quoted(&self) -> String;
}

impl Quoted for f64 {
    fn quoted(&self) -> String {
        flexrig_contact::validate::display(*self)
    }
}

impl Quoted for &f64 {
    fn quoted(&self) -> String {
        flexrig_contact::validate::display(**self)
    }
}

macro_rules! quoted_as_text {
    ($($t:ty),*) => {$(
        impl Quoted for $t {
            fn quoted(&self) -> String {
                self.to_string()
            }
        }
    )*};
}
quoted_as_text!(usize, u64, u32, i64, i32, String, &str, &String);
