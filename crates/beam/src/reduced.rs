//! A modal-reduced linear beam: the shortcut for small deflections.
//!
//! The displacements are approximated in a Ritz basis, q ≈ Φ η, built from
//! * the lowest `modes` free-vibration modes of the linearised model (K φ = ω² M φ), and
//! * one *static correction* shape per loaded DOF j: the residual flexibility
//!   Σ_{i not kept} φᵢ φᵢᵀ e_j / ωᵢ² (the residual attachment mode of the mode-acceleration /
//!   modal-truncation-augmentation method), so that the static response to loads at those DOFs
//!   is reproduced exactly and the truncated high modes do not leave the contact point too soft.
//!   It is computed as K̃⁻¹ (I − MΦΦᵀ) e_j with the kept modes deflated,
//!   K̃ = K + σ Σ_kept (Mφ)(Mφ)ᵀ, σ = EI/(ρA L⁴): the load is cleared of the kept modes, and on
//!   their M-orthogonal complement K̃ acts as K, while the lift makes K̃ positive definite and
//!   well conditioned even with a rigid mode (pinned root without spring) or a very soft spring.
//!
//! The correction shapes are made M-orthonormal to the modes and to each other (modified
//! Gram–Schmidt, twice; shapes already in the span are dropped), which also makes them
//! K-orthogonal to the modes, and their block of BᵀKB is diagonalised, so every coordinate obeys
//! η̈ᵢ + cᵢ η̇ᵢ + ωᵢ² ηᵢ = φᵢᵀ F(t), cᵢ = a₀ + a₁ ωᵢ² (Rayleigh damping). The kept modes are
//! exact eigenpairs of the full model; the correction shapes become Ritz pairs above them.
//!
//! Time stepping is the same generalized-α scheme as [`crate::dynamics`] (same parameters, same
//! â form, same step-change rescaling), solved in closed form per coordinate: with every mode kept
//! the reduced solution equals the full linear finite-element solution step by step (tested to
//! round-off). A step costs O(r) for r coordinates plus O(r) per nonzero load entry, against a
//! banded factorisation over all DOFs for the full model.
//!
//! Valid where the linear model is: small rotations (the corotational model differs by O(θ²)).

use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::{Mat, Par, Side};

use crate::BeamError;
use crate::dynamics::GeneralizedAlpha;
use crate::modal::{ModalDirection, dense_matrices, modal_analysis};
use crate::model::{BeamModel, NodalLoads};
use crate::node_load::NodeLoad;
use nalgebra::{Matrix3, Vector3};

/// M-norm, relative to the whole static shape, below which a correction shape counts as already
/// in the span of the basis.
const SPAN_TOLERANCE: f64 = 1e-8;

/// The reduced model: Ritz frequencies, damping and M-orthonormal shapes.
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedModel {
    n_dofs: usize,
    /// Length of the beam \[m\] (scales the Newton tolerance).
    length: f64,
    exact_modes: usize,
    /// ωᵢ [rad/s], ascending.
    omegas: Vec<f64>,
    /// cᵢ = a₀ + a₁ ωᵢ² [1/s].
    damping: Vec<f64>,
    /// φᵢ, one full DOF vector per coordinate (constrained entries 0), φᵢᵀ M φⱼ = δᵢⱼ.
    shapes: Vec<Vec<f64>>,
}

/// The state of a reduced model: modal coordinates, their rates and the generalized-α auxiliary
/// acceleration.
#[derive(Debug, Clone, PartialEq)]
pub struct ReducedState {
    /// Time t \[s\].
    pub t: f64,
    /// η [√kg·m].
    pub eta: Vec<f64>,
    /// η̇.
    pub eta_dot: Vec<f64>,
    /// η̈.
    pub eta_ddot: Vec<f64>,
    a_aux: Vec<f64>,
    h_prev: Option<f64>,
}

impl ReducedModel {
    /// Reduces `model` (linearised about the undeformed state) to its lowest `modes` modes plus one
    /// static correction shape for each DOF index in `loaded_dofs` (global indices 3·node + {0: u,
    /// 1: v, 2: θ}). Root dampers (c_θ > 0) are not modal and are rejected; Rayleigh damping is
    /// kept.
    ///
    /// The reduction is linear, so an ANCF model is refused: reduce the same spec with
    /// [`crate::Kinematics::Linear`] (the linearised ANCF element has the same bending stiffness
    /// and mass as the linear Hermite element).
    pub fn new(model: &BeamModel, modes: usize, loaded_dofs: &[usize]) -> Result<Self, BeamError> {
        if model.kinematics() == crate::Kinematics::Ancf {
            return Err(BeamError::invalid(
                "kinematics",
                "ancf",
                "linear or corotational for the modal-reduced (linear) beam: reduce the linear \
                 model of the same beam",
            ));
        }
        let (k_theta, c_theta, _) = model.root().spring_damper_inertia();
        if c_theta != 0.0 {
            return Err(BeamError::invalid(
                "c_theta",
                c_theta,
                "0 for a modal-reduced beam (only Rayleigh damping is modal)",
            ));
        }
        // The full model's a₁ term damps the element deformation rates only, not the root
        // spring: with both, C is not a₀M + a₁K and not modal.
        let a1 = model.spec().damping.beta_stiffness;
        if a1 != 0.0 && k_theta != 0.0 {
            return Err(BeamError::invalid(
                "rayleigh beta_stiffness",
                a1,
                "0 for a modal-reduced beam on a root spring (the stiffness-proportional damping \
                 of the full model leaves the spring out, which is not modal)",
            ));
        }
        let nfix = model.n_fixed();
        let n_dofs = model.n_dofs();
        for &j in loaded_dofs {
            if j < nfix || j >= n_dofs {
                return Err(BeamError::invalid(
                    "loaded DOF",
                    j,
                    format!("a free DOF index from {nfix} to {}", n_dofs - 1),
                ));
            }
        }
        let analysis = modal_analysis(model, modes, ModalDirection::All)?;
        let (k, m) = dense_matrices(model);
        let nf = k.nrows();
        let modes_free: Vec<Vec<f64>> =
            analysis.shapes.iter().map(|s| s[nfix..].to_vec()).collect();
        let mut corrections: Vec<Vec<f64>> = Vec::new();
        for (shape, reference) in residual_shapes(model, &k, &m, &modes_free, loaded_dofs)? {
            let basis: Vec<&Vec<f64>> = modes_free.iter().chain(&corrections).collect();
            if let Some(s) = m_orthonormalised(&m, &basis, shape, reference) {
                corrections.push(s);
            }
        }
        // M-orthogonal to the kept modes means K-orthogonal too (K φ = ω² M φ): the reduced
        // stiffness is diag(ωᵢ²) ⊕ K_cc, and only the correction block needs diagonalising.
        // Its Ritz values lie above ω_k (Rayleigh quotients in the complement of the lowest k).
        let (ritz_omegas, ritz) = diagonalise(&k, &corrections)?;
        let omegas: Vec<f64> = analysis.omegas.iter().copied().chain(ritz_omegas).collect();
        let ritz: Vec<Vec<f64>> = modes_free.into_iter().chain(ritz).collect();
        let spec = model.spec().damping;
        let shapes = ritz
            .into_iter()
            .map(|s| {
                let mut full = vec![0.0; n_dofs];
                full[nfix..nfix + nf].copy_from_slice(&s);
                full
            })
            .collect();
        Ok(ReducedModel {
            n_dofs,
            length: model.length(),
            exact_modes: modes,
            damping: omegas
                .iter()
                .map(|w| spec.alpha_mass + spec.beta_stiffness * w * w)
                .collect(),
            omegas,
            shapes,
        })
    }

    /// Number of modal coordinates r (kept modes plus independent correction shapes).
    pub fn n_coordinates(&self) -> usize {
        self.omegas.len()
    }

    /// Number of exact modes kept.
    pub fn exact_modes(&self) -> usize {
        self.exact_modes
    }

    /// Ritz angular frequencies ωᵢ [rad/s], ascending (the lowest [`Self::exact_modes`] are the
    /// full model's).
    pub fn omegas(&self) -> &[f64] {
        &self.omegas
    }

    /// Shape φᵢ (full DOF vector, M-orthonormal).
    pub fn shape(&self, i: usize) -> &[f64] {
        &self.shapes[i]
    }

    /// Displacement, velocity and acceleration of global DOF `dof` [m or rad, /s, /s²].
    pub fn dof(&self, state: &ReducedState, dof: usize) -> (f64, f64, f64) {
        let mut out = (0.0, 0.0, 0.0);
        for (i, s) in self.shapes.iter().enumerate() {
            out.0 += s[dof] * state.eta[i];
            out.1 += s[dof] * state.eta_dot[i];
            out.2 += s[dof] * state.eta_ddot[i];
        }
        out
    }

    /// Every displacement q = Φ η [m, rad].
    pub fn displacements(&self, state: &ReducedState) -> Vec<f64> {
        let mut q = vec![0.0; self.n_dofs];
        for (s, eta) in self.shapes.iter().zip(&state.eta) {
            for (qj, sj) in q.iter_mut().zip(s) {
                *qj += sj * eta;
            }
        }
        q
    }

    /// Kinetic ½ Σ η̇ᵢ² and strain ½ Σ ωᵢ² ηᵢ² energy \[J\] (exact for q in the span).
    pub fn energy(&self, state: &ReducedState) -> (f64, f64) {
        let kinetic = 0.5 * state.eta_dot.iter().map(|v| v * v).sum::<f64>();
        let strain = 0.5
            * self
                .omegas
                .iter()
                .zip(&state.eta)
                .map(|(w, e)| (w * e).powi(2))
                .sum::<f64>();
        (kinetic, strain)
    }

    /// Generalized forces gᵢ = φᵢᵀ F (only the nonzero entries of F are visited).
    fn generalized_forces(&self, loads: &[f64], out: &mut [f64]) {
        out.iter_mut().for_each(|g| *g = 0.0);
        for (j, &f) in loads.iter().enumerate().filter(|(_, f)| **f != 0.0) {
            for (g, s) in out.iter_mut().zip(&self.shapes) {
                *g += s[j] * f;
            }
        }
    }
}

impl ReducedState {
    /// The undeformed state at rest at t = 0 under `loads` (η̈ = Φᵀ F).
    pub fn at_rest(model: &ReducedModel, loads: &NodalLoads) -> Result<Self, BeamError> {
        check_loads(model, loads)?;
        let r = model.n_coordinates();
        let mut a = vec![0.0; r];
        model.generalized_forces(loads.as_slice(), &mut a);
        Ok(ReducedState {
            t: 0.0,
            eta: vec![0.0; r],
            eta_dot: vec![0.0; r],
            a_aux: a.clone(),
            eta_ddot: a,
            h_prev: None,
        })
    }
}

fn check_loads(model: &ReducedModel, loads: &NodalLoads) -> Result<(), BeamError> {
    let values = loads.as_slice();
    if values.len() != model.n_dofs {
        return Err(BeamError::invalid(
            "loads length",
            values.len(),
            format!("{} entries (3 per node)", model.n_dofs),
        ));
    }
    if let Some(i) = values.iter().position(|v| !v.is_finite()) {
        return Err(BeamError::invalid(
            format!("load at node {} ({})", i / 3, ["fx", "fy", "moment"][i % 3]),
            values[i],
            "a finite number",
        ));
    }
    Ok(())
}

impl GeneralizedAlpha {
    /// Advances a reduced `state` by `h` \[s\] (> 0, finite) with `loads` acting at t + h: the
    /// scheme of [`GeneralizedAlpha::step`] in closed form per modal coordinate,
    /// â_{n+1} [(1 − α_m)/(1 − α_f) + cγh + ω²βh²] = g_{n+1} − (α_m â_n − α_f η̈_n)/(1 − α_f)
    /// − c (η̇_n + (1 − γ) h â_n) − ω² (η_n + h η̇_n + (½ − β) h² â_n).
    pub fn step_reduced(
        &self,
        model: &ReducedModel,
        state: &mut ReducedState,
        h: f64,
        loads: &NodalLoads,
    ) -> Result<(), BeamError> {
        self.step_reduced_with(model, state, h, loads, None)
    }

    /// [`GeneralizedAlpha::step_reduced`] with a motion-dependent `node_load` treated
    /// implicitly: its generalized force Φ_kᵀ F(q_k, q̇_k) at the node's DOFs k couples the
    /// coordinates, and Newton solves D x − Φ_kᵀ F = b for the auxiliary accelerations x, with
    /// D = diag(lhsᵢ) and the iteration matrix D − Φ_kᵀ (βh² ∂F/∂q + γh ∂F/∂q̇) Φ_k: diagonal
    /// plus rank 3, solved through a 3×3 system (O(r) per iteration). Converged when the node
    /// moves by at most the Newton tolerance between iterations.
    pub fn step_reduced_with(
        &self,
        model: &ReducedModel,
        state: &mut ReducedState,
        h: f64,
        loads: &NodalLoads,
        node_load: Option<&mut dyn NodeLoad>,
    ) -> Result<(), BeamError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(BeamError::invalid("time step", h, "a finite number > 0"));
        }
        check_loads(model, loads)?;
        if state.eta.len() != model.n_coordinates() {
            return Err(BeamError::invalid(
                "reduced state length",
                state.eta.len(),
                format!("{} (the model's modal coordinates)", model.n_coordinates()),
            ));
        }
        if let Some(nl) = node_load.as_deref()
            && 3 * nl.node() + 2 >= model.n_dofs
        {
            return Err(BeamError::invalid(
                "node load node",
                nl.node(),
                format!("a node index from 0 to {} (the tip)", model.n_dofs / 3 - 1),
            ));
        }
        let (am, af, g, b) = self.parameters();
        let rescale = match state.h_prev {
            Some(hp) if hp != h => h / hp,
            _ => 1.0,
        };
        let r = model.n_coordinates();
        let mut forces = vec![0.0; r];
        model.generalized_forces(loads.as_slice(), &mut forces);
        // Per coordinate: η = Q + βh² x, η̇ = V + γh x, and lhs x = rhs (+ the node load).
        let mut q_base = vec![0.0; r];
        let mut v_base = vec![0.0; r];
        let mut lhs = vec![0.0; r];
        let mut rhs = vec![0.0; r];
        let mut a_hat = vec![0.0; r];
        for i in 0..r {
            let (w2, c) = (model.omegas[i] * model.omegas[i], model.damping[i]);
            let (q, v, a) = (state.eta[i], state.eta_dot[i], state.eta_ddot[i]);
            // â_n ≈ q̈(t_n + (α_m − α_f) h): rescale its offset from q̈_n when h changes.
            let ah = a + (state.a_aux[i] - a) * rescale;
            a_hat[i] = ah;
            q_base[i] = q + h * v + (0.5 - b) * h * h * ah;
            v_base[i] = v + (1.0 - g) * h * ah;
            lhs[i] = (1.0 - am) / (1.0 - af) + c * g * h + w2 * b * h * h;
            rhs[i] = forces[i] - (am * ah - af * a) / (1.0 - af) - c * v_base[i] - w2 * q_base[i];
        }
        let x = match node_load {
            None => (0..r).map(|i| rhs[i] / lhs[i]).collect(),
            Some(nl) => {
                let coupled = Coupled {
                    model,
                    t: state.t + h,
                    h,
                    beta: b,
                    gamma: g,
                    q_base: &q_base,
                    v_base: &v_base,
                    lhs: &lhs,
                    rhs: &rhs,
                };
                let (max_iterations, tolerance) = self.newton_limits();
                coupled.solve(
                    nl,
                    a_hat.clone(),
                    (max_iterations, tolerance * model.length),
                )?
            }
        };
        let mut next = state.clone();
        for i in 0..r {
            let (ah, a) = (a_hat[i], state.eta_ddot[i]);
            next.eta[i] = q_base[i] + b * h * h * x[i];
            next.eta_dot[i] = v_base[i] + g * h * x[i];
            next.eta_ddot[i] = ((1.0 - am) * x[i] + am * ah - af * a) / (1.0 - af);
            next.a_aux[i] = x[i];
        }
        // A failed step leaves `state` unchanged (as the full model's step does).
        if let Some(i) = (0..r).find(|&i| {
            !(next.eta[i].is_finite()
                && next.eta_dot[i].is_finite()
                && next.eta_ddot[i].is_finite())
        }) {
            return Err(BeamError::NonFinite {
                what: format!("modal coordinate {i}"),
            });
        }
        next.h_prev = Some(h);
        *state = next;
        state.t += h;
        Ok(())
    }
}

/// For each loaded DOF j: the residual flexibility shape K̃⁻¹ (I − MΦΦᵀ) e_j over the free DOFs
/// (see the module docs) and, as the scale against which it counts as significant, the M-norm of
/// the whole static shape K̃⁻¹ e_j.
fn residual_shapes(
    model: &BeamModel,
    k: &Mat<f64>,
    m: &Mat<f64>,
    kept: &[Vec<f64>],
    loaded_dofs: &[usize],
) -> Result<Vec<(Vec<f64>, f64)>, BeamError> {
    let nfix = model.n_fixed();
    let n = k.nrows();
    let sec = model.section();
    let sigma = sec.ei() / (sec.rho_a() * model.length().powi(4));
    let m_phi: Vec<Vec<f64>> = kept.iter().map(|phi| m_times(m, phi)).collect();
    let lifted = Mat::from_fn(n, n, |i, j| {
        k[(i, j)] + sigma * m_phi.iter().map(|v| v[i] * v[j]).sum::<f64>()
    });
    let llt = lifted
        .llt(Side::Lower)
        .map_err(|e| BeamError::Eigen(format!("Cholesky of the deflated K failed: {e:?}")))?;
    let l = llt.L();
    let solve = |rhs: &[f64]| -> Vec<f64> {
        let mut x = Mat::from_fn(n, 1, |i, _| rhs[i]);
        solve_lower_triangular_in_place(l, x.as_mut(), Par::Seq);
        solve_upper_triangular_in_place(l.transpose(), x.as_mut(), Par::Seq);
        (0..n).map(|i| x[(i, 0)]).collect()
    };
    Ok(loaded_dofs
        .iter()
        .map(|&j| {
            let e: Vec<f64> = (0..n)
                .map(|i| if i + nfix == j { 1.0 } else { 0.0 })
                .collect();
            let whole = solve(&e);
            let reference = m_dot(m, &whole, &whole).sqrt();
            // (I − MΦΦᵀ) e_j: φᵀ e_j is the j-th entry of φ.
            let mut load = e;
            for (phi, mp) in kept.iter().zip(&m_phi) {
                let c = phi[j - nfix];
                load.iter_mut().zip(mp).for_each(|(l, v)| *l -= c * v);
            }
            (solve(&load), reference)
        })
        .collect())
}

fn m_times(m: &Mat<f64>, x: &[f64]) -> Vec<f64> {
    (0..x.len())
        .map(|i| (0..x.len()).map(|j| m[(i, j)] * x[j]).sum())
        .collect()
}

fn m_dot(m: &Mat<f64>, x: &[f64], y: &[f64]) -> f64 {
    let n = x.len();
    let mut s = 0.0;
    for i in 0..n {
        let mut row = 0.0;
        for j in 0..n {
            row += m[(i, j)] * y[j];
        }
        s += x[i] * row;
    }
    s
}

/// `shape` made M-orthogonal to `basis` (modified Gram–Schmidt, twice) and M-normalised; `None`
/// when what is left is below [`SPAN_TOLERANCE`] of `reference` (the M-norm of the whole static
/// shape: the correction adds nothing significant, e.g. every mode is kept).
fn m_orthonormalised(
    m: &Mat<f64>,
    basis: &[&Vec<f64>],
    mut shape: Vec<f64>,
    reference: f64,
) -> Option<Vec<f64>> {
    if reference.is_nan() || reference <= 0.0 {
        return None;
    }
    for _ in 0..2 {
        for b in basis {
            let c = m_dot(m, b, &shape);
            shape
                .iter_mut()
                .zip(b.iter())
                .for_each(|(s, bj)| *s -= c * bj);
        }
    }
    let norm = m_dot(m, &shape, &shape).sqrt();
    if norm.is_nan() || norm <= SPAN_TOLERANCE * reference {
        return None;
    }
    shape.iter_mut().for_each(|s| *s /= norm);
    Some(shape)
}

/// Eigen-decomposition of the reduced stiffness Bᵀ K B of an M-orthonormal basis B: ascending
/// ωᵢ and the Ritz vectors B ψᵢ.
fn diagonalise(k: &Mat<f64>, basis: &[Vec<f64>]) -> Result<(Vec<f64>, Vec<Vec<f64>>), BeamError> {
    let r = basis.len();
    if r == 0 {
        return Ok((Vec::new(), Vec::new()));
    }
    let kb: Vec<Vec<f64>> = basis
        .iter()
        .map(|b| {
            (0..b.len())
                .map(|i| (0..b.len()).map(|j| k[(i, j)] * b[j]).sum())
                .collect()
        })
        .collect();
    let kr = Mat::from_fn(r, r, |i, j| {
        let a: f64 = basis[i].iter().zip(&kb[j]).map(|(x, y)| x * y).sum();
        let b: f64 = basis[j].iter().zip(&kb[i]).map(|(x, y)| x * y).sum();
        0.5 * (a + b)
    });
    let evd = kr
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| BeamError::Eigen(format!("reduced stiffness: {e:?}")))?;
    let (s, u) = (evd.S(), evd.U());
    let mut order: Vec<usize> = (0..r).collect();
    order.sort_by(|&a, &b| s[a].total_cmp(&s[b]));
    let n = basis.first().map_or(0, Vec::len);
    let mut omegas = Vec::with_capacity(r);
    let mut shapes = Vec::with_capacity(r);
    for idx in order {
        omegas.push(s[idx].max(0.0).sqrt());
        shapes.push(
            (0..n)
                .map(|d| (0..r).map(|c| basis[c][d] * u[(c, idx)]).sum())
                .collect(),
        );
    }
    Ok((omegas, shapes))
}

/// The coordinates coupled by a node load: D x − Φ_kᵀ F(q_k(x), q̇_k(x)) = b.
struct Coupled<'a> {
    model: &'a ReducedModel,
    t: f64,
    h: f64,
    beta: f64,
    gamma: f64,
    q_base: &'a [f64],
    v_base: &'a [f64],
    lhs: &'a [f64],
    rhs: &'a [f64],
}

impl Coupled<'_> {
    /// Newton from `x`; (maximum iterations, tolerance \[m or rad\] on the node's motion).
    fn solve(
        &self,
        node_load: &mut dyn NodeLoad,
        mut x: Vec<f64>,
        (max_iterations, tolerance): (usize, f64),
    ) -> Result<Vec<f64>, BeamError> {
        let k = 3 * node_load.node();
        let shapes = &self.model.shapes;
        let r = x.len();
        let (bh2, gh) = (self.beta * self.h * self.h, self.gamma * self.h);
        let node_motion = |x: &[f64]| {
            let (mut q, mut v) = ([0.0; 3], [0.0; 3]);
            for (i, s) in shapes.iter().enumerate() {
                for d in 0..3 {
                    q[d] += s[k + d] * (self.q_base[i] + bh2 * x[i]);
                    v[d] += s[k + d] * (self.v_base[i] + gh * x[i]);
                }
            }
            (q, v)
        };
        let mut residual = vec![0.0; r];
        for iteration in 0..=max_iterations {
            let (q, v) = node_motion(&x);
            let f = node_load.evaluate(self.t, q, v);
            if !f.is_finite() {
                return Err(BeamError::NonFinite {
                    what: "node load".into(),
                });
            }
            for i in 0..r {
                let generalized: f64 = (0..3).map(|d| shapes[i][k + d] * f.force[d]).sum();
                residual[i] = self.lhs[i] * x[i] - self.rhs[i] - generalized;
            }
            if iteration == max_iterations {
                return Err(BeamError::NotConverged {
                    solver: "modal-reduced generalized-α step".into(),
                    load_level: 1.0,
                    iterations: iteration,
                    residual: residual.iter().fold(0.0f64, |m, x: &f64| m.max(x.abs())),
                });
            }
            // J Δ = −R with J = D − U C Uᵀ, U = Φ_kᵀ (r×3), C = βh² ∂F/∂q + γh ∂F/∂q̇:
            // y = UᵀΔ solves (I − UᵀD⁻¹U C) y = Uᵀ D⁻¹ (−R), then Δ = D⁻¹(−R + U C y).
            let c = Matrix3::from_fn(|i, j| bh2 * f.d_dq[i][j] + gh * f.d_dv[i][j]);
            let mut utdu = Matrix3::zeros();
            let mut utdr = Vector3::zeros();
            for i in 0..r {
                let u = Vector3::new(shapes[i][k], shapes[i][k + 1], shapes[i][k + 2]);
                utdu += u * u.transpose() / self.lhs[i];
                utdr -= u * (residual[i] / self.lhs[i]);
            }
            let y = (Matrix3::identity() - utdu * c)
                .lu()
                .solve(&utdr)
                .ok_or_else(|| BeamError::Singular {
                    what: "modal-reduced node-load iteration matrix".into(),
                    dof: k,
                    hint: "the node load's stiffness cancels the beam's".into(),
                })?;
            let cy = c * y;
            let mut moved = [0.0f64; 3];
            for i in 0..r {
                let u = Vector3::new(shapes[i][k], shapes[i][k + 1], shapes[i][k + 2]);
                let delta = (-residual[i] + u.dot(&cy)) / self.lhs[i];
                x[i] += delta;
                for d in 0..3 {
                    moved[d] += u[d] * bh2 * delta;
                }
            }
            let step = moved.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            if !step.is_finite() {
                return Err(BeamError::NonFinite {
                    what: "modal coordinates".into(),
                });
            }
            if step <= tolerance {
                return Ok(x);
            }
        }
        unreachable!("the loop returns at the last iteration")
    }
}
