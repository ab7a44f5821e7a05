//! One call for a run summary: every severity measure of a sampled contact.
//!
//! [`severity`] is the one function every front uses (the test bed's runs, the lumped and FE
//! impacts, sweeps, logs): peak force, peak contact pressure under each contact-area model it
//! is given, the energy transferred, the peak acceleration of the struck body and its HIC15 and
//! HIC36 (exact for the piecewise-linear interpolant of the samples, [`crate::hic`]).

use serde::Serialize;

use crate::SafetyError;
use crate::contact_area::{ContactAreaModel, peak_pressure};
use crate::energy::{loading_work, peak_force};
use crate::hic::{HicResult, HicWindow, STANDARD_GRAVITY, hic};
use crate::trace::{check_paired, check_series};

/// How HIC is computed from the samples (for reports and logs).
pub const HIC_METHOD: &str = "exact maximum over all windows of the piecewise-linear \
                              interpolant of the sampled acceleration";

/// Traces of one contact, sampled together.
#[derive(Debug, Clone, Copy)]
pub struct ContactTraces<'a> {
    /// Times \[s\], strictly increasing.
    pub times: &'a [f64],
    /// Contact force \[N\].
    pub force: &'a [f64],
    /// Contact indentation \[m\].
    pub indentation: &'a [f64],
    /// Resultant acceleration of the struck body (the head) [m/s², ≥ 0], when known.
    pub head_acceleration: Option<&'a [f64]>,
}

/// The largest contact pressure under one contact-area model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PressureSeverity {
    /// The contact-area model.
    pub area_model: ContactAreaModel,
    /// Largest mean pressure f/A(δ) over the contact \[Pa\].
    pub mean_pa: f64,
    /// Its peak: the mean × the model's peak factor (3/2 Hertz, 2 thin layer, 1 fixed) \[Pa\].
    pub peak_pa: f64,
    /// Time of the largest mean pressure \[s\].
    pub time_s: f64,
}

/// HIC over one window limit, with the maximising window.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HicSeverity {
    /// HIC (s·g^2.5, conventionally quoted without unit).
    pub hic: f64,
    /// Window start \[s\].
    pub t1_s: f64,
    /// Window end \[s\].
    pub t2_s: f64,
    /// Mean acceleration over the window [g₀ = 9.80665 m/s²].
    pub mean_acceleration_g: f64,
}

impl From<HicResult> for HicSeverity {
    fn from(r: HicResult) -> Self {
        HicSeverity {
            hic: r.hic,
            t1_s: r.t1,
            t2_s: r.t2,
            mean_acceleration_g: r.mean_acceleration_g,
        }
    }
}

/// The severity measures of one contact (SI units; absent keys in JSON when not computed).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Severity {
    /// Peak contact force \[N\] (largest sample).
    pub peak_force_n: f64,
    /// Time of the peak force \[s\].
    pub time_of_peak_force_s: f64,
    /// Peak contact pressure under each contact-area model asked for, in that order.
    pub pressure: Vec<PressureSeverity>,
    /// Energy transferred to the struck body's contact: the work of the contact force over the
    /// indentation up to its maximum, ∫₀^{δ_max} f dδ \[J\] (what the skin stores at maximum
    /// compression; ½ μ v0² for a rigid free two-body impact).
    pub energy_transferred_j: f64,
    /// Net work of the contact force over the whole trace, ∮ f dδ \[J\]: the energy the contact
    /// dissipated (0 for an elastic contact that separated; ½ μ v0² (1 − e²) for a lumped impact
    /// with restitution e).
    pub contact_work_j: f64,
    /// Largest acceleration of the struck body [m/s²], when its acceleration was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_acceleration_mps2: Option<f64>,
    /// The same in g₀ = 9.80665 m/s².
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_acceleration_g: Option<f64>,
    /// HIC15 (window ≤ 15 ms), when the struck body's acceleration was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hic15: Option<HicSeverity>,
    /// HIC36 (window ≤ 36 ms), when the struck body's acceleration was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hic36: Option<HicSeverity>,
}

impl Severity {
    /// The peak pressure under the model of `kind`'s variant (e.g. any
    /// [`ContactAreaModel::HertzSphere`]), if it was asked for.
    pub fn pressure_of(&self, kind: &ContactAreaModel) -> Option<&PressureSeverity> {
        self.pressure
            .iter()
            .find(|p| std::mem::discriminant(&p.area_model) == std::mem::discriminant(kind))
    }
}

/// Net work of the force over the indentation across the whole trace, ∑ ½(f_i + f_{i−1})
/// (δ_i − δ_{i−1}) \[J\] (trapezoidal rule).
pub fn contact_work(force: &[f64], indentation: &[f64]) -> Result<f64, SafetyError> {
    check_paired("force", force, "indentation", indentation)?;
    Ok((1..force.len())
        .map(|i| 0.5 * (force[i] + force[i - 1]) * (indentation[i] - indentation[i - 1]))
        .sum())
}

/// Every severity measure of `traces`: peak force, peak pressure under each of `areas`, energy
/// transferred (loading work) and net contact work, and, with a head acceleration, its peak and
/// HIC15/HIC36 ([`HIC_METHOD`]).
pub fn severity(
    traces: &ContactTraces<'_>,
    areas: &[ContactAreaModel],
) -> Result<Severity, SafetyError> {
    check_series("force", traces.times, traces.force)?;
    check_series("indentation", traces.times, traces.indentation)?;
    let (f_max, i_max) = peak_force(traces.force)?;
    let pressure = areas
        .iter()
        .map(|model| {
            let (mean, i) = peak_pressure(traces.force, traces.indentation, model)?;
            Ok(PressureSeverity {
                area_model: *model,
                mean_pa: mean,
                peak_pa: mean * model.peak_factor(),
                time_s: traces.times[i],
            })
        })
        .collect::<Result<Vec<_>, SafetyError>>()?;
    let (peak_a, hic15, hic36) = match traces.head_acceleration {
        Some(a) => {
            check_series("head acceleration", traces.times, a)?;
            let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            (
                Some(peak),
                Some(hic(traces.times, a, HicWindow::Hic15)?.into()),
                Some(hic(traces.times, a, HicWindow::Hic36)?.into()),
            )
        }
        None => (None, None, None),
    };
    Ok(Severity {
        peak_force_n: f_max,
        time_of_peak_force_s: traces.times[i_max],
        pressure,
        energy_transferred_j: loading_work(traces.force, traces.indentation)?,
        contact_work_j: contact_work(traces.force, traces.indentation)?,
        peak_acceleration_mps2: peak_a,
        peak_acceleration_g: peak_a.map(|a| a / STANDARD_GRAVITY),
        hic15,
        hic36,
    })
}
