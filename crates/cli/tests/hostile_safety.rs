//! Regression tests of issue 35 (hostile inputs, round four) on the safety surfaces: user body
//! models (repeated names, absurd limits, keys that would break tables, huge files), the report
//! (never overwritten without --force, refused places write nothing, user text escaped, the
//! figure link encoded) and numbers in messages.

use std::path::{Path, PathBuf};
use std::process::Command;

const BUNDLED: &str = include_str!("../../../assets/safety/iso_ts_15066_2016.toml");

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "flexrig-hostile-safety-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn flexrig_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Exit 2 whose message holds every one of `words` (and no Debug text, no long digit runs).
fn refused_in(dir: &Path, args: &[&str], words: &[&str]) -> String {
    let (code, _, err) = flexrig_in(dir, args);
    assert_eq!(code, 2, "{args:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: {w:?} missing in {err}");
    }
    assert!(!err.contains("panicked") && !err.contains("\\u{"), "{err}");
    let longest = err
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0);
    assert!(longest <= 24, "{err}");
    err
}

/// The bundled table with `extra` inserted before the first area of the chest, and the 1-based
/// line where `extra` begins.
fn with_chest_area(extra: &str) -> (String, usize) {
    let chest = BUNDLED.find("key = \"chest\"").unwrap();
    let at = chest + BUNDLED[chest..].find("[[region.area]]").unwrap();
    let line = BUNDLED[..at].matches('\n').count() + 1;
    (format!("{}{extra}{}", &BUNDLED[..at], &BUNDLED[at..]), line)
}

#[test]
fn a_repeated_area_name_is_refused_naming_the_file_the_name_and_both_lines() {
    let dir = scratch("dup_area");
    // "sternum" repeats the chest's "Sternum" (the lookup ignores case) with a 100x limit
    let (text, line) = with_chest_area(
        "[[region.area]]\nnumber = 99\nname = \"sternum\"\nmax_pressure_n_per_cm2 = 20000.0\n",
    );
    std::fs::write(dir.join("dup.toml"), &text).unwrap();
    let name_line = line + 2;
    // the original Sternum now follows the inserted four lines
    let original = text[..text.find("name = \"Sternum\"").unwrap()]
        .matches('\n')
        .count()
        + 1;
    refused_in(
        &dir,
        &[
            "safety",
            "--region",
            "chest",
            "--area",
            "Sternum",
            "--body-model",
            "dup.toml",
        ],
        &[
            "--body-model = dup.toml",
            "\"Sternum\"",
            &format!("line {original}"),
            &format!("line {name_line}"),
        ],
    );
}

#[test]
fn a_region_name_or_key_given_twice_is_refused() {
    let dir = scratch("dup_region");
    let text = BUNDLED.replace("key = \"abdomen\"", "key = \"Chest\"");
    std::fs::write(dir.join("dup.toml"), text).unwrap();
    refused_in(
        &dir,
        &["safety", "--region", "chest", "--body-model", "dup.toml"],
        &["--body-model = dup.toml", "\"Chest\"", "line "],
    );
}

#[test]
fn denormal_and_absurd_limits_are_refused_with_their_range() {
    let dir = scratch("limits");
    for (from, to, words) in [
        (
            "max_force_n = 140.0",
            "max_force_n = 1e-310",
            ["max_force_n = 1e-310", "[0.01, 1e6] N"],
        ),
        (
            "effective_mass_kg = 40.0",
            "effective_mass_kg = 1e300",
            ["effective_mass_kg = 1e300", "[0.001, 10000] kg"],
        ),
    ] {
        assert!(BUNDLED.contains(from), "{from}");
        std::fs::write(dir.join("bad.toml"), BUNDLED.replacen(from, to, 1)).unwrap();
        refused_in(
            &dir,
            &["safety", "--region", "chest", "--body-model", "bad.toml"],
            &words,
        );
    }
}

#[test]
fn keys_that_would_break_the_maps_csv_and_names_with_line_breaks_are_refused() {
    let dir = scratch("keys");
    std::fs::write(
        dir.join("comma.toml"),
        BUNDLED.replace("key = \"chest\"", "key = \"che,st\""),
    )
    .unwrap();
    refused_in(
        &dir,
        &[
            "safety-map",
            "--x",
            "region=all",
            "--body-model",
            "comma.toml",
            "--out",
            "o",
        ],
        &["--body-model = comma.toml", "\"che,st\"", "letters, digits"],
    );
    assert!(!dir.join("o").join("safety_map.csv").exists());
    std::fs::write(
        dir.join("newline.toml"),
        BUNDLED.replace("name = \"Chest\"", "name = \"Chest\\n# Forged\""),
    )
    .unwrap();
    refused_in(
        &dir,
        &[
            "safety",
            "--region",
            "chest",
            "--body-model",
            "newline.toml",
        ],
        &["--body-model = newline.toml", "U+000A", "line breaks"],
    );
}

#[test]
fn a_body_model_read_is_bounded() {
    let dir = scratch("zero");
    refused_in(
        &dir,
        &["safety", "--region", "chest", "--body-model", "/dev/zero"],
        &["/dev/zero", "longer than 1048576 bytes"],
    );
}

#[test]
fn numbers_in_safety_messages_and_text_are_short() {
    let dir = scratch("numbers");
    refused_in(
        &dir,
        &["safety", "--region", "chest", "--m-eff", "1e300"],
        &["--m-eff = 1e300"],
    );
    let (code, out, err) = flexrig_in(
        &dir,
        &[
            "safety", "--region", "chest", "--m-eff", "3", "--speed", "1e-300",
        ],
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("at 1e-300 m/s: pass"), "{out}");
    let longest = out
        .split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap();
    assert!(longest <= 24, "{out}");
}

#[test]
fn a_report_is_never_overwritten_without_force_and_refused_places_write_nothing() {
    let dir = scratch("report");
    let args = |report: &str, force: bool| -> Vec<String> {
        let mut a: Vec<String> = [
            "safety",
            "--region",
            "hands_and_fingers",
            "--m-eff",
            "2",
            "--speed",
            "0.5",
            "--report",
            report,
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        if force {
            a.push("--force".into());
        }
        a
    };
    let run = |a: &[String]| {
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        flexrig_in(&dir, &a)
    };
    let (code, _, err) = run(&args("hand.md", false));
    assert_eq!(code, 0, "{err}");
    // the user's own edits of the report and of its figure survive a second run
    std::fs::write(dir.join("hand.md"), "mine").unwrap();
    std::fs::write(dir.join("hand_peak_force.svg"), "mine too").unwrap();
    let (code, _, err) = run(&args("hand.md", false));
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--report = hand.md") && err.contains("--force"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("hand.md")).unwrap(),
        "mine"
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("hand_peak_force.svg")).unwrap(),
        "mine too"
    );
    // the figure alone existing also refuses (a report would be written without its figure)
    std::fs::remove_file(dir.join("hand.md")).unwrap();
    let (code, _, err) = run(&args("hand.md", false));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("hand_peak_force.svg"), "{err}");
    assert!(!dir.join("hand.md").exists());
    // --force replaces both
    let (code, _, err) = run(&args("hand.md", true));
    assert_eq!(code, 0, "{err}");
    assert!(
        std::fs::read_to_string(dir.join("hand.md"))
            .unwrap()
            .starts_with("# ")
    );
    assert!(
        std::fs::read_to_string(dir.join("hand_peak_force.svg"))
            .unwrap()
            .contains("</svg>")
    );
    // a directory or a symbolic link as the report: refused naming --report, nothing written
    std::fs::create_dir(dir.join("d.md")).unwrap();
    let (code, _, err) = run(&args("d.md", true));
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--report = d.md") && err.contains("directory"),
        "{err}"
    );
    assert!(!dir.join("d_peak_force.svg").exists());
    std::os::unix::fs::symlink("elsewhere.md", dir.join("l.md")).unwrap();
    let (code, _, err) = run(&args("l.md", true));
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("--report = l.md") && err.contains("symbolic link"),
        "{err}"
    );
    assert!(!dir.join("l_peak_force.svg").exists() && !dir.join("elsewhere.md").exists());
}

#[test]
fn the_markdown_report_escapes_user_text_and_encodes_the_figure_link() {
    let dir = scratch("escape");
    let hostile = "Chest <script>alert(1)</script> | forged";
    std::fs::write(
        dir.join("model.toml"),
        BUNDLED.replace("name = \"Chest\"", &format!("name = \"{hostile}\"")),
    )
    .unwrap();
    let scene = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/driven_cj_free_head.toml"),
    )
    .unwrap()
    .replacen(
        "name = \"driven_cj_free_head\"",
        "name = \"mine\\n# Forged heading <b>x</b>\"",
        1,
    );
    std::fs::write(dir.join("scene.toml"), scene).unwrap();
    let (code, _, err) = flexrig_in(
        &dir,
        &[
            "safety",
            "--region",
            "chest",
            "--body-model",
            "model.toml",
            "--scene",
            "scene.toml",
            "--method",
            "standard,simulation",
            "--report",
            "my report#1.md",
        ],
    );
    assert_eq!(code, 0, "{err}");
    let md = std::fs::read_to_string(dir.join("my report#1.md")).unwrap();
    assert!(
        !md.contains("<script>") && !md.contains("<b>"),
        "raw HTML passed through"
    );
    assert!(
        md.contains("&lt;script&gt;"),
        "the name is not shown escaped"
    );
    assert!(
        !md.lines().any(|l| l.starts_with("# Forged")),
        "a forged heading"
    );
    // every table row has as many unescaped cell separators as its header
    let mut expected = None;
    for l in md.lines() {
        if !l.starts_with('|') {
            expected = None;
            continue;
        }
        let bars = l.replace("\\|", "").matches('|').count();
        match expected {
            None => expected = Some(bars),
            Some(n) => assert_eq!(bars, n, "a broken table row: {l}"),
        }
    }
    // the link: the space as %20 and '#' as %23 (RFC 3986), the file there under its own name
    assert!(md.contains("(my%20report%231_peak_force.svg)"), "{md}");
    assert!(dir.join("my report#1_peak_force.svg").exists());
}

#[test]
fn a_region_axis_naming_a_region_twice_is_refused() {
    let dir = scratch("regions_twice");
    refused_in(
        &dir,
        &[
            "safety-map",
            "--x",
            "region=chest,Chest",
            "--m-r",
            "0.5",
            "--m-e",
            "0.1",
            "--out",
            "o",
        ],
        &["--x = chest,Chest", "item 2 names chest again"],
    );
    assert!(!dir.join("o").exists());
}
