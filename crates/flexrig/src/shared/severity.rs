//! Severity measures of every run, by one function: flexrig-safety's
//! [`flexrig_safety::severity`] applied to the run's force, indentation and struck-body
//! acceleration traces (see `docs/safety.md`).
//!
//! - **Test bed** (`flexrig run`, experiments, sweeps, Python runs): [`of_samples`] over the
//!   sensor samples, filled into [`crate::testbed::run::RunSummary::severity`] by every run. The struck
//!   body is the operator block; its acceleration is the virtual operator accelerometer.
//! - **Driven strike** (`flexrig run` on a scene with `[drive]`, its sweeps and Python runs):
//!   [`of_driven`] over the driven run's trace inside the contact (the scene's
//!   `record.sample_rate_hz`; the CJ's samples between its integrator's steps from the
//!   method's interpolant); the struck body is the person's head, its acceleration
//!   (f − neck force)/m_h; against a wall the head does not move and has no HIC.
//! - **Lumped impact** (`flexrig impact --method ode`): [`of_lumped`] over the integrator's
//!   dense output sampled uniformly ([`LUMPED_TRACE_SAMPLES`] intervals over the contact); the
//!   struck body is the head of mass m_h, its acceleration f/m_h.
//!
//! Pressure is reported, for a skin's law with a contact geometry (n > 1), under both dome
//! contact-area models
//! ([`ContactAreaModel::dome_models`]: Hertz sphere A = πRδ, the default; thin layer on a rigid
//! backing A = π(2Rδ − δ²)); HIC15/HIC36 are exact for the piecewise-linear interpolant of the
//! samples ([`HIC_METHOD`]).

use flexrig_contact::Materials;
use flexrig_lumped::ImpactModel;
use flexrig_lumped::ode::{Formulation, OdeOptions, integrate};
use flexrig_safety::{ContactTraces, severity};

pub use flexrig_rig::severity::of_samples;
pub use flexrig_safety::{
    ContactAreaModel, HIC_METHOD, HicSeverity, PressureSeverity, STANDARD_GRAVITY, Severity,
};

use crate::Error;

/// Intervals of the uniform sampling of the lumped impact's dense output over the contact:
/// the HIC of the linear interpolant of a half-sine then differs from the pulse's by about
/// (π/N)²/12 ≈ 5e-8 relative.
pub const LUMPED_TRACE_SAMPLES: usize = 4000;

/// The dome radius \[m\] of the paper's fits (the bundled materials' `dome_radius_m`), the
/// default contact geometry of the lumped impact.
pub fn paper_dome_radius_m() -> Result<f64, Error> {
    Ok(Materials::bundled()?.dome_radius_m())
}

/// Severity of the lumped impact `model` (from contact to separation): integrated at relative
/// tolerance `rtol` with `formulation`, its dense output sampled every contact duration /
/// [`LUMPED_TRACE_SAMPLES`]; head acceleration f/m_h; contact area of a dome of radius
/// `dome_radius_m` \[m\] under both models when the contact law has a geometry (n > 1; a
/// linear contact reports no pressure, [`ContactAreaModel::dome_models_for_exponent`]).
pub fn of_lumped(
    model: &ImpactModel,
    rtol: f64,
    formulation: Formulation,
    dome_radius_m: f64,
) -> Result<Severity, Error> {
    let options = OdeOptions::new(rtol)?.formulation(formulation);
    let first = integrate(model, &options)?;
    // stopped at separation: the duration is there
    let duration = first.contact_duration.unwrap_or(2.0 * first.t_peak);
    let traced = integrate(
        model,
        &options.trace_interval(duration / LUMPED_TRACE_SAMPLES as f64)?,
    )?;
    let column = |f: fn(&flexrig_lumped::ode::TracePoint) -> f64| {
        traced.trace.iter().map(f).collect::<Vec<f64>>()
    };
    let times = column(|p| p.t);
    let force = column(|p| p.force);
    let indentation = column(|p| p.indentation);
    let inv_m_h = 1.0 / model.m_h();
    let acceleration: Vec<f64> = force.iter().map(|f| f * inv_m_h).collect();
    Ok(severity(
        &ContactTraces {
            times: &times,
            force: &force,
            indentation: &indentation,
            head_acceleration: Some(&acceleration),
        },
        &ContactAreaModel::dome_models_for_exponent(dome_radius_m, model.spring().contact().n()),
    )?)
}

/// Severity of a driven strike's contact from its trace: `times` \[s\], contact `force` \[N\],
/// `indentation` \[m\] and the head's acceleration \[m/s²\] (`None`: a head against a wall,
/// which does not move: no acceleration, no HIC), the samples with t in
/// [`onset_s`, `end_s`] (the trace holds the onset and the separation); contact area of a dome
/// of radius `dome_radius_m` \[m\] under both models for a skin's law of exponent `n` > 1 (none
/// for n ≤ 1: [`ContactAreaModel::dome_models_for_exponent`]). A negative indentation
/// (round-off at the onset and the separation) counts as 0.
pub fn of_driven(
    times: &[f64],
    force: &[f64],
    indentation: &[f64],
    head_acceleration: Option<&[f64]>,
    (onset_s, end_s): (f64, f64),
    dome_radius_m: f64,
    n: f64,
) -> Result<Severity, Error> {
    let inside: Vec<usize> = (0..times.len())
        .filter(|&i| times[i] >= onset_s && times[i] <= end_s)
        .collect();
    let pick = |v: &[f64], f: fn(f64) -> f64| inside.iter().map(|&i| f(v[i])).collect::<Vec<f64>>();
    let t = pick(times, |x| x);
    let f = pick(force, |x| x.max(0.0));
    let d = pick(indentation, |x| x.max(0.0));
    let a = head_acceleration.map(|a| pick(a, f64::abs));
    Ok(severity(
        &ContactTraces {
            times: &t,
            force: &f,
            indentation: &d,
            head_acceleration: a.as_deref(),
        },
        &ContactAreaModel::dome_models_for_exponent(dome_radius_m, n),
    )?)
}

/// The severity columns of tables (sweeps, experiments), units in the names: peak force \[N\],
/// peak pressure under the Hertz sphere and the thin layer \[Pa\] (the peak of each model's
/// distribution), energy transferred and net contact work \[J\], peak struck-body acceleration
/// [m/s² and g], HIC15 and HIC36.
pub const SEVERITY_COLUMNS: [&str; 9] = [
    "severity_peak_force_n",
    "peak_pressure_hertz_pa",
    "peak_pressure_thin_layer_pa",
    "energy_transferred_j",
    "contact_work_j",
    "peak_accel_mps2",
    "peak_accel_g",
    "hic15",
    "hic36",
];

/// The values of [`SEVERITY_COLUMNS`] (absent: `None`, e.g. without a severity).
pub fn severity_values(s: Option<&Severity>) -> [Option<f64>; 9] {
    let Some(s) = s else {
        return [None; 9];
    };
    let pressure = |model: ContactAreaModel| s.pressure_of(&model).map(|p| p.peak_pa);
    [
        Some(s.peak_force_n),
        pressure(ContactAreaModel::HertzSphere { radius_m: 1.0 }),
        pressure(ContactAreaModel::ThinLayer { radius_m: 1.0 }),
        Some(s.energy_transferred_j),
        Some(s.contact_work_j),
        s.peak_acceleration_mps2,
        s.peak_acceleration_g,
        s.hic15.map(|h| h.hic),
        s.hic36.map(|h| h.hic),
    ]
}

/// The severity of the FE CJ and CL impacts (flexrig-impact's), for the tables of `flexrig eta`,
/// `eta-map` and `eta-rotor`.
pub use flexrig_impact::severity::PairSeverity;

/// The severity columns of the FE impact tables, each leading comma included: the
/// [`SEVERITY_COLUMNS`] of the CJ (`cj_…`), then of the CL (`cl_…`).
pub fn pair_header() -> String {
    ["cj", "cl"]
        .iter()
        .flat_map(|design| {
            SEVERITY_COLUMNS
                .iter()
                .map(move |c| format!(",{design}_{c}"))
        })
        .collect()
}

/// The cells of [`pair_header`] (empty without a severity), each leading comma included.
pub fn pair_cells(pair: Option<&PairSeverity>) -> String {
    let cells = |s: Option<&Severity>| -> String {
        severity_values(s)
            .iter()
            .map(|v| v.map_or(",".to_string(), |v| format!(",{v}")))
            .collect()
    };
    cells(pair.map(|p| &p.cj)) + &cells(pair.map(|p| &p.cl))
}
