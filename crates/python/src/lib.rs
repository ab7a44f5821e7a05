//! `flexrig._flexrig`: the native half of the `flexrig` Python package, over the flexrig library
//! (`flexrig` crate). The Python half (`python/flexrig/__init__.py`) turns these results into
//! NumPy arrays, pandas DataFrames and Dask tasks; the public API and its documentation live
//! there and in `_flexrig.pyi`.
//!
//! Every long computation runs with the GIL released; Ctrl-C stops it (see [`detached`]).

use std::time::Duration;

use flexrig::{CancelToken, Error, ErrorKind};
use flexrig_rig::RigError;
use pyo3::create_exception;
use pyo3::exceptions::{PyFileNotFoundError, PyKeyboardInterrupt, PyOSError, PyRuntimeError};
use pyo3::prelude::*;

mod arm;
mod convert;
mod driven;
mod eta;
mod experiment;
mod lumped;
mod run;
mod safety;
mod sweep;
mod tools;

create_exception!(
    flexrig,
    InputError,
    pyo3::exceptions::PyValueError,
    "Bad input (a scene field, an override, an argument): a ValueError whose message names the \
     field, the value and what is allowed; the attribute `field` holds the field's name \
     (e.g. `robot.payload_kg`, `m_h[3]`, `grid`)."
);
create_exception!(
    flexrig,
    SimulationError,
    PyRuntimeError,
    "A run that could not finish (unstable, or its stop condition not reached): the message \
     says why and what to change."
);

/// A ValueError (`InputError`) naming `field`.
pub(crate) fn input_error(field: &str, message: String) -> PyErr {
    let err = InputError::new_err(message);
    Python::attach(|py| {
        // the attribute is a convenience: the message names the field either way
        let _ = err.value(py).setattr("field", field);
    });
    err
}

/// The name of the field a library error is about, if it is bad input.
pub(crate) fn field_of(e: &Error) -> Option<String> {
    use flexrig_contact::ContactError;
    let contact = |c: &ContactError| match c {
        ContactError::InvalidParameter { field, .. } => Some(field.clone()),
        _ => None,
    };
    match e {
        Error::InvalidArgument { arg, .. } => Some(arg.clone()),
        Error::Rig(RigError::InvalidScene { field, .. }) => Some(field.clone()),
        Error::Rig(RigError::SceneSyntax(_)) => Some("scene".into()),
        Error::Rig(RigError::Contact(c)) | Error::Contact(c) => contact(c),
        Error::Lumped(flexrig_lumped::LumpedError::Parameter(c)) => contact(c),
        _ => None,
    }
}

/// A library error as the Python exception a caller expects: bad input → `InputError`
/// (a ValueError naming the field), a missing file → `FileNotFoundError`, other I/O → `OSError`,
/// an interrupted run → `KeyboardInterrupt`, a run that failed → `SimulationError`.
pub(crate) fn to_py(e: Error) -> PyErr {
    match e.kind() {
        ErrorKind::Io => match &e {
            Error::Read { path, source } => {
                let message = format!("cannot read {}: {source}", path.display());
                if source.kind() == std::io::ErrorKind::NotFound {
                    PyFileNotFoundError::new_err(message)
                } else {
                    PyOSError::new_err(message)
                }
            }
            _ => PyOSError::new_err(e.to_string()),
        },
        ErrorKind::Interrupted => PyKeyboardInterrupt::new_err(e.to_string()),
        ErrorKind::Input => {
            let field = field_of(&e).unwrap_or_default();
            input_error(&field, e.to_string())
        }
        ErrorKind::Failed => SimulationError::new_err(e.to_string()),
    }
}

/// A library error that names command-line flags (`--c-max`), as the Python exception with the
/// keyword arguments in their place (`c_max`, also its `field`); other errors as [`to_py`].
pub(crate) fn flag_error(e: Error) -> PyErr {
    if e.kind() != ErrorKind::Input {
        return to_py(e);
    }
    let field = field_of(&e).map(|f| keywords(&f));
    let message = keywords(&e.to_string());
    let field = field
        .filter(|f| !f.is_empty())
        .or_else(|| first_keyword(&e.to_string()))
        .unwrap_or_default();
    input_error(&field, message)
}

/// `text` with each flag `--some-flag` written as the keyword argument `some_flag`.
pub(crate) fn keywords(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find("--") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let len = after
            .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
            .unwrap_or(after.len());
        if len > 0 && after.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str(&after[..len].replace('-', "_"));
        } else {
            out.push_str("--");
            out.push_str(&after[..len]);
        }
        rest = &after[len..];
    }
    out.push_str(rest);
    out
}

/// Each of a report's `warnings` with the flags it names (`--m-r`) written as the keyword
/// arguments (`m_r`), in its field and its message: the names a Python caller gave the values
/// by. A file's fields (`link.m_r`) stay as they are.
pub(crate) fn keyword_warnings(warnings: &mut [flexrig::safety::measured::Warning]) {
    for w in warnings {
        w.field = keywords(&w.field);
        w.message = keywords(&w.message);
    }
}

/// [`keyword_warnings`] for the beam's plausibility warnings (`beam_modal`, `beam_static`).
pub(crate) fn keyword_beam_warnings(warnings: &mut [flexrig::fe::beam::Warning]) {
    for w in warnings {
        w.field = keywords(&w.field);
        w.message = keywords(&w.message);
    }
}

/// The keyword argument of the first flag `text` names.
fn first_keyword(text: &str) -> Option<String> {
    let i = text.find("--")?;
    let after = &text[i + 2..];
    let len = after
        .find(|c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '-'))
        .unwrap_or(after.len());
    (len > 0).then(|| after[..len].replace('-', "_"))
}

/// Runs `work` with the GIL released, watching for Ctrl-C: the calling (main) thread checks
/// Python's signals every 50 ms while a scoped thread works; on a signal it cancels `cancel`
/// (which the work watches and stops on) and returns the signal's exception once the work ended.
pub(crate) fn detached<T: Send>(
    py: Python<'_>,
    cancel: &CancelToken,
    work: impl FnOnce() -> T + Send,
) -> PyResult<T> {
    let (result, signal) = py.detach(|| {
        std::thread::scope(|scope| {
            let (done_tx, done_rx) = std::sync::mpsc::channel::<()>();
            let handle = scope.spawn(move || {
                let result = work();
                let _ = done_tx.send(());
                result
            });
            let mut signal = None;
            loop {
                match done_rx.recv_timeout(Duration::from_millis(50)) {
                    Ok(()) | Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break,
                    Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                        if signal.is_none()
                            && let Err(e) = Python::attach(|py| py.check_signals())
                        {
                            cancel.cancel();
                            signal = Some(e);
                        }
                    }
                }
            }
            let result = match handle.join() {
                Ok(r) => r,
                Err(panic) => std::panic::resume_unwind(panic),
            };
            (result, signal)
        })
    });
    match signal {
        Some(e) => Err(e),
        None => Ok(result),
    }
}

/// The native module.
#[pymodule]
fn _flexrig(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("SimulationError", py.get_type::<SimulationError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(run::scene_text, m)?)?;
    m.add_function(wrap_pyfunction!(run::bundled_scenes, m)?)?;
    m.add_function(wrap_pyfunction!(run::scene_descriptions, m)?)?;
    m.add_function(wrap_pyfunction!(run::write_scene, m)?)?;
    m.add_function(wrap_pyfunction!(run::apply_overrides, m)?)?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(lumped::impact_exact, m)?)?;
    m.add_function(wrap_pyfunction!(lumped::impact_report, m)?)?;
    m.add_function(wrap_pyfunction!(lumped::fig6, m)?)?;
    m.add_function(wrap_pyfunction!(eta::eta, m)?)?;
    m.add_function(wrap_pyfunction!(eta::eta_map, m)?)?;
    m.add_function(wrap_pyfunction!(eta::eta_rotor, m)?)?;
    m.add_function(wrap_pyfunction!(experiment::experiment, m)?)?;
    m.add_function(wrap_pyfunction!(experiment::payload, m)?)?;
    m.add_function(wrap_pyfunction!(tools::fit, m)?)?;
    m.add_function(wrap_pyfunction!(tools::beam_modal, m)?)?;
    m.add_function(wrap_pyfunction!(tools::beam_static, m)?)?;
    m.add_function(wrap_pyfunction!(tools::prb, m)?)?;
    m.add_function(wrap_pyfunction!(tools::validate, m)?)?;
    m.add_function(wrap_pyfunction!(tools::bench, m)?)?;
    m.add_function(wrap_pyfunction!(safety::safety_json, m)?)?;
    m.add_function(wrap_pyfunction!(arm::arm_json, m)?)?;
    m.add_function(wrap_pyfunction!(safety::safety_map_json, m)?)?;
    m.add_function(wrap_pyfunction!(safety::safety_trace_json, m)?)?;
    m.add_function(wrap_pyfunction!(safety::parse_area, m)?)?;
    m.add_function(wrap_pyfunction!(driven::spin_up, m)?)?;
    m.add_function(wrap_pyfunction!(driven::strike, m)?)?;
    m.add_function(wrap_pyfunction!(driven::strike_flags, m)?)?;
    m.add_function(wrap_pyfunction!(driven::strike_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(driven::spin_up_defaults, m)?)?;
    m.add_function(wrap_pyfunction!(driven::role_switch, m)?)?;
    m.add_class::<sweep::Sweep>()?;
    m.add("DEFAULT_RTOL", flexrig::lumped::impact::DEFAULT_RTOL)?;
    m.add(
        "SUMMARY_COLUMNS",
        flexrig::study::sweep::SUMMARY_COLUMNS.to_vec(),
    )?;
    m.add(
        "INTEGER_SUMMARY_COLUMNS",
        flexrig::study::sweep::INTEGER_COLUMNS.to_vec(),
    )?;
    m.add("LINK_COLUMNS", flexrig::testbed::link::COLUMNS.to_vec())?;
    Ok(())
}
