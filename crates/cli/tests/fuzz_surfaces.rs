//! Generated hostile command lines on every surface of the `flexrig` binary: `run`, `experiment`,
//! `sweep` (grids, `@file` values, `--zip`, shards, `sweep merge`, resume), `eta`, `eta-map`,
//! `eta-rotor`, `payload`, `fit`, `beam`, `prb`, `impact` and `--set` wherever it exists; Ctrl-C
//! (SIGINT) during the long commands; overwrites and symlinks; torn resume journals.
//!
//! Every process runs under a 2 GiB address-space cap (`ulimit -v`, so an allocation that cannot
//! be served fails instead of swapping) and a generous kill-on-hang: a process that has used
//! [`CPU_LIMIT_S`] of CPU time, or is still running after [`WALL_BACKSTOP`] (a hang that sleeps),
//! is killed and the case fails, so only a hang fails. The guard counts CPU time, not the wall
//! clock, so a loaded machine (where a process gets a fraction of a core) does not trip it; no
//! test asserts a duration (speed lives in the benchmarks).
//!
//! The floors, for every case (see [`verdict`]):
//! - the process never dies by a signal (abort, segfault, out of memory);
//! - the exit code is 0 or 2, or 1 where the command documents a run failure (`run`, `sweep`);
//! - exit code 2 comes with a message that names the flag or field at fault;
//! - no message shows a Rust type name or Debug value (`struct `, `enum `, `usize`, `f64`,
//!   `Some(`, `None`, `Debug`, a panic, an escaped `\u{feff}`), a number of more than 24 digits
//!   or a byte-order mark that the user did not type;
//! - JSON on standard output holds no `null` and no non-finite number;
//! - every file in the output directory is either absent or complete: JSON and JSON Lines parse,
//!   every CSV record has the header's number of fields, SVGs end with `</svg>`, MCAP files
//!   carry the magic at both ends, and no temporary file is left behind.
//!
//! Cases are drawn by a fixed-seed generator ([`Rng`]), so a failure reproduces; every failing
//! case of a test is collected and reported together with its command line.

use std::collections::BTreeSet;
use std::io::Read;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// CPU time (user + system, all threads) a single process may use before it is killed and
/// counted as hung, s. Generous: the costliest case drawn here (eta at its tightest tolerance)
/// uses about 40 s of CPU.
const CPU_LIMIT_S: u64 = 180;

/// Clock ticks per second of `/proc/PID/stat` (`USER_HZ`, 100 on Linux).
const TICKS_PER_S: u64 = 100;

/// Wall-clock backstop for a hang that uses no CPU (a process blocked forever): long enough that
/// a process making progress on a heavily loaded machine never meets it first.
const WALL_BACKSTOP: Duration = Duration::from_secs(1200);

/// What the kill-on-hang guard says when it fired.
const HANG: &str = "still running after 3 min of CPU time (or 20 min without finishing)";

/// The address-space cap, KiB (2 GiB).
const AS_CAP_KIB: u64 = 2 * 1024 * 1024;

/// Substrings that betray an internal type or value in a user-facing message.
const RUST_LEAKS: [&str; 14] = [
    "panicked",
    "RUST_BACKTRACE",
    "struct ",
    "enum ",
    "usize",
    "u64",
    "i64",
    "f64",
    "Some(",
    "None",
    "Debug",
    "Ok(",
    "Err(",
    "\\u{feff}",
];

// ---------------------------------------------------------------------------------------------
// Running a capped process

/// What a finished (or killed) process left.
struct Outcome {
    /// The command line, for the report.
    line: String,
    code: Option<i32>,
    signal: Option<i32>,
    timed_out: bool,
    stdout: String,
    stderr: String,
}

fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_flexrig")
}

/// `flexrig args…` under the address-space cap, in `cwd`, its output captured.
fn spawn(args: &[String], cwd: &Path) -> Child {
    Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {AS_CAP_KIB} && exec \"$0\" \"$@\""))
        .arg(bin())
        .args(args)
        .current_dir(cwd)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn sh")
}

/// A thread that drains `r` into a string (so a chatty process never blocks on a full pipe).
fn drain<R: Read + Send + 'static>(mut r: R) -> std::thread::JoinHandle<String> {
    std::thread::spawn(move || {
        let mut buf = Vec::new();
        let _ = r.read_to_end(&mut buf);
        String::from_utf8_lossy(&buf).into_owned()
    })
}

/// Waits for `child` until it has used [`CPU_LIMIT_S`] of CPU time or [`WALL_BACKSTOP`] has
/// passed (killing it then), calling `poke` once per poll with the process id (used to
/// interrupt it).
fn finish(mut child: Child, line: String, mut poke: impl FnMut(u32) -> bool) -> Outcome {
    let out = drain(child.stdout.take().unwrap());
    let err = drain(child.stderr.take().unwrap());
    let start = Instant::now();
    let mut timed_out = false;
    let mut poked = false;
    let status = loop {
        if let Some(status) = child.try_wait().expect("try_wait") {
            break status;
        }
        if !poked {
            poked = poke(child.id());
        }
        let cpu_spent = cpu_ticks(child.id()).is_some_and(|t| t > CPU_LIMIT_S * TICKS_PER_S);
        if cpu_spent || start.elapsed() > WALL_BACKSTOP {
            timed_out = true;
            let _ = child.kill();
            break child.wait().expect("wait");
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    Outcome {
        line,
        code: status.code(),
        signal: if timed_out { None } else { status.signal() },
        timed_out,
        stdout: out.join().unwrap_or_default(),
        stderr: err.join().unwrap_or_default(),
    }
}

/// The command line as a reader would retype it (long arguments shortened).
fn show(args: &[String]) -> String {
    let mut s = String::from("flexrig");
    for a in args {
        let shown: String = if a.chars().count() > 80 {
            format!(
                "{}…[{} chars]",
                a.chars().take(60).collect::<String>(),
                a.chars().count()
            )
        } else {
            a.clone()
        };
        s.push(' ');
        s.push_str(&format!("{shown:?}"));
    }
    s
}

fn run_in(args: &[String], cwd: &Path) -> Outcome {
    finish(spawn(args, cwd), show(args), |_| true)
}

fn strings(args: &[&str]) -> Vec<String> {
    args.iter().map(|s| s.to_string()).collect()
}

/// A fresh empty scratch directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-fuzz-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn scene_path(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes")
        .join(format!("{name}.toml"))
        .to_string_lossy()
        .into_owned()
}

// ---------------------------------------------------------------------------------------------
// The floors

/// Which exit codes a case may end with, and what an exit-2 message must name.
struct Expect<'a> {
    /// Exit code 1 is a documented outcome (a run that failed).
    allow_1: bool,
    /// An exit-2 message must contain one of these (the flag or field at fault).
    names: &'a [&'a str],
}

fn shorten(s: &str, n: usize) -> String {
    if s.chars().count() > n {
        format!("{}…", s.chars().take(n).collect::<String>())
    } else {
        s.to_string()
    }
}

/// The longest run of ASCII digits in `s`.
fn longest_digit_run(s: &str) -> String {
    let mut best = "";
    let mut start = None;
    for (i, c) in s.char_indices().chain(std::iter::once((s.len(), ' '))) {
        match (c.is_ascii_digit(), start) {
            (true, None) => start = Some(i),
            (false, Some(b)) => {
                if i - b > best.len() {
                    best = &s[b..i];
                }
                start = None;
            }
            _ => {}
        }
    }
    best.to_string()
}

/// The floors every case must meet (see the module documentation); an `Err` says which broke.
fn verdict(o: &Outcome, args: &[String], expect: &Expect) -> Result<(), String> {
    let err = shorten(&o.stderr, 400);
    if o.timed_out {
        return Err(format!("{HANG} (killed: a hang)\n  stderr: {err}"));
    }
    if let Some(sig) = o.signal {
        return Err(format!("killed by signal {sig}\n  stderr: {err}"));
    }
    let code = o.code.unwrap_or(-1);
    match code {
        0 | 2 => {}
        1 if expect.allow_1 => {}
        _ => return Err(format!("exit code {code}\n  stderr: {err}")),
    }
    if code == 2 && !expect.names.iter().any(|n| o.stderr.contains(n)) {
        return Err(format!(
            "exit 2 without naming any of {:?}\n  stderr: {err}",
            expect.names
        ));
    }
    let both = format!("{}\n{}", o.stdout, o.stderr);
    for leak in RUST_LEAKS {
        if both.contains(leak) {
            return Err(format!(
                "output shows {leak:?}\n  stderr: {err}\n  stdout: {}",
                shorten(&o.stdout, 300)
            ));
        }
    }
    if both.contains('\u{feff}') && !args.iter().any(|a| a.contains('\u{feff}')) {
        return Err(format!(
            "output holds a byte-order mark the user did not type\n  stderr: {err}"
        ));
    }
    let digits = longest_digit_run(&both);
    if digits.len() > 24 && !args.iter().any(|a| a.contains(&digits)) {
        return Err(format!(
            "output holds a {}-digit number the user did not type\n  stderr: {err}",
            digits.len()
        ));
    }
    if code == 0 && args.iter().any(|a| a == "--json") {
        json_floor(&o.stdout).map_err(|e| format!("JSON output: {e}"))?;
    }
    Ok(())
}

/// Standard output of `--json`: a JSON document (or JSON Lines) with no null and no non-finite
/// number spelled as a string.
fn json_floor(text: &str) -> Result<(), String> {
    let docs: Vec<serde_json::Value> = match serde_json::from_str(text) {
        Ok(v) => vec![v],
        Err(_) => text
            .lines()
            .filter(|l| !l.trim().is_empty())
            .map(serde_json::from_str)
            .collect::<Result<_, _>>()
            .map_err(|e| format!("does not parse ({e}): {}", shorten(text, 200)))?,
    };
    for d in &docs {
        if let Some(p) = bad_json_value(d, "$") {
            return Err(p);
        }
    }
    Ok(())
}

fn bad_json_value(v: &serde_json::Value, at: &str) -> Option<String> {
    use serde_json::Value;
    match v {
        Value::Null => Some(format!("null at {at}")),
        Value::String(s)
            if ["nan", "inf", "-inf", "+inf", "infinity", "-infinity"]
                .contains(&s.to_ascii_lowercase().as_str()) =>
        {
            Some(format!("{s:?} at {at}"))
        }
        Value::Array(a) => a
            .iter()
            .enumerate()
            .find_map(|(i, x)| bad_json_value(x, &format!("{at}[{i}]"))),
        Value::Object(m) => m
            .iter()
            .find_map(|(k, x)| bad_json_value(x, &format!("{at}.{k}"))),
        _ => None,
    }
}

/// Splits CSV text into records of fields (RFC 4180 quoting; a quoted field may hold newlines).
fn csv_records(text: &str) -> Result<Vec<Vec<String>>, String> {
    let mut records = Vec::new();
    let mut record = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        if quoted {
            match c {
                '"' if chars.peek() == Some(&'"') => {
                    field.push('"');
                    chars.next();
                }
                '"' => quoted = false,
                _ => field.push(c),
            }
            continue;
        }
        match c {
            '"' if field.is_empty() => quoted = true,
            ',' => record.push(std::mem::take(&mut field)),
            '\r' => {}
            '\n' => {
                record.push(std::mem::take(&mut field));
                records.push(std::mem::take(&mut record));
            }
            _ => field.push(c),
        }
    }
    if quoted {
        return Err("ends inside a quoted field".into());
    }
    if !field.is_empty() || !record.is_empty() {
        return Err("the last record has no line end (cut short)".into());
    }
    Ok(records)
}

const MCAP_MAGIC: &[u8] = b"\x89MCAP0\r\n";

/// Every file under `dir` is complete (see the module documentation); the problems found.
fn output_floor(dir: &Path) -> Vec<String> {
    let mut problems = Vec::new();
    let Ok(entries) = std::fs::read_dir(dir) else {
        return problems;
    };
    for e in entries.flatten() {
        let path = e.path();
        let meta = match std::fs::symlink_metadata(&path) {
            Ok(m) => m,
            Err(_) => continue,
        };
        if meta.is_dir() {
            problems.extend(output_floor(&path));
            continue;
        }
        if meta.file_type().is_symlink() {
            continue;
        }
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let shown = path.display();
        if name.ends_with(".tmp") {
            problems.push(format!("{shown}: a temporary file left behind"));
            continue;
        }
        let Ok(bytes) = std::fs::read(&path) else {
            continue;
        };
        let text = || String::from_utf8_lossy(&bytes).into_owned();
        let ext = path.extension().map(|x| x.to_string_lossy().into_owned());
        let problem = match ext.as_deref() {
            Some("json") => serde_json::from_slice::<serde_json::Value>(&bytes)
                .err()
                .map(|e| format!("does not parse: {e}")),
            Some("jsonl") => {
                let t = text();
                if !t.is_empty() && !t.ends_with('\n') {
                    Some("the last line has no line end".into())
                } else {
                    t.lines()
                        .filter(|l| !l.is_empty())
                        .find_map(|l| serde_json::from_str::<serde_json::Value>(l).err())
                        .map(|e| format!("a line does not parse: {e}"))
                }
            }
            Some("csv") => match csv_records(&text()) {
                Err(e) => Some(e),
                Ok(r) if r.is_empty() => Some("empty".into()),
                Ok(r) => r
                    .iter()
                    .position(|rec| rec.len() != r[0].len())
                    .map(|i| format!("record {i} has a different number of fields")),
            },
            Some("svg") => (!text().trim_end().ends_with("</svg>"))
                .then(|| "does not end with </svg>".to_string()),
            Some("mcap") => (bytes.len() < 2 * MCAP_MAGIC.len()
                || !bytes.starts_with(MCAP_MAGIC)
                || !bytes.ends_with(MCAP_MAGIC))
            .then(|| "no MCAP magic at both ends (cut short)".to_string()),
            _ => None,
        };
        if let Some(p) = problem {
            problems.push(format!("{shown}: {p}"));
        }
    }
    problems
}

/// Runs `args` in `cwd` and applies [`verdict`] and, for `out`, [`output_floor`].
fn attack(
    args: &[String],
    cwd: &Path,
    out: Option<&Path>,
    expect: &Expect,
    failures: &mut Vec<String>,
) -> Outcome {
    let o = run_in(args, cwd);
    let mut problems: Vec<String> = verdict(&o, args, expect).err().into_iter().collect();
    if let Some(dir) = out {
        problems.extend(output_floor(dir));
    }
    for p in problems {
        failures.push(format!("{}\n  -> {p}", o.line));
    }
    o
}

fn report(test: &str, cases: usize, failures: &[String]) {
    assert!(
        failures.is_empty(),
        "{test}: {} of {cases} cases broke a floor:\n\n{}",
        failures.len(),
        failures.join("\n\n")
    );
}

// ---------------------------------------------------------------------------------------------
// Hostile values

/// SplitMix64: a fixed-seed generator so every drawn case reproduces.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// Hostile spellings of a number (each fits in one argument: well under the kernel's 128 KiB).
fn hostile_numbers() -> Vec<String> {
    let mut v = strings(&[
        "0",
        "-0",
        "-1",
        "1e-300",
        "5e-324",
        "1e300",
        "1.8e308",
        "-1e300",
        "nan",
        "NaN",
        "inf",
        "-inf",
        "+inf",
        "infinity",
        "1e",
        "",
        " ",
        "abc",
        "0x10",
        "1_000",
        "18446744073709551616",
        "-9223372036854775809",
        "4294967297",
        "１",
        "\u{feff}1",
        "1\n2",
        "1,2",
        "1:2",
        "2.5",
        "1e-12",
        "1e12",
        "--json",
        "-",
    ]);
    v.push("9".repeat(400));
    v.push(format!("0.{}1", "0".repeat(400)));
    v.push("x".repeat(20_000));
    v
}

/// Hostile values for a comma-separated list flag (`--m-h`, `--n`).
fn hostile_lists() -> Vec<String> {
    let mut v = hostile_numbers();
    v.extend(strings(&[",", "4,", ",4", "4,,4", "4;4", "4 4", "[4]"]));
    v.push(vec!["4"; 20_000].join(","));
    v.push(vec!["2"; 20_000].join(","));
    v.push(vec!["1e300"; 3000].join(","));
    v
}

/// Hostile `FROM:TO` ranges.
fn hostile_ranges() -> Vec<String> {
    let mut v = strings(&[
        "1:1",
        "2:1",
        "0:1",
        "-1:1",
        "1e-300:1e300",
        "nan:1",
        "1:inf",
        "1",
        ":",
        "1:",
        ":1",
        "1:2:3",
        "1e-20:1e-19",
        "1e10:1e11",
        "1e-3:1:3:log",
        "1e-3:1:0:log",
        "1e-3:1:4294967297:log",
        "1e-3:1:3:lin",
        "1:2:3:log:log",
        "a:b",
        "1::2",
    ]);
    v.push(format!("1:{}", "9".repeat(400)));
    v.extend(hostile_numbers().into_iter().take(12));
    v
}

/// Hostile output directories (relative to the case's scratch directory).
fn hostile_outs() -> Vec<String> {
    strings(&[
        "",
        "/dev/null",
        "/proc/self",
        "file.txt/sub",
        "a/../../../../../../../../nonexistent-root-dir/x",
        "\u{feff}out",
        "out\nline",
    ])
}

/// A generated case of a flag surface: `base` with one to three flags set to hostile values.
fn draw(
    rng: &mut Rng,
    base: &[&str],
    flags: &[(&str, &[String])],
    out_flag: Option<&str>,
) -> (Vec<String>, Vec<String>) {
    let mut args = strings(base);
    let mut drawn = Vec::new();
    let k = 1 + rng.below(3);
    let mut used = BTreeSet::new();
    for _ in 0..k {
        let (flag, values) = rng.pick(flags);
        if !used.insert(*flag) {
            continue;
        }
        let v = rng.pick(values);
        // A value after `=`, so that "-inf" or "--json" stays a value.
        args.retain_flag_removed(flag);
        args.push(format!("{flag}={v}"));
        drawn.push(flag.to_string());
    }
    if let Some(f) = out_flag
        && rng.below(8) == 0
    {
        args.retain_flag_removed(f);
        args.push(format!("{f}={}", rng.pick(&hostile_outs())));
        drawn.push(f.to_string());
    }
    (args, drawn)
}

trait RemoveFlag {
    fn retain_flag_removed(&mut self, flag: &str);
}

impl RemoveFlag for Vec<String> {
    /// Removes `flag VALUE` / `flag=VALUE` from the arguments.
    fn retain_flag_removed(&mut self, flag: &str) {
        let mut i = 0;
        while i < self.len() {
            if self[i] == flag {
                self.drain(i..(i + 2).min(self.len()));
            } else if self[i].starts_with(&format!("{flag}=")) {
                self.remove(i);
            } else {
                i += 1;
            }
        }
    }
}

/// Runs `n` generated cases of one flag surface.
#[allow(clippy::too_many_arguments)]
fn fuzz_surface(
    test: &str,
    seed: u64,
    n: usize,
    base: &[&str],
    flags: &[(&str, &[String])],
    out_flag: Option<&str>,
    allow_1: bool,
    failures: &mut Vec<String>,
) {
    let dir = scratch(test);
    std::fs::write(dir.join("file.txt"), "not a directory\n").unwrap();
    let mut rng = Rng(seed);
    for case in 0..n {
        let case_dir = dir.join(format!("c{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let _ = std::fs::copy(dir.join("file.txt"), case_dir.join("file.txt"));
        let (args, drawn) = draw(&mut rng, base, flags, out_flag);
        // The flags drawn in this case: an exit-2 message must name one of them (clap's own
        // messages name the flag with its value placeholder, e.g. `--points <N>`).
        let names: Vec<&str> = drawn.iter().map(String::as_str).collect();
        let expect = Expect {
            allow_1,
            names: &names,
        };
        attack(&args, &case_dir, Some(&case_dir), &expect, failures);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

// ---------------------------------------------------------------------------------------------
// Flag surfaces: eta, eta-map, eta-rotor, payload, prb, impact, beam

fn damping_flags() -> Vec<(&'static str, Vec<String>)> {
    let mut e = hostile_numbers();
    e.extend(strings(&["0", "1", "0.5", "1.0000001"]));
    let mut c = hostile_numbers();
    c.extend(strings(&["1e9", "1e10", "0"]));
    let mut d = hostile_numbers();
    d.extend(strings(&["1e-9", "1", "1e-10", "2"]));
    vec![
        (
            "--damping",
            strings(&[
                "none",
                "hunt-crossley",
                "lankarani-nikravesh",
                "adams-impact",
                "Hunt-Crossley",
                "",
                "adams",
            ]),
        ),
        ("--restitution", e),
        ("--c-max", c),
        ("--depth", d),
    ]
}

fn joint_flags() -> Vec<(&'static str, Vec<String>)> {
    let mut j = hostile_numbers();
    j.extend(strings(&["1e30", "1e-30", "1e9", "1e-9"]));
    vec![
        ("--joint", strings(&["held", "free-hub", "free", ""])),
        ("--rotor-inertia", j),
    ]
}

fn borrow<'a>(flags: &'a [(&'static str, Vec<String>)]) -> Vec<(&'static str, &'a [String])> {
    flags.iter().map(|(f, v)| (*f, v.as_slice())).collect()
}

/// Hostile integers for a count flag whose in-range values are cheap (`lo..=cheap_hi` only).
fn hostile_counts(cheap: &[&str]) -> Vec<String> {
    let mut v: Vec<String> = hostile_numbers()
        .into_iter()
        .filter(|s| !["1e-12", "1e12", "2.5", "1e-300", "5e-324"].contains(&s.as_str()))
        .collect();
    v.extend(strings(&["1", "1e9", "1000000000", "4294967296", "2.5"]));
    v.extend(strings(cheap));
    v
}

#[test]
fn eta_family_hostile_flags() {
    let mut failures = Vec::new();
    let tol: Vec<String> = {
        let mut t = hostile_numbers();
        t.extend(strings(&["0.1", "0.2", "1e-15"]));
        t
    };
    // eta: the modal method only for the cost-driving flags' in-range values.
    let mut eta = vec![
        ("--tol", tol.clone()),
        ("--method", strings(&["modal", "alpha", "Modal", "", "fe"])),
        ("--zone-elements", hostile_counts(&["0.5", "0.4", "1001"])),
        ("--window-periods", hostile_counts(&["0.001", "1001"])),
        ("--elements", hostile_counts(&["1", "4097"])),
        ("--steps-per-contact", hostile_counts(&["19", "2e6"])),
        ("--modes", hostile_counts(&["1001"])),
        ("--length", hostile_numbers()),
    ];
    eta.extend(damping_flags());
    eta.extend(joint_flags());
    fuzz_surface(
        "eta",
        0xE7A,
        40,
        &["eta", "--out", "out", "--json"],
        &borrow(&eta),
        Some("--out"),
        false,
        &mut failures,
    );
    let mut map = vec![
        ("--m-h", hostile_lists()),
        ("--n", hostile_lists()),
        ("--mass-ratio", hostile_ranges()),
        ("--stiffness-ratio", hostile_ranges()),
        ("--points", hostile_counts(&["201", "1"])),
        ("--tol", tol.clone()),
    ];
    map.extend(damping_flags());
    map.extend(joint_flags());
    fuzz_surface(
        "eta-map",
        0xE7A3A9,
        40,
        &[
            "eta-map", "--points", "2", "--m-h", "4", "--out", "out", "--json",
        ],
        &borrow(&map),
        Some("--out"),
        false,
        &mut failures,
    );
    let mut rotor = vec![
        ("--ratio", hostile_ranges()),
        ("--points", hostile_counts(&["201", "1"])),
        ("--n", hostile_lists()),
        ("--tol", tol),
    ];
    rotor.extend(damping_flags());
    fuzz_surface(
        "eta-rotor",
        0xE7A707,
        40,
        &[
            "eta-rotor",
            "--points",
            "2",
            "--n",
            "2",
            "--out",
            "out",
            "--json",
        ],
        &borrow(&rotor),
        Some("--out"),
        false,
        &mut failures,
    );
    report("eta_family_hostile_flags", 120, &failures);
}

/// The design and case flags of the Fig. 6 studies (`fig6`: the lumped model, cheap at any
/// value) and `flexrig scenes --write` with hostile names and files.
#[test]
fn fig6_design_and_scenes_hostile_flags() {
    let mut failures = Vec::new();
    let fig6 = vec![
        ("--m-r", hostile_numbers()),
        ("--k-c", hostile_numbers()),
        ("--v0", hostile_numbers()),
        ("--m-h", hostile_lists()),
        ("--k-delta", hostile_lists()),
        ("--m-e", hostile_lists()),
        ("--points", hostile_counts(&["2", "3"])),
    ];
    fuzz_surface(
        "fig6-design",
        0xF166,
        60,
        &["fig6", "--points", "3", "--out", "out", "--json"],
        &borrow(&fig6),
        Some("--out"),
        false,
        &mut failures,
    );
    let mut names = strings(&[
        "cj_aluminium",
        "cj_aluminum",
        "CJ_IRON",
        "",
        "../cj_iron",
        "cj_iron.toml",
        "\u{feff}cl_iron",
    ]);
    names.push("x".repeat(20_000));
    let mut files = hostile_outs();
    files.extend(strings(&["mine.toml", "file.txt", "new/dir/mine.toml"]));
    let scenes = vec![("--write", names), ("--out", files)];
    fuzz_surface(
        "scenes",
        0x5CE7E5,
        30,
        &["scenes", "--json"],
        &borrow(&scenes),
        None,
        false,
        &mut failures,
    );
    report("fig6_design_and_scenes_hostile_flags", 90, &failures);
}

#[test]
fn payload_prb_impact_beam_hostile_flags() {
    let mut failures = Vec::new();
    let scenes = {
        let mut s = strings(&[
            "cj_iron",
            "cl_iron",
            "nope",
            "",
            "../../../../etc/passwd",
            "/etc/passwd",
            "cj_iron.toml",
            "CJ_IRON",
        ]);
        s.push("s".repeat(20_000));
        s
    };
    let payload = vec![
        ("--scene", scenes),
        ("--payloads", hostile_ranges()),
        ("--points", hostile_counts(&["1", "1001"])),
    ];
    fuzz_surface(
        "payload",
        0xBA7,
        25,
        &["payload", "--points", "2", "--out", "out", "--json"],
        &borrow(&payload),
        Some("--out"),
        false,
        &mut failures,
    );
    let prb = vec![
        ("--elements", hostile_counts(&["3", "1025", "4"])),
        (
            "--model",
            strings(&["ancf", "corotational", "linear", "", "ANCF"]),
        ),
        ("--criterion", strings(&["deflection", "length", "", "tip"])),
    ];
    fuzz_surface(
        "prb",
        0x9B,
        20,
        &["prb", "--elements", "4", "--out", "out", "--json"],
        &borrow(&prb),
        Some("--out"),
        false,
        &mut failures,
    );
    let impact_flags: Vec<(&str, Vec<String>)> = [
        "--m-h",
        "--m-eff",
        "--k-delta",
        "--k-c",
        "--n",
        "--v0",
        "--rtol",
        "--gamma",
        "--m-r",
        "--m-e",
    ]
    .into_iter()
    .map(|f| (f, hostile_numbers()))
    .chain([
        (
            "--method",
            strings(&["exact", "analytic", "ode", "", "rk4"]),
        ),
        (
            "--formulation",
            strings(&["auto", "indentation", "displacement", "x"]),
        ),
    ])
    .collect();
    fuzz_surface(
        "impact",
        0x1A9AC7,
        60,
        &[
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
        ],
        &borrow(&impact_flags),
        None,
        false,
        &mut failures,
    );
    let beam_flags: Vec<(&str, Vec<String>)> = [
        "--length",
        "--youngs",
        "--density",
        "--width",
        "--thickness",
        "--tip-mass",
        "--k-theta",
        "--tip-load",
        "--tip-moment",
    ]
    .into_iter()
    .map(|f| (f, hostile_numbers()))
    .chain([
        ("--elements", hostile_counts(&["1000", "1001"])),
        ("--modes", hostile_counts(&["1", "100", "17"])),
        ("--load-steps", hostile_counts(&["1", "100"])),
        ("--root", strings(&["clamped", "pinned", "free", ""])),
        ("--model", strings(&["linear", "corotational", "ancf", "x"])),
    ])
    .collect();
    let beam = [
        "--length",
        "0.3",
        "--youngs",
        "1.5e9",
        "--density",
        "905",
        "--width",
        "0.064",
        "--thickness",
        "0.00256",
        "--json",
    ];
    let mut modal = vec!["beam", "modal"];
    modal.extend(beam);
    let modal_flags: Vec<_> = beam_flags
        .iter()
        .filter(|(f, _)| !["--tip-load", "--tip-moment", "--load-steps", "--model"].contains(f))
        .cloned()
        .collect();
    fuzz_surface(
        "beam-modal",
        0xBEA,
        30,
        &modal,
        &borrow(&modal_flags),
        None,
        false,
        &mut failures,
    );
    let mut statics = vec!["beam", "static", "--tip-load", "1"];
    statics.extend(beam);
    let static_flags: Vec<_> = beam_flags
        .iter()
        .filter(|(f, _)| *f != "--modes")
        .cloned()
        .collect();
    fuzz_surface(
        "beam-static",
        0xBEA5,
        30,
        &statics,
        &borrow(&static_flags),
        None,
        false,
        &mut failures,
    );
    report("payload_prb_impact_beam_hostile_flags", 165, &failures);
}

/// Generated hostile compression data for `fit`.
#[test]
fn fit_hostile_files() {
    let dir = scratch("fit");
    let mut rng = Rng(0xF17);
    let mut failures = Vec::new();
    let cells = hostile_numbers();
    let n = 40;
    for case in 0..n {
        let mut text = String::new();
        match rng.below(4) {
            0 => text.push_str("indentation_m,force_n\n"),
            1 => text.push_str("\u{feff}indentation_m,force_n\r\n"),
            2 => text.push_str("force_n,indentation_m,extra\n"),
            _ => {}
        }
        let rows = [0, 1, 2, 5, 20, 50_000][rng.below(6)];
        for i in 0..rows {
            let good_x = format!("{:e}", (i + 1) as f64 * 1e-4);
            let good_f = format!("{:e}", 1e6 * ((i + 1) as f64 * 1e-4).powf(1.5));
            let (x, f) = if rng.below(6) == 0 {
                (rng.pick(&cells).clone(), good_f)
            } else if rng.below(6) == 0 {
                (good_x, rng.pick(&cells).clone())
            } else {
                (good_x, good_f)
            };
            let sep = if rng.below(30) == 0 { ";" } else { "," };
            let end = if rng.below(30) == 0 { "\r\n" } else { "\n" };
            text.push_str(&format!("{x}{sep}{f}{end}"));
        }
        let path = dir.join(format!("case{case}.csv"));
        std::fs::write(&path, &text).unwrap();
        let p = path.to_string_lossy().into_owned();
        let args = vec!["fit".to_string(), p.clone(), "--json".to_string()];
        let expect = Expect {
            allow_1: false,
            names: &["line", &p, "FILE.csv", "indentation_m", "force_n"],
        };
        // The file's cells count as typed by the user (a message may quote one).
        let o = run_in(&args, &dir);
        let typed = [args.clone(), vec![text]].concat();
        if let Err(e) = verdict(&o, &typed, &expect) {
            failures.push(format!("{}\n  -> {e}", o.line));
        }
    }
    // Not a file: a directory, a missing file, a device, a binary file.
    std::fs::write(dir.join("binary.csv"), [0u8, 159, 146, 150, 255, 0, 10]).unwrap();
    for p in [
        dir.to_string_lossy().into_owned(),
        dir.join("missing.csv").to_string_lossy().into_owned(),
        "/dev/zero".to_string(),
        dir.join("binary.csv").to_string_lossy().into_owned(),
    ] {
        let args = vec!["fit".to_string(), p.clone(), "--json".to_string()];
        let expect = Expect {
            allow_1: false,
            names: &[&p, "line", "FILE.csv"],
        };
        attack(&args, &dir, None, &expect, &mut failures);
    }
    let _ = std::fs::remove_dir_all(&dir);
    report("fit_hostile_files", n + 4, &failures);
}

// ---------------------------------------------------------------------------------------------
// `--set` on run, experiment and sweep

/// Hostile dotted paths: deep, long, empty segments, unknown, unicode, TOML syntax.
fn hostile_paths(rng: &mut Rng) -> String {
    let valid = [
        "robot.payload_kg",
        "operator.start.release_angle_deg",
        "robot.design",
        "contact.damping",
        "stop",
        "solver.contact_steps",
        "robot.beam_elements",
        "record.sample_rate_hz",
        "gravity_mps2",
        "description",
        "operator.block_size_m",
    ];
    match rng.below(12) {
        0 => format!("robot.{}x", "x.".repeat(1 + rng.below(40_000))),
        1 => "a".repeat(1 + rng.below(60_000)),
        2 => [
            "",
            ".",
            "..",
            "robot.",
            ".robot",
            "robot..payload_kg",
            " robot.payload_kg",
        ][rng.below(7)]
        .to_string(),
        3 => [
            "robot.payload_kg.x",
            "robot.nope",
            "nope",
            "robot.payload_kg[0]",
            "operator.block_size_m.0",
            "\u{feff}robot.payload_kg",
            "róbot.payload_kg",
            "\"robot\".payload_kg",
            "robot.'payload_kg'",
        ][rng.below(9)]
        .to_string(),
        _ => rng.pick(&valid).to_string(),
    }
}

/// Hostile TOML values for `--set PATH=VALUE`.
fn hostile_set_value(rng: &mut Rng) -> String {
    let depth = 1 + rng.below(20_000);
    match rng.below(14) {
        0 => format!("{}1{}", "[".repeat(depth), "]".repeat(depth)),
        1 => format!("{}1{}", "{a=".repeat(depth), "}".repeat(depth)),
        2 => format!("\"{}\"", "y".repeat(1 + rng.below(60_000))),
        3 => "\"a\nb\"".to_string(),
        4 => "\"\\u0000\"".to_string(),
        5 => "{ at = \"peak\" }".to_string(),
        6 => "[0.08, 0.08, 0.08]".to_string(),
        7 => "{ model = \"hunt-crossley\", restitution = 2 }".to_string(),
        8 => ["cj", "cl", "\"cl\"", "CL", "true", "1979-05-27"][rng.below(6)].to_string(),
        9 => format!("[{}]", vec!["1"; 1 + rng.below(20_000)].join(",")),
        _ => rng.pick(&hostile_numbers()).clone(),
    }
}

#[test]
fn set_everywhere_hostile_paths_and_values() {
    let dir = scratch("set");
    let mut rng = Rng(0x5E7);
    let mut failures = Vec::new();
    let scene = scene_path("cj_iron");
    let mut cases = 0;
    for case in 0..60 {
        let out = dir.join(format!("c{case}"));
        std::fs::create_dir_all(&out).unwrap();
        let sets: Vec<String> = (0..1 + rng.below(2))
            .map(|_| {
                format!(
                    "{}={}",
                    hostile_paths(&mut rng),
                    hostile_set_value(&mut rng)
                )
            })
            .collect();
        let paths: Vec<String> = sets
            .iter()
            .map(|s| s.split('=').next().unwrap().to_string())
            .collect();
        // A path a reader can recognise must be named; a huge or empty one at least by the flag.
        let names: Vec<&str> = paths
            .iter()
            .map(|p| {
                if p.trim().is_empty() || p.len() > 256 {
                    "--set"
                } else {
                    p.as_str()
                }
            })
            .collect();
        let expect = Expect {
            allow_1: true,
            names: &names,
        };
        // run (every case), experiment (one in six: it runs ten scenes) and sweep (one in three).
        let mut args = vec!["run".to_string(), scene.clone(), "--json".to_string()];
        for s in &sets {
            args.push(format!("--set={s}"));
        }
        attack(&args, &out, Some(&out), &expect, &mut failures);
        cases += 1;
        if case % 6 == 0 {
            let mut args = strings(&["experiment", "--repeats", "1", "--json", "--out", "exp"]);
            for s in &sets {
                args.push(format!("--set={s}"));
            }
            attack(&args, &out, Some(&out), &expect, &mut failures);
            cases += 1;
        }
        // A TOML array is a list of points to `sweep`: a long one is a long (valid) sweep.
        let long_list = sets.iter().any(|s| s.matches(',').count() > 100);
        if case % 3 == 0 && !long_list {
            let mut args = vec![
                "sweep".to_string(),
                scene.clone(),
                "--out".to_string(),
                "sw".to_string(),
                "--json".to_string(),
            ];
            for s in &sets {
                args.push(format!("--set={s}"));
            }
            attack(&args, &out, Some(&out), &expect, &mut failures);
            cases += 1;
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    report("set_everywhere_hostile_paths_and_values", cases, &failures);
}

/// Regression cases of the campaign that exit 0 with a silently wrong result, or mislead.
#[test]
fn set_is_never_silently_ignored_or_misplaced() {
    let dir = scratch("set-silent");
    let scene = scene_path("cj_iron");
    let mut failures = Vec::new();
    let must_refuse = |args: &[&str], names: &[&str], failures: &mut Vec<String>| {
        let args = strings(args);
        let o = run_in(&args, &dir);
        let ok = o.code == Some(2) && names.iter().any(|n| o.stderr.contains(n));
        if !ok {
            failures.push(format!(
                "{}\n  -> expected exit 2 naming {names:?}; got exit {:?} signal {:?}\n  stderr: {}\n  stdout: {}",
                o.line,
                o.code,
                o.signal,
                shorten(&o.stderr, 300),
                shorten(&o.stdout, 200)
            ));
        }
    };
    // The same path twice in a sweep: which one runs? Refuse.
    must_refuse(
        &[
            "sweep",
            &scene,
            "--set",
            "robot.payload_kg=0.1,0.2",
            "--set",
            "robot.payload_kg=0.3",
            "--out",
            "dup",
        ],
        &["robot.payload_kg"],
        &mut failures,
    );
    // The experiment compares CJ with CL: overriding the design makes every pair the same.
    for d in ["cl", "cj"] {
        must_refuse(
            &[
                "experiment",
                "--repeats",
                "1",
                "--set",
                &format!("robot.design={d}"),
                "--out",
                "exp-design",
            ],
            &["robot.design"],
            &mut failures,
        );
    }
    // A value that is not TOML: the message must name the --set path, not a line of generated
    // text.
    for value in ["\"unterminated", "[1,", "{a=", "1 2"] {
        let args = strings(&["run", &scene, "--set", &format!("robot.payload_kg={value}")]);
        let o = run_in(&args, &dir);
        let line_number = o
            .stderr
            .match_indices("line ")
            .any(|(i, _)| o.stderr[i + 5..].starts_with(|c: char| c.is_ascii_digit()));
        if o.code != Some(2) || !o.stderr.contains("robot.payload_kg") || line_number {
            failures.push(format!(
                "{}\n  -> expected exit 2 naming robot.payload_kg without a line number of generated text; got exit {:?}\n  stderr: {}",
                o.line,
                o.code,
                shorten(&o.stderr, 300)
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    report("set_is_never_silently_ignored_or_misplaced", 7, &failures);
}

// ---------------------------------------------------------------------------------------------
// Sweep grids, files, shards, merge, resume

/// Hostile sweep SPECs.
fn hostile_spec(rng: &mut Rng) -> String {
    match rng.below(10) {
        0 => rng.pick(&hostile_numbers()).clone(),
        1 => [
            "0.1:1:0",
            "0.1:1:-1",
            "0.1:1:1e9",
            "0.1:1:2.5",
            "0:1:3:log",
            "-1:1:3:log",
            "1e-300:1e300:3:log",
            "nan:1:3",
            "0.1:inf:3",
            "0.1:1:3:lin",
            "0.1:1:3:log:x",
            "0.1:1:18446744073709551616",
            "0.1:1:10000001",
            "0.1:1",
            "0.1::3",
            ":::",
        ][rng.below(16)]
        .to_string(),
        2 => [
            ",",
            "0.1,",
            ",0.1",
            "0.1,,0.2",
            "[0.1, 0.2]",
            "[]",
            "[0.1, \"a\"]",
            "[[0.1]]",
            "cj,cl",
            "0.1,cj",
        ][rng.below(10)]
        .to_string(),
        3 => format!("{},abc", vec!["0.2"; 20_000].join(",")),
        4 => [
            "@missing.txt",
            "@",
            "@/dev/null",
            "@/dev/zero",
            "@values-empty.txt",
            "@values-bom.txt",
            "@values-bad.txt",
            "@values-many.txt",
            "@values-dir",
            "@values-nested.txt",
        ][rng.below(10)]
        .to_string(),
        _ => {
            ["0.1,0.2", "0.1:0.3:2", "0.05:1:2:log", "0.3", "@values.txt"][rng.below(5)].to_string()
        }
    }
}

fn sweep_files(dir: &Path) {
    std::fs::write(dir.join("values.txt"), "# payloads\n0.1\n0.2\n").unwrap();
    std::fs::write(dir.join("values-empty.txt"), "# nothing\n\n").unwrap();
    std::fs::write(dir.join("values-bom.txt"), "\u{feff}0.1\r\n0.2\r\n").unwrap();
    std::fs::write(dir.join("values-bad.txt"), "0.1\nabc\n1e999\n").unwrap();
    std::fs::write(dir.join("values-nested.txt"), "@values.txt\n").unwrap();
    // 10^7 + 1 values: over the limit of 10^7 points on its own.
    let many: String = "0.3\n".repeat(10_000_001);
    std::fs::write(dir.join("values-many.txt"), many).unwrap();
    std::fs::create_dir_all(dir.join("values-dir")).unwrap();
}

#[test]
fn sweep_hostile_grids_zips_and_shards() {
    let dir = scratch("sweep");
    sweep_files(&dir);
    let base = dir.join("base.toml");
    // From contact to the peak: the cheapest run of the scene.
    let text = std::fs::read_to_string(scene_path("cj_iron"))
        .unwrap()
        .replace(
            "start = { from = \"release\", release_angle_deg = 30.0 }",
            "start = { from = \"contact\", release_angle_deg = 30.0 }",
        )
        .replace("at = \"separation\"", "at = \"peak\"")
        // Rapier's contact: the workloads below are sized by its cost (the adaptive contact,
        // the CJ's default, finishes the interrupted sweeps before the interrupt)
        .replace(
            "contact_steps = 800",
            "contact_steps = 800\ncontact = \"fixed\"",
        );
    std::fs::write(&base, text).unwrap();
    let base = base.to_string_lossy().into_owned();
    let paths = [
        "robot.payload_kg",
        "operator.start.release_angle_deg",
        "robot.design",
        "robot.beam_elements",
    ];
    let mut rng = Rng(0x5EE9);
    let mut failures = Vec::new();
    let n = 50;
    for case in 0..n {
        let out = format!("sw{case}");
        let mut args = vec![
            "sweep".to_string(),
            base.clone(),
            "--out".to_string(),
            out.clone(),
            "--json".to_string(),
        ];
        let k = 1 + rng.below(3);
        let mut names = vec!["--set", "--zip", "--shard", "grid"];
        for path in paths.iter().take(k) {
            let spec = hostile_spec(&mut rng);
            args.push(format!("--set={path}={spec}"));
            names.push(path);
        }
        if rng.below(4) == 0 {
            args.push("--zip".into());
        }
        if rng.below(4) == 0 {
            let shard = [
                "0/2",
                "1/2",
                "2/2",
                "0/0",
                "-1/4",
                "1/",
                "/4",
                "a/b",
                "0/18446744073709551616",
                "0/1",
            ];
            args.push(format!("--shard={}", rng.pick(&shard)));
        }
        let expect = Expect {
            allow_1: true,
            names: &names,
        };
        attack(&args, &dir, Some(&dir.join(&out)), &expect, &mut failures);
    }
    // Huge grids are judged before anything runs: three large ranges, and @file values.
    for (what, sets) in [
        (
            "three ranges of 10^4",
            vec![
                "robot.payload_kg=0.01:1:10000",
                "operator.start.release_angle_deg=10:60:10000",
                "robot.length_m=0.2:0.4:10000",
            ],
        ),
        (
            "two files of 1e7 values",
            vec![
                "robot.payload_kg=@values-many.txt",
                "operator.start.release_angle_deg=@values-many.txt",
            ],
        ),
        (
            "a range of 1e7 and a file of 1e7",
            vec![
                "robot.payload_kg=0.01:1:10000000",
                "operator.start.release_angle_deg=@values-many.txt",
            ],
        ),
    ] {
        let mut args = vec![
            "sweep".to_string(),
            base.clone(),
            "--out".to_string(),
            "huge".to_string(),
        ];
        args.extend(sets.iter().map(|s| format!("--set={s}")));
        let o = run_in(&args, &dir);
        if o.code != Some(2) || !o.stderr.contains("points") {
            failures.push(format!(
                "{} ({what})\n  -> expected exit 2 saying the grid has too many points; got exit {:?} signal {:?} timed out {}\n  stderr: {}",
                o.line,
                o.code,
                o.signal,
                o.timed_out,
                shorten(&o.stderr, 300)
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    report("sweep_hostile_grids_zips_and_shards", n + 3, &failures);
}

/// The rows of a sweep table by index (the header first).
fn table(path: &Path) -> Result<Vec<Vec<String>>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    csv_records(&text).map_err(|e| format!("{}: {e}", path.display()))
}

fn sweep_base(dir: &Path) -> String {
    let base = dir.join("base.toml");
    let text = std::fs::read_to_string(scene_path("cj_iron"))
        .unwrap()
        .replace(
            "start = { from = \"release\", release_angle_deg = 30.0 }",
            "start = { from = \"contact\", release_angle_deg = 30.0 }",
        )
        .replace("at = \"separation\"", "at = \"peak\"")
        // Rapier's contact: the workloads below are sized by its cost (the adaptive contact,
        // the CJ's default, finishes the interrupted sweeps before the interrupt)
        .replace(
            "contact_steps = 800",
            "contact_steps = 800\ncontact = \"fixed\"",
        );
    std::fs::write(&base, text).unwrap();
    base.to_string_lossy().into_owned()
}

/// A sweep of four payloads into `out` (with a description holding a newline, a comma and
/// quotes in every row when `awkward`), with `extra` arguments.
fn small_sweep(dir: &Path, base: &str, out: &str, awkward: bool, extra: &[&str]) -> Outcome {
    let mut args = strings(&[
        "sweep",
        base,
        "--set",
        "robot.payload_kg=0.1:0.4:4",
        "--out",
        out,
    ]);
    if awkward {
        args.push("--set".into());
        args.push("description=\"two\\nlines, \\\"quoted\\\"\"".into());
    }
    args.extend(strings(extra));
    run_in(&args, dir)
}

fn expect_exit(o: &Outcome, code: i32, what: &str, failures: &mut Vec<String>) {
    if o.code != Some(code) || o.signal.is_some() || o.timed_out {
        failures.push(format!(
            "{} ({what})\n  -> expected exit {code}; got exit {:?} signal {:?} timed out {}\n  stderr: {}",
            o.line,
            o.code,
            o.signal,
            o.timed_out,
            shorten(&o.stderr, 300)
        ));
    }
}

#[test]
fn sweep_tables_with_awkward_cells_resume_and_merge() {
    // A cell holding a newline, a comma and quotes (a TOML string field varied or set): the CSV
    // quotes it, and everything that reads the table back (a rerun, a resume, `sweep merge`)
    // must read it as one cell.
    let dir = scratch("awkward");
    let base = sweep_base(&dir);
    let mut failures = Vec::new();
    let whole = small_sweep(&dir, &base, "whole", true, &[]);
    expect_exit(&whole, 0, "the reference", &mut failures);
    let reference = table(&dir.join("whole/sweep.csv"));
    match &reference {
        Ok(r) if r.len() == 5 => {}
        other => failures.push(format!(
            "whole/sweep.csv: expected a header and 4 rows, got {other:?}"
        )),
    }
    let again = small_sweep(&dir, &base, "whole", true, &[]);
    expect_exit(&again, 0, "rerun over the finished table", &mut failures);
    if table(&dir.join("whole/sweep.csv")) != reference {
        failures.push(format!("{}\n  -> the rerun changed the table", again.line));
    }
    for s in ["0/2", "1/2"] {
        let o = small_sweep(&dir, &base, "shards", true, &["--shard", s]);
        expect_exit(&o, 0, "a shard", &mut failures);
    }
    let shards = dir.join("shards").to_string_lossy().into_owned();
    let o = run_in(&strings(&["sweep", "merge", &shards]), &dir);
    expect_exit(&o, 0, "merge of clean shards", &mut failures);
    if o.code == Some(0) && table(&dir.join("shards/sweep.csv")) != reference {
        failures.push(format!(
            "{}\n  -> the merged table differs from the whole sweep's",
            o.line
        ));
    }
    // Interrupted half way (simulated: the shard's rows as the journal of the whole sweep).
    let o = small_sweep(&dir, &base, "resume", true, &["--shard", "0/2"]);
    expect_exit(&o, 0, "a shard", &mut failures);
    let shard_csv = dir.join("resume/sweep.shard-0-of-2.csv");
    let rows = std::fs::read_to_string(&shard_csv).unwrap_or_default();
    let _ = std::fs::remove_file(&shard_csv);
    std::fs::write(dir.join("resume/sweep.csv.partial"), rows).unwrap();
    let o = small_sweep(&dir, &base, "resume", true, &[]);
    expect_exit(&o, 0, "resume from a journal", &mut failures);
    if o.code == Some(0) && table(&dir.join("resume/sweep.csv")) != reference {
        failures.push(format!(
            "{}\n  -> the resumed table differs from the whole sweep's",
            o.line
        ));
    }
    for d in ["whole", "shards", "resume"] {
        failures.extend(output_floor(&dir.join(d)));
    }
    let _ = std::fs::remove_dir_all(&dir);
    report(
        "sweep_tables_with_awkward_cells_resume_and_merge",
        7,
        &failures,
    );
}

#[test]
fn sweep_merge_refuses_foreign_rows_and_resume_survives_torn_journals() {
    let dir = scratch("merge");
    let base = sweep_base(&dir);
    let mut failures = Vec::new();
    let whole = small_sweep(&dir, &base, "whole", false, &[]);
    expect_exit(&whole, 0, "the reference", &mut failures);
    let reference = table(&dir.join("whole/sweep.csv"));
    // Shards, merged; then a row whose index is outside the sweep, and a duplicated row.
    for s in ["0/2", "1/2"] {
        let o = small_sweep(&dir, &base, "shards", false, &["--shard", s]);
        expect_exit(&o, 0, "a shard", &mut failures);
    }
    let shards = dir.join("shards").to_string_lossy().into_owned();
    let merge = || run_in(&strings(&["sweep", "merge", &shards, "--json"]), &dir);
    let o = merge();
    expect_exit(&o, 0, "merge of clean shards", &mut failures);
    if table(&dir.join("shards/sweep.csv")) != reference {
        failures.push(format!(
            "{}\n  -> the merged table differs from the whole sweep's",
            o.line
        ));
    }
    let shard0 = dir.join("shards/sweep.shard-0-of-2.csv");
    let shard0_text = std::fs::read_to_string(&shard0).unwrap_or_default();
    let last_row = shard0_text.trim_end().rsplit('\n').next().unwrap_or("");
    let rest = last_row.split_once(',').map(|(_, r)| r).unwrap_or("");
    for (what, index) in [("outside the sweep", "99"), ("duplicated", "1")] {
        let _ = std::fs::remove_file(dir.join("shards/sweep.csv"));
        std::fs::write(&shard0, format!("{shard0_text}{index},{rest}\n")).unwrap();
        let o = merge();
        if o.code != Some(2) || !o.stderr.contains(index) || dir.join("shards/sweep.csv").exists() {
            failures.push(format!(
                "{} (a shard row with index {index}: {what})\n  -> expected exit 2 naming the index and no sweep.csv; got exit {:?}, sweep.csv {}\n  stderr: {}",
                o.line,
                o.code,
                if dir.join("shards/sweep.csv").exists() { "written" } else { "absent" },
                shorten(&o.stderr, 300)
            ));
        }
    }
    // A torn last journal line (a crash mid-write): the rerun finishes the same table.
    for (name, tear) in [
        ("torn", "3,0.4,o"),
        ("garbage", "\u{0}\u{0}\u{0}"),
        ("half-number", "2,0.3"),
        ("quote", "3,\"0.4"),
    ] {
        let out = format!("resume-{name}");
        let o = small_sweep(&dir, &base, &out, false, &["--shard", "0/2"]);
        expect_exit(&o, 0, "a shard", &mut failures);
        // The shard's finished rows become the journal of the whole sweep, its end torn.
        let shard_csv = dir.join(&out).join("sweep.shard-0-of-2.csv");
        let rows = std::fs::read_to_string(&shard_csv).unwrap_or_default();
        let _ = std::fs::remove_file(&shard_csv);
        std::fs::write(
            dir.join(&out).join("sweep.csv.partial"),
            format!("{rows}{tear}"),
        )
        .unwrap();
        let r = small_sweep(&dir, &base, &out, false, &[]);
        expect_exit(
            &r,
            0,
            &format!("resume after a journal ending in {tear:?}"),
            &mut failures,
        );
        if r.code == Some(0) && table(&dir.join(&out).join("sweep.csv")) != reference {
            failures.push(format!(
                "{}\n  -> after a journal ending in {tear:?} the table differs from the whole sweep's",
                r.line
            ));
        }
        failures.extend(output_floor(&dir.join(&out)));
    }
    let _ = std::fs::remove_dir_all(&dir);
    report(
        "sweep_merge_refuses_foreign_rows_and_resume_survives_torn_journals",
        11,
        &failures,
    );
}

// ---------------------------------------------------------------------------------------------
// Documented bounds, lists, overwrites

#[test]
fn documented_bounds_run_and_lists_are_bounded() {
    let dir = scratch("bounds");
    let mut failures = Vec::new();
    let at_bound = |args: &[&str], failures: &mut Vec<String>| {
        let args = strings(args);
        let o = run_in(&args, &dir);
        let v = verdict(
            &o,
            &args,
            &Expect {
                allow_1: false,
                names: &[],
            },
        );
        if o.code != Some(0) || v.is_err() {
            failures.push(format!(
                "{}\n  -> a documented bound must run: exit {:?} {:?}\n  stderr: {}",
                o.line,
                o.code,
                v.err(),
                shorten(&o.stderr, 300)
            ));
        }
        failures.extend(output_floor(&dir.join("out")));
    };
    // `prb --elements`: 4 to 256.
    at_bound(
        &["prb", "--elements", "256", "--out", "out", "--json"],
        &mut failures,
    );
    // `eta --damping adams-impact`: --c-max in [0, 1000 × the contact's critical damping]
    // (3.75e5 N·s/m for the light-payload n = 2 cases of the table), --depth in [1e-9, 1];
    // beyond that bound the refusal is tested below.
    for (c, d) in [("3.7e5", "1"), ("3.7e5", "1e-9"), ("0", "1e-9")] {
        at_bound(
            &[
                "eta",
                "--damping",
                "adams-impact",
                "--c-max",
                c,
                "--depth",
                d,
                "--out",
                "out",
                "--json",
            ],
            &mut failures,
        );
    }
    // `eta --tol`: 1e-10 to 0.1.
    for tol in ["1e-10", "0.1"] {
        at_bound(
            &["eta", "--tol", tol, "--out", "out", "--json"],
            &mut failures,
        );
    }
    // Lists: tens of thousands of head masses or exponents are refused at once, naming the flag.
    for (flag, cmd, value) in [
        ("--m-h", "eta-map", vec!["4"; 20_000].join(",")),
        ("--n", "eta-rotor", vec!["2"; 20_000].join(",")),
        ("--m-h", "eta-map", vec!["4"; 201].join(",")),
    ] {
        let args = vec![
            cmd.to_string(),
            format!("{flag}={value}"),
            "--points".to_string(),
            "2".to_string(),
            "--out".to_string(),
            "lists".to_string(),
        ];
        let o = run_in(&args, &dir);
        if o.code != Some(2) || !o.stderr.contains(flag) {
            failures.push(format!(
                "{}\n  -> expected exit 2 naming {flag}; got exit {:?} signal {:?} timed out {}\n  stderr: {}",
                o.line,
                o.code,
                o.signal,
                o.timed_out,
                shorten(&o.stderr, 300)
            ));
        }
    }
    // A rotor inertia out of range is refused before any figure is written.
    for j in ["1e30", "1e-30", "0"] {
        let args = strings(&[
            "eta-map",
            "--joint",
            "free-hub",
            "--rotor-inertia",
            j,
            "--points",
            "2",
            "--m-h",
            "4",
            "--out",
            "rotor",
        ]);
        let o = run_in(&args, &dir);
        let wrote = dir.join("rotor").exists();
        if o.code != Some(2) || !o.stderr.contains("--rotor-inertia") || wrote {
            failures.push(format!(
                "{}\n  -> expected exit 2 naming --rotor-inertia and no output; got exit {:?}, output directory {}\n  stderr: {}\n  stdout: {}",
                o.line,
                o.code,
                if wrote { "written" } else { "absent" },
                shorten(&o.stderr, 200),
                shorten(&o.stdout, 300)
            ));
        }
        let _ = std::fs::remove_dir_all(dir.join("rotor"));
    }
    // The experiment's JSON holds no null (a missing contact duration is left out).
    let args = strings(&["experiment", "--repeats", "1", "--out", "exp", "--json"]);
    let o = run_in(&args, &dir);
    if let Err(e) = verdict(
        &o,
        &args,
        &Expect {
            allow_1: false,
            names: &[],
        },
    ) {
        failures.push(format!("{}\n  -> {e}", o.line));
    }
    failures.extend(output_floor(&dir.join("exp")));
    let _ = std::fs::remove_dir_all(&dir);
    report("documented_bounds_run_and_lists_are_bounded", 16, &failures);
}

#[test]
fn run_out_never_overwrites_without_force_nor_replaces_symlinks() {
    let dir = scratch("overwrite");
    let scene = scene_path("cj_iron");
    let mut failures = Vec::new();
    // An existing layout beside a new MCAP file: refused without --force, left as it was.
    std::fs::write(dir.join("a.layout.json"), "{\"mine\": true}\n").unwrap();
    let args = strings(&["run", &scene, "--out", "a.mcap"]);
    let o = run_in(&args, &dir);
    let layout = std::fs::read_to_string(dir.join("a.layout.json")).unwrap_or_default();
    if o.code != Some(2) || layout != "{\"mine\": true}\n" || dir.join("a.mcap").exists() {
        failures.push(format!(
            "{}\n  -> an existing a.layout.json without --force: expected exit 2 and nothing written; got exit {:?}, layout {}\n  stderr: {}",
            o.line,
            o.code,
            if layout == "{\"mine\": true}\n" { "kept" } else { "replaced" },
            shorten(&o.stderr, 300)
        ));
    }
    // --force over symlinks: the links stay links (written through, or refused).
    std::fs::write(dir.join("target-mcap.bin"), "keep").unwrap();
    std::fs::write(dir.join("target-layout.bin"), "{}").unwrap();
    std::os::unix::fs::symlink(dir.join("target-mcap.bin"), dir.join("b.mcap")).unwrap();
    std::os::unix::fs::symlink(dir.join("target-layout.bin"), dir.join("b.layout.json")).unwrap();
    let args = strings(&["run", &scene, "--out", "b.mcap", "--force"]);
    let o = run_in(&args, &dir);
    for link in ["b.mcap", "b.layout.json"] {
        let still = std::fs::symlink_metadata(dir.join(link))
            .map(|m| m.file_type().is_symlink())
            .unwrap_or(false);
        if !still || !matches!(o.code, Some(0) | Some(2)) {
            failures.push(format!(
                "{}\n  -> {link} was a symlink: after the run it is {}; exit {:?}\n  stderr: {}",
                o.line,
                if still {
                    "still a symlink"
                } else {
                    "not a symlink"
                },
                o.code,
                shorten(&o.stderr, 300)
            ));
        }
    }
    // An --out that is a directory, or in a missing directory, or a device.
    for out in ["sub", "missing/x.mcap", "/dev/full"] {
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let args = strings(&["run", &scene, "--out", out, "--force"]);
        let o = run_in(&args, &dir);
        if let Err(e) = verdict(
            &o,
            &args,
            &Expect {
                allow_1: false,
                names: &["--out", out],
            },
        ) {
            failures.push(format!("{}\n  -> {e}", o.line));
        }
    }
    failures.extend(output_floor(&dir));
    let _ = std::fs::remove_dir_all(&dir);
    report(
        "run_out_never_overwrites_without_force_nor_replaces_symlinks",
        6,
        &failures,
    );
}

// ---------------------------------------------------------------------------------------------
// Interruption

/// CPU time (user + system, clock ticks) the process `pid` has used; None once it is gone.
fn cpu_ticks(pid: u32) -> Option<u64> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // Fields after the command name (which may hold spaces) in parentheses.
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split_whitespace().collect();
    Some(f.get(11)?.parse::<u64>().ok()? + f.get(12)?.parse::<u64>().ok()?)
}

/// Starts `args`, sends SIGINT once it has used `ticks` of CPU time (so it is past start-up
/// and into the work, however fast the machine), and checks exit 130, no signal death, and
/// complete-or-absent outputs in `out`.
fn interrupt(args: &[&str], cwd: &Path, out: &Path, ticks: u64, failures: &mut Vec<String>) {
    let args = strings(args);
    let child = spawn(&args, cwd);
    let mut sent = false;
    let o = finish(child, show(&args), |pid| {
        if cpu_ticks(pid).is_some_and(|t| t >= ticks) {
            let _ = Command::new("kill")
                .args(["-INT", &pid.to_string()])
                .status();
            sent = true;
            true
        } else {
            false
        }
    });
    let problem = if !sent {
        Some(format!(
            "finished (exit {:?}) before it had used {ticks} ticks of CPU time: make the workload longer",
            o.code
        ))
    } else if o.timed_out {
        Some(format!("{HANG}: Ctrl-C ignored"))
    } else if o.signal.is_some() || o.code != Some(130) {
        Some(format!(
            "expected exit 130 after Ctrl-C; got exit {:?} signal {:?}",
            o.code, o.signal
        ))
    } else {
        None
    };
    if let Some(p) = problem {
        failures.push(format!(
            "{}\n  -> {p}\n  stderr: {}",
            o.line,
            shorten(&o.stderr, 300)
        ));
    }
    for p in output_floor(out) {
        failures.push(format!("{} (interrupted)\n  -> {p}", o.line));
    }
}

#[test]
fn ctrl_c_stops_every_long_command_with_130_and_whole_files() {
    let dir = scratch("sigint");
    let base = sweep_base(&dir);
    let mut failures = Vec::new();
    // Each workload takes several seconds on a fast machine; the interrupt comes after 0.3 s of
    // CPU time.
    // (`eta --method alpha` is in its own test below: still open)
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["eta", "--window-periods", "200", "--out", "eta"],
            "eta",
        ),
        (vec!["eta-map", "--out", "eta-map"], "eta-map"),
        (
            vec!["eta-rotor", "--points", "200", "--out", "eta-rotor"],
            "eta-rotor",
        ),
        (vec!["experiment", "--repeats", "40", "--out", "exp"], "exp"),
        (
            vec![
                "sweep",
                &base,
                "--set",
                "robot.payload_kg=0.01:1:20000",
                "--out",
                "sweep",
            ],
            "sweep",
        ),
        (
            vec!["payload", "--points", "1000", "--out", "payload"],
            "payload",
        ),
        // the reference at 12 modes takes minutes: Ctrl-C stops it between two of its steps
        (
            vec![
                "spin-up",
                "--modes",
                "12",
                "--elements",
                "200",
                "--out",
                "spin",
            ],
            "spin",
        ),
    ];
    for (args, out) in &cases {
        interrupt(args, &dir, &dir.join(out), 30, &mut failures);
    }
    // The interrupted sweep resumes: a smaller sweep over the same directory is refused (another
    // sweep), the same command finishes it (checked on a cheap grid: interrupt, then resume).
    let args = [
        "sweep",
        &base,
        "--set",
        "robot.payload_kg=0.01:1:1000",
        "--out",
        "resume",
    ];
    interrupt(&args, &dir, &dir.join("resume"), 30, &mut failures);
    let o = run_in(&strings(&args), &dir);
    match table(&dir.join("resume/sweep.csv")) {
        Ok(t) if o.code == Some(0) && t.len() == 1001 => {
            let indices: BTreeSet<&str> = t[1..].iter().map(|r| r[0].as_str()).collect();
            if indices.len() != 1000 {
                failures.push(format!(
                    "{}\n  -> the resumed table has {} distinct indices, not 1000",
                    o.line,
                    indices.len()
                ));
            }
        }
        other => failures.push(format!(
            "{}\n  -> resume after Ctrl-C: exit {:?}, table {:?}\n  stderr: {}",
            o.line,
            o.code,
            other.map(|t| t.len()),
            shorten(&o.stderr, 300)
        )),
    }
    let _ = std::fs::remove_dir_all(&dir);
    report(
        "ctrl_c_stops_every_long_command_with_130_and_whole_files",
        cases.len() + 2,
        &failures,
    );
}

// ---------------------------------------------------------------------------------------------
// Concurrency

#[test]
fn concurrent_writers_leave_whole_tables_and_logs() {
    let dir = scratch("concurrent");
    let base = sweep_base(&dir);
    let mut failures = Vec::new();
    // Two identical sweeps into one directory at once: each finishes (0) or refuses (2, naming
    // the directory), and the table holds every point exactly once.
    let args = strings(&[
        "sweep",
        &base,
        "--set",
        "robot.payload_kg=0.01:1:300",
        "--out",
        "same",
    ]);
    let children: Vec<Child> = (0..2).map(|_| spawn(&args, &dir)).collect();
    for child in children {
        let o = finish(child, show(&args), |_| true);
        if let Err(e) = verdict(
            &o,
            &args,
            &Expect {
                allow_1: false,
                names: &["same", "--out"],
            },
        ) {
            failures.push(format!("{} (two at once)\n  -> {e}", o.line));
        }
    }
    match table(&dir.join("same/sweep.csv")) {
        Ok(t) => {
            let indices: BTreeSet<&str> = t[1..].iter().map(|r| r[0].as_str()).collect();
            if t.len() != 301 || indices.len() != 300 {
                failures.push(format!(
                    "same/sweep.csv after two sweeps at once: {} rows, {} distinct indices (expected 300)",
                    t.len() - 1,
                    indices.len()
                ));
            }
        }
        Err(e) => failures.push(format!("same/sweep.csv after two sweeps at once: {e}")),
    }
    failures.extend(output_floor(&dir.join("same")));
    // Two runs logging to one MCAP file at once (--force): a whole log either way.
    let scene = scene_path("cj_iron");
    let args = strings(&["run", &scene, "--out", "log.mcap", "--force"]);
    let children: Vec<Child> = (0..2).map(|_| spawn(&args, &dir)).collect();
    for child in children {
        let o = finish(child, show(&args), |_| true);
        if let Err(e) = verdict(
            &o,
            &args,
            &Expect {
                allow_1: false,
                names: &["log.mcap", "--out"],
            },
        ) {
            failures.push(format!("{} (two at once)\n  -> {e}", o.line));
        }
    }
    failures.extend(output_floor(&dir));
    let _ = std::fs::remove_dir_all(&dir);
    report(
        "concurrent_writers_leave_whole_tables_and_logs",
        4,
        &failures,
    );
}

/// Regression: Ctrl-C reached the reference (generalized-α) method of `eta` only between its
/// cases, each of which runs for tens of seconds; the stop flag now reaches the FE step loop.
#[test]
fn ctrl_c_stops_the_reference_method_of_eta_within_a_second() {
    let dir = scratch("sigint-alpha");
    let mut failures = Vec::new();
    interrupt(
        &["eta", "--method", "alpha", "--out", "eta"],
        &dir,
        &dir.join("eta"),
        30,
        &mut failures,
    );
    report("ctrl_c_alpha", 1, &failures);
}

/// Regression: with the stiffest ADAMS damping over the thinnest depth the integrators' steps
/// shrank to the contact's damping time scale and the release crept for minutes; a contact damped
/// more than a thousand times past critical is now refused up front, naming --c-max and its bound.
#[test]
fn the_stiffest_adams_damping_over_the_thinnest_depth_answers_in_seconds() {
    let dir = scratch("adams-bound");
    let args = strings(&[
        "eta",
        "--damping",
        "adams-impact",
        "--c-max",
        "1e9",
        "--depth",
        "1e-9",
        "--out",
        "out",
        "--json",
    ]);
    let o = run_in(&args, &dir);
    let mut failures = Vec::new();
    if o.code != Some(2) || !o.stderr.contains("--c-max") || !o.stderr.contains("critical") {
        failures.push(format!(
            "{}\n  -> exit {:?}, expected 2 naming --c-max and the critical damping; stderr: {}",
            o.line,
            o.code,
            shorten(&o.stderr, 300)
        ));
    }
    if dir.join("out").join("eta.csv").exists() {
        failures.push(format!("{}\n  -> wrote eta.csv although refused", o.line));
    }
    report("adams_bound", 1, &failures);
}

// ---------------------------------------------------------------------------------------------
// The driven surfaces: strike flags, traces, role-switch flags

/// A Rust Debug value in a message: `Name { field: … }` (a word, ` { `, then `field:`), or an
/// escaped character `\u{…}` the user did not type.
fn debug_text(text: &str) -> Option<String> {
    for (i, _) in text.match_indices(" { ") {
        let before = text[..i].chars().last().unwrap_or(' ');
        let after: String = text[i + 3..]
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        if before.is_alphanumeric()
            && !after.is_empty()
            && text[i + 3 + after.len()..].starts_with(':')
        {
            return Some(shorten(&text[i.saturating_sub(30)..], 80));
        }
    }
    text.find("\\u{").map(|i| shorten(&text[i..], 40))
}

/// `flexrig strike` with hostile flags (1–3 per case, a fixed seed, a case budget): every case
/// ends with exit 0 and a finished answer, or exit 2 naming the flag, never a panic, an abort,
/// a hang, a null in the JSON or Debug text. The contact's resolvability couples the speed,
/// the contact law and the masses, so a refusal may name `--speed` or `--k-c` for a drawn mass.
#[test]
fn strike_and_role_switch_hostile_flags() {
    let mut failures = Vec::new();
    let mut cases = 0;
    let mut numbers = hostile_numbers();
    numbers.retain(|s| s.len() < 1000);
    numbers.extend(strings(&[
        "95.5", "1e-20", "1e40", "1e-6", "600", "1e15", "0.1", "3",
    ]));
    let scalar = [
        "--m-r",
        "--length",
        "--k-delta",
        "--m-e",
        "--rotor-inertia",
        "--gear-ratio",
        "--friction",
        "--speed",
        "--ramp-time",
        "--kp",
        "--kd",
        "--torque-limit",
        "--m-h",
        "--k-c",
        "--n",
        "--settle",
        "--horizon",
        "--trace-every",
    ];
    let mut flags: Vec<(&str, Vec<String>)> =
        scalar.iter().map(|f| (*f, numbers.clone())).collect();
    flags.push(("--design", strings(&["cj", "cl", "cx", "", "CJ"])));
    flags.push(("--support", strings(&["free", "wall", "neck", ""])));
    let dir = scratch("strike_fuzz");
    let mut rng = Rng(0x5EED_0035);
    for case in 0..48 {
        let case_dir = dir.join(format!("c{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let base: &[&str] = if case % 2 == 0 {
            &["strike", "--json"]
        } else {
            &["strike"]
        };
        let (mut args, mut drawn) = draw(&mut rng, base, &borrow(&flags), None);
        if args.iter().any(|a| a.starts_with("--trace-every")) {
            args.push("--out=o".into());
        }
        drawn.extend(strings(&["--speed", "--k-c"]));
        let names: Vec<&str> = drawn.iter().map(String::as_str).collect();
        let expect = Expect {
            allow_1: false,
            names: &names,
        };
        let o = attack(&args, &case_dir, Some(&case_dir), &expect, &mut failures);
        if let Some(d) = debug_text(&format!("{}\n{}", o.stdout, o.stderr)) {
            failures.push(format!("{}\n  -> Debug text: {d}", o.line));
        }
        cases += 1;
    }
    // role-switch: the kappa list and the scalar flags, on the test bed's cases only
    let mut kappas = hostile_lists();
    kappas.retain(|s| s.len() < 200_000);
    kappas.extend(strings(&[
        "1,1",
        "1e7",
        "1,2,3,4,5,6,7,8,9,10,11,12,13",
        "1e-7",
    ]));
    let role: Vec<(&str, Vec<String>)> = vec![
        ("--kappa", kappas),
        ("--rotor-ratio", numbers.clone()),
        ("--damping-ratio", numbers.clone()),
    ];
    for case in 0..12 {
        let case_dir = dir.join(format!("r{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let (mut args, drawn) = draw(
            &mut rng,
            &["role-switch", "--no-fig6"],
            &borrow(&role),
            None,
        );
        args.push("--out=o".into());
        let names: Vec<&str> = drawn.iter().map(String::as_str).collect();
        let expect = Expect {
            allow_1: false,
            names: &names,
        };
        let o = attack(&args, &case_dir, Some(&case_dir), &expect, &mut failures);
        if let Some(d) = debug_text(&format!("{}\n{}", o.stdout, o.stderr)) {
            failures.push(format!("{}\n  -> Debug text: {d}", o.line));
        }
        cases += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    report("strike_and_role_switch_hostile_flags", cases, &failures);
}

/// A drive description's value lines (`key = value`) that the drive fuzzer rewrites, and the
/// words (the field's key) an exit-2 message may name for it.
fn drive_value_lines(text: &str) -> Vec<(usize, String)> {
    text.lines()
        .enumerate()
        .filter_map(|(i, l)| {
            let (key, _) = l.split_once(" = ")?;
            let key = key.trim();
            (!key.starts_with('#') && !key.is_empty()).then(|| (i, key.to_string()))
        })
        .collect()
}

/// A hostile TOML value for a drive or body-model field: numbers that parse and do not, words,
/// tables, arrays, strings with control characters.
fn hostile_toml_value(rng: &mut Rng) -> String {
    match rng.below(10) {
        0 => "nan".into(),
        1 => "inf".into(),
        2 => "-inf".into(),
        3 => "\"x\\u0000y\"".into(),
        4 => "\"a\\nb\"".into(),
        5 => "{ a = 1 }".into(),
        6 => "[1, 2]".into(),
        7 => "\"\"".into(),
        _ => [
            "0",
            "-0.0",
            "-1.0",
            "1e-300",
            "5e-324",
            "1e300",
            "1.7976931348623157e308",
            "1e-20",
            "1e40",
            "0.1",
            "95.5",
            "1e15",
            "true",
            "\"cl\"",
            "\"cj\"",
            "\"wall\"",
            "\"neck\"",
            "\"spin_up\"",
            "\"open_loop\"",
            "\"trajectory\"",
            "\"angle\"",
        ][rng.below(21)]
        .into(),
    }
}

/// The body model mutated one way: a limit or constant set to a hostile value, an area's name
/// repeated, a name with a control or format character, a key that breaks tables, the file cut
/// short, or a byte that is not UTF-8.
fn hostile_body_model(rng: &mut Rng, bundled: &str) -> Vec<u8> {
    let lines: Vec<&str> = bundled.lines().collect();
    let fields: Vec<usize> = lines
        .iter()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with('#') && l.contains(" = "))
        .map(|(i, _)| i)
        .collect();
    let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    match rng.below(7) {
        0 | 1 => {
            let i = *rng.pick(&fields);
            let key = edited[i].split(" = ").next().unwrap().to_string();
            edited[i] = format!("{key} = {}", hostile_toml_value(rng));
        }
        2 => {
            // a second area named like an earlier one of its region, in another case
            let names: Vec<usize> = fields
                .iter()
                .copied()
                .filter(|&i| {
                    edited[i].trim_start().starts_with("name = ") && edited[i].starts_with("  ")
                })
                .collect();
            let i = *rng.pick(&names);
            if let Some(&j) = names.iter().find(|&&j| j > i && j < i + 8) {
                edited[j] = edited[i].to_uppercase().replace("NAME =", "name =");
            }
        }
        3 => {
            let i = *rng.pick(&fields);
            if edited[i].trim_start().starts_with("name = ") {
                edited[i] = edited[i].replacen("\"", "\"\\u202e\\t", 1);
            } else {
                edited[i] = format!("{}\n# {}", edited[i], "\u{feff}");
            }
        }
        4 => {
            let keys: Vec<usize> = fields
                .iter()
                .copied()
                .filter(|&i| edited[i].starts_with("key = "))
                .collect();
            let i = *rng.pick(&keys);
            let bad = [
                "\"a,b\"",
                "\"a\\nb\"",
                "\"a\\\"b\"",
                "\"\"",
                "\"chest\"",
                "\"Chest\"",
            ];
            edited[i] = format!("key = {}", rng.pick(&bad));
        }
        5 => {
            let text = edited.join("\n");
            let cut = rng.below(text.len());
            let mut cut_at = cut;
            while !text.is_char_boundary(cut_at) {
                cut_at -= 1;
            }
            return text.as_bytes()[..cut_at].to_vec();
        }
        _ => {
            let mut bytes = edited.join("\n").into_bytes();
            let at = rng.below(bytes.len());
            bytes[at] = 0xFF;
            return bytes;
        }
    }
    let mut text = edited.join("\n");
    text.push('\n');
    text.into_bytes()
}

/// The surfaces added since the last round, with a fixed seed: `safety` flags (the methods,
/// scenes and reports included), user body models (for `safety` and `safety-map`), `spin-up`
/// flags and drive descriptions for `strike FILE` with one field made hostile. Every case ends
/// with exit 0 and a finished answer, or exit 2 naming the flag or field; never a panic, an
/// abort, a hang, a null or NaN in the JSON, Debug text, a 300-digit number or a torn file.
#[test]
fn safety_body_models_spin_up_and_drive_files_hostile() {
    let mut failures = Vec::new();
    let mut cases = 0;
    let dir = scratch("new_surfaces");
    let mut rng = Rng(0x5EED_0036);
    let mut numbers = hostile_numbers();
    numbers.retain(|s| s.len() < 1000);
    numbers.extend(strings(&["1e-20", "1e40", "95.5", "0.5", "2"]));
    let check = |o: &Outcome, failures: &mut Vec<String>| {
        if let Some(d) = debug_text(&format!("{}\n{}", o.stdout, o.stderr)) {
            failures.push(format!("{}\n  -> Debug text: {d}", o.line));
        }
    };

    // safety: flags, methods, scenes and report paths
    let mut words = strings(&[
        "chest",
        "Chest",
        "hands_and_fingers",
        "face",
        "",
        "chest,abdomen",
        "Sternum",
        "\u{202e}x",
    ]);
    words.push("y".repeat(5000));
    let methods = strings(&[
        "standard,",
        ",",
        "standard,standard",
        "simulation",
        "energy,simulation",
        "",
        "Standard",
        "standard,,energy",
    ]);
    let scenes = strings(&[
        "driven_cj_free_head",
        "driven_cl_wall",
        "cj_aluminium",
        "nope",
        "",
        "/dev/null",
        ".",
    ]);
    let reports = strings(&[
        "r.md",
        "r.html",
        "r.txt",
        "my report#1.md",
        "sub/dir/r.md",
        ".",
        "/dev/null",
        "file.txt/r.md",
        "r.MD",
    ]);
    let mut flags: Vec<(&str, Vec<String>)> = [
        "--speed",
        "--k-c",
        "--n",
        "--k-delta",
        "--payload",
        "--moving-mass",
        "--length",
        "--tol",
        "--root-rtol",
        "--radius",
        "--contact-area",
        "--m-eff",
    ]
    .iter()
    .map(|f| (*f, numbers.clone()))
    .collect();
    flags.push(("--region", words.clone()));
    flags.push(("--area", words));
    flags.push(("--method", methods));
    flags.push(("--scene", scenes));
    flags.push(("--report", reports));
    flags.push((
        "--area-model",
        strings(&["hertz-sphere", "thin-layer", "fixed", "", "x"]),
    ));
    flags.push((
        "--contact",
        strings(&["transient", "quasi-static", "", "clamped"]),
    ));
    for case in 0..36 {
        let case_dir = dir.join(format!("s{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        std::fs::write(case_dir.join("file.txt"), "not a directory\n").unwrap();
        let base: &[&str] = if case % 2 == 0 {
            &["safety", "--region", "chest", "--m-eff", "3", "--json"]
        } else {
            &["safety", "--region", "chest", "--m-eff", "3"]
        };
        let (mut args, mut drawn) = draw(&mut rng, base, &borrow(&flags), None);
        if args.iter().any(|a| a.starts_with("--scene")) {
            // a scene is the design: the mass flag conflicts with it
            args.retain_flag_removed("--m-eff");
        }
        // the contact law and area models come with their partners
        drawn.extend(strings(&[
            "--m-eff",
            "--speed",
            "--n",
            "--k-c",
            "--radius",
            "--contact-area",
            "--area-model",
            "--gamma",
        ]));
        let names: Vec<&str> = drawn.iter().map(String::as_str).collect();
        let expect = Expect {
            allow_1: false,
            names: &names,
        };
        let o = attack(&args, &case_dir, Some(&case_dir), &expect, &mut failures);
        check(&o, &mut failures);
        cases += 1;
    }

    // body models, for safety and for the map over every region
    let bundled = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/safety/iso_ts_15066_2016.toml"),
    )
    .unwrap();
    for case in 0..24 {
        let case_dir = dir.join(format!("b{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        std::fs::write(
            case_dir.join("m.toml"),
            hostile_body_model(&mut rng, &bundled),
        )
        .unwrap();
        let args: Vec<String> = if case % 3 == 2 {
            strings(&[
                "safety-map",
                "--x",
                "region=all",
                "--y",
                "k-delta=1e3:1e6:2:log",
                "--m-r",
                "0.5",
                "--m-e",
                "0.1",
                "--method",
                "energy",
                "--body-model",
                "m.toml",
                "--out",
                "o",
                "--json",
            ])
        } else {
            strings(&[
                "safety",
                "--region",
                "chest",
                "--m-eff",
                "3",
                "--speed",
                "0.5",
                "--body-model",
                "m.toml",
                "--json",
            ])
        };
        let expect = Expect {
            allow_1: false,
            names: &["--body-model", "--region", "--area", "--x"],
        };
        let o = attack(&args, &case_dir, Some(&case_dir), &expect, &mut failures);
        check(&o, &mut failures);
        cases += 1;
    }

    // spin-up flags, on a short, coarse run
    let spin: Vec<(&str, Vec<String>)> = [
        "--omega-s",
        "--t-s",
        "--duration",
        "--elements",
        "--max-step",
        "--sample-every",
        "--modes",
        "--length",
        "--area",
        "--second-moment",
        "--youngs-modulus",
        "--density",
    ]
    .iter()
    .map(|f| (*f, numbers.clone()))
    .collect();
    for case in 0..16 {
        let case_dir = dir.join(format!("u{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let base = [
            "spin-up",
            "--t-s",
            "2",
            "--duration",
            "3",
            "--elements",
            "4",
            "--out",
            "o",
            "--json",
        ];
        let (args, drawn) = draw(&mut rng, &base, &borrow(&spin), None);
        let names: Vec<&str> = drawn.iter().map(String::as_str).collect();
        let expect = Expect {
            allow_1: false,
            names: &names,
        };
        let o = attack(&args, &case_dir, Some(&case_dir), &expect, &mut failures);
        check(&o, &mut failures);
        cases += 1;
    }

    // drive descriptions with one field made hostile
    let drive = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/drives/cl_free_head.toml"),
    )
    .unwrap();
    let fields = drive_value_lines(&drive);
    for case in 0..30 {
        let case_dir = dir.join(format!("d{case}"));
        std::fs::create_dir_all(&case_dir).unwrap();
        let (line, key) = rng.pick(&fields).clone();
        let value = hostile_toml_value(&mut rng);
        let text: Vec<String> = drive
            .lines()
            .enumerate()
            .map(|(i, l)| {
                if i == line {
                    format!("{key} = {value}")
                } else {
                    l.to_string()
                }
            })
            .collect();
        std::fs::write(case_dir.join("d.toml"), text.join("\n") + "\n").unwrap();
        let mut args = strings(&["strike", "d.toml"]);
        if case % 2 == 0 {
            args.push("--json".into());
        }
        // the field's key, or the table it sits in, or a field it makes unreachable
        let mut names = vec![key.clone()];
        names.extend(strings(&[
            "d.toml",
            "speed",
            "horizon_s",
            "placement",
            "person.contact",
            "torque_limit",
            "m_e",
            "link.",
            "drive.",
        ]));
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        let expect = Expect {
            allow_1: false,
            names: &names,
        };
        let o = attack(&args, &case_dir, Some(&case_dir), &expect, &mut failures);
        check(&o, &mut failures);
        cases += 1;
    }
    let _ = std::fs::remove_dir_all(&dir);
    report(
        "safety_body_models_spin_up_and_drive_files_hostile",
        cases,
        &failures,
    );
}
