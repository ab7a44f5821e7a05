//! `flexrig sweep BASE --set PATH=SPEC ...` and `flexrig sweep merge DIR`: the CLI over
//! [`crate::study`].

use std::io::{IsTerminal, Write};
use std::path::PathBuf;

use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::CliError;
use crate::cli::Interrupt;
use crate::output::{ensure_dir, line, print_json, read_text, write_atomic};
use crate::study::spec::Dimension;
use crate::study::sweep::{
    Journal, Sweep, SweepManifest, SweepOptions, merge, rows_done, write_tables,
};

/// Arguments of `flexrig sweep`.
#[derive(Debug, Args)]
#[command(args_conflicts_with_subcommands = true)]
pub struct SweepArgs {
    /// `merge DIR` joins the shard tables of a sweep.
    #[command(subcommand)]
    pub merge: Option<SweepCommand>,
    /// The base scene (TOML), e.g. assets/scenes/cj_iron.toml.
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
    /// Directory of the table (sweep.csv), its manifest and journal; a rerun resumes.
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

fn parse_shard(text: &str) -> Result<(usize, usize), CliError> {
    let bad = || CliError::InvalidArgument {
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
pub fn run(args: &SweepArgs, out: &mut dyn Write, interrupt: &Interrupt) -> Result<(), CliError> {
    if let Some(SweepCommand::Merge { dir, json }) = &args.merge {
        let (path, rows) = merge(dir, *json)?;
        return if args.json {
            print_json(out, &serde_json::json!({ "table": path, "rows": rows }))
        } else {
            line(out, format!("merged {rows} rows into {}", path.display()))
        };
    }
    let Some(base_path) = &args.base else {
        return Err(CliError::InvalidArgument {
            arg: "BASE".into(),
            value: "(missing)".into(),
            allowed: "give a base scene file, or `merge DIR`".into(),
        });
    };
    let shard = args.shard.as_deref().map(parse_shard).transpose()?;
    let base_dir = base_path.parent().map(PathBuf::from).unwrap_or_default();
    let read =
        |file: &str| read_text(&base_dir.join(file)).or_else(|_| read_text(&PathBuf::from(file)));
    let dimensions = args
        .set
        .iter()
        .map(|s| Dimension::parse(s, &read))
        .collect::<Result<Vec<_>, _>>()?;
    let sweep = Sweep::new(&read_text(base_path)?, dimensions, args.zip)?;
    let paths = sweep.paths();
    let manifest = SweepManifest {
        fingerprint: sweep.fingerprint(),
        paths: paths.iter().map(|p| p.to_string()).collect(),
        points: sweep.len(),
    };
    ensure_dir(&args.out)?;
    let mut rows = rows_done(&args.out, shard, &manifest)?;
    write_atomic(
        &args.out.join("sweep.json"),
        serde_json::to_string_pretty(&manifest)
            .expect("a manifest serialises")
            .as_bytes(),
    )?;
    let todo: Vec<usize> = sweep
        .indices(shard)
        .into_iter()
        .filter(|i| !rows.contains_key(i))
        .collect();
    let mcap_dir = args.out.join("runs");
    if args.mcap {
        ensure_dir(&mcap_dir)?;
    }
    let options = SweepOptions {
        shard,
        mcap_dir: args.mcap.then_some(mcap_dir),
        interrupt: interrupt.0.clone(),
    };
    let progress = ProgressBar::with_draw_target(
        Some(todo.len() as u64),
        if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        },
    )
    .with_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} runs, {eta} left {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let journal = Journal::open(&args.out, shard, &paths)?;
    let skipped = rows.len();
    let new_rows = sweep.run(&todo, &options, &|row| {
        journal.append(row);
        progress.inc(1);
    });
    progress.finish_and_clear();
    let interrupted = interrupt.0.load(std::sync::atomic::Ordering::Relaxed)
        || new_rows.iter().any(|r| r.status == "interrupted");
    rows.extend(
        new_rows
            .into_iter()
            .filter(|r| r.status != "interrupted")
            .map(|r| (r.index, r)),
    );
    let table = write_tables(&args.out, shard, &paths, &rows, args.json)?;
    let total = sweep.indices(shard).len();
    if rows.len() == total {
        journal.remove();
    }
    let failed = rows.values().filter(|r| r.status != "ok").count();
    if args.json {
        print_json(
            out,
            &serde_json::json!({
                "table": table,
                "rows": rows.len(),
                "points": total,
                "resumed": skipped,
                "failed": failed,
            }),
        )?;
    } else {
        line(
            out,
            format!(
                "{} of {total} runs in {} ({skipped} from an earlier run, {failed} failed)",
                rows.len(),
                table.display()
            ),
        )?;
    }
    if interrupted {
        return Err(CliError::Rig(flexrig_rig::RigError::Interrupted { t: 0.0 }));
    }
    if failed > 0 {
        return Err(CliError::SweepFailed {
            failed,
            total,
            table,
        });
    }
    Ok(())
}
