//! Hostile command lines (issue 11): every case ends quickly with exit code 2 and an error that
//! names the flag, or runs to a result with no null or non-finite number; never a panic.

use std::process::{Command, Output};

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .unwrap()
}

const BEAM: [&str; 8] = [
    "--length",
    "0.3",
    "--youngs",
    "1.5e9",
    "--density",
    "905",
    "--width",
    "0.064",
];

/// `base` with `flag` set to `value` (as `--flag=value`, so that "-inf" is a value).
fn with(base: &[&str], flag: &str, value: &str) -> Vec<String> {
    let mut args: Vec<String> = Vec::new();
    let mut i = 0;
    while i < base.len() {
        if base[i] == flag {
            i += 2;
            continue;
        }
        args.push(base[i].to_string());
        i += 1;
    }
    args.push(format!("{flag}={value}"));
    args
}

/// Runs `args` and checks the outcome: exit 2 naming `flag`, or success without null/NaN.
fn check(args: &[String], flag: &str) {
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    let start = std::time::Instant::now();
    let o = flexrig(&refs);
    let stderr = String::from_utf8_lossy(&o.stderr);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(!stderr.contains("panicked"), "{args:?}: a panic\n{stderr}");
    match o.status.code() {
        Some(0) => assert!(
            !stdout.contains("null") && !stdout.contains("NaN") && !stdout.contains("inf"),
            "{args:?}: {stdout}"
        ),
        Some(2) => assert!(
            stderr.contains(flag),
            "{args:?}: {stderr} does not name {flag}"
        ),
        other => panic!("{args:?}: exit {other:?}\n{stderr}"),
    }
    assert!(
        start.elapsed().as_secs_f64() < 20.0,
        "{args:?}: took {:?}",
        start.elapsed()
    );
}

#[test]
fn beam_flags_out_of_range_name_the_flag() {
    // Regression: `beam modal --length 1e-300` failed with "Cholesky … NonPositivePivot",
    // `--thickness 5e-324` with "invalid ei = 0", `--elements 100000` panicked in faer.
    let mut modal = vec!["beam", "modal"];
    modal.extend(BEAM);
    modal.extend(["--thickness", "0.00256", "--json"]);
    let mut statics = vec!["beam", "static"];
    statics.extend(BEAM);
    statics.extend(["--thickness", "0.00256", "--tip-load", "1", "--json"]);
    let values = [
        "0", "-1", "1e-300", "5e-324", "1e300", "nan", "inf", "-inf", "1e-12", "1e12",
    ];
    for flag in [
        "--length",
        "--youngs",
        "--density",
        "--width",
        "--thickness",
        "--tip-mass",
        "--k-theta",
    ] {
        for v in values {
            check(&with(&modal, flag, v), flag);
        }
    }
    for v in ["0", "100000", "1001", "18446744073709551615", "-3"] {
        check(&with(&modal, "--elements", v), "--elements");
    }
    for v in ["nan", "1e300", "-1e300", "inf"] {
        check(&with(&statics, "--tip-load", v), "--tip-load");
        check(&with(&statics, "--tip-moment", v), "--tip-moment");
    }
    check(&with(&statics, "--load-steps", "0"), "--load-steps");
}

#[test]
fn impact_flags_out_of_range_name_the_flag_and_results_are_finite() {
    // Regression: `impact --v0 1e300` printed "f_max_n": null with exit code 0.
    let base = [
        "impact",
        "--m-h",
        "4",
        "--m-eff",
        "3.43",
        "--k-delta",
        "1e8",
        "--k-c",
        "1e8",
        "--n",
        "2",
        "--v0",
        "2",
        "--json",
    ];
    for flag in ["--m-h", "--m-eff", "--k-delta", "--k-c", "--n", "--v0"] {
        for v in [
            "0", "-1", "1e-300", "1e300", "nan", "inf", "1e-9", "1e3", "20",
        ] {
            check(&with(&base, flag, v), flag);
        }
    }
    for v in ["0", "1e-20", "1", "nan"] {
        let mut args = with(&base, "--method", "ode");
        args = with(
            &args.iter().map(String::as_str).collect::<Vec<_>>(),
            "--rtol",
            v,
        );
        check(&args, "--rtol");
    }
}

#[test]
fn fit_data_problems_name_the_line_and_extreme_units_work_or_say_why() {
    let dir = std::env::temp_dir().join(format!("flexrig-hostile-fit-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases = [
        (
            "negative",
            "indentation_m,force_n\n0.001,1\n0.002,-4\n0.003,9\n",
            "line 3",
        ),
        ("nan", "0.001,1\n0.002,nan\n", "line 2"),
        ("text", "0.001,1\nabc,2\n", "line 2"),
    ];
    for (name, text, expected) in cases {
        let path = dir.join(format!("{name}.csv"));
        std::fs::write(&path, text).unwrap();
        let o = flexrig(&["fit", path.to_str().unwrap(), "--json"]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains(expected), "{name}: {stderr}");
    }
    // Regression: values of 1e300 or 1e-300 gave null standard errors.
    for (name, d, f) in [
        ("huge", 1e-100, 1e150),
        ("tiny", 1e-300, 1e-300),
        ("big", 1.0, 1e300),
    ] {
        let text: String = (1..=20)
            .map(|i| {
                let x = i as f64 * 0.05;
                let y = 2.0 * x.powf(1.8) * (1.0 + 0.001 * ((i * 37) % 7) as f64);
                format!("{:e},{:e}\n", x * d, y * f)
            })
            .collect();
        let path = dir.join(format!("{name}.csv"));
        std::fs::write(&path, text).unwrap();
        let o = flexrig(&["fit", path.to_str().unwrap(), "--json"]);
        let stdout = String::from_utf8_lossy(&o.stdout);
        let stderr = String::from_utf8_lossy(&o.stderr);
        match o.status.code() {
            Some(0) => assert!(!stdout.contains("null"), "{name}: {stdout}"),
            _ => assert!(stderr.contains("not representable"), "{name}: {stderr}"),
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
