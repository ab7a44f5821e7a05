//! flexrig: the command-line front end and the experiments built on the flexrig crates.
//!
//! The binary `flexrig` is a thin wrapper around [`cli::run`]; every command lives in its own
//! module under [`commands`] and writes its report to a caller-supplied writer, so commands can be
//! tested and run in parallel in one process (no global state).

pub mod cli;
pub mod commands;
pub mod error;
pub mod mcap_log;
pub mod output;
pub mod plots;
pub mod validation;

pub use error::CliError;
