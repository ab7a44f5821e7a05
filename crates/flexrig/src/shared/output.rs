//! File helpers: files are written completely or not at all (a temporary file in the same
//! directory, renamed into place); input files are read with errors that name them; and the
//! range checks of arguments (errors name the field).

use std::path::{Path, PathBuf};

use crate::Error;

/// Creates `dir` (and parents) if needed.
pub fn ensure_dir(dir: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(dir).map_err(|e| match e.kind() {
        // a file where a directory must be: the user's path, not a failure of the machine
        std::io::ErrorKind::NotADirectory | std::io::ErrorKind::AlreadyExists => {
            Error::InvalidArgument {
                arg: "--out".into(),
                value: dir.display().to_string(),
                allowed: format!("must be a directory or a path where one can be made ({e})"),
            }
        }
        _ => Error::write(dir, e),
    })
}

/// Refuses an output path that names something other than a regular file or nothing: a
/// directory, a symbolic link, a device or a pipe (replacing it with a regular file, or writing
/// into a device, is never what was meant). The error names `--out` (exit code 2).
pub fn check_output_target(path: &Path) -> Result<(), Error> {
    let Ok(meta) = std::fs::symlink_metadata(path) else {
        return Ok(());
    };
    let what = if meta.is_dir() {
        "a directory: give a file name inside it"
    } else if meta.file_type().is_symlink() {
        "a symbolic link: flexrig replaces only regular files; give the file it points to, or \
         another name"
    } else if !meta.is_file() {
        "a device, pipe or socket: flexrig writes regular files only; give another name"
    } else {
        return Ok(());
    };
    Err(Error::InvalidArgument {
        arg: "--out".into(),
        value: path.display().to_string(),
        allowed: format!("is {what}"),
    })
}

/// A number as a message quotes it: plain for ordinary magnitudes, in exponent form for very
/// small or large ones (1e300, not 301 digits).
pub use flexrig_contact::validate::display as display_number;

/// A value as a message quotes it: a number written by Rust's `{}` (which prints 1e300 with 301
/// digits) through [`display_number`], any other text as it is.
pub fn value_text(value: impl ToString) -> String {
    let text = value.to_string();
    match text.parse::<f64>() {
        Ok(v) if text.len() > 12 => display_number(v),
        _ => text,
    }
}

/// Writes `bytes` to `path` atomically: a half-written file is never left at `path`; a path
/// that is not a regular file is refused ([`check_output_target`]).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    check_output_target(path)?;
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
    let bytes = std::fs::read(path).map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })?;
    utf8_text(path, bytes)
}

/// `bytes` of `path` as text; bytes that are not UTF-8 are an error naming the file, the line,
/// the byte offset and the byte.
fn utf8_text(path: &Path, bytes: Vec<u8>) -> Result<String, Error> {
    String::from_utf8(bytes).map_err(|e| {
        let at = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        let line = bytes[..at].iter().filter(|&&b| b == b'\n').count() + 1;
        let column = at
            - bytes[..at]
                .iter()
                .rposition(|&b| b == b'\n')
                .map_or(0, |i| i + 1)
            + 1;
        Error::Read {
            path: path.to_path_buf(),
            source: std::io::Error::other(format!(
                "not UTF-8 text: line {line}, column {column} (byte offset {at}) holds the byte \
                 0x{:02X}; save the file as UTF-8",
                bytes[at]
            )),
        }
    })
}

/// Reads a text file of at most `max_bytes` (a value list, not a stream: `/dev/zero` or a huge
/// file is refused once the bound is passed, without reading the rest); an error names the file.
pub fn read_text_limited(path: &Path, max_bytes: u64) -> Result<String, Error> {
    read_text_bounded(path, max_bytes, "a list of values is expected")
}

/// [`read_text_limited`] for a file that is `expected` (said in the error when it is too long).
pub fn read_text_bounded(path: &Path, max_bytes: u64, expected: &str) -> Result<String, Error> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let mut bytes = Vec::new();
    file.take(max_bytes + 1)
        .read_to_end(&mut bytes)
        .map_err(|source| Error::Read {
            path: path.to_path_buf(),
            source,
        })?;
    if bytes.len() as u64 > max_bytes {
        return Err(Error::Read {
            path: path.to_path_buf(),
            source: std::io::Error::other(format!("longer than {max_bytes} bytes ({expected})")),
        });
    }
    utf8_text(path, bytes)
}

/// A command-line number that must be finite and > 0 (the error names the flag).
pub fn positive_arg(flag: &str, value: f64) -> Result<f64, Error> {
    Ok(flexrig_contact::validate::positive(flag, value)?)
}

/// A command-line number that must be finite and ≥ 0 (the error names the flag).
pub fn non_negative_arg(flag: &str, value: f64) -> Result<f64, Error> {
    Ok(flexrig_contact::validate::non_negative(flag, value)?)
}

/// A command-line number in `unit` ("" for a ratio) that must lie in the physical range
/// [lo, hi] (the error names the flag, the value, the range with its unit and, for a length,
/// mass or modulus that looks given in mm, g or GPa/MPa, the conversion).
pub fn range_arg(flag: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<f64, Error> {
    use flexrig_contact::validate::{display, interval_in, unit_hint_in};
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(Error::InvalidArgument {
            arg: flag.into(),
            value: display(value),
            allowed: format!(
                "{}{}",
                interval_in(unit, lo, hi),
                unit_hint_in(unit, value, lo, hi)
            ),
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
