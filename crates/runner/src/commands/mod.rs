//! One module per `flexrig` command.

pub mod beam;
pub mod bench;
pub mod eta;
pub mod eta_map;
pub mod eta_rotor;
pub mod experiment;
pub mod fig6;
pub mod fit;
pub mod impact;
pub mod payload;
pub mod prb;
pub mod run;
pub mod sweep;
pub mod validate;

use std::io::Write;
use std::path::Path;

use crate::CliError;

/// The main job on bundled defaults: the paper's §VI experiment replayed (Fig. 9) into
/// `out_dir`, with its table and where its files are.
pub fn default_job(
    out_dir: &Path,
    out: &mut dyn Write,
    interrupt: &crate::cli::Interrupt,
) -> Result<(), CliError> {
    let args = experiment::ExperimentArgs {
        repeats: 5,
        jitter_deg: 0.5,
        seed: 1,
        out: out_dir.to_path_buf(),
        scenes: None,
        set: Vec::new(),
        json: false,
    };
    experiment::run(&args, out, interrupt)
}
