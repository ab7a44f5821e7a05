//! The planar ANCF cable element (absolute nodal coordinate formulation, Gerstmayr & Irschik
//! 2008): cubic Hermite positions with nodal positions and slopes, a constant consistent mass,
//! and a geometrically exact (Reissner–Kirchhoff) strain energy.
//!
//! **Interpolation.** Element of reference length l, ξ = s/l ∈ [0, 1], nodal coordinates
//! e = (r₁, r₁′, r₂, r₂′) (positions and slopes r′ = ∂r/∂s, 2-vectors), Hermite cubics
//! N₁ … N₄ (see [`crate::element`]):
//! r(ξ) = N₁ r₁ + l N₂ r₁′ + N₃ r₂ + l N₄ r₂′ = S(ξ) e.
//! Rigid motion (translation and any rotation) is represented exactly; a straight reference
//! along x has r₀′ = (1, 0) everywhere, r₀″ = 0.
//!
//! **Mass.** T = ½ ρA ∫ |ṙ|² ds = ½ ėᵀ M ė with the constant consistent matrix
//! M = ρA l ∫₀¹ SᵀS dξ, M_(a,i),(b,j) = ρA l sₐ s_b H_ab δᵢⱼ, s = (1, l, 1, l), H_ab = ∫ NₐN_b dξ:
//! exact for every motion of the interpolated centre line (no gyroscopic or centrifugal term).
//!
//! **Strain energy** (per reference length, Reissner's planar rod without shear):
//! W = ½ EA ε² + ½ EI κ²,  ε = |r′| − 1,  κ = dθ/ds = (r′ × r″)/|r′|²,
//! so the axial force is N = EA ε along the tangent and the bending moment M = EI θ′, the
//! constitutive law of the extensible elastica ([`crate::canonical`]'s references). Both strains
//! are invariant under rigid motion: no force under any rigid motion, for any rotation.
//! ε is computed from the displacement gradient d′ = r′ − r₀′ without cancellation,
//! |r′|² − 1 = 2d′ₓ + |d′|², ε = (|r′|² − 1)/(|r′| + 1).
//!
//! **Integration and locking.** κ² is integrated with 3 Gauss points ([`BENDING_RULE`]; 2 are
//! exact for the linearised element, where κ ≈ v″ is linear, but leave a 6× larger elastica
//! error). The axial term is integrated with the 3-point Gauss–Lobatto (Simpson) rule
//! ([`AXIAL_RULE`]): ξ = 0, ½, 1. A thin cubic cable (EA l²/EI ≫ 1) integrated with Gauss points
//! must keep |r′| ≈ 1 at 3 or more interior points of every curved element, more constraints
//! than the element's 2 axial parameters can meet, so it becomes too stiff in bending
//! (membrane locking: at EA L²/EI = 1.08e6 the elastica error with 5 Gauss points is 2.3e-3 at
//! 8 elements and 2.7e-4 at 16, converging as O(h³) instead of O(h⁴)). The Lobatto points at the
//! nodes are shared by the neighbouring elements (the strain there depends on the nodal slope
//! only), so each element adds 2 constraints for its 2 axial parameters: the error is then
//! independent of EA (3.1e-5, 2.0e-6, 1.2e-7, 7.6e-9 at 8, 16, 32, 64 elements for
//! EA L²/EI from 1e4 to 1e7: O(h⁴)), and unlike 2 Gauss points (also 2 constraints per element)
//! the root slope's length is held too, so no zero-energy axial mode remains. The energy is an
//! exact function of e, so the element stays conservative and its tangent symmetric.
//!
//! **Derivatives.** With r′ = Σ c¹ₐ eₐ, r″ = Σ c²ₐ eₐ (c¹ = (N₁′/l, N₂′, N₃′/l, N₄′),
//! c² = (N₁″/l², N₂″/l, N₃″/l², N₄″/l)), t = r′/|r′|, P = I − t tᵀ, g = |r′|², J = [[0, 1],
//! [−1, 0]], p = J r″, q = Jᵀ r′:
//! ∂ε/∂eₐ = c¹ₐ t,  ∂²ε/∂eₐ∂e_b = c¹ₐ c¹_b P/|r′|,
//! ∂κ/∂eₐ = c¹ₐ α + c²ₐ β,  α = p/g − 2κ r′/g,  β = q/g,
//! ∂²κ/∂eₐ∂e_b = c¹ₐc¹_b B₁₁ + c¹ₐc²_b B₁₂ + c²ₐc¹_b B₁₂ᵀ,
//! B₁₁ = −2(p r′ᵀ + r′ pᵀ)/g² − 2κ I/g + 8κ r′r′ᵀ/g²,  B₁₂ = J/g − 2 r′ qᵀ/g²,
//! and the tangent K = ∫ EA (∇ε∇εᵀ + ε∇²ε) + EI (∇κ∇κᵀ + κ∇²κ) ds (analytic, checked against
//! finite differences). The *material* part ∫ EA ∇ε∇εᵀ + EI ∇κ∇κᵀ ds weighs strain rates for
//! stiffness-proportional (Rayleigh) damping, which then vanishes under rigid motion.
//!
//! **One file, one concept** (about 1 400 lines before its tests): the ANCF cable element — its
//! interpolation, mass, strain energy, internal force and tangent kernels, and their four-lane
//! versions, which must stay bit for bit the one-element kernels and are kept beside them.

use nalgebra::{SMatrix, SVector, Vector2};

use crate::element::HERMITE_PRODUCTS;
use crate::lanes::{Lanes4, Real};

/// Element coordinates: (r₁ₓ, r₁ᵧ, r₁′ₓ, r₁′ᵧ, r₂ₓ, r₂ᵧ, r₂′ₓ, r₂′ᵧ).
pub type Vector8 = SVector<f64, 8>;
/// An 8 × 8 element matrix.
pub type Matrix8 = SMatrix<f64, 8, 8>;

/// Rule of the axial term (see the module docs).
pub const AXIAL_RULE: Quadrature = Quadrature::Lobatto3;
/// Rule of the bending term.
pub const BENDING_RULE: Quadrature = Quadrature::Gauss(3);
/// The largest Gauss rule available.
pub const MAX_POINTS: usize = 5;

/// Gauss–Legendre points on [0, 1] and weights (summing to 1), n = 1 … 5.
pub fn gauss_rule(n: usize) -> ([f64; MAX_POINTS], [f64; MAX_POINTS]) {
    let (x, w): (&[f64], &[f64]) = match n {
        1 => (&[0.0], &[2.0]),
        2 => (
            &[-0.577_350_269_189_625_8, 0.577_350_269_189_625_8],
            &[1.0, 1.0],
        ),
        3 => (
            &[-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4],
            &[5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0],
        ),
        4 => (
            &[
                -0.861_136_311_594_052_6,
                -0.339_981_043_584_856_3,
                0.339_981_043_584_856_3,
                0.861_136_311_594_052_6,
            ],
            &[
                0.347_854_845_137_453_9,
                0.652_145_154_862_546_1,
                0.652_145_154_862_546_1,
                0.347_854_845_137_453_9,
            ],
        ),
        5 => (
            &[
                -0.906_179_845_938_664,
                -0.538_469_310_105_683_1,
                0.0,
                0.538_469_310_105_683_1,
                0.906_179_845_938_664,
            ],
            &[
                0.236_926_885_056_189_1,
                0.478_628_670_499_366_5,
                0.568_888_888_888_888_9,
                0.478_628_670_499_366_5,
                0.236_926_885_056_189_1,
            ],
        ),
        _ => panic!("Gauss rule with {n} points: 1 to {MAX_POINTS} available"),
    };
    let mut xs = [0.0; MAX_POINTS];
    let mut ws = [0.0; MAX_POINTS];
    for i in 0..x.len() {
        xs[i] = 0.5 * (x[i] + 1.0);
        ws[i] = 0.5 * w[i];
    }
    (xs, ws)
}

/// 3-point Gauss–Lobatto (Simpson) rule on [0, 1]: the ends and the middle, weights 1/6, 4/6,
/// 1/6.
pub fn lobatto3_rule() -> ([f64; MAX_POINTS], [f64; MAX_POINTS]) {
    let mut x = [0.0; MAX_POINTS];
    let mut w = [0.0; MAX_POINTS];
    x[..3].copy_from_slice(&[0.0, 0.5, 1.0]);
    w[..3].copy_from_slice(&[1.0 / 6.0, 4.0 / 6.0, 1.0 / 6.0]);
    (x, w)
}

/// A quadrature rule on [0, 1].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quadrature {
    /// Gauss–Legendre with 1 … [`MAX_POINTS`] points.
    Gauss(usize),
    /// 3-point Gauss–Lobatto (Simpson): the nodes and the middle.
    Lobatto3,
}

impl Quadrature {
    fn points(self) -> (usize, [f64; MAX_POINTS], [f64; MAX_POINTS]) {
        match self {
            Quadrature::Gauss(n) => {
                let (x, w) = gauss_rule(n);
                (n, x, w)
            }
            Quadrature::Lobatto3 => {
                let (x, w) = lobatto3_rule();
                (3, x, w)
            }
        }
    }
}

/// What an element evaluation computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Want {
    /// The strain energy only.
    Energy,
    /// Energy and internal force.
    Force,
    /// Energy, force and tangent.
    Tangent,
    /// Energy, force, tangent and material matrices.
    TangentAndMaterial,
}

/// One integration point: weight × l and the coefficients of r′ and r″ per slot.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Point {
    wl: f64,
    c1: [f64; 4],
    c2: [f64; 4],
}

impl Point {
    fn at(xi: f64, w: f64, l: f64) -> Self {
        let x2 = xi * xi;
        // dN/dξ and d²N/dξ²
        let d1 = [
            -6.0 * xi + 6.0 * x2,
            1.0 - 4.0 * xi + 3.0 * x2,
            6.0 * xi - 6.0 * x2,
            -2.0 * xi + 3.0 * x2,
        ];
        let d2 = [
            -6.0 + 12.0 * xi,
            -4.0 + 6.0 * xi,
            6.0 - 12.0 * xi,
            -2.0 + 6.0 * xi,
        ];
        Point {
            wl: w * l,
            c1: [d1[0] / l, d1[1], d1[2] / l, d1[3]],
            c2: [d2[0] / (l * l), d2[1] / l, d2[2] / (l * l), d2[3] / l],
        }
    }
}

/// Result of an element evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AncfEvaluation {
    /// Strain energy \[J\].
    pub energy: f64,
    /// Internal force ∂U/∂e [N] (zero unless requested).
    pub force: Vector8,
    /// Tangent ∂²U/∂e² (zero unless requested).
    pub tangent: Matrix8,
    /// Material part ∫ EA ∇ε∇εᵀ + EI ∇κ∇κᵀ ds (zero unless requested with
    /// [`Want::TangentAndMaterial`]).
    pub material: Matrix8,
}

/// An ANCF cable element of given length, stiffness and integration rules (all elements of a
/// uniform mesh share one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AncfElement {
    l: f64,
    ea: f64,
    ei: f64,
    n_axial: usize,
    n_bending: usize,
    axial: [Point; MAX_POINTS],
    bending: [Point; MAX_POINTS],
    /// The default rules (see `AncfElement::default_rules`).
    default_rules: bool,
    /// Default rules: the coefficients per slot of the 7 interior lanes (c¹ of the middle
    /// axial point, c¹ of the 3 bending points, c² of the 3 bending points).
    lanes: [[f64; 4]; LANES],
}

/// Interior lanes of the default rules (see `AncfElement::lanes`).
const LANES: usize = 7;

/// The element coordinates as an array.
#[inline(always)]
fn coordinates(d: &Vector8) -> [f64; 8] {
    // (plain loops rather than `std::array::from_fn`, whose helper is not inlined into the
    // AVX2 build of the kernels)
    let mut dd = [0.0f64; 8];
    for (k, x) in dd.iter_mut().enumerate() {
        *x = d[k];
    }
    dd
}

/// The lanes' values Σₐ cₐ (d₂ₐ, d₂ₐ₊₁) (r′ or r″ at each point, as displacements): the
/// sums in the order of the per-point loops.
#[inline(always)]
fn gather_lanes<T: Real>(lanes: &[[f64; 4]; LANES], dd: &[T; 8]) -> [[T; 2]; LANES] {
    let mut out = [[T::splat(0.0); 2]; LANES];
    for (s, lane) in out.iter_mut().zip(lanes) {
        for a in 0..4 {
            s[0] = s[0] + dd[2 * a] * T::splat(lane[a]);
            s[1] = s[1] + dd[2 * a + 1] * T::splat(lane[a]);
        }
    }
    out
}

/// Adds Σₖ cₐ,ₖ `fl`ₖ to the slot forces `f` (element coordinates).
#[inline(always)]
fn scatter_lanes<T: Real>(lanes: &[[f64; 4]; LANES], fl: &[[T; 2]; LANES], f: &mut [T; 8]) {
    for k in 0..LANES {
        for a in 0..4 {
            f[2 * a] = f[2 * a] + T::splat(lanes[k][a]) * fl[k][0];
            f[2 * a + 1] = f[2 * a + 1] + T::splat(lanes[k][a]) * fl[k][1];
        }
    }
}

impl AncfElement {
    /// Element of length `l` \[m\], axial stiffness `ea` \[N\], bending stiffness `ei` [N·m²]
    /// with the default rules ([`AXIAL_RULE`], [`BENDING_RULE`]).
    pub fn new(l: f64, ea: f64, ei: f64) -> Self {
        Self::with_rules(l, ea, ei, AXIAL_RULE, BENDING_RULE)
    }

    /// Element with the rules `axial` and `bending` for the two terms (e.g. Gauss(5) for the
    /// axial term: the fully integrated element that locks).
    pub fn with_rules(l: f64, ea: f64, ei: f64, axial: Quadrature, bending: Quadrature) -> Self {
        let table = |rule: Quadrature| {
            let (n, x, w) = rule.points();
            let pts: [Point; MAX_POINTS] = std::array::from_fn(|i| Point::at(x[i], w[i], l));
            (n, pts)
        };
        let (n_axial, axial) = table(axial);
        let (n_bending, bending) = table(bending);
        let default_rules = n_axial == 3
            && n_bending == 3
            && axial[0].c1 == [0.0, 1.0, 0.0, 0.0]
            && axial[2].c1 == [0.0, 0.0, 0.0, 1.0];
        let lanes = [
            axial[1].c1,
            bending[0].c1,
            bending[1].c1,
            bending[2].c1,
            bending[0].c2,
            bending[1].c2,
            bending[2].c2,
        ];
        AncfElement {
            default_rules,
            lanes,
            l,
            ea,
            ei,
            n_axial,
            n_bending,
            axial,
            bending,
        }
    }

    /// Element length l \[m\].
    pub fn length(&self) -> f64 {
        self.l
    }

    /// Constant consistent mass matrix for mass per length `rho_a` [kg/m] (see the module docs).
    pub fn mass(&self, rho_a: f64) -> Matrix8 {
        let l = self.l;
        let s = [1.0, l, 1.0, l];
        let m_e = rho_a * l;
        let mut m = Matrix8::zeros();
        for a in 0..4 {
            for b in 0..4 {
                let v = m_e * s[a] * s[b] * HERMITE_PRODUCTS[a][b];
                m[(2 * a, 2 * b)] = v;
                m[(2 * a + 1, 2 * b + 1)] = v;
            }
        }
        m
    }

    /// Strain energy \[J\] and internal force ∂U/∂e \[N\] at the displacement `d` (as in
    /// [`AncfElement::evaluate`] with [`Want::Force`], the same operations, without the 8 × 8
    /// matrices: the residual-only assembly of every Newton iteration).
    #[inline]
    pub fn force(&self, d: &Vector8) -> (f64, Vector8) {
        if self.default_rules() {
            return self.force_default(d);
        }
        let ds: [[f64; 2]; 4] = std::array::from_fn(|a| [d[2 * a], d[2 * a + 1]]);
        let mut f = [0.0f64; 8];
        let mut energy = 0.0;
        for p in &self.axial[..self.n_axial] {
            let mut dp = [0.0f64; 2];
            for a in 0..4 {
                dp[0] += ds[a][0] * p.c1[a];
                dp[1] += ds[a][1] * p.c1[a];
            }
            let g1 = 2.0 * dp[0] + (dp[0] * dp[0] + dp[1] * dp[1]);
            let norm = (1.0 + g1).sqrt();
            let eps = g1 / (norm + 1.0);
            let n_ax = self.ea * eps;
            energy += 0.5 * p.wl * n_ax * eps;
            let w = p.wl * n_ax / norm;
            let ft = [(1.0 + dp[0]) * w, dp[1] * w];
            for a in 0..4 {
                f[2 * a] += p.c1[a] * ft[0];
                f[2 * a + 1] += p.c1[a] * ft[1];
            }
        }
        for p in &self.bending[..self.n_bending] {
            let mut dp = [0.0f64; 2];
            let mut rpp = [0.0f64; 2];
            for a in 0..4 {
                dp[0] += ds[a][0] * p.c1[a];
                dp[1] += ds[a][1] * p.c1[a];
                rpp[0] += ds[a][0] * p.c2[a];
                rpp[1] += ds[a][1] * p.c2[a];
            }
            let rp = [1.0 + dp[0], dp[1]];
            let g = rp[0] * rp[0] + rp[1] * rp[1];
            let kappa = (rp[0] * rpp[1] - rp[1] * rpp[0]) / g;
            let m_b = self.ei * kappa;
            energy += 0.5 * p.wl * m_b * kappa;
            // α = J r″/g − 2κ r′/g, β = Jᵀ r′/g
            let alpha = [
                rpp[1] / g - rp[0] * (2.0 * kappa / g),
                -rpp[0] / g - rp[1] * (2.0 * kappa / g),
            ];
            let beta = [-rp[1] / g, rp[0] / g];
            let fm = p.wl * m_b;
            for a in 0..4 {
                f[2 * a] += fm * (alpha[0] * p.c1[a] + beta[0] * p.c2[a]);
                f[2 * a + 1] += fm * (alpha[1] * p.c1[a] + beta[1] * p.c2[a]);
            }
        }
        (energy, Vector8::from(f))
    }

    /// Evaluates the element at the displacement `d` of its coordinates from the straight
    /// reference along x (positions (X₁, 0), (X₂, 0) and unit slopes (1, 0)), slot order
    /// (r₁, r₁′, r₂, r₂′).
    pub fn evaluate(&self, d: &Vector8, want: Want) -> AncfEvaluation {
        let slot = |a: usize| Vector2::new(d[2 * a], d[2 * a + 1]);
        let ds = [slot(0), slot(1), slot(2), slot(3)];
        let mut out = AncfEvaluation {
            energy: 0.0,
            force: Vector8::zeros(),
            tangent: Matrix8::zeros(),
            material: Matrix8::zeros(),
        };
        let mut k = [[0.0f64; 8]; 8];
        let mut km = [[0.0f64; 8]; 8];
        // axial: ε = |r′| − 1
        for p in &self.axial[..self.n_axial] {
            let dp = ds[0] * p.c1[0] + ds[1] * p.c1[1] + ds[2] * p.c1[2] + ds[3] * p.c1[3];
            let rp = Vector2::new(1.0 + dp.x, dp.y);
            let g1 = 2.0 * dp.x + dp.norm_squared(); // |r′|² − 1
            let norm = (1.0 + g1).sqrt();
            let eps = g1 / (norm + 1.0);
            let n_ax = self.ea * eps;
            out.energy += 0.5 * p.wl * n_ax * eps;
            if want == Want::Energy {
                continue;
            }
            let t = rp / norm;
            let ft = t * (p.wl * n_ax);
            for a in 0..4 {
                out.force[2 * a] += p.c1[a] * ft.x;
                out.force[2 * a + 1] += p.c1[a] * ft.y;
            }
            if want == Want::Force {
                continue;
            }
            // A = wl EA (t tᵀ + ε P/|r′|), material part wl EA t tᵀ
            let ea_w = p.wl * self.ea;
            let s = eps / norm;
            let mt = [
                [ea_w * t.x * t.x, ea_w * t.x * t.y],
                [ea_w * t.y * t.x, ea_w * t.y * t.y],
            ];
            let geo = [
                [ea_w * s * (1.0 - t.x * t.x), -ea_w * s * t.x * t.y],
                [-ea_w * s * t.x * t.y, ea_w * s * (1.0 - t.y * t.y)],
            ];
            let kk = [
                [mt[0][0] + geo[0][0], mt[0][1] + geo[0][1]],
                [mt[1][0] + geo[1][0], mt[1][1] + geo[1][1]],
            ];
            let material = want == Want::TangentAndMaterial;
            // the tangent is symmetric: the blocks b ≥ a here, the others mirrored at the end
            for a in 0..4 {
                for b in a..4 {
                    let cc = p.c1[a] * p.c1[b];
                    for i in 0..2 {
                        for j in 0..2 {
                            k[2 * a + i][2 * b + j] += cc * kk[i][j];
                            if material {
                                km[2 * a + i][2 * b + j] += cc * mt[i][j];
                            }
                        }
                    }
                }
            }
        }
        // bending: κ = (r′ × r″)/|r′|²
        for p in &self.bending[..self.n_bending] {
            let dp = ds[0] * p.c1[0] + ds[1] * p.c1[1] + ds[2] * p.c1[2] + ds[3] * p.c1[3];
            let rpp = ds[0] * p.c2[0] + ds[1] * p.c2[1] + ds[2] * p.c2[2] + ds[3] * p.c2[3];
            let rp = Vector2::new(1.0 + dp.x, dp.y);
            let g = rp.norm_squared();
            let c = rp.x * rpp.y - rp.y * rpp.x;
            let kappa = c / g;
            let m_b = self.ei * kappa;
            out.energy += 0.5 * p.wl * m_b * kappa;
            if want == Want::Energy {
                continue;
            }
            let pv = Vector2::new(rpp.y, -rpp.x); // J r″
            let qv = Vector2::new(-rp.y, rp.x); // Jᵀ r′
            let alpha = pv / g - rp * (2.0 * kappa / g);
            let beta = qv / g;
            let fm = p.wl * m_b;
            for a in 0..4 {
                let grad = alpha * p.c1[a] + beta * p.c2[a];
                out.force[2 * a] += fm * grad.x;
                out.force[2 * a + 1] += fm * grad.y;
            }
            if want == Want::Force {
                continue;
            }
            let ei_w = p.wl * self.ei;
            let g2 = g * g;
            // B₁₁ and B₁₂ (see the module docs)
            let b11 = [
                [
                    -4.0 * pv.x * rp.x / g2 - 2.0 * kappa / g + 8.0 * kappa * rp.x * rp.x / g2,
                    -2.0 * (pv.x * rp.y + rp.x * pv.y) / g2 + 8.0 * kappa * rp.x * rp.y / g2,
                ],
                [
                    -2.0 * (pv.y * rp.x + rp.y * pv.x) / g2 + 8.0 * kappa * rp.y * rp.x / g2,
                    -4.0 * pv.y * rp.y / g2 - 2.0 * kappa / g + 8.0 * kappa * rp.y * rp.y / g2,
                ],
            ];
            let b12 = [
                [-2.0 * rp.x * qv.x / g2, 1.0 / g - 2.0 * rp.x * qv.y / g2],
                [-1.0 / g - 2.0 * rp.y * qv.x / g2, -2.0 * rp.y * qv.y / g2],
            ];
            let (al, be) = ([alpha.x, alpha.y], [beta.x, beta.y]);
            // K_ab = c¹ₐ P_b + c²ₐ Q_b, P_b = c¹_b K₁₁ + c²_b K₁₂, Q_b = c¹_b K₁₂ᵀ + c²_b K₂₂
            let mut k11 = [[0.0; 2]; 2];
            let mut k12 = [[0.0; 2]; 2];
            let mut k22 = [[0.0; 2]; 2];
            let mut m11 = [[0.0; 2]; 2];
            let mut m12 = [[0.0; 2]; 2];
            for i in 0..2 {
                for j in 0..2 {
                    m11[i][j] = ei_w * al[i] * al[j];
                    m12[i][j] = ei_w * al[i] * be[j];
                    k22[i][j] = ei_w * be[i] * be[j];
                    k11[i][j] = m11[i][j] + ei_w * kappa * b11[i][j];
                    k12[i][j] = m12[i][j] + ei_w * kappa * b12[i][j];
                }
            }
            let material = want == Want::TangentAndMaterial;
            for b in 0..4 {
                let (c1b, c2b) = (p.c1[b], p.c2[b]);
                let mut pb = [[0.0; 2]; 2];
                let mut qb = [[0.0; 2]; 2];
                let mut pm = [[0.0; 2]; 2];
                let mut qm = [[0.0; 2]; 2];
                for i in 0..2 {
                    for j in 0..2 {
                        pb[i][j] = c1b * k11[i][j] + c2b * k12[i][j];
                        qb[i][j] = c1b * k12[j][i] + c2b * k22[i][j];
                        if material {
                            pm[i][j] = c1b * m11[i][j] + c2b * m12[i][j];
                            qm[i][j] = c1b * m12[j][i] + c2b * k22[i][j];
                        }
                    }
                }
                for a in 0..=b {
                    let (c1a, c2a) = (p.c1[a], p.c2[a]);
                    for i in 0..2 {
                        for j in 0..2 {
                            k[2 * a + i][2 * b + j] += c1a * pb[i][j] + c2a * qb[i][j];
                            if material {
                                km[2 * a + i][2 * b + j] += c1a * pm[i][j] + c2a * qm[i][j];
                            }
                        }
                    }
                }
            }
        }
        if matches!(want, Want::Tangent | Want::TangentAndMaterial) {
            // mirror the blocks a > b from the blocks b > a (both matrices are symmetric)
            for a in 1..4 {
                for b in 0..a {
                    for i in 0..2 {
                        for j in 0..2 {
                            k[2 * a + i][2 * b + j] = k[2 * b + j][2 * a + i];
                            km[2 * a + i][2 * b + j] = km[2 * b + j][2 * a + i];
                        }
                    }
                }
            }
            out.tangent = Matrix8::from_fn(|i, j| k[i][j]);
            if want == Want::TangentAndMaterial {
                out.material = Matrix8::from_fn(|i, j| km[i][j]);
            }
        }
        out
    }
}

/// The shape-function products of an element's integration points, weighted by wl, as 4 × 4
/// slot matrices (row-major, entry 4a + b): what the tangent kernel
/// [`AncfElement::force_and_tangent`] combines with a few scalars per point.
///
/// With P¹¹ = wl c¹c¹ᵀ, P¹² = wl c¹c²ᵀ, P²¹ = (P¹²)ᵀ, P²² = wl c²c²ᵀ (c¹, c² of the module
/// docs), the 2 × 2 block (a, b) of a point's tangent, c¹ₐc¹_b K₁₁ + c¹ₐc²_b K₁₂ + c²ₐc¹_b K₁₂ᵀ +
/// c²ₐc²_b K₂₂, has the x–x entries K₁₁,ₓₓ P¹¹ + K₁₂,ₓₓ (P¹² + P²¹) + K₂₂,ₓₓ P²² (and y–y
/// alike) and the x–y entries K₁₁,ₓᵧ P¹¹ + K₁₂,ₓᵧ P¹² + K₁₂,ᵧₓ P²¹ + K₂₂,ₓᵧ P²²: three 4 × 4
/// matrices, each a sum of fixed products times scalars, in 16-long loops that vectorise.
#[derive(Debug, Clone, PartialEq)]
pub struct TangentTables {
    /// P¹¹ of each axial point, full and packed (upper triangle, [`PACKED`]).
    axial: [[f64; 16]; MAX_POINTS],
    axial_packed: [[f64; 10]; MAX_POINTS],
    /// Per bending point: P¹¹, P¹² + P²¹, P²² packed (the symmetric ones).
    bending_sym: [[[f64; 10]; 3]; MAX_POINTS],
    /// Per bending point: P¹¹, P²², P¹², P²¹ (full).
    bending_cross: [[[f64; 16]; 4]; MAX_POINTS],
}

/// Index of the slot pair (a, b) in a packed symmetric 4 × 4 matrix (upper triangle by rows:
/// 00 01 02 03 11 12 13 22 23 33).
pub const PACKED: [[usize; 4]; 4] = [[0, 1, 2, 3], [1, 4, 5, 6], [2, 5, 7, 8], [3, 6, 8, 9]];

/// The upper triangle of a symmetric 4 × 4 matrix (row-major, entry 4a + b), packed.
fn pack(m: &[f64; 16]) -> [f64; 10] {
    [
        m[0], m[1], m[2], m[3], m[5], m[6], m[7], m[10], m[11], m[15],
    ]
}

/// The element tangent (or material matrix) as its three distinct 4 × 4 slot matrices:
/// K₍₂ₐ,₂_b₎ = `xx`, K₍₂ₐ₊₁,₂_b₊₁₎ = `yy` (symmetric, packed: entry [`PACKED`]\[a\]\[b\]),
/// K₍₂ₐ,₂_b₊₁₎ = `xy` (row-major, entry 4a + b), K₍₂ₐ₊₁,₂_b₎ = `xy`ᵀ (element coordinates
/// 2a + i, slot a, component i).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlotBlocks {
    /// x–x entries (packed upper triangle).
    pub xx: [f64; 10],
    /// y–y entries (packed upper triangle).
    pub yy: [f64; 10],
    /// x–y entries (y–x: the transpose).
    pub xy: [f64; 16],
}

impl SlotBlocks {
    /// All zero.
    pub const ZERO: SlotBlocks = SlotBlocks {
        xx: [0.0; 10],
        yy: [0.0; 10],
        xy: [0.0; 16],
    };

    /// Entry (k, m) in element coordinates (k = 2a + i, m = 2b + j).
    #[inline(always)]
    pub fn entry(&self, k: usize, m: usize) -> f64 {
        let (a, i, b, j) = (k / 2, k % 2, m / 2, m % 2);
        match (i, j) {
            (0, 0) => self.xx[PACKED[a][b]],
            (1, 1) => self.yy[PACKED[a][b]],
            (0, 1) => self.xy[4 * a + b],
            _ => self.xy[4 * b + a],
        }
    }

    /// The 8 × 8 matrix.
    pub fn matrix(&self) -> Matrix8 {
        Matrix8::from_fn(|k, m| self.entry(k, m))
    }

    /// The product with `x` (element coordinates).
    pub fn mul(&self, x: &Vector8) -> Vector8 {
        Vector8::from_fn(|k, _| (0..8).map(|m| self.entry(k, m) * x[m]).sum())
    }
}

/// Σₜ c[t] rows[t], added to `acc` (R, N fixed: unrolled, `acc` kept in registers).
#[inline(always)]
fn combine<const R: usize, const N: usize>(acc: &mut [f64; N], rows: [&[f64; N]; R], c: [f64; R]) {
    let mut s = *acc;
    for (row, ct) in rows.iter().zip(c) {
        for l in 0..N {
            s[l] += ct * row[l];
        }
    }
    *acc = s;
}

/// One axial point's energy and force term (EA ε wl t, to be multiplied by c¹ₐ) at the
/// displacement gradient d′ = `dp`: the force part of [`axial_point`], the same operations, for
/// one element or four side by side.
#[inline(always)]
fn axial_force<T: Real>(ea: f64, wl: f64, dp: [T; 2]) -> (T, [T; 2]) {
    let one = T::splat(1.0);
    let g1 = T::splat(2.0) * dp[0] + (dp[0] * dp[0] + dp[1] * dp[1]);
    let norm = (one + g1).sqrt();
    let eps = g1 / (norm + one);
    let n_ax = T::splat(ea) * eps;
    let inv = one / norm;
    let (tx, ty) = ((one + dp[0]) * inv, dp[1] * inv);
    let w = T::splat(wl) * n_ax;
    (T::splat(0.5 * wl) * n_ax * eps, [tx * w, ty * w])
}

/// One bending point's energy and force factors α wl M, β wl M (to be multiplied by c¹ₐ, c²ₐ):
/// the force part of [`bending_point`], the same operations, for one element or four side by
/// side.
#[inline(always)]
fn bending_force<T: Real>(ei: f64, wl: f64, dp: [T; 2], rpp: [T; 2]) -> (T, [T; 2], [T; 2]) {
    let rp = [T::splat(1.0) + dp[0], dp[1]];
    let g = rp[0] * rp[0] + rp[1] * rp[1];
    let gi = T::splat(1.0) / g;
    let kappa = (rp[0] * rpp[1] - rp[1] * rpp[0]) * gi;
    let m_b = T::splat(ei) * kappa;
    let (pv, qv) = ([rpp[1], -rpp[0]], [-rp[1], rp[0]]);
    let k2 = T::splat(2.0) * kappa * gi;
    let al = [pv[0] * gi - rp[0] * k2, pv[1] * gi - rp[1] * k2];
    let be = [qv[0] * gi, qv[1] * gi];
    let fm = T::splat(wl) * m_b;
    (
        T::splat(0.5 * wl) * m_b * kappa,
        [fm * al[0], fm * al[1]],
        [fm * be[0], fm * be[1]],
    )
}

/// One axial point at the displacement gradient d′ = `dp`: its energy, the force term
/// (EA ε wl t, to be multiplied by c¹ₐ) and the 2 × 2 tangent EA (t tᵀ + ε P/|r′|) and material
/// EA t tᵀ blocks as (xx, yy, xy) (without wl, which the tables carry).
#[inline(always)]
fn axial_point<T: Real>(ea: f64, wl: f64, dp: [T; 2]) -> (T, [T; 2], [T; 3], [T; 3]) {
    let (one, ea) = (T::splat(1.0), T::splat(ea));
    let g1 = T::splat(2.0) * dp[0] + (dp[0] * dp[0] + dp[1] * dp[1]);
    let norm = (one + g1).sqrt();
    let eps = g1 / (norm + one);
    let n_ax = ea * eps;
    let inv = one / norm;
    let (tx, ty) = ((one + dp[0]) * inv, dp[1] * inv);
    let w = T::splat(wl) * n_ax;
    let s = eps * inv;
    let (txx, txy, tyy) = (tx * tx, tx * ty, ty * ty);
    (
        T::splat(0.5 * wl) * n_ax * eps,
        [tx * w, ty * w],
        [
            ea * (txx + s * (one - txx)),
            ea * (tyy + s * (one - tyy)),
            ea * (txy - s * txy),
        ],
        [ea * txx, ea * tyy, ea * txy],
    )
}

/// One bending point: energy, the force factors α wl M, β wl M (to be multiplied by c¹ₐ,
/// c²ₐ), and the coefficients (`ei` times K₁₁, K₁₂, K₂₂ of the module docs) of the symmetric
/// rows (P¹¹, P¹² + P²¹, P²²) for x–x and y–y and of the rows (P¹¹, P²², P¹², P²¹) for x–y.
struct BendingPoint<T> {
    energy: T,
    fa: [T; 2],
    fb: [T; 2],
    al: [T; 2],
    be: [T; 2],
    xx: [T; 3],
    yy: [T; 3],
    xy: [T; 4],
}

/// The coefficients of a bending point's material matrix `ei` (ααᵀ, αβᵀ, ββᵀ) for the rows of
/// [`BendingPoint`]: (x–x, y–y, x–y).
#[inline(always)]
fn bending_material<T: Real>(ei: f64, al: [T; 2], be: [T; 2]) -> ([T; 3], [T; 3], [T; 4]) {
    let ei = T::splat(ei);
    (
        [ei * al[0] * al[0], ei * al[0] * be[0], ei * be[0] * be[0]],
        [ei * al[1] * al[1], ei * al[1] * be[1], ei * be[1] * be[1]],
        [
            ei * al[0] * al[1],
            ei * be[0] * be[1],
            ei * al[0] * be[1],
            ei * al[1] * be[0],
        ],
    )
}

/// A bending point (see [`BendingPoint`]): the force with `ei`, the tangent coefficients with
/// `ei_k` (`ei` times the tangent's scale).
#[inline(always)]
fn bending_point<T: Real>(ei: f64, ei_k: f64, wl: f64, dp: [T; 2], rpp: [T; 2]) -> BendingPoint<T> {
    let c = T::splat;
    let (ei, ei_k) = (c(ei), c(ei_k));
    let rp = [c(1.0) + dp[0], dp[1]];
    let g = rp[0] * rp[0] + rp[1] * rp[1];
    let gi = c(1.0) / g;
    let kappa = (rp[0] * rpp[1] - rp[1] * rpp[0]) * gi;
    let m_b = ei * kappa;
    // J r″, Jᵀ r′; α = J r″/g − 2κ r′/g, β = Jᵀ r′/g
    let pv = [rpp[1], -rpp[0]];
    let qv = [-rp[1], rp[0]];
    let k2 = c(2.0) * kappa * gi;
    let al = [pv[0] * gi - rp[0] * k2, pv[1] * gi - rp[1] * k2];
    let be = [qv[0] * gi, qv[1] * gi];
    let fm = c(wl) * m_b;
    // B₁₁ (symmetric), B₁₂ (module docs)
    let gi2 = gi * gi;
    let b11 = [
        c(-4.0) * pv[0] * rp[0] * gi2 - c(2.0) * kappa * gi + c(8.0) * kappa * rp[0] * rp[0] * gi2,
        c(-4.0) * pv[1] * rp[1] * gi2 - c(2.0) * kappa * gi + c(8.0) * kappa * rp[1] * rp[1] * gi2,
        c(-2.0) * (pv[0] * rp[1] + rp[0] * pv[1]) * gi2 + c(8.0) * kappa * rp[0] * rp[1] * gi2,
    ];
    let b12 = [
        [
            c(-2.0) * rp[0] * qv[0] * gi2,
            gi - c(2.0) * rp[0] * qv[1] * gi2,
        ],
        [
            -gi - c(2.0) * rp[1] * qv[0] * gi2,
            c(-2.0) * rp[1] * qv[1] * gi2,
        ],
    ];
    let k12 = |i: usize, j: usize| ei_k * (al[i] * be[j] + kappa * b12[i][j]);
    BendingPoint {
        energy: c(0.5 * wl) * m_b * kappa,
        fa: [fm * al[0], fm * al[1]],
        fb: [fm * be[0], fm * be[1]],
        al,
        be,
        xx: [
            ei_k * (al[0] * al[0] + kappa * b11[0]),
            k12(0, 0),
            ei_k * (be[0] * be[0]),
        ],
        yy: [
            ei_k * (al[1] * al[1] + kappa * b11[1]),
            k12(1, 1),
            ei_k * (be[1] * be[1]),
        ],
        xy: [
            ei_k * (al[0] * al[1] + kappa * b11[2]),
            ei_k * (be[0] * be[1]),
            k12(0, 1),
            k12(1, 0),
        ],
    }
}

/// The per-point values of an element's tangent evaluation (default rules): energy, force,
/// the nodal axial points' 2 × 2 blocks (tangent, material), the coefficients of the table
/// rows (x–x, y–y, x–y), the middle axial point's material block and each bending point's
/// α, β (for the material matrix).
#[derive(Debug, Clone, Copy)]
struct TangentPoints<T> {
    energy: T,
    f: [T; 8],
    nodal_k: [[T; 3]; 2],
    nodal_m: [[T; 3]; 2],
    cxx: [T; 10],
    cyy: [T; 10],
    cxy: [T; 13],
    mm: [T; 3],
    albe: [([T; 2], [T; 2]); 3],
}

impl TangentPoints<Lanes4> {
    /// The values of the element in lane `j`.
    #[inline(always)]
    fn lane(&self, j: usize) -> TangentPoints<f64> {
        let l = |x: &Lanes4| x.0[j];
        let pair = |x: &[Lanes4; 2]| [l(&x[0]), l(&x[1])];
        TangentPoints {
            energy: l(&self.energy),
            f: self.f.each_ref().map(l),
            nodal_k: self.nodal_k.each_ref().map(|r| r.each_ref().map(l)),
            nodal_m: self.nodal_m.each_ref().map(|r| r.each_ref().map(l)),
            cxx: self.cxx.each_ref().map(l),
            cyy: self.cyy.each_ref().map(l),
            cxy: self.cxy.each_ref().map(l),
            mm: self.mm.each_ref().map(l),
            albe: self.albe.each_ref().map(|(a, b)| (pair(a), pair(b))),
        }
    }
}

/// Four elements' coordinates side by side (lane k: element k).
#[inline(always)]
fn transpose_in(d: &[Vector8; 4]) -> [Lanes4; 8] {
    let mut x = [Lanes4([0.0; 4]); 8];
    for (k, xk) in x.iter_mut().enumerate() {
        for (j, dj) in d.iter().enumerate() {
            xk.0[j] = dj[k];
        }
    }
    x
}

impl AncfElement {
    /// True for the default rules (Lobatto-3 axial, Gauss-3 bending): the kernels then run
    /// with fixed point counts, and the axial points at the nodes, where r′ is the nodal slope
    /// (c¹ = the unit vector of the slope slot), touch only that slot.
    #[inline(always)]
    fn default_rules(&self) -> bool {
        self.default_rules
    }

    /// [`AncfElement::force`] for the default rules, compiled for AVX2 when the processor has
    /// it (the same operations in the same order, no fused multiply-add: the same results bit
    /// for bit, tested).
    #[inline]
    fn force_default(&self, d: &Vector8) -> (f64, Vector8) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.force_default_avx2(d) };
        }
        self.force_default_portable(d)
    }

    /// [`AncfElement::force_default`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn force_default_avx2(&self, d: &Vector8) -> (f64, Vector8) {
        self.force_default_portable(d)
    }

    /// [`AncfElement::force`] for the default rules.
    #[inline(always)]
    fn force_default_portable(&self, d: &Vector8) -> (f64, Vector8) {
        let (energy, f) = self.force_default_lanes(&coordinates(d));
        (energy, Vector8::from(f))
    }

    /// [`AncfElement::force`] for the default rules (fixed point counts; the nodal axial
    /// points read and write the slope slots alone), for one element (`T` = `f64`) or four
    /// side by side ([`Lanes4`]: each lane gets that element's result bit for bit).
    #[inline(always)]
    fn force_default_lanes<T: Real>(&self, d: &[T; 8]) -> (T, [T; 8]) {
        let zero = T::splat(0.0);
        let mut f = [zero; 8];
        let mut energy = zero;
        for (slot, t) in [(1usize, 0usize), (3, 2)] {
            let (u, ft) = axial_force(self.ea, self.axial[t].wl, [d[2 * slot], d[2 * slot + 1]]);
            energy = energy + u;
            f[2 * slot] = f[2 * slot] + ft[0];
            f[2 * slot + 1] = f[2 * slot + 1] + ft[1];
        }
        let g = gather_lanes(&self.lanes, d);
        let mut fl = [[zero; 2]; LANES];
        let (u, ft) = axial_force(self.ea, self.axial[1].wl, g[0]);
        energy = energy + u;
        fl[0] = ft;
        for t in 0..3 {
            let (u, fa, fb) = bending_force(self.ei, self.bending[t].wl, g[1 + t], g[4 + t]);
            energy = energy + u;
            fl[1 + t] = fa;
            fl[4 + t] = fb;
        }
        scatter_lanes(&self.lanes, &fl, &mut f);
        (energy, f)
    }

    /// [`AncfElement::force`] of four elements at once (element k at the displacement
    /// `d[k]`, its energy and force into `out[k]`): with the default rules the kernel runs once with the four elements side by
    /// side, one per vector lane (compiled for AVX2 when the processor has it), so that their
    /// square roots and divisions share instructions; each element's energy and force are
    /// those of [`AncfElement::force`] bit for bit (the same operations, tested).
    #[inline]
    pub fn force4(&self, d: &[Vector8; 4], out: &mut [(f64, Vector8); 4]) {
        if !self.default_rules() {
            for (o, dk) in out.iter_mut().zip(d) {
                *o = self.force(dk);
            }
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.force4_default_avx2(d, out) };
        }
        self.force4_default_portable(d, out)
    }

    /// [`AncfElement::force4`] for the default rules compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn force4_default_avx2(&self, d: &[Vector8; 4], out: &mut [(f64, Vector8); 4]) {
        self.force4_default_portable(d, out)
    }

    /// [`AncfElement::force4`] for the default rules.
    #[inline(always)]
    fn force4_default_portable(&self, d: &[Vector8; 4], out: &mut [(f64, Vector8); 4]) {
        let (energy, f) = self.force_default_lanes(&transpose_in(d));
        for (j, (e, fj)) in out.iter_mut().enumerate() {
            *e = energy.0[j];
            for k in 0..8 {
                fj[k] = f[k].0[j];
            }
        }
    }

    /// The shape-function products of this element's points (see [`TangentTables`]).
    pub fn tangent_tables(&self) -> TangentTables {
        let outer = |wl: f64, u: &[f64; 4], v: &[f64; 4]| -> [f64; 16] {
            std::array::from_fn(|k| wl * (u[k / 4] * v[k % 4]))
        };
        let axial: [[f64; 16]; MAX_POINTS] = std::array::from_fn(|t| {
            let p = &self.axial[t];
            outer(p.wl, &p.c1, &p.c1)
        });
        TangentTables {
            axial_packed: std::array::from_fn(|t| pack(&axial[t])),
            axial,
            bending_sym: std::array::from_fn(|t| {
                let p = &self.bending[t];
                let p12 = outer(p.wl, &p.c1, &p.c2);
                let p21 = outer(p.wl, &p.c2, &p.c1);
                [
                    pack(&outer(p.wl, &p.c1, &p.c1)),
                    pack(&std::array::from_fn(|k| p12[k] + p21[k])),
                    pack(&outer(p.wl, &p.c2, &p.c2)),
                ]
            }),
            bending_cross: std::array::from_fn(|t| {
                let p = &self.bending[t];
                [
                    outer(p.wl, &p.c1, &p.c1),
                    outer(p.wl, &p.c2, &p.c2),
                    outer(p.wl, &p.c1, &p.c2),
                    outer(p.wl, &p.c2, &p.c1),
                ]
            }),
        }
    }

    /// Strain energy \[J\], internal force ∂U/∂e \[N\] and `scale` × the tangent ∂²U/∂e² added
    /// to `tangent` (and, if given, the material matrix, unscaled, added to `material`) at
    /// the displacement `d`, with the products `tables` of [`AncfElement::tangent_tables`]:
    /// the same quantities as [`AncfElement::evaluate`] (to round-off), for the assembly of
    /// the iteration matrix. Per point a few scalars (the 2 × 2 blocks of the module docs),
    /// then the three 4 × 4 sums of [`TangentTables`]; the x–x and y–y parts and the x–y part
    /// are each assembled once, so the tangent is symmetric by construction.
    pub fn force_and_tangent(
        &self,
        tables: &TangentTables,
        d: &Vector8,
        scale: f64,
        tangent: &mut SlotBlocks,
        material: Option<&mut SlotBlocks>,
    ) -> (f64, Vector8) {
        if self.default_rules() {
            self.force_and_tangent_default(tables, d, scale, tangent, material)
        } else {
            self.force_and_tangent_any(tables, d, scale, tangent, material)
        }
    }

    /// [`AncfElement::force_and_tangent`] for the default rules, compiled for AVX2 when the
    /// processor has it (as [`AncfElement::force_default`]: the same results bit for bit).
    fn force_and_tangent_default(
        &self,
        tables: &TangentTables,
        d: &Vector8,
        scale: f64,
        tangent: &mut SlotBlocks,
        material: Option<&mut SlotBlocks>,
    ) -> (f64, Vector8) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe {
                self.force_and_tangent_default_avx2(tables, d, scale, tangent, material)
            };
        }
        self.force_and_tangent_default_portable(tables, d, scale, tangent, material)
    }

    /// [`AncfElement::force_and_tangent_default`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn force_and_tangent_default_avx2(
        &self,
        tables: &TangentTables,
        d: &Vector8,
        scale: f64,
        tangent: &mut SlotBlocks,
        material: Option<&mut SlotBlocks>,
    ) -> (f64, Vector8) {
        self.force_and_tangent_default_portable(tables, d, scale, tangent, material)
    }

    /// [`AncfElement::force_and_tangent`] for the default rules: the nodal axial points add
    /// their 2 × 2 blocks to the slope slots' diagonal blocks alone, the middle axial point
    /// and the 3 bending points go through the tables (10 packed rows for x–x and y–y, 13
    /// rows for x–y).
    #[inline(always)]
    fn force_and_tangent_default_portable(
        &self,
        tables: &TangentTables,
        d: &Vector8,
        scale: f64,
        tangent: &mut SlotBlocks,
        material: Option<&mut SlotBlocks>,
    ) -> (f64, Vector8) {
        let points = self.tangent_points(&coordinates(d), scale);
        self.tangent_from_points(tables, &points, tangent, material)
    }

    /// The per-point part of [`AncfElement::force_and_tangent`] (default rules): energy,
    /// force and the coefficients of the table rows, for one element (`T` = `f64`) or four
    /// side by side ([`Lanes4`]: each lane gets that element's values bit for bit).
    #[inline(always)]
    fn tangent_points<T: Real>(&self, d: &[T; 8], scale: f64) -> TangentPoints<T> {
        let zero = T::splat(0.0);
        let mut f = [zero; 8];
        let mut energy = zero;
        let mut nodal_k = [[zero; 3]; 2];
        let mut nodal_m = [[zero; 3]; 2];
        for (n, (slot, t)) in [(1usize, 0usize), (3, 2)].into_iter().enumerate() {
            let p = &self.axial[t];
            let (u, ft, k, m) = axial_point(self.ea, p.wl, [d[2 * slot], d[2 * slot + 1]]);
            energy = energy + u;
            f[2 * slot] = f[2 * slot] + ft[0];
            f[2 * slot + 1] = f[2 * slot + 1] + ft[1];
            nodal_k[n] = k.map(|x| x * T::splat(p.wl * scale));
            nodal_m[n] = m.map(|x| x * T::splat(p.wl));
        }
        let g = gather_lanes(&self.lanes, d);
        let mut fl = [[zero; 2]; LANES];
        let (u, ft, km, mm) = axial_point(self.ea, self.axial[1].wl, g[0]);
        energy = energy + u;
        fl[0] = ft;
        // row coefficients: x–x and y–y over the symmetric rows, x–y over the cross rows
        let mut cxx = [zero; 10];
        let mut cyy = [zero; 10];
        let mut cxy = [zero; 13];
        cxx[0] = km[0] * T::splat(scale);
        cyy[0] = km[1] * T::splat(scale);
        cxy[0] = km[2] * T::splat(scale);
        let mut albe = [([zero; 2], [zero; 2]); 3];
        for t in 0..3 {
            let b = bending_point(
                self.ei,
                self.ei * scale,
                self.bending[t].wl,
                g[1 + t],
                g[4 + t],
            );
            energy = energy + b.energy;
            fl[1 + t] = b.fa;
            fl[4 + t] = b.fb;
            cxx[1 + 3 * t..4 + 3 * t].copy_from_slice(&b.xx);
            cyy[1 + 3 * t..4 + 3 * t].copy_from_slice(&b.yy);
            cxy[1 + 4 * t..5 + 4 * t].copy_from_slice(&b.xy);
            albe[t] = (b.al, b.be);
        }
        scatter_lanes(&self.lanes, &fl, &mut f);
        TangentPoints {
            energy,
            f,
            nodal_k,
            nodal_m,
            cxx,
            cyy,
            cxy,
            mm,
            albe,
        }
    }

    /// [`AncfElement::force_and_tangent`] of four elements at once (default rules; others one
    /// by one): element k at the displacement `d[k]`, `tangent[k]`, `material[k]`, its
    /// energy and force into `out[k]`. The
    /// per-point part runs once with the four elements side by side, one per vector lane
    /// (compiled for AVX2 when the processor has it), the table part element by element: each
    /// element's energy, force, tangent and material matrix are those of
    /// [`AncfElement::force_and_tangent`] bit for bit (tested).
    #[inline]
    pub fn force_and_tangent4(
        &self,
        tables: &TangentTables,
        d: &[Vector8; 4],
        scale: f64,
        tangent: &mut [SlotBlocks; 4],
        material: Option<&mut [SlotBlocks; 4]>,
        out: &mut [(f64, Vector8); 4],
    ) {
        if !self.default_rules() {
            let mut material = material;
            for k in 0..4 {
                let m = material.as_deref_mut().map(|m| &mut m[k]);
                out[k] = self.force_and_tangent(tables, &d[k], scale, &mut tangent[k], m);
            }
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe {
                self.force_and_tangent4_default_avx2(tables, d, scale, tangent, material, out)
            };
        }
        self.force_and_tangent4_default_portable(tables, d, scale, tangent, material, out)
    }

    /// [`AncfElement::force_and_tangent4`] for the default rules compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn force_and_tangent4_default_avx2(
        &self,
        tables: &TangentTables,
        d: &[Vector8; 4],
        scale: f64,
        tangent: &mut [SlotBlocks; 4],
        material: Option<&mut [SlotBlocks; 4]>,
        out: &mut [(f64, Vector8); 4],
    ) {
        self.force_and_tangent4_default_portable(tables, d, scale, tangent, material, out)
    }

    /// [`AncfElement::force_and_tangent4`] for the default rules.
    #[inline(always)]
    fn force_and_tangent4_default_portable(
        &self,
        tables: &TangentTables,
        d: &[Vector8; 4],
        scale: f64,
        tangent: &mut [SlotBlocks; 4],
        mut material: Option<&mut [SlotBlocks; 4]>,
        out: &mut [(f64, Vector8); 4],
    ) {
        let p = self.tangent_points(&transpose_in(d), scale);
        for (k, (o, t)) in out.iter_mut().zip(tangent.iter_mut()).enumerate() {
            let m = material.as_deref_mut().map(|m| &mut m[k]);
            *o = self.tangent_from_points(tables, &p.lane(k), t, m);
        }
    }

    /// The table part of [`AncfElement::force_and_tangent`] (default rules) from the element's
    /// per-point values: the tangent (and material) sums added to `tangent` (`material`);
    /// returns the energy and force.
    #[inline(always)]
    fn tangent_from_points(
        &self,
        tables: &TangentTables,
        points: &TangentPoints<f64>,
        tangent: &mut SlotBlocks,
        material: Option<&mut SlotBlocks>,
    ) -> (f64, Vector8) {
        let TangentPoints {
            energy,
            f,
            nodal_k,
            nodal_m,
            cxx,
            cyy,
            cxy,
            mm,
            albe,
        } = *points;
        let (ts, tc) = (&tables.bending_sym, &tables.bending_cross);
        let sym_rows = [
            &tables.axial_packed[1],
            &ts[0][0],
            &ts[0][1],
            &ts[0][2],
            &ts[1][0],
            &ts[1][1],
            &ts[1][2],
            &ts[2][0],
            &ts[2][1],
            &ts[2][2],
        ];
        let cross_rows = [
            &tables.axial[1],
            &tc[0][0],
            &tc[0][1],
            &tc[0][2],
            &tc[0][3],
            &tc[1][0],
            &tc[1][1],
            &tc[1][2],
            &tc[1][3],
            &tc[2][0],
            &tc[2][1],
            &tc[2][2],
            &tc[2][3],
        ];
        combine(&mut tangent.xx, sym_rows, cxx);
        combine(&mut tangent.yy, sym_rows, cyy);
        combine(&mut tangent.xy, cross_rows, cxy);
        for (n, slot) in [1usize, 3].into_iter().enumerate() {
            tangent.xx[PACKED[slot][slot]] += nodal_k[n][0];
            tangent.yy[PACKED[slot][slot]] += nodal_k[n][1];
            tangent.xy[5 * slot] += nodal_k[n][2];
        }
        if let Some(m) = material {
            let (mut mxx, mut myy, mut mxy) = ([0.0f64; 10], [0.0f64; 10], [0.0f64; 13]);
            (mxx[0], myy[0], mxy[0]) = (mm[0], mm[1], mm[2]);
            for (t, (al, be)) in albe.into_iter().enumerate() {
                let (xx, yy, xy) = bending_material(self.ei, al, be);
                mxx[1 + 3 * t..4 + 3 * t].copy_from_slice(&xx);
                myy[1 + 3 * t..4 + 3 * t].copy_from_slice(&yy);
                mxy[1 + 4 * t..5 + 4 * t].copy_from_slice(&xy);
            }
            combine(&mut m.xx, sym_rows, mxx);
            combine(&mut m.yy, sym_rows, myy);
            combine(&mut m.xy, cross_rows, mxy);
            for (n, slot) in [1usize, 3].into_iter().enumerate() {
                m.xx[PACKED[slot][slot]] += nodal_m[n][0];
                m.yy[PACKED[slot][slot]] += nodal_m[n][1];
                m.xy[5 * slot] += nodal_m[n][2];
            }
        }
        (energy, Vector8::from(f))
    }

    /// [`AncfElement::force_and_tangent`] for any rules.
    fn force_and_tangent_any(
        &self,
        tables: &TangentTables,
        d: &Vector8,
        scale: f64,
        tangent: &mut SlotBlocks,
        mut material: Option<&mut SlotBlocks>,
    ) -> (f64, Vector8) {
        let ds: [[f64; 2]; 4] = std::array::from_fn(|a| [d[2 * a], d[2 * a + 1]]);
        let mut f = [0.0f64; 8];
        let mut energy = 0.0;
        for (t, p) in self.axial[..self.n_axial].iter().enumerate() {
            let mut dp = [0.0f64; 2];
            for a in 0..4 {
                dp[0] += ds[a][0] * p.c1[a];
                dp[1] += ds[a][1] * p.c1[a];
            }
            let (u, ft, k, m) = axial_point(self.ea, p.wl, dp);
            energy += u;
            for a in 0..4 {
                f[2 * a] += p.c1[a] * ft[0];
                f[2 * a + 1] += p.c1[a] * ft[1];
            }
            let (sym, cross) = ([&tables.axial_packed[t]], [&tables.axial[t]]);
            combine(&mut tangent.xx, sym, [k[0] * scale]);
            combine(&mut tangent.yy, sym, [k[1] * scale]);
            combine(&mut tangent.xy, cross, [k[2] * scale]);
            if let Some(mt) = material.as_deref_mut() {
                combine(&mut mt.xx, sym, [m[0]]);
                combine(&mut mt.yy, sym, [m[1]]);
                combine(&mut mt.xy, cross, [m[2]]);
            }
        }
        for (t, p) in self.bending[..self.n_bending].iter().enumerate() {
            let mut dp = [0.0f64; 2];
            let mut rpp = [0.0f64; 2];
            for a in 0..4 {
                dp[0] += ds[a][0] * p.c1[a];
                dp[1] += ds[a][1] * p.c1[a];
                rpp[0] += ds[a][0] * p.c2[a];
                rpp[1] += ds[a][1] * p.c2[a];
            }
            let b = bending_point(self.ei, self.ei * scale, p.wl, dp, rpp);
            energy += b.energy;
            for a in 0..4 {
                f[2 * a] += b.fa[0] * p.c1[a] + b.fb[0] * p.c2[a];
                f[2 * a + 1] += b.fa[1] * p.c1[a] + b.fb[1] * p.c2[a];
            }
            let (rs, rc) = (&tables.bending_sym[t], &tables.bending_cross[t]);
            let sym = [&rs[0], &rs[1], &rs[2]];
            let cross = [&rc[0], &rc[1], &rc[2], &rc[3]];
            combine(&mut tangent.xx, sym, b.xx);
            combine(&mut tangent.yy, sym, b.yy);
            combine(&mut tangent.xy, cross, b.xy);
            if let Some(mt) = material.as_deref_mut() {
                let (xx, yy, xy) = bending_material(self.ei, b.al, b.be);
                combine(&mut mt.xx, sym, xx);
                combine(&mut mt.yy, sym, yy);
                combine(&mut mt.xy, cross, xy);
            }
        }
        (energy, Vector8::from(f))
    }
}

/// Node angle θ = atan2(r′ᵧ, r′ₓ) \[rad\] of the slope `(sx, sy)` (absolute), its gradient
/// ∂θ/∂(r′ₓ, r′ᵧ) = (−r′ᵧ, r′ₓ)/|r′|² and Hessian
/// [[2 r′ₓr′ᵧ, r′ᵧ² − r′ₓ²], [r′ᵧ² − r′ₓ², −2 r′ₓr′ᵧ]]/|r′|⁴.
pub fn slope_angle(sx: f64, sy: f64) -> (f64, [f64; 2], [[f64; 2]; 2]) {
    let g = sx * sx + sy * sy;
    let g2 = g * g;
    let off = (sy * sy - sx * sx) / g2;
    (
        sy.atan2(sx),
        [-sy / g, sx / g],
        [[2.0 * sx * sy / g2, off], [off, -2.0 * sx * sy / g2]],
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Vector8 {
        Vector8::from_column_slice(&[0.01, -0.02, -0.3, 0.4, -0.05, 0.09, -0.6, 0.5])
    }

    #[test]
    fn tangent_and_force_match_finite_differences() {
        let el =
            AncfElement::with_rules(0.25, 5.0e4, 3.0, Quadrature::Gauss(3), Quadrature::Gauss(4));
        test_fd(&el);
        test_fd(&AncfElement::new(0.25, 5.0e4, 3.0));
    }

    fn test_fd(el: &AncfElement) {
        let d = sample();
        let e = el.evaluate(&d, Want::Tangent);
        let h = 1e-6;
        let kscale = e.tangent.abs().max();
        let fscale = e.force.abs().max();
        for k in 0..8 {
            let mut dp = d;
            let mut dm = d;
            dp[k] += h;
            dm[k] -= h;
            let (ep, em) = (el.evaluate(&dp, Want::Force), el.evaluate(&dm, Want::Force));
            let du = (ep.energy - em.energy) / (2.0 * h);
            assert!((du - e.force[k]).abs() < 1e-7 * fscale, "dU/de {k}");
            for i in 0..8 {
                let fd = (ep.force[i] - em.force[i]) / (2.0 * h);
                assert!(
                    (fd - e.tangent[(i, k)]).abs() < 1e-7 * kscale,
                    "K {i} {k}: {fd} vs {}",
                    e.tangent[(i, k)]
                );
            }
        }
    }

    #[test]
    fn the_force_kernel_matches_the_full_evaluation() {
        // the residual-only kernel against evaluate(): same energy and force to round-off
        for el in [
            AncfElement::new(0.25, 5.0e4, 3.0),
            AncfElement::with_rules(
                0.1,
                3.7e4,
                3.1e-3,
                Quadrature::Gauss(5),
                Quadrature::Gauss(2),
            ),
        ] {
            for s in [0.0, 1.0, -0.7] {
                let d = sample() * s;
                let (u, f) = el.force(&d);
                let e = el.evaluate(&d, Want::Force);
                let scale = e.force.abs().max().max(1e-300);
                assert!((u - e.energy).abs() <= 1e-13 * e.energy.abs().max(1e-300));
                assert!(
                    (f - e.force).abs().max() <= 1e-13 * scale,
                    "{f} vs {}",
                    e.force
                );
            }
        }
    }

    #[test]
    fn the_processor_specific_kernels_give_the_portable_results_bit_for_bit() {
        // The dispatched kernels (AVX2 where the processor has it) against the portable code:
        // energy, force, tangent and material matrix identical to the last bit.
        let el = AncfElement::new(0.3 / 32.0, 1.5e9 * 2.5e-5, 3.125e-3);
        let tables = el.tangent_tables();
        let bits8 = |v: &Vector8| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let bits = |b: &SlotBlocks| {
            [&b.xx[..], &b.yy[..], &b.xy[..]]
                .concat()
                .iter()
                .map(|x| x.to_bits())
                .collect::<Vec<_>>()
        };
        for s in [0.0, 1e-3, 1.0, -0.7, 2.5] {
            let d = sample() * s;
            let (u, f) = el.force(&d);
            let (up, fp) = el.force_default_portable(&d);
            assert_eq!(
                (u.to_bits(), bits8(&f)),
                (up.to_bits(), bits8(&fp)),
                "force, s {s}"
            );
            let (mut k, mut m) = (SlotBlocks::ZERO, SlotBlocks::ZERO);
            let (mut kp, mut mp) = (SlotBlocks::ZERO, SlotBlocks::ZERO);
            let (u, f) = el.force_and_tangent(&tables, &d, 0.37, &mut k, Some(&mut m));
            let (up, fp) =
                el.force_and_tangent_default_portable(&tables, &d, 0.37, &mut kp, Some(&mut mp));
            assert_eq!(
                (u.to_bits(), bits8(&f)),
                (up.to_bits(), bits8(&fp)),
                "s {s}"
            );
            assert_eq!(bits(&k), bits(&kp), "tangent, s {s}");
            assert_eq!(bits(&m), bits(&mp), "material, s {s}");
        }
    }

    #[test]
    fn four_elements_side_by_side_get_the_single_element_forces_bit_for_bit() {
        // force4 (four elements in the lanes of one kernel run; AVX2 where the processor has
        // it, and the portable build) against force element by element: energy and force
        // identical to the last bit, for four different states in the four lanes (a straight,
        // a small, a large and a stretched one), in every order; with other rules force4 calls
        // force itself.
        let bits = |(u, f): (f64, Vector8)| {
            let mut b = vec![u.to_bits()];
            b.extend(f.iter().map(|x| x.to_bits()));
            b
        };
        let mut states = [
            sample() * 0.0,
            sample() * 1e-3,
            sample() * 2.5,
            sample() * -0.7,
        ];
        states[3][2] += 0.01; // a stretched slope
        for el in [
            AncfElement::new(0.3 / 32.0, 1.5e9 * 2.5e-5, 3.125e-3),
            AncfElement::with_rules(
                0.3 / 8.0,
                37.5e3,
                3.125e-3,
                Quadrature::Gauss(5),
                Quadrature::Gauss(3),
            ),
        ] {
            for shift in 0..4 {
                let d: [Vector8; 4] = std::array::from_fn(|k| states[(k + shift) % 4]);
                let single = d.map(|dk| bits(el.force(&dk)));
                let mut out = [(f64::NAN, Vector8::zeros()); 4];
                el.force4(&d, &mut out);
                assert_eq!(out.map(bits), single, "dispatched, shift {shift}");
                if el.default_rules() {
                    let mut out = [(f64::NAN, Vector8::zeros()); 4];
                    el.force4_default_portable(&d, &mut out);
                    assert_eq!(out.map(bits), single, "portable, shift {shift}");
                }
            }
        }
    }

    #[test]
    fn four_elements_side_by_side_get_the_single_element_tangents_bit_for_bit() {
        // force_and_tangent4 against force_and_tangent element by element: energy, force,
        // tangent (added to different starting blocks) and material matrix identical to the
        // last bit, four different states in the four lanes, for the default and other rules.
        let bits8 = |(u, f): (f64, Vector8)| {
            let mut b = vec![u.to_bits()];
            b.extend(f.iter().map(|x| x.to_bits()));
            b
        };
        let bits = |b: &SlotBlocks| {
            [&b.xx[..], &b.yy[..], &b.xy[..]]
                .concat()
                .iter()
                .map(|x| x.to_bits())
                .collect::<Vec<_>>()
        };
        let mut states = [
            sample() * 0.0,
            sample() * 1e-3,
            sample() * 2.5,
            sample() * -0.7,
        ];
        states[3][2] += 0.01;
        let mut start = SlotBlocks::ZERO;
        start.xx[4] = 3.5;
        start.xy[7] = -1.25;
        for el in [
            AncfElement::new(0.3 / 32.0, 1.5e9 * 2.5e-5, 3.125e-3),
            AncfElement::with_rules(
                0.3 / 8.0,
                37.5e3,
                3.125e-3,
                Quadrature::Gauss(5),
                Quadrature::Gauss(3),
            ),
        ] {
            let tables = el.tangent_tables();
            for shift in 0..4 {
                let d: [Vector8; 4] = std::array::from_fn(|k| states[(k + shift) % 4]);
                let (mut k4, mut m4) = ([start; 4], [SlotBlocks::ZERO; 4]);
                let mut out = [(f64::NAN, Vector8::zeros()); 4];
                el.force_and_tangent4(&tables, &d, 0.37, &mut k4, Some(&mut m4), &mut out);
                for j in 0..4 {
                    let (mut k, mut m) = (start, SlotBlocks::ZERO);
                    let single = el.force_and_tangent(&tables, &d[j], 0.37, &mut k, Some(&mut m));
                    assert_eq!(
                        bits8(out[j]),
                        bits8(single),
                        "force, shift {shift} lane {j}"
                    );
                    assert_eq!(bits(&k4[j]), bits(&k), "tangent, shift {shift} lane {j}");
                    assert_eq!(bits(&m4[j]), bits(&m), "material, shift {shift} lane {j}");
                }
            }
        }
    }

    #[test]
    fn the_table_tangent_kernel_matches_the_full_evaluation() {
        // force_and_tangent against evaluate(): energy, force, tangent and material matrix
        // to round-off, for several rules and states; the tangent exactly symmetric
        for el in [
            AncfElement::new(0.25, 5.0e4, 3.0),
            AncfElement::with_rules(
                0.1,
                3.7e4,
                3.1e-3,
                Quadrature::Gauss(5),
                Quadrature::Gauss(2),
            ),
            AncfElement::with_rules(0.3, 1.0e6, 0.4, Quadrature::Gauss(3), Quadrature::Gauss(4)),
        ] {
            let tables = el.tangent_tables();
            for s in [0.0, 1.0, -0.7, 2.5] {
                let d = sample() * s;
                let e = el.evaluate(&d, Want::TangentAndMaterial);
                let scale = 0.37;
                let mut k = SlotBlocks::ZERO;
                let mut m = SlotBlocks::ZERO;
                let (u, f) = el.force_and_tangent(&tables, &d, scale, &mut k, Some(&mut m));
                let kmax = e.tangent.abs().max();
                let mmax = e.material.abs().max().max(1e-300);
                assert!((u - e.energy).abs() <= 1e-13 * e.energy.abs().max(1e-300));
                assert!((f - e.force).abs().max() <= 1e-13 * e.force.abs().max().max(1e-300));
                let (kt, km) = (k.matrix(), m.matrix());
                assert!(
                    (kt - e.tangent * scale).abs().max() <= 1e-13 * kmax * scale,
                    "{kt} vs {}",
                    e.tangent * scale
                );
                assert!((km - e.material).abs().max() <= 1e-13 * mmax);
                assert_eq!(kt, kt.transpose());
                assert_eq!(km, km.transpose());
                let x = sample();
                assert!((k.mul(&x) - kt * x).abs().max() <= 1e-14 * (kt * x).abs().max());
                // without the material matrix: the same tangent
                let mut k2 = SlotBlocks::ZERO;
                let _ = el.force_and_tangent(&tables, &d, scale, &mut k2, None);
                assert_eq!(k2.matrix(), kt);
                // it adds to what is there
                let _ = el.force_and_tangent(&tables, &d, scale, &mut k2, None);
                assert!((k2.matrix() - kt * 2.0).abs().max() <= 1e-14 * kmax);
            }
        }
    }

    #[test]
    fn slope_angle_derivatives_match_finite_differences() {
        let (sx, sy) = (0.7, -1.3);
        let (_, g, hs) = slope_angle(sx, sy);
        let h = 1e-6;
        let fd = |dx: f64, dy: f64| slope_angle(sx + dx, sy + dy);
        let gx = (fd(h, 0.0).0 - fd(-h, 0.0).0) / (2.0 * h);
        let gy = (fd(0.0, h).0 - fd(0.0, -h).0) / (2.0 * h);
        assert!((gx - g[0]).abs() < 1e-9 && (gy - g[1]).abs() < 1e-9);
        for j in 0..2 {
            let (dx, dy) = if j == 0 { (h, 0.0) } else { (0.0, h) };
            let (p, m) = (fd(dx, dy).1, fd(-dx, -dy).1);
            for i in 0..2 {
                assert!(((p[i] - m[i]) / (2.0 * h) - hs[i][j]).abs() < 1e-8);
            }
        }
    }
}
