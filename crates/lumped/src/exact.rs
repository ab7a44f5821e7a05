//! The exact peak force of the two-mass impact for any Hertz exponent, by energy.
//!
//! The relative motion μ δ̈ = −f(δ) is conservative, so at maximum compression (δ̇ = 0) the whole
//! relative kinetic energy is stored in the link spring and the contact:
//!
//! ½ μ v0² = U(f_max),  U(f) = f²/(2k_δ) + f δ_c/(n + 1),  δ_c = (f/k_c)^{1/n}.
//!
//! U is strictly increasing, so this scalar equation has exactly one root; it is solved to
//! round-off by the convex Newton iteration of
//! [`SeriesCompliance::force_at_energy`](flexrig_contact::SeriesCompliance::force_at_energy).
//! The paper (§IV–V) states that no explicit formulation exists for n ≠ 1 and integrates the ODE
//! instead; for the peak alone this equation is exact. For n = 1 it reduces to Eq. 13.

use crate::model::{ImpactModel, Peak};

/// Peak state of the impact from the energy balance (any n).
pub fn peak_exact(model: &ImpactModel) -> Peak {
    let solve = model.spring().force_at_energy(model.impact_energy());
    Peak::at_force(model.spring(), solve.force)
}
