//! The severity of a test-bed run from its sensor samples (flexrig-safety's [`severity`], the
//! one function every front uses).
//!
//! The struck body is the operator pendulum's block (the human side: its skin is the contact's
//! compliant layer). Its acceleration is the **virtual operator accelerometer**, magnitude of
//! the component along the strike direction: in contact the mean acceleration of the block over
//! each integration step (the change of its velocity over the step divided by the step), out
//! of contact the exact acceleration of the free swing. That is the acceleration the run's log
//! records on `/sensors/accel/operator`, so the summary can be recomputed from the log; the
//! component normal to the strike (the centripetal l φ̇², below 1 % of the contact's) is left
//! out. Force and indentation are the force sensor and the contact indentation at the same
//! sample times; the contact area is the dome of the scene (`robot.dome_radius_m`) under
//! [`ContactAreaModel::dome_models`] (Hertz sphere, thin layer).

use flexrig_safety::{ContactAreaModel, ContactTraces, SafetyError, Severity, severity};

use crate::sensors::SensorSample;

/// Severity of the samples of one run (every contact; HIC over the whole trace), with the
/// dome of radius `dome_radius_m` \[m\]. Computed over [`carrying`] the samples: the same
/// measures as over every sample, without the work of a long approach at rest.
pub fn of_samples(samples: &[SensorSample], dome_radius_m: f64) -> Result<Severity, SafetyError> {
    let samples = carrying(samples);
    let column = |f: fn(&SensorSample) -> f64| samples.iter().map(f).collect::<Vec<f64>>();
    let times = column(|s| s.t);
    let force = column(|s| s.force_n);
    let indentation = column(|s| s.indentation_m);
    let acceleration = column(|s| s.operator_accel_mps2.abs());
    severity(
        &ContactTraces {
            times: &times,
            force: &force,
            indentation: &indentation,
            head_acceleration: Some(&acceleration),
        },
        &ContactAreaModel::dome_models(dome_radius_m),
    )
}

/// The samples that carry the severity: from the last sample before the first with a force, an
/// indentation or an acceleration (any not exactly 0) to the first after the last such sample;
/// every sample when no sample has both a force and an indentation (a run without contact).
///
/// The traces are piecewise linear between samples, so the samples left out (force,
/// indentation and acceleration all exactly 0 outside the kept stretch, e.g. a block hanging
/// at rest while a drive swings the link for seconds) add nothing to any measure: the peaks
/// and their times are positive values inside the stretch, the work sums add exact zeros, and
/// a HIC window reaching into them has the integral of its part inside over a longer time (a
/// smaller HIC). The kept zero sample at each end keeps the first and last ramps of the
/// interpolants.
pub fn carrying(samples: &[SensorSample]) -> &[SensorSample] {
    let live = |s: &SensorSample| {
        s.force_n != 0.0 || s.indentation_m != 0.0 || s.operator_accel_mps2 != 0.0
    };
    let contact = samples
        .iter()
        .any(|s| s.force_n > 0.0 && s.indentation_m > 0.0);
    match (
        contact,
        samples.iter().position(live),
        samples.iter().rposition(live),
    ) {
        (true, Some(first), Some(last)) => {
            &samples[first.saturating_sub(1)..(last + 2).min(samples.len())]
        }
        _ => samples,
    }
}
