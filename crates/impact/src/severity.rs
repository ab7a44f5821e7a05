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

use serde::Serialize;

use flexrig_safety::{ContactAreaModel, ContactTraces, Severity, severity};

use crate::ImpactError;

/// Intervals of the CJ's dense output over the contact when its traces are recorded.
pub const CJ_TRACE_SAMPLES: usize = 4000;

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
    /// pressure under both dome models of radius `dome_radius_m` \[m\]
    /// ([`ContactAreaModel::dome_models`]).
    pub fn severity(&self, m_h: f64, dome_radius_m: f64) -> Result<Severity, ImpactError> {
        let acceleration: Vec<f64> = self.force.iter().map(|f| f / m_h).collect();
        Ok(severity(
            &ContactTraces {
                times: &self.times,
                force: &self.force,
                indentation: &self.indentation,
                head_acceleration: Some(&acceleration),
            },
            &ContactAreaModel::dome_models(dome_radius_m),
        )?)
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
