//! Assembly of the global residual and its Jacobian over the free DOFs.
//!
//! Residual (one entry per DOF, constrained ones hold the reactions):
//! r(q, q̇, q̈) = f_int(q) + f_damp(q, q̇) + f_in(q, q̇, q̈) + f_root − f_ext,
//! with f_damp = a₀ M(q) q̇ + a₁ Σ Bᵀ K_l B q̇ (Rayleigh), f_root = k_θ θ₀ + c_θ θ̇₀ + J_hub θ̈₀,
//! point masses m q̈ and rotary inertias J θ̈ added at their nodes.
//! Jacobian J = c_k ∂r/∂q + c_v ∂r/∂q̇ + c_a ∂r/∂q̈ (the ∂/∂q of the a₁ damping term is
//! neglected; it only slows Newton when a₁ > 0).

use nalgebra::{Matrix6, Vector6};

use crate::banded::BandMatrix;
use crate::corotational::{
    corotational_element_trig, corotational_force_trig, corotational_strain_energy_trig,
};
use crate::element::{
    consistent_inertia_force_trig, consistent_inertia_trig, linear_stiffness, lumped_mass,
};
pub use crate::evaluation::{JacobianWeights, Kinematic};
use crate::model::{BeamModel, Kinematics, MassMatrix};

/// Half-bandwidth of the node-ordered system (one element spans 6 consecutive DOFs).
pub const HALF_BANDWIDTH: usize = 5;

/// A zero band matrix for the free DOFs of `model` (half-bandwidth 5, or 7 for ANCF).
pub fn band_for(model: &BeamModel) -> BandMatrix {
    let hb = model.half_bandwidth();
    BandMatrix::zeros(model.n_free(), hb, hb)
}

fn gather(x: &[f64], e: usize) -> Vector6<f64> {
    Vector6::from_column_slice(&x[3 * e..3 * e + 6])
}

/// Assembles r = f_int + f_damp + f_in + f_root − f_ext into `r` and, if `jac` is given, the
/// weighted Jacobian into the band matrix (over free DOFs; it is cleared first). Returns the
/// sum of the element strain energies (plus the root spring) \[J\]. `f_ext` holds 3 entries
/// per node (fx, fy, m); ANCF models are assembled by [`crate::assembly_ancf`].
///
/// On an x86-64 processor with AVX2 the element kernels run compiled for it: the same
/// operations in the same order without fused multiply-adds, so the same results bit for bit.
pub fn assemble(
    model: &BeamModel,
    kin: Kinematic<'_>,
    f_ext: &[f64],
    r: &mut [f64],
    jac: Option<(&mut BandMatrix, JacobianWeights)>,
) -> f64 {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("avx2") {
        // SAFETY: the processor has AVX2 (checked just above).
        return unsafe { assemble_avx2(model, kin, f_ext, r, jac) };
    }
    assemble_portable(model, kin, f_ext, r, jac)
}

/// [`assemble`] compiled for AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn assemble_avx2(
    model: &BeamModel,
    kin: Kinematic<'_>,
    f_ext: &[f64],
    r: &mut [f64],
    jac: Option<(&mut BandMatrix, JacobianWeights)>,
) -> f64 {
    assemble_portable(model, kin, f_ext, r, jac)
}

/// [`assemble`] for any processor.
#[inline(always)]
fn assemble_portable(
    model: &BeamModel,
    kin: Kinematic<'_>,
    f_ext: &[f64],
    r: &mut [f64],
    mut jac: Option<(&mut BandMatrix, JacobianWeights)>,
) -> f64 {
    if model.kinematics() == Kinematics::Ancf {
        return crate::assembly_ancf::assemble_ancf(model, kin, f_ext, r, jac, None);
    }
    let nfix = model.n_fixed();
    let sec = *model.section();
    let l = model.element_length();
    let damping = model.spec().damping;
    let dynamic = kin.v.is_some() && kin.a.is_some();
    let nonlinear = model.kinematics() == Kinematics::Corotational;
    let lumped = model.spec().mass == MassMatrix::Lumped;
    r.iter_mut().zip(f_ext).for_each(|(ri, fi)| *ri = -fi);
    if let Some((band, _)) = jac.as_mut() {
        band.clear();
    }
    let k_lin = linear_stiffness(l, sec.ea(), sec.ei());
    let m_lump = lumped_mass(l, sec.rho_a());
    let mut energy = 0.0;
    // no Jacobian and no stiffness-proportional damping (which needs the material matrix):
    // the force kernels alone
    let force_only = jac.is_none() && !(dynamic && damping.beta_stiffness > 0.0);
    // (sin θ, cos θ) of the element's first node, carried over from the previous element
    let mut trig_next = if nonlinear {
        kin.q[2].sin_cos()
    } else {
        (0.0, 1.0)
    };
    for e in 0..model.n_elements() {
        let p = gather(kin.q, e);
        let trig = [
            trig_next,
            if nonlinear {
                p[5].sin_cos()
            } else {
                (0.0, 1.0)
            },
        ];
        trig_next = trig[1];
        if force_only {
            // the residual alone (modified Newton's most frequent call): no 6 × 6 matrices
            let mut f = if nonlinear {
                let (f, u) = corotational_force_trig(l, sec.ea(), sec.ei(), &p, trig);
                energy += u;
                f
            } else {
                let f = k_lin * p;
                energy += 0.5 * p.dot(&f);
                f
            };
            if dynamic {
                let pv = gather(kin.v.unwrap(), e);
                let pa = gather(kin.a.unwrap(), e);
                if lumped {
                    for d in 0..6 {
                        f[d] += m_lump[d] * (pa[d] + damping.alpha_mass * pv[d]);
                    }
                } else {
                    let acc = pa + pv * damping.alpha_mass;
                    f += consistent_inertia_force_trig(
                        l,
                        sec.rho_a(),
                        trig,
                        [pv[2], pv[5]],
                        &acc,
                        nonlinear,
                    );
                }
            }
            for d in 0..6 {
                r[3 * e + d] += f[d];
            }
            continue;
        }
        let (mut f, mut kt, kmat) = if nonlinear {
            let ce = corotational_element_trig(l, sec.ea(), sec.ei(), &p, trig);
            energy += ce.strain_energy;
            (ce.force, ce.tangent, ce.material)
        } else {
            let f = k_lin * p;
            energy += 0.5 * p.dot(&f);
            (f, k_lin, k_lin)
        };
        let mut cv = Matrix6::zeros();
        let mut ca = Matrix6::zeros();
        if dynamic {
            let pv = gather(kin.v.unwrap(), e);
            let pa = gather(kin.a.unwrap(), e);
            if damping.beta_stiffness > 0.0 {
                f += kmat * pv * damping.beta_stiffness;
                cv += kmat * damping.beta_stiffness;
            }
            if lumped {
                for d in 0..6 {
                    f[d] += m_lump[d] * (pa[d] + damping.alpha_mass * pv[d]);
                    ca[(d, d)] = m_lump[d];
                    cv[(d, d)] += damping.alpha_mass * m_lump[d];
                }
            } else {
                let acc = pa + pv * damping.alpha_mass;
                let inert =
                    consistent_inertia_trig(l, sec.rho_a(), trig, [pv[2], pv[5]], &acc, nonlinear);
                f += inert.force;
                ca = inert.mass;
                cv += inert.d_dv + inert.mass * damping.alpha_mass;
                kt += inert.d_dq;
            }
        }
        for d in 0..6 {
            r[3 * e + d] += f[d];
        }
        if let Some((band, w)) = jac.as_mut() {
            let entry = |d: usize, k: usize| {
                w.stiffness * kt[(d, k)] + w.velocity * cv[(d, k)] + w.acceleration * ca[(d, k)]
            };
            if 3 * e >= nfix {
                // the element's 6 × 6 block, by columns
                let block: [[f64; 6]; 6] =
                    std::array::from_fn(|k| std::array::from_fn(|d| entry(d, k)));
                band.add_block(3 * e - nfix, &block);
            } else {
                for d in 0..6 {
                    let gd = 3 * e + d;
                    if gd < nfix {
                        continue;
                    }
                    for k in 0..6 {
                        let gk = 3 * e + k;
                        if gk < nfix {
                            continue;
                        }
                        band.add(gd - nfix, gk - nfix, entry(d, k));
                    }
                }
            }
        }
    }
    // Root spring, damper and hub inertia on θ₀.
    let (k_theta, c_theta, j_hub) = model.root().spring_damper_inertia();
    if nfix == 2 {
        let mut f = k_theta * kin.q[2];
        energy += 0.5 * k_theta * kin.q[2] * kin.q[2];
        let (mut cv, mut ca) = (0.0, 0.0);
        if dynamic {
            let (v, a) = (kin.v.unwrap()[2], kin.a.unwrap()[2]);
            f += c_theta * v + j_hub * (a + damping.alpha_mass * v);
            cv = c_theta + damping.alpha_mass * j_hub;
            ca = j_hub;
        }
        r[2] += f;
        if let Some((band, w)) = jac.as_mut() {
            band.add(
                0,
                0,
                w.stiffness * k_theta + w.velocity * cv + w.acceleration * ca,
            );
        }
    }
    // Point masses and rotary inertias.
    if dynamic {
        let (v, a) = (kin.v.unwrap(), kin.a.unwrap());
        for pm in &model.spec().point_masses {
            for (d, m) in [(0, pm.mass), (1, pm.mass), (2, pm.inertia)] {
                let g = 3 * pm.node + d;
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
    energy
}

/// (sin θ, cos θ) of each element's two nodes at displacements `q`, each node's computed once
/// and handed on to the next element ((0, 1) for a model that is not corotational).
fn element_trig<'q>(model: &BeamModel, q: &'q [f64]) -> impl Iterator<Item = [(f64, f64); 2]> + 'q {
    let nonlinear = model.kinematics() == Kinematics::Corotational;
    let trig = move |node: usize| {
        if nonlinear {
            q[3 * node + 2].sin_cos()
        } else {
            (0.0, 1.0)
        }
    };
    (0..model.n_elements()).scan(trig(0), move |first, e| {
        let next = trig(e + 1);
        let pair = [*first, next];
        *first = next;
        Some(pair)
    })
}

/// The element energies' constants, taken from the model once per pass.
struct ElementEnergies {
    l: f64,
    ea: f64,
    ei: f64,
    rho_a: f64,
    corotational: bool,
    lumped: bool,
    /// The linear element's stiffness (a model that is not corotational).
    k_lin: Matrix6<f64>,
}

impl ElementEnergies {
    fn of(model: &BeamModel) -> Self {
        let sec = model.section();
        let l = model.element_length();
        ElementEnergies {
            l,
            ea: sec.ea(),
            ei: sec.ei(),
            rho_a: sec.rho_a(),
            corotational: model.kinematics() == Kinematics::Corotational,
            lumped: model.spec().mass == MassMatrix::Lumped,
            k_lin: linear_stiffness(l, sec.ea(), sec.ei()),
        }
    }

    /// Kinetic energy ½ q̇ₑᵀ Mₑ q̇ₑ of element `e` at velocities `v`, its nodes' (sin θ, cos θ)
    /// `trig` \[J\].
    #[inline(always)]
    fn kinetic(&self, v: &[f64], e: usize, trig: [(f64, f64); 2]) -> f64 {
        let pv = gather(v, e);
        if self.lumped {
            let m = lumped_mass(self.l, self.rho_a);
            0.5 * (0..6).map(|d| m[d] * pv[d] * pv[d]).sum::<f64>()
        } else {
            // f_in with a = q̇ and θ̇ = 0 gives M(q) q̇.
            let f = consistent_inertia_force_trig(
                self.l,
                self.rho_a,
                trig,
                [0.0; 2],
                &pv,
                self.corotational,
            );
            0.5 * pv.dot(&f)
        }
    }

    /// Strain energy of element `e` at displacements `q`, its nodes' (sin θ, cos θ) `trig`
    /// \[J\].
    #[inline(always)]
    fn strain(&self, q: &[f64], e: usize, trig: [(f64, f64); 2]) -> f64 {
        let p = gather(q, e);
        if self.corotational {
            corotational_strain_energy_trig(self.l, self.ea, self.ei, &p, trig)
        } else {
            0.5 * p.dot(&(self.k_lin * p))
        }
    }
}

/// Kinetic energy of the point masses and the hub added to the elements' `t` \[J\].
fn with_point_and_hub_kinetic_energy(model: &BeamModel, v: &[f64], mut t: f64) -> f64 {
    for pm in &model.spec().point_masses {
        let g = 3 * pm.node;
        t += 0.5
            * (pm.mass * (v[g] * v[g] + v[g + 1] * v[g + 1]) + pm.inertia * v[g + 2] * v[g + 2]);
    }
    let (_, _, j_hub) = model.root().spring_damper_inertia();
    t + 0.5 * j_hub * v[2] * v[2]
}

/// The root spring's strain energy added to the elements' `energy` \[J\].
fn with_root_strain_energy(model: &BeamModel, q: &[f64], mut energy: f64) -> f64 {
    if model.n_fixed() == 2 {
        let (k_theta, _, _) = model.root().spring_damper_inertia();
        energy += 0.5 * k_theta * q[2] * q[2];
    }
    energy
}

/// Kinetic energy ½ q̇ᵀ M(q) q̇ of the beam, its point masses and the hub \[J\].
pub fn kinetic_energy(model: &BeamModel, q: &[f64], v: &[f64]) -> f64 {
    if model.kinematics() == Kinematics::Ancf {
        return crate::assembly_ancf::kinetic_energy_ancf(model, v);
    }
    let elements = ElementEnergies::of(model);
    let mut t = 0.0;
    for (e, trig) in element_trig(model, q).enumerate() {
        t += elements.kinetic(v, e, trig);
    }
    with_point_and_hub_kinetic_energy(model, v, t)
}

/// Strain energy of the elements and the root spring \[J\] (the energy [`assemble`] returns,
/// without the forces).
pub fn strain_energy(model: &BeamModel, q: &[f64]) -> f64 {
    if model.kinematics() == Kinematics::Ancf {
        let mut out = vec![0.0; model.n_nodes()];
        return crate::assembly_ancf::strain_energies_ancf(model, q, &mut out);
    }
    let elements = ElementEnergies::of(model);
    let mut energy = 0.0;
    for (e, trig) in element_trig(model, q).enumerate() {
        energy += elements.strain(q, e, trig);
    }
    with_root_strain_energy(model, q, energy)
}

/// ([`kinetic_energy`], [`strain_energy`]) in one pass over the elements: each node's sin and
/// cos computed once for both (the same operations in the same order: the same two energies
/// bit for bit).
pub fn kinetic_and_strain_energy(model: &BeamModel, q: &[f64], v: &[f64]) -> (f64, f64) {
    if model.kinematics() == Kinematics::Ancf {
        return (kinetic_energy(model, q, v), strain_energy(model, q));
    }
    let elements = ElementEnergies::of(model);
    let (mut t, mut u) = (0.0, 0.0);
    for (e, trig) in element_trig(model, q).enumerate() {
        t += elements.kinetic(v, e, trig);
        u += elements.strain(q, e, trig);
    }
    (
        with_point_and_hub_kinetic_energy(model, v, t),
        with_root_strain_energy(model, q, u),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{BeamSpec, PointMass, Rayleigh};
    use crate::section::Section;

    /// The dispatched assembly (AVX2 where the processor has it) against the portable code:
    /// the same residual, energy and iteration matrix to the last bit, for the corotational
    /// and the linear link, consistent and lumped mass, with and without Rayleigh damping, with
    /// the Jacobian and without.
    #[test]
    fn the_processor_specific_assembly_gives_the_portable_results_bit_for_bit() {
        let section = Section::from_stiffness(1.5e5, 0.139, 0.0463).unwrap();
        for kinematics in [Kinematics::Corotational, Kinematics::Linear] {
            for mass in [MassMatrix::Consistent, MassMatrix::Lumped] {
                for damping in [(0.0, 0.0), (0.3, 1e-4)] {
                    let mut spec = BeamSpec::cantilever(0.338, section, 16, kinematics);
                    spec.mass = mass;
                    spec.damping = Rayleigh {
                        alpha_mass: damping.0,
                        beta_stiffness: damping.1,
                    };
                    spec.point_masses.push(PointMass {
                        node: 16,
                        mass: 0.1,
                        inertia: 1e-5,
                    });
                    let model = BeamModel::new(spec).unwrap();
                    let n = model.n_dofs();
                    let wave = |k: f64, s: f64| -> Vec<f64> {
                        (0..n).map(|i| s * (k * i as f64).sin()).collect()
                    };
                    let (q, v, a) = (wave(1.3, 0.05), wave(0.7, 2.0), wave(2.1, 30.0));
                    let f_ext = wave(0.4, 1e-2);
                    let kin = Kinematic {
                        q: &q,
                        v: Some(&v),
                        a: Some(&a),
                    };
                    let w = JacobianWeights {
                        stiffness: 1.0,
                        velocity: 3.3e3,
                        acceleration: 1.1e7,
                    };
                    let bits = |x: &[f64]| x.iter().map(|y| y.to_bits()).collect::<Vec<_>>();
                    for with_jacobian in [true, false] {
                        let (mut r_fast, mut r_portable) = (vec![0.0; n], vec![0.0; n]);
                        let (mut band_fast, mut band_portable) =
                            (band_for(&model), band_for(&model));
                        let (e_fast, e_portable) = if with_jacobian {
                            (
                                assemble(
                                    &model,
                                    kin,
                                    &f_ext,
                                    &mut r_fast,
                                    Some((&mut band_fast, w)),
                                ),
                                assemble_portable(
                                    &model,
                                    kin,
                                    &f_ext,
                                    &mut r_portable,
                                    Some((&mut band_portable, w)),
                                ),
                            )
                        } else {
                            (
                                assemble(&model, kin, &f_ext, &mut r_fast, None),
                                assemble_portable(&model, kin, &f_ext, &mut r_portable, None),
                            )
                        };
                        let what = format!("{kinematics:?} {mass:?} {damping:?} {with_jacobian}");
                        assert_eq!(e_fast.to_bits(), e_portable.to_bits(), "{what}: energy");
                        assert_eq!(bits(&r_fast), bits(&r_portable), "{what}: residual");
                        assert!(r_fast.iter().all(|x| x.is_finite()) && e_fast > 0.0);
                        let m = band_fast.n();
                        for i in 0..m {
                            for j in i.saturating_sub(5)..(i + 6).min(m) {
                                assert_eq!(
                                    band_fast.get(i, j).to_bits(),
                                    band_portable.get(i, j).to_bits(),
                                    "{what}: iteration matrix ({i}, {j})"
                                );
                            }
                        }
                    }
                }
            }
        }
    }
}
