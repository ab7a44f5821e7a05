//! Hostile command lines: every case ends with exit code 2 and an error that names the flag, or
//! runs to a result with no null or non-finite number; never a panic, never a hang.

use std::process::{Command, Output, Stdio};
use std::time::Duration;

/// Far above any case's run time: only a hang reaches it (no test asserts a duration).
const HANG: Duration = Duration::from_secs(300);

/// Runs the binary with `args`; a process still running after [`HANG`] is killed and fails the
/// test as a hang.
fn flexrig(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    // drain the pipes in threads so a chatty process cannot block on a full pipe
    let mut stdout = child.stdout.take().unwrap();
    let mut stderr = child.stderr.take().unwrap();
    let out = std::thread::spawn(move || {
        let mut v = Vec::new();
        std::io::Read::read_to_end(&mut stdout, &mut v).map(|_| v)
    });
    let err = std::thread::spawn(move || {
        let mut v = Vec::new();
        std::io::Read::read_to_end(&mut stderr, &mut v).map(|_| v)
    });
    let start = std::time::Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > HANG {
            let _ = child.kill();
            panic!("{args:?}: still running after {HANG:?} (a hang)");
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Output {
        status,
        stdout: out.join().unwrap().unwrap(),
        stderr: err.join().unwrap().unwrap(),
    }
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

/// Regression: Ctrl-C was ignored by eta, eta-map and eta-rotor (they ran on for many seconds,
/// one exited 0). Each stops with exit code 130 and writes none of its files (they are written
/// only once everything is computed). The signal is sent once the process has started; each
/// computation below takes many seconds, so it is still under way.
#[test]
fn ctrl_c_stops_the_eta_commands_with_exit_130_and_no_half_output() {
    for (name, args) in [
        ("eta-map", vec!["eta-map", "--points", "200"]),
        ("eta-rotor", vec!["eta-rotor", "--points", "200"]),
        ("eta", vec!["eta", "--window-periods", "200"]),
    ] {
        let dir =
            std::env::temp_dir().join(format!("flexrig-ctrl-c-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let mut all = args.clone();
        all.extend(["--out", dir.to_str().unwrap()]);
        let mut child = Command::new(env!("CARGO_BIN_EXE_flexrig"))
            .args(&all)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(300));
        let killed = Command::new("kill")
            .args(["-INT", &child.id().to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        let start = std::time::Instant::now();
        let status = loop {
            if let Some(status) = child.try_wait().unwrap() {
                break status;
            }
            if start.elapsed() > HANG {
                let _ = child.kill();
                panic!("{name}: still running {HANG:?} after Ctrl-C");
            }
            std::thread::sleep(Duration::from_millis(20));
        };
        let mut stderr = String::new();
        std::io::Read::read_to_string(&mut child.stderr.take().unwrap(), &mut stderr).unwrap();
        assert_eq!(status.code(), Some(130), "{name}: {status:?} {stderr}");
        assert!(stderr.contains("stopped on request"), "{name}: {stderr}");
        let written: Vec<_> = std::fs::read_dir(&dir)
            .map(|d| d.filter_map(|e| e.ok()).map(|e| e.file_name()).collect())
            .unwrap_or_default();
        assert!(written.is_empty(), "{name}: wrote {written:?}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
