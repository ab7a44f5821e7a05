//! flexrig's checks of itself that a user can run: the canonical problems against their
//! references (`flexrig validate`, [`validation`]) and the benchmarks (`flexrig bench`,
//! [`bench`]).
//!
//! May use: every folder below the fronts.

pub mod bench;
pub mod validation;

#[cfg(test)]
mod figures_print;
