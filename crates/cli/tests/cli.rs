//! End-to-end tests of the `flexrig` binary: JSON output against independent references, files
//! written, and bad input rejected with exit code 2 and the flag named.

use std::path::PathBuf;
use std::process::{Command, Output};

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
    let dir = std::env::temp_dir().join(format!("flexrig-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn rel(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

const FIG6_CJ: [&str; 15] = [
    "impact",
    "--m-h",
    "4",
    "--gamma",
    "1",
    "--m-r",
    "10",
    "--m-e",
    "0.1",
    "--k-delta",
    "1e8",
    "--k-c",
    "1e8",
    "--v0",
    "2",
];

#[test]
fn impact_methods_agree_with_the_references() {
    // references.md: 19222.55775 N (n = 1) and 2296.617006 N (n = 2).
    for (n, reference) in [("1", 19222.55775), ("2", 2296.617006)] {
        for method in ["exact", "ode"] {
            let mut args = FIG6_CJ.to_vec();
            args.extend(["--n", n, "--method", method, "--rtol", "1e-12", "--json"]);
            let v = json(&args);
            assert_eq!(v["method"], method);
            let f = v["f_max_n"].as_f64().unwrap();
            assert!(rel(f, reference) < 5e-10, "{method} n = {n}: {f}");
            assert!(v["delta_max_m"].as_f64().unwrap() > 0.0);
            if method == "ode" {
                let t_peak = v["t_peak_s"].as_f64().unwrap();
                let duration = v["contact_duration_s"].as_f64().unwrap();
                assert!(rel(duration, 2.0 * t_peak) < 1e-8);
                assert!(v["rhs_evals"].as_u64().unwrap() > 0);
            }
        }
    }
    let mut args = FIG6_CJ.to_vec();
    args.extend(["--n", "1", "--method", "analytic", "--json"]);
    let v = json(&args);
    assert!(rel(v["f_max_n"].as_f64().unwrap(), 19222.55775) < 5e-10);
}

#[test]
fn impact_text_report() {
    let mut args = FIG6_CJ.to_vec();
    args.extend(["--n", "2"]);
    let out = flexrig(&args);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("peak force f_max") && text.contains("2.2966170057e3"),
        "{text}"
    );
}

#[test]
fn bad_impact_input_names_the_flag_and_exits_2() {
    let base = [
        "impact",
        "--m-h",
        "4",
        "--m-eff",
        "1",
        "--k-delta",
        "1e8",
        "--k-c",
        "1e8",
        "--n",
        "2",
        "--v0",
        "2",
    ];
    for (flag, bad) in [
        ("--m-h", "-4"),
        ("--m-eff", "0"),
        ("--k-delta", "NaN"),
        ("--k-c", "inf"),
        ("--n", "0"),
        ("--n", "-1"),
        ("--v0", "0"),
    ] {
        let mut args = base.to_vec();
        let i = args.iter().position(|a| *a == flag).unwrap();
        args[i + 1] = bad;
        let out = flexrig(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{flag} {bad}: {err}");
        assert!(err.contains(flag) && err.contains("must"), "{err}");
        assert!(out.stdout.is_empty(), "no half report on stdout");
    }
    let mut args = FIG6_CJ.to_vec();
    args.extend(["--n", "2"]);
    args[4] = "1.5"; // --gamma
    let out = flexrig(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--gamma"));
    // analytic needs n = 1
    let mut args = base.to_vec();
    args.extend(["--method", "analytic"]);
    let out = flexrig(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("n = 1"));
    // rtol out of range
    let mut args = base.to_vec();
    args.extend(["--method", "ode", "--rtol", "0"]);
    let out = flexrig(&args);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--rtol"));
    // missing mass
    let out = flexrig(&[
        "impact",
        "--m-h",
        "4",
        "--k-delta",
        "1",
        "--k-c",
        "1",
        "--n",
        "1",
        "--v0",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn fig6_writes_csv_and_svg_and_reports_the_papers_etas() {
    let dir = scratch_dir("fig6");
    let v = json(&[
        "fig6",
        "--out",
        dir.to_str().unwrap(),
        "--points",
        "11",
        "--json",
    ]);
    let cases = v["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 16);
    for c in cases {
        assert_eq!(c["gamma"].as_array().unwrap().len(), 11);
        assert_eq!(c["eta"].as_array().unwrap().len(), 11);
        let (m_h, m_e, n) = (
            c["m_h"].as_f64().unwrap(),
            c["m_e"].as_f64().unwrap(),
            c["n"].as_f64().unwrap(),
        );
        let eta = c["eta_at_2_3"].as_f64().unwrap();
        // The paper's η(2/3) = 0.89 (m_h = 4) and 0.82 (m_h = 1000) for m_e = 0.1, n = 1.
        if m_e == 0.1 && n == 1.0 {
            let paper = if m_h == 4.0 { 0.89 } else { 0.82 };
            assert!((eta - paper).abs() < 0.005, "{c}");
        }
    }
    let csv = std::fs::read_to_string(dir.join("fig6.csv")).unwrap();
    assert!(csv.starts_with("m_h_kg,k_delta_n_per_m,m_e_kg,n,gamma,eta\n"));
    assert_eq!(csv.lines().count(), 1 + 16 * 11);
    let svg = std::fs::read_to_string(dir.join("fig6.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    // η(2/3) tabulated per panel (n = 1, m_e = 0.1 kg: the paper's 0.89 and 0.82), the legend,
    // the four panels and the note on the coinciding curves of the soft link.
    for label in [
        "η(2/3)",
        "0.892",
        "0.823",
        "n = 1 (linear contact)",
        "n = 2 (Hertz contact)",
        "(d) m",
        "coincide",
    ] {
        assert!(svg.contains(label), "{label} missing from fig6.svg");
    }
    assert!(!svg.contains("NaN"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fig6_rejects_too_few_points() {
    let out = flexrig(&["fig6", "--points", "1", "--out", "/nonexistent/never"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--points"));
}

#[test]
fn fit_recovers_a_known_law_from_a_csv() {
    let dir = scratch_dir("fit");
    let path = dir.join("data.csv");
    let mut text = String::from("indentation_m,force_n\n");
    for i in 1..=40 {
        let d = 1e-4 * i as f64;
        // Deterministic ±0.5 N "noise" with zero mean.
        let noise = if i % 2 == 0 { 0.5 } else { -0.5 };
        text.push_str(&format!("{d},{}\n", 7.359e7 * d.powf(1.961) + noise));
    }
    std::fs::write(&path, text).unwrap();
    let v = json(&["fit", path.to_str().unwrap(), "--json"]);
    let (k, n) = (v["k"].as_f64().unwrap(), v["n"].as_f64().unwrap());
    let (k_se, n_se) = (
        v["k_stderr"].as_f64().unwrap(),
        v["n_stderr"].as_f64().unwrap(),
    );
    assert!((n - 1.961).abs() < 4.0 * n_se, "{v}");
    assert!((k - 7.359e7).abs() < 4.0 * k_se, "{v}");
    assert!(v["r2"].as_f64().unwrap() > 0.999);

    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "indentation_m,force_n\n0.001,1\n0.002,oops\n").unwrap();
    let out = flexrig(&["fit", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("line 3"));
    std::fs::write(&bad, "").unwrap();
    let out = flexrig(&["fit", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let out = flexrig(&["fit", dir.join("missing.csv").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing.csv"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn default_job_runs_and_says_where_its_output_is() {
    let dir = scratch_dir("default");
    let out = Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.contains("out/fig9.svg") && text.contains("out/experiment.csv"),
        "{text}"
    );
    assert!(dir.join("out/fig9.svg").exists() && dir.join("out/cl_iron_4.mcap").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn experiment_reports_the_papers_comparison() {
    let dir = scratch_dir("experiment");
    let v = json(&[
        "experiment",
        "--repeats",
        "3",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let groups = v["groups"].as_array().unwrap();
    assert_eq!(groups.len(), 6);
    let mean = |scene: &str| {
        groups.iter().find(|g| g["scene"] == scene).unwrap()["mean_peak_force_n"]
            .as_f64()
            .unwrap()
    };
    // The paper's findings (Fig. 9): CL at most slightly below CJ with the 412 g payload (here
    // 1–2 %), clearly below with the light load (here about 6 %).
    for op in ["aluminium", "iron"] {
        let ratio = mean(&format!("cl_{op}")) / mean(&format!("cj_{op}"));
        assert!(ratio < 1.0 && ratio > 0.95, "{op}: CL/CJ = {ratio}");
    }
    let light = mean("cl_light_load") / mean("cj_light_load");
    assert!(
        light < mean("cl_aluminium") / mean("cj_aluminium"),
        "light load CL/CJ = {light}"
    );
    // 3 repeats × 4 configurations + 2 light-load runs, each with its log.
    let runs = v["runs"].as_array().unwrap();
    assert_eq!(runs.len(), 14);
    for r in runs {
        assert!(std::path::Path::new(r["mcap"].as_str().unwrap()).exists());
    }
    let csv = std::fs::read_to_string(dir.join("experiment.csv")).unwrap();
    assert_eq!(csv.lines().count(), 15);
    check_paired_ratios(&v, &csv);
    let svg = std::fs::read_to_string(dir.join("fig9.svg")).unwrap();
    let text = flexrig::plots::inspect::texts(&svg).join("\n");
    for label in [
        "(a) m_e = 412 g",
        // panel (b), the light load, is one run: the note says which panel is a mean
        "Bars: (a) mean of 3 runs ± 95 % CI; (b) one run, no confidence interval.",
        "(b) m_e = 100 g",
        "1 pair, no CI",
        "(c) CL/CJ, paired by repeat",
        "CL = CJ",
        "peak impact force [N]",
        "iron",
        "m_h = 4008 g",
    ] {
        assert!(
            text.contains(label) || text.replace('\n', " ").contains(label),
            "{label} missing from fig9.svg:\n{text}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
    // The same seed gives the same runs (release angles from a seeded RNG).
    let again = json(&[
        "experiment",
        "--repeats",
        "3",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    assert_eq!(again["groups"], v["groups"]);
    let _ = std::fs::remove_dir_all(&dir);
    let out = flexrig(&["experiment", "--repeats", "0"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--repeats"));
}

/// The paired CL/CJ ratios of `flexrig experiment --json` (3 repeats) against an independent
/// computation from its own runs: per-repeat ratios at the same release angle, their mean and
/// the Student t half-width with t(0.975, 2) = 4.303 (tables); one light-load pair, no interval.
fn check_paired_ratios(v: &serde_json::Value, csv: &str) {
    let runs = v["runs"].as_array().unwrap();
    let run = |scene: &str, repeat: u64| {
        runs.iter()
            .find(|r| r["scene"] == scene && r["repeat"] == repeat)
            .unwrap()
    };
    let ratios = v["ratios"].as_array().unwrap();
    assert_eq!(ratios.len(), 3, "{ratios:?}");
    let find = |case: &str| ratios.iter().find(|r| r["case"] == case).unwrap();
    for op in ["aluminium", "iron"] {
        let (cj, cl) = (format!("cj_{op}"), format!("cl_{op}"));
        let x: Vec<f64> = (0..3)
            .map(|i| {
                let (a, b) = (run(&cj, i), run(&cl, i));
                assert_eq!(a["release_angle_deg"], b["release_angle_deg"]);
                b["peak_force_n"].as_f64().unwrap() / a["peak_force_n"].as_f64().unwrap()
            })
            .collect();
        let mean = (x[0] + x[1] + x[2]) / 3.0;
        let s =
            (((x[0] - mean).powi(2) + (x[1] - mean).powi(2) + (x[2] - mean).powi(2)) / 2.0).sqrt();
        let half = 4.303 * s / 3f64.sqrt();
        let r = find(op);
        assert_eq!(r["pairs"], 3);
        assert!(
            rel(r["mean_cl_over_cj"].as_f64().unwrap(), mean) < 1e-14,
            "{r}"
        );
        // the same ratios summed in another order: round-off of ratios near 1 (a few 1e-16),
        // relative to an interval as narrow as 5e-7 (the aluminium pair) up to 1e-9 of it
        let ci95 = r["ci95"].as_f64().unwrap();
        assert!((ci95 - half).abs() <= 1e-12 * half + 1e-14, "{r} vs {half}");
        // The CSV's CL rows carry the same numbers (to its 10 significant digits).
        let column = csv
            .lines()
            .next()
            .unwrap()
            .split(',')
            .position(|c| c == "cl_over_cj_ci95")
            .unwrap();
        for line in csv.lines().filter(|l| l.starts_with(&format!("{cl},"))) {
            let fields: Vec<&str> = line.split(',').collect();
            let ci: f64 = fields[column].parse().unwrap();
            assert!(rel(ci, half) < 1e-9, "{line}");
        }
    }
    let light = find("light_load");
    assert_eq!(light["pairs"], 1);
    assert!(light.get("ci95").is_none(), "{light}");
}

/// Regression: `experiment --json` wrote `null` for the contact duration of runs stopped at the
/// peak, where `run --json` omits the key.
#[test]
fn experiment_json_omits_a_missing_duration_like_run() {
    let dir = scratch_dir("experiment-peak");
    let out_dir = dir.to_str().unwrap();
    let v = json(&[
        "experiment",
        "--repeats",
        "1",
        "--set",
        "stop.at=peak",
        "--out",
        out_dir,
        "--json",
    ]);
    let text = v.to_string();
    assert!(!text.contains("null") && !text.contains("NaN"), "{text}");
    for r in v["runs"].as_array().unwrap() {
        assert!(r.get("contact_duration_s").is_none(), "{r}");
        assert!(r["peak_force_n"].as_f64().unwrap() > 0.0);
    }
    let scene = format!(
        "{}/../../assets/scenes/cj_aluminium.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let run = json(&["run", &scene, "--set", "stop.at=peak", "--json"]);
    assert!(run.get("contact_duration_s").is_none(), "{run}");
}

/// A plausibility warning is a line on standard error and an entry of the JSON's `warnings`;
/// the run goes on (exit 0).
#[test]
fn a_plausibility_warning_is_printed_and_listed() {
    let scene = format!(
        "{}/../../assets/scenes/cj_aluminium.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let scene = scene.as_str();
    let o = flexrig(&[
        "run",
        scene,
        "--set",
        "operator.start.release_angle_deg=0.5",
        "--json",
    ]);
    assert!(o.status.success(), "{o:?}");
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("warning: operator.start.release_angle_deg: 0.5 looks like radians"),
        "{stderr}"
    );
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let warnings = v["warnings"].as_array().unwrap();
    assert_eq!(warnings.len(), 1, "{v}");
    assert_eq!(warnings[0]["field"], "operator.start.release_angle_deg");
    // none for a bundled scene as it is
    let v = json(&["run", scene, "--json"]);
    assert_eq!(v["warnings"], serde_json::json!([]));
}

/// One repeat: every mean, no interval anywhere — absent from the JSON (never 0, NaN or null),
/// blank in the CSV and the table, and no whisker in the figure.
#[test]
fn one_repeat_gives_no_interval() {
    let dir = scratch_dir("one-repeat");
    let out_dir = dir.to_str().unwrap();
    let v = json(&["experiment", "--repeats", "1", "--out", out_dir, "--json"]);
    let text = v.to_string();
    assert!(!text.contains("null") && !text.contains("NaN"), "{text}");
    for g in v["groups"].as_array().unwrap() {
        assert!(g.get("ci95_n").is_none(), "{g}");
        assert!(g["mean_peak_force_n"].as_f64().unwrap() > 0.0);
    }
    let ratios = v["ratios"].as_array().unwrap();
    assert_eq!(ratios.len(), 3);
    for r in ratios {
        assert!(r.get("ci95").is_none(), "{r}");
        assert!(r["mean_cl_over_cj"].as_f64().unwrap() < 1.0);
    }
    let csv = std::fs::read_to_string(dir.join("experiment.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let ci = header.iter().position(|h| *h == "cl_over_cj_ci95").unwrap();
    for line in csv.lines().skip(1) {
        assert_eq!(
            line.split(',').nth(ci),
            Some(""),
            "an empty interval field: {line}"
        );
    }
    let svg = std::fs::read_to_string(dir.join("fig9.svg")).unwrap();
    let text = flexrig::plots::inspect::texts(&svg).join("\n");
    assert!(
        text.replace('\n', " ")
            .contains("Bars: one run, no confidence interval.")
            && text.contains("1 pair, no CI"),
        "{text}"
    );
    let out = flexrig(&["experiment", "--repeats", "1", "--out", out_dir]);
    let table = String::from_utf8(out.stdout).unwrap();
    assert!(out.status.success());
    assert!(
        !table.contains("0.000") && !table.contains("NaN"),
        "{table}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// docs/cli.md's `experiment.csv` columns are the CSV's header, and its JSON keys are the JSON's.
#[test]
fn experiment_docs_list_its_csv_columns_and_json_keys() {
    let doc = std::fs::read_to_string(format!("{}/../../docs/cli.md", env!("CARGO_MANIFEST_DIR")))
        .unwrap();
    let section = &doc[doc.find("## flexrig experiment").unwrap()..];
    let section = &section[..section[3..].find("\n## ").unwrap()];
    let paragraph = |start: &str| {
        let p = &section[section.find(start).unwrap()..];
        let p = &p[..p.find("\n\n").unwrap_or(p.len())];
        p.split('`')
            .skip(1)
            .step_by(2)
            .filter(|k| {
                k.chars()
                    .all(|c| c.is_ascii_lowercase() || c == '_' || c.is_ascii_digit())
            })
            .map(str::to_string)
            .collect::<Vec<String>>()
    };
    let columns = paragraph("`experiment.csv` columns");
    let dir = scratch_dir("experiment-docs");
    let v = json(&[
        "experiment",
        "--repeats",
        "2",
        "--out",
        dir.to_str().unwrap(),
        "--json",
    ]);
    let csv = std::fs::read_to_string(dir.join("experiment.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert_eq!(columns, header, "docs/cli.md against experiment.csv");
    let keys = paragraph("JSON keys");
    let mut seen: Vec<String> = Vec::new();
    let mut collect = |value: &serde_json::Value| {
        for k in value.as_object().unwrap().keys() {
            if !seen.contains(k) {
                seen.push(k.clone());
            }
        }
    };
    collect(&v);
    for list in ["groups", "ratios", "runs"] {
        v[list].as_array().unwrap().iter().for_each(&mut collect);
    }
    for k in &seen {
        assert!(keys.contains(k), "{k} is not in docs/cli.md");
    }
    for k in keys
        .iter()
        .filter(|k| !["aluminium", "iron", "light_load"].contains(&k.as_str()))
    {
        assert!(seen.contains(k), "docs/cli.md lists {k}, the JSON has none");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_command_has_help() {
    for cmd in [
        &["--help"][..],
        &["impact", "--help"],
        &["fig6", "--help"],
        &["fit", "--help"],
    ] {
        let out = flexrig(cmd);
        assert!(out.status.success(), "{cmd:?}");
        assert!(!out.stdout.is_empty());
    }
    // the top-level help says what no command does, in the product's words
    let help = String::from_utf8(flexrig(&["--help"]).stdout).unwrap();
    assert!(
        help.contains("Without a command, flexrig replays the paper's §VI experiment"),
        "{help}"
    );
    assert!(!help.contains("clap"), "{help}");
}

fn scene_path(name: &str) -> String {
    format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    )
}

/// The JSON keys docs/cli.md promises for `flexrig run --json`: the backquoted names of its
/// "JSON keys" paragraph, split into the top level and those of each `contacts` entry (the
/// parenthesis after `contacts`).
fn documented_run_keys() -> (Vec<String>, Vec<String>) {
    let doc = std::fs::read_to_string(format!("{}/../../docs/cli.md", env!("CARGO_MANIFEST_DIR")))
        .unwrap();
    let section = &doc[doc.find("## flexrig run").expect("a run section")..];
    let para = &section[section.find("JSON keys").expect("a key list")..];
    let para = &para[..para.find("\n\n").unwrap_or(para.len())];
    let names = |text: &str| -> Vec<String> {
        text.split('`')
            .skip(1)
            .step_by(2)
            .filter(|k| {
                k.chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
            })
            .map(str::to_string)
            .collect()
    };
    let open = para.find("`contacts` (").expect("the contacts entry");
    let close = open + para[open..].find(')').unwrap();
    let inner = names(&para[open + "`contacts`".len()..close]);
    let mut outer = names(&para[..open + "`contacts`".len()]);
    outer.extend(names(&para[close..]));
    (outer, inner)
}

#[test]
fn run_json_has_every_documented_key_and_nothing_undocumented() {
    // Regression (issue 11): separation_velocity_mps and energy_through_contact_j were
    // documented but missing.
    let (outer, inner) = documented_run_keys();
    assert!(outer.len() > 15 && inner.len() > 8, "{outer:?} {inner:?}");
    for name in ["cj_aluminium", "cl_aluminium"] {
        let v = json(&["run", &scene_path(name), "--json"]);
        let map = v.as_object().unwrap();
        for key in &outer {
            assert!(
                map.contains_key(key),
                "{name}: documented {key} missing in {v}"
            );
        }
        for key in map.keys() {
            assert!(outer.contains(key), "{name}: {key} is not documented");
        }
        let contact = v["contacts"][0].as_object().unwrap();
        for key in &inner {
            assert!(
                contact.contains_key(key),
                "{name}: contacts[0] has no {key}"
            );
        }
        for key in contact.keys() {
            assert!(
                inner.contains(key),
                "{name}: contacts[0].{key} is not documented"
            );
        }
        // no null and no non-finite number anywhere
        let text = v.to_string();
        assert!(!text.contains("null") && !text.contains("NaN"), "{text}");
        // Impact speed of the 30° release of the bundled pendulum (compound pendulum energy,
        // 0.8912 m/s; the swing integration is within 1e-4).
        let speed = v["impact_velocity_mps"].as_f64().unwrap();
        assert!((speed - 0.8912).abs() < 2e-4, "{name}: {speed}");
        let peak = v["peak_force_n"].as_f64().unwrap();
        assert!(peak > 150.0 && peak < 200.0, "{name}: {peak}");
    }
}

#[test]
fn run_rejects_bad_scenes_with_exit_code_2() {
    let dir = scratch_dir("run");
    let text = std::fs::read_to_string(scene_path("cj_iron")).unwrap();
    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        text.replace("payload_kg = 0.412", "payload_kg = -1.0"),
    )
    .unwrap();
    let out = flexrig(&["run", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("robot.payload_kg"));
    let out = flexrig(&["run", dir.join("missing.toml").to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn validate_passes_every_case_and_writes_the_report() {
    let dir = scratch_dir("validate");
    let v = json(&["validate", "--out", dir.to_str().unwrap(), "--json"]);
    let cases = v["cases"].as_array().unwrap();
    assert!(cases.len() >= 40, "{} cases", cases.len());
    for c in cases {
        assert_eq!(c["pass"], true, "{c}");
        for key in ["name", "reference", "value", "error", "tolerance"] {
            assert!(c.get(key).is_some(), "{key}");
        }
    }
    let report = std::fs::read_to_string(dir.join("validation.md")).unwrap();
    assert!(report.contains(&format!("{} of {} cases pass", cases.len(), cases.len())));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_quick_reports_rows_and_plots() {
    let dir = scratch_dir("bench");
    let v = json(&["bench", "--quick", "--out", dir.to_str().unwrap(), "--json"]);
    let rows = v["rows"].as_array().unwrap();
    for model in ["lumped", "beam", "rig"] {
        assert!(rows.iter().any(|r| r["model"] == model), "no {model} rows");
    }
    for r in rows {
        for key in ["model", "method", "setting", "error", "seconds"] {
            assert!(r.get(key).is_some(), "{key} in {r}");
        }
        assert!(r["seconds"].as_f64().unwrap() > 0.0);
    }
    // The scipy peer's interpreter: FLEXRIG_PYTHON, else the project's .venv, else python3.
    let python = v["peer_python"].as_str().unwrap();
    let venv = concat!(env!("CARGO_MANIFEST_DIR"), "/../../.venv/bin/python");
    match std::env::var("FLEXRIG_PYTHON") {
        Ok(p) if !p.is_empty() => assert_eq!(python, p),
        _ if std::path::Path::new(venv).exists() => {
            assert!(python.ends_with("/.venv/bin/python"), "{python}")
        }
        _ => assert_eq!(python, "python3"),
    }
    // Tighter tolerances give smaller errors (work–precision): the lumped ode rows of one method
    // are ordered by rtol, and the error falls by at least 100× from the loosest to the tightest.
    let errors: Vec<f64> = rows
        .iter()
        .filter(|r| r["method"] == "ode indentation n=2 stiff")
        .map(|r| r["error"].as_f64().unwrap())
        .collect();
    assert!(
        errors.len() >= 3 && errors[0] > 100.0 * errors[errors.len() - 1],
        "{errors:?}"
    );
    // Each plot in panels with their legends (the labels of the series, not of the rows).
    for (name, labels) in [
        (
            "bench_lumped.svg",
            &[
                "(a) stiff link",
                "(b) soft link",
                "indentation state, n = 1",
                "median run time [s]",
            ][..],
        ),
        (
            "bench_beam.svg",
            &["(a) transients", "(b) modes and statics"][..],
        ),
        (
            "bench_rig.svg",
            &[
                "compliant joint (cj_aluminium)",
                "compliant link (cl_aluminium)",
                "start at contact",
            ][..],
        ),
    ] {
        let svg = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(svg.starts_with("<svg"));
        for label in labels {
            assert!(svg.contains(label), "{label} missing from {name}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn run_set_overrides_a_field_like_the_file_and_names_a_bad_path() {
    let dir = scratch_dir("set");
    let text = std::fs::read_to_string(scene_path("cj_aluminium"))
        .unwrap()
        .replace("payload_kg = 0.412", "payload_kg = 0.2");
    let edited = dir.join("edited.toml");
    std::fs::write(&edited, text).unwrap();
    let by_file = json(&["run", edited.to_str().unwrap(), "--json"]);
    let by_set = json(&[
        "run",
        &scene_path("cj_aluminium"),
        "--set",
        "robot.payload_kg=0.2",
        "--json",
    ]);
    assert_eq!(by_file["peak_force_n"], by_set["peak_force_n"]);
    let o = flexrig(&[
        "run",
        &scene_path("cj_aluminium"),
        "--set",
        "robot.payload=0.2",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("robot.payload"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Regression (issue 16): the README's shortcut `start = { from = "contact" }` was refused (it
/// needs the release angle). Every `start = { … }` the README shows runs, as does the `--set`
/// form it names, and both start at the contact with the speed of the bundled release.
#[test]
fn the_readme_start_shortcuts_run() {
    let readme =
        std::fs::read_to_string(format!("{}/../../README.md", env!("CARGO_MANIFEST_DIR"))).unwrap();
    let tables: Vec<&str> = readme
        .lines()
        .filter_map(|l| {
            let i = l.find("start = {")?;
            let rest = &l[i + "start = ".len()..];
            Some(&rest[..=rest.find('}')?])
        })
        .collect();
    assert!(!tables.is_empty(), "the README shows no start shortcut");
    let scene = format!(
        "{}/../../assets/scenes/cj_iron.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let release = json(&["run", &scene, "--json"]);
    let mut sets: Vec<String> = tables
        .iter()
        .map(|t| format!("operator.start={t}"))
        .collect();
    assert!(readme.contains("--set operator.start.from=contact"));
    sets.push("operator.start.from=contact".into());
    for set in &sets {
        let s = json(&["run", &scene, "--set", set, "--json"]);
        assert!(s["onset_time_s"].as_f64().unwrap() < 1e-9, "{set}: {s}");
        if !set.contains("release_angle_deg") || set.contains("= 30.0") {
            // the bundled scene releases from 30°: the same impact speed, without the swing
            let (a, b) = (
                s["impact_velocity_mps"].as_f64().unwrap(),
                release["impact_velocity_mps"].as_f64().unwrap(),
            );
            assert!(rel(a, b) < 1e-5, "{set}: {a} vs {b}");
        }
    }
}

/// The bundled compression-test example (issue 16): synthetic data made from the paper's
/// aluminium fit (k = 7.359e7, n = 1.961, §III-B) with 1 % noise; the fit recovers both within
/// three of its standard errors.
#[test]
fn the_bundled_compression_example_fits_the_paper_values() {
    let csv = format!(
        "{}/../../assets/data/compression_aluminium.csv",
        env!("CARGO_MANIFEST_DIR")
    );
    let v = json(&["fit", &csv, "--json"]);
    let (k, n) = (v["k"].as_f64().unwrap(), v["n"].as_f64().unwrap());
    let (sk, sn) = (
        v["k_stderr"].as_f64().unwrap(),
        v["n_stderr"].as_f64().unwrap(),
    );
    assert!((k - 7.359e7).abs() < 3.0 * sk, "k {k} ± {sk}");
    assert!((n - 1.961).abs() < 3.0 * sn, "n {n} ± {sn}");
    assert!(sn < 0.02 && sk < 0.1 * k, "standard errors {sk} {sn}");
}

/// `flexrig eta` (issue 14): bad input names the flag, exits 2 and leaves no CSV; a coarse run
/// prints every case with a finite η_FE and writes the CSV.
#[test]
fn eta_refuses_bad_input_and_runs_coarse() {
    let dir = scratch_dir("eta");
    let out = dir.to_str().unwrap();
    for (args, flag) in [
        (vec!["--method", "alpha", "--elements", "1"], "--elements"),
        (
            vec!["--method", "alpha", "--steps-per-contact", "5"],
            "--steps-per-contact",
        ),
        (vec!["--elements", "64"], "--elements"),
        (vec!["--method", "alpha", "--tol", "1e-6"], "--tol"),
        (vec!["--tol", "0"], "--tol"),
        (vec!["--zone-elements", "nan"], "--zone-elements"),
        (vec!["--window-periods", "0"], "--window-periods"),
        (vec!["--joint", "free-hub"], "--joint"),
        (vec!["--rotor-inertia", "2"], "--rotor-inertia"),
        (
            vec!["--joint", "free-hub", "--rotor-inertia=-1"],
            "--rotor-inertia",
        ),
        (vec!["--length", "nan"], "--length"),
        (vec!["--method", "alpha", "--modes", "0"], "--modes"),
        (
            vec!["--method", "alpha", "--elements", "2000", "--modes", "8"],
            "--modes",
        ),
        (vec!["--damping", "hunt-crossley"], "--restitution"),
        (
            vec!["--damping", "lankarani-nikravesh", "--restitution", "1.5"],
            "--restitution",
        ),
        (vec!["--restitution", "0.8"], "--restitution"),
        (
            vec!["--damping", "adams-impact", "--c-max", "1e3"],
            "--damping = adams-impact: needs --depth",
        ),
        (
            vec!["--damping", "adams-impact", "--c-max=-1", "--depth", "1e-4"],
            "--c-max",
        ),
        (
            vec![
                "--damping",
                "hunt-crossley",
                "--restitution",
                "0.8",
                "--depth",
                "1e-4",
            ],
            "--depth",
        ),
        (vec!["--damping", "viscous"], "--damping"),
    ] {
        let mut all = vec!["eta", "--out", out];
        all.extend(args);
        let o = flexrig(&all);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {stderr}");
        assert!(stderr.contains(flag), "{all:?}: {stderr}");
        assert!(!dir.join("eta.csv").exists() && !dir.join("eta.svg").exists());
    }
    // the reference method, coarse, and the default modal method
    let coarse = json(&[
        "eta",
        "--out",
        out,
        "--method",
        "alpha",
        "--elements",
        "4",
        "--steps-per-contact",
        "50",
        "--json",
    ]);
    let v = json(&["eta", "--out", out, "--json"]);
    let rows = v["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 16);
    assert_eq!(coarse["rows"].as_array().unwrap().len(), 16);
    for r in rows {
        let eta = r["eta_fe"].as_f64().unwrap();
        assert!(eta.is_finite() && eta > 0.0, "{r}");
        assert!(r["f_placed_n"].as_f64().unwrap() > 0.0, "{r}");
    }
    // the headline case against the generalized-α reference in docs/impact-fe.md (256 elements,
    // 800 steps per contact: η_FE = 0.9207)
    assert!(
        (rows[0]["eta_fe"].as_f64().unwrap() - 0.9207).abs() < 1e-4,
        "{}",
        rows[0]
    );
    let csv = std::fs::read_to_string(dir.join("eta.csv")).unwrap();
    assert_eq!(csv.lines().count(), 17);
    let svg = std::fs::read_to_string(dir.join("eta.svg")).unwrap();
    let text = flexrig::plots::inspect::texts(&svg).join("\n");
    assert!(
        text.contains("finite elements η_FE") && text.contains("held joint"),
        "{text}"
    );
    // a damped contact: no peak above the elastic one (at e = 0.8 the stiff-link peaks drop by
    // 5–10 %; on the soft lumped link the contact barely moves and damping changes the peak by
    // less than the damped lumped run's tolerance, 1e-8, so the bound allows 1e-7), and the
    // settings say which law ran
    let hc = json(&[
        "eta",
        "--out",
        out,
        "--damping",
        "hunt-crossley",
        "--restitution",
        "0.8",
        "--json",
    ]);
    assert_eq!(hc["settings"]["damping"]["model"], "hunt_crossley");
    for (d, e) in hc["rows"].as_array().unwrap().iter().zip(rows) {
        for key in ["f_cj_n", "f_cl_n", "f_cj_lumped_n"] {
            let (fd, fe) = (d[key].as_f64().unwrap(), e[key].as_f64().unwrap());
            assert!(fd <= fe * (1.0 + 1e-7), "{key}: {fd} vs elastic {fe}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `flexrig eta-map` (issue 14): bad ranges and flags name the flag, exit 2 and leave no CSV or
/// figure; a 2 × 2 map over the Fig. 6 soft-link/light-payload and rigid-link/heavy-payload
/// corners reproduces `flexrig eta`'s rows (tol 1e-5 against 1e-6: within 1e-4).
#[test]
fn the_eta_map_refuses_bad_ranges_and_matches_the_eta_table() {
    let dir = scratch_dir("eta_map");
    let out = dir.to_str().unwrap();
    for (args, flag) in [
        (vec!["--points", "1"], "--points"),
        (vec!["--mass-ratio", "1:0.1"], "--mass-ratio"),
        (vec!["--mass-ratio", "abc"], "--mass-ratio"),
        (vec!["--mass-ratio", "1e-9:1"], "--mass-ratio"),
        (vec!["--stiffness-ratio", "0:1"], "--stiffness-ratio"),
        (vec!["--stiffness-ratio", "1e-3:1e9"], "--stiffness-ratio"),
        (vec!["--m-h", "0"], "--m-h"),
        (vec!["--m-h", "4,nan"], "--m-h"),
        (vec!["--n", "5"], "--n"),
        (vec!["--tol", "0"], "--tol"),
        (vec!["--joint", "free-hub"], "--joint"),
        // Regression: an out-of-range rotor inertia failed every point, yet the figures were
        // written and the exit code was 0; a 1e20 was quoted as 21 digits.
        (
            vec!["--joint", "free-hub", "--rotor-inertia", "1e20"],
            "--rotor-inertia = 1e20",
        ),
    ] {
        let mut all = vec!["eta-map", "--out", out];
        all.extend(args);
        let o = flexrig(&all);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {stderr}");
        assert!(stderr.contains(flag), "{all:?}: {stderr}");
        assert!(!dir.exists() || std::fs::read_dir(&dir).unwrap().next().is_none());
    }
    let v = json(&[
        "eta-map",
        "--out",
        out,
        "--m-h",
        "4",
        "--n",
        "1",
        "--points",
        "2",
        "--mass-ratio",
        "1e-2:1",
        "--stiffness-ratio",
        "2e-6:1",
        "--json",
    ]);
    assert_eq!(v["maps"][0]["points"], 4);
    assert_eq!(v["maps"][0]["failed"], 0);
    let csv = std::fs::read_to_string(dir.join("eta_map.csv")).unwrap();
    assert_eq!(csv.lines().count(), 5);
    assert!(dir.join("eta_map_mh4.svg").exists());
    let table = json(&["eta", "--out", out, "--json"]);
    let eta_of = |m_e: f64, k: f64| {
        table["rows"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| {
                r["case"]["m_h"] == 4.0
                    && r["case"]["m_e"] == m_e
                    && r["case"]["k_delta"] == k
                    && r["n"] == 1.0
            })
            .unwrap()["eta_fe"]
            .as_f64()
            .unwrap()
    };
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for row in csv.lines().skip(1) {
        let f: Vec<&str> = row.split(',').collect();
        let (m_e, k): (f64, f64) = (
            f[col("m_e_kg")].parse().unwrap(),
            f[col("k_delta_n_per_m")].parse().unwrap(),
        );
        let eta: f64 = f[col("eta_fe")].parse().unwrap();
        for (case_m_e, case_k) in [(0.1, 2e2), (10.0, 1e8)] {
            if (m_e / case_m_e - 1.0).abs() < 1e-9 && (k / case_k - 1.0).abs() < 1e-9 {
                let reference = eta_of(case_m_e, case_k);
                assert!((eta / reference - 1.0).abs() < 1e-4, "{row}: {reference}");
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `flexrig payload` (issue 14): the curve's point at the bundled light-load payload (0.1 kg) is
/// the bundled cj_light_load/cl_light_load pair run on its own; bad input names the flag, exit 2.
#[test]
fn the_payload_curve_runs_the_bundled_light_load_pair() {
    let dir = scratch_dir("payload");
    let out = dir.to_str().unwrap();
    let v = json(&[
        "payload",
        "--payloads",
        "0.1:1:2:log",
        "--out",
        out,
        "--json",
    ]);
    let row = &v["rows"][0];
    assert_eq!(row["payload_kg"].as_f64(), Some(0.1));
    for design in ["cj", "cl"] {
        let scene = format!(
            "{}/../../assets/scenes/{design}_light_load.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let alone = json(&["run", &scene, "--json"])["peak_force_n"]
            .as_f64()
            .unwrap();
        let curve = row[format!("{design}_peak_n")].as_f64().unwrap();
        assert!(rel(curve, alone) < 1e-12, "{design}: {curve} vs {alone}");
    }
    assert_eq!(v["logs"].as_array().unwrap().len(), 6);
    for (args, flag) in [
        (vec!["--payloads", "0:1"], "--payloads"),
        (vec!["--payloads", "1:0.5"], "FROM must be smaller than TO"),
        (vec!["--payloads", "100:1000"], "did you give grams?"),
        (vec!["--payloads", "0.1:1:5"], "--payloads"),
        (vec!["--points", "1"], "--points"),
        (vec!["--scene", "nope"], "--scene"),
    ] {
        let mut all = vec!["payload", "--out", out];
        all.extend(args);
        let o = flexrig(&all);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {stderr}");
        assert!(stderr.contains(flag), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `flexrig experiment --set` (issue 15): the override reaches every scene; the light-load run
/// (no jitter) equals `flexrig run --set` of the same scene; an unknown field exits 2, naming it.
#[test]
fn experiment_overrides_reach_every_scene() {
    let dir = scratch_dir("experiment-set");
    let out = dir.to_str().unwrap();
    let v = json(&[
        "experiment",
        "--repeats",
        "2",
        "--set",
        "robot.payload_kg=0.2",
        "--out",
        out,
        "--json",
    ]);
    let scene = format!(
        "{}/../../assets/scenes/cj_light_load.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let alone = json(&["run", &scene, "--set", "robot.payload_kg=0.2", "--json"]);
    let light = v["groups"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["scene"] == "cj_light_load")
        .unwrap();
    let (a, b) = (
        light["mean_peak_force_n"].as_f64().unwrap(),
        alone["peak_force_n"].as_f64().unwrap(),
    );
    assert!(rel(a, b) < 1e-12, "{a} vs {b}");
    let o = flexrig(&["experiment", "--set", "robot.nope=1", "--out", out]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("nope"), "{stderr}");
    // Regression: `--set robot.design=cl` ran and made every CL/CJ ratio 1.0; an override's
    // range error cited a line of the text the overrides had produced.
    for (set, named) in [
        ("robot.design=cl", "--set robot.design"),
        (
            "operator.block_material=skinned_iron",
            "--set operator.block_material",
        ),
        ("robot={ design = \"cl\" }", "--set robot"),
        ("robot.payload_kg=-1", "robot.payload_kg"),
    ] {
        let o = flexrig(&["experiment", "--set", set, "--out", out]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{set}: {stderr}");
        assert!(stderr.contains(named), "{set}: {stderr}");
        assert!(!stderr.contains("line "), "{set}: {stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `flexrig eta-rotor` (issue 14): bad input names the flag, exits 2 and writes nothing; a
/// two-point sweep ends in the held joint, whose η_FE is `flexrig eta`'s (CJ by the modal
/// integrator here, by DOP853 there: within 1e-5), and at ρ = 1e8 the curve has reached it.
#[test]
fn the_rotor_sweep_refuses_bad_input_and_ends_at_the_held_joint() {
    let dir = scratch_dir("eta_rotor");
    let out = dir.to_str().unwrap();
    for (args, flag) in [
        (vec!["--ratio", "1e-12:1"], "--ratio"),
        (vec!["--ratio", "10:1"], "--ratio"),
        (vec!["--ratio", "x"], "--ratio"),
        (vec!["--points", "1"], "--points"),
        (vec!["--n", "5"], "--n"),
        (vec!["--tol", "0"], "--tol"),
        (vec!["--damping", "hunt-crossley"], "--restitution"),
    ] {
        let mut all = vec!["eta-rotor", "--out", out];
        all.extend(args);
        let o = flexrig(&all);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {stderr}");
        assert!(stderr.contains(flag), "{all:?}: {stderr}");
        assert!(!dir.exists() || std::fs::read_dir(&dir).unwrap().next().is_none());
    }
    let v = json(&[
        "eta-rotor",
        "--out",
        out,
        "--ratio",
        "1e-8:1e8",
        "--points",
        "2",
        "--n",
        "2",
        "--json",
    ]);
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 8 * 3);
    let table = json(&["eta", "--out", out, "--json"]);
    for curve in points.chunks(3) {
        let held = &curve[2];
        assert!(held["inertia_ratio"].is_null());
        let row = table["rows"]
            .as_array()
            .unwrap()
            .iter()
            .find(|r| r["case"] == held["case"] && r["n"] == held["n"])
            .unwrap();
        let (a, b) = (
            held["eta_fe"].as_f64().unwrap(),
            row["eta_fe"].as_f64().unwrap(),
        );
        assert!((a - b).abs() <= 1e-5 * b, "{held} vs {row}");
        let heavy = curve[1]["eta_fe"].as_f64().unwrap();
        assert!((heavy - a).abs() <= 1e-5 * a, "{} vs held {a}", curve[1]);
    }
    assert!(dir.join("eta_rotor.csv").exists() && dir.join("eta_rotor.svg").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
