//! Pseudo-Rigid-Body (PRB) model of a cantilever with a perpendicular dead end load, fitted to
//! the corotational FE tip path the way Howell does ("Compliant Mechanisms", 2001, §5.1).
//!
//! The PRB model replaces the beam by a rigid segment (1 − γ)L from the root, a pin with a
//! torsion spring k = γ K_Θ EI/L, and a rigid link γL to the tip, at the PRB angle Θ:
//! a/L = 1 − γ(1 − cos Θ), b/L = γ sin Θ.
//!
//! **γ.** For a trial γ, each FE tip point (a, b) gives Θ = atan2(b, a − (1 − γ)L) and the tip
//! position error e = | |(a − (1 − γ)L, b)| − γL | (its distance to the PRB circle, i.e. to
//! the PRB tip at the same Θ), relative either to the tip deflection δ = |(L − a, b)| (Howell's
//! measure, [`ErrorMeasure::Deflection`]) or to L ([`ErrorMeasure::Length`]).
//! Θ_max(γ) is the largest Θ up to which e ≤ 0.5 % (linear
//! interpolation between traced points); γ maximises Θ_max(γ) (grid of step 1e-4, then golden
//! section).
//!
//! **K_Θ.** Moment balance about the pin: K_Θ Θ = (PL²/EI) cos Θ. K_Θ is the least-squares slope
//! through the origin over 0 < Θ ≤ Θ_max, uniform in Θ (trapezoidal weights wᵢ):
//! K_Θ = Σ wᵢ Θᵢ Φᵢ cos Θᵢ / Σ wᵢ Θᵢ², Φ = PL²/EI (Howell's book quotes 2.67617; this
//! continuous fit gives ≈ 2.70, depending on the weighting).
//!
//! **Small-deflection limit.** From the smallest traced load: γ₀ = (b/L)/θ_tip (→ 2/3) and
//! K_Θ0 = Φ/θ_tip (→ 2).

use serde::{Deserialize, Serialize};

use crate::BeamError;
use crate::canonical::unit_cantilever;
use crate::model::{Kinematics, NodalLoads};
use crate::statics::{StaticOptions, solve_static_from};

/// Tip-position error limit: 0.5 % (Howell).
pub const TIP_ERROR_LIMIT: f64 = 0.005;

/// What the tip-position error is relative to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorMeasure {
    /// Relative to the tip deflection δ = |(L − a, b)| (Howell 1995; reproduces γ = 0.8517,
    /// Θ_max ≈ 64.3°).
    Deflection,
    /// Relative to the beam length L (a looser criterion at small Θ; gives a larger γ).
    Length,
}

/// One traced point of the FE tip path (nondimensional).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TipPoint {
    /// Load index Φ = PL²/EI.
    pub load_index: f64,
    /// Horizontal tip position a/L (1 − axial shortening).
    pub a: f64,
    /// Vertical tip deflection b/L.
    pub b: f64,
    /// Tip slope angle \[rad\].
    pub tip_angle: f64,
}

/// Traces the tip path of the unit corotational cantilever (L = 1, EI = 1, EA = 1e7) with
/// `elements` elements for Φ = PL²/EI in `load_indices` (ascending, > 0), by continuation.
pub fn trace_tip_path(elements: usize, load_indices: &[f64]) -> Result<Vec<TipPoint>, BeamError> {
    trace_tip_path_with(Kinematics::Corotational, elements, load_indices)
}

/// [`trace_tip_path`] with the large-deflection element `kinematics` (corotational or ANCF;
/// the ANCF path is O(h⁴) accurate, the corotational O(h²)).
pub fn trace_tip_path_with(
    kinematics: Kinematics,
    elements: usize,
    load_indices: &[f64],
) -> Result<Vec<TipPoint>, BeamError> {
    let model = unit_cantilever(elements, kinematics)?;
    let mut q = vec![0.0; model.n_dofs()];
    let mut prev = NodalLoads::zeros(&model);
    let mut last_phi = 0.0;
    let mut out = Vec::with_capacity(load_indices.len());
    for &phi in load_indices {
        if !(phi.is_finite() && phi > last_phi) {
            return Err(BeamError::invalid(
                "load index",
                phi,
                "finite, positive and ascending",
            ));
        }
        let mut loads = NodalLoads::zeros(&model);
        loads.set_force(model.tip_node(), 0.0, phi)?;
        let steps = (((phi - last_phi) / 0.5).ceil() as usize).max(1);
        let sol = solve_static_from(
            &model,
            &prev,
            &q,
            &loads,
            &StaticOptions::with_load_steps(steps)?,
        )?;
        let (u, v, th) = sol.node(model.tip_node());
        out.push(TipPoint {
            load_index: phi,
            a: 1.0 + u,
            b: v,
            tip_angle: th,
        });
        q = sol.q;
        prev = loads;
        last_phi = phi;
    }
    Ok(out)
}

/// PRB angle Θ \[rad\] and tip error of `p` for a characteristic radius `gamma`, relative to L
/// or to the tip deflection.
pub fn prb_angle_and_error(p: &TipPoint, gamma: f64, measure: ErrorMeasure) -> (f64, f64) {
    let x = p.a - (1.0 - gamma);
    let theta = p.b.atan2(x);
    let err = (x.hypot(p.b) - gamma).abs();
    match measure {
        ErrorMeasure::Length => (theta, err),
        ErrorMeasure::Deflection => (theta, err / (1.0 - p.a).hypot(p.b)),
    }
}

/// Θ_max(γ) \[rad\]: the PRB angle up to which the error stays ≤ [`TIP_ERROR_LIMIT`] (the last
/// traced Θ if it never exceeds it).
pub fn theta_max(path: &[TipPoint], gamma: f64, measure: ErrorMeasure) -> f64 {
    let mut prev = (0.0, 0.0);
    for p in path {
        let (th, e) = prb_angle_and_error(p, gamma, measure);
        if e > TIP_ERROR_LIMIT {
            let s = (TIP_ERROR_LIMIT - prev.1) / (e - prev.1);
            return prev.0 + s * (th - prev.0);
        }
        prev = (th, e);
    }
    prev.0
}

/// The fitted PRB parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PrbFit {
    /// Characteristic radius γ.
    pub gamma: f64,
    /// Stiffness coefficient K_Θ (least squares, see the module docs).
    pub k_theta: f64,
    /// Parametric limit Θ_max \[deg\].
    pub theta_max_deg: f64,
    /// Small-deflection γ₀ from the smallest load.
    pub gamma_small: f64,
    /// Small-deflection K_Θ0 from the smallest load.
    pub k_theta_small: f64,
    /// Θ_max \[deg\] of Howell's γ = 0.8517 on this path.
    pub theta_max_deg_howell_gamma: f64,
}

/// Fits (γ, K_Θ) to a traced tip path (at least 3 points, ascending loads).
pub fn fit_prb(path: &[TipPoint], measure: ErrorMeasure) -> Result<PrbFit, BeamError> {
    if path.len() < 3 {
        return Err(BeamError::invalid(
            "path length",
            path.len(),
            "at least 3 traced points",
        ));
    }
    let (lo, hi) = (0.5, 1.0);
    let mut best = (lo, theta_max(path, lo, measure));
    let n = 5000;
    for i in 0..=n {
        let g = lo + (hi - lo) * i as f64 / n as f64;
        let t = theta_max(path, g, measure);
        if t > best.1 {
            best = (g, t);
        }
    }
    // golden-section refinement around the best grid point
    let h = (hi - lo) / n as f64;
    let (mut a, mut b) = (best.0 - h, best.0 + h);
    let r = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..60 {
        let c = b - r * (b - a);
        let d = a + r * (b - a);
        if theta_max(path, c, measure) >= theta_max(path, d, measure) {
            b = d;
        } else {
            a = c;
        }
    }
    let g_ref = 0.5 * (a + b);
    let gamma = if theta_max(path, g_ref, measure) >= best.1 {
        g_ref
    } else {
        best.0
    };
    let th_max = theta_max(path, gamma, measure);
    // least squares uniform in Θ: trapezoidal weights wᵢ = (Θᵢ₊₁ − Θᵢ₋₁)/2
    let thetas: Vec<f64> = path
        .iter()
        .map(|p| prb_angle_and_error(p, gamma, measure).0)
        .collect();
    let (mut num, mut den) = (0.0, 0.0);
    for (i, p) in path.iter().enumerate() {
        let th = thetas[i];
        if th <= th_max {
            let lo = if i == 0 { 0.0 } else { thetas[i - 1] };
            let hi = thetas.get(i + 1).copied().unwrap_or(th).min(th_max);
            let w = 0.5 * (hi - lo);
            num += w * th * p.load_index * th.cos();
            den += w * th * th;
        }
    }
    let p0 = path[0];
    Ok(PrbFit {
        gamma,
        k_theta: num / den,
        theta_max_deg: th_max.to_degrees(),
        gamma_small: p0.b / p0.tip_angle,
        k_theta_small: p0.load_index / p0.tip_angle,
        theta_max_deg_howell_gamma: theta_max(path, crate::canonical::HOWELL_GAMMA, measure)
            .to_degrees(),
    })
}

/// The default load indices of the trace: Φ = 0.01, then 0.05 … 30 in steps of 0.05.
pub fn default_load_indices() -> Vec<f64> {
    let mut v = vec![0.01];
    v.extend((1..=600).map(|i| 0.05 * i as f64));
    v
}
