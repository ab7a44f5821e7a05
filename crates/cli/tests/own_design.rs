//! Own-robot parameters of `fig6`, `eta`, `eta-map` and `eta-rotor` (m_r, k_c, v0, L and the
//! cases): the paper's values given explicitly reproduce the defaults bit for bit; another design
//! matches the lumped model's independent closed forms (paper Eq. 13 for n = 1, the energy
//! balance for n = 2), and the figures and tables say which values ran.

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
    let dir = std::env::temp_dir().join(format!("flexrig-design-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The paper's design and cases, spelt out.
const PAPER: [&str; 12] = [
    "--m-r",
    "10",
    "--k-c",
    "1e8",
    "--v0",
    "2",
    "--m-h",
    "4,1000",
    "--k-delta",
    "1e8,200",
    "--m-e",
    "0.1,10",
];

/// Lumped peak force [N] by the energy balance ½ μ v0² = f²/(2 k_δ) + f (f/k_c)^{1/n}/(n + 1)
/// (paper Eq. 10–14), solved by bisection: independent of the library.
fn lumped_peak(m_h: f64, m_eff: f64, k_delta: f64, k_c: f64, n: f64, v0: f64) -> f64 {
    let mu = m_h * m_eff / (m_h + m_eff);
    let energy = 0.5 * mu * v0 * v0;
    let u = |f: f64| f * f / (2.0 * k_delta) + f * (f / k_c).powf(1.0 / n) / (n + 1.0);
    let (mut lo, mut hi) = (0.0, 1.0);
    while u(hi) < energy {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if u(mid) < energy { lo = mid } else { hi = mid }
    }
    0.5 * (lo + hi)
}

#[test]
fn fig6_with_the_papers_values_given_is_the_default_bit_for_bit() {
    let dir = scratch_dir("fig6");
    let out = dir.to_str().unwrap();
    let default = json(&["fig6", "--points", "5", "--out", out, "--json"]);
    let mut args = vec!["fig6", "--points", "5", "--out", out, "--json"];
    args.extend(PAPER);
    let explicit = json(&args);
    assert_eq!(default["cases"], explicit["cases"]);
    assert_eq!(default["cases"].as_array().unwrap().len(), 16);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn fig6_of_another_robot_matches_the_closed_forms_and_says_what_ran() {
    let dir = scratch_dir("fig6-own");
    let out = dir.to_str().unwrap();
    let (m_r, k_c, v0, m_h, k_delta, m_e): (f64, f64, f64, f64, f64, f64) =
        (3.0, 5e7, 1.5, 70.0, 1e5, 0.5);
    let v = json(&[
        "fig6",
        "--points",
        "3",
        "--out",
        out,
        "--json",
        "--m-r",
        "3",
        "--k-c",
        "5e7",
        "--v0",
        "1.5",
        "--m-h",
        "70",
        "--k-delta",
        "1e5",
        "--m-e",
        "0.5",
    ]);
    let cases = v["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 2);
    let m_eff = |gamma: f64| m_e + gamma * m_r / 3.0;
    // n = 1, Eq. 13: f_max = v0 √(k_o μ), k_o = k_δ k_c/(k_δ + k_c); η(γ) = √(μ(γ)/μ(1))
    let mu = |gamma: f64| m_h * m_eff(gamma) / (m_h + m_eff(gamma));
    let eta1 = (mu(2.0 / 3.0) / mu(1.0)).sqrt();
    let got = cases[0]["eta_at_2_3"].as_f64().unwrap();
    assert_eq!(cases[0]["n"], 1.0);
    assert!((got / eta1 - 1.0).abs() < 1e-12, "{got} vs {eta1}");
    // n = 2 by the energy balance (tolerance: the library's root finder, 1e-10)
    let eta2 = lumped_peak(m_h, m_eff(2.0 / 3.0), k_delta, k_c, 2.0, v0)
        / lumped_peak(m_h, m_eff(1.0), k_delta, k_c, 2.0, v0);
    let got = cases[1]["eta_at_2_3"].as_f64().unwrap();
    assert!((got / eta2 - 1.0).abs() < 1e-9, "{got} vs {eta2}");
    // the figure and the table name the values that ran
    let svg = std::fs::read_to_string(dir.join("fig6.svg")).unwrap();
    assert!(
        svg.contains("</tspan> = 3 kg") && svg.contains("</tspan> = 1.5 m/s"),
        "title"
    );
    let text = String::from_utf8(
        flexrig(&[
            "fig6",
            "--points",
            "3",
            "--out",
            out,
            "--m-r",
            "3",
            "--m-h",
            "70",
            "--k-delta",
            "1e5",
            "--m-e",
            "0.5",
        ])
        .stdout,
    )
    .unwrap();
    assert!(
        text.contains("m_r = 3 kg") && !text.contains("0.89"),
        "{text}"
    );
    // out of range: exit 2 naming the flag
    for (flag, value) in [
        ("--m-r", "0"),
        ("--k-c", "-1"),
        ("--v0", "1e9"),
        ("--m-h", "nan"),
        ("--m-e", "0.1,0.1"),
        ("--k-delta", "1,2,3,4,5"),
    ] {
        let o = flexrig(&["fig6", "--out", out, &format!("{flag}={value}")]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}: {stderr}");
        assert!(stderr.contains(flag), "{stderr}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn eta_and_its_maps_take_the_design_and_the_papers_values_change_nothing() {
    let dir = scratch_dir("eta");
    let out = dir.to_str().unwrap();
    // eta on one case: the paper's values spelt out reproduce the default bit for bit
    let one = ["--m-h", "4", "--k-delta", "1e8", "--m-e", "0.1"];
    let mut args = vec!["eta", "--out", out, "--json"];
    args.extend(one);
    let default = json(&args);
    args.extend(["--m-r", "10", "--k-c", "1e8", "--v0", "2", "--length", "1"]);
    let explicit = json(&args);
    assert_eq!(default["rows"], explicit["rows"]);
    assert_eq!(default["rows"].as_array().unwrap().len(), 2);
    // another robot: the lumped columns are the closed forms (n = 1: Eq. 13)
    let (m_r, k_c, v0, m_h, k_delta, m_e): (f64, f64, f64, f64, f64, f64) =
        (2.0, 3e7, 1.0, 4.0, 1e8, 0.1);
    let v = json(&[
        "eta",
        "--out",
        out,
        "--json",
        "--m-h",
        "4",
        "--k-delta",
        "1e8",
        "--m-e",
        "0.1",
        "--m-r",
        "2",
        "--k-c",
        "3e7",
        "--v0",
        "1",
    ]);
    let row = &v["rows"][0];
    assert_eq!(row["n"], 1.0);
    let m_eff = m_e + m_r / 3.0;
    let mu = m_h * m_eff / (m_h + m_eff);
    let k_o = k_delta * k_c / (k_delta + k_c);
    let f_cj = v0 * (k_o * mu).sqrt();
    let got = row["f_cj_lumped_n"].as_f64().unwrap();
    assert!((got / f_cj - 1.0).abs() < 1e-10, "{got} vs {f_cj}");
    assert_eq!(v["settings"]["design"]["m_r"], 2.0);

    // eta-rotor and eta-map: the paper's values spelt out change nothing
    let rotor = |extra: &[&str]| {
        let mut a = vec![
            "eta-rotor",
            "--out",
            out,
            "--json",
            "--points",
            "2",
            "--n",
            "2",
            "--m-h",
            "4",
            "--k-delta",
            "1e8",
            "--m-e",
            "0.1",
        ];
        a.extend(extra);
        json(&a)
    };
    assert_eq!(
        rotor(&[])["points"],
        rotor(&["--m-r", "10", "--k-c", "1e8", "--v0", "2", "--length", "1"])["points"]
    );
    // eta-map: the same table, byte for byte
    let map = |sub: &str, extra: &[&str]| {
        let d = dir.join(sub);
        let mut a = vec![
            "eta-map",
            "--out",
            d.to_str().unwrap(),
            "--points",
            "2",
            "--m-h",
            "4",
        ];
        a.extend(extra);
        let o = flexrig(&a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(d.join("eta_map.csv")).unwrap()
    };
    assert_eq!(
        map("map-default", &[]),
        map(
            "map-explicit",
            &["--m-r", "10", "--k-c", "1e8", "--v0", "2", "--length", "1"]
        )
    );
    let svg = std::fs::read_to_string(dir.join("map-default/eta_map_mh4.svg")).unwrap();
    // the title typesets m_r with a subscript
    assert!(svg.contains("</tspan> = 10 kg"), "map title");
    let o = flexrig(&["eta-map", "--out", out, "--points", "2", "--m-r", "1e9"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--m-r"));
    let _ = std::fs::remove_dir_all(&dir);
}
