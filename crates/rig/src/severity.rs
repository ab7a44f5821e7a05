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

#[cfg(test)]
mod tests {
    use super::*;

    /// A sample at `t` with force `f`, indentation `d` and acceleration `a`.
    fn sample(t: f64, f: f64, d: f64, a: f64) -> SensorSample {
        SensorSample {
            t,
            operator_angle_rad: 0.0,
            robot_angle_rad: 0.0,
            link_tip_deflection_m: 0.0,
            operator_accel_mps2: a,
            load_accel_mps2: 0.0,
            force_n: f,
            indentation_m: d,
        }
    }

    /// The severity of every sample, by flexrig-safety on the whole trace.
    fn of_every(samples: &[SensorSample], dome: f64) -> Severity {
        let column = |f: fn(&SensorSample) -> f64| samples.iter().map(f).collect::<Vec<f64>>();
        let (times, force, indentation) = (
            column(|s| s.t),
            column(|s| s.force_n),
            column(|s| s.indentation_m),
        );
        let acceleration = column(|s| s.operator_accel_mps2.abs());
        severity(
            &ContactTraces {
                times: &times,
                force: &force,
                indentation: &indentation,
                head_acceleration: Some(&acceleration),
            },
            &ContactAreaModel::dome_models(dome),
        )
        .unwrap()
    }

    /// Zeros, a half-sine contact with its acceleration, zeros, then a swing's acceleration
    /// without contact: the kept stretch is the contact's and the swing's with a zero at the
    /// start, and its severity is every sample's; a trace without contact is kept whole (its
    /// peaks sit at the first sample).
    #[test]
    fn the_carrying_samples_give_the_severity_of_every_sample() {
        let h = 1e-4;
        let mut trace: Vec<SensorSample> = (0..1000)
            .map(|k| {
                let t = k as f64 * h;
                let s = if (400..450).contains(&k) {
                    (std::f64::consts::PI * (k - 400) as f64 / 50.0).sin()
                } else {
                    0.0
                };
                let swing = if k >= 600 { 0.3 * (t * 7.0).sin() } else { 0.0 };
                sample(t, 90.0 * s, 1e-3 * s, -200.0 * s + swing)
            })
            .collect();
        let kept = carrying(&trace);
        assert_eq!((kept[0].t, kept.len()), (trace[400].t, 600));
        assert_eq!(of_samples(&trace, 0.07).unwrap(), of_every(&trace, 0.07));
        for s in &mut trace {
            (s.force_n, s.indentation_m, s.operator_accel_mps2) = (0.0, 0.0, 0.0);
        }
        assert_eq!(carrying(&trace).len(), trace.len());
        assert_eq!(of_samples(&trace, 0.07).unwrap(), of_every(&trace, 0.07));
    }
}
