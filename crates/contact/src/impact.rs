//! The ADAMS-style IMPACT contact force with a cubic STEP damping ramp.
//!
//! ADAMS defines, for a marker distance x approaching a trigger distance x₁,
//! F = max(0, k (x₁ − x)^e − STEP(x, x₁ − d, c_max, x₁, 0) · ẋ) for x < x₁.
//! With the indentation δ = x₁ − x and its rate δ̇ = −ẋ this is
//! f = max(0, k δ^e + c(δ) δ̇), where the damping coefficient c(δ) rises from 0 at δ = 0 to
//! c_max at δ = d along the cubic STEP h₀ + (h₁ − h₀) Δ² (3 − 2Δ).

use crate::{ContactError, ContactLaw, Hertz, validate};

/// ADAMS's cubic STEP: h₀ for x ≤ x₀, h₁ for x ≥ x₁, and h₀ + (h₁ − h₀) Δ²(3 − 2Δ) with
/// Δ = (x − x₀)/(x₁ − x₀) in between.
pub fn cubic_step(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
    if x <= x0 {
        h0
    } else if x >= x1 {
        h1
    } else {
        let d = (x - x0) / (x1 - x0);
        h0 + (h1 - h0) * d * d * (3.0 - 2.0 * d)
    }
}

/// Derivative of [`cubic_step`] with respect to x.
pub fn cubic_step_slope(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
    if x <= x0 || x >= x1 {
        0.0
    } else {
        let d = (x - x0) / (x1 - x0);
        (h1 - h0) * 6.0 * d * (1.0 - d) / (x1 - x0)
    }
}

/// ADAMS IMPACT: f = max(0, k δ^e + STEP(δ, 0, 0, d, c_max) δ̇).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdamsImpact {
    elastic: Hertz,
    c_max: f64,
    depth: f64,
}

impl AdamsImpact {
    /// Stiffness `k` [N/m^e] > 0, exponent `exponent` ∈ (0, 10], maximum damping `c_max`
    /// [N·s/m] ≥ 0 reached at the penetration `depth` d \[m\] > 0.
    pub fn new(k: f64, exponent: f64, c_max: f64, depth: f64) -> Result<Self, ContactError> {
        Ok(AdamsImpact {
            elastic: Hertz::named(k, exponent, "k", "exponent")?,
            c_max: validate::non_negative("c_max", c_max)?,
            depth: validate::positive("depth", depth)?,
        })
    }

    /// Damping coefficient c(δ) [N·s/m] at indentation δ.
    pub fn damping_coefficient(&self, delta: f64) -> f64 {
        cubic_step(delta, 0.0, 0.0, self.depth, self.c_max)
    }
}

impl ContactLaw for AdamsImpact {
    fn force(&self, delta: f64, delta_dot: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        (self.elastic.force(delta, 0.0) + self.damping_coefficient(delta) * delta_dot).max(0.0)
    }

    fn stiffness(&self, delta: f64, delta_dot: f64) -> f64 {
        if self.force(delta, delta_dot) > 0.0 {
            self.elastic.stiffness(delta, 0.0)
                + cubic_step_slope(delta, 0.0, 0.0, self.depth, self.c_max) * delta_dot
        } else {
            0.0
        }
    }

    fn damping(&self, delta: f64, delta_dot: f64) -> f64 {
        if self.force(delta, delta_dot) > 0.0 {
            self.damping_coefficient(delta)
        } else {
            0.0
        }
    }

    fn elastic(&self) -> Hertz {
        self.elastic
    }
}
