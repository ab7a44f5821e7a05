//! The closed-form solution for a linear contact (n = 1), paper Eq. 13.
//!
//! With n = 1 the series spring is linear, k_o = k_c k_δ/(k_c + k_δ), the relative motion is a
//! half sine of angular frequency ω = √(k_o/μ), and
//!
//! f_max = v0 √(k_o μ)  (Eq. 13),  t_peak = π/(2ω),  contact duration π/ω.

use crate::LumpedError;
use crate::model::{ImpactModel, Peak};

/// The n = 1 impact in closed form.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct AnalyticImpact {
    /// Peak state.
    pub peak: Peak,
    /// Overall stiffness k_o [N/m].
    pub k_o: f64,
    /// Time from first contact to the peak \[s\].
    pub t_peak: f64,
    /// Contact duration \[s\].
    pub contact_duration: f64,
}

/// Eq. 13; an error for n ≠ 1.
pub fn peak_analytic(model: &ImpactModel) -> Result<AnalyticImpact, LumpedError> {
    let spring = model.spring();
    let contact = spring.contact();
    if contact.n() != 1.0 {
        return Err(LumpedError::NotApplicable {
            method: "analytic",
            reason: format!(
                "the closed form (Eq. 13) needs a linear contact, n = 1, but n = {}; use the \
                 exact (energy) or ode method",
                contact.n()
            ),
        });
    }
    let k_o = contact.k() * spring.k_delta() / (contact.k() + spring.k_delta());
    let mu = model.reduced_mass();
    let omega = (k_o / mu).sqrt();
    let f_max = model.v0() * (k_o * mu).sqrt();
    Ok(AnalyticImpact {
        peak: Peak::at_force(spring, f_max),
        k_o,
        t_peak: 0.5 * std::f64::consts::PI / omega,
        contact_duration: std::f64::consts::PI / omega,
    })
}
