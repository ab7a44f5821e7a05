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

use flexrig_safety::{
    ContactAreaModel, ContactTraces, STANDARD_GRAVITY, SafetyError, Severity, severity,
};

use crate::sensors::{Sampler, SensorSample};

/// The longest HIC window \[s\] (HIC36).
const LONGEST_WINDOW: f64 = 0.036;

/// Severity of the samples of one run (every contact; HIC over the whole trace), with the
/// dome of radius `dome_radius_m` \[m\].
///
/// Computed over the **contact stretches** ([`stretches`]: the samples with a force or an
/// indentation, one sample more at each end, stretches closer than the longest HIC window
/// joined) when that provably gives every measure of the whole trace ([`of_parts`]); over
/// [`carrying`] the samples otherwise. The peaks, their times and the work sums are those of
/// every sample exactly (outside the stretches force and indentation are exactly 0: they add
/// exact zeros); the peak acceleration and HIC are the whole trace's maxima by the bound of
/// [`of_parts`], computed on the stretches' samples alone — so a run that never computes its
/// free swing's samples ([`of_sampler`]) gets the same numbers, bit for bit.
pub fn of_samples(samples: &[SensorSample], dome_radius_m: f64) -> Result<Severity, SafetyError> {
    let parts = stretches(samples.len(), |k| samples[k], samples.iter().map(is_live));
    if !parts.is_empty() {
        let inside = |k: usize| parts.iter().any(|r| r.contains(&k));
        let outside = (0..samples.len())
            .filter(|&k| !inside(k))
            .fold(0.0f64, |m, k| m.max(samples[k].operator_accel_mps2.abs()));
        let slices: Vec<&[SensorSample]> = parts.iter().map(|r| &samples[r.clone()]).collect();
        if let Some(result) = of_parts(&slices, outside, dome_radius_m) {
            return result;
        }
    }
    of_every(carrying(samples), dome_radius_m)
}

/// [`of_samples`] of every sample a (lean) sampler took, computing only the deferred samples
/// the contact stretches need: the same result, bit for bit. Outside the stretches the
/// deferred samples' acceleration is bounded by their spans' bounds; when the bound does not
/// settle it, every sample is computed.
pub fn of_sampler(sampler: &Sampler, dome_radius_m: f64) -> Result<Severity, SafetyError> {
    if !sampler.is_lean() || sampler.deferred().is_empty() {
        let all = sampler.materialize();
        return of_samples(&all, dome_radius_m);
    }
    let total = sampler.count() as usize;
    // Every live sample is computed (a deferred span is a free swing: no force, no
    // indentation); the live flags by index.
    let mut live = vec![false; total];
    for (k, s) in sampler.computed() {
        if is_live(s) {
            live[k as usize] = true;
        }
    }
    // Below the count, an index without a sample (a step that skipped one) leaves the
    // positions of the samples unknown without computing them all: the full computation.
    let spans = sampler.deferred();
    let in_span = |k: u64| spans.iter().any(|d| d.first <= k && k < d.end);
    let covered = spans.iter().map(|d| d.end - d.first).sum::<u64>()
        + sampler.computed().filter(|(k, _)| !in_span(*k)).count() as u64;
    if covered != sampler.count() {
        return of_samples(&sampler.materialize(), dome_radius_m);
    }
    let at = |k: usize| {
        sampler
            .sample_at(k as u64)
            .expect("every index below the count holds a sample (checked)")
    };
    let parts = stretches(total, at, live.iter().copied());
    if !parts.is_empty() {
        let inside = |k: usize| parts.iter().any(|r| r.contains(&k));
        let mut outside = 0.0f64;
        for (k, s) in sampler.computed() {
            if !inside(k as usize) {
                outside = outside.max(s.operator_accel_mps2.abs());
            }
        }
        for span in sampler.deferred() {
            outside = outside.max(span.operator_accel_bound);
        }
        let owned: Vec<Vec<SensorSample>> =
            parts.iter().map(|r| r.clone().map(at).collect()).collect();
        let slices: Vec<&[SensorSample]> = owned.iter().map(Vec::as_slice).collect();
        if let Some(result) = of_parts(&slices, outside, dome_radius_m) {
            return result;
        }
    }
    of_samples(&sampler.materialize(), dome_radius_m)
}

fn is_live(s: &SensorSample) -> bool {
    s.force_n != 0.0 || s.indentation_m != 0.0
}

/// The contact stretches of `n` samples (`at` a sample by index, `live` whether each has a
/// force or an indentation): each run of live samples with one sample more at each end, runs
/// whose stretches are less than the longest HIC window apart (36 ms) joined with every sample
/// between. Empty when no sample is live.
pub fn stretches(
    n: usize,
    at: impl Fn(usize) -> SensorSample,
    live: impl Iterator<Item = bool>,
) -> Vec<std::ops::Range<usize>> {
    let mut parts: Vec<std::ops::Range<usize>> = Vec::new();
    let mut run: Option<(usize, usize)> = None;
    let close = |parts: &mut Vec<std::ops::Range<usize>>, (a, b): (usize, usize)| {
        let r = a.saturating_sub(1)..(b + 2).min(n);
        match parts.last_mut() {
            Some(last)
                if r.start <= last.end
                    || at(r.start).t - at(last.end - 1).t <= LONGEST_WINDOW * (1.0 + 1e-9) =>
            {
                last.end = r.end;
            }
            _ => parts.push(r),
        }
    };
    for (k, l) in live.enumerate() {
        run = match (run, l) {
            (None, true) => Some((k, k)),
            (Some((a, _)), true) => Some((a, k)),
            (Some(r), false) => {
                close(&mut parts, r);
                None
            }
            (None, false) => None,
        };
    }
    if let Some(r) = run {
        close(&mut parts, r);
    }
    parts
}

/// The severity over the contact stretches `parts` (in time order, each with its end
/// samples), when that is the whole trace's: `outside` \[m/s²\] bounds |acceleration| at every
/// sample outside them. `None` when the bound does not settle it.
///
/// The parts are joined into one trace. Force, indentation and their sums are exact (zeros
/// outside). The largest |acceleration| is the whole trace's when it is at least `outside`.
/// HIC: with A = max(`outside`, the parts' end samples' |a|), a window with an end outside
/// the parts (or between two of them, where the joined trace is a line between end samples)
/// and mean acceleration m ≥ A/0.6 only gains by moving that end into the part
/// (∂ ln HIC/∂t₁ = 1.5/Δ − 2.5 a(t₁)/I ≥ 0 while a(t₁) ≤ 0.6 m, and the mean does not drop on
/// the way); one with m < A/0.6 has HIC < Δ_max (A/0.6)^2.5. So when the parts' HIC is at
/// least that, it is the whole trace's (and parts more than Δ_max apart share no window).
pub fn of_parts(
    parts: &[&[SensorSample]],
    outside: f64,
    dome_radius_m: f64,
) -> Option<Result<Severity, SafetyError>> {
    let joined: Vec<SensorSample> = parts.iter().flat_map(|p| p.iter().copied()).collect();
    let ends = parts
        .iter()
        .flat_map(|p| [p.first(), p.last()])
        .flatten()
        .fold(0.0f64, |m, s| m.max(s.operator_accel_mps2.abs()));
    let bound = outside.max(ends);
    let severity = match of_every(&joined, dome_radius_m) {
        Ok(s) => s,
        Err(e) => return Some(Err(e)),
    };
    if !(severity.peak_acceleration_mps2? >= outside) {
        return None;
    }
    let a = bound / STANDARD_GRAVITY / 0.6;
    for (hic, window) in [(&severity.hic15, 0.015), (&severity.hic36, LONGEST_WINDOW)] {
        let floor = window * a * a * a.sqrt();
        if !(hic.as_ref()?.hic > floor * (1.0 + 1e-9)) {
            return None;
        }
    }
    Some(Ok(severity))
}

/// flexrig-safety's severity of every one of `samples`.
fn of_every(samples: &[SensorSample], dome_radius_m: f64) -> Result<Severity, SafetyError> {
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
