//! An explicit adaptive Runge–Kutta integrator of order 8 (Dormand–Prince 8(5,3), Hairer's
//! DOP853) with 7th-order dense output, for small systems y' = F(t, y) of fixed size N.
//!
//! Error control as in Hairer–Nørsett–Wanner §II.10: the 5th- and 3rd-order embedded estimates
//! are combined, err = |h| ‖e5‖² / √(‖e5‖² + 0.01 ‖e3‖²) in the weighted RMS norm with weights
//! atol_i + rtol·max(|y_i|, |y_new_i|); a step is accepted when err ≤ 1 and the next step is
//! h·min(10, max(0.2, 0.9 err^{−1/8})) (no growth right after a rejection).
//!
//! The integrator holds its own state and counters (no global state); the caller owns the loop,
//! so events are found between accepted steps on the dense output.

use super::tableau::{A, B, C, D, E3, E5, STAGES, STAGES_EXTENDED};

/// A first-order system y' = F(t, y) of size N.
pub trait OdeSystem<const N: usize> {
    /// The right-hand side F(t, y).
    fn rhs(&self, t: f64, y: &[f64; N]) -> [f64; N];
}

/// Tolerances and limits of [`Dop853`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dop853Options<const N: usize> {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance per component (in the component's unit).
    pub atol: [f64; N],
    /// First step size; `None` selects it automatically (Hairer's algorithm).
    pub first_step: Option<f64>,
    /// Largest step size.
    pub max_step: f64,
    /// Cap on the number of attempted steps.
    pub max_steps: usize,
}

/// Why a step failed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepFailure {
    /// The step size fell below the resolution of t.
    StepTooSmall {
        /// Time reached \[s\].
        t: f64,
        /// Step size tried \[s\].
        h: f64,
    },
    /// The right-hand side or the state became non-finite.
    NonFinite {
        /// Time reached \[s\].
        t: f64,
    },
    /// More than `max_steps` attempts.
    TooManySteps {
        /// Time reached \[s\].
        t: f64,
        /// The cap.
        max_steps: usize,
    },
}

impl std::fmt::Display for StepFailure {
    /// In words, with compact numbers (a message for the user, not a Rust value).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            StepFailure::StepTooSmall { t, h } => write!(
                f,
                "at t = {t:.6e} s the step size ({h:.3e} s) fell below the resolution of t"
            ),
            StepFailure::NonFinite { t } => {
                write!(f, "at t = {t:.6e} s the state became non-finite")
            }
            StepFailure::TooManySteps { t, max_steps } => write!(
                f,
                "{max_steps} steps were not enough (stopped at t = {t:.6e} s): the motion is \
                 stiffer or longer than the integrator's step budget"
            ),
        }
    }
}

/// Work counters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Dop853Stats {
    /// Right-hand-side evaluations.
    pub rhs_evals: usize,
    /// Accepted steps.
    pub accepted: usize,
    /// Rejected steps.
    pub rejected: usize,
}

/// The integrator: current point, last step (for dense output) and counters.
#[derive(Debug, Clone)]
pub struct Dop853<const N: usize> {
    options: Dop853Options<N>,
    t: f64,
    y: [f64; N],
    f: [f64; N],
    h: f64,
    t_old: f64,
    y_old: [f64; N],
    h_prev: f64,
    k: [[f64; N]; STAGES_EXTENDED],
    dense_ready: bool,
    last_rejected: bool,
    /// (h, err) of the previous rejected attempt from the current point, if any.
    rejected_attempt: Option<(f64, f64)>,
    stats: Dop853Stats,
}

/// The 7th-order interpolant over the last accepted step.
#[derive(Debug, Clone, Copy)]
pub struct DenseOutput<const N: usize> {
    t_old: f64,
    h: f64,
    y_old: [f64; N],
    coeffs: [[f64; N]; 7],
}

impl<const N: usize> DenseOutput<N> {
    /// y(t) for t in the last step [t_old, t_old + h].
    pub fn eval(&self, t: f64) -> [f64; N] {
        let x = (t - self.t_old) / self.h;
        let mut y = [0.0; N];
        for (i, c) in self.coeffs.iter().rev().enumerate() {
            let w = if i % 2 == 0 { x } else { 1.0 - x };
            for j in 0..N {
                y[j] = (y[j] + c[j]) * w;
            }
        }
        for j in 0..N {
            y[j] += self.y_old[j];
        }
        y
    }

    /// Start of the step \[s\].
    pub fn t_start(&self) -> f64 {
        self.t_old
    }

    /// End of the step \[s\].
    pub fn t_end(&self) -> f64 {
        self.t_old + self.h
    }
}

const SAFETY: f64 = 0.9;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;

impl<const N: usize> Dop853<N> {
    /// Starts at (t0, y0).
    pub fn new(
        system: &impl OdeSystem<N>,
        t0: f64,
        y0: [f64; N],
        options: Dop853Options<N>,
    ) -> Self {
        let mut stats = Dop853Stats::default();
        let f0 = system.rhs(t0, &y0);
        stats.rhs_evals += 1;
        let mut s = Dop853 {
            options,
            t: t0,
            y: y0,
            f: f0,
            h: 0.0,
            t_old: t0,
            y_old: y0,
            h_prev: 0.0,
            k: [[0.0; N]; STAGES_EXTENDED],
            dense_ready: false,
            last_rejected: false,
            rejected_attempt: None,
            stats,
        };
        s.h = match options.first_step {
            Some(h) => h.min(options.max_step),
            None => s.initial_step(system),
        };
        s
    }

    /// Current time \[s\].
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &[f64; N] {
        &self.y
    }

    /// Derivative at the current point.
    pub fn dy(&self) -> &[f64; N] {
        &self.f
    }

    /// Start of the last accepted step \[s\].
    pub fn t_old(&self) -> f64 {
        self.t_old
    }

    /// State at the start of the last accepted step.
    pub fn y_old(&self) -> &[f64; N] {
        &self.y_old
    }

    /// Work counters so far.
    pub fn stats(&self) -> Dop853Stats {
        self.stats
    }

    fn scale(&self, a: &[f64; N], b: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| {
            self.options.atol[i] + self.options.rtol * a[i].abs().max(b[i].abs())
        })
    }

    fn rms(v: &[f64; N], scale: &[f64; N]) -> f64 {
        (v.iter()
            .zip(scale)
            .map(|(x, s)| (x / s).powi(2))
            .sum::<f64>()
            / N as f64)
            .sqrt()
    }

    /// Hairer's starting step: a step for which an explicit Euler step would change the solution
    /// by about 1 % of the tolerance, then corrected by the second derivative.
    fn initial_step(&mut self, system: &impl OdeSystem<N>) -> f64 {
        let scale = self.scale(&self.y, &self.y);
        let d0 = Self::rms(&self.y, &scale);
        let d1 = Self::rms(&self.f, &scale);
        let h0 = if d0 < 1e-5 || d1 < 1e-5 {
            1e-6
        } else {
            0.01 * d0 / d1
        };
        let y1: [f64; N] = std::array::from_fn(|i| self.y[i] + h0 * self.f[i]);
        let f1 = system.rhs(self.t + h0, &y1);
        self.stats.rhs_evals += 1;
        let df: [f64; N] = std::array::from_fn(|i| f1[i] - self.f[i]);
        let d2 = Self::rms(&df, &scale) / h0;
        let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            (0.01 / d1.max(d2)).powf(1.0 / 8.0)
        };
        (100.0 * h0).min(h1).min(self.options.max_step)
    }

    /// The state reached by one step of the method from the start of the last accepted step to
    /// `t_target` ∈ (t_old, t] (11 evaluations). About an order of magnitude more accurate than
    /// the 7th-order dense output (measured on the impact peak); the integrator's own state is
    /// unchanged.
    pub fn restep_to(&mut self, system: &impl OdeSystem<N>, t_target: f64) -> [f64; N] {
        let h = t_target - self.t_old;
        if !(h > 0.0) {
            return self.y_old;
        }
        let mut k = [[0.0; N]; STAGES];
        k[0] = self.k[0];
        for s in 1..STAGES {
            let ys: [f64; N] = std::array::from_fn(|i| {
                self.y_old[i] + h * (0..s).map(|j| A[s][j] * k[j][i]).sum::<f64>()
            });
            k[s] = system.rhs(self.t_old + C[s] * h, &ys);
        }
        self.stats.rhs_evals += STAGES - 1;
        std::array::from_fn(|i| {
            self.y_old[i] + h * (0..STAGES).map(|j| B[j] * k[j][i]).sum::<f64>()
        })
    }

    /// Goes back to the start of the last accepted step (its end state is discarded), keeping the
    /// proposed step size and the counters.
    pub fn rewind(&mut self) {
        self.t = self.t_old;
        self.y = self.y_old;
        self.f = self.k[0];
        self.dense_ready = false;
        self.rejected_attempt = None;
    }

    /// Advances by one accepted step that does not go past `t_end`, landing on it exactly when
    /// within reach.
    pub fn step_until(
        &mut self,
        system: &impl OdeSystem<N>,
        t_end: f64,
    ) -> Result<(), StepFailure> {
        let remaining = t_end - self.t;
        if self.h >= remaining {
            self.h = remaining;
            self.step(system)?;
            if self.h_prev == remaining {
                self.t = t_end;
            }
            return Ok(());
        }
        self.step(system)
    }

    /// Advances by one accepted step (retrying with smaller steps as needed).
    pub fn step(&mut self, system: &impl OdeSystem<N>) -> Result<(), StepFailure> {
        loop {
            if self.stats.accepted + self.stats.rejected >= self.options.max_steps {
                return Err(StepFailure::TooManySteps {
                    t: self.t,
                    max_steps: self.options.max_steps,
                });
            }
            let h = self.h.min(self.options.max_step);
            if !(h > 4.0 * f64::EPSILON * self.t.abs()) || h < f64::MIN_POSITIVE {
                return Err(StepFailure::StepTooSmall { t: self.t, h });
            }
            let mut k = [[0.0; N]; STAGES_EXTENDED];
            k[0] = self.f;
            for s in 1..STAGES {
                let ys: [f64; N] = std::array::from_fn(|i| {
                    self.y[i] + h * (0..s).map(|j| A[s][j] * k[j][i]).sum::<f64>()
                });
                k[s] = system.rhs(self.t + C[s] * h, &ys);
            }
            let y_new: [f64; N] = std::array::from_fn(|i| {
                self.y[i] + h * (0..STAGES).map(|j| B[j] * k[j][i]).sum::<f64>()
            });
            let f_new = system.rhs(self.t + h, &y_new);
            self.stats.rhs_evals += STAGES;
            if !(y_new.iter().chain(f_new.iter()).all(|v| v.is_finite())) {
                // Treat like a large error first; give up only when the step cannot shrink.
                self.stats.rejected += 1;
                self.h = 0.25 * h;
                self.last_rejected = true;
                if self.h < 4.0 * f64::EPSILON * self.t.abs().max(1e-300) {
                    return Err(StepFailure::NonFinite { t: self.t });
                }
                continue;
            }
            k[STAGES] = f_new;
            let scale = self.scale(&self.y, &y_new);
            let err = Self::error_norm(&k, h, &scale);
            if err <= 1.0 {
                let factor = if err == 0.0 {
                    MAX_FACTOR
                } else {
                    (SAFETY * err.powf(-1.0 / 8.0)).min(MAX_FACTOR)
                };
                let factor = if self.last_rejected {
                    factor.min(1.0)
                } else {
                    factor
                };
                self.t_old = self.t;
                self.y_old = self.y;
                self.h_prev = h;
                self.k = k;
                self.t += h;
                self.y = y_new;
                self.f = f_new;
                self.h = h * factor;
                self.dense_ready = false;
                self.last_rejected = false;
                self.rejected_attempt = None;
                self.stats.accepted += 1;
                return Ok(());
            }
            self.stats.rejected += 1;
            self.last_rejected = true;
            self.h = h * rejection_factor(h, err, self.rejected_attempt);
            self.rejected_attempt = Some((h, err));
        }
    }

    fn error_norm(k: &[[f64; N]; STAGES_EXTENDED], h: f64, scale: &[f64; N]) -> f64 {
        let (mut e5, mut e3) = (0.0, 0.0);
        for i in 0..N {
            let mut s5 = 0.0;
            let mut s3 = 0.0;
            for j in 0..STAGES {
                s5 += E5[j] * k[j][i];
                s3 += E3[j] * k[j][i];
            }
            e5 += (s5 / scale[i]).powi(2);
            e3 += (s3 / scale[i]).powi(2);
        }
        if e5 == 0.0 && e3 == 0.0 {
            return 0.0;
        }
        h.abs() * e5 / ((e5 + 0.01 * e3) * N as f64).sqrt()
    }

    /// The 7th-order interpolant over the last accepted step (three extra right-hand-side
    /// evaluations the first time it is asked for after a step).
    pub fn dense_output(&mut self, system: &impl OdeSystem<N>) -> DenseOutput<N> {
        let h = self.h_prev;
        if !self.dense_ready {
            for s in STAGES + 1..STAGES_EXTENDED {
                let ys: [f64; N] = std::array::from_fn(|i| {
                    self.y_old[i] + h * (0..s).map(|j| A[s][j] * self.k[j][i]).sum::<f64>()
                });
                self.k[s] = system.rhs(self.t_old + C[s] * h, &ys);
            }
            self.stats.rhs_evals += STAGES_EXTENDED - STAGES - 1;
            self.dense_ready = true;
        }
        let mut coeffs = [[0.0; N]; 7];
        for i in 0..N {
            let dy = self.y[i] - self.y_old[i];
            coeffs[0][i] = dy;
            coeffs[1][i] = h * self.k[0][i] - dy;
            coeffs[2][i] = 2.0 * dy - h * (self.f[i] + self.k[0][i]);
            for (r, d) in D.iter().enumerate() {
                coeffs[3 + r][i] = h
                    * (0..STAGES_EXTENDED)
                        .map(|j| d[j] * self.k[j][i])
                        .sum::<f64>();
            }
        }
        DenseOutput {
            t_old: self.t_old,
            h,
            y_old: self.y_old,
            coeffs,
        }
    }
}

/// Step reduction after a rejected step of size `h` with error `err` > 1.
///
/// The textbook factor assumes the error scales like h^8. Where the solution is not smooth on
/// the scale of the step (first contact, a stiffness knee, separation) it scales with a lower
/// power and that factor needs many rejections to get there. After two rejections from the same
/// point the observed order p = ln(err₁/err₂)/ln(h₁/h₂) (clamped to [1, 8]) is used instead.
fn rejection_factor(h: f64, err: f64, previous: Option<(f64, f64)>) -> f64 {
    match previous {
        Some((h_prev, err_prev)) if h_prev > h && err_prev > err => {
            let order = ((err_prev / err).ln() / (h_prev / h).ln()).clamp(1.0, 8.0);
            (SAFETY * err.powf(-1.0 / order)).clamp(0.01, SAFETY)
        }
        _ => (SAFETY * err.powf(-1.0 / 8.0)).max(MIN_FACTOR),
    }
}

/// Finds t in [a, b] with g(t) = 0, given g(a) and g(b) of opposite signs (Illinois variant of
/// regula falsi; superlinear, bracketing). Stops when the bracket is below `t_tol`.
pub fn find_root(
    g: impl Fn(f64) -> f64,
    mut a: f64,
    mut ga: f64,
    mut b: f64,
    mut gb: f64,
    t_tol: f64,
) -> f64 {
    let mut side = 0i8;
    for _ in 0..200 {
        if (b - a).abs() <= t_tol {
            break;
        }
        let mut t = (a * gb - b * ga) / (gb - ga);
        if !(t > a.min(b) && t < a.max(b)) {
            t = 0.5 * (a + b);
        }
        let gt = g(t);
        if gt == 0.0 {
            return t;
        }
        if (gt > 0.0) == (gb > 0.0) {
            b = t;
            gb = gt;
            if side == 1 {
                ga *= 0.5;
            }
            side = 1;
        } else {
            a = t;
            ga = gt;
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        }
    }
    if ga.abs() < gb.abs() { a } else { b }
}
