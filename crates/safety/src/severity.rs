//! One call for a run summary: every severity measure of a sampled contact.

use serde::Serialize;

use crate::SafetyError;
use crate::contact_area::{ContactAreaModel, peak_pressure};
use crate::energy::{loading_work, peak_force};
use crate::hic::{HicResult, HicWindow, hic};
use crate::trace::check_series;

/// Traces of one contact, sampled together from first contact.
#[derive(Debug, Clone, Copy)]
pub struct ContactTraces<'a> {
    /// Times \[s\], strictly increasing.
    pub times: &'a [f64],
    /// Contact force \[N\].
    pub force: &'a [f64],
    /// Contact indentation \[m\].
    pub indentation: &'a [f64],
    /// Resultant head acceleration [m/s²], when the struck body is a head.
    pub head_acceleration: Option<&'a [f64]>,
}

/// The severity measures of one contact.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Severity {
    /// Peak force \[N\].
    pub peak_force: f64,
    /// Time of the peak force \[s\].
    pub t_peak_force: f64,
    /// Largest mean contact pressure \[Pa\] with the given area model.
    pub peak_pressure: Option<f64>,
    /// Work of the force over the indentation up to its maximum \[J\].
    pub loading_work: f64,
    /// HIC15, when a head acceleration was given.
    pub hic15: Option<HicResult>,
    /// HIC36, when a head acceleration was given.
    pub hic36: Option<HicResult>,
}

/// Peak force, peak pressure (with `area`), loading work and HIC15/HIC36 of `traces`.
pub fn severity(
    traces: &ContactTraces<'_>,
    area: Option<&ContactAreaModel>,
) -> Result<Severity, SafetyError> {
    check_series("force", traces.times, traces.force)?;
    check_series("indentation", traces.times, traces.indentation)?;
    let (f_max, i_max) = peak_force(traces.force)?;
    let pressure = match area {
        Some(model) => Some(peak_pressure(traces.force, traces.indentation, model)?.0),
        None => None,
    };
    let (hic15, hic36) = match traces.head_acceleration {
        Some(a) => (
            Some(hic(traces.times, a, HicWindow::Hic15)?),
            Some(hic(traces.times, a, HicWindow::Hic36)?),
        ),
        None => (None, None),
    };
    Ok(Severity {
        peak_force: f_max,
        t_peak_force: traces.times[i_max],
        peak_pressure: pressure,
        loading_work: loading_work(traces.force, traces.indentation)?,
        hic15,
        hic36,
    })
}
