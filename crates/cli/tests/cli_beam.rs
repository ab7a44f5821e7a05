//! End-to-end tests of `flexrig beam modal|static` and `flexrig prb` against the published
//! references (docs/references.md); bad input exits with code 2 and names the flag.

use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .expect("run flexrig")
}

fn json(args: &[&str]) -> serde_json::Value {
    let out = flexrig(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

fn assert_rel(what: &str, got: f64, want: f64, rel: f64) {
    let e = (got / want - 1.0).abs();
    assert!(
        e <= rel,
        "{what}: got {got:e}, reference {want:e}, rel. error {e:e} > {rel:e}"
    );
}

// A steel strip: L = 1 m, 20 mm × 5 mm.
const L: f64 = 1.0;
const E: f64 = 2.0e11;
const RHO: f64 = 7850.0;
const W: f64 = 0.02;
const T: f64 = 0.005;
const BEAM: [&str; 10] = [
    "--length",
    "1",
    "--youngs",
    "2e11",
    "--density",
    "7850",
    "--width",
    "0.02",
    "--thickness",
    "0.005",
];

fn ei() -> f64 {
    E * W * T.powi(3) / 12.0
}
fn rho_a() -> f64 {
    RHO * W * T
}
fn f_hz(beta_l: f64) -> f64 {
    beta_l * beta_l * (ei() / (rho_a() * L.powi(4))).sqrt() / (2.0 * std::f64::consts::PI)
}

fn with(extra: &[&'static str]) -> Vec<&'static str> {
    let mut v = BEAM.to_vec();
    v.extend_from_slice(extra);
    v
}

#[test]
fn modal_cantilever_frequencies_match_the_beta_roots() {
    let mut args = vec!["beam", "modal"];
    args.extend(with(&["--elements", "32", "--json"]));
    let v = json(&args);
    let f = v["frequencies_hz"].as_array().unwrap();
    assert_eq!(f.len(), 4);
    for (i, beta) in [1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349]
        .iter()
        .enumerate()
    {
        assert_rel(
            &format!("f{}", i + 1),
            f[i].as_f64().unwrap(),
            f_hz(*beta),
            1e-5,
        );
    }
}

#[test]
fn modal_with_tip_mass_and_pinned_root() {
    // μ = 1: tip mass = ρAL
    let m = format!("{}", rho_a() * L);
    let m: &'static str = Box::leak(m.into_boxed_str());
    let mut args = vec!["beam", "modal"];
    args.extend(with(&[
        "--elements",
        "32",
        "--tip-mass",
        m,
        "--modes",
        "1",
        "--json",
    ]));
    let v = json(&args);
    assert_rel(
        "f1 with μ = 1",
        v["frequencies_hz"][0].as_f64().unwrap(),
        f_hz(1.24792),
        2e-5,
    );
    let mut args = vec!["beam", "modal"];
    args.extend(with(&[
        "--elements",
        "32",
        "--root",
        "pinned",
        "--modes",
        "3",
        "--json",
    ]));
    let v = json(&args);
    assert_eq!(
        v["frequencies_hz"][0].as_f64().unwrap(),
        0.0,
        "rigid mode reported as 0"
    );
    assert_rel(
        "pinned-free f",
        v["frequencies_hz"][1].as_f64().unwrap(),
        f_hz(3.92660),
        2e-5,
    );
}

#[test]
fn static_linear_is_pl3_over_3ei_and_corotational_matches_the_elastica() {
    let mut args = vec!["beam", "static"];
    args.extend(with(&["--elements", "8", "--tip-load", "0.5", "--json"]));
    let v = json(&args);
    assert_rel(
        "PL³/3EI",
        v["tip_v_m"].as_f64().unwrap(),
        0.5 / (3.0 * ei()),
        1e-10,
    );
    assert_rel(
        "PL²/2EI",
        v["tip_angle_rad"].as_f64().unwrap(),
        0.5 / (2.0 * ei()),
        1e-10,
    );
    // PL²/EI = 5
    let p = format!("{}", 5.0 * ei());
    let p: &'static str = Box::leak(p.into_boxed_str());
    let mut args = vec!["beam", "static"];
    args.extend(with(&[
        "--elements",
        "32",
        "--tip-load",
        p,
        "--model",
        "corotational",
        "--json",
    ]));
    let v = json(&args);
    assert_rel(
        "elastica v/L",
        v["tip_v_m"].as_f64().unwrap(),
        0.7137915236,
        5e-4,
    );
    assert_rel(
        "elastica u/L",
        -v["tip_u_m"].as_f64().unwrap(),
        0.3876283607,
        1e-3,
    );
    assert_rel(
        "elastica angle",
        v["tip_angle_rad"].as_f64().unwrap(),
        1.2153681176,
        5e-4,
    );
    assert!(v["iterations"].as_u64().unwrap() >= 10);
}

#[test]
fn adaptive_load_steps_reach_the_same_elastica_in_fewer_iterations() {
    // PL²/EI = 5, both large-deflection models: the whole load at once (`--load-steps 1
    // --adaptive-steps`) ends at the equilibrium of 10 fixed increments (within the Newton
    // tolerance times the length, 1e-10 m) and on the elastica table
    let p = format!("{}", 5.0 * ei());
    for model in ["corotational", "ancf"] {
        let run = |extra: &[&str]| {
            let mut args = vec!["beam", "static"];
            args.extend(BEAM);
            args.extend([
                "--elements",
                "32",
                "--tip-load",
                &p,
                "--model",
                model,
                "--json",
            ]);
            args.extend(extra);
            json(&args)
        };
        let fixed = run(&[]);
        let adaptive = run(&["--load-steps", "1", "--adaptive-steps"]);
        for key in ["tip_u_m", "tip_v_m", "tip_angle_rad"] {
            let (a, f) = (
                adaptive[key].as_f64().unwrap(),
                fixed[key].as_f64().unwrap(),
            );
            assert!((a - f).abs() <= 1e-10 * L, "{model} {key}: {a} against {f}");
        }
        assert_rel(
            "elastica v/L",
            adaptive["tip_v_m"].as_f64().unwrap(),
            0.7137915236,
            5e-4,
        );
        assert_eq!(adaptive["load_level"].as_f64(), Some(1.0));
        let (a, f) = (
            adaptive["iterations"].as_u64().unwrap(),
            fixed["iterations"].as_u64().unwrap(),
        );
        assert!(
            4 * a <= f,
            "{model}: {a} adaptive against {f} fixed iterations"
        );
    }
}

#[test]
fn prb_reproduces_howell_and_writes_the_svg() {
    let dir = std::env::temp_dir().join(format!("flexrig-prb-{}", std::process::id()));
    let d = dir.to_str().unwrap().to_string();
    let v = json(&["prb", "--json", "--out", &d]);
    assert!(
        (v["gamma"].as_f64().unwrap() - 0.8517).abs() < 1e-3,
        "γ {}",
        v["gamma"]
    );
    assert!((v["theta_max_deg"].as_f64().unwrap() - 64.3).abs() < 0.5);
    assert!((v["k_theta"].as_f64().unwrap() - 2.70).abs() < 0.03);
    assert_rel(
        "small-deflection γ",
        v["small_deflection"]["gamma"].as_f64().unwrap(),
        2.0 / 3.0,
        1e-4,
    );
    let svg = std::fs::read_to_string(dir.join("prb.svg")).expect("prb.svg");
    assert!(svg.starts_with("<svg") && svg.contains("</svg>"));
    let _ = std::fs::remove_dir_all(&dir);
}

fn assert_input_error(args: &[&str], flag: &str) {
    let out = flexrig(args);
    assert_eq!(out.status.code(), Some(2), "{args:?} should exit 2");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains(flag),
        "{args:?}: stderr does not name {flag}: {err}"
    );
}

#[test]
fn bad_input_exits_2_and_names_the_flag() {
    let modal = |extra: &[&'static str]| {
        let mut a = vec!["beam", "modal"];
        a.extend(with(extra));
        a
    };
    assert_input_error(&modal(&["--elements", "0"]), "--elements");
    assert_input_error(&modal(&["--root", "welded"]), "--root");
    assert_input_error(
        &modal(&["--root", "pinned", "--k-theta", "-3"]),
        "--k-theta",
    );
    assert_input_error(&modal(&["--tip-mass", "NaN"]), "--tip-mass");
    assert_input_error(&modal(&["--modes", "0"]), "--modes");
    assert_input_error(
        &[
            "beam",
            "modal",
            "--length",
            "-1",
            "--youngs",
            "2e11",
            "--density",
            "7850",
            "--width",
            "0.02",
            "--thickness",
            "0.005",
        ],
        "--length",
    );
    assert_input_error(
        &[
            "beam",
            "modal",
            "--length",
            "1",
            "--youngs",
            "0",
            "--density",
            "7850",
            "--width",
            "0.02",
            "--thickness",
            "0.005",
        ],
        "--youngs",
    );
    let stat = |extra: &[&'static str]| {
        let mut a = vec!["beam", "static"];
        a.extend(with(extra));
        a
    };
    assert_input_error(&stat(&["--tip-load", "NaN"]), "--tip-load");
    assert_input_error(&stat(&["--tip-load", "1", "--model", "elastic"]), "--model");
    assert_input_error(
        &stat(&["--tip-load", "1", "--load-steps", "0"]),
        "--load-steps",
    );
    assert_input_error(&["prb", "--elements", "0"], "--elements");
    assert_input_error(&["prb", "--criterion", "strict"], "--criterion");
}
