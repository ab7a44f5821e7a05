//! What every concept of the library shares, below all of them: the one error type and its kind
//! ([`error`]), stopping a computation ([`cancel`]), progress of many runs ([`progress`]), files
//! written whole or not at all and numbers as printed ([`output`]), the plausibility warnings of
//! typed masses, lengths and speeds ([`plausibility`]), and the severity of an impact
//! (peak force, pressure, HIC, transferred energy) filled into every run's result ([`severity`]).
//!
//! May use: the physics crates only — no other folder of the library.

pub mod cancel;
pub mod error;
pub mod output;
pub mod plausibility;
pub mod progress;
pub mod severity;
