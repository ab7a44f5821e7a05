//! `flexrig safety`: the standard's formula against hand arithmetic, the identity of the energy
//! and simulation methods with the standard's formula (n = 1, rigid link), the simulation's
//! convergence for a nonlinear skin and a compliant link, the head refusal, bad flags.

use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .expect("the flexrig binary runs")
}

fn json(args: &[&str]) -> serde_json::Value {
    let mut all = vec!["safety", "--json"];
    all.extend_from_slice(args);
    let out = flexrig(&all);
    assert!(
        out.status.success(),
        "{all:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        !text.contains("null") && !text.contains("NaN") && !text.contains("inf"),
        "{text}"
    );
    serde_json::from_str(&text).expect("valid JSON on stdout")
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

fn method<'a>(v: &'a serde_json::Value, name: &str) -> &'a serde_json::Value {
    v["methods"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["method"] == name)
        .unwrap_or_else(|| panic!("no method {name} in {v}"))
}

fn num(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn standard_formula_matches_hand_arithmetic_for_the_chest() {
    // Chest (Table A.2/A.3): K = 25 N/mm, m_H = 40 kg, F = 140 N quasi-static, ×2 transient;
    // sternum 120 N/cm² (×2). Robot: M = 20 kg, m_L = 1 kg ⇒ m_R = 11 kg (Eq. A.4).
    let k = 25.0e3;
    let m_r = 20.0 / 2.0 + 1.0;
    let mu = 1.0 / (1.0 / 40.0 + 1.0 / m_r);
    let base = [
        "--region",
        "chest",
        "--area",
        "Sternum",
        "--moving-mass",
        "20",
        "--payload",
        "1",
        "--method",
        "standard",
        "--area-model",
        "fixed",
        "--contact-area",
        "1cm2",
    ];
    let v = json(&base);
    let s = method(&v, "standard");
    assert!(rel(num(&s["robot_mass_kg"]), 11.0) < 1e-15);
    assert!(rel(num(&s["reduced_mass_kg"]), mu) < 1e-14);
    let by_force = 280.0 / (mu * k).sqrt();
    // 240 N/cm² × 1 cm² = 240 N < 280 N: the pressure governs (Eq. A.6).
    let by_pressure = 240.0 / (mu * k).sqrt();
    assert!(rel(num(&s["by_force_mps"]), by_force) < 1e-14);
    assert!(rel(num(&s["by_pressure_mps"]), by_pressure) < 1e-14);
    assert!(rel(num(&s["v_max_mps"]), by_pressure) < 1e-14);
    assert_eq!(s["governing"], "pressure");

    // Quasi-static: m_H = ∞ (clamped) ⇒ μ = m_R, F = 140 N; absent human mass key.
    let mut qs = base.to_vec();
    qs.extend(["--contact", "quasi-static", "--speed", "0.25"]);
    let v = json(&qs);
    assert!(v.get("human_mass_kg").is_none());
    let s = method(&v, "standard");
    let by_force = 140.0 / (m_r * k).sqrt();
    assert!(rel(num(&s["by_force_mps"]), by_force) < 1e-14);
    let verdict = &s["verdict"];
    assert!(rel(num(&verdict["peak_force_n"]), 0.25 * (m_r * k).sqrt()) < 1e-14);
    assert_eq!(verdict["pass"], 0.25 <= num(&s["v_max_mps"]));
}

#[test]
fn energy_and_simulation_reduce_to_the_standard_with_n_1_and_a_rigid_link() {
    // n = 1, k_c = K of the region, rigid link (the default law and link): Eq. 13 is Eq. A.5.
    for (region, contact) in [
        ("hands_and_fingers", "transient"),
        ("chest", "quasi-static"),
        ("lower_legs", "transient"),
    ] {
        let v = json(&[
            "--region",
            region,
            "--contact",
            contact,
            "--moving-mass",
            "20",
            "--payload",
            "1",
            "--method",
            "standard,energy",
            "--speed",
            "0.3",
        ]);
        let a = method(&v, "standard");
        let b = method(&v, "energy");
        let va = num(&a["v_max_mps"]);
        assert!(rel(num(&b["v_max_mps"]), va) < 1e-12, "{region}: {v}");
        let fa = num(&a["verdict"]["peak_force_n"]);
        assert!(rel(num(&b["verdict"]["peak_force_n"]), fa) < 1e-12);
    }
    // The simulation (the finite-element CJ and CL) of a rigid link (k_δ = 1e12 N/m) on a free
    // hub: one rigid body of tip mass m_e + m_r/3 + J_R/L² = 1 + 1 + 0.5 kg, the standard's
    // m_R = M/2 + m_L = 3/2 + 1 kg; transient and clamped (m_h = 1e9 kg). Within 1e-6: the
    // root search (1e-6), DOP853 (1e-10), the modal force hold (1e-6), K/k_δ ≤ 1.5e-7.
    for (region, contact) in [
        ("hands_and_fingers", "transient"),
        ("chest", "quasi-static"),
        ("lower_legs", "transient"),
    ] {
        for link in ["cj", "cl"] {
            let v = json(&[
                "--region",
                region,
                "--contact",
                contact,
                "--m-r",
                "3",
                "--m-e",
                "1",
                "--link",
                link,
                "--joint",
                "free-hub",
                "--rotor-inertia",
                "0.5",
                "--length",
                "1",
                "--moving-mass",
                "3",
                "--payload",
                "1",
                "--method",
                "standard,simulation",
                "--speed",
                "0.3",
            ]);
            let a = method(&v, "standard");
            let c = method(&v, "simulation");
            let va = num(&a["v_max_mps"]);
            assert!(rel(num(&c["v_max_mps"]), va) < 1e-6, "{region} {link}: {v}");
            let fa = num(&a["verdict"]["peak_force_n"]);
            assert!(rel(num(&c["verdict"]["peak_force_n"]), fa) < 1e-6, "{v}");
        }
    }
}

#[test]
fn the_simulated_speed_is_converged_to_1e_4() {
    // The test bed's link (m_r = 51 g, payload 412 g) on skinned aluminium (n = 1.961), hand
    // transient, Hertz-sphere area of the dome, held joint: the default tolerances (root 1e-6,
    // modal hold 1e-6) against root 1e-10 and hold 1e-8, CJ and CL, by force and by pressure.
    for link in ["cj", "cl"] {
        let run = |extra: &[&str]| {
            let mut args = vec![
                "--region",
                "hands_and_fingers",
                "--area",
                "Back of the hand ND",
                "--m-r",
                "0.051",
                "--m-e",
                "0.412",
                "--link",
                link,
                "--material",
                "skinned_aluminium",
                "--k-delta",
                "1e4",
                "--method",
                "energy,simulation",
            ];
            args.extend_from_slice(extra);
            json(&args)
        };
        let coarse = run(&[]);
        let fine = run(&["--root-rtol", "1e-10", "--tol", "1e-8"]);
        let (c, f) = (method(&coarse, "simulation"), method(&fine, "simulation"));
        for key in ["by_force_mps", "by_pressure_mps", "v_max_mps"] {
            assert!(
                rel(num(&c[key]), num(&f[key])) < 1e-4,
                "{link} {key}: {coarse}"
            );
        }
    }
}

#[test]
fn transient_head_contact_is_refused_with_the_clause() {
    for region in ["skull_and_forehead", "face"] {
        let out = flexrig(&["safety", "--region", region, "--m-eff", "5"]);
        assert_eq!(out.status.code(), Some(2), "{region}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("not permitted") && err.contains("5.5.5.4"),
            "{err}"
        );
    }
    // Quasi-static contact with the forehead is assessed.
    let v = json(&[
        "--region",
        "skull_and_forehead",
        "--contact",
        "quasi-static",
        "--m-eff",
        "5",
    ]);
    let s = method(&v, "standard");
    assert!(rel(num(&s["by_force_mps"]), 130.0 / (5.0f64 * 150e3).sqrt()) < 1e-14);
}

#[test]
fn bad_input_exits_2_naming_the_flag() {
    let cases: [(&[&str], &str); 12] = [
        (&["--region", "chest", "--m-eff", "-1"], "--m-eff"),
        (
            &["--region", "chest", "--m-eff", "5", "--k-delta", "0"],
            "--k-delta",
        ),
        (
            &["--region", "chest", "--m-eff", "5", "--speed", "NaN"],
            "--speed",
        ),
        (&["--region", "chest"], "--moving-mass"),
        (&["--region", "elbow", "--m-eff", "5"], "elbow"),
        (
            &["--region", "chest", "--m-eff", "5", "--area", "Toe"],
            "Toe",
        ),
        (
            &["--region", "chest", "--m-eff", "5", "--material", "steel"],
            "--material",
        ),
        (
            &["--region", "chest", "--m-eff", "5", "--area-model", "fixed"],
            "--contact-area",
        ),
        // an area without its unit: 1 m² or 1 cm²?
        (
            &["--region", "chest", "--m-eff", "5", "--contact-area", "1"],
            "--contact-area",
        ),
        // a linear contact (the body spring, n = 1) has no dome
        (
            &["--region", "chest", "--m-eff", "5", "--radius", "0.05"],
            "--area-model",
        ),
        (
            &[
                "--region",
                "chest",
                "--m-eff",
                "5",
                "--radius",
                "0.05",
                "--contact-area",
                "1cm2",
            ],
            "--area-model",
        ),
        (
            &["--region", "chest", "--trace", "no/such/trace.csv"],
            "no/such/trace.csv",
        ),
    ];
    for (args, flag) in cases {
        let mut all = vec!["safety"];
        all.extend_from_slice(args);
        let out = flexrig(&all);
        assert_eq!(out.status.code(), Some(2), "{all:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(flag), "{all:?}: {err}");
    }
}

#[test]
fn a_driven_scene_is_the_design_and_its_commanded_speed_is_searched() {
    // The bundled driven CL against a wall: the chest clamped (quasi-static limit 140 N), the
    // three methods by default, the simulation's speed is where the scene's peak force is the
    // limit (the run at the root, to the search's 1e-6).
    let v = json(&["--region", "chest", "--scene", "driven_cl_wall"]);
    assert_eq!(v["contact"], "quasi_static");
    assert_eq!(num(&v["force_limit_n"]), 140.0);
    assert_eq!(v["methods"].as_array().unwrap().len(), 3);
    let sim = method(&v, "simulation");
    let scene = &v["scene"];
    assert_eq!(scene["name"], "driven_cl_wall");
    assert_eq!(num(&sim["by_force_mps"]), num(&scene["by_force_mps"]));
    assert!(
        rel(num(&scene["peak_force_at_root_n"]), 140.0) < 1e-5,
        "{scene}"
    );
    // the design flags of another design are refused beside a scene
    let out = flexrig(&[
        "safety",
        "--region",
        "chest",
        "--scene",
        "driven_cl_wall",
        "--k-delta",
        "1e4",
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--k-delta") && err.contains("--scene"),
        "{err}"
    );
}

#[test]
fn a_test_bed_scene_searches_the_operators_speed_and_refuses_the_head() {
    // The bundled CJ test bed against the abdomen (transient limit 220 N): the simulated speed
    // is the operator's speed at contact, its run at the root reaches the limit (the search's
    // 1e-6), and the release angle gives that speed by the pendulum's energy.
    let v = json(&["--region", "abdomen", "--scene", "cj_aluminium"]);
    assert_eq!(v["contact"], "transient");
    let f = num(&v["force_limit_n"]);
    let scene = &v["scene"];
    assert_eq!(scene["name"], "cj_aluminium");
    assert_eq!(scene["support"], "pendulum");
    assert_eq!(scene["limit_reached"], true);
    let angle = num(&scene["release_angle_at_root_deg"]);
    assert!(angle > 0.0 && angle <= 170.0, "{scene}");
    assert_eq!(
        num(&method(&v, "simulation")["by_force_mps"]),
        num(&scene["by_force_mps"])
    );
    assert!(
        rel(num(&scene["peak_force_at_root_n"]), f) < 1e-5,
        "{scene}"
    );
    // the operator's block is the person: a transient head contact is refused with the clause
    let out = flexrig(&["safety", "--region", "face", "--scene", "cj_aluminium"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("5.5.5.4"));
}

/// A mistyped region is named before any other input is asked for, and grams typed for
/// kilograms are warned about in text (standard error) and JSON alike, with the conversion.
#[test]
fn an_unknown_region_comes_first_and_unit_slips_are_warned_about() {
    let out = flexrig(&["safety", "--region", "chset", "--m-r", "1", "--m-e", "1"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("chset") && err.contains("chest"), "{err}");
    let args = [
        "safety",
        "--region",
        "chest",
        "--m-r",
        "1200",
        "--m-e",
        "2000",
        "--gamma",
        "1",
        "--method",
        "standard,energy",
    ];
    let out = flexrig(&args);
    assert_eq!(out.status.code(), Some(0));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning: --m-r: 1200 kg") && err.contains("2000 g is 2 kg"),
        "{err}"
    );
    let v = json(&args[1..]);
    let w = v["warnings"].as_array().unwrap();
    assert_eq!(w.len(), 2, "{w:?}");
    assert_eq!(w[0]["field"], "--m-r");
    assert!(
        w[0]["message"]
            .as_str()
            .unwrap()
            .contains("1200 g is 1.2 kg")
    );
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-cli-trace-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Areas with their unit: `1cm2`, `1e-4m2` and `100mm2` give the same answer bit for bit; an
/// implausible area is warned about on stderr and in the JSON; without a contact geometry each
/// method says "pressure not assessed" instead of a governing limit.
#[test]
fn areas_carry_their_unit_and_pressure_not_assessed_is_said() {
    let base = ["--region", "chest", "--m-eff", "3", "--speed", "0.5"];
    let with = |area: &str| {
        let mut args = base.to_vec();
        args.extend(["--contact-area", area]);
        json(&args)
    };
    let cm2 = with("1cm2");
    assert_eq!(cm2, with("1e-4m2"));
    assert_eq!(cm2["area_model"]["area_m2"], 1e-4);
    let mm2 = with("100mm2");
    assert!(rel(num(&mm2["area_model"]["area_m2"]), 1e-4) < 1e-15);
    assert!(method(&cm2, "standard")["pressure_assessed"] == true);
    assert!(cm2.get("warnings").is_none());
    let mut args = vec!["safety"];
    args.extend(base);
    args.extend(["--contact-area", "1m2"]);
    let out = flexrig(&args);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("warning: --contact-area") && err.contains("10000 cm²"),
        "{err}"
    );
    assert_eq!(with("1m2")["warnings"][0]["field"], "--contact-area");
    // no geometry: force only
    let mut args = vec!["safety"];
    args.extend(base);
    let out = flexrig(&args);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("force only") && text.contains("pressure not assessed"),
        "{text}"
    );
    let v = json(&base);
    assert!(method(&v, "energy")["pressure_assessed"] == false);
    // the transferred energy at the judged speed: ½ μ v² for the standard (Eq. A.2)
    let mu = 1.0 / (1.0 / 40.0 + 1.0 / 3.0);
    let e = num(&method(&v, "standard")["verdict"]["energy_transferred_j"]);
    assert!(rel(e, 0.5 * mu * 0.25) < 1e-12, "{e}");
}

/// `flexrig safety --trace FILE`: the text and the JSON agree; a measured pulse over the limit
/// is FAIL, within it pass; a bad CSV exits 2 naming the line; design flags are refused.
#[test]
fn a_measured_trace_is_judged_and_a_bad_one_refused_by_line() {
    let dir = scratch("judge");
    let path = dir.join("pulse.csv");
    let pulse = |f0: f64| {
        let mut text = String::from("t [ms], F [N], a [m/s^2], delta [mm]\n");
        for i in 0..=200 {
            let s = (std::f64::consts::PI * i as f64 / 200.0).sin();
            text.push_str(&format!(
                "{}, {}, {}, {}\n",
                0.05 * i as f64,
                f0 * s,
                100.0 * s,
                s
            ));
        }
        text
    };
    let p = path.to_str().unwrap();
    let args = [
        "safety",
        "--trace",
        p,
        "--region",
        "hands_and_fingers",
        "--contact-area",
        "2cm2",
    ];
    for (f0, pass) in [(270.0, true), (290.0, false)] {
        std::fs::write(&path, pulse(f0)).unwrap();
        let v = json(&args[1..]);
        assert_eq!(v["verdict"]["pass"], pass, "{v}");
        assert!(rel(num(&v["severity"]["peak_force_n"]), f0) < 1e-12);
        // ∫ f dδ over the loading of a straight line f = F0 δ/D: F0 D/2
        assert!(rel(num(&v["severity"]["energy_transferred_j"]), 0.5 * f0 * 1e-3) < 1e-12);
        let out = flexrig(&args);
        assert!(out.status.success());
        let text = String::from_utf8_lossy(&out.stdout);
        let verdict = if pass {
            "verdict            pass"
        } else {
            "verdict            FAIL"
        };
        assert!(text.contains(verdict), "{text}");
        assert!(
            text.contains(&format!("peak force         {f0:.3} N")),
            "{text}"
        );
        assert!(text.contains("HIC15"), "{text}");
    }
    // a bad line
    std::fs::write(&path, "t [s], F [N]\n0, 1\n0.001, 2\n0.001, 3\n").unwrap();
    let out = flexrig(&args);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("--trace") && err.contains("line 4") && err.contains("line 3"),
        "{err}"
    );
    // a header without units
    std::fs::write(&path, "time, force\n0, 1\n0.001, 2\n").unwrap();
    let out = flexrig(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("line 1"));
    // a design flag beside a trace
    let mut with_design = args.to_vec();
    with_design.extend(["--m-eff", "3"]);
    let out = flexrig(&with_design);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--m-eff"));
    let _ = std::fs::remove_dir_all(&dir);
}
