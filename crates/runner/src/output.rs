//! Output helpers: files are written completely or not at all (a temporary file in the same
//! directory, renamed into place), and JSON goes to the report writer.

use std::io::Write;
use std::path::{Path, PathBuf};

use crate::CliError;

/// Creates `dir` (and parents) if needed.
pub fn ensure_dir(dir: &Path) -> Result<(), CliError> {
    std::fs::create_dir_all(dir).map_err(|e| CliError::write(dir, e))
}

/// Writes `bytes` to `path` atomically: a half-written file is never left at `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), CliError> {
    let tmp = temporary_sibling(path);
    let result = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(CliError::write(path, e));
    }
    Ok(())
}

/// A hidden temporary name beside `path` (same directory, so a rename is atomic).
pub(crate) fn temporary_sibling(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Reads an input text file; an error names the file (exit code 2).
pub fn read_text(path: &Path) -> Result<String, CliError> {
    std::fs::read_to_string(path).map_err(|source| CliError::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// Writes `value` as pretty JSON and a newline to the report.
pub fn print_json(out: &mut dyn Write, value: &serde_json::Value) -> Result<(), CliError> {
    let text = serde_json::to_string_pretty(value).expect("a serde_json::Value always serialises");
    writeln!(out, "{text}").map_err(|e| CliError::write("<stdout>", e))
}

/// Writes one line of text to the report.
pub fn line(out: &mut dyn Write, text: impl std::fmt::Display) -> Result<(), CliError> {
    writeln!(out, "{text}").map_err(|e| CliError::write("<stdout>", e))
}

/// A command-line number that must be finite and > 0 (the error names the flag).
pub fn positive_arg(flag: &str, value: f64) -> Result<f64, CliError> {
    Ok(flexrig_contact::validate::positive(flag, value)?)
}

/// A command-line number that must be finite and ≥ 0 (the error names the flag).
pub fn non_negative_arg(flag: &str, value: f64) -> Result<f64, CliError> {
    Ok(flexrig_contact::validate::non_negative(flag, value)?)
}

/// A command-line number that must lie in the physical range [lo, hi] (the error names the flag,
/// the value and the range).
pub fn range_arg(flag: &str, value: f64, lo: f64, hi: f64) -> Result<f64, CliError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(CliError::InvalidArgument {
            arg: flag.into(),
            value: flexrig_contact::validate::display(value),
            allowed: format!("must lie in [{lo:e}, {hi:e}]"),
        })
    }
}

/// Refuses a result that is not a finite number: the computation left double precision for
/// these arguments (the error says which quantity and what to change).
pub fn finite_result(what: &str, value: f64, advice: &str) -> Result<f64, CliError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(CliError::NonFinite {
            what: what.into(),
            value: format!("{value}"),
            advice: advice.into(),
        })
    }
}
