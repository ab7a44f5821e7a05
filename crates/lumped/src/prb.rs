//! Pseudo-Rigid-Body (PRB) relations of the paper (§II, §IV).
//!
//! A compliant link (CL) of length L and bending stiffness EI and a rigid link on a torsion
//! spring (CJ) present the same lateral stiffness at the tip when k_θr = 3EI/L (Eq. 1–3). The PRB
//! model replaces the CL by two rigid segments joined at the characteristic radius γL from the
//! tip by a torsion spring k_θp = π EI γ²/L (§IV, after Howell), and the link and its payload by
//! the effective mass m_eff = m_e + γ m_r/3 (Eq. 5).

use flexrig_contact::{ContactError, validate};

/// Lateral tip stiffness of a rigid link on a torsion spring, k_δ = k_θr/L² [N/m] (Eq. 1).
/// `k_theta_r` [N·m/rad], `length` \[m\].
pub fn lateral_stiffness_cj(k_theta_r: f64, length: f64) -> f64 {
    k_theta_r / (length * length)
}

/// Lateral tip stiffness of a uniform cantilever, k_δ = 3EI/L³ [N/m] (Eq. 2). `ei` [N·m²].
pub fn lateral_stiffness_cl(ei: f64, length: f64) -> f64 {
    3.0 * ei / length.powi(3)
}

/// Torsion spring giving a CJ the CL's lateral stiffness, k_θr = 3EI/L [N·m/rad] (Eq. 3).
pub fn equal_stiffness_torsion_spring(ei: f64, length: f64) -> f64 {
    3.0 * ei / length
}

/// PRB torsion spring k_θp = π EI γ²/L [N·m/rad] (paper §IV).
pub fn prb_torsion_spring(ei: f64, length: f64, gamma: f64) -> f64 {
    std::f64::consts::PI * ei * gamma * gamma / length
}

/// Reduced mass μ = m₁ m₂/(m₁ + m₂) \[kg\].
pub fn reduced_mass(m1: f64, m2: f64) -> f64 {
    m1 * m2 / (m1 + m2)
}

/// A link described for the PRB effective mass: characteristic radius γ ∈ (0, 1] (γ = 1 is the
/// rigid link on a compliant joint, 2/3 the small-deflection compliant link, 0.85 the large-
/// deflection one), link mass m_r \[kg\] > 0 and payload m_e \[kg\] ≥ 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PrbLink {
    gamma: f64,
    m_r: f64,
    m_e: f64,
}

impl PrbLink {
    /// Validated constructor; errors name `gamma`, `m_r` or `m_e`.
    pub fn new(gamma: f64, m_r: f64, m_e: f64) -> Result<Self, ContactError> {
        Ok(PrbLink {
            gamma: validate::in_left_open("gamma", gamma, 0.0, 1.0)?,
            m_r: validate::positive("m_r", m_r)?,
            m_e: validate::non_negative("m_e", m_e)?,
        })
    }

    /// Characteristic radius γ.
    pub fn gamma(&self) -> f64 {
        self.gamma
    }

    /// Link mass m_r \[kg\].
    pub fn m_r(&self) -> f64 {
        self.m_r
    }

    /// Payload m_e \[kg\].
    pub fn m_e(&self) -> f64 {
        self.m_e
    }

    /// Effective mass at the tip, m_eff = m_e + γ m_r/3 \[kg\] (Eq. 5).
    pub fn effective_mass(&self) -> f64 {
        self.m_e + self.gamma * self.m_r / 3.0
    }
}
