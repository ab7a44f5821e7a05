//! Lumped links as serial chains of masses and springs from the struck tip to the joint, run
//! through [`TipModes`] and the exact modal integrator ([`crate::modal_run`]).
//!
//! * **CJ** (the rigid link on its torsion spring, Eq. 3): one mass M = m_e + m_r/3 on k_δ.
//! * **Placed model** (issue 14's better reduced model of the CL, derived in docs/theory.md): the
//!   payload m_e at the tip *ahead* of the link's spring; behind it, through the spring k_r, the
//!   beam's first-mode mass m_b = m_r/4 (a cantilever's first mode referred to its tip:
//!   ∫φ₁² ρA dx/φ₁(L)² = m_r/4) on the spring k_b = ω₁² m_b = β₁⁴/4 · EI/L³ (β₁ = 1.8751) to the
//!   joint; k_r closes the static tip compliance, 1/k_r + 1/k_b = 1/k_δ (k_r ≈ 34 k_δ).
//!
//! The last spring ends at the ground (held joint) or on the rotor (free hub) of tip-equivalent
//! mass J_R/L², which for the placed model also carries the rest of the beam's rigid-rotation
//! inertia, m_r/3 − m_b = m_r/12. A zero payload leaves k_r as a massless series spring (the
//! residual compliance R = 1/k_r of [`TipModes`]).

use faer::Mat;

use crate::ImpactError;
use crate::setup::{FreeMassImpact, Joint};
use crate::tip_modes::TipModes;

/// β₁ of a cantilever's first mode: 1 + cos β cosh β = 0.
pub const BETA_1: f64 = 1.875_104_068_711_961;

/// A serial chain from the tip to the joint.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// Masses from the tip \[kg\], each > 0.
    pub masses: Vec<f64>,
    /// Springs \[N/m\]: `springs[i]` joins mass i to mass i + 1, the last one the last mass to
    /// the joint.
    pub springs: Vec<f64>,
    /// A massless spring between the contact and the first mass \[m/N\] (0: none).
    pub series_compliance: f64,
}

impl Chain {
    /// The CJ link.
    pub fn cj(setup: &FreeMassImpact) -> Chain {
        Chain {
            masses: vec![setup.link.cj_tip_mass()],
            springs: vec![setup.link.k_delta],
            series_compliance: 0.0,
        }
    }

    /// The placed model of the CL link (module docs).
    pub fn placed(setup: &FreeMassImpact) -> Chain {
        let link = setup.link;
        let m_b = link.m_r / 4.0;
        let k_b = BETA_1.powi(4) / 4.0 * link.ei() / link.length.powi(3);
        let k_r = 1.0 / (1.0 / link.k_delta - 1.0 / k_b);
        if link.m_e > 0.0 {
            Chain {
                masses: vec![link.m_e, m_b],
                springs: vec![k_r, k_b],
                series_compliance: 0.0,
            }
        } else {
            Chain {
                masses: vec![m_b],
                springs: vec![k_b],
                series_compliance: 1.0 / k_r,
            }
        }
    }

    /// The chain's [`TipModes`] under the joint of `setup` (a free hub adds the rotor, J_R/L²
    /// plus `rotor_extra` \[kg\], and moves everything at −v0 at t = 0).
    pub fn tip_modes(
        &self,
        setup: &FreeMassImpact,
        rotor_extra: f64,
    ) -> Result<TipModes, ImpactError> {
        let mut masses = self.masses.clone();
        let grounded = match setup.joint {
            Joint::Held => true,
            Joint::FreeHub { rotor_inertia } => {
                let l = setup.link.length;
                masses.push(rotor_inertia / (l * l) + rotor_extra);
                false
            }
        };
        let n = masses.len();
        let mut k = Mat::<f64>::zeros(n, n);
        for (i, &ks) in self.springs.iter().enumerate() {
            k[(i, i)] += ks;
            if i + 1 < n {
                k[(i + 1, i + 1)] += ks;
                k[(i, i + 1)] -= ks;
                k[(i + 1, i)] -= ks;
            } else if !grounded {
                unreachable!("a free hub's chain ends on the rotor");
            }
        }
        let m = Mat::from_fn(n, n, |i, j| if i == j { masses[i] } else { 0.0 });
        let v0 = match setup.joint {
            Joint::Held => vec![0.0; n],
            Joint::FreeHub { .. } => vec![-setup.v0; n],
        };
        // shift: the softest spring on the whole mass, of the order of the lowest ω²
        let shift =
            self.springs.iter().copied().fold(f64::INFINITY, f64::min) / masses.iter().sum::<f64>();
        let mut modes = TipModes::from_matrices(&k, &m, 0, &v0, f64::INFINITY, shift)?;
        modes.residual += self.series_compliance;
        Ok(modes)
    }
}

/// The paper's lumped model (Fig. 5c–d, Eq. 5) as a structure for the modal integrator: the
/// free mass `m_eff` \[kg\] behind the massless link spring `k_delta` \[N/m\] in series with the
/// contact, no ground anywhere. With any contact law (damped ones included) it gives the
/// lumped peak that [`flexrig_lumped::peak_exact`] gives in closed form for the elastic law.
pub fn paper_lumped(m_eff: f64, k_delta: f64) -> TipModes {
    TipModes {
        omegas: vec![0.0],
        gains: vec![1.0 / m_eff.sqrt()],
        rates: vec![0.0],
        residual: 1.0 / k_delta,
    }
}
