//! Natural frequencies and mode shapes: K φ = ω² M φ about the undeformed state.
//!
//! Method (dense, faer): with a positive shift σ = EI/(ρA L⁴) the pencil is rewritten as
//! M φ = λ (K + σM) φ, λ = 1/(ω² + σ); K + σM = L Lᵀ (faer Cholesky) is positive definite even
//! with rigid modes (pinned root) or massless rotational DOFs, and
//! C = L⁻¹ M L⁻ᵀ ψ = λ ψ is a symmetric standard problem (faer self-adjoint eigensolver).
//! Then ω² = 1/λ − σ (reported as 0 when |ω²| ≤ 1e-9 σ: a rigid mode) and φ = L⁻ᵀ ψ, scaled
//! to φᵀ M φ = 1. Dense O(n³): meant for n up to a few thousand DOFs.

use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};
use serde::{Deserialize, Serialize};

use crate::BeamError;
use crate::assembly::{JacobianWeights, Kinematic, assemble, band_for};
use crate::model::{BeamModel, Kinematics};

/// Which DOFs take part (the undeformed straight beam decouples axial and transverse motion).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ModalDirection {
    /// Bending: v and θ (u held; ANCF: v and r′ᵧ, u and r′ₓ held).
    Transverse,
    /// Axial: u only (ANCF: u and r′ₓ).
    Axial,
    /// Every free DOF.
    All,
}

/// The lowest modes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModalAnalysis {
    /// Angular frequencies ω [rad/s], ascending.
    pub omegas: Vec<f64>,
    /// Frequencies f = ω/2π \[Hz\].
    pub frequencies_hz: Vec<f64>,
    /// Mass-normalised mode shapes, one full DOF vector (constrained entries 0) per mode.
    pub shapes: Vec<Vec<f64>>,
}

/// Largest mesh for the dense eigen solve: 3000 DOFs, 72 MB per matrix, a few seconds.
pub const MAX_MODAL_ELEMENTS: usize = 1000;

/// Dense K and M over the free DOFs of the model linearised about the undeformed state (the
/// linear element for the corotational model; the ANCF element's own tangent and mass for ANCF).
pub fn dense_matrices(model: &BeamModel) -> (Mat<f64>, Mat<f64>) {
    let lin = match model.kinematics() {
        Kinematics::Ancf => model.clone(),
        _ => model.with_kinematics(Kinematics::Linear),
    };
    let n = lin.n_dofs();
    let zeros = vec![0.0; n];
    let no_loads = vec![0.0; 3 * lin.n_nodes()];
    let mut r = vec![0.0; n];
    let mut band = band_for(&lin);
    let mut out = Vec::new();
    for w in [
        JacobianWeights {
            stiffness: 1.0,
            velocity: 0.0,
            acceleration: 0.0,
        },
        JacobianWeights {
            stiffness: 0.0,
            velocity: 0.0,
            acceleration: 1.0,
        },
    ] {
        let kin = Kinematic {
            q: &zeros,
            v: Some(&zeros),
            a: Some(&zeros),
        };
        assemble(&lin, kin, &no_loads, &mut r, Some((&mut band, w)));
        let nf = band.n();
        out.push(Mat::from_fn(nf, nf, |i, j| band.get(i, j)));
    }
    let m = out.pop().unwrap();
    let k = out.pop().unwrap();
    (k, m)
}

/// The symmetric pencil M φ = λ (K + σM) φ of dense K and M with a shift σ > 0 (K + σM positive
/// definite): λ = 1/(ω² + σ), ascending, so the lowest modes have the largest λ and carry only
/// round-off relative to themselves however stiff the highest ones are. K + σM = L Lᵀ (faer
/// Cholesky), C = L⁻¹ M L⁻ᵀ = Ψ Λ Ψᵀ (faer's self-adjoint eigensolver), φ = L⁻ᵀ ψ with
/// φᵀ (K + σM) φ = 1, hence φᵀ M φ = λ.
pub struct ShiftedPencil {
    /// λᵢ = 1/(ωᵢ² + σ), ascending.
    pub lambda: Vec<f64>,
    l: Mat<f64>,
    psi: Mat<f64>,
}

impl ShiftedPencil {
    /// Solves the pencil of `k` and `m` (n × n, symmetric) with shift `sigma` [1/s²].
    pub fn solve(k: &Mat<f64>, m: &Mat<f64>, sigma: f64) -> Result<ShiftedPencil, BeamError> {
        let n = k.nrows();
        let a = Mat::from_fn(n, n, |i, j| k[(i, j)] + sigma * m[(i, j)]);
        let llt = a
            .llt(Side::Lower)
            .map_err(|e| BeamError::Eigen(format!("Cholesky of K + σM failed: {e:?}")))?;
        let l = llt.L().to_owned();
        // C = L⁻¹ (L⁻¹ M)ᵀ
        let mut x = m.clone();
        solve_lower_triangular_in_place(l.as_ref(), x.as_mut(), Par::Seq);
        let mut c = x.transpose().to_owned();
        solve_lower_triangular_in_place(l.as_ref(), c.as_mut(), Par::Seq);
        let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]));
        let evd = c
            .self_adjoint_eigen(Side::Lower)
            .map_err(|e| BeamError::Eigen(format!("{e:?}")))?;
        let s = evd.S();
        Ok(ShiftedPencil {
            lambda: (0..n).map(|i| s[i]).collect(),
            l,
            psi: evd.U().to_owned(),
        })
    }

    /// φᵢ = L⁻ᵀ ψᵢ (an n × 1 column), φᵢᵀ (K + σM) φᵢ = 1.
    pub fn vector(&self, i: usize) -> Mat<f64> {
        let n = self.psi.nrows();
        let mut phi = Mat::from_fn(n, 1, |r, _| self.psi[(r, i)]);
        solve_upper_triangular_in_place(self.l.transpose(), phi.as_mut(), Par::Seq);
        phi
    }
}

/// The lowest `modes` modes of `model` in `direction`.
pub fn modal_analysis(
    model: &BeamModel,
    modes: usize,
    direction: ModalDirection,
) -> Result<ModalAnalysis, BeamError> {
    if modes == 0 {
        return Err(BeamError::invalid("modes", modes, "an integer ≥ 1"));
    }
    if model.n_elements() > MAX_MODAL_ELEMENTS {
        return Err(BeamError::invalid(
            "elements",
            model.n_elements(),
            format!("at most {MAX_MODAL_ELEMENTS} for the dense modal analysis"),
        ));
    }
    let nfix = model.n_fixed();
    let (k_all, m_all) = dense_matrices(model);
    // axial components: u (and r′ₓ for ANCF); transverse: v and θ (ANCF: r′ᵧ)
    let dpn = model.dofs_per_node();
    let keep: Vec<usize> = (0..model.n_free())
        .filter(|&i| {
            let c = (i + nfix) % dpn;
            let axial = c == 0 || c == 3;
            match direction {
                ModalDirection::Transverse => !axial,
                ModalDirection::Axial => axial,
                ModalDirection::All => true,
            }
        })
        .collect();
    let n = keep.len();
    if modes > n {
        return Err(BeamError::invalid(
            "modes",
            modes,
            format!("at most {n} (the DOFs of this mesh in that direction)"),
        ));
    }
    let k = Mat::from_fn(n, n, |i, j| k_all[(keep[i], keep[j])]);
    let m = Mat::from_fn(n, n, |i, j| m_all[(keep[i], keep[j])]);
    let sec = model.section();
    let sigma = sec.ei() / (sec.rho_a() * model.length().powi(4));
    let pencil = ShiftedPencil::solve(&k, &m, sigma)?;
    let lam_max = pencil.lambda.iter().copied().fold(0.0f64, f64::max);
    let mut omegas = Vec::new();
    let mut shapes = Vec::new();
    // λ ascending: lowest frequencies at the end.
    for idx in (0..n).rev() {
        if omegas.len() == modes {
            break;
        }
        let lam = pencil.lambda[idx];
        if lam <= lam_max * 1e-13 {
            break; // massless DOFs: infinite frequency
        }
        let w2 = 1.0 / lam - sigma;
        let w2 = if w2.abs() <= 1e-9 * sigma {
            0.0
        } else {
            w2.max(0.0)
        };
        let psi = pencil.vector(idx);
        let mut mphi = 0.0;
        for i in 0..n {
            for j in 0..n {
                mphi += psi[(i, 0)] * m[(i, j)] * psi[(j, 0)];
            }
        }
        let scale = 1.0 / mphi.sqrt();
        let mut shape = vec![0.0; model.n_dofs()];
        for (i, &g) in keep.iter().enumerate() {
            shape[g + nfix] = psi[(i, 0)] * scale;
        }
        omegas.push(w2.sqrt());
        shapes.push(shape);
    }
    if omegas.len() < modes {
        return Err(BeamError::invalid(
            "modes",
            modes,
            format!("at most {} (the DOFs that carry mass)", omegas.len()),
        ));
    }
    let frequencies_hz = omegas
        .iter()
        .map(|w| w / (2.0 * std::f64::consts::PI))
        .collect();
    Ok(ModalAnalysis {
        omegas,
        frequencies_hz,
        shapes,
    })
}
