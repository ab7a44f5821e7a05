//! One module per `flexrig` command: its clap arguments, their conversion into the library's
//! inputs, the call, and the printed report.

pub mod arm;
pub mod beam;
pub mod bench;
pub mod eta;
pub mod eta_map;
pub mod eta_rotor;
pub mod experiment;
pub mod fig6;
pub mod figure_args;
pub mod fit;
pub mod impact;
pub mod impact_args;
pub mod payload;
pub mod prb;
pub mod role_switch;
pub mod run;
pub mod safety;
pub mod safety_args;
pub mod safety_map;
pub mod safety_trace;
pub mod scenes;
pub mod spin_up;
pub mod strike;
pub mod sweep;
pub mod validate;

use std::io::Write;
use std::path::Path;

use flexrig::{CancelToken, Error};

/// The main job on bundled defaults: the paper's §VI experiment replayed (Fig. 9) into
/// `out_dir`, with its table and where its files are.
pub fn default_job(out_dir: &Path, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let options = flexrig::testbed::experiment::ExperimentOptions::defaults(out_dir.to_path_buf());
    experiment::report(&options, false, out, cancel)
}
