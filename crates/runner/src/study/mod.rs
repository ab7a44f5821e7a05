//! Studies over many runs: sweeps of a base scene over dotted scene paths, in parallel, into one
//! tidy table; shards for a cluster and their merge. The library side shared by the `flexrig`
//! CLI and the Python package (argument parsing and printing live in `commands`).

pub mod spec;
pub mod sweep;

pub use spec::Dimension;
pub use sweep::{Sweep, SweepOptions, SweepRow};
