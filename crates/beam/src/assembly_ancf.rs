//! Assembly for the ANCF cable model ([`crate::model::Kinematics::Ancf`]).
//!
//! Node `i` carries the displacements (u, v, r′ᵧ, r′ₓ − 1) at `4i … 4i+3` (constrained DOFs
//! first at the root: clamped u, v, r′ᵧ; pinned u, v). The residual is that of
//! [`crate::assembly`]:
//! r = f_int(q) + a₀ M q̇ + a₁ K_m(q) q̇ + M q̈ + f_root − f_ext,
//! with the constant consistent mass M, the material matrix K_m of [`crate::ancf`] (Rayleigh
//! damping of the strain rates: no damping of rigid motion), and in node terms:
//! * a point mass m on (u, v) and its rotary inertia J on both slope DOFs: ½ J |ṙ′|², which is
//!   ½ J θ̇² exactly while the slope keeps unit length and differs by O(ε) (the axial strain,
//!   ≈ 1e-6 for the CL link) otherwise, so that M stays constant;
//! * the root spring and damper on θ₀ = atan2(r′ᵧ, r′ₓ) (valid for |θ₀| < π), hub inertia as a
//!   point rotary inertia at node 0;
//! * the dead force (fx, fy) on (u, v) and the dead moment m on the slope,
//!   m ∂θ/∂r′ = m (−r′ᵧ, r′ₓ)/|r′|², with its load stiffness −m ∂²θ/∂r′² in the tangent.
//!
//! **Discrete gradient** (energy-conserving step, [`crate::energy_conserving`]). With a
//! [`Discrete`] the elastic force of each element (and of the root spring) is Gonzalez's
//! discrete gradient between q₀ and q₁ = q₀ + Δq,
//! f̄ = ∇U(q_mid) + [U(q₁) − U(q₀) − ∇U(q_mid)·Δq] W Δq / (Δqᵀ W Δq),
//! W = diag(1, 1, l², l², …) (slopes scaled to lengths), so that f̄·Δq = U(q₁) − U(q₀) exactly,
//! and a moment m does the work m (θ₁ − θ₀) through the discrete gradient of θ.

use nalgebra::Vector2;

use crate::ancf::{
    AncfElement, AncfEvaluation, Matrix8, PACKED, SlotBlocks, Vector8, Want, slope_angle,
};
use crate::banded::BandMatrix;
use crate::element::lumped_mass;
use crate::evaluation::{JacobianWeights, Kinematic};
use crate::model::{BeamModel, MassMatrix};

/// Global DOF (relative to 4e) of element coordinate k (slot order r₁, r₁′, r₂, r₂′; x, y).
pub const ELEMENT_DOFS: [usize; 8] = [0, 1, 3, 2, 4, 5, 7, 6];

/// Element coordinate of global DOF 4e + k (the inverse of [`ELEMENT_DOFS`], which swaps the
/// two slope entries of each node, so it is its own inverse).
const PERMUTE: [usize; 8] = ELEMENT_DOFS;

/// Offsets of the slope DOFs (r′ₓ, r′ᵧ) within a node.
pub const SLOPE_X: usize = 3;
/// Offset of r′ᵧ within a node.
pub const SLOPE_Y: usize = 2;

/// The element of a model.
pub fn element_of(model: &BeamModel) -> &AncfElement {
    &model.ancf_parts().element
}

#[inline(always)]
fn gather(x: &[f64], e: usize) -> Vector8 {
    let x: &[f64; 8] = x[4 * e..4 * e + 8].try_into().expect("element DOFs");
    Vector8::from_fn(|k, _| x[ELEMENT_DOFS[k]])
}

/// Absolute slope (r′ₓ, r′ᵧ) of node `i` from the displacements `q`.
pub fn slope(q: &[f64], i: usize) -> (f64, f64) {
    (1.0 + q[4 * i + SLOPE_X], q[4 * i + SLOPE_Y])
}

/// (u, v, θ) of node `i`.
pub fn node_uvt(q: &[f64], i: usize) -> [f64; 3] {
    let (sx, sy) = slope(q, i);
    [q[4 * i], q[4 * i + 1], sy.atan2(sx)]
}

/// (u̇, v̇, θ̇) of node `i`, θ̇ = ∂θ/∂r′ · ṙ′.
pub fn node_uvt_rate(q: &[f64], v: &[f64], i: usize) -> [f64; 3] {
    let (sx, sy) = slope(q, i);
    let (_, g, _) = slope_angle(sx, sy);
    [
        v[4 * i],
        v[4 * i + 1],
        g[0] * v[4 * i + SLOPE_X] + g[1] * v[4 * i + SLOPE_Y],
    ]
}

/// (ü, v̈, θ̈) of node `i`, θ̈ = ∂θ/∂r′ · r̈′ + ṙ′ᵀ ∂²θ/∂r′² ṙ′.
pub fn node_uvt_acceleration(q: &[f64], v: &[f64], a: &[f64], i: usize) -> [f64; 3] {
    let (sx, sy) = slope(q, i);
    let (_, g, h) = slope_angle(sx, sy);
    let sd = [v[4 * i + SLOPE_X], v[4 * i + SLOPE_Y]];
    let quad =
        sd[0] * (h[0][0] * sd[0] + h[0][1] * sd[1]) + sd[1] * (h[1][0] * sd[0] + h[1][1] * sd[1]);
    [
        a[4 * i],
        a[4 * i + 1],
        g[0] * a[4 * i + SLOPE_X] + g[1] * a[4 * i + SLOPE_Y] + quad,
    ]
}

/// Discrete-gradient data of an energy-conserving step: the start q₀, the end q₁ and the
/// element (and root spring) energies at q₀; the energies at q₁ are written to `u1`.
pub struct Discrete<'a> {
    /// q₀ (one entry per DOF).
    pub q0: &'a [f64],
    /// q₁.
    pub q1: &'a [f64],
    /// Energies at q₀: one per element, then the root spring.
    pub u0: &'a [f64],
    /// Energies at q₁ (written).
    pub u1: &'a mut [f64],
}

/// Discrete gradient of θ(r′) between the slopes `s0` and `s1` (absolute):
/// ∇θ(s_mid) + [θ₁ − θ₀ − ∇θ(s_mid)·Δs] Δs/|Δs|², so that ∇̄θ·Δs = θ₁ − θ₀ (angles unwrapped
/// across ±π). Also returns ∂²θ/∂r′² at the midpoint.
pub fn discrete_angle_gradient(s0: (f64, f64), s1: (f64, f64)) -> ([f64; 2], [[f64; 2]; 2]) {
    let mid = (0.5 * (s0.0 + s1.0), 0.5 * (s0.1 + s1.1));
    let (_, g, h) = slope_angle(mid.0, mid.1);
    let ds = [s1.0 - s0.0, s1.1 - s0.1];
    let n2 = ds[0] * ds[0] + ds[1] * ds[1];
    if n2 == 0.0 {
        return (g, h);
    }
    // θ₁ − θ₀ as the angle from s0 to s1 (no branch cut)
    let dtheta = (s0.0 * s1.1 - s0.1 * s1.0).atan2(s0.0 * s1.0 + s0.1 * s1.1);
    let c = (dtheta - g[0] * ds[0] - g[1] * ds[1]) / n2;
    ([g[0] + c * ds[0], g[1] + c * ds[1]], h)
}

/// Assembles the ANCF residual into `r` (one entry per DOF) and, if `jac` is given, the weighted
/// Jacobian over the free DOFs (cleared first); `f_ext` holds 3 entries per node (fx, fy, m).
/// With `discrete`, `kin.q` must be the midpoint ½(q₀ + q₁) and the elastic forces and the
/// moments are discrete gradients (module docs). Returns the strain energy at `kin.q` (or, with
/// `discrete`, at q₁) \[J\].
///
/// On an x86-64 processor with AVX2 the same code runs compiled for it (the element kernels
/// are too, see `AncfElement::force`): the same operations in the same order without fused
/// multiply-adds, so the same results bit for bit.
pub fn assemble_ancf(
    model: &BeamModel,
    kin: Kinematic<'_>,
    f_ext: &[f64],
    r: &mut [f64],
    jac: Option<(&mut BandMatrix, JacobianWeights)>,
    discrete: Option<&mut Discrete<'_>>,
) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2 (checked just above).
        return unsafe { assemble_ancf_avx2(model, kin, f_ext, r, jac, discrete) };
    }
    assemble_ancf_portable(model, kin, f_ext, r, jac, discrete)
}

/// [`assemble_ancf`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn assemble_ancf_avx2(
    model: &BeamModel,
    kin: Kinematic<'_>,
    f_ext: &[f64],
    r: &mut [f64],
    jac: Option<(&mut BandMatrix, JacobianWeights)>,
    discrete: Option<&mut Discrete<'_>>,
) -> f64 {
    assemble_ancf_portable(model, kin, f_ext, r, jac, discrete)
}

/// [`assemble_ancf`] for any processor.
#[inline(always)]
fn assemble_ancf_portable(
    model: &BeamModel,
    kin: Kinematic<'_>,
    f_ext: &[f64],
    r: &mut [f64],
    mut jac: Option<(&mut BandMatrix, JacobianWeights)>,
    mut discrete: Option<&mut Discrete<'_>>,
) -> f64 {
    let nfix = model.n_fixed();
    let sec = *model.section();
    let l = model.element_length();
    let damping = model.spec().damping;
    let dynamic = kin.v.is_some() && kin.a.is_some();
    let lumped = model.spec().mass == MassMatrix::Lumped;
    let el = element_of(model);
    let mass = el.mass(sec.rho_a());
    let lm = lumped_mass(l, sec.rho_a());
    let m_lump =
        Vector8::from_column_slice(&[lm[0], lm[1], lm[2], lm[2], lm[3], lm[4], lm[5], lm[5]]);
    let metric = [1.0, 1.0, l * l, l * l, 1.0, 1.0, l * l, l * l];
    let need_material = dynamic && damping.beta_stiffness > 0.0;
    // the constant inertia part of the iteration matrix, (w_a + w_v a₀) M
    let inertia_weighted = match jac.as_ref() {
        Some((_, w)) => {
            let c = w.acceleration + w.velocity * damping.alpha_mass;
            if lumped {
                Matrix8::from_diagonal(&(m_lump * c))
            } else {
                mass * c
            }
        }
        None => Matrix8::zeros(),
    };
    let want = if need_material {
        Want::TangentAndMaterial
    } else if jac.is_some() {
        Want::Tangent
    } else {
        Want::Force
    };
    r.iter_mut().for_each(|x| *x = 0.0);
    if let Some((band, _)) = jac.as_mut() {
        band.clear();
    }
    // the iteration matrix without a discrete gradient: the table-based tangent kernel
    // (AncfElement::force_and_tangent), the inertia part as its slot blocks
    let tables = (jac.is_some() && discrete.is_none()).then(|| &model.ancf_parts().tables);
    let inertia_blocks = if dynamic && tables.is_some() {
        let mut b = SlotBlocks::ZERO;
        for a in 0..4 {
            for bb in a..4 {
                b.xx[PACKED[a][bb]] = inertia_weighted[(2 * a, 2 * bb)];
                b.yy[PACKED[a][bb]] = inertia_weighted[(2 * a + 1, 2 * bb + 1)];
            }
        }
        b
    } else {
        SlotBlocks::ZERO
    };
    let mut energy = 0.0;
    // the residual alone (the most frequent call): the element forces four elements at a time
    // (`AncfElement::force4`), no 8 × 8 matrix formed or zeroed
    let residual_only = want == Want::Force && discrete.is_none() && tables.is_none();
    let ne = model.n_elements();
    let mut e0 = 0;
    let mut forces = [(0.0, Vector8::zeros()); 4];
    while residual_only && e0 < ne {
        let batch = (ne - e0).min(4);
        if batch == 4 {
            let d = [
                gather(kin.q, e0),
                gather(kin.q, e0 + 1),
                gather(kin.q, e0 + 2),
                gather(kin.q, e0 + 3),
            ];
            el.force4(&d, &mut forces);
        } else {
            for (k, x) in forces.iter_mut().take(batch).enumerate() {
                *x = el.force(&gather(kin.q, e0 + k));
            }
        }
        for (k, &(element_energy, mut f)) in forces.iter().take(batch).enumerate() {
            let e = e0 + k;
            energy += element_energy;
            if dynamic {
                let pv = gather(kin.v.unwrap(), e);
                let pa = gather(kin.a.unwrap(), e);
                let acc = pa + pv * damping.alpha_mass;
                add_inertia_force(&mut f, &acc, &mass, lumped.then_some(&m_lump));
            }
            let re: &mut [f64; 8] = (&mut r[4 * e..4 * e + 8]).try_into().expect("element DOFs");
            for k in 0..8 {
                re[ELEMENT_DOFS[k]] += f[k];
            }
        }
        e0 += batch;
    }
    // the iteration matrix's element kernels four elements at a time
    // (`AncfElement::force_and_tangent4`), the rest element by element
    let mut batch = (
        [(0.0, Vector8::zeros()); 4],
        [SlotBlocks::ZERO; 4],
        [SlotBlocks::ZERO; 4],
    );
    for e in (0..ne).filter(|_| !residual_only) {
        let d = gather(kin.q, e);
        if let (Some(tables), Some((band, w))) = (tables.as_ref(), jac.as_mut()) {
            // w_k K_t + (w_a + w_v a₀) M + w_v a₁ K_m
            let k = e % 4;
            let (res, kb4, mb4) = &mut batch;
            if k == 0 {
                let count = (ne - e).min(4);
                kb4[..count].fill(inertia_blocks);
                if need_material {
                    mb4[..count].fill(SlotBlocks::ZERO);
                }
                if count == 4 {
                    el.force_and_tangent4(
                        tables,
                        &[
                            d,
                            gather(kin.q, e + 1),
                            gather(kin.q, e + 2),
                            gather(kin.q, e + 3),
                        ],
                        w.stiffness,
                        kb4,
                        need_material.then_some(mb4),
                        res,
                    );
                } else {
                    for j in 0..count {
                        res[j] = el.force_and_tangent(
                            tables,
                            &gather(kin.q, e + j),
                            w.stiffness,
                            &mut kb4[j],
                            need_material.then_some(&mut mb4[j]),
                        );
                    }
                }
            }
            let (u, mut f) = res[k];
            let (kb, mb) = (&mut kb4[k], &mb4[k]);
            energy += u;
            if dynamic {
                let pv = gather(kin.v.unwrap(), e);
                let pa = gather(kin.a.unwrap(), e);
                if need_material {
                    f += mb.mul(&pv) * damping.beta_stiffness;
                    let c = w.velocity * damping.beta_stiffness;
                    for l in 0..10 {
                        kb.xx[l] += c * mb.xx[l];
                        kb.yy[l] += c * mb.yy[l];
                    }
                    for l in 0..16 {
                        kb.xy[l] += c * mb.xy[l];
                    }
                }
                add_inertia_force(
                    &mut f,
                    &(pa + pv * damping.alpha_mass),
                    &mass,
                    lumped.then_some(&m_lump),
                );
            }
            let re: &mut [f64; 8] = (&mut r[4 * e..4 * e + 8]).try_into().expect("element DOFs");
            for k in 0..8 {
                re[ELEMENT_DOFS[k]] += f[k];
            }
            // the block in the global DOF order 4e … 4e+7, by columns
            let block = global_block(kb);
            if 4 * e >= nfix {
                band.add_block(4 * e - nfix, &block);
            } else {
                for (j, col) in block.iter().enumerate() {
                    for (i, v) in col.iter().enumerate() {
                        if 4 * e + i >= nfix && 4 * e + j >= nfix {
                            band.add(4 * e + i - nfix, 4 * e + j - nfix, *v);
                        }
                    }
                }
            }
            continue;
        }
        let full = (want != Want::Force).then(|| el.evaluate(&d, want));
        let (element_energy, mut f) = match &full {
            Some(ev) => (ev.energy, ev.force),
            None => el.force(&d),
        };
        let mut kt = match &full {
            Some(ev) => ev.tangent,
            None => Matrix8::zeros(),
        };
        let material =
            |ev: &Option<AncfEvaluation>| ev.as_ref().map_or_else(Matrix8::zeros, |e| e.material);
        match discrete.as_deref_mut() {
            Some(dg) => {
                let d1 = gather(dg.q1, e);
                let d0 = gather(dg.q0, e);
                let at1 = el.evaluate(
                    &d1,
                    if jac.is_some() {
                        Want::Force
                    } else {
                        Want::Energy
                    },
                );
                let u1 = at1.energy;
                dg.u1[e] = u1;
                energy += u1;
                let dd = d1 - d0;
                let wdd = Vector8::from_fn(|k, _| metric[k] * dd[k]);
                let n2 = dd.dot(&wdd);
                if n2 > 0.0 {
                    let c = (u1 - dg.u0[e] - f.dot(&dd)) / n2;
                    if jac.is_some() {
                        // ∂f̄/∂Δ = ½ H(m) + W Δ ∂cᵀ + c W, ∂c = [∇U(q₁) − ∇U(m) − ½ H Δ − 2c W Δ]/n²;
                        // kt is weighted by ½ below, hence the factor 2
                        let dc = (at1.force - f - kt * dd * 0.5 - wdd * (2.0 * c)) / n2;
                        kt += wdd * dc.transpose() * 2.0;
                        for k in 0..8 {
                            kt[(k, k)] += 2.0 * c * metric[k];
                        }
                    }
                    f += wdd * c;
                }
            }
            None => energy += element_energy,
        }
        if dynamic {
            let pv = gather(kin.v.unwrap(), e);
            let pa = gather(kin.a.unwrap(), e);
            if need_material {
                f += material(&full) * pv * damping.beta_stiffness;
            }
            add_inertia_force(
                &mut f,
                &(pa + pv * damping.alpha_mass),
                &mass,
                lumped.then_some(&m_lump),
            );
        }
        let re: &mut [f64; 8] = (&mut r[4 * e..4 * e + 8]).try_into().expect("element DOFs");
        for k in 0..8 {
            re[ELEMENT_DOFS[k]] += f[k];
        }
        if let Some((band, w)) = jac.as_mut() {
            // w_k K_t + (w_a + w_v a₀) M + w_v a₁ K_m
            kt *= w.stiffness;
            if dynamic {
                kt += inertia_weighted;
                if need_material {
                    kt += material(&full) * (w.velocity * damping.beta_stiffness);
                }
            }
            if 4 * e >= nfix {
                // the element's DOFs 4e … 4e+7 are consecutive: add the block column by column
                let block: [[f64; 8]; 8] =
                    std::array::from_fn(|j| std::array::from_fn(|i| kt[(PERMUTE[i], PERMUTE[j])]));
                band.add_block(4 * e - nfix, &block);
            } else {
                for i in 0..8 {
                    let gi = 4 * e + ELEMENT_DOFS[i];
                    if gi < nfix {
                        continue;
                    }
                    for j in 0..8 {
                        let gj = 4 * e + ELEMENT_DOFS[j];
                        if gj >= nfix {
                            band.add(gi - nfix, gj - nfix, kt[(i, j)]);
                        }
                    }
                }
            }
        }
    }
    // Root spring, damper and hub inertia on θ₀ (pinned or hub root).
    let (k_theta, c_theta, j_hub) = model.root().spring_damper_inertia();
    if nfix == 2 {
        let (sx, sy) = slope(kin.q, 0);
        let (theta, g, h) = slope_angle(sx, sy);
        let dofs = [SLOPE_X, SLOPE_Y];
        let mut f = [k_theta * theta * g[0], k_theta * theta * g[1]];
        let mut k = [[0.0; 2]; 2];
        for i in 0..2 {
            for j in 0..2 {
                k[i][j] = k_theta * (g[i] * g[j] + theta * h[i][j]);
            }
        }
        match discrete.as_deref_mut() {
            Some(dg) => {
                let (s0, s1) = (slope(dg.q0, 0), slope(dg.q1, 0));
                let th1 = s1.1.atan2(s1.0);
                let u1 = 0.5 * k_theta * th1 * th1;
                let slot = model.n_elements();
                dg.u1[slot] = u1;
                energy += u1;
                let ds = [s1.0 - s0.0, s1.1 - s0.1];
                let n2 = ds[0] * ds[0] + ds[1] * ds[1];
                if n2 > 0.0 {
                    let c = (u1 - dg.u0[slot] - f[0] * ds[0] - f[1] * ds[1]) / n2;
                    f[0] += c * ds[0];
                    f[1] += c * ds[1];
                }
            }
            None => energy += 0.5 * k_theta * theta * theta,
        }
        let (mut cv, mut ca) = ([[0.0; 2]; 2], 0.0);
        if dynamic {
            let (v, a) = (kin.v.unwrap(), kin.a.unwrap());
            let sd = [v[SLOPE_X], v[SLOPE_Y]];
            let theta_dot = g[0] * sd[0] + g[1] * sd[1];
            for i in 0..2 {
                f[i] += c_theta * theta_dot * g[i]
                    + j_hub * (a[dofs[i]] + damping.alpha_mass * v[dofs[i]]);
                let hs = h[i][0] * sd[0] + h[i][1] * sd[1];
                for j in 0..2 {
                    cv[i][j] = c_theta * g[i] * g[j];
                    k[i][j] += c_theta
                        * (theta_dot * h[i][j] + g[i] * (h[j][0] * sd[0] + h[j][1] * sd[1]));
                }
                let _ = hs;
                cv[i][i] += damping.alpha_mass * j_hub;
            }
            ca = j_hub;
        }
        for i in 0..2 {
            r[dofs[i]] += f[i];
        }
        if let Some((band, w)) = jac.as_mut() {
            for i in 0..2 {
                for j in 0..2 {
                    let mut v = w.stiffness * k[i][j] + w.velocity * cv[i][j];
                    if i == j {
                        v += w.acceleration * ca;
                    }
                    band.add(dofs[i] - nfix, dofs[j] - nfix, v);
                }
            }
        }
    }
    // Point masses (u, v) and rotary inertias (both slope DOFs).
    if dynamic {
        let (v, a) = (kin.v.unwrap(), kin.a.unwrap());
        for pm in &model.spec().point_masses {
            for (d, m) in [
                (0, pm.mass),
                (1, pm.mass),
                (SLOPE_Y, pm.inertia),
                (SLOPE_X, pm.inertia),
            ] {
                let g = 4 * pm.node + d;
                r[g] += m * (a[g] + damping.alpha_mass * v[g]);
                if g >= nfix
                    && let Some((band, w)) = jac.as_mut()
                {
                    band.add(
                        g - nfix,
                        g - nfix,
                        w.acceleration * m + w.velocity * damping.alpha_mass * m,
                    );
                }
            }
        }
    }
    // Dead loads: forces on (u, v), moments on the slope through ∂θ/∂r′.
    for i in 0..model.n_nodes() {
        let (fx, fy, m) = (f_ext[3 * i], f_ext[3 * i + 1], f_ext[3 * i + 2]);
        r[4 * i] -= fx;
        r[4 * i + 1] -= fy;
        if m == 0.0 {
            continue;
        }
        let (g, h) = match discrete.as_deref() {
            Some(dg) => discrete_angle_gradient(slope(dg.q0, i), slope(dg.q1, i)),
            None => {
                let (sx, sy) = slope(kin.q, i);
                let (_, g, h) = slope_angle(sx, sy);
                (g, h)
            }
        };
        let dofs = [4 * i + SLOPE_X, 4 * i + SLOPE_Y];
        r[dofs[0]] -= m * g[0];
        r[dofs[1]] -= m * g[1];
        if let Some((band, w)) = jac.as_mut() {
            for a in 0..2 {
                for b in 0..2 {
                    if dofs[a] >= nfix && dofs[b] >= nfix {
                        band.add(dofs[a] - nfix, dofs[b] - nfix, -w.stiffness * m * h[a][b]);
                    }
                }
            }
        }
    }
    energy
}

/// The element matrix `k` as a dense block over the element's global DOFs 4e … 4e+7 in their
/// order (by columns: `block[j][i]` is entry (4e + i, 4e + j)).
#[inline(always)]
fn global_block(k: &SlotBlocks) -> [[f64; 8]; 8] {
    let g = ELEMENT_DOFS;
    let mut block = [[0.0; 8]; 8];
    for a in 0..4 {
        for b in 0..4 {
            // element coordinates (2a + i, 2b + j)
            block[g[2 * b]][g[2 * a]] = k.xx[PACKED[a][b]];
            block[g[2 * b + 1]][g[2 * a + 1]] = k.yy[PACKED[a][b]];
            block[g[2 * b + 1]][g[2 * a]] = k.xy[4 * a + b];
            block[g[2 * b]][g[2 * a + 1]] = k.xy[4 * b + a];
        }
    }
    block
}

/// Adds M `acc` to `f` (element coordinates): the consistent `mass`, or the diagonal `lumped`
/// one if given.
#[inline(always)]
fn add_inertia_force(f: &mut Vector8, acc: &Vector8, mass: &Matrix8, lumped: Option<&Vector8>) {
    if let Some(m_lump) = lumped {
        for k in 0..8 {
            f[k] += m_lump[k] * acc[k];
        }
    } else {
        // M = (ρA l sₐ s_b H_ab) ⊗ I₂: two 4 × 4 products (the same sums, in the same order, as
        // the 8 × 8 one without its zero terms)
        for a in 0..4 {
            let (mut fx, mut fy) = (0.0, 0.0);
            for bb in 0..4 {
                let m = mass[(2 * a, 2 * bb)];
                fx += m * acc[2 * bb];
                fy += m * acc[2 * bb + 1];
            }
            f[2 * a] += fx;
            f[2 * a + 1] += fy;
        }
    }
}

/// Kinetic energy ½ q̇ᵀ M q̇ of the ANCF beam, its point masses and the hub \[J\].
pub fn kinetic_energy_ancf(model: &BeamModel, v: &[f64]) -> f64 {
    let sec = model.section();
    let el = element_of(model);
    let mut t = 0.0;
    match model.spec().mass {
        MassMatrix::Consistent => {
            let m = el.mass(sec.rho_a());
            for e in 0..model.n_elements() {
                let pv = gather(v, e);
                t += 0.5 * pv.dot(&(m * pv));
            }
        }
        MassMatrix::Lumped => {
            let lm = lumped_mass(model.element_length(), sec.rho_a());
            for e in 0..model.n_elements() {
                let pv = gather(v, e);
                let w = [lm[0], lm[1], lm[2], lm[2], lm[3], lm[4], lm[5], lm[5]];
                t += 0.5 * (0..8).map(|k| w[k] * pv[k] * pv[k]).sum::<f64>();
            }
        }
    }
    let sq = |g: usize| v[g] * v[g];
    for pm in &model.spec().point_masses {
        let g = 4 * pm.node;
        t += 0.5 * pm.mass * (sq(g) + sq(g + 1))
            + 0.5 * pm.inertia * (sq(g + SLOPE_X) + sq(g + SLOPE_Y));
    }
    let (_, _, j_hub) = model.root().spring_damper_inertia();
    t + 0.5 * j_hub * (sq(SLOPE_X) + sq(SLOPE_Y))
}

/// Strain energies of the elements and then of the root spring into `out` (length N + 1);
/// returns their sum \[J\].
pub fn strain_energies_ancf(model: &BeamModel, q: &[f64], out: &mut [f64]) -> f64 {
    let el = element_of(model);
    let mut total = 0.0;
    for e in 0..model.n_elements() {
        let u = el.evaluate(&gather(q, e), Want::Energy).energy;
        out[e] = u;
        total += u;
    }
    let (k_theta, _, _) = model.root().spring_damper_inertia();
    let (sx, sy) = slope(q, 0);
    let th = sy.atan2(sx);
    let u = if model.n_fixed() == 2 {
        0.5 * k_theta * th * th
    } else {
        0.0
    };
    out[model.n_elements()] = u;
    total + u
}

/// The 2-vector slope of node `i`.
pub fn slope_vector(q: &[f64], i: usize) -> Vector2<f64> {
    let (sx, sy) = slope(q, i);
    Vector2::new(sx, sy)
}

/// The dead loads `f_ext` (3 per node) as generalized forces on the ANCF DOFs at `q` (moments
/// through ∂θ/∂r′) into `out` (one entry per DOF).
pub fn generalized_loads(model: &BeamModel, q: &[f64], f_ext: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|x| *x = 0.0);
    for i in 0..model.n_nodes() {
        out[4 * i] = f_ext[3 * i];
        out[4 * i + 1] = f_ext[3 * i + 1];
        let m = f_ext[3 * i + 2];
        if m != 0.0 {
            let (sx, sy) = slope(q, i);
            let (_, g, _) = slope_angle(sx, sy);
            out[4 * i + SLOPE_X] = m * g[0];
            out[4 * i + SLOPE_Y] = m * g[1];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_processor_specific_assembly_gives_the_portable_residual_and_matrix_bit_for_bit() {
        // assemble_ancf (AVX2 where the processor has it) against the portable code at a
        // deformed, moving state: identical residual, energy and iteration matrix.
        let (model, loads) =
            crate::canonical::polypropylene_cantilever(8, crate::model::Kinematics::Ancf).unwrap();
        let n = model.n_dofs();
        let wave = |s: f64| -> Vec<f64> {
            (0..n)
                .map(|i| {
                    if i < model.n_fixed() {
                        0.0
                    } else {
                        s * (0.37 * i as f64).sin()
                    }
                })
                .collect()
        };
        let (q, v, a) = (wave(0.05), wave(0.7), wave(30.0));
        let kin = Kinematic {
            q: &q,
            v: Some(&v),
            a: Some(&a),
        };
        let w = JacobianWeights {
            stiffness: 1.0,
            velocity: 2.0e3,
            acceleration: 3.6e6,
        };
        let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        let (mut r1, mut r2) = (vec![0.0; n], vec![0.0; n]);
        let (mut b1, mut b2) = (
            crate::assembly::band_for(&model),
            crate::assembly::band_for(&model),
        );
        let u1 = assemble_ancf(
            &model,
            kin,
            loads.as_slice(),
            &mut r1,
            Some((&mut b1, w)),
            None,
        );
        let u2 = assemble_ancf_portable(
            &model,
            kin,
            loads.as_slice(),
            &mut r2,
            Some((&mut b2, w)),
            None,
        );
        assert_eq!(u1.to_bits(), u2.to_bits());
        assert_eq!(bits(&r1), bits(&r2));
        let m = model.n_free();
        for i in 0..m {
            for j in 0..m {
                assert_eq!(b1.get(i, j).to_bits(), b2.get(i, j).to_bits(), "({i}, {j})");
            }
        }
        assert!(r1.iter().any(|x| x.abs() > 0.0) && b1.get(3, 3) > 0.0);
        // the residual alone
        let u1 = assemble_ancf(&model, kin, loads.as_slice(), &mut r1, None, None);
        let u2 = assemble_ancf_portable(&model, kin, loads.as_slice(), &mut r2, None, None);
        assert_eq!((u1.to_bits(), bits(&r1)), (u2.to_bits(), bits(&r2)));
    }
}
