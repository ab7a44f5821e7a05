//! `flexrig scenes`: the bundled scenes with a one-line description each, and `--write NAME`
//! to copy one out for editing ([`flexrig::testbed::scenes`]).

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::Error;
use flexrig::testbed::scenes::{list_bundled, write_bundled};
use serde_json::json;

use crate::print::{line, print_json};

/// Arguments of `flexrig scenes`.
#[derive(Debug, Args)]
pub struct ScenesArgs {
    /// Write the bundled scene NAME's TOML file, to edit and run with `flexrig run FILE`.
    #[arg(long, value_name = "NAME")]
    pub write: Option<String>,
    /// File the scene is written to (default: NAME.toml in the current directory).
    #[arg(long, value_name = "FILE.toml", requires = "write")]
    pub out: Option<PathBuf>,
    /// Overwrite the --out file if it exists.
    #[arg(long, requires = "write")]
    pub force: bool,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `flexrig scenes`.
pub fn run(args: &ScenesArgs, out: &mut dyn Write) -> Result<(), Error> {
    if let Some(name) = &args.write {
        let path = args
            .out
            .clone()
            .unwrap_or_else(|| PathBuf::from(format!("{name}.toml")));
        write_bundled(name, &path, args.force)?;
        return if args.json {
            print_json(out, &json!({ "scene": name, "written": path }))
        } else {
            line(
                out,
                format!(
                    "Wrote {}: edit it, then `flexrig run {}`",
                    path.display(),
                    path.display()
                ),
            )
        };
    }
    let scenes = list_bundled();
    if args.json {
        return print_json(out, &json!({ "scenes": scenes }));
    }
    let width = scenes.iter().map(|s| s.name.len()).max().unwrap_or(0);
    line(
        out,
        "Bundled scenes (give the name wherever a scene is asked for, e.g. `flexrig run \
         cj_aluminium`; `flexrig scenes --write NAME` writes one to edit):",
    )?;
    for s in &scenes {
        line(out, format!("  {:<width$}  {}", s.name, s.summary))?;
    }
    Ok(())
}
