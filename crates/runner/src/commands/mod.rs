//! One module per `flexrig` command.

pub mod beam;
pub mod fig6;
pub mod fit;
pub mod impact;
pub mod prb;
pub mod run;

use std::io::Write;
use std::path::Path;

use crate::CliError;

/// The main job on bundled defaults: the Fig. 6 study into `out_dir`.
pub fn default_job(out_dir: &Path, out: &mut dyn Write) -> Result<(), CliError> {
    let args = fig6::Fig6Args {
        out: out_dir.to_path_buf(),
        points: fig6::DEFAULT_POINTS,
        json: false,
    };
    fig6::run(&args, out)
}
