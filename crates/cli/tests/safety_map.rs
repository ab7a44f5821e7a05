//! `flexrig safety-map` and `flexrig safety --report`: a lumped cell is the single-point answer
//! bit for bit, the energy method equals the standard's formula with n = 1 and a rigid link,
//! the simulated speeds converge to 1e-4, the files (CSV with units, JSON, figure, report), and
//! bad input named by flag with exit code 2.

use std::path::Path;
use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .expect("the flexrig binary runs")
}

fn ok(args: &[&str]) -> String {
    let out = flexrig(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

fn tmp(name: &str) -> std::path::PathBuf {
    let dir =
        std::env::temp_dir().join(format!("flexrig_safety_map_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The CSV as rows of (column → text).
fn table(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(
        !text.contains("NaN") && !text.contains("null") && !text.contains("inf,"),
        "{text}"
    );
    let mut lines = text.lines();
    let head: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            head.iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

fn f(row: &std::collections::HashMap<String, String>, col: &str) -> f64 {
    row[col]
        .parse()
        .unwrap_or_else(|_| panic!("{col} = {:?} is not a number", row[col]))
}

#[test]
fn a_lumped_cell_is_the_single_point_safety_answer_bit_for_bit() {
    let dir = tmp("cell");
    let d = dir.to_str().unwrap();
    ok(&[
        "safety-map",
        "--region",
        "hands_and_fingers",
        "--material",
        "skinned_aluminium",
        "--m-r",
        "0.051",
        "--x",
        "m-e=0.01:5:4:log",
        "--y",
        "k-delta=10:1e7:3:log",
        "--method",
        "energy",
        "--out",
        d,
    ]);
    let rows = table(&dir.join("safety_map.csv"));
    assert_eq!(rows.len(), 12);
    assert!(rows[0].contains_key("x_m_e_kg") && rows[0].contains_key("v_max_cl_mps"));
    for row in [&rows[1], &rows[6], &rows[11]] {
        for (gamma, col) in [
            ("1", "v_max_cj_mps"),
            ("0.6666666666666666", "v_max_cl_mps"),
        ] {
            let text = ok(&[
                "safety",
                "--json",
                "--region",
                "hands_and_fingers",
                "--material",
                "skinned_aluminium",
                "--m-r",
                "0.051",
                "--m-e",
                &row["m_e_kg"],
                "--gamma",
                gamma,
                "--k-delta",
                &row["k_delta_n_per_m"],
                "--method",
                "energy",
            ]);
            let v: serde_json::Value = serde_json::from_str(&text).unwrap();
            let single = v["methods"][0]["v_max_mps"].as_f64().unwrap();
            assert_eq!(f(row, col).to_bits(), single.to_bits(), "{col} at {row:?}");
        }
        let ratio = f(row, "v_max_cl_mps") / f(row, "v_max_cj_mps");
        assert_eq!(ratio.to_bits(), f(row, "ratio_cl_cj").to_bits());
    }
    assert!(dir.join("safety_map.svg").exists() && dir.join("safety_map.json").exists());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("safety_map.json")).unwrap())
            .unwrap();
    assert_eq!(json["cells"].as_array().unwrap().len(), 12);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn with_n_1_and_a_rigid_link_the_energy_map_is_the_standard_formula_to_1e_12() {
    let dir = tmp("identity");
    for (method, sub) in [("standard", "a"), ("energy", "b")] {
        let out = dir.join(sub);
        ok(&[
            "safety-map",
            "--region",
            "chest",
            "--x",
            "m-e=0.1:20:5:log",
            "--y",
            "m-r=0.05:30:4:log",
            "--method",
            method,
            "--out",
            out.to_str().unwrap(),
        ]);
    }
    for contact in ["transient", "quasi-static"] {
        let a = dir.join(format!("a_{contact}"));
        let b = dir.join(format!("b_{contact}"));
        for (method, out) in [("standard", &a), ("energy", &b)] {
            ok(&[
                "safety-map",
                "--region",
                "lower_legs",
                "--contact",
                contact,
                "--x",
                "m-e=0.1:20:3:log",
                "--y",
                "m-r=0.05:30:3:log",
                "--method",
                method,
                "--out",
                out.to_str().unwrap(),
            ]);
        }
        let (sa, sb) = (
            table(&a.join("safety_map.csv")),
            table(&b.join("safety_map.csv")),
        );
        for (ra, rb) in sa.iter().zip(&sb) {
            for col in ["v_max_cj_mps", "v_max_cl_mps", "by_force_cj_mps"] {
                let (x, y) = (f(ra, col), f(rb, col));
                assert!(((x - y) / x).abs() < 1e-12, "{contact} {col}: {x} vs {y}");
            }
        }
    }
    let (sa, sb) = (
        table(&dir.join("a/safety_map.csv")),
        table(&dir.join("b/safety_map.csv")),
    );
    assert_eq!(sa.len(), 20);
    for (ra, rb) in sa.iter().zip(&sb) {
        // and by hand: v = F/√(μK), μ = (1/m_H + 1/m_eff)⁻¹, chest F = 280 N, K = 25 N/mm, 40 kg
        let m_eff = f(ra, "m_e_kg") + f(ra, "m_r_kg") / 3.0;
        let mu = 1.0 / (1.0 / 40.0 + 1.0 / m_eff);
        let v = 280.0 / (mu * 25e3).sqrt();
        assert!((f(ra, "v_max_cj_mps") / v - 1.0).abs() < 1e-12);
        assert!((f(rb, "v_max_cj_mps") / v - 1.0).abs() < 1e-12);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn simulated_speeds_converge_to_1e_4() {
    let dir = tmp("converge");
    let base = [
        "safety-map",
        "--region",
        "hands_and_fingers",
        "--material",
        "skinned_aluminium",
        "--m-r",
        "0.051",
        "--x",
        "m-e=0.05:2:2:log",
        "--y",
        "k-delta=300:3e5:2:log",
        "--method",
        "simulation",
    ];
    let coarse = dir.join("coarse");
    let fine = dir.join("fine");
    let mut a = base.to_vec();
    a.extend(["--out", coarse.to_str().unwrap()]);
    let text = ok(&a);
    // the dome spreads the hand's 280 N far below 380 N/cm²: the force governs every design,
    // and the pressure's speed is written as a bound, not searched
    assert!(
        text.contains("governs    force in 8 designs, pressure in 0 (the other limit not searched"),
        "{text}"
    );
    let mut b = base.to_vec();
    b.extend([
        "--tol",
        "1e-8",
        "--root-rtol",
        "1e-10",
        "--out",
        fine.to_str().unwrap(),
    ]);
    ok(&b);
    let (ra, rb) = (
        table(&coarse.join("safety_map.csv")),
        table(&fine.join("safety_map.csv")),
    );
    assert_eq!(ra.len(), 4);
    for (x, y) in ra.iter().zip(&rb) {
        assert_eq!(x["error"], "");
        for col in ["v_max_cj_mps", "v_max_cl_mps"] {
            let (p, q) = (f(x, col), f(y, col));
            assert!(((p - q) / q).abs() < 1e-4, "{col}: {p} vs {q}");
        }
        // the FE CJ and CL differ by the link's own compliance: not the lumped γ's ratio
        assert!(f(x, "runs_cj") >= 3.0 && f(x, "runs_cl") >= 3.0);
        for link in ["cj", "cl"] {
            let v_max = &x[&format!("v_max_{link}_mps")];
            assert_eq!(x[&format!("by_pressure_{link}_mps")], format!(">={v_max}"));
            assert_eq!(&x[&format!("by_force_{link}_mps")], v_max);
            assert_eq!(x[&format!("governing_{link}")], "force");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_input_exits_2_naming_the_flag() {
    let dir = tmp("bad");
    let d = dir.to_str().unwrap();
    for (args, flag) in [
        (vec!["--x", "m-e", "--m-r", "0.05"], "--x"),
        (vec!["--x", "speed=1:2:3", "--m-r", "0.05"], "--x"),
        (vec!["--y", "m-e=0.1:1:3:log", "--m-r", "0.05"], "--y"),
        (vec!["--x", "m-e=0:1:3", "--m-r", "0.05"], "--x"),
        (vec![], "--m-r"),
        (
            vec!["--y", "m-r=0.01:0.1:3:log", "--method", "simulation"],
            "--k-delta",
        ),
        (
            vec![
                "--m-r",
                "0.05",
                "--method",
                "simulation",
                "--contact",
                "quasi-static",
            ],
            "--contact",
        ),
        (
            vec!["--m-r", "0.05", "--joint", "free-hub"],
            "--rotor-inertia",
        ),
        (
            vec!["--m-r", "0.05", "--method", "simulation", "--tol", "1"],
            "--tol",
        ),
    ] {
        let mut all = vec!["safety-map", "--region", "chest", "--out", d];
        all.extend(args.iter());
        let out = flexrig(&all);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{all:?}: {err}");
        assert!(err.contains(flag), "{all:?}: {err}");
        assert!(!dir.join("safety_map.csv").exists(), "no partial output");
    }
}

#[test]
fn the_report_is_written_as_markdown_and_html_with_trace_figure_and_caveat() {
    let dir = tmp("report");
    std::fs::create_dir_all(&dir).unwrap();
    let base = [
        "safety",
        "--region",
        "hands_and_fingers",
        "--area",
        "Back of the hand ND",
        "--m-r",
        "0.051",
        "--m-e",
        "0.412",
        "--gamma",
        "1",
        "--material",
        "skinned_aluminium",
        "--k-delta",
        "1e4",
        "--moving-mass",
        "0.9",
        "--payload",
        "0.412",
        "--method",
        "standard,energy,simulation",
        "--speed",
        "1.5",
    ];
    for name in ["r.md", "r.html"] {
        let path = dir.join(name);
        let mut args = base.to_vec();
        // the second report replaces the first one's figure beside it: --force
        args.extend(["--report", path.to_str().unwrap(), "--force"]);
        let text = ok(&args);
        assert!(text.contains("wrote"), "{text}");
        let report = std::fs::read_to_string(&path).unwrap();
        for needle in [
            "ISO/PAS 5672",
            "ISO/TS 15066:2016",
            "first edition, 2016-02-15",
            "Table A.3",
            "spring_constant_n_per_mm",
            "Method a: the standard",
            "Method b: the lumped energy method",
            "Method c: simulation",
            "(Eq. A.5)",
            "U(F_max) =",
            "peak/F_max − 1",
            "pass",
            "Overall: the permissible speed is",
        ] {
            assert!(report.contains(needle), "{name}: no {needle:?}");
        }
        // the Markdown links its figure; the HTML is self-contained, the figure inline
        if name == "r.md" {
            assert!(
                report.contains("r_peak_force.svg"),
                "{name}: no figure link"
            );
        } else {
            assert!(
                report.contains("<svg") && !report.contains("<img"),
                "{name}: not inline"
            );
        }
        assert!(!report.contains("NaN") && !report.contains("null"));
        assert!(dir.join("r_peak_force.svg").exists());
    }
    assert!(
        std::fs::read_to_string(dir.join("r.html"))
            .unwrap()
            .starts_with("<!DOCTYPE html>")
    );
    let out = flexrig(&[
        "safety", "--region", "chest", "--m-eff", "1", "--report", "r.txt",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--report"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// The one-column figure (three panels stacked in 3.5 in) fits a journal page's column: at most
/// 9 in tall, its text at least 8 pt (the panels are flattened rather than the text shrunk).
#[test]
fn the_one_column_map_fits_a_page_column() {
    let dir = tmp("one_column");
    let d = dir.to_str().unwrap();
    ok(&[
        "safety-map",
        "--region",
        "hands_and_fingers",
        "--material",
        "skinned_aluminium",
        "--m-r",
        "0.051",
        "--x",
        "m-e=0.01:5:4:log",
        "--y",
        "k-delta=10:1e7:4:log",
        "--size",
        "1",
        "--format",
        "svg",
        "--out",
        d,
    ]);
    let svg = std::fs::read_to_string(dir.join("safety_map.svg")).unwrap();
    let inches = |attr: &str| -> f64 {
        let at = svg.find(&format!("{attr}=\"")).unwrap() + attr.len() + 2;
        let end = svg[at..].find("in\"").unwrap();
        svg[at..at + end].parse().unwrap()
    };
    assert_eq!(inches("width"), 3.5);
    let h = inches("height");
    assert!(h <= 9.0 && h > 6.0, "height {h} in");
}
