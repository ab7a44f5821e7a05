//! Studies over many runs: sweeps of a base scene over dotted scene paths, in parallel, into one
//! tidy table; shards for a cluster and their merge. The library side shared by the `flexrig`
//! CLI and the Python package.

pub mod run;
pub mod spec;
pub mod sweep;

pub use run::{SweepReport, SweepRequest, parse_dimensions, run_sweep};
pub use spec::Dimension;
pub use sweep::{Sweep, SweepOptions, SweepRow};
