//! The two-mass impact model of the paper (Fig. 5c–d, Eq. 10–12).
//!
//! The effective robot mass m_eff and the human mass m_h meet at relative speed v0 through the
//! link spring k_δ in series with the Hertz contact:
//!
//! m_eff ẍ_eff = −f,  m_h ẍ_h = f,  δ = x_eff − x_h            (Eq. 10–12)
//!
//! so the relative displacement obeys μ δ̈ = −f(δ) with μ = m_h m_eff/(m_h + m_eff),
//! δ(0) = 0, δ̇(0) = v0, and f(δ) from the series compliance (Eq. 6–9).

use flexrig_contact::{SeriesCompliance, validate};

use crate::LumpedError;
use crate::prb::{PrbLink, reduced_mass};

/// A validated two-mass impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactModel {
    m_h: f64,
    m_eff: f64,
    spring: SeriesCompliance,
    v0: f64,
}

impl ImpactModel {
    /// Human (operator) mass `m_h` \[kg\] > 0, effective robot mass `m_eff` \[kg\] > 0, the series
    /// spring, and the approach speed `v0` [m/s] > 0.
    pub fn new(
        m_h: f64,
        m_eff: f64,
        spring: SeriesCompliance,
        v0: f64,
    ) -> Result<Self, LumpedError> {
        Ok(ImpactModel {
            m_h: validate::positive("m_h", m_h)?,
            m_eff: validate::positive("m_eff", m_eff)?,
            spring,
            v0: validate::positive("v0", v0)?,
        })
    }

    /// As [`ImpactModel::new`] with m_eff = m_e + γ m_r/3 from a PRB link (Eq. 5).
    pub fn with_prb_link(
        m_h: f64,
        link: PrbLink,
        spring: SeriesCompliance,
        v0: f64,
    ) -> Result<Self, LumpedError> {
        Self::new(m_h, link.effective_mass(), spring, v0)
    }

    /// Human mass m_h \[kg\].
    pub fn m_h(&self) -> f64 {
        self.m_h
    }

    /// Effective robot mass m_eff \[kg\].
    pub fn m_eff(&self) -> f64 {
        self.m_eff
    }

    /// The series link–contact spring.
    pub fn spring(&self) -> &SeriesCompliance {
        &self.spring
    }

    /// Approach speed v0 [m/s].
    pub fn v0(&self) -> f64 {
        self.v0
    }

    /// Reduced mass μ = m_h m_eff/(m_h + m_eff) \[kg\].
    pub fn reduced_mass(&self) -> f64 {
        reduced_mass(self.m_h, self.m_eff)
    }

    /// Kinetic energy of the relative motion, ½ μ v0² \[J\]: all of it is stored in the springs at
    /// the peak.
    pub fn impact_energy(&self) -> f64 {
        0.5 * self.reduced_mass() * self.v0 * self.v0
    }

    /// The same impact with another effective robot mass.
    pub fn with_m_eff(&self, m_eff: f64) -> Result<Self, LumpedError> {
        Self::new(self.m_h, m_eff, self.spring, self.v0)
    }
}

/// The state at maximum compression.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Peak {
    /// Peak force f_max \[N\].
    pub f_max: f64,
    /// Total displacement at the peak, δ_max \[m\].
    pub delta_max: f64,
    /// Contact indentation at the peak, δ_c \[m\].
    pub indentation_max: f64,
    /// Link deflection at the peak, δ_l \[m\].
    pub link_deflection_max: f64,
}

impl Peak {
    /// The peak state of `spring` at force `f_max`.
    pub fn at_force(spring: &SeriesCompliance, f_max: f64) -> Self {
        let indentation_max = spring.indentation(f_max);
        let link_deflection_max = spring.link_deflection(f_max);
        Peak {
            f_max,
            delta_max: indentation_max + link_deflection_max,
            indentation_max,
            link_deflection_max,
        }
    }
}
