//! The modes of a beam clamped to a hub that turns: the rigid rotation of the whole link plus
//! the clamped beam's modes, coupled through the link's inertia, solved by the secular equation.
//!
//! **Why.** A free hub (a rotor, possibly held by a position loop's spring K_p) on a stiff beam
//! has one mode far below the beam's: the rigid rotation (ω = 0) or the loop's mode
//! (ω² ≈ K_p/J). Taken from the dense pencil of the whole link, that frequency is the difference
//! of two numbers of the size of the beam's own, 1/λ − σ, and its error grows with the mesh's
//! stiffest element: on the stiff Fig. 6 link (k_δ = 1e8 N/m) an L/96 mesh gave the rigid
//! rotation ω = 0.38 rad/s and the loop's ω² 1e-3 off. Here that mode is exact by construction.
//!
//! **The equations.** The link's displacement is the rigid rotation ι (x on v, 1 on θ) by the
//! hub's angle θ₀ plus the clamped beam's motion y = Σ Φᵢ qᵢ (mass-normalised clamped modes, ωᵢ):
//!
//! [J gᵀ; g I] [θ̈₀; q̈] + [K_p 0; 0 Ω²] [θ₀; q] = [u − L f; −b f],
//!
//! J = ιᵀMι (rotor included), gᵢ = Φᵢᵀ(Mι)_c (c: the clamped DOFs), bᵢ = Φᵢ(tip); K ι = 0, so
//! the stiffness stays diagonal. A mode of frequency ω² = s has qᵢ = s gᵢ θ₀/(ωᵢ² − s) and
//!
//! f(s) = K_p − s J_r − s Σ gᵢ² ωᵢ²/(ωᵢ² − s) = 0,  J_r = J − Σ gᵢ² (the rotor and the root's
//! share of the inertia that the clamped modes cannot carry, ≥ 0),
//!
//! decreasing between consecutive ωᵢ² from +∞ to −∞: one root below ω₁² (0 when K_p = 0), one
//! between each pair, one above the last. Each root is found by bisection in its distance from
//! the nearer pole (so a root that hugs its pole keeps its digits). Its mode, mass-normalised:
//! θ-part a = 1/√N, N = J_r + Σ gᵢ² ωᵢ⁴/(ωᵢ² − s)² (= −f′(s)), hub gain a, tip gain
//! a (L + Σ bᵢ s gᵢ/(ωᵢ² − s)).

/// The coupled modes: frequencies [rad/s], the hub's angle per unit modal coordinate, the tip's
/// displacement per unit modal coordinate [m], ascending in frequency.
#[derive(Debug, Clone)]
pub struct HubModes {
    /// ωᵣ [rad/s].
    pub omegas: Vec<f64>,
    /// θ₀ of mode r (its mass-normalised hub angle) [rad].
    pub hub: Vec<f64>,
    /// The tip's transverse displacement of mode r [m].
    pub tip: Vec<f64>,
    /// The modal coordinate of a rigid rotation by 1 rad, φᵣᵀ M ι = a (J_r + Σ gᵢ² ωᵢ²/(ωᵢ² − s))
    /// [√(kg·m²)] per rad.
    pub rigid: Vec<f64>,
}

/// The clamped beam's side of [`hub_modes`].
#[derive(Debug, Clone)]
pub struct ClampedModes<'a> {
    /// ωᵢ [rad/s], ascending.
    pub omegas: &'a [f64],
    /// gᵢ = Φᵢᵀ (M ι)_c.
    pub coupling: &'a [f64],
    /// bᵢ = Φᵢ(tip) [m].
    pub tip: &'a [f64],
}

/// The coupled modes of the clamped modes `clamped` on a hub of total inertia `j_total` = ιᵀMι
/// [kg·m²] held by a spring `k_p` [N·m/rad] (0: a free rotation), the tip at `length` [m] on the
/// rigid rotation.
pub fn hub_modes(clamped: &ClampedModes<'_>, j_total: f64, k_p: f64, length: f64) -> HubModes {
    let p: Vec<f64> = clamped.omegas.iter().map(|w| w * w).collect();
    let g = clamped.coupling;
    let j_r = (j_total - g.iter().map(|x| x * x).sum::<f64>()).max(0.0);
    let n = p.len();
    let mut out = HubModes {
        omegas: Vec::with_capacity(n + 1),
        hub: Vec::with_capacity(n + 1),
        tip: Vec::with_capacity(n + 1),
        rigid: Vec::with_capacity(n + 1),
    };
    // f at s = origin + δ, with ωᵢ² − s formed as (ωᵢ² − origin) − δ
    let f = |origin: f64, delta: f64| -> f64 {
        let s = origin + delta;
        let mut sum = 0.0;
        for i in 0..n {
            sum += g[i] * g[i] * p[i] / ((p[i] - origin) - delta);
        }
        k_p - s * j_r - s * sum
    };
    for r in 0..=n {
        let lo = if r == 0 { 0.0 } else { p[r - 1] };
        let (origin, delta) = if r == 0 && k_p == 0.0 {
            (0.0, 0.0)
        } else if r < n {
            let hi = p[r];
            let mid = 0.5 * (hi - lo);
            if f(lo, mid) < 0.0 {
                // the root in (lo, mid): from lo (a pole, or s = 0 where f = K_p > 0)
                (lo, bisect(|d| f(lo, d), 0.0, mid, r > 0))
            } else {
                (hi, bisect(|d| f(hi, d), -mid, 0.0, true))
            }
        } else {
            // above the last pole: widen until f < 0
            let mut span = if n > 0 { lo.max(1e-300) } else { 1.0 };
            let mut guard = 0;
            while f(lo, span) >= 0.0 && guard < 2000 {
                span *= 2.0;
                guard += 1;
            }
            (lo, bisect(|d| f(lo, d), 0.0, span, n > 0))
        };
        let s = origin + delta;
        let (mut norm, mut tip, mut rigid) = (j_r, length, j_r);
        for i in 0..n {
            let d = (p[i] - origin) - delta;
            let ratio = p[i] / d;
            norm += g[i] * g[i] * ratio * ratio;
            tip += clamped.tip[i] * s * g[i] / d;
            rigid += g[i] * g[i] * ratio;
        }
        let a = 1.0 / norm.sqrt();
        out.omegas.push(s.max(0.0).sqrt());
        out.hub.push(a);
        out.tip.push(a * tip);
        out.rigid.push(a * rigid);
    }
    out
}

/// The root of a decreasing g on (a, b), g > 0 towards a and < 0 towards b; `open_at_zero`:
/// the end at 0 is a pole (g infinite there), so the search is geometric near it.
fn bisect(g: impl Fn(f64) -> f64, mut a: f64, mut b: f64, open_at_zero: bool) -> f64 {
    // a pole at 0: start the geometric search a long way from it
    if open_at_zero {
        let tiny = 1e-280 * (a.abs() + b.abs());
        if a == 0.0 {
            a = tiny;
        } else if b == 0.0 {
            b = -tiny;
        }
        // the root even nearer than that: it is the pole to every digit
        if a > 0.0 && g(a) <= 0.0 {
            return a;
        }
        if b < 0.0 && g(b) >= 0.0 {
            return b;
        }
    }
    for _ in 0..400 {
        let same_sign = a * b > 0.0;
        let m = if same_sign && (b / a > 4.0 || a / b > 4.0) {
            a.signum() * (a.abs().sqrt() * b.abs().sqrt())
        } else {
            0.5 * (a + b)
        };
        if m <= a || m >= b {
            break;
        }
        if g(m) > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two rigid bodies (J₁ on the hub, a mass on a lever) on a spring: the 2 × 2 problem in
    /// closed form against the secular solution.
    #[test]
    fn a_single_clamped_mode_matches_the_two_by_two_eigenproblem() {
        let (w1, g1, j, kp, b1, l) = (30.0, 0.8, 2.0, 50.0, 0.7, 1.0);
        let modes = hub_modes(
            &ClampedModes {
                omegas: &[w1],
                coupling: &[g1],
                tip: &[b1],
            },
            j,
            kp,
            l,
        );
        // det([kp − sJ, −s g; −s g, w1² − s]) = 0
        let (a2, a1, a0) = (j - g1 * g1, -(kp + j * w1 * w1), kp * w1 * w1);
        let disc = (a1 * a1 - 4.0 * a2 * a0).sqrt();
        let roots = [(-a1 - disc) / (2.0 * a2), (-a1 + disc) / (2.0 * a2)];
        for r in 0..2 {
            let s = roots[r];
            assert!((modes.omegas[r].powi(2) - s).abs() <= 1e-12 * s, "{r}");
            // mass-normalised: [1, q]ᵀ M [1, q] a² = 1
            let q = s * g1 / (w1 * w1 - s);
            let norm = j + 2.0 * g1 * q + q * q;
            let a = modes.hub[r];
            assert!((a * a * norm - 1.0).abs() < 1e-12);
            assert!((modes.tip[r] - a * (l + b1 * q)).abs() < 1e-12);
        }
    }
}
