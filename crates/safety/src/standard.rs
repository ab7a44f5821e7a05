//! The standard's permissible speed: ISO/TS 15066:2016 Annex A, the two-body energy model.
//!
//! The body region is a linear spring k (Table A.3's K) and a mass m_H; the robot an effective
//! mass m_R. All the relative kinetic energy is stored in the body spring at the peak:
//!
//! E = F²/(2k) = A² p²/(2k)                         (Eq. A.1)
//! E = ½ μ v²                                       (Eq. A.2)
//! μ = (1/m_H + 1/m_R)⁻¹                            (Eq. A.3)
//! m_R = M/2 + m_L                                   (Eq. A.4)
//! v_max = F_max/√(μ k) = p_max A/√(μ k)             (Eq. A.5, A.6)
//!
//! This is the paper's Eq. 13 solved for v₀ with a linear contact (n = 1) of stiffness k_c = K
//! and a rigid link (k_δ → ∞): everything the energy method of [`crate::energy_method`] adds —
//! the nonlinear skin and the link's or joint's compliance — is what the formula leaves out.
//! For quasi-static (clamped) contact flexrig sets m_H = ∞ (the body cannot recoil), so μ = m_R,
//! and uses the quasi-static limits.

use serde::{Deserialize, Serialize};

use crate::SafetyError;
use crate::body_model::{BodyArea, BodyRegion, ContactKind};
use crate::speed::{PermissibleSpeed, Verdict};

/// The robot's moving mass and payload (ISO/TS 15066:2016 Eq. A.4).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotMass {
    /// Total mass of the moving parts of the robot M \[kg\] ≥ 0.
    pub total_moving_mass: f64,
    /// Effective payload including tooling and workpiece m_L \[kg\] ≥ 0.
    pub payload: f64,
}

impl RobotMass {
    /// m_R = M/2 + m_L \[kg\] (Eq. A.4); an error unless both are ≥ 0 and m_R > 0.
    pub fn effective(&self) -> Result<f64, SafetyError> {
        let m =
            flexrig_contact::validate::non_negative("total_moving_mass", self.total_moving_mass)?;
        let l = flexrig_contact::validate::non_negative("payload", self.payload)?;
        Ok(flexrig_contact::validate::positive(
            "robot effective mass M/2 + m_L",
            0.5 * m + l,
        )?)
    }
}

/// Reduced mass μ = (1/m_H + 1/m_R)⁻¹ \[kg\] (Eq. A.3); m_H = +∞ gives μ = m_R.
pub fn reduced_mass(human_mass: f64, robot_mass: f64) -> f64 {
    if human_mass.is_infinite() {
        robot_mass
    } else {
        human_mass * robot_mass / (human_mass + robot_mass)
    }
}

/// A contact judged by the standard's formula.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandardContact<'a> {
    /// The body region (K, m_H, force limit).
    pub region: &'a BodyRegion,
    /// The body area and the contact area A [m²], for the pressure form (Eq. A.6).
    pub area: Option<(&'a BodyArea, f64)>,
    /// Effective robot mass m_R \[kg\] (e.g. from [`RobotMass::effective`]).
    pub robot_mass: f64,
    /// Quasi-static (clamped) or transient.
    pub kind: ContactKind,
}

impl StandardContact<'_> {
    fn checked(&self) -> Result<(f64, f64, Option<f64>), SafetyError> {
        let m_r = flexrig_contact::validate::positive("robot_mass", self.robot_mass)?;
        let mu = reduced_mass(self.region.human_mass(self.kind), m_r);
        let area = match self.area {
            Some((_, a)) => Some(flexrig_contact::validate::positive("contact_area_m2", a)?),
            None => None,
        };
        Ok((mu, self.region.spring_constant(), area))
    }

    /// v_max = F_max/√(μk) and p_max A/√(μk) (Eq. A.5–A.6); an error citing the clause for
    /// transient contact with head or face.
    pub fn permissible_speed(&self) -> Result<PermissibleSpeed, SafetyError> {
        let limits = self.region.limits(self.area.map(|(a, _)| a), self.kind)?;
        let (mu, k, area) = self.checked()?;
        let root = (mu * k).sqrt();
        let by_force = limits.force / root;
        let by_pressure = match (limits.pressure, area) {
            (Some(p), Some(a)) => Some(p * a / root),
            _ => None,
        };
        Ok(PermissibleSpeed::from_parts(
            by_force,
            by_pressure,
            mu,
            limits,
        ))
    }

    /// Peak force F = v √(μk) \[N\] at relative speed `speed` [m/s] (Eq. A.5 solved for F).
    pub fn peak_force(&self, speed: f64) -> Result<f64, SafetyError> {
        let v = flexrig_contact::validate::non_negative("speed", speed)?;
        let (mu, k, _) = self.checked()?;
        Ok(v * (mu * k).sqrt())
    }

    /// Pass/fail at `speed` [m/s] with margins and the governing limit.
    pub fn verdict(&self, speed: f64) -> Result<Verdict, SafetyError> {
        let permissible = self.permissible_speed()?;
        let force = self.peak_force(speed)?;
        let pressure = self.area.map(|(_, a)| force / a);
        Ok(Verdict::new(speed, permissible, force, pressure))
    }
}
