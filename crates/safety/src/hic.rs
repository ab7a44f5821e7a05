//! Head Injury Criterion over a window (HIC15, HIC36).
//!
//! HIC = max over t₁ < t₂, t₂ − t₁ ≤ Δ_max of (t₂ − t₁) · [ (1/(t₂ − t₁)) ∫_{t₁}^{t₂} a(t) dt ]^{2.5}
//!
//! with a the resultant head acceleration in units of g₀ = 9.80665 m/s² and t in seconds
//! (Versace 1971; FMVSS 208 uses Δ_max = 15 ms and 36 ms). Windows whose integral is not
//! positive contribute 0.
//!
//! # Algorithm: the exact maximum for the piecewise-linear interpolant
//!
//! The samples are joined linearly, so the running integral is piecewise quadratic and
//! ln HIC(t₁, t₂) = 2.5 ln I − 1.5 ln Δ is smooth on each cell (t₁ in segment i, t₂ in segment
//! j). Its maximum over the whole domain lies at a point where every coordinate is either on a
//! cell boundary or stationary, so it is among these candidates, all found in closed form:
//!
//! 1. t₁ at a sample, t₂ free in a segment: ∂/∂t₂ = 0 ⇔ 2.5 a(t₂) Δ = 1.5 I — a quadratic;
//! 2. t₂ at a sample, t₁ free: 2.5 a(t₁) Δ = 1.5 I — a quadratic;
//! 3. on the window limit Δ = Δ_max: d I/d t₁ = 0 ⇔ a(t₁) = a(t₁ + Δ_max) — linear;
//! 4. interior of a cell: a(t₁) = a(t₂) = 0.6 I/Δ — t₂ linear in t₁, then a quadratic;
//!
//! plus the end points of every 1-D interval above (which include all cell corners). The result
//! is the continuous maximum of HIC for the interpolated trace, not only over windows that start
//! and end on samples.
//!
//! # Pruning: branch and bound over the window ends, exact for any trace
//!
//! There are O(N·W) cells (W the samples in one window: O(N²) when the window covers the
//! trace). For each window start segment i, the end segments j are visited down a segment tree
//! over the segments, and a block of ends [j_lo, j_hi] is skipped when an upper bound of HIC²
//! over all its windows does not exceed the best value found so far. With F the running integral,
//! a_max the largest sample in [t_i, t_{j_hi+1}] and I⁺ = max_{segments j_lo..j_hi} F −
//! min_{segment i} F (also ≤ a_max Δ⁺, Δ⁺ the longest window), every window of the block has
//!
//! HIC² = I⁵/Δ³ = (I/Δ)³ I² ≤ a_max³ (I⁺)²   and   HIC² ≤ (I⁺)⁵/(Δ⁻)³,
//!
//! Δ⁻ = t_{j_lo} − t_{i+1} the shortest window (the second bound only when Δ⁻ > 0). Both are
//! true upper bounds (the window mean never exceeds the largest sample; the integral never
//! exceeds I⁺), inflated by 1e-9 relative against rounding, so no cell that could raise the
//! maximum is skipped and the result is the one of the search over every cell (tested bit for
//! bit on random traces). For a smooth pulse the bounds are tight away from the diagonal and
//! only the cells near the optimum survive: about O(N log² N) work instead of O(N·W).

use serde::{Deserialize, Serialize};

use crate::SafetyError;
use crate::trace::check_series;

/// Standard gravity g₀ [m/s²] (CGPM 1901), the unit of acceleration in HIC.
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// The HIC window limit Δ_max.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HicWindow {
    /// HIC15: Δ_max = 15 ms.
    Hic15,
    /// HIC36: Δ_max = 36 ms.
    Hic36,
    /// Any Δ_max \[s\] > 0.
    Custom(f64),
}

impl HicWindow {
    /// The window limit Δ_max \[s\], validated (> 0, finite).
    pub fn max_duration(&self) -> Result<f64, SafetyError> {
        match *self {
            HicWindow::Hic15 => Ok(0.015),
            HicWindow::Hic36 => Ok(0.036),
            HicWindow::Custom(d) => Ok(flexrig_contact::validate::positive("hic_window", d)?),
        }
    }
}

/// The maximising window and its value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HicResult {
    /// HIC [s·g^2.5] (conventionally quoted without unit).
    pub hic: f64,
    /// Window start \[s\].
    pub t1: f64,
    /// Window end \[s\].
    pub t2: f64,
    /// Mean acceleration over the window [g].
    pub mean_acceleration_g: f64,
}

/// The exact HIC of the piecewise-linear interpolant of `acceleration` [m/s², resultant] sampled
/// at `times` \[s\] (strictly increasing), with window limit `window`. A trace whose every
/// window has a non-positive integral gives HIC = 0 on an empty window at the first sample.
pub fn hic(
    times: &[f64],
    acceleration: &[f64],
    window: HicWindow,
) -> Result<HicResult, SafetyError> {
    check_series("acceleration", times, acceleration)?;
    let max_dt = window.max_duration()?;
    let trace = Interpolant::new(times, acceleration);
    let mut best = Best {
        value: 0.0,
        t1: times[0],
        t2: times[0],
    };
    trace.seed(max_dt, &mut best);
    trace.branch_and_bound(max_dt, &mut best);
    // best.value holds HIC² = I⁵/Δ³ (a monotone transform that needs no powf per candidate).
    let hic = best.value.sqrt();
    let mean = if best.t2 > best.t1 {
        (hic / (best.t2 - best.t1)).powf(0.4)
    } else {
        0.0
    };
    Ok(HicResult {
        hic,
        t1: best.t1,
        t2: best.t2,
        mean_acceleration_g: mean,
    })
}

/// The closed-form HIC of a half-sine pulse a(t) = A sin(π t/T), 0 ≤ t ≤ T (A in m/s², T in s).
///
/// By symmetry the best window of any length is centred on the peak; with half-width φ in phase
/// (window length Δ = 2φT/π) HIC(φ) = (2T/π) (A/g₀)^{2.5} sin^{2.5}φ / φ^{1.5}, which increases up
/// to the root φ* ≈ 1.05280 of tan φ = (5/3) φ and decreases after it. So the optimum is
/// φ = min(φ*, π Δ_max/(2T)): the window limit binds when Δ_max < (2φ*/π) T ≈ 0.67023 T. Even an
/// unlimited window never covers the whole pulse: at its ends a = 0 < 0.6 × the window mean.
pub fn hic_half_sine(amplitude: f64, duration: f64, window: HicWindow) -> Result<f64, SafetyError> {
    let a = flexrig_contact::validate::positive("amplitude", amplitude)? / STANDARD_GRAVITY;
    let t = flexrig_contact::validate::positive("duration", duration)?;
    let max_dt = window.max_duration()?;
    let phi = half_sine_optimal_phase().min(std::f64::consts::PI * max_dt / (2.0 * t));
    Ok(2.0 * t / std::f64::consts::PI * a.powf(2.5) * phi.sin().powf(2.5) / phi.powf(1.5))
}

/// φ* ∈ (0, π/2), the root of tan φ = (5/3) φ (Newton from π/3, quadratic convergence).
pub fn half_sine_optimal_phase() -> f64 {
    // g(φ) = 5φ cos φ − 3 sin φ = 0 ⇔ tan φ = 5φ/3; g'(φ) = 2 cos φ − 5φ sin φ.
    let mut phi = std::f64::consts::FRAC_PI_3;
    for _ in 0..50 {
        let g = 5.0 * phi * phi.cos() - 3.0 * phi.sin();
        let dg = 2.0 * phi.cos() - 5.0 * phi * phi.sin();
        let step = g / dg;
        phi -= step;
        if step.abs() < 1e-16 {
            break;
        }
    }
    phi
}

/// End segments below which the branch and bound visits cells one by one (each by
/// [`Interpolant::cell_bound`]) rather than down the tree.
const LEAF_BLOCK: usize = 16;

struct Best {
    /// HIC² = I⁵/Δ³ of the best window so far.
    value: f64,
    t1: f64,
    t2: f64,
}

/// The piecewise-linear acceleration [g] and its running integral [g·s].
struct Interpolant<'a> {
    t: &'a [f64],
    a: Vec<f64>,
    slope: Vec<f64>,
    integral: Vec<f64>,
}

impl<'a> Interpolant<'a> {
    fn new(t: &'a [f64], acceleration: &[f64]) -> Self {
        let a: Vec<f64> = acceleration.iter().map(|x| x / STANDARD_GRAVITY).collect();
        let n = t.len();
        let mut slope = Vec::with_capacity(n - 1);
        let mut integral = Vec::with_capacity(n);
        integral.push(0.0);
        for k in 0..n - 1 {
            let h = t[k + 1] - t[k];
            slope.push((a[k + 1] - a[k]) / h);
            integral.push(integral[k] + 0.5 * h * (a[k] + a[k + 1]));
        }
        Interpolant {
            t,
            a,
            slope,
            integral,
        }
    }

    /// A good first candidate, so that the bound prunes early: windows between samples centred
    /// on the largest sample (any window is a valid lower bound of the maximum).
    fn seed(&self, max_dt: f64, best: &mut Best) {
        let n = self.t.len();
        let peak = (0..n).fold(0, |b, k| if self.a[k] > self.a[b] { k } else { b });
        let (mut lo, mut hi) = (peak, peak);
        while lo > 0 || hi + 1 < n {
            let widen_lo = lo > 0 && (hi + 1 >= n || self.a[lo - 1] >= self.a[hi + 1]);
            if widen_lo {
                lo -= 1;
            } else {
                hi += 1;
            }
            if self.t[hi] - self.t[lo] > max_dt {
                break;
            }
            let (i, x) = (lo, 0.0);
            let (j, y) = (hi - 1, self.h(hi - 1));
            self.offer(i, x, j, y, max_dt, best);
        }
    }

    fn h(&self, k: usize) -> f64 {
        self.t[k + 1] - self.t[k]
    }

    /// The smallest and the largest running integral over segment k (its ends, and its
    /// interior extremum where a = 0).
    fn integral_range(&self, k: usize) -> (f64, f64) {
        let (f0, f1) = (self.integral[k], self.integral[k + 1]);
        let (mut lo, mut hi) = (f0.min(f1), f0.max(f1));
        let m = self.slope[k];
        if m != 0.0 {
            let x = -self.a[k] / m;
            if x > 0.0 && x < self.h(k) {
                let f = self.integral_at(k, x);
                lo = lo.min(f);
                hi = hi.max(f);
            }
        }
        (lo, hi)
    }

    /// Every cell that may hold a window better than `best`, by branch and bound over the end
    /// segments (module docs); the others are skipped by a true upper bound.
    fn branch_and_bound(&self, max_dt: f64, best: &mut Best) {
        let n_seg = self.t.len() - 1;
        let ranges: Vec<(f64, f64)> = (0..n_seg).map(|k| self.integral_range(k)).collect();
        let f_max = MaxTree::new(ranges.iter().map(|r| r.1));
        let a_max = MaxTree::new(self.a.iter().copied());
        let mut j_end = 0;
        for i in 0..n_seg {
            // the last end segment a window from segment i can reach
            j_end = j_end.max(i);
            while j_end + 1 < n_seg && self.t[j_end + 1] - self.t[i + 1] <= max_dt {
                j_end += 1;
            }
            let row = Row {
                i,
                j_end,
                f_min: ranges[i].0,
                max_dt,
            };
            self.descend(&row, &f_max, &a_max, 1, 0, f_max.size - 1, best);
        }
    }

    /// Visits the tree node `node` (end segments lo..=hi) for the window starts of `row`.
    #[allow(clippy::too_many_arguments)]
    fn descend(
        &self,
        row: &Row,
        f_max: &MaxTree,
        a_max: &MaxTree,
        node: usize,
        lo: usize,
        hi: usize,
        best: &mut Best,
    ) {
        let (j_lo, j_hi) = (lo.max(row.i), hi.min(row.j_end));
        if j_lo > j_hi {
            return;
        }
        if !(self.block_bound(
            row,
            f_max.node(node),
            a_max.range(row.i, j_hi + 1),
            j_lo,
            j_hi,
        ) > best.value)
        {
            return;
        }
        if j_lo > row.i + 1
            && !(self.ends_bound(row.i, j_lo, j_hi, a_max.range(j_lo, j_hi + 1)) > best.value)
        {
            return;
        }
        if hi - lo < LEAF_BLOCK {
            // a few end segments: each cell by its own (tight) bound, in order
            for j in j_lo..=j_hi {
                if self.cell_bound(row.i, j) > best.value {
                    self.search_cell(row.i, j, row.max_dt, best);
                }
            }
            return;
        }
        let mid = (lo + hi) / 2;
        self.descend(row, f_max, a_max, 2 * node, lo, mid, best);
        self.descend(row, f_max, a_max, 2 * node + 1, mid + 1, hi, best);
    }

    /// An upper bound of HIC² (times 1 + 1e-9) over the windows from segment `row.i` to the
    /// segments j_lo..=j_hi, given the largest running integral `f_top` over those segments
    /// (or a superset) and the largest sample `a_top` in [t_i, t_{j_hi+1}].
    fn block_bound(&self, row: &Row, f_top: f64, a_top: f64, j_lo: usize, j_hi: usize) -> f64 {
        if !(a_top > 0.0) {
            return 0.0;
        }
        let i = row.i;
        let longest = row.max_dt.min(self.t[j_hi + 1] - self.t[i]);
        let integral = (f_top - row.f_min).min(a_top * longest);
        if !(integral > 0.0) {
            return 0.0;
        }
        let i2 = integral * integral;
        let mut bound = a_top * a_top * a_top * i2;
        let shortest = self.t[j_lo] - self.t[i + 1];
        if shortest > 0.0 {
            bound = bound.min(i2 * i2 * integral / (shortest * shortest * shortest));
        }
        bound * (1.0 + 1e-9)
    }

    /// An upper bound of HIC² (times 1 + 1e-9) over the cell (t₁ in segment i, t₂ in segment
    /// j), tight to second order in the segments' lengths: F(t_i + x) ≥ F_i + x min(a_i, a_{i+1})
    /// and F(t_j + y) ≤ F_j + y max(a_j, a_{j+1}), so I ≤ Ĩ(x, y) = I₀₀ + A y − B x, linear,
    /// with Δ = Δ₀₀ + y − x; along either coordinate Ĩ⁵/Δ³ = (c + A y)⁵/(d + y)³ has no interior
    /// maximum where Ĩ > 0 (its one stationary point is a minimum), so the bound is the largest
    /// of the four corners (0 where Ĩ ≤ 0). Infinite (no bound) when a window of the cell can
    /// have Δ ≤ 0.
    fn cell_bound(&self, i: usize, j: usize) -> f64 {
        let (h_i, h_j) = (self.h(i), self.h(j));
        let d00 = self.t[j] - self.t[i];
        if !(d00 - h_i > 0.0) {
            return f64::INFINITY;
        }
        let b = self.a[i].min(self.a[i + 1]);
        let a = self.a[j].max(self.a[j + 1]);
        let i00 = self.integral[j] - self.integral[i];
        let mut bound = 0.0f64;
        for (x, y) in [(0.0, 0.0), (0.0, h_j), (h_i, 0.0), (h_i, h_j)] {
            let integral = i00 + a * y - b * x;
            if integral > 0.0 {
                let dt = d00 + y - x;
                let i2 = integral * integral;
                bound = bound.max(i2 * i2 * integral / (dt * dt * dt));
            }
        }
        bound * (1.0 + 1e-9)
    }

    /// An upper bound of HIC² (times 1 + 1e-9) over the windows from segment i to the end
    /// segments j_lo..=j_hi (j_lo > i + 1), `a_top` the largest sample over those: as
    /// [`Interpolant::cell_bound`] with t₂ = t_{j_lo} + u anywhere in the block,
    /// F(t₂) ≤ F_{j_lo} + a_top u, so I ≤ I₀ + a_top u − B x and Δ = Δ₀ + u − x: the largest
    /// of the four corners u ∈ {0, t_{j_hi+1} − t_{j_lo}}, x ∈ {0, h_i}.
    fn ends_bound(&self, i: usize, j_lo: usize, j_hi: usize, a_top: f64) -> f64 {
        let h_i = self.h(i);
        let span = self.t[j_hi + 1] - self.t[j_lo];
        let d00 = self.t[j_lo] - self.t[i];
        if !(d00 - h_i > 0.0) {
            return f64::INFINITY;
        }
        let b = self.a[i].min(self.a[i + 1]);
        let i00 = self.integral[j_lo] - self.integral[i];
        let mut bound = 0.0f64;
        for (x, u) in [(0.0, 0.0), (0.0, span), (h_i, 0.0), (h_i, span)] {
            let integral = i00 + a_top * u - b * x;
            if integral > 0.0 {
                let dt = d00 + u - x;
                let i2 = integral * integral;
                bound = bound.max(i2 * i2 * integral / (dt * dt * dt));
            }
        }
        bound * (1.0 + 1e-9)
    }

    /// Running integral at offset x into segment k.
    fn integral_at(&self, k: usize, x: f64) -> f64 {
        self.integral[k] + x * (self.a[k] + 0.5 * self.slope[k] * x)
    }

    /// Offers the window (segment i at x, segment j at y) to `best`.
    fn offer(&self, i: usize, x: f64, j: usize, y: f64, max_dt: f64, best: &mut Best) {
        let (h_i, h_j) = (self.h(i), self.h(j));
        let (Some(x), Some(y)) = (clamp_offset(x, h_i), clamp_offset(y, h_j)) else {
            return;
        };
        let t1 = self.t[i] + x;
        let t2 = self.t[j] + y;
        let dt = t2 - t1;
        // Allow the window limit up to rounding of t1 + Δ_max.
        if !(dt > 0.0) || dt > max_dt * (1.0 + 4.0 * f64::EPSILON) {
            return;
        }
        let integral = self.integral_at(j, y) - self.integral_at(i, x);
        if !(integral > 0.0) {
            return;
        }
        let i2 = integral * integral;
        let value = i2 * i2 * integral / (dt * dt * dt);
        if value > best.value {
            *best = Best { value, t1, t2 };
        }
    }

    /// All candidates of the cell (t₁ in segment i, t₂ in segment j).
    fn search_cell(&self, i: usize, j: usize, max_dt: f64, best: &mut Best) {
        let (ti, tj) = (self.t[i], self.t[j]);
        let (h_i, h_j) = (self.h(i), self.h(j));
        let (ai, aj) = (self.a[i], self.a[j]);
        let (mi, mj) = (self.slope[i], self.slope[j]);

        // 1. t₁ = t_i, t₂ = t_j + y: 1.75 m_j y² + (a_j + 2.5 m_j D0) y + 2.5 a_j D0 − 1.5 J0 = 0.
        let d0 = tj - ti;
        let j0 = self.integral[j] - self.integral[i];
        let (lo, hi) = ((ti - tj).max(0.0), h_j.min(ti + max_dt - tj));
        if lo <= hi {
            for y in [lo, hi] {
                self.offer(i, 0.0, j, y, max_dt, best);
            }
            for y in quadratic_roots(1.75 * mj, aj + 2.5 * mj * d0, 2.5 * aj * d0 - 1.5 * j0) {
                if y > lo && y < hi {
                    self.offer(i, 0.0, j, y, max_dt, best);
                }
            }
        }

        // 2. t₂ = t_{j+1}, t₁ = t_i + x: −1.75 m_i x² + (−a_i + 2.5 m_i D0) x + 2.5 a_i D0 − 1.5 J0 = 0.
        let t2 = self.t[j + 1];
        let d0 = t2 - ti;
        let j0 = self.integral[j + 1] - self.integral[i];
        let (lo, hi) = ((t2 - max_dt - ti).max(0.0), h_i.min(t2 - ti));
        if lo <= hi {
            for x in [lo, hi] {
                self.offer(i, x, j, h_j, max_dt, best);
            }
            for x in quadratic_roots(-1.75 * mi, -ai + 2.5 * mi * d0, 2.5 * ai * d0 - 1.5 * j0) {
                if x > lo && x < hi {
                    self.offer(i, x, j, h_j, max_dt, best);
                }
            }
        }

        // 3. Δ = Δ_max: t₂ = t₁ + Δ_max, y = c + x; a(t₁) = a(t₂).
        let c = ti + max_dt - tj;
        let (lo, hi) = ((-c).max(0.0), h_i.min(h_j - c));
        if lo <= hi {
            for x in [lo, hi] {
                self.offer(i, x, j, c + x, max_dt, best);
            }
            if mi != mj {
                let x = (aj + mj * c - ai) / (mi - mj);
                if x > lo && x < hi {
                    self.offer(i, x, j, c + x, max_dt, best);
                }
            }
        }

        // 4. Interior: a(t₁) = a(t₂) and 2.5 a(t₁) Δ = 1.5 I.
        self.interior(i, j, max_dt, best);
    }

    fn interior(&self, i: usize, j: usize, max_dt: f64, best: &mut Best) {
        let (ai, aj) = (self.a[i], self.a[j]);
        let (mi, mj) = (self.slope[i], self.slope[j]);
        let d0 = self.t[j] - self.t[i];
        let j0 = self.integral[j] - self.integral[i];
        if mj != 0.0 {
            // y = α + β x.
            let alpha = (ai - aj) / mj;
            let beta = mi / mj;
            let (p0, p1) = (d0 + alpha, beta - 1.0);
            let q0 = j0 + aj * alpha + 0.5 * mj * alpha * alpha;
            let q1 = aj * beta + mj * alpha * beta - ai;
            let q2 = 0.5 * (mj * beta * beta - mi);
            let roots = quadratic_roots(
                2.5 * mi * p1 - 1.5 * q2,
                2.5 * (ai * p1 + mi * p0) - 1.5 * q1,
                2.5 * ai * p0 - 1.5 * q0,
            );
            for x in roots {
                self.offer(i, x, j, alpha + beta * x, max_dt, best);
            }
        } else if mi != 0.0 && aj != 0.0 {
            // a(t₂) = a_j everywhere in segment j: t₁ fixed by a(t₁) = a_j, y from a linear equation.
            let x = (aj - ai) / mi;
            let rhs = -2.5 * aj * (d0 - x) + 1.5 * (j0 - ai * x - 0.5 * mi * x * x);
            self.offer(i, x, j, rhs / aj, max_dt, best);
        }
        // Both segments flat: HIC is constant along t₁ = t₂ − const, so a boundary attains it.
    }
}

/// The window starts of one segment i: their end segments reach to `j_end`; `f_min` is the
/// smallest running integral over segment i.
struct Row {
    i: usize,
    j_end: usize,
    f_min: f64,
    max_dt: f64,
}

/// A max segment tree over a sequence (padded to a power of two with −∞): the largest value of
/// a node and of any index range.
struct MaxTree {
    size: usize,
    node: Vec<f64>,
}

impl MaxTree {
    fn new(values: impl ExactSizeIterator<Item = f64>) -> Self {
        let size = values.len().next_power_of_two();
        let mut node = vec![f64::NEG_INFINITY; 2 * size];
        for (k, v) in values.enumerate() {
            node[size + k] = v;
        }
        for k in (1..size).rev() {
            node[k] = node[2 * k].max(node[2 * k + 1]);
        }
        MaxTree { size, node }
    }

    /// The largest value under tree node `k` (1 the root).
    fn node(&self, k: usize) -> f64 {
        self.node[k]
    }

    /// The largest value with index in lo..=hi.
    fn range(&self, lo: usize, hi: usize) -> f64 {
        let (mut l, mut r) = (lo + self.size, hi + self.size + 1);
        let mut out = f64::NEG_INFINITY;
        while l < r {
            if l & 1 == 1 {
                out = out.max(self.node[l]);
                l += 1;
            }
            if r & 1 == 1 {
                r -= 1;
                out = out.max(self.node[r]);
            }
            l /= 2;
            r /= 2;
        }
        out
    }
}

/// An offset into a segment of length h, clamped when it is outside by rounding only.
fn clamp_offset(x: f64, h: f64) -> Option<f64> {
    let tol = 1e-12 * h;
    if x >= -tol && x <= h + tol {
        Some(x.clamp(0.0, h))
    } else {
        None
    }
}

/// Real roots of a x² + b x + c = 0 (a linear equation when a = 0); NaN marks no root.
fn quadratic_roots(a: f64, b: f64, c: f64) -> [f64; 2] {
    let none = f64::NAN;
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return [none, none];
    }
    if a.abs() <= 1e-14 * scale {
        return if b != 0.0 {
            [-c / b, none]
        } else {
            [none, none]
        };
    }
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return [none, none];
    }
    // Citardauq form for the root that would cancel.
    let q = -0.5 * (b + b.signum() * disc.sqrt());
    if q == 0.0 {
        return [0.0, none];
    }
    [q / a, c / q]
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrig_contact::tolerance::assert_close;

    #[test]
    fn quadratic_roots_are_roots() {
        for (a, b, c) in [
            (1.0, -3.0, 2.0),
            (1e-3, 5.0, -1.0),
            (0.0, 2.0, -4.0),
            (2.0, 1e8, 1.0),
        ] {
            for r in quadratic_roots(a, b, c) {
                if r.is_finite() {
                    let residual = a * r * r + b * r + c;
                    let scale = (a * r * r).abs() + (b * r).abs() + c.abs();
                    assert!(residual.abs() <= 1e-14 * scale, "{a} {b} {c}: {r}");
                }
            }
        }
    }

    /// The search over every cell, without pruning (the reference of the branch and bound).
    fn hic_every_cell(times: &[f64], acceleration: &[f64], max_dt: f64) -> f64 {
        let trace = Interpolant::new(times, acceleration);
        let mut best = Best {
            value: 0.0,
            t1: times[0],
            t2: times[0],
        };
        let n_seg = times.len() - 1;
        for i in 0..n_seg {
            for j in i..n_seg {
                if times[j] - times[i + 1] > max_dt {
                    break;
                }
                trace.search_cell(i, j, max_dt, &mut best);
            }
        }
        best.value.sqrt()
    }

    /// A linear congruential generator (Knuth's MMIX constants): uniform in [0, 1).
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
    }

    #[test]
    fn branch_and_bound_equals_the_search_over_every_cell_bit_for_bit() {
        let mut rng = Lcg(0x5eed);
        for case in 0..400 {
            let n = 2 + (rng.next() * 400.0) as usize;
            let uniform = case % 3 == 0;
            let mut t = vec![0.0];
            for _ in 1..n {
                let h = if uniform {
                    1e-4
                } else {
                    1e-5 + 2e-4 * rng.next()
                };
                t.push(t.last().unwrap() + h);
            }
            let span = t[n - 1];
            let a: Vec<f64> = t
                .iter()
                .map(|&x| match case % 4 {
                    // noise of both signs
                    0 => 2000.0 * (rng.next() - 0.3),
                    // a half-sine with noise
                    1 => 4000.0 * (std::f64::consts::PI * x / span).sin() + 300.0 * rng.next(),
                    // sparse spikes on a negative floor
                    2 => {
                        if rng.next() < 0.05 {
                            5000.0 * rng.next()
                        } else {
                            -50.0 * rng.next()
                        }
                    }
                    // two pulses
                    _ => {
                        3000.0 * (-((x - 0.3 * span) / (0.05 * span)).powi(2)).exp()
                            + 2500.0 * (-((x - 0.7 * span) / (0.1 * span)).powi(2)).exp()
                    }
                })
                .collect();
            let max_dt = match case % 5 {
                0 => 0.015,
                1 => span * 0.1,
                2 => span * (0.05 + rng.next()),
                3 => span * 3.0,
                _ => span * 0.01 + 1e-9,
            };
            let fast = hic(&t, &a, HicWindow::Custom(max_dt)).unwrap().hic;
            let every = hic_every_cell(&t, &a, max_dt);
            assert_eq!(
                fast.to_bits(),
                every.to_bits(),
                "case {case}: {fast} vs {every}"
            );
        }
    }

    #[test]
    fn a_half_sine_of_16385_samples_is_within_1e_7_of_the_closed_form() {
        // 40 g over 20 ms, sampled at 16385 points (the cost that motivated the pruning).
        let (amp, dur, n) = (40.0 * STANDARD_GRAVITY, 0.02, 16385);
        let t: Vec<f64> = (0..n).map(|k| dur * k as f64 / (n - 1) as f64).collect();
        let a: Vec<f64> = t
            .iter()
            .map(|&x| amp * (std::f64::consts::PI * x / dur).sin())
            .collect();
        for window in [HicWindow::Hic15, HicWindow::Hic36] {
            let got = hic(&t, &a, window).unwrap().hic;
            let exact = hic_half_sine(amp, dur, window).unwrap();
            // the interpolant's integral is low by about (π h/T)²/12 ≈ 3e-9 relative, HIC ∝ I^2.5
            assert_close("HIC of the sampled half-sine", got, exact, 1e-7);
        }
    }

    #[test]
    fn optimal_phase_solves_tan_phi_equals_five_thirds_phi() {
        let phi = half_sine_optimal_phase();
        assert_close("tan φ*", phi.tan(), 5.0 / 3.0 * phi, 1e-14);
        assert!(phi > 1.0 && phi < std::f64::consts::FRAC_PI_2);
    }
}
