//! Help and message consistency: one unit style in every `--help`, a broken pipe ends quietly,
//! `sweep --threads`, words instead of Debug values in `sweep merge`, a resumable Ctrl-C
//! message, `impact --gamma` naming exactly the missing flags, the map ranges' syntax, the
//! `fit` millimetre warning and the `prb` report's model, load angle and payload ratio.

use std::io::Read;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .expect("the flexrig binary runs")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = flexrig(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("valid JSON on stdout")
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("flexrig-consistency-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The subcommand names in the `Commands:` section of a help text (without `help`).
fn subcommands(help: &str) -> Vec<String> {
    help.lines()
        .skip_while(|l| l.trim() != "Commands:")
        .skip(1)
        .take_while(|l| l.starts_with("  ") && !l.trim().is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .map(str::to_string)
        .collect()
}

/// Every command path of the CLI, read from its own help (`[]` is `flexrig` itself), so that a
/// command added later is checked too.
fn commands() -> Vec<Vec<String>> {
    let mut found = Vec::new();
    let mut todo: Vec<Vec<String>> = vec![Vec::new()];
    while let Some(path) = todo.pop() {
        let mut args: Vec<&str> = path.iter().map(String::as_str).collect();
        args.push("--help");
        let help = String::from_utf8(flexrig(&args).stdout).unwrap();
        for sub in subcommands(&help) {
            let mut next = path.clone();
            next.push(sub);
            todo.push(next);
        }
        found.push(path);
    }
    found
}

#[test]
fn every_help_writes_units_in_brackets() {
    // the other styles once in use: "(kg)", ", kg.", "(degrees)"
    let paren = regex_free_units();
    let commands = commands();
    for expected in [
        "safety-map",
        "spin-up",
        "role-switch",
        "strike",
        "scenes",
        "merge",
    ] {
        assert!(
            commands
                .iter()
                .any(|c| c.last().is_some_and(|n| n == expected)),
            "{expected} not found in the help: {commands:?}"
        );
    }
    for cmd in &commands {
        let mut args: Vec<&str> = cmd.iter().map(String::as_str).collect();
        args.push("--help");
        let o = flexrig(&args);
        assert!(o.status.success(), "{args:?}");
        let help = String::from_utf8(o.stdout).unwrap();
        for bad in &paren {
            assert!(!help.contains(bad.as_str()), "{args:?}: {bad:?} in\n{help}");
        }
    }
}

/// Unit spellings of the styles replaced by "[unit]".
fn regex_free_units() -> Vec<String> {
    let units = [
        "kg", "m", "s", "N", "N/m", "m/s", "Pa", "rad", "kg·m²", "N·s/m", "Hz", "deg", "degrees",
    ];
    let mut v = Vec::new();
    for u in units {
        v.push(format!(" ({u})"));
        v.push(format!(", {u}."));
        v.push(format!(", {u} ("));
    }
    v
}

#[test]
fn a_broken_pipe_ends_quietly() {
    let dir = scratch_dir("pipe");
    // about a megabyte of JSON: far more than a pipe holds, so the writes meet the closed end
    let mut child = Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(["fig6", "--points", "3000", "--json", "--out"])
        .arg(&dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child
        .stdout
        .as_mut()
        .unwrap()
        .read_exact(&mut first)
        .unwrap();
    drop(child.stdout.take());
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    assert_eq!(status.code(), Some(0), "{stderr}");
    assert!(stderr.is_empty(), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweep_threads_merge_and_interruption_speak_words() {
    let dir = scratch_dir("sweep");
    let out = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let set = "operator.start.release_angle_deg=20,30";
    // one thread gives the table of every core, row for row
    let (a, b) = (out("all"), out("one"));
    json(&["sweep", "cj_iron", "--set", set, "--out", &a, "--json"]);
    json(&[
        "sweep",
        "cj_iron",
        "--set",
        set,
        "--out",
        &b,
        "--threads",
        "1",
        "--json",
    ]);
    assert_eq!(
        std::fs::read_to_string(dir.join("all/sweep.csv")).unwrap(),
        std::fs::read_to_string(dir.join("one/sweep.csv")).unwrap()
    );
    for bad in ["0", "5000"] {
        let o = flexrig(&[
            "sweep",
            "cj_iron",
            "--set",
            set,
            "--out",
            &b,
            "--threads",
            bad,
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains("--threads"), "{stderr}");
    }
    // a merge with a shard missing says which point, in words
    let s = out("shards");
    json(&[
        "sweep", "cj_iron", "--set", set, "--out", &s, "--shard", "0/2", "--json",
    ]);
    let o = flexrig(&["sweep", "merge", &s]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("1 of 2 points are missing, the first is point 1")
            && !stderr.contains("Some("),
        "{stderr}"
    );
    // an interrupted sweep says how to resume it, and exits as interrupted
    let report = flexrig::study::SweepReport {
        table: PathBuf::from("out/sweep/sweep.csv"),
        rows: 3,
        points: 10,
        resumed: 0,
        failed: 0,
        interrupted: true,
    };
    let e = report.check().unwrap_err();
    assert_eq!(e.exit_code(), 130);
    let text = e.to_string();
    assert!(
        text.contains("3 of 10 runs") && text.contains("run the same command again to resume"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn impact_names_exactly_the_missing_flags() {
    let base = [
        "impact",
        "--m-h",
        "4",
        "--k-delta",
        "1e8",
        "--k-c",
        "1e8",
        "--n",
        "1",
        "--v0",
        "2",
    ];
    for (given, missing, not_missing) in [
        (vec!["--gamma", "1"], "--m-r and --m-e", "--gamma and"),
        (
            vec!["--gamma", "1", "--m-r", "10"],
            "add --m-e",
            "--m-eff <",
        ),
        (vec!["--m-e", "0.1"], "add --gamma and --m-r", "--m-eff <"),
    ] {
        let mut args = base.to_vec();
        args.extend(given.iter());
        let o = flexrig(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(missing), "{given:?}: {stderr}");
        assert!(!stderr.contains(not_missing), "{given:?}: {stderr}");
    }
    // complete sets still run: Eq. 13, f = v0 √(k_o μ)
    let mut args = base.to_vec();
    args.extend([
        "--gamma", "1", "--m-r", "10", "--m-e", "0.1", "--method", "analytic", "--json",
    ]);
    let f = json(&args)["f_max_n"].as_f64().unwrap();
    let m_eff = 0.1 + 10.0 / 3.0;
    let mu: f64 = 4.0 * m_eff / (4.0 + m_eff);
    let expected = 2.0 * (5e7 * mu).sqrt();
    assert!((f / expected - 1.0).abs() < 1e-12, "{f} vs {expected}");
}

#[test]
fn map_ranges_take_the_one_range_syntax() {
    let dir = scratch_dir("ranges");
    let out = dir.to_str().unwrap();
    let v = json(&[
        "eta-map",
        "--m-h",
        "4",
        "--points",
        "2",
        "--mass-ratio",
        "1e-2:1:3:log",
        "--out",
        out,
        "--json",
    ]);
    assert_eq!(v["maps"][0]["points"], 6);
    let o = flexrig(&[
        "eta-map",
        "--m-h",
        "4",
        "--mass-ratio",
        "1e-2:1:3",
        "--out",
        out,
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--mass-ratio") && stderr.contains("log-spaced"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fit_warns_of_millimetres() {
    let dir = scratch_dir("fit");
    // the paper's aluminium law, f = 7.359e7 δ^1.961, sampled in metres and in millimetres
    let (k, n) = (7.359e7, 1.961);
    let mut metres = String::from("indentation_m,force_n\n");
    let mut millimetres = metres.clone();
    for i in 1..=20 {
        let d = 2e-4 * f64::from(i);
        let f = k * f64::powf(d, n);
        metres.push_str(&format!("{d},{f}\n"));
        millimetres.push_str(&format!("{},{f}\n", d * 1000.0));
    }
    let (good, bad) = (dir.join("m.csv"), dir.join("mm.csv"));
    std::fs::write(&good, metres).unwrap();
    std::fs::write(&bad, millimetres).unwrap();
    let o = flexrig(&["fit", good.to_str().unwrap(), "--json"]);
    assert!(o.status.success() && o.stderr.is_empty());
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["warnings"], serde_json::json!([]));
    assert!((v["k"].as_f64().unwrap() / k - 1.0).abs() < 1e-6, "{v}");
    let o = flexrig(&["fit", bad.to_str().unwrap(), "--json"]);
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("warning: indentation_m") && stderr.contains("millimetres"),
        "{stderr}"
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["warnings"][0]["field"], "indentation_m");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn prb_names_its_model_load_angle_and_payload_ratios() {
    let dir = scratch_dir("prb");
    let out = dir.to_str().unwrap();
    for (model, label) in [
        ("corotational", "corotational FE tip path"),
        ("ancf", "ANCF FE tip path"),
    ] {
        let o = flexrig(&["prb", "--elements", "8", "--model", model, "--out", out]);
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(text.contains(label), "{text}");
        assert!(text.contains("90° to the undeformed beam"), "{text}");
        // the paper's light load 0.1 kg and test payload 0.412 kg on m_r = 51 g
        assert!(
            text.contains("m_e/m_r = 1.961") && text.contains("m_e/m_r = 8.078"),
            "{text}"
        );
        let svg = std::fs::read_to_string(dir.join("prb.svg")).unwrap();
        assert!(svg.contains(label), "figure legend");
    }
    let v = json(&["prb", "--elements", "8", "--out", out, "--json"]);
    assert_eq!(v["load_angle_deg"], 90.0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn ranges_in_messages_carry_their_unit_and_no_exponent_of_zero() {
    let dir = scratch_dir("units");
    let out = dir.to_str().unwrap();
    let cases: [(&[&str], &[&str]); 3] = [
        // a link mass given in grams: the range in kg and the conversion
        (
            &["fig6", "--m-r", "51000", "--out", out],
            &[
                "--m-r",
                "must lie in [0.001, 10000] kg",
                "did you give grams? 51000 g is 51 kg",
            ],
        ),
        (
            &[
                "eta",
                "--damping",
                "hunt-crossley",
                "--restitution",
                "2",
                "--out",
                out,
            ],
            &["--restitution", "must lie in [0, 1]"],
        ),
        (
            &[
                "beam",
                "static",
                "--length",
                "0.3",
                "--youngs",
                "7e10",
                "--width",
                "0.01",
                "--thickness",
                "0.001",
                "--tip-load",
                "1",
                "--tip-mass",
                "-1",
            ],
            &["--tip-mass", "must lie in [0, 1e6] kg"],
        ),
    ];
    for (args, expected) in cases {
        let o = flexrig(args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        for e in expected {
            assert!(stderr.contains(e), "{args:?}: '{e}' not in {stderr}");
        }
        assert!(!stderr.contains("0e0"), "{args:?}: {stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn list_defaults_show_as_the_lists_they_are() {
    // a comma-separated list's default in the help reads as one would type it
    for (cmd, default) in [
        (&["eta-map"][..], "[default: 4,1000]"),
        (&["fig6"][..], "[default: 1e8,200]"),
        (&["eta-rotor"][..], "[default: 1,2]"),
        (&["role-switch"][..], "[default: 10000,100,1,0.01]"),
    ] {
        let mut args = cmd.to_vec();
        args.push("--help");
        let help = String::from_utf8(flexrig(&args).stdout).unwrap();
        assert!(help.contains(default), "{cmd:?}: {default} not in\n{help}");
        assert!(!help.contains("[default: 4 1000]"), "{cmd:?}\n{help}");
    }
}

#[test]
fn a_scene_whose_design_was_set_is_named_by_the_design_that_ran() {
    let o = flexrig(&["run", "cj_aluminium", "--set", "robot.design=cl"]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let first = stdout.lines().next().unwrap_or_default();
    assert_eq!(
        first, "scene cl_aluminium (scene cj_aluminium, design set to CL)",
        "{stdout}"
    );
    let o = flexrig(&["run", "cj_aluminium"]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(
        stdout.lines().next(),
        Some("scene cj_aluminium (CJ)"),
        "{stdout}"
    );
}

#[test]
fn a_list_given_with_spaces_is_answered_with_the_comma_list() {
    let o = flexrig(&[
        "eta-map",
        "--m-h",
        "4",
        "1000",
        "--out",
        "/nonexistent-never-written",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("unexpected argument '1000'"), "{err}");
    assert!(err.contains("--m-h 4,1000"), "{err}");
    // a stray word is not a list: no tip
    let o = flexrig(&["eta-map", "--m-h", "4", "oops"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!String::from_utf8_lossy(&o.stderr).contains("tip:"));
}
