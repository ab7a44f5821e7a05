//! `flexrig sweep`: the table against single runs, shards + merge = the whole sweep, resume,
//! failed runs as rows, bad input refused before anything is written.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .unwrap()
}

fn scene(name: &str) -> String {
    format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A quick sweep: CJ and CL from contact to the peak over three release angles.
fn sweep_args<'a>(out: &'a Path, extra: &[&'a str]) -> Vec<String> {
    let mut args: Vec<String> = [
        "sweep",
        &scene("cj_iron"),
        "--set",
        "operator.start.release_angle_deg=20:40:3",
        "--set",
        "robot.design=cj,cl",
        "--set",
        "operator.start.from=contact",
        "--set",
        "stop={ at = \"peak\" }",
        "--out",
        out.to_str().unwrap(),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn run(args: &[String]) -> Output {
    flexrig(&args.iter().map(String::as_str).collect::<Vec<_>>())
}

#[test]
fn the_table_has_a_row_per_point_equal_to_single_runs() {
    let dir = scratch("table");
    let o = run(&sweep_args(&dir, &["--json"]));
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 7, "{csv}");
    assert!(lines[0].starts_with("index,operator.start.release_angle_deg,robot.design"));
    // row 3: 30°, cl — the same as `flexrig run --set …`
    let single = flexrig(&[
        "run",
        &scene("cj_iron"),
        "--set",
        "operator.start.release_angle_deg=30.0",
        "--set",
        "robot.design=cl",
        "--set",
        "operator.start.from=contact",
        "--set",
        "stop={ at = \"peak\" }",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&single.stdout).unwrap();
    let peak = v["peak_force_n"].as_f64().unwrap();
    let row: Vec<&str> = lines[4].split(',').collect();
    assert_eq!(&row[..3], &["3", "30.0", "cl"], "{}", lines[4]);
    let header: Vec<&str> = lines[0].split(',').collect();
    let col = header.iter().position(|c| *c == "peak_force_n").unwrap();
    // the table holds the value to all its digits (one more column: the quoted stop table)
    let cells: Vec<String> = {
        let mut out = Vec::new();
        let mut cell = String::new();
        let mut quoted = false;
        for c in lines[4].chars() {
            match c {
                '"' => quoted = !quoted,
                ',' if !quoted => out.push(std::mem::take(&mut cell)),
                c => cell.push(c),
            }
        }
        out.push(cell);
        out
    };
    assert_eq!(cells[col].parse::<f64>().unwrap(), peak);
    // JSON Lines too
    let jsonl = std::fs::read_to_string(dir.join("sweep.jsonl")).unwrap();
    let third: serde_json::Value = serde_json::from_str(jsonl.lines().nth(3).unwrap()).unwrap();
    assert_eq!(third["peak_force_n"].as_f64().unwrap(), peak);
    assert_eq!(third["robot.design"], "cl");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn shards_merged_equal_the_whole_sweep_and_a_rerun_resumes() {
    let whole = scratch("whole");
    assert!(run(&sweep_args(&whole, &[])).status.success());
    let sharded = scratch("sharded");
    for shard in ["0/2", "1/2"] {
        let o = run(&sweep_args(&sharded, &["--shard", shard]));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let o = flexrig(&["sweep", "merge", sharded.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let a = std::fs::read_to_string(whole.join("sweep.csv")).unwrap();
    let b = std::fs::read_to_string(sharded.join("sweep.csv")).unwrap();
    assert_eq!(a, b, "deterministic: shards merged = the whole sweep");
    // Resume: drop two rows from the table; the rerun runs only those and gives the same table.
    let kept: Vec<&str> = a
        .lines()
        .enumerate()
        .filter(|(i, _)| *i != 2 && *i != 5)
        .map(|(_, l)| l)
        .collect();
    std::fs::write(whole.join("sweep.csv"), kept.join("\n") + "\n").unwrap();
    let o = run(&sweep_args(&whole, &["--json"]));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["resumed"], 4, "{v}");
    assert_eq!(std::fs::read_to_string(whole.join("sweep.csv")).unwrap(), a);
    // A different sweep in the same directory is refused, not mixed.
    let o = flexrig(&[
        "sweep",
        &scene("cj_iron"),
        "--set",
        "robot.payload_kg=0.1,0.2",
        "--out",
        whole.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("another sweep"));
    let _ = std::fs::remove_dir_all(&whole);
    let _ = std::fs::remove_dir_all(&sharded);
}

#[test]
fn a_failed_run_is_a_row_and_the_exit_status_counts_failures() {
    // max_steps = 50 cannot reach the peak: every run fails, each a row with its error.
    let dir = scratch("failed");
    let o = run(&sweep_args(&dir, &["--set", "solver.max_steps=50,1000000"]));
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("6 of 12 runs failed"), "{stderr}");
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    assert_eq!(
        csv.lines()
            .skip(1)
            .filter(|l| l.contains(",error,"))
            .count(),
        6
    );
    assert!(csv.contains("solver.max_steps"), "{csv}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_sweeps_are_refused_before_anything_is_written() {
    let dir = scratch("bad");
    for (set, named) in [
        ("robot.no_such=1,2", "robot.no_such"),
        ("robot.payload_kg=1:2:0", "--set robot.payload_kg"),
        ("robot.payload_kg=heavy,light", "robot.payload_kg"),
        ("robot.payload_kg", "--set"),
    ] {
        let o = flexrig(&[
            "sweep",
            &scene("cj_iron"),
            "--set",
            set,
            "--out",
            dir.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {stderr}");
        assert!(stderr.contains(named), "{set}: {stderr}");
        assert!(
            !dir.join("sweep.csv").exists(),
            "{set}: a table was written"
        );
    }
    let o = run(&sweep_args(&dir, &["--shard", "3/2"]));
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--shard"));
    let o = run(&sweep_args(
        &dir,
        &["--zip", "--set", "robot.payload_kg=0.1,0.2"],
    ));
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--zip"));
    let _ = std::fs::remove_dir_all(&dir);
}
