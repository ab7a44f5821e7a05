//! Regression tests of issue 35 (hostile inputs, round four) on the driven surfaces: each case
//! named after the bug it pins ends with exit 2 and a message that names the flag or field, its
//! value and what is allowed — or with a finished answer.

use std::process::Command;

fn flexrig(args: &[&str]) -> (i32, String, String) {
    let dir = std::env::temp_dir().join(format!("flexrig-hostile-driven-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .current_dir(&dir)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Exit 2 whose message holds every one of `words`.
fn refused(args: &[&str], words: &[&str]) {
    let (code, _, err) = flexrig(args);
    assert_eq!(code, 2, "{args:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: {w:?} missing in {err}");
    }
    assert!(!err.contains("panicked") && !err.contains(" { "), "{err}");
    assert!(err.len() < 1000, "{err}");
}

#[test]
fn driven_contact_k_outside_the_test_beds_range_is_refused_not_a_silent_zero_peak() {
    refused(
        &["strike", "--k-c", "1e40"],
        &["--k-c = 1e40", "[1e-3, 1e20]"],
    );
    refused(
        &["strike", "--k-c", "1e-300"],
        &["--k-c = 1e-300", "[1e-3, 1e20]"],
    );
    refused(
        &["strike", "--k-c", "1e-3"],
        &["--k-c = 0.001", "would indent"],
    );
    refused(
        &[
            "run",
            "driven_cl_free_head",
            "--set",
            "person.contact.k=1e40",
        ],
        &["person.contact.k", "1e40"],
    );
}

#[test]
fn a_speed_too_small_to_make_a_contact_is_refused_not_a_panic() {
    refused(
        &["strike", "--speed", "1e-20"],
        &["--speed = 1e-20", "rad/s"],
    );
    refused(&["strike", "--speed", "1e-300"], &["--speed = 1e-300"]);
    refused(&["strike", "--speed", "0"], &["--speed = 0"]);
    refused(
        &[
            "run",
            "driven_cj_free_head",
            "--set",
            "drive.command.profile.speed=1e-300",
        ],
        &["drive.command.profile.speed"],
    );
}

#[test]
fn a_negative_number_reaches_the_range_check() {
    refused(&["strike", "--speed", "-1"], &["--speed = -1", "≥ 0"]);
    refused(&["strike", "--m-h", "-1"], &["--m-h = -1"]);
}

#[test]
fn strike_errors_name_the_flag_and_the_typed_value() {
    refused(
        &["strike", "--length", "600"],
        &["--speed = 2", "--length", "1000 m/s"],
    );
    refused(
        &["strike", "--rotor-inertia", "5e-324"],
        &["--rotor-inertia = 5e-324"],
    );
    refused(&["strike", "--n", "1e300"], &["--n = 1e300"]);
    refused(&["strike", "--n", "0.1"], &["--n = 0.1", "[0.5, 10]"]);
}

#[test]
fn an_unstable_integral_gain_is_refused() {
    refused(
        &[
            "run",
            "driven_cl_free_head",
            "--set",
            "drive.command.gains.ki=1e11",
        ],
        &["drive.command.gains.ki", "1e11", "Routh"],
    );
}

#[test]
fn the_trace_has_a_budget_checked_before_the_work() {
    refused(
        &["strike", "--design", "cj", "--trace-every", "1e-12"],
        &["--trace-every = 1e-12", "at least"],
    );
}

#[test]
fn strike_notes_are_words_and_the_json_has_no_null() {
    let (code, out, err) = flexrig(&["strike", "--speed", "95.5"]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("warning") && err.contains("degrees"), "{err}");
    assert!(!out.contains(" { ") && out.contains("note: "), "{out}");
    let (code, out, err) = flexrig(&["strike", "--json"]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("null"), "{out}");
}

#[test]
fn role_switch_kappas_are_bounded_and_distinct_before_the_work() {
    refused(
        &["role-switch", "--kappa", "1,1"],
        &["--kappa[1] = 1", "repeats"],
    );
    let many = vec!["1"; 13].join(",");
    refused(
        &["role-switch", "--kappa", &many],
        &["--kappa", "at most 12"],
    );
    refused(
        &["role-switch", "--rotor-ratio", "1e-12"],
        &["--rotor-ratio = 1e-12"],
    );
}
