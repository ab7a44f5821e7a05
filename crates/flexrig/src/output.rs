//! File helpers: files are written completely or not at all (a temporary file in the same
//! directory, renamed into place); input files are read with errors that name them; and the
//! range checks of arguments (errors name the field).

use std::path::{Path, PathBuf};

use crate::Error;

/// Creates `dir` (and parents) if needed.
pub fn ensure_dir(dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| Error::write(dir, e))
}

/// Writes `bytes` to `path` atomically: a half-written file is never left at `path`.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    let tmp = temporary_sibling(path);
    let result = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(Error::write(path, e));
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
pub fn read_text(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path).map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })
}

/// A command-line number that must be finite and > 0 (the error names the flag).
pub fn positive_arg(flag: &str, value: f64) -> Result<f64, Error> {
    Ok(flexrig_contact::validate::positive(flag, value)?)
}

/// A command-line number that must be finite and ≥ 0 (the error names the flag).
pub fn non_negative_arg(flag: &str, value: f64) -> Result<f64, Error> {
    Ok(flexrig_contact::validate::non_negative(flag, value)?)
}

/// A command-line number that must lie in the physical range [lo, hi] (the error names the flag,
/// the value and the range).
pub fn range_arg(flag: &str, value: f64, lo: f64, hi: f64) -> Result<f64, Error> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(Error::InvalidArgument {
            arg: flag.into(),
            value: flexrig_contact::validate::display(value),
            allowed: format!("must lie in [{lo:e}, {hi:e}]"),
        })
    }
}

/// Refuses a result that is not a finite number: the computation left double precision for
/// these arguments (the error says which quantity and what to change).
pub fn finite_result(what: &str, value: f64, advice: &str) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::NonFinite {
            what: what.into(),
            value: format!("{value}"),
            advice: advice.into(),
        })
    }
}
