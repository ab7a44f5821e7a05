//! The two-node Hermite-cubic Euler–Bernoulli element: linear stiffness and element inertia.
//!
//! Element DOFs `(u₁, v₁, θ₁, u₂, v₂, θ₂)`, length l, ξ = s/l ∈ [0, 1]. Hermite cubics
//! N₁ = 1 − 3ξ² + 2ξ³, N₂ = ξ − 2ξ² + ξ³, N₃ = 3ξ² − 2ξ³, N₄ = −ξ² + ξ³.
//!
//! **Stiffness** (small strain): axial EA/l [[1, −1], [−1, 1]] on (u₁, u₂) and bending
//! (EI/l³) [[12, 6l, −12, 6l], [6l, 4l², −6l, 2l²], [−12, −6l, 12, −6l], [6l, 2l², −6l, 4l²]] on
//! (v₁, θ₁, v₂, θ₂).
//!
//! **Consistent inertia.** The position of the centre line is interpolated as a Hermite curve of
//! the nodal positions xᵢ and unit tangents tᵢ = (cos θᵢ, sin θᵢ):
//! r(ξ) = N₁ x₁ + N₂ l t₁ + N₃ x₂ + N₄ l t₂.
//! This reproduces any rigid motion exactly, so the inertia is invariant under rotation (a
//! corotational element needs that), and for small rotations its transverse part is the classic
//! consistent bending mass (ρAl/420)[156, 22l, 54, −13l; …]. Its axial part uses N₁, N₃ instead
//! of linear shape functions (entries 13/35 and 9/70 instead of 1/3 and 1/6 of ρAl), which only
//! shifts the (high) axial modes. With ṙ = G(θ) q̇, the virtual work of the inertia forces
//! ∫ ρA r̈·δr ds gives
//! f_in = M(θ) q̈ + g(θ, θ̇),  M = ρA ∫ Gᵀ G ds,  g = −ρA ∫ Gᵀ l (N₂ θ̇₁² t₁ + N₄ θ̇₂² t₂) ds,
//! evaluated in closed form with the integrals H_ab = ∫₀¹ N_a N_b dξ.
//!
//! **Lumped inertia** (row-sum/HRZ): ρAl/2 on u and v of each node and ρAl³/78 on θ
//! (rotation invariant, no gyroscopic term).

use nalgebra::{Matrix6, Vector2, Vector6};

/// H_ab = ∫₀¹ N_a N_b dξ for the Hermite cubics (N₁, N₂, N₃, N₄).
pub const HERMITE_PRODUCTS: [[f64; 4]; 4] = [
    [13.0 / 35.0, 11.0 / 210.0, 9.0 / 70.0, -13.0 / 420.0],
    [11.0 / 210.0, 1.0 / 105.0, 13.0 / 420.0, -1.0 / 140.0],
    [9.0 / 70.0, 13.0 / 420.0, 13.0 / 35.0, -11.0 / 210.0],
    [-13.0 / 420.0, -1.0 / 140.0, -11.0 / 210.0, 1.0 / 105.0],
];

/// Lumped rotary inertia factor: ρA l³/78 per node (HRZ scaling of the consistent diagonal).
pub const LUMPED_ROTARY_FACTOR: f64 = 1.0 / 78.0;

/// Linear element stiffness matrix for an element along x of length `l` \[m\].
pub fn linear_stiffness(l: f64, ea: f64, ei: f64) -> Matrix6<f64> {
    let a = ea / l;
    let b = ei / (l * l * l);
    let mut k = Matrix6::zeros();
    k[(0, 0)] = a;
    k[(0, 3)] = -a;
    k[(3, 0)] = -a;
    k[(3, 3)] = a;
    let kb = [
        [12.0, 6.0 * l, -12.0, 6.0 * l],
        [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
        [-12.0, -6.0 * l, 12.0, -6.0 * l],
        [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
    ];
    let idx = [1, 2, 4, 5];
    for i in 0..4 {
        for j in 0..4 {
            k[(idx[i], idx[j])] = b * kb[i][j];
        }
    }
    k
}

/// Inertia force of one element and its derivatives.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementInertia {
    /// f_in = M(θ) a + g(θ, θ̇) [N, N·m].
    pub force: Vector6<f64>,
    /// M(θ) [kg, kg·m, kg·m²].
    pub mass: Matrix6<f64>,
    /// ∂f_in/∂q at fixed a and θ̇.
    pub d_dq: Matrix6<f64>,
    /// ∂f_in/∂q̇ (gyroscopic part only; a mass-proportional damping term is added by the caller).
    pub d_dv: Matrix6<f64>,
}

/// Consistent, rotation-invariant inertia of an element of length `l` and mass per length
/// `rho_a`, at nodal rotations `theta` = (θ₁, θ₂) \[rad\], rotation rates `omega` [rad/s] and
/// generalized accelerations `acc` (the vector M multiplies). With `nonlinear == false` the
/// rotations are taken as 0 and the gyroscopic term is dropped (the linear model).
pub fn consistent_inertia(
    l: f64,
    rho_a: f64,
    theta: [f64; 2],
    omega: [f64; 2],
    acc: &Vector6<f64>,
    nonlinear: bool,
) -> ElementInertia {
    consistent_inertia_trig(
        l,
        rho_a,
        [theta[0].sin_cos(), theta[1].sin_cos()],
        omega,
        acc,
        nonlinear,
    )
}

/// The inertia force f_in alone of [`consistent_inertia_trig`] (the same operations, without
/// the 6 × 6 matrices: the residual-only assembly).
#[inline]
pub fn consistent_inertia_force_trig(
    l: f64,
    rho_a: f64,
    trig: [(f64, f64); 2],
    omega: [f64; 2],
    acc: &Vector6<f64>,
    nonlinear: bool,
) -> Vector6<f64> {
    let (trig, om) = if nonlinear {
        (trig, omega)
    } else {
        ([(0.0, 1.0), (0.0, 1.0)], [0.0, 0.0])
    };
    let t = [
        Vector2::new(trig[0].1, trig[0].0),
        Vector2::new(trig[1].1, trig[1].0),
    ];
    let n = [Vector2::new(-t[0].y, t[0].x), Vector2::new(-t[1].y, t[1].x)];
    let h = &HERMITE_PRODUCTS;
    let a_slot = [
        Vector2::new(acc[0], acc[1]),
        n[0] * (l * acc[2]) - t[0] * (l * om[0] * om[0]),
        Vector2::new(acc[3], acc[4]),
        n[1] * (l * acc[5]) - t[1] * (l * om[1] * om[1]),
    ];
    let w: [Vector2<f64>; 4] = std::array::from_fn(|a| {
        a_slot[0] * h[a][0] + a_slot[1] * h[a][1] + a_slot[2] * h[a][2] + a_slot[3] * h[a][3]
    });
    let m_e = rho_a * l;
    let ln = [n[0] * l, n[1] * l];
    Vector6::new(
        m_e * w[0].x,
        m_e * w[0].y,
        m_e * ln[0].dot(&w[1]),
        m_e * w[2].x,
        m_e * w[2].y,
        m_e * ln[1].dot(&w[3]),
    )
}

/// [`consistent_inertia`] with the nodal (sin θᵢ, cos θᵢ) given.
#[inline(always)]
pub fn consistent_inertia_trig(
    l: f64,
    rho_a: f64,
    trig: [(f64, f64); 2],
    omega: [f64; 2],
    acc: &Vector6<f64>,
    nonlinear: bool,
) -> ElementInertia {
    let (trig, om) = if nonlinear {
        (trig, omega)
    } else {
        ([(0.0, 1.0), (0.0, 1.0)], [0.0, 0.0])
    };
    let t = [
        Vector2::new(trig[0].1, trig[0].0),
        Vector2::new(trig[1].1, trig[1].0),
    ];
    let n = [Vector2::new(-t[0].y, t[0].x), Vector2::new(-t[1].y, t[1].x)];
    let h = &HERMITE_PRODUCTS;
    // Slot accelerations A_b (including the centripetal term −l θ̇² t).
    let a_slot = [
        Vector2::new(acc[0], acc[1]),
        n[0] * (l * acc[2]) - t[0] * (l * om[0] * om[0]),
        Vector2::new(acc[3], acc[4]),
        n[1] * (l * acc[5]) - t[1] * (l * om[1] * om[1]),
    ];
    let w: [Vector2<f64>; 4] = std::array::from_fn(|a| {
        a_slot[0] * h[a][0] + a_slot[1] * h[a][1] + a_slot[2] * h[a][2] + a_slot[3] * h[a][3]
    });
    let m_e = rho_a * l;
    let ln = [n[0] * l, n[1] * l];
    let force = Vector6::new(
        m_e * w[0].x,
        m_e * w[0].y,
        m_e * ln[0].dot(&w[1]),
        m_e * w[2].x,
        m_e * w[2].y,
        m_e * ln[1].dot(&w[3]),
    );
    // M: translations (slots 0, 2; axis x or y) and rotations (slots 1, 3; direction l nⱼ)
    let mut mass = Matrix6::zeros();
    let trans = [(0usize, 0usize, 0usize), (1, 0, 1), (3, 2, 0), (4, 2, 1)]; // (dof, slot, axis)
    let rot = [(2usize, 1usize, 0usize), (5, 3, 1)]; // (dof, slot, node)
    for &(d, sd, ax) in &trans {
        for &(k, sk, bx) in &trans {
            if ax == bx {
                mass[(d, k)] = m_e * h[sd][sk];
            }
        }
        for &(k, sk, j) in &rot {
            let v = m_e * h[sd][sk] * ln[j][ax];
            mass[(d, k)] = v;
            mass[(k, d)] = v;
        }
    }
    let n12 = ln[0].dot(&ln[1]);
    mass[(2, 2)] = m_e * h[1][1] * l * l;
    mass[(5, 5)] = m_e * h[3][3] * l * l;
    mass[(2, 5)] = m_e * h[1][3] * n12;
    mass[(5, 2)] = mass[(2, 5)];
    let mut d_dq = Matrix6::zeros();
    let mut d_dv = Matrix6::zeros();
    if nonlinear {
        for &(k, sk, j) in &rot {
            let dadtheta = -t[j] * (l * acc[k]) - n[j] * (l * om[j] * om[j]);
            let dadomega = -t[j] * (2.0 * l * om[j]);
            for &(d, sd, ax) in &trans {
                let hk = m_e * h[sd][sk];
                d_dq[(d, k)] = hk * dadtheta[ax];
                d_dv[(d, k)] = hk * dadomega[ax];
            }
            for &(d, sd, i) in &rot {
                let hk = m_e * h[sd][sk];
                d_dq[(d, k)] = hk * ln[i].dot(&dadtheta);
                d_dv[(d, k)] = hk * ln[i].dot(&dadomega);
            }
            d_dq[(k, k)] += m_e * (-t[j] * l).dot(&w[sk]);
        }
    }
    ElementInertia {
        force,
        mass,
        d_dq,
        d_dv,
    }
}

/// Lumped (diagonal) element mass: ρAl/2 on u, v and ρAl³/78 on θ of each node.
pub fn lumped_mass(l: f64, rho_a: f64) -> Vector6<f64> {
    let m = rho_a * l;
    let r = m * l * l * LUMPED_ROTARY_FACTOR;
    Vector6::new(m / 2.0, m / 2.0, r, m / 2.0, m / 2.0, r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_inertia_force_kernel_matches_the_full_evaluation() {
        let acc = Vector6::new(0.3, -1.2, 4.0, 0.7, 2.2, -3.0);
        for nonlinear in [false, true] {
            let trig = [0.4f64.sin_cos(), (-1.1f64).sin_cos()];
            let full = consistent_inertia_trig(0.2, 1.7, trig, [2.0, -5.0], &acc, nonlinear);
            let f = consistent_inertia_force_trig(0.2, 1.7, trig, [2.0, -5.0], &acc, nonlinear);
            assert_eq!(f, full.force);
        }
    }

    /// The transverse part of the consistent inertia at θ = 0 is the classic bending mass
    /// (ρAl/420)[156, 22l, 54, −13l; 22l, 4l², 13l, −3l²; …].
    #[test]
    fn bending_part_is_classic_consistent_mass() {
        let (l, rho_a) = (0.3, 2.0);
        let ei = consistent_inertia(l, rho_a, [0.0; 2], [0.0; 2], &Vector6::zeros(), true);
        let c = rho_a * l / 420.0;
        let classic = [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ];
        let idx = [1, 2, 4, 5];
        for i in 0..4 {
            for j in 0..4 {
                let got = ei.mass[(idx[i], idx[j])];
                assert!((got - c * classic[i][j]).abs() < 1e-15, "{i} {j}: {got}");
            }
        }
    }

    /// The inertia force and its derivatives against central finite differences.
    #[test]
    fn inertia_derivatives_match_finite_differences() {
        let (l, rho_a) = (0.7, 1.3);
        let q = [0.4, -1.1];
        let v = [2.0, -3.0];
        let acc = Vector6::new(0.3, -0.2, 1.5, 0.7, 0.1, -2.5);
        let f0 = consistent_inertia(l, rho_a, q, v, &acc, true);
        let hstep = 1e-6;
        for (j, k) in [(0usize, 2usize), (1, 5)] {
            let mut qp = q;
            let mut qm = q;
            qp[j] += hstep;
            qm[j] -= hstep;
            let fp = consistent_inertia(l, rho_a, qp, v, &acc, true).force;
            let fm = consistent_inertia(l, rho_a, qm, v, &acc, true).force;
            let fd = (fp - fm) / (2.0 * hstep);
            for d in 0..6 {
                assert!((fd[d] - f0.d_dq[(d, k)]).abs() < 1e-7, "dq {d} {k}");
            }
            let mut vp = v;
            let mut vm = v;
            vp[j] += hstep;
            vm[j] -= hstep;
            let fp = consistent_inertia(l, rho_a, q, vp, &acc, true).force;
            let fm = consistent_inertia(l, rho_a, q, vm, &acc, true).force;
            let fd = (fp - fm) / (2.0 * hstep);
            for d in 0..6 {
                assert!((fd[d] - f0.d_dv[(d, k)]).abs() < 1e-7, "dv {d} {k}");
            }
        }
        // M is the derivative with respect to the acceleration.
        for k in 0..6 {
            let mut ap = acc;
            ap[k] += 1.0;
            let fp = consistent_inertia(l, rho_a, q, v, &ap, true).force;
            for d in 0..6 {
                assert!((fp[d] - f0.force[d] - f0.mass[(d, k)]).abs() < 1e-12);
            }
        }
    }

    /// A rigid rotation about the first node: kinetic energy ½ J ω², J = ρA l³/3.
    #[test]
    fn rigid_rotation_kinetic_energy_is_exact() {
        let (l, rho_a, w, phi) = (0.5, 3.0, 1.7, 2.2);
        let ei = consistent_inertia(l, rho_a, [phi, phi], [w, w], &Vector6::zeros(), true);
        let qd = Vector6::new(0.0, 0.0, w, -l * w * phi.sin(), l * w * phi.cos(), w);
        let t = 0.5 * qd.dot(&(ei.mass * qd));
        let exact = 0.5 * rho_a * l.powi(3) / 3.0 * w * w;
        assert!((t - exact).abs() < 1e-13 * exact, "{t} vs {exact}");
    }
}
