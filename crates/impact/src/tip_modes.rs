//! A linear structure seen from the struck point: its modes' frequencies, their amplitudes at the
//! tip and their initial rates, plus the static compliance of the modes left out.
//!
//! From dense K, M (symmetric, K + σM positive definite) over n DOFs, by flexrig-beam's shifted
//! pencil ([`flexrig_beam::modal::ShiftedPencil`]), the modes M-normalised. In modal
//! coordinates every mode obeys q̈ᵢ + ωᵢ² qᵢ = bᵢ f(t) with bᵢ = φᵢ(tip) \[1/√kg\] and f the force on the tip \[N\]; the tip deflection is
//! w = Σ bᵢ qᵢ + R f, where R = Σ_{left out} bᵢ²/ωᵢ² \[m/N\] is the quasi-static response of the
//! modes above the cut-off (the mode-acceleration correction). Initial rates q̇ᵢ(0) = φᵢᵀ M v₀.

use faer::Mat;

use crate::ImpactError;

/// The modes of a linear structure at its struck point.
#[derive(Debug, Clone, PartialEq)]
pub struct TipModes {
    /// ωᵢ [rad/s], ascending; 0 for a rigid-body mode.
    pub omegas: Vec<f64>,
    /// bᵢ = φᵢ(tip) [1/√kg] of the M-orthonormal modes.
    pub gains: Vec<f64>,
    /// q̇ᵢ(0) [√kg·m/s].
    pub rates: Vec<f64>,
    /// Static compliance R of the modes above the cut-off \[m/N\].
    pub residual: f64,
}

impl TipModes {
    /// The modes of free vibration K φ = ω² M φ with ω ≤ `omega_cut` [rad/s] (every mode for
    /// `f64::INFINITY`), seen at DOF `tip`, for the structure moving at `v0` [m/s, rad/s] at
    /// t = 0 and at rest in its undeformed shape. `shift` σ [1/s²] > 0, of the order of the lowest
    /// flexible ω², makes the solve well posed with rigid modes and keeps the *lowest* modes
    /// accurate to round-off whatever the highest: with K + σM = L Lᵀ the eigenvalues of
    /// L⁻¹ M L⁻ᵀ are λ = 1/(ω² + σ), largest for the lowest modes, and their error ε λ_max is
    /// relative to them (a mesh graded to L/2000 at the tip spans ω²_max/ω₁² ≈ 1e12). Modes with
    /// |ω²| ≤ 1e-8 σ are rigid (ω = 0).
    pub fn from_matrices(
        k: &Mat<f64>,
        m: &Mat<f64>,
        tip: usize,
        v0: &[f64],
        omega_cut: f64,
        shift: f64,
    ) -> Result<TipModes, ImpactError> {
        let n = k.nrows();
        let failed = |what: String| ImpactError::NotFinished {
            design: "modes",
            reason: what,
        };
        if !(shift.is_finite() && shift > 0.0) {
            return Err(failed(format!("the eigen shift must be > 0, not {shift}")));
        }
        let pencil = flexrig_beam::modal::ShiftedPencil::solve(k, m, shift)?;
        let mv0: Vec<f64> = (0..n)
            .map(|i| (0..n).map(|j| m[(i, j)] * v0[j]).sum())
            .collect();
        let mut modes = TipModes {
            omegas: Vec::new(),
            gains: Vec::new(),
            rates: Vec::new(),
            residual: 0.0,
        };
        let lambda_max = pencil.lambda.iter().copied().fold(0.0_f64, f64::max);
        if !(lambda_max > 0.0) {
            return Err(failed("the structure has no mass".into()));
        }
        // λ ascending: the lowest modes last
        for i in (0..n).rev() {
            let lambda = pencil.lambda[i];
            if lambda <= 1e-14 * lambda_max {
                // below round-off: a mode of (numerically) infinite frequency, no static part
                break;
            }
            let phi = pencil.vector(i);
            let w2 = 1.0 / lambda - shift;
            let w2 = if w2.abs() <= 1e-8 * shift {
                0.0
            } else {
                w2.max(0.0)
            };
            let omega = w2.sqrt();
            let scale = 1.0 / lambda.sqrt();
            let gain = phi[(tip, 0)] * scale;
            if omega > omega_cut {
                modes.residual += gain * gain / w2;
                continue;
            }
            let rate: f64 = (0..n).map(|j| phi[(j, 0)] * mv0[j]).sum::<f64>() * scale;
            modes.omegas.push(omega);
            modes.gains.push(gain);
            modes.rates.push(rate);
        }
        Ok(modes)
    }

    /// Number of modes kept.
    pub fn len(&self) -> usize {
        self.omegas.len()
    }

    /// True when no mode is kept.
    pub fn is_empty(&self) -> bool {
        self.omegas.is_empty()
    }

    /// The static tip compliance Σ bᵢ²/ωᵢ² + R over the flexible modes \[m/N\] (∞ with a rigid
    /// mode).
    pub fn static_compliance(&self) -> f64 {
        self.omegas
            .iter()
            .zip(&self.gains)
            .map(|(w, b)| {
                if *w > 0.0 {
                    b * b / (w * w)
                } else {
                    f64::INFINITY
                }
            })
            .sum::<f64>()
            + self.residual
    }
}
