//! `flexrig sweep BASE --set PATH=SPEC ...` and `flexrig sweep merge DIR`: the CLI over
//! [`flexrig::study`].

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, Subcommand};
use flexrig::study::sweep::merge;
use flexrig::study::{SweepRequest, parse_dimensions, run_sweep};
use flexrig::{CancelToken, Error};

use crate::print::{Bar, line, print_json};

/// Arguments of `flexrig sweep`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct SweepArgs {
    /// `merge DIR` joins the shard tables of a sweep.
    #[command(subcommand)]
    pub merge: Option<SweepCommand>,
    /// The base scene: a bundled scene's name (e.g. cj_iron; `flexrig scenes` lists them) or a
    /// scene file's path.
    #[arg(value_name = "BASE")]
    pub base: Option<PathBuf>,
    /// A varied field: PATH=SPEC with SPEC a list (0.1,0.2,0.5 or cj,cl), a range
    /// (10:60:11, both ends included; 1e-3:1:25:log), a file (@values.txt) or a value.
    /// Repeatable; the points are the full grid (or --zip).
    #[arg(long = "set", value_name = "PATH=SPEC")]
    pub set: Vec<String>,
    /// Zip the --set lists (same length) instead of the full grid.
    #[arg(long)]
    pub zip: bool,
    /// Directory for the table (sweep.csv), its manifest and journal (created if missing); a
    /// rerun of the same command resumes.
    #[arg(long, value_name = "DIR", default_value = "out/sweep")]
    pub out: PathBuf,
    /// Also write JSON Lines (sweep.jsonl) and print the summary as JSON.
    #[arg(long)]
    pub json: bool,
    /// Keep an MCAP log per run (DIR/runs/run-<index>.mcap, its Foxglove layout beside it).
    #[arg(long)]
    pub mcap: bool,
    /// Run only shard I of N (points with index ≡ I mod N), e.g. 0/4; merge the shards with
    /// `flexrig sweep merge DIR`.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Threads running points (1 to 4096; default: every core).
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

/// `flexrig sweep merge`.
#[derive(Debug, Subcommand)]
pub enum SweepCommand {
    /// Join the shard tables of DIR into DIR/sweep.csv (every point exactly once).
    Merge {
        /// The sweep directory (--out of the shards).
        #[arg(value_name = "DIR")]
        dir: PathBuf,
        /// Also write sweep.jsonl.
        #[arg(long)]
        json: bool,
    },
}

fn parse_shard(text: &str) -> Result<(usize, usize), Error> {
    let bad = || Error::InvalidArgument {
        arg: "--shard".into(),
        value: text.into(),
        allowed: "must be I/N with 0 <= I < N, e.g. 0/4".into(),
    };
    let (i, n) = text.split_once('/').ok_or_else(bad)?;
    let (i, n): (usize, usize) = (
        i.trim().parse().map_err(|_| bad())?,
        n.trim().parse().map_err(|_| bad())?,
    );
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// Runs `flexrig sweep`.
pub fn run(args: &SweepArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    if let Some(SweepCommand::Merge { dir, json }) = &args.merge {
        let (path, rows) = merge(dir, *json)?;
        return if args.json {
            print_json(out, &serde_json::json!({ "table": path, "rows": rows }))
        } else {
            line(out, format!("merged {rows} rows into {}", path.display()))
        };
    }
    let Some(base_path) = &args.base else {
        return Err(Error::InvalidArgument {
            arg: "BASE".into(),
            value: "(missing)".into(),
            allowed: "give a base scene file, or `merge DIR`".into(),
        });
    };
    let shard = args.shard.as_deref().map(parse_shard).transpose()?;
    let request = SweepRequest {
        base: base_path.clone(),
        dimensions: parse_dimensions(&args.set, base_path, args.zip)?,
        zip: args.zip,
        out: args.out.clone(),
        jsonl: args.json,
        mcap: args.mcap,
        shard,
        threads: args.threads,
    };
    let bar = Bar::on_terminal("{bar:30} {pos}/{len} runs, {eta} left {msg}");
    let r = run_sweep(&request, cancel, &bar)?;
    if args.json {
        print_json(out, &flexrig::fronts::sweep_report(&r))?;
    } else {
        line(
            out,
            format!(
                "{} of {} runs in {} ({} from an earlier run, {} failed)",
                r.rows,
                r.points,
                r.table.display(),
                r.resumed,
                r.failed
            ),
        )?;
    }
    r.check()
}
