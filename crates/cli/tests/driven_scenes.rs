//! Driven scenes through the product's fronts: `flexrig run` (text, JSON, MCAP log and its
//! layout, bad input), `flexrig sweep`, and the equality with `flexrig strike`.

use std::path::PathBuf;
use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .unwrap()
}

fn scene_path(name: &str) -> String {
    format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn drive_path(name: &str) -> String {
    format!(
        "{}/../../assets/drives/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-driven-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn json(o: &Output) -> serde_json::Value {
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    serde_json::from_slice(&o.stdout).unwrap()
}

#[test]
fn a_driven_scene_runs_and_equals_the_strike_of_its_drive_file() {
    let run = json(&flexrig(&[
        "run",
        &scene_path("driven_cj_free_head"),
        "--json",
    ]));
    let strike = json(&flexrig(&["strike", &drive_path("cj_free_head"), "--json"]));
    assert_eq!(run["kind"], "driven");
    assert_eq!(run["design"], "cj");
    assert_eq!(run["head"], "free");
    // the same solver on the same description: the same bits
    let peak = run["peak_force_n"].as_f64().unwrap();
    let strike_peak = strike["outcome"]["contact"]["peak_force_n"]
        .as_f64()
        .unwrap();
    assert_eq!(peak, strike_peak, "{strike}");
    for key in [
        "time_of_peak_s",
        "contact_duration_s",
        "impact_velocity_mps",
        "pre_impact_deflection_m",
        "peak_motor_torque_nm",
        "max_indentation_m",
        "impulse_n_s",
        "motor_work_j",
    ] {
        let v = run[key].as_f64().unwrap_or(f64::NAN);
        assert!(v.is_finite(), "{key}: {run}");
    }
    // the text summary names the driven quantities
    let text = flexrig(&["run", &scene_path("driven_cj_wall")]);
    assert!(text.status.success());
    let text = String::from_utf8_lossy(&text.stdout);
    for words in [
        "driven CJ",
        "against a wall",
        "peak force",
        "pre-impact deflection",
        "motor torque peak",
        "contact duration",
    ] {
        assert!(text.contains(words), "{words}: {text}");
    }
}

#[test]
fn bad_driven_values_exit_2_naming_the_field() {
    for (set, field, allowed) in [
        (
            "drive.motor.rotor_inertia=-1",
            "drive.motor.rotor_inertia",
            "[0, 1e9]",
        ),
        (
            "drive.motor.gear_ratio=0",
            "drive.motor.gear_ratio",
            "(0, 1e6]",
        ),
        (
            "drive.command.torque_limit=0.01",
            "drive.command.torque_limit",
            "at least",
        ),
        ("placement.settle=-1", "placement.settle", "[0, 1e6]"),
        (
            "horizon_s=0.1",
            "horizon_s = 0.1",
            "ramp_time + placement.settle = 0.8 s",
        ),
        (
            "drive.motor.gear_ratio=fast",
            "drive.motor.gear_ratio",
            "fast",
        ),
    ] {
        let o = flexrig(&["run", &scene_path("driven_cl_free_head"), "--set", set]);
        assert_eq!(o.status.code(), Some(2), "{set}");
        let e = String::from_utf8_lossy(&o.stderr);
        assert!(e.contains(field) && e.contains(allowed), "{set}: {e}");
        assert!(!e.contains("panicked"), "{e}");
    }
}

#[test]
fn a_driven_log_carries_the_drive_and_a_layout_that_plots_it() {
    let dir = scratch("log");
    let out = dir.join("driven.mcap");
    let run = json(&flexrig(&[
        "run",
        &scene_path("driven_cl_wall"),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    let bytes = std::fs::read(&out).unwrap();
    let summary = mcap::Summary::read(&bytes)
        .unwrap()
        .expect("a finished log");
    let mut counts = std::collections::BTreeMap::<String, u64>::new();
    let mut last = std::collections::BTreeMap::<String, u64>::new();
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        *counts.entry(m.channel.topic.clone()).or_default() += 1;
        let before = last
            .insert(m.channel.topic.clone(), m.log_time)
            .unwrap_or(0);
        assert!(m.log_time >= before);
    }
    let stats = summary.stats.as_ref().unwrap();
    for (id, n) in &stats.channel_message_counts {
        assert_eq!(counts.get(&summary.channels[id].topic), Some(n));
    }
    for topic in [
        "/drive/joint",
        "/drive/command",
        "/drive/torque",
        "/link",
        "/contact",
    ] {
        assert!(counts[topic] > 10, "{topic}: {counts:?}");
    }
    // one message per channel per logged sample
    assert_eq!(counts["/drive/joint"], counts["/contact"]);
    // the layout beside it plots the drive's channels, the contact plots over the contact
    let layout: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("driven.layout.json")).unwrap())
            .unwrap();
    let text = layout.to_string();
    for path in [
        "/drive/command.angle_rad",
        "/drive/joint.angle_rad",
        "/drive/joint.speed_rad_s",
        "/drive/torque.joint_nm",
        "/link.moment_nm",
        "/link.tip_deflection_mm",
        "/contact.force_n",
        "/contact.indentation_mm",
    ] {
        assert!(text.contains(path), "{path}");
    }
    let onset = run["onset_time_s"].as_f64().unwrap();
    let end = onset + run["contact_duration_s"].as_f64().unwrap();
    let force = &layout["configById"]["Plot!force"];
    assert!(force["minXValue"].as_f64().unwrap() <= onset);
    assert!(force["maxXValue"].as_f64().unwrap() >= end);
    // the log's metadata: the scene attached, its kind, the summary
    let mut kinds = Vec::new();
    let mut summary_peak = None;
    for index in &summary.metadata_indexes {
        let record = mcap::read::metadata(&bytes, index).unwrap();
        if record.name == "flexrig" {
            kinds.push(record.metadata["kind"].clone());
        }
        if record.name == "summary" {
            summary_peak = Some(record.metadata["peak_force_n"].parse::<f64>().unwrap());
        }
    }
    assert_eq!(kinds, ["driven"]);
    assert_eq!(summary_peak, run["peak_force_n"].as_f64());
    // a second run does not replace the log without --force
    let again = flexrig(&[
        "run",
        &scene_path("driven_cl_wall"),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(again.status.code(), Some(2));
    independent_python_check(&out);
    let _ = std::fs::remove_dir_all(&dir);
}

fn python() -> String {
    if let Ok(p) = std::env::var("FLEXRIG_PYTHON") {
        return p;
    }
    let venv = format!("{}/../../.venv/bin/python", env!("CARGO_MANIFEST_DIR"));
    if std::path::Path::new(&venv).exists() {
        return venv;
    }
    "python3".into()
}

/// scripts/check_mcap.py on the driven log (the Python `mcap` reader, CRCs, decoding with the
/// stored schemas, the logged peak against the summary's); skipped without the Python packages
/// unless FLEXRIG_REQUIRE_PYTHON is set.
fn independent_python_check(log: &std::path::Path) {
    let python = python();
    let available = Command::new(&python)
        .args(["-c", "import mcap, mcap_protobuf"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !available {
        assert!(
            std::env::var_os("FLEXRIG_REQUIRE_PYTHON").is_none(),
            "FLEXRIG_REQUIRE_PYTHON is set but {python} has no mcap"
        );
        use std::io::Write;
        let _ = writeln!(
            std::io::stderr(),
            "\nSKIPPED the independent check of the driven log: {python} has no mcap"
        );
        return;
    }
    let script = format!("{}/../../scripts/check_mcap.py", env!("CARGO_MANIFEST_DIR"));
    let o = Command::new(&python).arg(script).arg(log).output().unwrap();
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains(", ok;"));
}

#[test]
fn a_sweep_over_the_drive_speed_runs_every_point() {
    let dir = scratch("sweep");
    let out = dir.join("sw");
    let r = json(&flexrig(&[
        "sweep",
        &scene_path("driven_cj_wall"),
        "--set",
        "drive.command.profile.speed=1,2",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(r["rows"], 2, "{r}");
    assert_eq!(r["failed"], 0, "{r}");
    let table = std::fs::read_to_string(r["table"].as_str().unwrap()).unwrap();
    let mut lines = table.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let peak = header.iter().position(|h| *h == "peak_force_n").unwrap();
    let speed = header
        .iter()
        .position(|h| *h == "impact_velocity_mps")
        .unwrap();
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    let value = |row: &Vec<String>, i: usize| row[i].parse::<f64>().unwrap();
    // each point equals the single run with the same override
    let single = json(&flexrig(&[
        "run",
        &scene_path("driven_cj_wall"),
        "--set",
        "drive.command.profile.speed=1",
        "--json",
    ]));
    assert_eq!(
        value(&rows[0], peak),
        single["peak_force_n"].as_f64().unwrap()
    );
    // twice the speed: the link arrives about twice as fast and strikes harder
    assert!(value(&rows[1], speed) > 1.9 * value(&rows[0], speed));
    assert!(value(&rows[1], peak) > 1.5 * value(&rows[0], peak));
    // the driven columns, and the drive's notes as `flexrig run` gives them, in the last column
    for column in [
        "pre_impact_deflection_m",
        "peak_motor_torque_nm",
        "joint_speed_at_contact_rad_s",
        "commanded_tip_speed_mps",
    ] {
        let i = header.iter().position(|h| *h == column).expect(column);
        assert!(value(&rows[0], i).is_finite(), "{column}");
    }
    assert_eq!(header.last(), Some(&"notes"));
    let notes: Vec<String> = single["notes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap().to_string())
        .collect();
    assert!(
        notes.iter().any(|n| n.contains("torque reached its limit"))
            && notes
                .iter()
                .any(|n| n.contains("slower than the commanded")),
        "{notes:?}"
    );
    let jsonl = std::fs::read_to_string(out.join("sweep.jsonl")).unwrap();
    let first: serde_json::Value = serde_json::from_str(jsonl.lines().next().unwrap()).unwrap();
    assert_eq!(first["notes"], notes.join("; "), "{first}");
    let quoted = format!("\"{}\"", notes.join("; "));
    assert!(table.lines().nth(1).unwrap().ends_with(&quoted), "{table}");
    // a value out of range is refused before anything runs, naming the field
    let o = flexrig(&[
        "sweep",
        &scene_path("driven_cj_wall"),
        "--set",
        "drive.motor.gear_ratio=50,0",
        "--out",
        dir.join("bad").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("drive.motor.gear_ratio"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A test-bed scene with a motor on its joint: the sweep's notes are the notes `flexrig run`
/// prints (the torque limit reached), empty for the point whose controller never reached it.
#[test]
fn a_test_bed_sweep_keeps_the_drives_notes_as_run_prints_them() {
    let dir = scratch("rig-notes");
    let out = dir.join("sw");
    let o = flexrig(&[
        "sweep",
        "rig_driven_cj",
        "--set",
        "robot.drive.command.torque_limit=0.2,0.004",
        "--out",
        out.to_str().unwrap(),
        "--json",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let jsonl = std::fs::read_to_string(out.join("sweep.jsonl")).unwrap();
    let rows: Vec<serde_json::Value> = jsonl
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows.len(), 2);
    assert!(rows[0].get("notes").is_none(), "{}", rows[0]);
    let printed = flexrig(&[
        "run",
        "rig_driven_cj",
        "--set",
        "robot.drive.command.torque_limit=0.004",
    ]);
    let text = String::from_utf8_lossy(&printed.stdout);
    let notes: Vec<&str> = text
        .lines()
        .filter_map(|l| l.trim().strip_prefix("note: "))
        .collect();
    assert_eq!(notes.len(), 1, "{text}");
    assert!(notes[0].contains("torque limit"), "{text}");
    assert_eq!(rows[1]["notes"], notes[0], "{}", rows[1]);
    let _ = std::fs::remove_dir_all(&dir);
}
