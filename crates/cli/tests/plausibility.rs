//! The same plausibility rule on every front that takes a robot's masses, lengths and speeds:
//! scenes (`flexrig run`, the test bed's and the driven ones), `strike`, `safety` and
//! `safety-map`. A slip gets the same words on each, in the text (standard error, `warning:
//! FIELD: MESSAGE`) and in the JSON (`warnings`, each with the `field` or flag it is about); the
//! numbers in the message are recomputed here (grams read as kilograms: 250 g = 0.25 kg).

use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .expect("the flexrig binary runs")
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "flexrig-plausibility-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The warnings of a command: from its text run (standard error) and its `--json` run, as
/// (field, message) pairs; both must agree and the runs succeed.
fn warnings(args: &[&str]) -> Vec<(String, String)> {
    let text = flexrig(args);
    assert!(
        text.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&text.stderr)
    );
    let mut with_json = args.to_vec();
    with_json.push("--json");
    let json = flexrig(&with_json);
    assert!(
        json.status.success(),
        "{args:?} --json: {}",
        String::from_utf8_lossy(&json.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&json.stdout).expect("JSON on stdout");
    let listed: Vec<(String, String)> = v["warnings"]
        .as_array()
        .unwrap_or_else(|| panic!("{args:?}: a warnings list in {v}"))
        .iter()
        .map(|w| {
            (
                w["field"].as_str().unwrap().to_string(),
                w["message"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    let stderr = String::from_utf8_lossy(&text.stderr);
    for (field, message) in &listed {
        assert!(
            stderr.contains(&format!("warning: {field}: {message}")),
            "{args:?}: the text run does not warn {field}: {message}\n{stderr}"
        );
    }
    listed
}

fn message_of<'a>(found: &'a [(String, String)], field: &str) -> &'a str {
    found
        .iter()
        .find(|(f, _)| f == field)
        .map(|(_, m)| m.as_str())
        .unwrap_or_else(|| panic!("no warning about {field}: {found:?}"))
}

/// 250 kg typed for a payload (250 g meant): the same message on the five fronts.
#[test]
fn a_mass_slip_gets_the_same_warning_on_every_front() {
    let dir = scratch("mass");
    let map_out = dir.join("map");
    let map_out = map_out.to_str().unwrap();
    let expected = "250 kg is heavier than a robot near a person moves (up to about 200 kg); \
                    if grams were meant, 250 g is 0.25 kg";
    let fronts: [(Vec<&str>, &str); 5] = [
        (
            vec!["run", "cj_aluminium", "--set", "robot.payload_kg=250"],
            "robot.payload_kg",
        ),
        (
            vec![
                "run",
                "driven_cj_free_head",
                "--set",
                "link.m_e=250",
                "--set",
                "drive.command.torque_limit=1000",
            ],
            "link.m_e",
        ),
        (vec!["strike", "--m-e", "250"], "--m-e"),
        (
            vec![
                "safety",
                "--region",
                "chest",
                "--m-r",
                "0.051",
                "--m-e",
                "250",
                "--gamma",
                "1",
                "--k-delta",
                "1e4",
                "--material",
                "skinned_aluminium",
                "--method",
                "standard,energy",
            ],
            "--m-e",
        ),
        (
            vec![
                "safety-map",
                "--region",
                "chest",
                "--m-r",
                "0.051",
                "--m-e",
                "250",
                "--x",
                "k-c=1e7:1e8:2",
                "--y",
                "k-delta=10:1e7:2:log",
                "--method",
                "energy",
                "--out",
                map_out,
            ],
            "--m-e",
        ),
    ];
    for (args, field) in fronts {
        let found = warnings(&args);
        assert_eq!(message_of(&found, field), expected, "{args:?}");
    }
    // a mass axis of the map that reaches the slip is named by its flag and parameter
    let found = warnings(&[
        "safety-map",
        "--region",
        "chest",
        "--m-r",
        "0.051",
        "--x",
        "m-e=0.1:5000:3:log",
        "--y",
        "k-delta=10:1e7:2:log",
        "--method",
        "energy",
        "--out",
        map_out,
    ]);
    assert!(message_of(&found, "--x (m-e)").starts_with("5000 kg is heavier"));
    // plausible values say nothing
    assert!(warnings(&["strike"]).is_empty());
    assert!(warnings(&["run", "driven_cl_wall"]).is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

/// 6 m typed for a link (6 mm meant) and 20 m/s for a speed: the same messages on every front
/// that takes them; a joint speed whose tip speed v = |ω| L passes 10 m/s is named with its
/// value in degrees per second read as radians (20°/s = 0.349066 rad/s).
#[test]
fn a_length_and_a_speed_slip_get_the_same_warning_on_every_front() {
    let dir = scratch("length");
    let map_out = dir.join("map");
    let map_out = map_out.to_str().unwrap();
    let long = "6 m is longer than a robot's link (up to about 5 m); if millimetres were meant, \
                6 mm is 0.006 m";
    let fast = "20 m/s is faster than robot arms move near people (up to about 10 m/s)";
    let found = warnings(&["run", "cj_aluminium", "--set", "robot.length_m=6"]);
    assert_eq!(message_of(&found, "robot.length_m"), long);
    let found = warnings(&["strike", "--length", "6", "--speed", "0.3"]);
    assert_eq!(message_of(&found, "--length"), long);
    let safety = [
        "safety",
        "--region",
        "chest",
        "--m-r",
        "0.051",
        "--m-e",
        "0.4",
        "--gamma",
        "1",
        "--k-delta",
        "1e4",
        "--material",
        "skinned_aluminium",
        "--length",
        "6",
        "--speed",
        "20",
    ];
    let found = warnings(&safety);
    assert_eq!(message_of(&found, "--length"), long);
    assert_eq!(message_of(&found, "--speed"), fast);
    let found = warnings(&[
        "safety-map",
        "--region",
        "chest",
        "--m-r",
        "0.051",
        "--m-e",
        "0.4",
        "--x",
        "ei=1:10:2",
        "--y",
        "k-c=1e7:1e8:2",
        "--length",
        "6",
        "--speed",
        "20",
        "--method",
        "energy",
        "--out",
        map_out,
    ]);
    assert_eq!(message_of(&found, "--length"), long);
    assert_eq!(message_of(&found, "--speed"), fast);
    let found = warnings(&["run", "driven_cj_free_head", "--set", "person.speed=20"]);
    assert_eq!(message_of(&found, "person.speed"), fast);
    // a joint speed: 20 rad/s on the 1 m link moves the tip at 20 m/s
    let joint = "20 rad/s moves the tip at 20 m/s, faster than robot arms go (up to about 10 \
                 m/s); if 20 was meant in degrees per second, it is 0.349066 rad/s";
    let found = warnings(&[
        "run",
        "driven_cj_free_head",
        "--set",
        "drive.command.profile.speed=20",
        "--set",
        "drive.command.profile.ramp_time=0.1",
        "--set",
        "placement.settle=0.05",
        "--set",
        "drive.command.torque_limit=1000",
    ]);
    assert_eq!(message_of(&found, "drive.command.profile.speed"), joint);
    let found = warnings(&[
        "strike",
        "--speed",
        "20",
        "--ramp-time",
        "0.1",
        "--settle",
        "0.05",
        "--torque-limit",
        "1000",
    ]);
    assert_eq!(message_of(&found, "--speed"), joint);
    let _ = std::fs::remove_dir_all(&dir);
}
