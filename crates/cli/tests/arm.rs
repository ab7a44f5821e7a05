//! `flexrig arm`: the bundled UR5 answers with no arguments; the governing sample's permissible
//! speed is `flexrig safety`'s for the same single link bit for bit (through both command
//! lines); bad flags, a link the URDF does not have and a trajectory whose joints do not match
//! are refused naming them (exit code 2).

use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .output()
        .expect("flexrig runs")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = flexrig(args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn refused(args: &[&str]) -> String {
    let out = flexrig(args);
    assert_eq!(
        out.status.code(),
        Some(2),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

#[test]
fn the_bundled_arm_answers_with_no_arguments() {
    let out = flexrig(&["arm"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    for want in [
        "verdict",
        "speed scaling",
        "ur5",
        "tool0:0,0,0.1",
        "forearm_link",
        "chest",
    ] {
        assert!(text.contains(want), "{want}: {text}");
    }
}

#[test]
fn the_governing_sample_is_flexrig_safety_bit_for_bit() {
    let arm = json(&[
        "arm",
        "--k-delta",
        "2e4",
        "--material",
        "skinned_aluminium",
        "--mass-step",
        "0",
        "--point",
        "tool0:0,0,0.1",
        "--speed-scale",
        "0.5",
        "--json",
    ]);
    let g = &arm["governing"];
    let m = g["effective_mass_kg"].as_f64().unwrap();
    let m_r = arm["link_mass_kg"].as_f64().unwrap();
    let m_e = m - m_r / 3.0;
    // the numbers as Rust prints them round-trip exactly
    let safety = json(&[
        "safety",
        "--region",
        "chest",
        "--link",
        "cj",
        "--m-r",
        &m_r.to_string(),
        "--m-e",
        &m_e.to_string(),
        "--k-delta",
        "2e4",
        "--material",
        "skinned_aluminium",
        "--joint",
        "free-hub",
        "--rotor-inertia",
        "1e-12",
        "--length",
        "1",
        "--json",
    ]);
    assert_eq!(g["v_max_mps"], safety["overall"]["v_max_mps"]);
    assert_eq!(g["method"], safety["overall"]["method"]);
    assert_eq!(
        g["safety"]["methods"][0]["v_max_mps"],
        safety["methods"][0]["v_max_mps"]
    );
}

#[test]
fn bad_flags_are_refused_naming_them() {
    let e = refused(&["arm", "--point", "toool0:0,0,0.1"]);
    assert!(
        e.contains("--point") && e.contains("\"toool0\"") && e.contains("wrist_3_link"),
        "{e}"
    );
    let e = refused(&["arm", "--urdf", "assets/robots/ur5.urdf"]);
    assert!(e.contains("--trajectory") && e.contains("(missing)"), "{e}");
    let e = refused(&["arm", "--trajectory", "assets/robots/ur5_swing.csv"]);
    assert!(e.contains("--urdf"), "{e}");
    let e = refused(&[
        "arm",
        "--urdf",
        "assets/robots/panda.urdf",
        "--trajectory",
        "assets/robots/ur5_swing.csv",
        "--point",
        "panda_hand",
    ]);
    assert!(
        e.contains("ur5_swing.csv")
            && e.contains("shoulder_pan_joint")
            && e.contains("panda_joint1"),
        "{e}"
    );
    let e = refused(&["arm", "--armature", "0.1,0.2"]);
    assert!(
        e.contains("--armature") && e.contains("--joints armature"),
        "{e}"
    );
    let e = refused(&["arm", "--joints", "armature", "--armature", "0.1,0.2"]);
    assert!(e.contains("--armature") && e.contains("2 values"), "{e}");
    let e = refused(&["arm", "--mass-step", "2"]);
    assert!(e.contains("--mass-step") && e.contains("[0, 0.25]"), "{e}");
    let e = refused(&["arm", "--speed-scale", "0"]);
    assert!(e.contains("--speed-scale"), "{e}");
    let e = refused(&["arm", "--figure", "out.txt"]);
    assert!(e.contains("--figure") && e.contains(".svg"), "{e}");
    let e = refused(&["arm", "--log", "out.txt"]);
    assert!(e.contains("--log") && e.contains(".mcap"), "{e}");
    let e = refused(&["arm", "--report", "out.txt"]);
    assert!(e.contains("--report") && e.contains(".md"), "{e}");
    let e = refused(&["arm", "--region", "chestt"]);
    assert!(e.contains("--region") && e.contains("chest"), "{e}");
    let e = refused(&["arm", "--link-mass", "50"]);
    assert!(
        e.contains("--link-mass") && e.contains("less than a third"),
        "{e}"
    );
    let e = refused(&[
        "arm",
        "--urdf",
        "no/such.urdf",
        "--trajectory",
        "no/such.csv",
    ]);
    assert!(e.contains("no/such.urdf"), "{e}");
}
