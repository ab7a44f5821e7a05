//! Hertz contact with nonlinear damping, f = k δ^n (1 + χ δ̇), and χ set from a coefficient of
//! restitution by the Hunt–Crossley or the Lankarani–Nikravesh formula.
//!
//! References: K. H. Hunt, F. R. E. Crossley, "Coefficient of restitution interpreted as damping
//! in vibroimpact", J. Appl. Mech. 42 (1975); H. M. Lankarani, P. E. Nikravesh, "A contact force
//! model with hysteresis damping for impact analysis of multibody systems", J. Mech. Des. 112
//! (1990). Both closed forms are derived for e close to 1; for low e they do not reproduce the
//! target restitution (see the tests in flexrig-lumped for the measured restitution).

use serde::{Deserialize, Serialize};

use crate::{ContactError, ContactLaw, Hertz, validate};

/// How the damping factor χ was chosen.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DampingModel {
    /// χ given directly.
    Explicit,
    /// Hunt–Crossley: χ = 3(1 − e)/(2 v0).
    HuntCrossley,
    /// Lankarani–Nikravesh: χ = 3(1 − e²)/(4 v0).
    LankaraniNikravesh,
}

/// Damped Hertz contact f = max(0, k δ^n (1 + χ δ̇)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DampedHertz {
    elastic: Hertz,
    chi: f64,
    model: DampingModel,
}

impl DampedHertz {
    /// Damped Hertz with an explicit damping factor χ [s/m] ≥ 0.
    pub fn new(elastic: Hertz, chi: f64) -> Result<Self, ContactError> {
        let chi = validate::non_negative("chi", chi)?;
        Ok(DampedHertz {
            elastic,
            chi,
            model: DampingModel::Explicit,
        })
    }

    /// Hunt–Crossley: χ = 3(1 − e)/(2 v0), restitution e ∈ [0, 1], impact speed v0 [m/s] > 0.
    pub fn hunt_crossley(elastic: Hertz, e: f64, v0: f64) -> Result<Self, ContactError> {
        let (e, v0) = Self::check_restitution(e, v0)?;
        Ok(DampedHertz {
            elastic,
            chi: 3.0 * (1.0 - e) / (2.0 * v0),
            model: DampingModel::HuntCrossley,
        })
    }

    /// Lankarani–Nikravesh: χ = 3(1 − e²)/(4 v0), restitution e ∈ [0, 1], impact speed
    /// v0 [m/s] > 0.
    pub fn lankarani_nikravesh(elastic: Hertz, e: f64, v0: f64) -> Result<Self, ContactError> {
        let (e, v0) = Self::check_restitution(e, v0)?;
        Ok(DampedHertz {
            elastic,
            chi: 3.0 * (1.0 - e * e) / (4.0 * v0),
            model: DampingModel::LankaraniNikravesh,
        })
    }

    fn check_restitution(e: f64, v0: f64) -> Result<(f64, f64), ContactError> {
        Ok((
            validate::in_closed("restitution", e, 0.0, 1.0)?,
            validate::positive("v0", v0)?,
        ))
    }

    /// Damping factor χ [s/m].
    pub fn chi(&self) -> f64 {
        self.chi
    }

    /// How χ was set.
    pub fn model(&self) -> DampingModel {
        self.model
    }
}

impl ContactLaw for DampedHertz {
    fn force(&self, delta: f64, delta_dot: f64) -> f64 {
        (self.elastic.force(delta, 0.0) * (1.0 + self.chi * delta_dot)).max(0.0)
    }

    fn stiffness(&self, delta: f64, delta_dot: f64) -> f64 {
        if self.force(delta, delta_dot) > 0.0 {
            self.elastic.stiffness(delta, 0.0) * (1.0 + self.chi * delta_dot)
        } else {
            0.0
        }
    }

    fn damping(&self, delta: f64, delta_dot: f64) -> f64 {
        if self.force(delta, delta_dot) > 0.0 {
            self.elastic.force(delta, 0.0) * self.chi
        } else {
            0.0
        }
    }

    fn elastic(&self) -> Hertz {
        self.elastic
    }
}
