//! flexrig: the command-line front end and the experiments built on the flexrig crates.
//!
//! The binary `flexrig` is a thin wrapper around [`cli::run`]; every command lives in its own
//! module under [`commands`] and writes its report to a caller-supplied writer, so commands can be
//! tested and run in parallel in one process (no global state).

//!
//! ```
//! use clap::Parser;
//! // The same as `flexrig impact ... --json` on the command line, run in-process.
//! let cli = flexrig::cli::Cli::parse_from([
//!     "flexrig", "impact", "--m-h", "4", "--m-eff", "3.4333", "--k-delta", "1e8", "--k-c", "1e8",
//!     "--n", "1", "--v0", "2", "--method", "analytic", "--json",
//! ]);
//! let mut out = Vec::new();
//! flexrig::cli::run(&cli, &mut out).unwrap();
//! let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
//! assert!(v["f_max_n"].as_f64().unwrap() > 19_000.0);
//! ```

pub mod cli;
pub mod commands;
pub mod error;
pub mod foxglove_layout;
pub mod mcap_log;
pub mod output;
pub mod plots;
pub mod study;
pub mod traces;
pub mod validation;

pub use error::CliError;
