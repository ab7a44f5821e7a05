//! Permissible speed by the paper's energy method: the lumped two-mass impact with a Hertz skin
//! contact f = k_c δ_c^n (Eq. 4) in series with the link's (or joint's) lateral stiffness k_δ
//! (Eq. 6–9), solved exactly by energy.
//!
//! The relative motion μ δ̈ = −f(δ) (Eq. 10–12) is conservative, so at maximum compression
//!
//! ½ μ v² = U(f_max),  U(f) = f²/(2k_δ) + f δ_c/(n + 1),  δ_c = (f/k_c)^{1/n},  μ = m_h m_eff/(m_h + m_eff)
//!
//! (for n = 1 this is Eq. 13; [`flexrig_contact::SeriesCompliance::energy`] is the same U). Both
//! directions are exact:
//!
//! - the speed that brings the peak force to a limit F is closed form, v_F = √(2 U(F)/μ);
//! - the peak force at a speed solves U(f) = ½ μ v² (closed form for a rigid link,
//!   f = ((n+1)E)^{n/(n+1)} k_c^{1/(n+1)}; the convex Newton solve of
//!   [`flexrig_contact::SeriesCompliance::force_at_energy`] otherwise);
//! - the speed that brings the mean contact pressure f/A(δ_c) to a limit p first finds the force
//!   f_p where the pressure reaches p (closed form for the Hertz and fixed areas; a scan in ln δ_c
//!   and bisection for the thin-layer area), then v_p = √(2 U(f_p)/μ).
//!
//! With n = 1, k_c = K and a rigid link this reproduces the standard's formula
//! ([`crate::standard`]) identically; the test `identity_with_the_standard_formula` checks it.
//! For clamped (quasi-static) contact the human mass is +∞ and μ = m_eff.

use flexrig_contact::{Hertz, SeriesCompliance};
use serde::{Deserialize, Serialize};

use crate::SafetyError;
use crate::body_model::{BodyRegion, ContactKind, Limits};
use crate::contact_area::ContactAreaModel;
use crate::speed::{PermissibleSpeed, Verdict};
use crate::standard::reduced_mass;

/// Smallest indentation \[m\] the pressure scan starts from (far below any skin's roughness).
const SCAN_MIN_INDENTATION: f64 = 1e-12;
/// Largest indentation \[m\] the pressure scan reaches.
const SCAN_MAX_INDENTATION: f64 = 10.0;
/// Points of the logarithmic pressure scan.
const SCAN_POINTS: usize = 400;

/// The link's (or joint's) lateral stiffness in series with the contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LinkStiffness {
    /// k_δ → ∞: the pure Hertz contact.
    Rigid,
    /// k_δ [N/m] > 0 (e.g. k_θr/L² for a compliant joint, 3EI/L³ for a compliant link, Eq. 1–2).
    Finite(f64),
}

/// Where the contact pressure reaches a limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PressureCrossing {
    /// At this force \[N\] (the smallest force where the mean pressure reaches the limit).
    AtForce(f64),
    /// The pressure exceeds the limit at every force (e.g. n < 1 with the Hertz area).
    Always,
    /// The pressure never reaches the limit (e.g. n = 1 with a low enough k_c/(πR)).
    Never,
}

/// A validated lumped contact for the energy method.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyContact {
    human_mass: f64,
    robot_mass: f64,
    contact: Hertz,
    link: LinkStiffness,
    series: Option<SeriesCompliance>,
    area: Option<ContactAreaModel>,
}

impl EnergyContact {
    /// Human mass m_h \[kg\] (> 0, or +∞ for a clamped body), effective robot mass m_eff \[kg\] > 0
    /// (Eq. 5 for a PRB link), the skin's Hertz law, the link stiffness, and the contact-area
    /// model for pressure (optional).
    pub fn new(
        human_mass: f64,
        robot_mass: f64,
        contact: Hertz,
        link: LinkStiffness,
        area: Option<ContactAreaModel>,
    ) -> Result<Self, SafetyError> {
        if !(human_mass == f64::INFINITY) {
            flexrig_contact::validate::positive("human_mass", human_mass)?;
        }
        let robot_mass = flexrig_contact::validate::positive("robot_mass", robot_mass)?;
        let series = match link {
            LinkStiffness::Rigid => None,
            LinkStiffness::Finite(k) => Some(SeriesCompliance::new(k, contact)?),
        };
        if let Some(a) = &area {
            a.validate()?;
        }
        Ok(EnergyContact {
            human_mass,
            robot_mass,
            contact,
            link,
            series,
            area,
        })
    }

    /// As [`EnergyContact::new`] with the human mass of `region` for `kind` (Table A.3's m_H for
    /// transient contact, +∞ for quasi-static); refuses transient contact where the standard
    /// forbids it ([`SafetyError::ContactNotPermitted`]).
    pub fn for_region(
        region: &BodyRegion,
        kind: ContactKind,
        robot_mass: f64,
        contact: Hertz,
        link: LinkStiffness,
        area: Option<ContactAreaModel>,
    ) -> Result<Self, SafetyError> {
        region.force_limit(kind)?;
        Self::new(region.human_mass(kind), robot_mass, contact, link, area)
    }

    /// The same contact with another effective robot mass \[kg\].
    pub fn with_robot_mass(&self, robot_mass: f64) -> Result<Self, SafetyError> {
        Self::new(
            self.human_mass,
            robot_mass,
            self.contact,
            self.link,
            self.area,
        )
    }

    /// The same contact with another link stiffness.
    pub fn with_link(&self, link: LinkStiffness) -> Result<Self, SafetyError> {
        Self::new(
            self.human_mass,
            self.robot_mass,
            self.contact,
            link,
            self.area,
        )
    }

    /// Reduced mass μ \[kg\] (μ = m_eff for a clamped body).
    pub fn reduced_mass(&self) -> f64 {
        reduced_mass(self.human_mass, self.robot_mass)
    }

    /// Contact indentation δ_c = (f/k_c)^{1/n} \[m\] at force f \[N\] (Eq. 6).
    pub fn indentation(&self, force: f64) -> f64 {
        self.contact.indentation(force)
    }

    /// Stored energy U(f) = f²/(2k_δ) + f δ_c/(n+1) \[J\] at force f \[N\].
    pub fn stored_energy(&self, force: f64) -> f64 {
        match &self.series {
            Some(s) => s.energy(force),
            None if force > 0.0 => force * self.indentation(force) / (self.contact.n() + 1.0),
            None => 0.0,
        }
    }

    /// Relative speed [m/s] at which the peak force is `force` \[N\]: √(2 U(f)/μ) (closed form).
    pub fn speed_at_force(&self, force: f64) -> f64 {
        (2.0 * self.stored_energy(force) / self.reduced_mass()).sqrt()
    }

    /// Peak force \[N\] at relative speed `speed` [m/s]: the root of U(f) = ½ μ v².
    pub fn peak_force(&self, speed: f64) -> Result<f64, SafetyError> {
        let v = flexrig_contact::validate::non_negative("speed", speed)?;
        let energy = 0.5 * self.reduced_mass() * v * v;
        if energy == 0.0 {
            return Ok(0.0);
        }
        Ok(match &self.series {
            Some(s) => s.force_at_energy(energy).force,
            None => {
                let n = self.contact.n();
                ((n + 1.0) * energy).powf(n / (n + 1.0)) * self.contact.k().powf(1.0 / (n + 1.0))
            }
        })
    }

    /// Mean contact pressure \[Pa\] at force f \[N\] (`None` without an area model).
    pub fn pressure_at_force(&self, force: f64) -> Option<f64> {
        self.area
            .map(|a| a.mean_pressure(force, self.indentation(force)))
    }

    /// The smallest force at which the mean pressure reaches `pressure` \[Pa\] (`None` without an
    /// area model).
    pub fn force_at_pressure(&self, pressure: f64) -> Option<PressureCrossing> {
        let area = self.area?;
        let (k, n) = (self.contact.k(), self.contact.n());
        Some(match area {
            ContactAreaModel::Fixed { area_m2 } => PressureCrossing::AtForce(pressure * area_m2),
            ContactAreaModel::HertzSphere { radius_m } => {
                // p = f/(π R δ_c) = k_c^{1/n} f^{1−1/n}/(π R).
                let pi_r = std::f64::consts::PI * radius_m;
                if n > 1.0 {
                    PressureCrossing::AtForce(
                        (pressure * pi_r * k.powf(-1.0 / n)).powf(n / (n - 1.0)),
                    )
                } else if n == 1.0 {
                    if k / pi_r >= pressure {
                        PressureCrossing::Always
                    } else {
                        PressureCrossing::Never
                    }
                } else {
                    PressureCrossing::Always
                }
            }
            ContactAreaModel::ThinLayer { .. } => self.scan_pressure(&area, pressure),
        })
    }

    /// First crossing of p(δ_c) = k_c δ_c^n / A(δ_c) with `pressure` on a log scan of δ_c, refined
    /// by bisection in ln δ_c to round-off.
    fn scan_pressure(&self, area: &ContactAreaModel, pressure: f64) -> PressureCrossing {
        let (k, n) = (self.contact.k(), self.contact.n());
        let excess = |ln_d: f64| {
            let d = ln_d.exp();
            let f = k * d.powf(n);
            f / area.area(d) - pressure
        };
        let (lo, hi) = (SCAN_MIN_INDENTATION.ln(), SCAN_MAX_INDENTATION.ln());
        if excess(lo) >= 0.0 {
            return PressureCrossing::Always;
        }
        let step = (hi - lo) / (SCAN_POINTS - 1) as f64;
        let mut below = lo;
        for i in 1..SCAN_POINTS {
            let s = lo + step * i as f64;
            if excess(s) >= 0.0 {
                let (mut a, mut b) = (below, s);
                for _ in 0..200 {
                    let mid = 0.5 * (a + b);
                    if mid <= a || mid >= b {
                        break;
                    }
                    if excess(mid) >= 0.0 {
                        b = mid;
                    } else {
                        a = mid;
                    }
                }
                return PressureCrossing::AtForce(k * b.exp().powf(n));
            }
            below = s;
        }
        PressureCrossing::Never
    }

    /// The permissible speed for `limits` (force always; pressure if both a pressure limit and
    /// an area model are given).
    pub fn permissible_speed(&self, limits: Limits) -> Result<PermissibleSpeed, SafetyError> {
        let force = flexrig_contact::validate::positive("force limit", limits.force)?;
        let by_force = self.speed_at_force(force);
        let by_pressure = match limits.pressure {
            Some(p) => {
                let p = flexrig_contact::validate::positive("pressure limit", p)?;
                self.force_at_pressure(p).map(|c| match c {
                    PressureCrossing::AtForce(f) => self.speed_at_force(f),
                    PressureCrossing::Always => 0.0,
                    PressureCrossing::Never => f64::INFINITY,
                })
            }
            None => None,
        };
        Ok(PermissibleSpeed::from_parts(
            by_force,
            by_pressure,
            self.reduced_mass(),
            limits,
        ))
    }

    /// Pass/fail at relative speed `speed` [m/s] with margins and the governing limit.
    pub fn verdict(&self, speed: f64, limits: Limits) -> Result<Verdict, SafetyError> {
        let permissible = self.permissible_speed(limits)?;
        let force = self.peak_force(speed)?;
        let pressure = limits.pressure.and(self.pressure_at_force(force));
        Ok(Verdict::new(speed, permissible, force, pressure))
    }
}

/// Permissible speeds over a grid of effective robot masses (rows) × link stiffnesses (columns),
/// row-major, for one contact and one set of limits.
pub fn speed_map(
    contact: &EnergyContact,
    limits: Limits,
    robot_masses: &[f64],
    links: &[LinkStiffness],
) -> Result<Vec<PermissibleSpeed>, SafetyError> {
    let mut out = Vec::with_capacity(robot_masses.len() * links.len());
    for &m in robot_masses {
        let row = contact.with_robot_mass(m)?;
        for &link in links {
            out.push(row.with_link(link)?.permissible_speed(limits)?);
        }
    }
    Ok(out)
}
