//! The figures as a reader gets them: every figure command at one column (3.5 in) and two
//! columns (7 in) writes SVGs whose text is at least 8 pt at that width (font-size × width
//! [in] / viewBox width ≥ 8/72 in), at one column at most 9 in tall (a page's column; `bench`'s
//! figures by the unit test of their layout), PNG and PDF of the printed size; and fig9's text, read back,
//! is the inputs that ran (`--set` of the payload, the block mass and the design), as are the
//! spin-up's and the role switch's.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use flexrig::plots::inspect::{min_text_pt, printed_height, printed_width, texts};

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-figures-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn flexrig(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .output()
        .unwrap()
}

fn ok(args: &[&str]) -> String {
    let out = flexrig(args);
    assert!(
        out.status.success(),
        "flexrig {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// The SVGs of `dir`.
fn svgs(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
        .collect();
    v.sort();
    v
}

/// Checks the printed width and the smallest text of the SVG at `path`, and that a one-column
/// figure fits a journal page's column (at most 9 in tall); returns its text.
fn check_svg(path: &Path, inches: f64) -> String {
    let svg = std::fs::read_to_string(path).unwrap();
    let (w, _) = printed_width(&svg).unwrap();
    assert!((w - inches).abs() < 1e-9, "{}: {w} in", path.display());
    if inches <= 3.5 {
        let h = printed_height(&svg).unwrap();
        assert!(
            h <= 9.0 + 1e-9,
            "{}: {h} in tall at one column",
            path.display()
        );
    }
    let min = min_text_pt(&svg).unwrap();
    assert!(
        min >= 8.0 - 1e-3,
        "{}: text of {min:.2} pt at {inches} in",
        path.display()
    );
    texts(&svg).join("\n")
}

#[test]
fn every_figure_command_writes_text_of_at_least_8_pt_at_its_width() {
    let commands: [&[&str]; 11] = [
        &[
            "spin-up",
            "--elements",
            "4",
            "--modes",
            "3",
            "--t-s",
            "2",
            "--duration",
            "3",
        ],
        &["role-switch", "--no-fig6", "--kappa", "1"],
        // the Fig. 6 cases too: their legend is the longest of the curve figures
        &["role-switch", "--link-model", "linear", "--kappa", "1,100"],
        &[
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
            "--method",
            "energy",
        ],
        &["fig6"],
        &["prb", "--elements", "16"],
        &["payload", "--points", "3"],
        &["eta"],
        &["eta-rotor", "--points", "3"],
        &["eta-map", "--points", "3"],
        &["experiment", "--repeats", "2"],
    ];
    for (size, inches) in [("1", 3.5), ("2", 7.0), ("5in", 5.0)] {
        let dir = scratch(&format!("size{inches}"));
        for args in commands {
            let out = dir.join(args[0]);
            let mut all: Vec<&str> = args.to_vec();
            all.extend(["--out", out.to_str().unwrap(), "--size", size]);
            ok(&all);
            let found = svgs(&out);
            assert!(!found.is_empty(), "{args:?} wrote no SVG");
            for svg in found {
                let text = check_svg(&svg, inches);
                for internal in ["issue", "1e8", "e-5", "f_CL/f_CJ", "NaN"] {
                    assert!(
                        !text.contains(internal),
                        "{}: '{internal}' in\n{text}",
                        svg.display()
                    );
                }
            }
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn png_and_pdf_are_written_at_the_printed_size() {
    let dir = scratch("formats");
    let stdout = ok(&[
        "fig6",
        "--out",
        dir.to_str().unwrap(),
        "--size",
        "1",
        "--format",
        "svg,png,pdf",
        "--dpi",
        "200",
    ]);
    assert!(stdout.contains("fig6.svg"), "{stdout}");
    let png = std::fs::read(dir.join("fig6.png")).unwrap();
    let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
    // 3.5 in at 200 dpi
    assert_eq!(width, 700);
    let pdf = std::fs::read(dir.join("fig6.pdf")).unwrap();
    let text = String::from_utf8_lossy(&pdf);
    assert!(text.starts_with("%PDF-"));
    // 3.5 in = 252 pt wide, the font embedded
    assert!(text.contains("/MediaBox [0 0 252 "), "page size");
    assert!(text.contains("DejaVuSans"));
    // bad flags are named
    for (flag, value) in [("--size", "0.5"), ("--format", "jpeg"), ("--dpi", "0")] {
        let out = flexrig(&["fig6", "--out", dir.to_str().unwrap(), flag, value]);
        assert_eq!(out.status.code(), Some(2), "{flag} {value}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(flag));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The `flexrig` metadata record of the MCAP log at `path`: key → value.
fn log_metadata(path: &Path) -> std::collections::BTreeMap<String, String> {
    let bytes = std::fs::read(path).unwrap();
    let summary = mcap::Summary::read(&bytes).unwrap().unwrap();
    let index = summary
        .metadata_indexes
        .iter()
        .find(|m| m.name == "flexrig")
        .unwrap_or_else(|| panic!("no flexrig metadata in {}", path.display()));
    mcap::read::metadata(&bytes, index).unwrap().metadata
}

#[test]
fn fig9_says_the_inputs_that_ran() {
    let dir = scratch("fig9-set");
    let stdout = ok(&[
        "experiment",
        "--repeats",
        "2",
        "--set",
        "robot.payload_kg=1.0",
        "--set",
        "operator.block_mass_kg=4",
        "--out",
        dir.to_str().unwrap(),
    ]);
    let text = check_svg(&dir.join("fig9.svg"), 7.0);
    assert!(
        text.contains("(a) m_e = 1000 g") && text.contains("(b) m_e = 1000 g"),
        "{text}"
    );
    assert!(text.contains("m_h = 4000 g"), "{text}");
    for stale in ["412 g", "100 g", "0.1 kg", "398 g", "4008 g"] {
        assert!(!text.contains(stale), "'{stale}' in fig9:\n{text}");
    }
    // the note says where the interval comes from
    assert!(
        text.replace('\n', " ")
            .contains("simulated release-angle scatter (σ = 0.5°, seed 1)")
    );
    // the paper's sentence only for the paper's inputs
    assert!(
        !stdout.contains("The paper: CL slightly below CJ"),
        "{stdout}"
    );
    assert!(stdout.contains("does not apply"), "{stdout}");
    let csv = std::fs::read_to_string(dir.join("experiment.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[col("payload_kg")], "1");
        assert_eq!(f[col("block_mass_kg")], "4");
        let t: f64 = f[col("time_of_peak_s")].parse().unwrap();
        assert!(t > 0.1 && t < 1.0, "time of the peak {t} s");
    }
    let _ = std::fs::remove_dir_all(&dir);

    // robot.design for every scene would make every CL/CJ pair compare a design with itself:
    // the experiment refuses it; a run of a CJ scene as CL names its log by what ran
    let refused = flexrig(&[
        "experiment",
        "--repeats",
        "2",
        "--set",
        "robot.design=cl",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(refused.status.code(), Some(2));
    std::fs::create_dir_all(&dir).unwrap();
    let log = dir.join("as_cl.mcap");
    ok(&[
        "run",
        &format!(
            "{}/../../assets/scenes/cj_aluminium.toml",
            env!("CARGO_MANIFEST_DIR")
        ),
        "--set",
        "robot.design=cl",
        "--out",
        log.to_str().unwrap(),
    ]);
    let meta = log_metadata(&log);
    assert_eq!(meta["design"], "cl");
    assert_eq!(
        meta["scene"],
        "cl_aluminium (scene cj_aluminium, design set to CL)"
    );
    assert_eq!(meta["scene_file_name"], "cj_aluminium");
    let _ = std::fs::remove_dir_all(&dir);

    // the paper's inputs: its sentence and its numbers
    let stdout = ok(&[
        "experiment",
        "--repeats",
        "2",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        stdout.contains("The paper: CL slightly below CJ"),
        "{stdout}"
    );
    let text = check_svg(&dir.join("fig9.svg"), 7.0);
    for label in [
        "(a) m_e = 412 g",
        "(b) m_e = 100 g",
        "m_h = 398 g",
        "m_h = 4008 g",
        "(c) CL/CJ",
    ] {
        assert!(text.contains(label), "{label} missing:\n{text}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn spin_up_and_role_switch_figures_say_the_inputs_that_ran() {
    let dir = scratch("driven-labels");
    ok(&[
        "spin-up",
        "--length",
        "8",
        "--omega-s",
        "4",
        "--t-s",
        "2",
        "--duration",
        "3",
        "--elements",
        "5",
        "--modes",
        "3",
        "--out",
        dir.to_str().unwrap(),
        "--format",
        "svg,png",
    ]);
    assert!(dir.join("spin_up.png").exists());
    let text = check_svg(&dir.join("spin_up.svg"), 7.0).replace('\n', " ");
    for label in [
        "L = 8 m",
        "ω_s = 4 rad/s",
        "T_s = 2 s",
        "5 corotational elements",
        "3 modes",
        "time t [s]",
    ] {
        assert!(
            text.contains(label),
            "'{label}' not in the spin-up figure:\n{text}"
        );
    }
    for stale in ["10 m", "6 rad/s", "15 s", "16 ", "7 modes", "e-"] {
        assert!(
            !text.contains(stale),
            "'{stale}' in the spin-up figure:\n{text}"
        );
    }
    ok(&[
        "role-switch",
        "--no-fig6",
        "--kappa",
        "100,1",
        "--rotor-ratio",
        "2",
        "--damping-ratio",
        "0.5",
        "--out",
        dir.to_str().unwrap(),
        "--size",
        "1",
    ]);
    let lines = check_svg(&dir.join("role_switch.svg"), 3.5).replace('\u{a0}', " ");
    // the rotor's inertia on one line of the wrapped title, never broken inside
    assert!(lines.contains("J_R = 2 m_r L²/3"), "{lines}");
    let text = lines.replace('\n', " ");
    for label in ["J_R = 2 m_r L²/3", "damping ratio 0.5", "k_θr/K_p"] {
        assert!(
            text.contains(label),
            "'{label}' not in the role-switch figure:\n{text}"
        );
    }
    assert!(
        !text.contains("1e-3") && !text.contains("f_driven"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
