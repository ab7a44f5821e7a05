//! The sample outputs in README.md and docs/*.md are what the commands print today.
//!
//! A fenced block preceded by the comment `<!-- sample -->` holds one or more commands, each on
//! a line starting with `$ ` (continued by a trailing `\`, a `#` starting a comment), each
//! followed by what it prints: standard output and standard error interleaved, as a terminal
//! shows them. The test runs every command with the built binary in a scratch directory (paths
//! under `assets/` are the repository's; the marker names the files a command reads that the
//! test makes, `<!-- sample, with pulse.csv -->`) and compares what it printed with the block:
//! the text exactly, the numbers at their printed precision — one unit in the last printed digit
//! (a rounding that flips on another machine), whole numbers exactly, the same number of digits.
//! A line holding only `…` stands for any number of lines: the lines above it are the output's
//! first, those below it its last. docs/validation.md is `flexrig validate`'s report and is
//! compared in the same way (a round-off residue below 1e-9 on both sides counts as equal).
//!
//! A fenced block that starts with `$ ` or `>>> ` without a marker fails the test, so no sample
//! is left unchecked. `>>>` blocks are Python sessions (`<!-- sample: python -->`), run by
//! crates/python/tests/test_doc_samples.py.
//!
//! `FLEXRIG_BLESS=1 cargo test --release --workspace --test doc_samples` rewrites the blocks and
//! docs/validation.md with what the commands print (scripts/bless-docs.sh does it for the Python
//! sessions too).

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The repository's root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the repository's root")
}

fn blessing() -> bool {
    std::env::var("FLEXRIG_BLESS").is_ok_and(|v| v == "1")
}

/// README.md and every docs/*.md, in name order.
fn documents() -> Vec<PathBuf> {
    let root = root();
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("a docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    docs.insert(0, root.join("README.md"));
    docs
}

/// A fenced block: its opening and closing fence lines (0-based) and the sample marker above it
/// (the text after `sample`, trimmed), if any.
#[derive(Debug)]
struct Block {
    open: usize,
    close: usize,
    marker: Option<String>,
}

/// The fenced blocks of a Markdown text.
fn blocks(lines: &[&str]) -> Vec<Block> {
    let mut out = Vec::new();
    let mut open = None;
    for (i, l) in lines.iter().enumerate() {
        if !l.trim_start().starts_with("```") {
            continue;
        }
        match open.take() {
            None => open = Some(i),
            Some(o) => {
                let marker = lines[..o]
                    .iter()
                    .rev()
                    .find(|l| !l.trim().is_empty())
                    .and_then(|l| {
                        let l = l.trim();
                        l.strip_prefix("<!-- sample")
                            .and_then(|rest| rest.strip_suffix("-->"))
                            .map(|rest| rest.trim_start_matches([':', ',']).trim().to_string())
                    });
                out.push(Block {
                    open: o,
                    close: i,
                    marker,
                });
            }
        }
    }
    assert!(open.is_none(), "a fenced block is not closed");
    out
}

/// One command of a sample and what the block says it prints.
#[derive(Debug)]
struct Step {
    /// The command as typed (continuation lines joined).
    command: String,
    /// The lines (0-based, in the document) of the printed text: `expected.0 .. expected.1`.
    expected: (usize, usize),
}

/// The commands of the block between fences `open` and `close`.
fn steps(lines: &[&str], open: usize, close: usize) -> Vec<Step> {
    let mut out = Vec::new();
    let mut i = open + 1;
    assert!(
        lines[i].starts_with("$ "),
        "a sample block starts with a `$ ` command line, not {:?}",
        lines[i]
    );
    while i < close {
        let mut command = lines[i]["$ ".len()..].to_string();
        while command.ends_with('\\') && i + 1 < close {
            command.pop();
            i += 1;
            command.push(' ');
            command.push_str(lines[i].trim());
        }
        i += 1;
        let start = i;
        while i < close && !lines[i].starts_with("$ ") {
            i += 1;
        }
        out.push(Step {
            command,
            expected: (start, i),
        });
    }
    out
}

/// The words of a command line as a POSIX shell splits it: single and double quotes, a
/// backslash escaping the next character, `#` at the start of a word beginning a comment.
fn words(command: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    let mut in_word = false;
    let mut chars = command.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '#' if !in_word => break,
            c if c.is_whitespace() => {
                if in_word {
                    out.push(std::mem::take(&mut word));
                    in_word = false;
                }
            }
            '\'' => {
                in_word = true;
                for q in chars.by_ref() {
                    if q == '\'' {
                        break;
                    }
                    word.push(q);
                }
            }
            '"' => {
                in_word = true;
                while let Some(q) = chars.next() {
                    match q {
                        '"' => break,
                        '\\' => word.extend(chars.next()),
                        q => word.push(q),
                    }
                }
            }
            '\\' => {
                in_word = true;
                word.extend(chars.next());
            }
            c => {
                in_word = true;
                word.push(c);
            }
        }
    }
    if in_word {
        out.push(word);
    }
    out
}

/// A piece of a printed line: text, or a number as printed.
#[derive(Debug, PartialEq)]
enum Token<'a> {
    Text(&'a str),
    Number(&'a str),
}

/// The length in bytes of the number starting at `s` (`-`? digits, `.` digits, an exponent),
/// if `s` starts with one.
fn number_len(s: &str) -> Option<usize> {
    let b = s.as_bytes();
    let digits = |from: usize| b[from..].iter().take_while(|c| c.is_ascii_digit()).count();
    let mut i = usize::from(b.first() == Some(&b'-'));
    let whole = digits(i);
    if whole == 0 {
        return None;
    }
    i += whole;
    if b.get(i) == Some(&b'.') && digits(i + 1) > 0 {
        i += 1 + digits(i + 1);
    }
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(b.get(i + 1), Some(b'-' | b'+')));
        let exponent = digits(i + 1 + sign);
        if exponent > 0 {
            i += 1 + sign + exponent;
        }
    }
    Some(i)
}

/// A line cut into text and numbers. A number starts at a digit (or a `-` before one) that does
/// not continue a word (`HIC15`, `v0` and `cl_wall` are text).
fn tokens(line: &str) -> Vec<Token<'_>> {
    let mut out = Vec::new();
    let mut text_from = 0;
    let mut i = 0;
    let mut previous: Option<char> = None;
    while i < line.len() {
        let rest = &line[i..];
        let c = rest.chars().next().expect("not at the end");
        let starts = !previous.is_some_and(|p| p.is_alphanumeric() || p == '_' || p == '.');
        if starts && let Some(n) = number_len(rest) {
            if text_from < i {
                out.push(Token::Text(&line[text_from..i]));
            }
            out.push(Token::Number(&line[i..i + n]));
            previous = line[..i + n].chars().next_back();
            i += n;
            text_from = i;
            continue;
        }
        previous = Some(c);
        i += c.len_utf8();
    }
    if text_from < line.len() {
        out.push(Token::Text(&line[text_from..]));
    }
    out
}

/// The digits after the point of a printed number's mantissa, and its exponent (0 without one).
fn shape(number: &str) -> (usize, i32) {
    let (mantissa, exponent) = match number.find(['e', 'E']) {
        Some(at) => (
            &number[..at],
            number[at + 1..].parse().expect("an exponent"),
        ),
        None => (number, 0),
    };
    let decimals = mantissa.find('.').map_or(0, |p| mantissa.len() - p - 1);
    (decimals, exponent)
}

/// True when the printed numbers `doc` and `now` agree at the printed precision: the same
/// text, or the same number of digits and within one unit of the last one (whole numbers
/// exactly); both below `round_off` in magnitude count as equal.
fn numbers_agree(doc: &str, now: &str, round_off: f64) -> bool {
    if doc == now {
        return true;
    }
    let (a, b): (f64, f64) = (
        doc.parse().expect("a number"),
        now.parse().expect("a number"),
    );
    if a.abs() < round_off && b.abs() < round_off {
        return true;
    }
    let whole = !doc.contains(['.', 'e', 'E']);
    let (decimals, exponent) = shape(doc);
    if whole || shape(now).0 != decimals || doc.contains(['e', 'E']) != now.contains(['e', 'E']) {
        return false;
    }
    let unit = 10f64.powi(exponent - decimals as i32);
    (a - b).abs() <= unit * (1.0 + 1e-9)
}

/// True when the printed lines agree: the same text, the numbers at their printed precision.
fn lines_agree(doc: &str, now: &str, round_off: f64) -> bool {
    let (d, n) = (tokens(doc.trim_end()), tokens(now.trim_end()));
    d.len() == n.len()
        && d.iter().zip(&n).all(|pair| match pair {
            (Token::Text(a), Token::Text(b)) => a == b,
            (Token::Number(a), Token::Number(b)) => numbers_agree(a, b, round_off),
            _ => false,
        })
}

/// The first disagreement of the printed `now` with the documented `doc` (a `…` line standing
/// for any number of lines), as (line of `doc`, what differs); `None` when they agree.
fn disagreement(doc: &[&str], now: &[&str], round_off: f64) -> Option<(usize, String)> {
    let (head, tail) = match doc.iter().position(|l| l.trim() == "…") {
        Some(at) => (&doc[..at], &doc[at + 1..]),
        None => (doc, &doc[doc.len()..]),
    };
    let elided = head.len() < doc.len();
    if now.len() < head.len() + tail.len() || (!elided && now.len() != doc.len()) {
        return Some((
            0,
            format!(
                "{} lines printed, the block has {}{}",
                now.len(),
                head.len() + tail.len(),
                if elided { " around its `…`" } else { "" }
            ),
        ));
    }
    let tail_from = now.len() - tail.len();
    let pairs = head.iter().zip(&now[..head.len()]).enumerate().chain(
        tail.iter()
            .zip(&now[tail_from..])
            .enumerate()
            .map(|(i, p)| (head.len() + usize::from(elided) + i, p)),
    );
    for (i, (d, n)) in pairs {
        if !lines_agree(d, n, round_off) {
            return Some((i, format!("documented: {d}\n    printed:    {n}")));
        }
    }
    None
}

/// The block's lines as the command prints them now, keeping a `…` with as many lines around it.
fn blessed(doc: &[&str], now: &[&str]) -> Vec<String> {
    match doc.iter().position(|l| l.trim() == "…") {
        Some(at) if now.len() >= doc.len() - 1 => {
            let tail = doc.len() - at - 1;
            let mut out: Vec<String> = now[..at].iter().map(|s| s.to_string()).collect();
            out.push("…".into());
            out.extend(now[now.len() - tail..].iter().map(|s| s.to_string()));
            out
        }
        _ => now.iter().map(|s| s.to_string()).collect(),
    }
}

/// The files a marker can ask for, made in the scratch directory before the commands run.
fn make_file(dir: &Path, name: &str) {
    let text = match name {
        // a measured impact as docs/safety.md describes it: a 30 ms half-sine of 250 N, 60 g
        // and 2 mm, 4001 samples, with units in the header
        "pulse.csv" => {
            let mut text = String::from("t [ms], F [N], a [g], delta [mm]\n");
            let intervals = 4000;
            for i in 0..=intervals {
                let x = i as f64 / intervals as f64;
                let s = (std::f64::consts::PI * x).sin();
                text.push_str(&format!(
                    "{:?}, {:?}, {:?}, {:?}\n",
                    30.0 * x,
                    250.0 * s,
                    60.0 * s,
                    2.0 * s
                ));
            }
            text
        }
        other => panic!("a sample asks for the file {other}, which the test does not know"),
    };
    std::fs::write(dir.join(name), text).expect("the sample's file is written");
}

/// Runs `command` (its words; the first `flexrig`) in `dir`: its exit code and what it printed
/// on both streams, interleaved as a terminal shows them, with the repository's root written
/// as the relative path the command was given.
fn run(command: &[String], dir: &Path) -> (Option<i32>, String) {
    assert_eq!(
        command.first().map(String::as_str),
        Some("flexrig"),
        "a sample runs flexrig: {command:?}"
    );
    let root = root();
    let args: Vec<String> = command[1..]
        .iter()
        .map(|a| match a.strip_prefix("assets/") {
            Some(rest) => root.join("assets").join(rest).display().to_string(),
            None => a.clone(),
        })
        .collect();
    let capture = dir.join(".printed");
    let file = std::fs::File::create(&capture).expect("a capture file");
    let status = Command::new(env!("CARGO_BIN_EXE_flexrig"))
        .args(&args)
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(file.try_clone().expect("the capture file, twice"))
        .stderr(file)
        .status()
        .expect("the flexrig binary runs");
    let printed = std::fs::read_to_string(&capture).expect("the captured output");
    let printed = printed.replace(&format!("{}/", root.display()), "");
    (status.code(), printed.trim_end_matches('\n').to_string())
}

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("flexrig-doc-samples-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch directory");
    dir
}

/// Every `<!-- sample -->` block of README.md and docs/*.md prints what it shows; every block
/// that looks like a sample is marked as one.
#[test]
fn documented_sample_outputs_are_what_the_commands_print() {
    let root = root();
    let mut failures = Vec::new();
    let mut checked = 0;
    let mut python = 0;
    for path in documents() {
        let name = path
            .strip_prefix(&root)
            .unwrap_or(&path)
            .display()
            .to_string();
        let text = std::fs::read_to_string(&path).expect("a document");
        let lines: Vec<&str> = text.lines().collect();
        let mut replacements: Vec<((usize, usize), Vec<String>)> = Vec::new();
        for block in blocks(&lines) {
            let first = lines[block.open + 1..block.close]
                .first()
                .copied()
                .unwrap_or("");
            let Some(marker) = &block.marker else {
                if first.starts_with("$ ") || first.starts_with(">>> ") {
                    failures.push(format!(
                        "{name}:{}: a sample without a `<!-- sample -->` marker (it would never \
                         be checked)",
                        block.open + 1
                    ));
                }
                continue;
            };
            if marker == "python" {
                assert!(
                    first.starts_with(">>> "),
                    "{name}:{}: a Python sample starts with `>>> `",
                    block.open + 1
                );
                python += 1;
                continue;
            }
            let dir = scratch(&format!("{}-{}", name.replace(['/', '.'], "_"), block.open));
            if let Some(files) = marker.strip_prefix("with ") {
                for file in files.split(',') {
                    make_file(&dir, file.trim());
                }
            } else {
                assert!(
                    marker.is_empty(),
                    "{name}:{}: unknown sample marker {marker:?}",
                    block.open + 1
                );
            }
            for step in steps(&lines, block.open, block.close) {
                checked += 1;
                let (code, printed) = run(&words(&step.command), &dir);
                let now: Vec<&str> = printed.lines().collect();
                let doc = &lines[step.expected.0..step.expected.1];
                if code != Some(0) {
                    failures.push(format!(
                        "{name}:{}: `{}` exited with {code:?}:\n{printed}",
                        step.expected.0, step.command
                    ));
                    continue;
                }
                if let Some((at, what)) = disagreement(doc, &now, 0.0) {
                    if blessing() {
                        replacements.push((step.expected, blessed(doc, &now)));
                    } else {
                        failures.push(format!(
                            "{name}:{}: `{}` prints otherwise:\n    {what}",
                            step.expected.0 + at + 1,
                            step.command
                        ));
                    }
                }
            }
            let _ = std::fs::remove_dir_all(&dir);
        }
        if !replacements.is_empty() {
            let mut out: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
            replacements.sort_by_key(|r| std::cmp::Reverse(r.0.0));
            for ((from, to), new) in replacements {
                out.splice(from..to, new);
            }
            std::fs::write(&path, out.join("\n") + "\n").expect("the blessed document");
            eprintln!("blessed {name}");
        }
    }
    // the documents hold samples of the driven commands, safety and a Python session
    assert!(checked >= 7, "only {checked} sample commands found");
    assert!(python >= 1, "no Python sample found");
    assert!(
        failures.is_empty(),
        "{} documented sample(s) differ from what the commands print (rewrite them with \
         FLEXRIG_BLESS=1 cargo test --release --workspace --test doc_samples):\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// docs/validation.md is the report `flexrig validate` writes.
#[test]
fn the_verification_report_in_the_docs_is_what_validate_writes() {
    let dir = scratch("validate");
    let (code, printed) = run(
        &["flexrig", "validate", "--out", "."].map(String::from),
        &dir,
    );
    assert_eq!(code, Some(0), "flexrig validate: {printed}");
    let now = std::fs::read_to_string(dir.join("validation.md")).expect("validation.md written");
    let path = root().join("docs/validation.md");
    let doc = std::fs::read_to_string(&path).expect("docs/validation.md");
    let (doc_lines, now_lines): (Vec<&str>, Vec<&str>) =
        (doc.lines().collect(), now.lines().collect());
    if let Some((at, what)) = disagreement(&doc_lines, &now_lines, 1e-9) {
        if blessing() {
            std::fs::write(&path, &now).expect("docs/validation.md blessed");
            eprintln!("blessed docs/validation.md");
        } else {
            panic!(
                "docs/validation.md:{} differs from what `flexrig validate` writes (rewrite it \
                 with FLEXRIG_BLESS=1 cargo test --release --workspace --test doc_samples):\n    \
                 {what}",
                at + 1
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The significant digits of a printed number (`7.494788162835072e-6`: 16; `0.000768`: 3).
fn significant_digits(number: &str) -> usize {
    let mantissa = number.split(['e', 'E']).next().unwrap_or(number);
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    let trimmed = digits.trim_start_matches('0');
    if mantissa.contains('.') {
        trimmed.len()
    } else {
        // a whole number's trailing zeros are not digits of precision
        trimmed.trim_end_matches('0').len()
    }
}

/// The text reports print numbers to sensible digits (at most 12 significant digits: `impact`
/// and `validate` print 11 on purpose, to compare methods), never a float's every digit
/// (`7.494788162835072e-6 s`, `1.0000000199999999 m/s`); the JSON keeps every digit. Checked
/// on the commands whose reports print computed numbers beside the typed ones.
#[test]
fn text_reports_print_numbers_to_sensible_digits() {
    let dir = scratch("digits");
    let commands: [&[&str]; 9] = [
        &["safety", "--scene", "cl_iron", "--region", "abdomen"],
        &["safety", "--scene", "driven_cl_wall", "--region", "chest"],
        &[
            "safety",
            "--scene",
            "rig_driven_cl",
            "--region",
            "hands_and_fingers",
        ],
        &["run", "driven_cl_wall"],
        &["run", "rig_driven_cj"],
        &["run", "cj_aluminium"],
        &["strike", "assets/drives/cj_free_head.toml"],
        &["role-switch", "--no-fig6", "--kappa", "1", "--out", "out"],
        &[
            "safety",
            "--region",
            "chest",
            "--m-r",
            "0.051",
            "--m-e",
            "0.412",
            "--gamma",
            "1",
            "--k-delta",
            "1e4",
            "--material",
            "skinned_aluminium",
            "--method",
            "standard,energy,simulation",
            "--speed",
            "1.0000000199999999",
        ],
    ];
    let mut found = Vec::new();
    for args in commands {
        let command: Vec<String> = std::iter::once("flexrig")
            .chain(args.iter().copied())
            .map(String::from)
            .collect();
        let (code, printed) = run(&command, &dir);
        assert_eq!(code, Some(0), "{args:?}: {printed}");
        for line in printed.lines() {
            for token in tokens(line) {
                if let Token::Number(n) = token
                    && significant_digits(n) > 12
                    && !line.contains("1.0000000199999999")
                {
                    found.push(format!("{args:?}: {n} in {line}"));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "numbers printed with every digit:\n{}",
        found.join("\n")
    );
    assert_eq!(significant_digits("7.494788162835072e-6"), 16);
    assert_eq!(significant_digits("0.000768"), 3);
    assert_eq!(significant_digits("2.2966170056e3"), 11);
    assert_eq!(significant_digits("5000"), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The comparison itself: numbers at their printed precision, text exactly, `…` for lines.
#[test]
fn the_comparison_reads_numbers_at_their_printed_precision() {
    assert_eq!(
        tokens("peak 3.520793e3 N at t = 0.801009 s (-3.21 %), HIC15 v0 cl_wall 2cm2"),
        vec![
            Token::Text("peak "),
            Token::Number("3.520793e3"),
            Token::Text(" N at t = "),
            Token::Number("0.801009"),
            Token::Text(" s ("),
            Token::Number("-3.21"),
            Token::Text(" %), HIC15 v0 cl_wall "),
            Token::Number("2"),
            Token::Text("cm2"),
        ]
    );
    // one unit in the last printed digit, not two; the same digits; whole numbers exactly
    assert!(numbers_agree("3.520793e3", "3.520794e3", 0.0));
    assert!(!numbers_agree("3.520793e3", "3.520795e3", 0.0));
    assert!(!numbers_agree("3.521926e3", "3.520800e3", 0.0));
    assert!(!numbers_agree("1.5", "1.50", 0.0));
    assert!(!numbers_agree("57", "56", 0.0));
    assert!(numbers_agree("2.12e-13", "1.37e-13", 1e-9));
    assert!(lines_agree("a 0.9971 b", "a 0.9972 b", 0.0));
    assert!(!lines_agree("a 0.9971 b", "a 0.9971 c", 0.0));
    // `…` keeps the first and the last lines
    let doc = ["head", "…", "tail"];
    assert!(disagreement(&doc, &["head", "x", "y", "tail"], 0.0).is_none());
    assert!(disagreement(&doc, &["head", "tail"], 0.0).is_none());
    assert!(disagreement(&doc, &["head", "x"], 0.0).is_some());
    assert_eq!(
        blessed(&doc, &["head2", "x", "tail2"]),
        vec!["head2", "…", "tail2"]
    );
    assert_eq!(
        words(r#"flexrig safety --area "Back of the hand ND" --m-r 0.051   # a comment"#),
        vec![
            "flexrig",
            "safety",
            "--area",
            "Back of the hand ND",
            "--m-r",
            "0.051"
        ]
    );
}
