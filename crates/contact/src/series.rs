//! Series compliance of the link and the contact (paper Eq. 6–9).
//!
//! A massless lateral link spring k_δ in series with the Hertz contact f = k_c δ_c^n carries the
//! same force f. The total displacement is
//!
//! δ(f) = δ_l + δ_c = f/k_δ + (f/k_c)^{1/n}          (Eq. 6–8)
//!
//! and the overall (secant) stiffness k_o = f/δ (Eq. 9). Both inverse problems — the force at a
//! given total displacement, and the force at which the stored energy
//! U(f) = f²/(2k_δ) + f δ_c/(n + 1) equals a given energy — are solved by Newton's method in
//! s = ln f. In that variable both ln δ(e^s) and ln U(e^s) are log-sum-exp functions of affine
//! functions of s, hence convex and increasing; Newton started right of the root (at the smaller
//! of the two single-spring solutions, each an upper bound) therefore decreases monotonically
//! onto the root with quadratic convergence, for any exponent n > 0 and any ratio k_δ/k_c. The
//! iterate is nevertheless kept inside the bracket [lower bound, upper bound] and bisected
//! (geometrically) if rounding ever pushed it out.

use serde::{Deserialize, Serialize};

use crate::{ContactError, Hertz, validate};

/// Iteration cap of the Newton solves (a safeguard; typical counts are 2–6).
const MAX_NEWTON_ITERATIONS: usize = 60;

/// Convergence threshold on the Newton step in ln f.
const LOG_STEP_TOL: f64 = 4.0 * f64::EPSILON;

/// A lateral link spring k_δ in series with a Hertz contact (paper Fig. 5d).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SeriesCompliance {
    k_delta: f64,
    contact: Hertz,
}

/// Result of a force solve, with its cost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ForceSolve {
    /// The force f \[N\].
    pub force: f64,
    /// Newton iterations used (0 for a closed form).
    pub iterations: usize,
}

impl SeriesCompliance {
    /// Link lateral stiffness `k_delta` [N/m] > 0 in series with `contact`.
    pub fn new(k_delta: f64, contact: Hertz) -> Result<Self, ContactError> {
        Ok(SeriesCompliance {
            k_delta: validate::positive("k_delta", k_delta)?,
            contact,
        })
    }

    /// Link lateral stiffness k_δ [N/m].
    pub fn k_delta(&self) -> f64 {
        self.k_delta
    }

    /// The contact law.
    pub fn contact(&self) -> Hertz {
        self.contact
    }

    /// Link deflection δ_l = f/k_δ \[m\] (Eq. 7).
    pub fn link_deflection(&self, f: f64) -> f64 {
        f.max(0.0) / self.k_delta
    }

    /// Contact indentation δ_c = (f/k_c)^{1/n} \[m\] (Eq. 6).
    pub fn indentation(&self, f: f64) -> f64 {
        self.contact.indentation(f)
    }

    /// Total displacement δ = δ_l + δ_c \[m\] at force f \[N\] (Eq. 8).
    pub fn displacement(&self, f: f64) -> f64 {
        self.link_deflection(f) + self.indentation(f)
    }

    /// Tangent compliance dδ/df = 1/k_δ + δ_c/(n f) [m/N]; for f → 0 it tends to 1/k_δ (n < 1),
    /// 1/k_δ + 1/k_c (n = 1) or +∞ (n > 1).
    pub fn compliance(&self, f: f64) -> f64 {
        let n = self.contact.n();
        if f > 0.0 {
            1.0 / self.k_delta + self.indentation(f) / (n * f)
        } else if n < 1.0 {
            1.0 / self.k_delta
        } else if n == 1.0 {
            1.0 / self.k_delta + 1.0 / self.contact.k()
        } else {
            f64::INFINITY
        }
    }

    /// Overall secant stiffness k_o = f/δ = f k_δ/(f + k_δ (f/k_c)^{1/n}) [N/m] (Eq. 9), at
    /// force f > 0.
    pub fn overall_stiffness(&self, f: f64) -> f64 {
        f / self.displacement(f)
    }

    /// Stored strain energy U(f) = f²/(2k_δ) + f δ_c/(n + 1) \[J\] at force f \[N\].
    pub fn energy(&self, f: f64) -> f64 {
        if f <= 0.0 {
            return 0.0;
        }
        0.5 * f * f / self.k_delta + f * self.indentation(f) / (self.contact.n() + 1.0)
    }

    /// dU/df = f/k_δ + δ_c/n [J/N].
    pub fn energy_slope(&self, f: f64) -> f64 {
        if f <= 0.0 {
            return 0.0;
        }
        f / self.k_delta + self.indentation(f) / self.contact.n()
    }

    /// Force f \[N\] at total displacement δ \[m\]: the root of δ(f) = δ (0 for δ ≤ 0). Closed form
    /// f = k_o δ, k_o = k_c k_δ/(k_c + k_δ), for n = 1.
    pub fn force(&self, delta: f64) -> f64 {
        self.solve_force(delta).force
    }

    /// As [`SeriesCompliance::force`], also reporting the Newton iterations.
    pub fn solve_force(&self, delta: f64) -> ForceSolve {
        if delta.is_nan() || delta <= 0.0 {
            return ForceSolve {
                force: 0.0,
                iterations: 0,
            };
        }
        if self.contact.n() == 1.0 {
            let k_o = self.contact.k() * self.k_delta / (self.contact.k() + self.k_delta);
            return ForceSolve {
                force: k_o * delta,
                iterations: 0,
            };
        }
        self.force_by_newton(delta)
    }

    /// Newton's method in ln f on ln δ(f) = ln δ (any n, no closed-form shortcut).
    pub(crate) fn force_by_newton(&self, delta: f64) -> ForceSolve {
        let (k_d, k_c, n) = (self.k_delta, self.contact.k(), self.contact.n());
        let upper = (k_d * delta).min(k_c * delta.powf(n));
        let lower = (0.5 * k_d * delta).min(k_c * (0.5 * delta).powf(n));
        let residual = |f: f64| {
            let dl = f / k_d;
            let dc = (f / k_c).powf(1.0 / n);
            let total = dl + dc;
            // g(s) = ln(δ(f)/δ) and g'(s) = f δ'(f)/δ(f).
            (((total - delta) / delta).ln_1p(), (dl + dc / n) / total)
        };
        newton_in_log(upper, lower, residual)
    }

    /// Upper bound \[N\] on the force at which the stored energy reaches `energy` \[J\]: the smaller
    /// of the two single-spring solutions √(2 E k_δ) and ((n + 1) E)^{n/(n+1)} k_c^{1/(n+1)}
    /// (U exceeds each of its two parts). The true force is at least the bound at E/2.
    pub fn force_bound_at_energy(&self, energy: f64) -> f64 {
        let (k_d, k_c, n) = (self.k_delta, self.contact.k(), self.contact.n());
        let f_link = (2.0 * energy * k_d).sqrt();
        let f_contact = (energy * (n + 1.0)).powf(n / (n + 1.0)) * k_c.powf(1.0 / (n + 1.0));
        f_link.min(f_contact)
    }

    /// Force f \[N\] at which the stored energy U(f) equals `energy` \[J\] ≥ 0 — the peak force of an
    /// undamped impact with kinetic energy `energy` (see flexrig-lumped). No closed-form shortcut
    /// for n = 1 (that one is checked against it).
    pub fn force_at_energy(&self, energy: f64) -> ForceSolve {
        if energy.is_nan() || energy <= 0.0 {
            return ForceSolve {
                force: 0.0,
                iterations: 0,
            };
        }
        let (k_d, k_c, n) = (self.k_delta, self.contact.k(), self.contact.n());
        let upper = self.force_bound_at_energy(energy);
        // At the root one part holds at least half the energy.
        let lower = self.force_bound_at_energy(0.5 * energy);
        let residual = |f: f64| {
            let ul = 0.5 * f * f / k_d;
            let dc = (f / k_c).powf(1.0 / n);
            let uc = f * dc / (n + 1.0);
            let u = ul + uc;
            // h(s) = ln(U/E), h'(s) = f U'(f)/U.
            (
                ((u - energy) / energy).ln_1p(),
                (f * f / k_d + f * dc / n) / u,
            )
        };
        newton_in_log(upper, lower, residual)
    }
}

/// Newton's method on a convex increasing function of s = ln f, started at `upper` (right of the
/// root), kept inside [lower, upper]. `residual(f)` returns (h, dh/ds).
fn newton_in_log(upper: f64, lower: f64, residual: impl Fn(f64) -> (f64, f64)) -> ForceSolve {
    let (mut lo, mut hi) = (lower.ln(), upper.ln());
    let mut s = hi;
    for iteration in 1..=MAX_NEWTON_ITERATIONS {
        let (h, slope) = residual(s.exp());
        if h == 0.0 {
            return ForceSolve {
                force: s.exp(),
                iterations: iteration,
            };
        }
        if h > 0.0 {
            hi = hi.min(s);
        } else {
            lo = lo.max(s);
        }
        let step = h / slope;
        if step.abs() <= LOG_STEP_TOL * s.abs().max(1.0) {
            return ForceSolve {
                force: (s - step).exp(),
                iterations: iteration,
            };
        }
        let next = s - step;
        s = if next >= lo && next <= hi && next.is_finite() {
            next
        } else {
            0.5 * (lo + hi)
        };
    }
    ForceSolve {
        force: s.exp(),
        iterations: MAX_NEWTON_ITERATIONS,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tolerance::assert_close;

    #[test]
    fn newton_path_matches_closed_form_for_n_equal_1() {
        for ratio in [1e-8, 1e-3, 1.0, 1e3, 1e8] {
            let s = SeriesCompliance::new(1e6 * ratio, Hertz::new(1e6, 1.0).unwrap()).unwrap();
            for delta in [1e-9, 1e-5, 1e-2, 1.0] {
                let newton = s.force_by_newton(delta);
                assert_close("f(δ) Newton vs k_o δ", newton.force, s.force(delta), 2e-15);
                assert!(newton.iterations <= 8, "{} iterations", newton.iterations);
            }
        }
    }
}
