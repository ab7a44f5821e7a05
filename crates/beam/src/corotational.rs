//! Crisfield's planar corotational beam element (large displacement and rotation, small strain).
//!
//! The element's rigid motion is carried by its chord: current length l = |x₂ − x₁| and angle
//! β = atan2(y₂ − y₁, x₂ − x₁) (the undeformed element lies along x, β₀ = 0). The local
//! deformations are
//! ū = l − l₀,  θ̄ᵢ = atan2(sin(θᵢ − β), cos(θᵢ − β))  (i = 1, 2),
//! so any number of rigid turns gives θ̄ = 0 (the nodal θ is not wrapped, the local one is).
//! Local forces from the linear element: N = EA ū/l₀, [M₁, M₂] = (EI/l₀)[[4, 2], [2, 4]][θ̄₁, θ̄₂].
//! With c = cos β, s = sin β, r = (−c, −s, 0, c, s, 0), z = (s, −c, 0, −s, c, 0):
//! δū = rᵀδp, δβ = zᵀδp/l, δθ̄ᵢ = δθᵢ − δβ, i.e. B = [rᵀ; e₃ᵀ − zᵀ/l; e₆ᵀ − zᵀ/l] and
//! f = Bᵀ (N, M₁, M₂),
//! K_t = Bᵀ K_l B + (N/l) z zᵀ + ((M₁ + M₂)/l²)(r zᵀ + z rᵀ)  (Crisfield 1991, §7.3).

use nalgebra::{Matrix6, Vector3, Vector6};

/// Result of one corotational element evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CorotationalElement {
    /// Global internal force f [N, N·m].
    pub force: Vector6<f64>,
    /// Tangent stiffness ∂f/∂p.
    pub tangent: Matrix6<f64>,
    /// Material part Bᵀ K_l B (used for stiffness-proportional damping of the local rates).
    pub material: Matrix6<f64>,
    /// Strain energy ½ (N ū + M₁ θ̄₁ + M₂ θ̄₂) \[J\].
    pub strain_energy: f64,
    /// Local deformations (ū \[m\], θ̄₁, θ̄₂ \[rad\]).
    pub local: Vector3<f64>,
}

/// Evaluates an element of undeformed length `l0` along x with axial stiffness `ea`, bending
/// stiffness `ei`, at element displacements `p` = (u₁, v₁, θ₁, u₂, v₂, θ₂).
pub fn corotational_element(l0: f64, ea: f64, ei: f64, p: &Vector6<f64>) -> CorotationalElement {
    corotational_element_trig(l0, ea, ei, p, [p[2].sin_cos(), p[5].sin_cos()])
}

/// [`corotational_element`] with the nodal (sin θᵢ, cos θᵢ) given (the assembly computes them
/// once per node). θ̄ᵢ = atan2(sin θᵢ cos β − cos θᵢ sin β, cos θᵢ cos β + sin θᵢ sin β).
#[inline(always)]
pub fn corotational_element_trig(
    l0: f64,
    ea: f64,
    ei: f64,
    p: &Vector6<f64>,
    trig: [(f64, f64); 2],
) -> CorotationalElement {
    let d = Deformation::of(l0, p, trig);
    let (l, c, s) = (d.length, d.cos, d.sin);
    let (ka, kb) = (ea / l0, ei / l0);
    let (n_ax, m1, m2, strain_energy) = d.forces(ka, kb);
    let r = [-c, -s, 0.0, c, s, 0.0];
    let z = [s, -c, 0.0, -s, c, 0.0];
    // rows 2 and 3 of B: b₁ = e₃ − z/l, b₂ = e₆ − z/l
    let mut b1 = [0.0; 6];
    let mut b2 = [0.0; 6];
    for j in 0..6 {
        b1[j] = -z[j] / l;
        b2[j] = -z[j] / l;
    }
    b1[2] += 1.0;
    b2[5] += 1.0;
    let mut force = Vector6::zeros();
    for j in 0..6 {
        force[j] = r[j] * n_ax + b1[j] * m1 + b2[j] * m2;
    }
    // Bᵀ K_l B = (EA/l₀) r rᵀ + (EI/l₀)(4 b₁b₁ᵀ + 2 b₁b₂ᵀ + 2 b₂b₁ᵀ + 4 b₂b₂ᵀ)
    let (kn, km) = (n_ax / l, (m1 + m2) / (l * l));
    let mut material = Matrix6::zeros();
    let mut tangent = Matrix6::zeros();
    for i in 0..6 {
        let (p1, p2) = (4.0 * b1[i] + 2.0 * b2[i], 2.0 * b1[i] + 4.0 * b2[i]);
        for j in 0..6 {
            let km_ij = ka * r[i] * r[j] + kb * (p1 * b1[j] + p2 * b2[j]);
            material[(i, j)] = km_ij;
            tangent[(i, j)] = km_ij + kn * z[i] * z[j] + km * (r[i] * z[j] + z[i] * r[j]);
        }
    }
    let local = Vector3::new(d.axial, d.theta1, d.theta2);
    CorotationalElement {
        force,
        tangent,
        material,
        strain_energy,
        local,
    }
}

/// Internal force f [N, N·m] and strain energy \[J\] of [`corotational_element_trig`] alone (the
/// same operations, without the 6 × 6 matrices: the residual-only assembly).
#[inline]
pub fn corotational_force_trig(
    l0: f64,
    ea: f64,
    ei: f64,
    p: &Vector6<f64>,
    trig: [(f64, f64); 2],
) -> (Vector6<f64>, f64) {
    let d = Deformation::of(l0, p, trig);
    let (l, c, s) = (d.length, d.cos, d.sin);
    let (n_ax, m1, m2, strain_energy) = d.forces(ea / l0, ei / l0);
    let r = [-c, -s, 0.0, c, s, 0.0];
    let z = [s, -c, 0.0, -s, c, 0.0];
    let mut force = Vector6::zeros();
    for j in 0..6 {
        let zl = -z[j] / l;
        let (b1, b2) = (
            zl + if j == 2 { 1.0 } else { 0.0 },
            zl + if j == 5 { 1.0 } else { 0.0 },
        );
        force[j] = r[j] * n_ax + b1 * m1 + b2 * m2;
    }
    (force, strain_energy)
}

/// The strain energy \[J\] of [`corotational_element_trig`] alone (the same operations, without
/// the force: the energy of a state).
#[inline]
pub fn corotational_strain_energy_trig(
    l0: f64,
    ea: f64,
    ei: f64,
    p: &Vector6<f64>,
    trig: [(f64, f64); 2],
) -> f64 {
    Deformation::of(l0, p, trig).forces(ea / l0, ei / l0).3
}

/// The element's chord (length l, direction (cos β, sin β)) and local deformations ū, θ̄₁, θ̄₂.
struct Deformation {
    length: f64,
    cos: f64,
    sin: f64,
    axial: f64,
    theta1: f64,
    theta2: f64,
}

impl Deformation {
    /// At element displacements `p` with the nodal (sin θᵢ, cos θᵢ) `trig`, undeformed length
    /// `l0` \[m\].
    #[inline(always)]
    fn of(l0: f64, p: &Vector6<f64>, trig: [(f64, f64); 2]) -> Self {
        let dx = l0 + p[3] - p[0];
        let dy = p[4] - p[1];
        let l = dx.hypot(dy);
        let (c, s) = (dx / l, dy / l);
        let local_angle = |(sn, cs): (f64, f64)| (sn * c - cs * s).atan2(cs * c + sn * s);
        Deformation {
            length: l,
            cos: c,
            sin: s,
            axial: l - l0,
            theta1: local_angle(trig[0]),
            theta2: local_angle(trig[1]),
        }
    }

    /// The local forces N \[N\], M₁, M₂ \[N·m\] and the strain energy \[J\], with `ka` = EA/l₀
    /// and `kb` = EI/l₀.
    #[inline(always)]
    fn forces(&self, ka: f64, kb: f64) -> (f64, f64, f64, f64) {
        let (ub, t1, t2) = (self.axial, self.theta1, self.theta2);
        let n_ax = ka * ub;
        let m1 = kb * (4.0 * t1 + 2.0 * t2);
        let m2 = kb * (2.0 * t1 + 4.0 * t2);
        (n_ax, m1, m2, 0.5 * (n_ax * ub + m1 * t1 + m2 * t2))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_matches_finite_differences_of_force() {
        let (l0, ea, ei) = (0.25, 5.0e4, 3.0);
        let p = Vector6::new(0.01, -0.02, 0.3, -0.04, 0.09, 0.8);
        let e = corotational_element(l0, ea, ei, &p);
        let h = 1e-7;
        let mut worst: f64 = 0.0;
        for k in 0..6 {
            let mut pp = p;
            let mut pm = p;
            pp[k] += h;
            pm[k] -= h;
            let fd = (corotational_element(l0, ea, ei, &pp).force
                - corotational_element(l0, ea, ei, &pm).force)
                / (2.0 * h);
            for d in 0..6 {
                let scale = e.tangent.abs().max();
                worst = worst.max((fd[d] - e.tangent[(d, k)]).abs() / scale);
            }
        }
        assert!(worst < 1e-7, "relative FD mismatch {worst:e}");
        // and the force is the gradient of the strain energy
        for k in 0..6 {
            let mut pp = p;
            let mut pm = p;
            pp[k] += h;
            pm[k] -= h;
            let du = (corotational_element(l0, ea, ei, &pp).strain_energy
                - corotational_element(l0, ea, ei, &pm).strain_energy)
                / (2.0 * h);
            assert!(
                (du - e.force[k]).abs() < 1e-6 * e.force.abs().max(),
                "dU/dp {k}"
            );
        }
    }

    #[test]
    fn the_force_kernel_matches_the_full_evaluation() {
        let (l0, ea, ei) = (0.25, 5.0e4, 3.0);
        for p in [
            Vector6::new(0.01, -0.02, 0.3, -0.04, 0.09, 0.8),
            Vector6::new(0.0, 0.0, -2.0, 0.1, -0.2, 7.0),
        ] {
            let e = corotational_element(l0, ea, ei, &p);
            let (f, u) = corotational_force_trig(l0, ea, ei, &p, [p[2].sin_cos(), p[5].sin_cos()]);
            assert_eq!(f, e.force);
            assert_eq!(u, e.strain_energy);
            let trig = [p[2].sin_cos(), p[5].sin_cos()];
            assert_eq!(corotational_strain_energy_trig(l0, ea, ei, &p, trig), u);
        }
    }

    #[test]
    fn rigid_motion_of_several_turns_has_no_internal_force() {
        let (l0, ea, ei) = (0.4, 1.0e6, 7.0);
        for &phi in &[0.3, 3.0, -2.9, 7.5, 4.0 * std::f64::consts::PI + 1.0, -20.0] {
            let (tx, ty) = (0.17, -0.3);
            // node 1 translated, node 2 rotated about node 1 by phi
            let p = Vector6::new(
                tx,
                ty,
                phi,
                tx + l0 * phi.cos() - l0,
                ty + l0 * phi.sin(),
                phi,
            );
            let e = corotational_element(l0, ea, ei, &p);
            assert!(e.force.abs().max() < 1e-9, "phi {phi}: {:?}", e.force);
            assert!(e.strain_energy.abs() < 1e-20);
        }
    }
}
