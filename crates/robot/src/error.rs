//! Errors of the robot crate. Every variant says, in plain words, where the problem is (the file,
//! the URDF element with its name and line, or the CSV line) and what is allowed.

/// Everything the robot crate can fail with.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RobotError {
    /// A file could not be read.
    #[error("cannot read {path}: {reason}")]
    Io {
        /// The path as given.
        path: String,
        /// The operating system's reason.
        reason: String,
    },
    /// A file is larger than the crate reads (bounded memory for untrusted input).
    #[error("{path} is {bytes} bytes long; at most {max} bytes are read (is it really a {what}?)")]
    FileTooLarge {
        /// The path as given.
        path: String,
        /// Its size in bytes.
        bytes: u64,
        /// The largest size read, in bytes.
        max: u64,
        /// `URDF file` or `trajectory CSV`.
        what: &'static str,
    },
    /// The file is not well-formed XML (or uses a DTD, which is refused).
    #[error("{source_name}, line {line}, column {column}: not well-formed XML: {reason}")]
    Xml {
        /// The file name (or `<string>`).
        source_name: String,
        /// 1-based line.
        line: u32,
        /// 1-based column.
        column: u32,
        /// The XML parser's message.
        reason: String,
    },
    /// A URDF element is invalid or unsupported: names the element, its line and what is allowed.
    #[error("{source_name}, line {line}, {element}: {problem}")]
    Urdf {
        /// The file name (or `<string>`).
        source_name: String,
        /// 1-based line of the element.
        line: u32,
        /// The element, e.g. `joint "panda_joint2"` or `link "base" <inertia>`.
        element: String,
        /// What is wrong and what is allowed.
        problem: String,
    },
    /// A trajectory CSV line is invalid: names the line and what is allowed.
    #[error("{source_name}, line {line}: {problem}")]
    Csv {
        /// The file name (or `<string>`).
        source_name: String,
        /// 1-based line (0 when the problem is with the file as a whole).
        line: usize,
        /// What is wrong and what is allowed.
        problem: String,
    },
    /// A numeric argument is outside its allowed range.
    #[error("{field} = {value} is not allowed: {allowed}")]
    Parameter {
        /// The argument, e.g. `q[3] (elbow_joint)` or `direction`.
        field: String,
        /// The rejected value, as text.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A link name that the robot does not have.
    #[error("robot {robot:?} has no link {name:?}; its links are {known}")]
    UnknownLink {
        /// The robot's name.
        robot: String,
        /// The requested link.
        name: String,
        /// Comma-separated link names.
        known: String,
    },
    /// The joint-space mass matrix is not positive definite at this posture (a joint moves no
    /// inertia), so the Cholesky factorisation stops at that joint.
    #[error(
        "the mass matrix is not positive definite at joint {joint:?} (pivot {pivot:e}): the \
         joint moves no inertia at this posture; give the links it moves a mass and an inertia"
    )]
    NotPositiveDefinite {
        /// The joint at which the factorisation failed.
        joint: String,
        /// The pivot found (≤ 0 or negligible against the diagonal).
        pivot: f64,
    },
    /// The contact point does not move, so no direction can be taken from its velocity.
    #[error(
        "the contact point on link {link:?} does not move at these joint velocities (speed \
         {speed:e} m/s); give the direction explicitly"
    )]
    PointAtRest {
        /// The contact point's link.
        link: String,
        /// Its speed, m/s.
        speed: f64,
    },
}

impl RobotError {
    /// A [`RobotError::Parameter`] from displayable parts.
    pub(crate) fn parameter(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        RobotError::Parameter {
            field: field.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}
