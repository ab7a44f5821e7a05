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

    /// Refuses ADAMS IMPACT damping so far past the contact's critical damping that the bodies
    /// stick and no integrator can resolve the release in reasonable time: `c_max` must not
    /// exceed [`MAX_OVERDAMPING`] × c_crit, with c_crit = 2 √(k_lin μ) the critical damping of
    /// the contact linearised at its undamped peak (k_lin = n k δ_max^{n−1},
    /// ½ μ v0² = k δ_max^{n+1}/(n+1), Eq. 4 and the energy balance of Eq. 13) for the reduced
    /// mass `mu` \[kg\] of the bodies in contact at approach speed `v0` \[m/s\]. At that bound
    /// the damping time μ/c_max is 1/(2000) of the contact's natural period scale: the contact
    /// is dead (restitution ≈ 0), so a larger c_max changes nothing a user could want, while
    /// the explicit time scale μ/c_max and the creeping release (δ̇ = −k δ^n/c) make a run take
    /// minutes. The other models are bounded by their restitution and pass.
    pub fn check_overdamping(&self, elastic: Hertz, mu: f64, v0: f64) -> Result<(), ContactError> {
        let DampingSpec::AdamsImpact {
            c_max_n_s_per_m, ..
        } = *self
        else {
            return Ok(());
        };
        if !(mu.is_finite() && mu > 0.0 && v0.is_finite() && v0 > 0.0) {
            return Ok(());
        }
        let bound = MAX_OVERDAMPING * critical_damping(elastic, mu, v0);
        if c_max_n_s_per_m > bound {
            return Err(ContactError::InvalidParameter {
                field: "c_max".into(),
                value: format!("{} N·s/m", crate::validate::display(c_max_n_s_per_m)),
                allowed: format!(
                    "at most {} N·s/m here ({MAX_OVERDAMPING} × the contact's critical damping \
                     2√(k_lin μ) = {} N·s/m for the reduced mass {} kg at {} m/s): a contact \
                     damped further sticks (restitution ≈ 0) and its release cannot be resolved \
                     in reasonable time",
                    three_digits(bound),
                    three_digits(bound / MAX_OVERDAMPING),
                    three_digits(mu),
                    three_digits(v0)
                ),
            });
        }
        Ok(())
    }

    /// True for [`DampingSpec::None`].
    pub fn is_none(&self) -> bool {
        matches!(self, DampingSpec::None {})
    }
}

/// `x` to three significant digits, compact (6.25e6, 6250, 0.0976).
fn three_digits(x: f64) -> String {
    let rounded: f64 = format!("{x:.2e}").parse().unwrap_or(x);
    crate::validate::display(rounded)
}

/// Most ADAMS IMPACT damping allowed, as a multiple of the contact's critical damping
/// ([`DampingSpec::check_overdamping`]).
pub const MAX_OVERDAMPING: f64 = 1000.0;

/// Critical damping 2 √(k_lin μ) \[N·s/m\] of the Hertz contact `elastic` linearised at the
/// undamped peak of an impact of reduced mass `mu` \[kg\] at `v0` \[m/s\]:
/// δ_max = ((n + 1) μ v0²/(2k))^{1/(n+1)}, k_lin = n k δ_max^{n−1}.
pub fn critical_damping(elastic: Hertz, mu: f64, v0: f64) -> f64 {
    let (k, n) = (elastic.k(), elastic.n());
    let delta_max = ((n + 1.0) * mu * v0 * v0 / (2.0 * k)).powf(1.0 / (n + 1.0));
    let k_lin = n * k * delta_max.powf(n - 1.0);
    2.0 * (k_lin * mu).sqrt()
}

impl Default for DampingSpec {
    fn default() -> Self {
        DampingSpec::NONE
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The critical damping against its closed forms: 2√(kμ) for n = 1; for n = 2 the energy
    /// balance ½μv0² = kδ³/3 gives δ_max = (3μv0²/(2k))^{1/3} and k_lin = 2kδ_max.
    #[test]
    fn critical_damping_matches_the_linearised_closed_forms() {
        let (mu, v0) = (0.0976, 2.0);
        let linear = Hertz::new(1e8, 1.0).unwrap();
        let exact = 2.0 * (1e8_f64 * mu).sqrt();
        assert!((critical_damping(linear, mu, v0) / exact - 1.0).abs() < 1e-14);
        let quadratic = Hertz::new(1e8, 2.0).unwrap();
        let delta = (3.0 * mu * v0 * v0 / 2e8).cbrt();
        let exact = 2.0 * (2e8 * delta * mu).sqrt();
        assert!((critical_damping(quadratic, mu, v0) / exact - 1.0).abs() < 1e-13);
    }

    /// Regression (an `eta` with the stiffest ADAMS damping over the thinnest depth ran for
    /// minutes): c_max beyond 1000 × critical is refused naming `c_max`; at the bound it passes,
    /// and the restitution models are never refused.
    #[test]
    fn adams_damping_far_past_critical_is_refused_naming_c_max() {
        let hertz = Hertz::new(1e8, 2.0).unwrap();
        let (mu, v0) = (0.0976, 2.0);
        let bound = MAX_OVERDAMPING * critical_damping(hertz, mu, v0);
        let adams = |c| DampingSpec::AdamsImpact {
            c_max_n_s_per_m: c,
            depth_m: 1e-9,
        };
        assert!(adams(bound).check_overdamping(hertz, mu, v0).is_ok());
        let e = adams(1e9).check_overdamping(hertz, mu, v0).unwrap_err();
        let text = e.to_string();
        assert!(text.contains("c_max") && text.contains("1e9"), "{text}");
        assert!(text.contains("critical damping"), "{text}");
        let hc = DampingSpec::HuntCrossley { restitution: 0.0 };
        assert!(hc.check_overdamping(hertz, mu, v0).is_ok());
    }

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
