//! flexrig-cli: the `flexrig` command line over the [`flexrig`] library. Each command's module
//! under [`commands`] holds its clap arguments, turns them into the library's typed inputs, calls
//! the library and prints its result (a table or JSON) to a caller-supplied writer, so commands
//! can be tested in-process; [`cli`] dispatches, `main.rs` wires Ctrl-C and the exit codes.
//!
//! ```
//! use clap::Parser;
//! // The same as `flexrig impact ... --json` on the command line, run in-process.
//! let cli = flexrig_cli::cli::Cli::parse_from([
//!     "flexrig", "impact", "--m-h", "4", "--m-eff", "3.4333", "--k-delta", "1e8", "--k-c", "1e8",
//!     "--n", "1", "--v0", "2", "--method", "analytic", "--json",
//! ]);
//! let mut out = Vec::new();
//! flexrig_cli::cli::run(&cli, &mut out).unwrap();
//! let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
//! assert!(v["f_max_n"].as_f64().unwrap() > 19_000.0);
//! ```

pub mod cli;
pub mod commands;
pub mod print;
