//! The choice of damping added to an elastic Hertz law, as plain data (a scene file's
//! `[contact.damping]` table, a CLI flag), and the [`ContactLaw`] it makes.

use serde::{Deserialize, Serialize};

use crate::{AdamsImpact, ContactError, ContactLaw, DampedHertz, Hertz};

/// Damping added to an elastic Hertz law (default: none).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "model", deny_unknown_fields)]
pub enum DampingSpec {
    /// No damping (default).
    None {},
    /// Hunt–Crossley with restitution `restitution` at the impact speed.
    HuntCrossley {
        /// Coefficient of restitution ∈ [0, 1].
        restitution: f64,
    },
    /// Lankarani–Nikravesh with restitution `restitution` at the impact speed.
    LankaraniNikravesh {
        /// Coefficient of restitution ∈ [0, 1].
        restitution: f64,
    },
    /// ADAMS IMPACT: damping ramped by a cubic STEP from 0 at first touch to `c_max` at the
    /// penetration `depth_m` (stiffness and exponent from the Hertz law).
    AdamsImpact {
        /// Maximum damping [N·s/m], ≥ 0.
        c_max_n_s_per_m: f64,
        /// Penetration at which the damping reaches c_max \[m\], > 0.
        depth_m: f64,
    },
}

impl DampingSpec {
    /// No damping.
    pub const NONE: DampingSpec = DampingSpec::None {};

    /// The law: `elastic` (k δ^n) with this damping, for an impact at approach speed `v0`
    /// [m/s] (Hunt–Crossley and Lankarani–Nikravesh set χ from it). The error names the
    /// damping field (`restitution`, `c_max`, `depth`) and the allowed range.
    pub fn law(&self, elastic: Hertz, v0: f64) -> Result<Box<dyn ContactLaw>, ContactError> {
        Ok(match *self {
            DampingSpec::None {} => Box::new(elastic),
            DampingSpec::HuntCrossley { restitution } => {
                Box::new(DampedHertz::hunt_crossley(elastic, restitution, v0)?)
            }
            DampingSpec::LankaraniNikravesh { restitution } => {
                Box::new(DampedHertz::lankarani_nikravesh(elastic, restitution, v0)?)
            }
            DampingSpec::AdamsImpact {
                c_max_n_s_per_m,
                depth_m,
            } => Box::new(AdamsImpact::new(
                elastic.k(),
                elastic.n(),
                c_max_n_s_per_m,
                depth_m,
            )?),
        })
    }

    /// True for [`DampingSpec::None`].
    pub fn is_none(&self) -> bool {
        matches!(self, DampingSpec::None {})
    }
}

impl Default for DampingSpec {
    fn default() -> Self {
        DampingSpec::NONE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_choice_makes_its_law_and_bad_values_name_the_field() {
        let hertz = Hertz::new(1e8, 1.5).unwrap();
        let (delta, rate) = (1e-4, 0.5);
        let elastic = hertz.force(delta, 0.0);
        let none = DampingSpec::NONE.law(hertz, 2.0).unwrap();
        assert_eq!(none.force(delta, rate), elastic);
        // Hunt–Crossley e = 0.8 at 2 m/s: χ = 3 (0.2)/(2·2) = 0.15 s/m
        let hc = DampingSpec::HuntCrossley { restitution: 0.8 }
            .law(hertz, 2.0)
            .unwrap();
        assert!((hc.force(delta, rate) / elastic - (1.0 + 0.15 * rate)).abs() < 1e-14);
        // Lankarani–Nikravesh e = 0.8: χ = 3 (1 − 0.64)/(4·2) = 0.135 s/m
        let ln = DampingSpec::LankaraniNikravesh { restitution: 0.8 }
            .law(hertz, 2.0)
            .unwrap();
        assert!((ln.force(delta, rate) / elastic - (1.0 + 0.135 * rate)).abs() < 1e-14);
        // ADAMS beyond the ramp depth: k δ^n + c_max δ̇
        let adams = DampingSpec::AdamsImpact {
            c_max_n_s_per_m: 100.0,
            depth_m: 1e-5,
        }
        .law(hertz, 2.0)
        .unwrap();
        assert!((adams.force(delta, rate) - (elastic + 50.0)).abs() < 1e-9);
        let bad = DampingSpec::HuntCrossley { restitution: 1.5 }.law(hertz, 2.0);
        assert!(bad.unwrap_err().to_string().contains("restitution"));
        let bad = DampingSpec::AdamsImpact {
            c_max_n_s_per_m: 1.0,
            depth_m: 0.0,
        }
        .law(hertz, 2.0);
        assert!(bad.unwrap_err().to_string().contains("depth"));
    }
}
