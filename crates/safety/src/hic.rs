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
//! and end on samples. Cost: O(N·W) cells, W the number of samples in one window (O(N²) when the
//! window covers the trace), each a handful of closed-form evaluations.

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
    let n_seg = times.len() - 1;
    trace.seed(max_dt, &mut best);
    let window_max = window_maxima(times, &trace.a, max_dt);
    for i in 0..n_seg {
        // No window from segment i can beat the best: HIC² ≤ Δ_max² a_max⁵.
        let a_win = window_max[i];
        if !(a_win > 0.0 && max_dt * max_dt * a_win.powi(5) > best.value) {
            continue;
        }
        let mut a_max = trace.a[i];
        for j in i..n_seg {
            if times[j] - times[i + 1] > max_dt {
                break;
            }
            // Skip the cell when even its largest acceleration over its longest window cannot
            // beat the best value: HIC² ≤ Δ² a_max⁵ (the window mean never exceeds a_max).
            a_max = a_max.max(trace.a[j + 1]);
            let dt_max = max_dt.min(times[j + 1] - times[i]);
            if a_max > 0.0 && dt_max * dt_max * a_max.powi(5) > best.value {
                trace.search_cell(i, j, max_dt, &mut best);
            }
        }
    }
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

/// For each segment start i, the largest sample in [t_i, t_i + Δ_max] and the next sample after
/// it (every sample a window starting in segment i can reach), by a monotone deque: O(N).
fn window_maxima(t: &[f64], a: &[f64], max_dt: f64) -> Vec<f64> {
    let n = t.len();
    let mut out = vec![0.0; n];
    let mut deque = std::collections::VecDeque::new();
    let mut end = 0; // next sample to push
    for i in 0..n {
        // push every sample up to the first one beyond t_{i+1} + Δ_max (inclusive)
        let reach = t[(i + 1).min(n - 1)] + max_dt;
        while end < n {
            while deque.back().is_some_and(|&b: &usize| a[b] <= a[end]) {
                deque.pop_back();
            }
            deque.push_back(end);
            end += 1;
            if t[end - 1] > reach {
                break;
            }
        }
        while deque.front().is_some_and(|&f| f < i) {
            deque.pop_front();
        }
        out[i] = deque.front().map_or(a[i], |&f| a[f]);
    }
    out
}

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

    #[test]
    fn optimal_phase_solves_tan_phi_equals_five_thirds_phi() {
        let phi = half_sine_optimal_phase();
        assert_close("tan φ*", phi.tan(), 5.0 / 3.0 * phi, 1e-14);
        assert!(phi > 1.0 && phi < std::f64::consts::FRAC_PI_2);
    }
}
