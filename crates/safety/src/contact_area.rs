//! Contact-area models for the pressure of a spherical dome pressed into skin.
//!
//! The paper's fitted law f = k_c δ^n (Eq. 4; skinned aluminium n = 1.961) is not Hertz's
//! n = 3/2, so no single contact radius follows from it; the area must be modelled. Two physical
//! limits bracket a soft skin on a stiff block, plus the standard's fixed area:
//!
//! - [`ContactAreaModel::HertzSphere`]: elastic half-space (Hertz): contact radius a = √(R δ),
//!   area A = π R δ; ellipsoidal pressure, peak p₀ = 3/2 × mean.
//! - [`ContactAreaModel::ThinLayer`]: a thin compliant layer on a rigid backing (Winkler
//!   foundation): the contact circle is the geometric intersection, a² = 2Rδ − δ², area
//!   A = π(2Rδ − δ²) ≈ 2πRδ (twice Hertz's), parabolic pressure, peak = 2 × mean. For δ ≥ R the
//!   projected area saturates at πR².
//! - [`ContactAreaModel::Fixed`]: a given area (ISO/TS 15066 A.3.2's A: the smaller of the robot's
//!   and the body's contact surfaces).
//!
//! The mean pressure is f/A; [`ContactAreaModel::peak_factor`] converts it to the peak of the
//! model's pressure distribution.

use serde::{Deserialize, Serialize};

use crate::SafetyError;
use crate::trace::check_paired;

/// How the contact area grows with the indentation δ.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case", deny_unknown_fields)]
pub enum ContactAreaModel {
    /// Hertz sphere on an elastic half-space: A = π R δ.
    HertzSphere {
        /// Sphere (dome) radius R \[m\] > 0.
        radius_m: f64,
    },
    /// Rigid sphere into a thin layer on a rigid backing: A = π(2Rδ − δ²) for δ < R, else πR².
    ThinLayer {
        /// Sphere (dome) radius R \[m\] > 0.
        radius_m: f64,
    },
    /// A fixed contact area.
    Fixed {
        /// Area A [m²] > 0.
        area_m2: f64,
    },
}

impl ContactAreaModel {
    /// The two models of a dome of radius `radius_m` \[m\] pressed into skin, in the order runs
    /// report them: Hertz sphere (the default) and thin layer on a rigid backing.
    pub fn dome_models(radius_m: f64) -> [ContactAreaModel; 2] {
        [
            ContactAreaModel::HertzSphere { radius_m },
            ContactAreaModel::ThinLayer { radius_m },
        ]
    }

    /// The dome models ([`ContactAreaModel::dome_models`]) for a contact law f = k δ^n of
    /// exponent `n`: both for n > 1, none for n ≤ 1. A law with n ≤ 1 is a spring, not a dome
    /// pressed into skin: it has no contact geometry, and its Hertz-sphere mean pressure
    /// k δ^{n−1}/(πR) would not vanish with the force (k/(πR) at every force for n = 1), so no
    /// pressure is reported.
    pub fn dome_models_for_exponent(radius_m: f64, n: f64) -> Vec<ContactAreaModel> {
        if n > 1.0 {
            Self::dome_models(radius_m).to_vec()
        } else {
            Vec::new()
        }
    }

    /// Checks the parameter (names `radius_m` or `area_m2`).
    pub fn validate(&self) -> Result<(), SafetyError> {
        match *self {
            ContactAreaModel::HertzSphere { radius_m }
            | ContactAreaModel::ThinLayer { radius_m } => {
                flexrig_contact::validate::positive("radius_m", radius_m)?;
            }
            ContactAreaModel::Fixed { area_m2 } => {
                flexrig_contact::validate::positive("area_m2", area_m2)?;
            }
        }
        Ok(())
    }

    /// Contact area [m²] at indentation `delta` \[m\] (0 for δ ≤ 0 except the fixed area).
    pub fn area(&self, delta: f64) -> f64 {
        let pi = std::f64::consts::PI;
        match *self {
            ContactAreaModel::HertzSphere { radius_m } => pi * radius_m * delta.max(0.0),
            ContactAreaModel::ThinLayer { radius_m } => {
                let d = delta.clamp(0.0, radius_m);
                pi * d * (2.0 * radius_m - d)
            }
            ContactAreaModel::Fixed { area_m2 } => area_m2,
        }
    }

    /// Peak over mean pressure of the model's distribution: 3/2 (Hertz), 2 (thin layer), 1
    /// (fixed area, uniform).
    pub fn peak_factor(&self) -> f64 {
        match self {
            ContactAreaModel::HertzSphere { .. } => 1.5,
            ContactAreaModel::ThinLayer { .. } => 2.0,
            ContactAreaModel::Fixed { .. } => 1.0,
        }
    }

    /// Mean contact pressure f/A \[Pa\] at force `force` \[N\] and indentation `delta` \[m\]; 0 without
    /// contact (f ≤ 0 or A = 0).
    pub fn mean_pressure(&self, force: f64, delta: f64) -> f64 {
        let area = self.area(delta);
        if force > 0.0 && area > 0.0 {
            force / area
        } else {
            0.0
        }
    }
}

/// The largest mean pressure \[Pa\] over a sampled contact: max f_i/A(δ_i), with `force` \[N\] and
/// `indentation` \[m\] sampled together. Also returns the sample index.
pub fn peak_pressure(
    force: &[f64],
    indentation: &[f64],
    model: &ContactAreaModel,
) -> Result<(f64, usize), SafetyError> {
    model.validate()?;
    check_paired("force", force, "indentation", indentation)?;
    let mut best = (0.0, 0);
    for (i, (&f, &d)) in force.iter().zip(indentation).enumerate() {
        let p = model.mean_pressure(f, d);
        if p > best.0 {
            best = (p, i);
        }
    }
    Ok(best)
}
