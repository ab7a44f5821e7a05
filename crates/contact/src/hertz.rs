//! The Hertz contact law f = k_c δ_c^n (paper Eq. 4).

use serde::{Deserialize, Serialize};

use crate::{ContactError, ContactLaw, validate};

/// Largest Hertz exponent accepted. Physical fits lie in [1, 3] (paper §III-B: 1.817 … 2.002;
/// sphere on a half-space: 3/2); the solvers are tested on [0.5, 4].
pub const MAX_EXPONENT: f64 = 10.0;

/// Elastic Hertz contact, f = k δ^n for δ > 0 and 0 otherwise (paper Eq. 4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "HertzSpec", into = "HertzSpec")]
pub struct Hertz {
    k: f64,
    n: f64,
}

/// Serialised form of [`Hertz`], validated on the way in.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HertzSpec {
    /// Contact stiffness k_c [N/m^n].
    pub k: f64,
    /// Hertz exponent n [-].
    pub n: f64,
}

impl TryFrom<HertzSpec> for Hertz {
    type Error = ContactError;
    fn try_from(s: HertzSpec) -> Result<Self, Self::Error> {
        Hertz::new(s.k, s.n)
    }
}

impl From<Hertz> for HertzSpec {
    fn from(h: Hertz) -> Self {
        HertzSpec { k: h.k, n: h.n }
    }
}

impl Hertz {
    /// A Hertz law with stiffness `k` [N/m^n] > 0 and exponent `n` ∈ (0, 10].
    pub fn new(k: f64, n: f64) -> Result<Self, ContactError> {
        Self::named(k, n, "k_c", "n")
    }

    /// As [`Hertz::new`], naming the two fields `k_field` and `n_field` in errors.
    pub fn named(k: f64, n: f64, k_field: &str, n_field: &str) -> Result<Self, ContactError> {
        let k = validate::positive(k_field, k)?;
        let n = validate::in_left_open(n_field, n, 0.0, MAX_EXPONENT)?;
        Ok(Hertz { k, n })
    }

    /// Contact stiffness k_c [N/m^n].
    pub fn k(&self) -> f64 {
        self.k
    }

    /// Hertz exponent n [-].
    pub fn n(&self) -> f64 {
        self.n
    }

    /// Indentation at force f \[m\]: δ_c = (f/k_c)^{1/n} (paper Eq. 6); 0 for f ≤ 0.
    pub fn indentation(&self, f: f64) -> f64 {
        if f > 0.0 {
            (f / self.k).powf(1.0 / self.n)
        } else {
            0.0
        }
    }

    /// Stored energy at indentation δ \[J\]: k δ^{n+1}/(n+1); 0 for δ ≤ 0.
    pub fn energy(&self, delta: f64) -> f64 {
        if delta > 0.0 {
            self.k * delta.powf(self.n + 1.0) / (self.n + 1.0)
        } else {
            0.0
        }
    }

    /// Peak indentation \[m\] of an undamped impact of reduced mass μ \[kg\] at approach speed v0
    /// [m/s]: ½ μ v0² = k δ^{n+1}/(n+1).
    pub fn peak_indentation(&self, mu: f64, v0: f64) -> f64 {
        (0.5 * mu * v0 * v0 * (self.n + 1.0) / self.k).powf(1.0 / (self.n + 1.0))
    }
}

impl ContactLaw for Hertz {
    fn force(&self, delta: f64, _delta_dot: f64) -> f64 {
        if delta > 0.0 {
            self.k * delta.powf(self.n)
        } else {
            0.0
        }
    }

    /// k δ^n > 0 for δ ≥ 1e-20 and k ≥ 1e-100 without the power (n ≤ 10: δ^n ≥ 1e-200, the
    /// product ≥ 1e-300, far from underflow); the force itself decides below.
    fn pushes(&self, delta: f64, delta_dot: f64) -> bool {
        if delta >= 1e-20 && self.k >= 1e-100 {
            return true;
        }
        !(-self.force(delta, delta_dot) >= 0.0)
    }

    fn stiffness(&self, delta: f64, _delta_dot: f64) -> f64 {
        if delta > 0.0 {
            self.n * self.k * delta.powf(self.n - 1.0)
        } else {
            0.0
        }
    }

    /// k δ^n and n k δ^{n−1} from the one power δ^{n−1} (each within a few ulps of
    /// [`Self::force`] and [`Self::stiffness`]).
    fn force_and_stiffness(&self, delta: f64, _delta_dot: f64) -> (f64, f64) {
        if delta > 0.0 {
            let k_pow = self.k * delta.powf(self.n - 1.0);
            (k_pow * delta, self.n * k_pow)
        } else {
            (0.0, 0.0)
        }
    }

    fn elastic(&self) -> Hertz {
        *self
    }
}
