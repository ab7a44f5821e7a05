//! Severity of the FE impacts: the CJ and CL runs of `flexrig eta`, `eta-map` and `eta-rotor`
//! record their contact's force and indentation, and [`flexrig_safety::severity`] (the one
//! function behind every run's severity) turns them into peak force, peak pressure under the
//! dome's contact-area models, energy transferred, peak head acceleration and HIC15/HIC36.
//!
//! **Struck body.** The free head of mass m_h: its acceleration is f/m_h (no other force acts
//! on it), so its trace is the force trace over m_h.
//!
//! **Samples.** The CJ (DOP853) is run twice: once to find the contact duration T, then with
//! its 8th-order dense output sampled every T/[`CJ_TRACE_SAMPLES`] (HIC of the linear interpolant
//! of a half-sine so sampled differs from the pulse's by about (π/N)²/12 ≈ 5e-8 relative, the
//! same rule as the lumped impact). The modal CL records the force at every step: its scheme
//! holds the force linear between steps, so the samples *are* the force the run used (their
//! interpolant deviates from a smooth force by at most `tol` × the peak per step). The
//! generalized-α CL records every step (h = the payload's contact time / `steps_per_contact`).
//!
//! **Bounded work.** The exact HIC search grows faster than the number of samples, and a run at
//! a tight tolerance takes millions of steps; a trace longer than [`MAX_SEVERITY_SAMPLES`] is
//! therefore read on a uniform grid of that many intervals over the contact (its piecewise-linear
//! interpolant evaluated there), with the samples of the largest force and of the deepest
//! indentation kept exactly, so the peaks are the run's own. For a pulse resolved by n grid
//! intervals the HIC of the grid differs by about (π/n)²/12 relative: 5e-8 for a half-sine.

use serde::Serialize;

use flexrig_safety::{ContactAreaModel, ContactTraces, Severity, severity};

use crate::ImpactError;

/// Intervals of the CJ's dense output over the contact when its traces are recorded.
pub const CJ_TRACE_SAMPLES: usize = 4000;

/// Most samples a trace hands to the severity; a longer one is read on a uniform grid (module
/// documentation, "Bounded work").
pub const MAX_SEVERITY_SAMPLES: usize = 4096;

/// The force and indentation of a contact, sampled together (times strictly increasing).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ContactTrace {
    /// Times from the onset \[s\].
    pub times: Vec<f64>,
    /// Contact force \[N\].
    pub force: Vec<f64>,
    /// Indentation \[m\] (≤ 0 outside contact).
    pub indentation: Vec<f64>,
}

impl ContactTrace {
    /// Appends a sample; one at or before the last time is dropped (times stay increasing).
    pub fn push(&mut self, t: f64, force: f64, indentation: f64) {
        if self.times.last().is_some_and(|&last| t <= last) {
            return;
        }
        self.times.push(t);
        self.force.push(force);
        self.indentation.push(indentation);
    }

    /// The severity of this contact with a free head of mass `m_h` \[kg\] (acceleration f/m_h),
    /// pressure under both dome models of radius `dome_radius_m` \[m\] for a contact law of
    /// exponent `n` > 1, none for n ≤ 1 (a spring without a contact geometry:
    /// [`ContactAreaModel::dome_models_for_exponent`]).
    pub fn severity(&self, m_h: f64, dome_radius_m: f64, n: f64) -> Result<Severity, ImpactError> {
        let bounded;
        let trace = if self.times.len() > MAX_SEVERITY_SAMPLES + 1 {
            bounded = self.on_uniform_grid(MAX_SEVERITY_SAMPLES);
            &bounded
        } else {
            self
        };
        let acceleration: Vec<f64> = trace.force.iter().map(|f| f / m_h).collect();
        Ok(severity(
            &ContactTraces {
                times: &trace.times,
                force: &trace.force,
                indentation: &trace.indentation,
                head_acceleration: Some(&acceleration),
            },
            &ContactAreaModel::dome_models_for_exponent(dome_radius_m, n),
        )?)
    }
}

impl ContactTrace {
    /// The piecewise-linear trace read at `intervals` + 1 evenly spaced times from its first to
    /// its last sample, with the samples of the largest force and of the deepest indentation
    /// kept exactly (times stay strictly increasing).
    fn on_uniform_grid(&self, intervals: usize) -> ContactTrace {
        let n = self.times.len();
        let argmax =
            |v: &[f64]| (0..v.len()).fold(0, |best, i| if v[i] > v[best] { i } else { best });
        let mut keep = [argmax(&self.force), argmax(&self.indentation)];
        keep.sort_unstable();
        let (t0, t1) = (self.times[0], self.times[n - 1]);
        let mut out = ContactTrace::default();
        let mut seg = 0;
        let mut kept = 0;
        for k in 0..=intervals {
            let t = if k == intervals {
                t1
            } else {
                t0 + (t1 - t0) * k as f64 / intervals as f64
            };
            while kept < keep.len() && self.times[keep[kept]] <= t {
                let i = keep[kept];
                out.push(self.times[i], self.force[i], self.indentation[i]);
                kept += 1;
            }
            while seg + 2 < n && self.times[seg + 1] <= t {
                seg += 1;
            }
            let (ta, tb) = (self.times[seg], self.times[seg + 1]);
            let w = ((t - ta) / (tb - ta)).clamp(0.0, 1.0);
            let lerp = |v: &[f64]| v[seg] + w * (v[seg + 1] - v[seg]);
            out.push(t, lerp(&self.force), lerp(&self.indentation));
        }
        out
    }
}

/// The severity of the CJ and the CL impact of one design (first contact).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PairSeverity {
    /// The compliant joint's.
    pub cj: Severity,
    /// The compliant link's.
    pub cl: Severity,
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrig_safety::{HicWindow, hic_half_sine};

    /// A half-sine force pulse sampled far more finely than the bound: read on the bounded grid,
    /// its HIC stays within 1e-6 of the closed form and its peak force is the sampled peak.
    #[test]
    fn a_trace_longer_than_the_bound_keeps_the_half_sine_hic_and_its_peak() {
        let (f_max, duration, m_h) = (2000.0, 4e-3, 4.0);
        let n = 20 * MAX_SEVERITY_SAMPLES + 7;
        let mut trace = ContactTrace::default();
        for k in 0..=n {
            let t = duration * k as f64 / n as f64;
            let f = f_max * (std::f64::consts::PI * t / duration).sin();
            trace.push(t, f.max(0.0), 1e-3 * f.max(0.0) / f_max);
        }
        let grid = trace.on_uniform_grid(MAX_SEVERITY_SAMPLES);
        assert!(grid.times.len() <= MAX_SEVERITY_SAMPLES + 3);
        assert!(grid.times.windows(2).all(|w| w[1] > w[0]));
        let s = trace.severity(m_h, 0.0715, 2.0).unwrap();
        let sampled_peak = trace.force.iter().cloned().fold(0.0, f64::max);
        assert_eq!(s.peak_force_n, sampled_peak);
        for (window, got) in [(HicWindow::Hic15, &s.hic15), (HicWindow::Hic36, &s.hic36)] {
            let exact = hic_half_sine(f_max / m_h, duration, window).unwrap();
            let got = got.as_ref().unwrap().hic;
            assert!((got - exact).abs() <= 1e-6 * exact, "{got} vs {exact}");
        }
    }
}
