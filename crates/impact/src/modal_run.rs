//! The impact on a linear structure given by its [`TipModes`], integrated exactly between force
//! samples: every contact in a stated window, with a step that follows the contact's own time
//! scale and free flight crossed in long exact jumps.
//!
//! **Scheme.** The structure is linear and the contact is the only nonlinearity, at one point.
//! Over a step [t, t + h] the contact force is taken linear in time, f(τ) = f₀ + (f₁ − f₀) τ/h;
//! each mode q̈ᵢ + ωᵢ² qᵢ = bᵢ f is then integrated *exactly* (Duhamel's integral of a linear
//! load, Nigam & Jennings 1969):
//!
//! qᵢ(h) = cos(x) qᵢ + (sin x/ωᵢ) q̇ᵢ + bᵢ (αᵢ f₀ + βᵢ f₁),  x = ωᵢ h,
//! βᵢ = h² (x − sin x)/x³, αᵢ = h² (1 − cos x)/x² − βᵢ,
//!
//! and the rates likewise; the head (m_h ẍ = −f) is the ω = 0 case, α = h²/3, β = h²/6 (the
//! linear-acceleration method). So the structure carries no time-discretisation error at all —
//! no period error, no numerical damping, unconditionally stable for modes of any frequency — and
//! the only error is the linear hold of f, O(h²). The tip deflection w = Σ bᵢ qᵢ + R f and the head
//! are linear in f₁, so the end-of-step force solves one monotone scalar equation
//! f₁ = F(D − C f₁, E − C′ f₁) (safeguarded Newton; any law of flexrig-contact, damped ones through
//! δ̇).
//!
//! **Quadratic hold** ([`ForceHold::Quadratic`], [`run_modes_quadratic_against`]). The force is
//! held on the parabola through the sample before the step, f₋₁ at −h₀, and the step's two
//! ends: the linear hold plus κ τ(τ − h), κ = ((f₁ − f₀)/h − (f₀ − f₋₁)/h₀)/(h + h₀), still
//! linear in f₁. Each mode's response to the load τ(τ − h) is exact as well,
//! γᵢ = h⁴ (x² − 2 + 2 cos x)/x⁴ − h² βᵢ and γ_v,i = 2h³ (x − sin x)/x³ − h² β_v,i (the head:
//! −h⁴/12, −h³/6), so the end-of-step force is again one monotone scalar equation with C and C′
//! reduced by κ's share. The hold's error is f‴ (τ + h₀) τ (τ − h)/6, third order; its step
//! control keeps |f‴| h³/12 (f‴ from the last four samples) below the same `tol` × force, which
//! takes about a twentieth of the linear hold's steps per contact at tol 1e-6 with the same
//! peak error (tests/modal.rs measures the orders 2 and 3 against DOP853). A contact's first step,
//! with no sample before it, is linear.
//!
//! **Cubic hold** ([`ForceHold::Cubic`], [`run_modes_cubic_against`]; the safety searches').
//! The force is held on the cubic through the two samples before the step and the step's two
//! ends: the linear hold plus τ(τ − h)(κ + λ τ), with κ and λ from the divided differences of
//! the earlier samples, still linear in f₁. Each mode's response to τ²(τ − h) is exact too,
//! εᵢ = P₃ − h P₂ and ε_v,i = V₃ − h V₂ with P₃ = 6h⁵ (sin x − x + x³/6)/x⁵,
//! V₃ = 3h⁴ (x² − 2 + 2 cos x)/x⁴ (the head: −h⁵/30, −h⁴/12). The hold's error is
//! f⁗ τ(τ − h)(τ + h₀)(τ + h₀ + h₀₀)/24, fourth order; its step control keeps |f⁗| h⁴/16 (f⁗
//! from the last five samples) below `tol` × force. A contact's first step is linear, its second
//! quadratic. A contact's peak is refined on the cubic through the four samples around it (the
//! parabola through three would cost the hold's order at its longer steps). On the DOP853 cases
//! of tests/modal.rs it takes a quarter of the quadratic hold's steps at the same `tol`, closer
//! to DOP853 (8e-10 against 5e-9 at 1e-9), and its measured order is 4.0.
//!
//! **Step.** In contact, h follows the force: with f″ estimated from the last three samples, the
//! linear hold's deviation h² |f″|/8 is kept below `tol` × the largest force so far (h changes by
//! at most 2× per step, on a grid of 2^{1/4} so that the per-mode coefficients are computed once
//! per level). The separation is located exactly: the last step is shortened to the h′ at which
//! the gap closes with f₁ = 0. In free flight (f = 0) the motion is exact for any jump; the jump
//! is the longer of two that provably keep the gap open: gap/|ġ|max, with |ġ|max = |ẋ_h −
//! Σ_rigid bᵢ q̇ᵢ| + Σ_flex |bᵢ| Aᵢ ωᵢ (Aᵢ the mode's amplitude), and the root of the gap's
//! tangent bounded by each mode's curvature (|bᵢ| Aᵢ ωᵢ² τ²/2) or, for the fast modes, its swing
//! (|bᵢ| (2Aᵢ + |q̇ᵢ| τ)), which follows the gap's slow closing rather than the fastest mode's rate
//! (a soft CL's rattle: ≈ 8 jumps per free flight instead of ≈ 100). No contact can be skipped,
//! and the onset is located on the exact free motion.
//! The bodies have **parted for good** when they move apart (rigid parts) with a gap larger
//! than Σ_flex |bᵢ| Aᵢ, the most the vibrating tip can ever reach.

use flexrig_contact::{ContactLaw, Hertz};

use crate::ImpactError;
use crate::setup::{ContactEvent, ImpactOutcome, RunEnd};
use crate::severity::ContactTrace;
use crate::tip_modes::TipModes;

/// How long to follow the impact and how accurately.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ModalOptions {
    /// Relative deviation of the linear force hold per step (h² |f″|/8 against the largest
    /// force so far).
    pub tol: f64,
    /// `None`: stop at the first separation; `Some(T)`: follow every contact up to T \[s\] after
    /// the first onset (but at least to the end of the first contact), or until the bodies part
    /// for good.
    pub window_s: Option<f64>,
    /// Most steps (contact and free flight) before the run stops with [`RunEnd::StepBudget`]
    /// (an error if the first contact is not finished by then: its peak is not known).
    pub max_steps: usize,
}

impl ModalOptions {
    /// tol 1e-6, first contact only, 10⁶ steps.
    pub const DEFAULT: ModalOptions = ModalOptions {
        tol: 1e-6,
        window_s: None,
        max_steps: 1_000_000,
    };

    /// Checks the options; the error names the field.
    pub fn validate(&self) -> Result<(), ImpactError> {
        // below 1e-10 the hold's step count outgrows the step budget on the stiff cases
        // (round-off sets the floor of the force's linear hold)
        if !(self.tol.is_finite() && (1e-10..=1e-1).contains(&self.tol)) {
            return Err(ImpactError::invalid(
                "tol",
                self.tol,
                "must lie in [1e-10, 0.1]",
            ));
        }
        if let Some(w) = self.window_s
            && !(w.is_finite() && w > 0.0 && w <= 1e6)
        {
            return Err(ImpactError::invalid("window", w, "must lie in (0, 1e6] s"));
        }
        if !(100..=100_000_000).contains(&self.max_steps) {
            return Err(ImpactError::invalid(
                "max_steps",
                self.max_steps,
                "must lie in [100, 1e8]",
            ));
        }
        Ok(())
    }
}

/// The head: mass \[kg\], position \[m\] and speed [m/s] towards the structure.
#[derive(Debug, Clone, Copy)]
pub struct Head {
    /// Mass m_h \[kg\].
    pub mass: f64,
    /// Position x_h \[m\] (the indentation is δ = x_h − w).
    pub x: f64,
    /// Speed ẋ_h [m/s].
    pub v: f64,
}

/// Per-mode coefficients of one step of length h: [cos x, sin x/ω, ω sin x, α, β, α_v, β_v,
/// γ, γ_v, ε, ε_v] (γ, γ_v: the response to the load τ(τ − h); ε, ε_v: to τ²(τ − h);
/// [`mode_coefficients`]).
struct StepCoefficients {
    h: f64,
    /// The coefficients by column (column j: the j-th of the list above, one entry per mode),
    /// so that the step's loops over the modes run on contiguous slices.
    cols: [Vec<f64>; 11],
    /// Σ bᵢ² βᵢ and Σ bᵢ² β_v,i.
    sum_beta: f64,
    sum_beta_v: f64,
    /// Σ bᵢ² γᵢ and Σ bᵢ² γ_v,i.
    sum_gamma: f64,
    sum_gamma_v: f64,
    /// Σ bᵢ² εᵢ and Σ bᵢ² ε_v,i.
    sum_eps: f64,
    sum_eps_v: f64,
}

impl StepCoefficients {
    fn new(modes: &TipModes, h: f64) -> StepCoefficients {
        let mut cols: [Vec<f64>; 11] = std::array::from_fn(|_| Vec::with_capacity(modes.len()));
        let (mut sum_beta, mut sum_beta_v) = (0.0, 0.0);
        let (mut sum_gamma, mut sum_gamma_v) = (0.0, 0.0);
        let (mut sum_eps, mut sum_eps_v) = (0.0, 0.0);
        for (&w, &b) in modes.omegas.iter().zip(&modes.gains) {
            let c = mode_coefficients(w, h);
            sum_beta += b * b * c[4];
            sum_beta_v += b * b * c[6];
            sum_gamma += b * b * c[7];
            sum_gamma_v += b * b * c[8];
            sum_eps += b * b * c[9];
            sum_eps_v += b * b * c[10];
            for (col, value) in cols.iter_mut().zip(c) {
                col.push(value);
            }
        }
        StepCoefficients {
            h,
            cols,
            sum_beta,
            sum_beta_v,
            sum_gamma,
            sum_gamma_v,
            sum_eps,
            sum_eps_v,
        }
    }
}

/// [cos x, sin x/ω, ω sin x, α, β, α_v, β_v, γ, γ_v, ε, ε_v] for one mode ω over h (ω = 0: a
/// free mass): the response at h from rest of q̈ + ω²q = g(τ) to g = 1 − τ/h (α, α_v), τ/h
/// (β, β_v), τ(τ − h) (γ = h⁴ (x² − 2 + 2 cos x)/x⁴ − h² β, γ_v = 2h³ (x − sin x)/x³ − h² β_v;
/// the quadratic hold's bend, \[m·s²\] per unit of g's τ² coefficient) and τ²(τ − h) (ε = P₃ −
/// h P₂, ε_v = V₃ − h V₂ with the moments P_k = ∫₀ʰ sin(ω(h − s))/ω s^k ds and V_k = dP_k/dh:
/// P₃ = 6h⁵ (sin x − x + x³/6)/x⁵, V₃ = 6h⁴ (cos x − 1 + x²/2)/x⁴ = 3h⁴ (x² − 2 + 2 cos x)/x⁴;
/// the cubic hold's twist).
fn mode_coefficients(omega: f64, h: f64) -> [f64; 11] {
    let x = omega * h;
    let (sin, cos) = x.sin_cos();
    // (1 − cos x)/x², (x − sin x)/x³, by series for small x
    let (one_minus_cos, x_minus_sin) = if x < SERIES_BELOW {
        let x2 = x * x;
        (
            0.5 - x2 / 24.0 + x2 * x2 / 720.0,
            1.0 / 6.0 - x2 / 120.0 + x2 * x2 / 5040.0,
        )
    } else {
        ((1.0 - cos) / (x * x), (x - sin) / (x * x * x))
    };
    let sinc = sinc(x, sin);
    let quartic = quartic_response(x, cos);
    let h2 = h * h;
    let beta = h2 * x_minus_sin;
    let alpha = h2 * one_minus_cos - beta;
    let beta_v = h * one_minus_cos;
    let alpha_v = h * sinc - beta_v;
    let gamma = h2 * h2 * quartic - h2 * beta;
    let gamma_v = 2.0 * h2 * h * x_minus_sin - h2 * beta_v;
    // P₂ = h⁴ quartic, V₂ = 2h³ (x − sin x)/x³
    let (p2, v2) = (h2 * h2 * quartic, 2.0 * h2 * h * x_minus_sin);
    let eps = 6.0 * h2 * h2 * h * quintic_response(x, sin) - h * p2;
    let eps_v = 3.0 * h2 * h2 * quartic - h * v2;
    [
        cos,
        h * sinc,
        omega * sin,
        alpha,
        beta,
        alpha_v,
        beta_v,
        gamma,
        gamma_v,
        eps,
        eps_v,
    ]
}

/// (sin x − x + x³/6)/x⁵ = Σ_{j≥0} (−1)^j x^{2j}/(2j + 5)! (1/120 at x = 0) given sin x: by its
/// series through x¹⁴ below x = 1 (the first omitted term, x¹⁶/21! < 2e-20, is 2.4e-18 of it),
/// else in closed form (its cancellation loses at most 20 ε/x² ≤ 5e-15 of it).
fn quintic_response(x: f64, sin: f64) -> f64 {
    if x < 1.0 {
        // (−1)^j/(2j + 5)! for j = 0 … 7, innermost last
        const C: [f64; 8] = [
            1.0 / 120.0,
            -1.0 / 5_040.0,
            1.0 / 362_880.0,
            -1.0 / 39_916_800.0,
            1.0 / 6_227_020_800.0,
            -1.0 / 1_307_674_368_000.0,
            1.0 / 355_687_428_096_000.0,
            -1.0 / 121_645_100_408_832_000.0,
        ];
        even_series(&C, x)
    } else {
        let x2 = x * x;
        (sin - x + x2 * x / 6.0) / (x2 * x2 * x)
    }
}

/// [cos x, sin x/ω, ω sin x] of one mode ω over h, x = ωh (the free oscillation's; sin x/ω by
/// its series below x = 0.01, as in [`mode_coefficients`]).
fn free_coefficients(omega: f64, h: f64) -> [f64; 3] {
    let x = omega * h;
    let (sin, cos) = x.sin_cos();
    [cos, h * sinc(x, sin), omega * sin]
}

/// Below this x = ωh the step's coefficients are taken from their series.
const SERIES_BELOW: f64 = 1e-2;

/// sin x/x given sin x, by its series below [`SERIES_BELOW`].
fn sinc(x: f64, sin: f64) -> f64 {
    if x < SERIES_BELOW {
        let x2 = x * x;
        1.0 - x2 / 6.0 + x2 * x2 / 120.0
    } else {
        sin / x
    }
}

/// (x² − 2 + 2 cos x)/x⁴ = Σ_{k≥2} 2(−1)^k x^{2k−4}/(2k)! (1/12 at x = 0) given cos x: by its
/// series through x¹⁴ below x = 1 (the first omitted term is below 1e-18 there), else in closed
/// form (its cancellation loses at most 12 ε/x² ≤ 3e-15).
fn quartic_response(x: f64, cos: f64) -> f64 {
    if x < 1.0 {
        // 2(−1)^k/(2k)! for k = 2 … 9, innermost last
        const C: [f64; 8] = [
            1.0 / 12.0,
            -1.0 / 360.0,
            1.0 / 20_160.0,
            -1.0 / 1_814_400.0,
            1.0 / 239_500_800.0,
            -1.0 / 43_589_145_600.0,
            1.0 / 10_461_394_944_000.0,
            -1.0 / 3_201_186_852_864_000.0,
        ];
        even_series(&C, x)
    } else {
        let x2 = x * x;
        (x2 - 2.0 + 2.0 * cos) / (x2 * x2)
    }
}

/// Σⱼ cⱼ x^{2j} by Horner's rule in x² (the series of [`quartic_response`] and
/// [`quintic_response`] below x = 1).
fn even_series(c: &[f64; 8], x: f64) -> f64 {
    let x2 = x * x;
    c.iter().rev().fold(0.0, |acc, c| acc * x2 + c)
}

/// The coefficient sets of the step levels h = h_ref 2^{k/4}.
struct LevelCache {
    h_ref: f64,
    levels: Vec<(i32, StepCoefficients)>,
}

impl LevelCache {
    fn level_for(&self, h: f64) -> i32 {
        (4.0 * (h / self.h_ref).log2()).floor() as i32
    }

    fn get(&mut self, modes: &TipModes, level: i32) -> &StepCoefficients {
        let index = match self.levels.iter().position(|(l, _)| *l == level) {
            Some(i) => i,
            None => {
                let h = self.h_ref * 2f64.powf(level as f64 / 4.0);
                self.levels.push((level, StepCoefficients::new(modes, h)));
                self.levels.len() - 1
            }
        };
        &self.levels[index].1
    }
}

/// The structure, the head and the force at one instant.
#[derive(Clone)]
struct Motion {
    t: f64,
    q: Vec<f64>,
    q_dot: Vec<f64>,
    head: Head,
    /// Contact force \[N\].
    f: f64,
    /// Indentation δ = x_h − w \[m\] and its rate.
    delta: f64,
    delta_dot: f64,
}

/// One step's linear part: the free motion with f₁ = 0, and δ₁ = D − C f₁, δ̇₁ = E − C′ f₁.
struct Prediction {
    q: Vec<f64>,
    q_dot: Vec<f64>,
    x: f64,
    v: f64,
    d: f64,
    c: f64,
    e: f64,
    c_v: f64,
    /// The quadratic hold's bend per newton of f₁, κ_f \[1/s²\] (κ = κ_f f₁ + κ₀; 0 for the
    /// linear hold).
    kappa_f: f64,
    /// The cubic hold's twist per newton of f₁, λ_f \[1/s³\] (λ = λ_f f₁ + λ₀; 0 for the
    /// linear and the quadratic hold).
    lambda_f: f64,
}

/// The modal coordinates' storage of a spent motion, reused by the next step.
#[derive(Default)]
struct Buffers {
    q: Vec<f64>,
    q_dot: Vec<f64>,
}

impl Buffers {
    /// The storage of `m`, which is spent.
    fn of(m: Motion) -> Buffers {
        Buffers {
            q: m.q,
            q_dot: m.q_dot,
        }
    }
}

/// The sample before the step's start, for the quadratic hold: how long before \[s\] and the
/// force then \[N\]; for the cubic hold also the sample before that (how long before the
/// step's start \[s\], its force \[N\]).
#[derive(Debug, Clone, Copy)]
struct Before {
    h0: f64,
    f: f64,
    earlier: Option<(f64, f64)>,
}

/// How the contact force is held over a step between its samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub enum ForceHold {
    /// Linear in time between the step's two ends (second order, the scheme of
    /// [`run_modes`]).
    Linear,
    /// Quadratic in time through the sample before the step and the step's two ends (third
    /// order; the first step of each contact is linear). The same tolerance on the hold's
    /// deviation is met with about a tenth of the linear hold's steps
    /// ([`run_modes_quadratic_against`]).
    Quadratic,
    /// Cubic in time through the two samples before the step and the step's two ends (fourth
    /// order; the first step of each contact is linear, the second quadratic)
    /// ([`run_modes_cubic_against`]).
    Cubic,
}

struct Integrator<'a> {
    modes: &'a TipModes,
    law: &'a dyn ContactLaw,
    m_h: f64,
    hold: ForceHold,
}

impl Integrator<'_> {
    /// The hold's bend and twist over a step of length h from the force f₀ (`before`: the
    /// samples before the step): κ = κ_f f₁ + κ₀ and λ = λ_f f₁ + λ₀ as (κ_f, κ₀, λ_f, λ₀), all 0
    /// for the linear hold.
    fn hold_terms(&self, h: f64, f0: f64, before: Option<Before>) -> (f64, f64, f64, f64) {
        // the quadratic through (−h₀, f₋₁), (0, f₀), (h, f₁) is the linear hold plus κ τ(τ − h),
        // κ = ((f₁ − f₀)/h − (f₀ − f₋₁)/h₀)/(h + h₀) = κ_f f₁ + κ₀
        let quadratic = |b: Before| {
            let kappa_f = 1.0 / (h * (h + b.h0));
            (kappa_f, -f0 * kappa_f - (f0 - b.f) / (b.h0 * (h + b.h0)))
        };
        // the cubic through (−h_e, f_e), (−h₀, f₋₁), (0, f₀), (h, f₁) is the linear hold plus
        // τ(τ − h)(κ + λ τ): (f(s) − line(s))/(s(s − h)) = g₀ + g_f f₁ at s = −h₀ and s = −h_e,
        // g_f = 1/(h(h − s)), g₀ = (f(s) − f₀ + f₀ s/h)/(s(s − h)); λ their slope in s, κ the
        // line's value at s = 0
        let cubic = |b: Before, (h_e, f_e): (f64, f64)| {
            let g = |s: f64, fs: f64| ((fs - f0 + f0 * s / h) / (s * (s - h)), 1.0 / (h * (h - s)));
            let (g1_0, g1_f) = g(-b.h0, b.f);
            let (g2_0, g2_f) = g(-h_e, f_e);
            let ds = h_e - b.h0;
            let (lambda_0, lambda_f) = ((g1_0 - g2_0) / ds, (g1_f - g2_f) / ds);
            (
                g1_f + lambda_f * b.h0,
                g1_0 + lambda_0 * b.h0,
                lambda_f,
                lambda_0,
            )
        };
        match (self.hold, before) {
            (
                ForceHold::Cubic,
                Some(
                    b @ Before {
                        earlier: Some(e), ..
                    },
                ),
            ) => cubic(b, e),
            (ForceHold::Quadratic | ForceHold::Cubic, Some(b)) => {
                let (kappa_f, kappa_0) = quadratic(b);
                (kappa_f, kappa_0, 0.0, 0.0)
            }
            _ => (0.0, 0.0, 0.0, 0.0),
        }
    }

    /// The step from `s` over `k.h` with the force held from s.f to f₁ (linear, or bent
    /// through the sample `before` with the quadratic hold), up to f₁.
    fn predict(&self, s: &Motion, k: &StepCoefficients, before: Option<Before>) -> Prediction {
        self.predict_into(s, k, before, Buffers::default())
    }

    /// [`Self::predict`] into the storage of `buffers` (a spent motion's, so that a step
    /// allocates nothing).
    fn predict_into(
        &self,
        s: &Motion,
        k: &StepCoefficients,
        before: Option<Before>,
        buffers: Buffers,
    ) -> Prediction {
        let (h, f0, r) = (k.h, s.f, self.modes.residual);
        let (kappa_f, kappa_0, lambda_f, lambda_0) = self.hold_terms(h, f0, before);
        let n = self.modes.len();
        let Buffers { mut q, mut q_dot } = buffers;
        q.clear();
        q_dot.clear();
        q.resize(n, 0.0);
        q_dot.resize(n, 0.0);
        let [
            cos,
            sinc_h,
            w_sin,
            alpha,
            _,
            alpha_v,
            _,
            gamma,
            gamma_v,
            eps,
            eps_v,
        ] = &k.cols;
        let (cos, sinc_h, w_sin) = (&cos[..n], &sinc_h[..n], &w_sin[..n]);
        let (alpha, alpha_v, gamma, gamma_v) =
            (&alpha[..n], &alpha_v[..n], &gamma[..n], &gamma_v[..n]);
        let (eps, eps_v, gains) = (&eps[..n], &eps_v[..n], &self.modes.gains[..n]);
        let (q0, v0) = (&s.q[..n], &s.q_dot[..n]);
        let (q1, v1) = (&mut q[..n], &mut q_dot[..n]);
        // each mode on its own (contiguous columns: the loop vectorises), then the tip's sums in
        // the modes' order
        for i in 0..n {
            let load = alpha[i] * f0 + gamma[i] * kappa_0 + eps[i] * lambda_0;
            let load_v = alpha_v[i] * f0 + gamma_v[i] * kappa_0 + eps_v[i] * lambda_0;
            q1[i] = cos[i] * q0[i] + sinc_h[i] * v0[i] + gains[i] * load;
            v1[i] = -w_sin[i] * q0[i] + cos[i] * v0[i] + gains[i] * load_v;
        }
        let (mut w, mut w_dot) = (0.0, 0.0);
        for i in 0..n {
            w += gains[i] * q1[i];
            w_dot += gains[i] * v1[i];
        }
        // the head (ω = 0): γ = −h⁴/12, γ_v = −h³/6, ε = −h⁵/30, ε_v = −h⁴/12, and ẍ = −f/m_h
        let (h2, m) = (h * h, self.m_h);
        let x = s.head.x + h * s.head.v - h2 * f0 / (3.0 * m)
            + h2 * h2 * kappa_0 / (12.0 * m)
            + h2 * h2 * h * lambda_0 / (30.0 * m);
        let v = s.head.v - 0.5 * h * f0 / m
            + h2 * h * kappa_0 / (6.0 * m)
            + h2 * h2 * lambda_0 / (12.0 * m);
        // δ and δ̇ gain from κ and λ: the head's share minus the tip's (the residual spring's
        // rate R ḟ(h) with ḟ(h) = (f₁ − f₀)/h + κ h + λ h²)
        let bend = h2 * h2 / (12.0 * m) - k.sum_gamma;
        let bend_v = h2 * h / (6.0 * m) - k.sum_gamma_v - r * h;
        let twist = h2 * h2 * h / (30.0 * m) - k.sum_eps;
        let twist_v = h2 * h2 / (12.0 * m) - k.sum_eps_v - r * h2;
        Prediction {
            q,
            q_dot,
            x,
            v,
            d: x - w,
            c: h2 / (6.0 * m) + k.sum_beta + r - bend * kappa_f - twist * lambda_f,
            // the residual spring's rate with the linear hold: R (f₁ − f₀)/h
            e: v - w_dot + r * f0 / h - r * h * kappa_0 - r * h2 * lambda_0,
            c_v: 0.5 * h / m + k.sum_beta_v + r / h - bend_v * kappa_f - twist_v * lambda_f,
            kappa_f,
            lambda_f,
        }
    }

    /// The end-of-step force: f₁ = F(D − C f₁, E − C′ f₁), the unique root in [0, D/C].
    fn solve_force(&self, p: &Prediction, guess: f64) -> f64 {
        // the residual f − F(D − C f, E − C′ f) at f = 0 is ≥ 0 unless the law pushes there
        if p.d <= 0.0 || !self.law.pushes(p.d, p.e) {
            return 0.0;
        }
        let (mut lo, mut hi) = (0.0, p.d / p.c);
        let mut f = guess.clamp(lo, hi);
        for _ in 0..200 {
            let (delta, rate) = (p.d - p.c * f, p.e - p.c_v * f);
            let (force, stiffness) = self.force_and_stiffness(delta, rate);
            let res = f - force;
            if res == 0.0 {
                // the root itself: bisecting on from it (its Newton step lands on the bracket's
                // end) only wanders back to it, some forty evaluations later
                return f;
            }
            if res < 0.0 {
                lo = f;
            } else {
                hi = f;
            }
            let slope = 1.0 + p.c * stiffness + p.c_v * self.law.damping(delta, rate);
            let mut next = f - res / slope;
            let newton = next > lo && next < hi;
            if !newton {
                next = 0.5 * (lo + hi);
            }
            if (next - f).abs() <= 1e-15 * next.abs() || hi - lo <= 1e-15 * hi {
                return next;
            }
            // with the quadratic hold: a Newton correction below 1e-9 of the force leaves an
            // error of the order of its square (the residual's curvature is of the order of
            // the force over δ, and δ ≈ D over a step), far below the last bit: one evaluation
            // fewer than waiting for a correction of one ulp
            if self.hold != ForceHold::Linear && newton && (next - f).abs() <= 1e-9 * next {
                return next;
            }
            f = next;
        }
        f
    }

    /// The law's force and tangent stiffness at (δ, δ̇): with the quadratic hold from one power
    /// of δ ([`ContactLaw::force_and_stiffness`]); the linear hold keeps the two separate
    /// evaluations its runs were measured with.
    fn force_and_stiffness(&self, delta: f64, rate: f64) -> (f64, f64) {
        match self.hold {
            ForceHold::Quadratic | ForceHold::Cubic => self.law.force_and_stiffness(delta, rate),
            ForceHold::Linear => (self.law.force(delta, rate), self.law.stiffness(delta, rate)),
        }
    }

    /// True when the unloaded motion from `s` over `h` meets a positive contact force at one of
    /// seven interior points (h/8 apart).
    fn engages_within(&self, s: &Motion, h: f64) -> bool {
        (1..8).any(|j| {
            let m = self.step_unloaded(s, h * j as f64 / 8.0, None);
            m.delta > 0.0 && self.law.force(m.delta, m.delta_dot) > 0.0
        })
    }

    fn finish(&self, p: Prediction, k: &StepCoefficients, f1: f64, t: f64) -> Motion {
        let (h, m) = (k.h, self.m_h);
        let mut q = p.q;
        let mut q_dot = p.q_dot;
        let n = q.len();
        let [_, _, _, _, beta, _, beta_v, gamma, gamma_v, eps, eps_v] = &k.cols;
        let (beta, beta_v, gamma, gamma_v) = (&beta[..n], &beta_v[..n], &gamma[..n], &gamma_v[..n]);
        let (eps, eps_v, gains) = (&eps[..n], &eps_v[..n], &self.modes.gains[..n]);
        let (kf, lf) = (p.kappa_f, p.lambda_f);
        let (q1, v1) = (&mut q[..n], &mut q_dot[..n]);
        for i in 0..n {
            q1[i] += gains[i] * (beta[i] + kf * gamma[i] + lf * eps[i]) * f1;
            v1[i] += gains[i] * (beta_v[i] + kf * gamma_v[i] + lf * eps_v[i]) * f1;
        }
        let (bend, twist) = (p.kappa_f * f1, p.lambda_f * f1);
        Motion {
            t,
            q,
            q_dot,
            head: Head {
                mass: m,
                x: p.x - h * h * f1 / (6.0 * m)
                    + h * h * h * h * bend / (12.0 * m)
                    + h * h * h * h * h * twist / (30.0 * m),
                v: p.v - 0.5 * h * f1 / m
                    + h * h * h * bend / (6.0 * m)
                    + h * h * h * h * twist / (12.0 * m),
            },
            f: f1,
            delta: p.d - p.c * f1,
            delta_dot: p.e - p.c_v * f1,
        }
    }

    /// One contact step over `k.h` from `s` (`before`: the sample before it, for the
    /// quadratic hold), the end-of-step force solved from `guess`.
    fn step(
        &self,
        s: &Motion,
        k: &StepCoefficients,
        before: Option<Before>,
        guess: f64,
        buffers: Buffers,
    ) -> Motion {
        let p = self.predict_into(s, k, before, buffers);
        let f1 = self.solve_force(&p, guess);
        self.finish(p, k, f1, s.t + k.h)
    }

    /// A step of length h with f₁ = 0 (free flight, or the last step of a contact, bent through
    /// `before` with the quadratic hold).
    fn step_unloaded(&self, s: &Motion, h: f64, before: Option<Before>) -> Motion {
        if h == 0.0 {
            // a step of no length (an onset located at the step's start, e.g. a tip that
            // re-engages the instant it separates): the residual spring's rate R (f₁ − f₀)/h
            // below would be 0/0
            return Motion {
                f: 0.0,
                ..s.clone()
            };
        }
        if s.f == 0.0 && before.is_none() {
            return self.free_motion(s, h);
        }
        let k = StepCoefficients::new(self.modes, h);
        let p = self.predict(s, &k, before);
        self.finish(p, &k, 0.0, s.t + h)
    }

    /// The motion from `s` over h without a force (free flight): each mode's free oscillation
    /// and the head's uniform motion — the unloaded step's own numbers, without the load's
    /// coefficients.
    fn free_motion(&self, s: &Motion, h: f64) -> Motion {
        let n = self.modes.len();
        let (mut q, mut q_dot) = (Vec::with_capacity(n), Vec::with_capacity(n));
        let (mut w, mut w_dot) = (0.0, 0.0);
        for i in 0..n {
            let [cos, sinc_h, w_sin] = free_coefficients(self.modes.omegas[i], h);
            let b = self.modes.gains[i];
            let qi = cos * s.q[i] + sinc_h * s.q_dot[i];
            let vi = -w_sin * s.q[i] + cos * s.q_dot[i];
            w += b * qi;
            w_dot += b * vi;
            q.push(qi);
            q_dot.push(vi);
        }
        let x = s.head.x + h * s.head.v;
        Motion {
            t: s.t + h,
            q,
            q_dot,
            head: Head { x, ..s.head },
            f: 0.0,
            delta: x - w,
            delta_dot: s.head.v - w_dot,
        }
    }

    /// The indentation δ \[m\] after a free jump h from `s` ([`Self::free_motion`]'s, bit for
    /// bit, without its modal coordinates).
    fn free_gap(&self, s: &Motion, h: f64) -> f64 {
        let mut w = 0.0;
        for i in 0..self.modes.len() {
            let [cos, sinc_h, _] = free_coefficients(self.modes.omegas[i], h);
            let qi = cos * s.q[i] + sinc_h * s.q_dot[i];
            w += self.modes.gains[i] * qi;
        }
        let x = s.head.x + h * s.head.v;
        x - w
    }

    /// The indentation δ \[m\] at the end of a step h from `s` with the force falling to 0
    /// (held through `before`): [`Self::predict`]'s D, bit for bit, without the step's
    /// coefficient set or its modal coordinates.
    fn unloaded_gap(&self, s: &Motion, h: f64, before: Option<Before>) -> f64 {
        let f0 = s.f;
        let (_, kappa_0, _, lambda_0) = self.hold_terms(h, f0, before);
        let mut w = 0.0;
        for i in 0..self.modes.len() {
            let c = mode_coefficients(self.modes.omegas[i], h);
            let (cos, sinc_h, alpha, gamma, eps) = (c[0], c[1], c[3], c[7], c[9]);
            let b = self.modes.gains[i];
            let load = alpha * f0 + gamma * kappa_0 + eps * lambda_0;
            let qi = cos * s.q[i] + sinc_h * s.q_dot[i] + b * load;
            w += b * qi;
        }
        let (h2, m) = (h * h, self.m_h);
        let x = s.head.x + h * s.head.v - h2 * f0 / (3.0 * m)
            + h2 * h2 * kappa_0 / (12.0 * m)
            + h2 * h2 * h * lambda_0 / (30.0 * m);
        x - w
    }

    /// Kinetic, modal strain, contact and residual-spring energy \[J\].
    fn energy(&self, s: &Motion) -> f64 {
        let modal: f64 = (0..s.q.len())
            .map(|i| {
                let w = self.modes.omegas[i];
                0.5 * (s.q_dot[i] * s.q_dot[i] + w * w * s.q[i] * s.q[i])
            })
            .sum();
        0.5 * self.m_h * s.head.v * s.head.v
            + modal
            + self.law.elastic_energy(s.delta.max(0.0))
            + 0.5 * self.modes.residual * s.f * s.f
    }

    /// In free flight with the head moving away (ẋ_h ≤ 0) and no rigid mode: the most energy
    /// U_c(δ) + ½ R f² \[J\] a later contact can hold at its peak, E_modes − ½ ẋ_h²/Σ bᵢ²
    /// ([`largest_peak_quadratic_against`]); `None` otherwise.
    fn later_peak_energy(&self, s: &Motion) -> Option<f64> {
        let v = s.head.v;
        if !(s.f == 0.0 && v <= 0.0) || self.modes.omegas.iter().any(|&w| w <= 0.0) {
            return None;
        }
        let mut modal = 0.0;
        let mut gain_sq = 0.0;
        for i in 0..s.q.len() {
            let (w, b) = (self.modes.omegas[i], self.modes.gains[i]);
            modal += 0.5 * (s.q_dot[i] * s.q_dot[i] + w * w * s.q[i] * s.q[i]);
            gain_sq += b * b;
        }
        Some(modal - 0.5 * v * v / gain_sq)
    }

    /// The contact's and the residual spring's energy U_c(δ) + ½ R f² \[J\] at the stepped
    /// force and indentation `(f, δ)`.
    fn peak_energy(&self, (f, delta): (f64, f64)) -> f64 {
        self.law.elastic_energy(delta.max(0.0)) + 0.5 * self.modes.residual * f * f
    }

    /// Free flight: the longest jump \[s\] over which the gap provably stays open, from the
    /// bound on each flexible mode's departure from its tangent, ρᵢ(τ) = bᵢ (qᵢ(τ) − qᵢ − q̇ᵢ τ):
    /// |ρᵢ| ≤ |bᵢ| Aᵢ ωᵢ² τ²/2 (its acceleration) and |ρᵢ| ≤ |bᵢ| (2Aᵢ + |q̇ᵢ| τ) (its swing).
    /// With the modes below the j-th (ascending ω) on the first bound and the rest on the second,
    /// δ(τ) ≤ δ + K_j + (δ̇ + L_j) τ + C_j τ², convex, so it stays below 0 up to its positive
    /// root when it starts below 0 (δ̇ the free gap's rate, rigid modes exact); the longest over
    /// every j. High modes, which swing fast but little, then cost their reach instead of their
    /// speed: the jump follows the gap's slow closing, not the fastest mode's rate. 0 when no
    /// split gives a jump.
    fn flight_jump(&self, s: &Motion) -> f64 {
        let n = s.q.len();
        let mut rate = s.head.v;
        // (2|b|A, |b q̇|, |b| A ω²/2) per flexible mode, ascending ω
        let mut low = 0.0;
        for i in 0..n {
            let (w, b) = (self.modes.omegas[i], self.modes.gains[i]);
            rate -= b * s.q_dot[i];
            if w > 0.0 {
                let amplitude = (s.q[i] * s.q[i] + (s.q_dot[i] / w).powi(2)).sqrt();
                low += b.abs() * amplitude * w * w / 2.0;
            }
        }
        // j = n: every flexible mode on its acceleration bound; then move the highest modes one
        // by one onto their swing bound
        let (mut reach, mut swing, mut bend) = (0.0, 0.0, low);
        let mut best = 0.0_f64;
        for j in (0..=n).rev() {
            best = best.max(first_root(s.delta + reach, rate + swing, bend));
            if j == 0 {
                break;
            }
            let i = j - 1;
            let (w, b) = (self.modes.omegas[i], self.modes.gains[i]);
            if w > 0.0 {
                let amplitude = (s.q[i] * s.q[i] + (s.q_dot[i] / w).powi(2)).sqrt();
                reach += 2.0 * b.abs() * amplitude;
                swing += (b * s.q_dot[i]).abs();
                bend -= b.abs() * amplitude * w * w / 2.0;
                bend = bend.max(0.0);
            }
        }
        best
    }

    /// Free flight: (linear part of the gap, its rate, Σ_flex |bᵢ| Aᵢ, Σ_flex |bᵢ| Aᵢ ωᵢ).
    fn gap_bounds(&self, s: &Motion) -> (f64, f64, f64, f64) {
        let (mut lin, mut lin_rate) = (s.head.x, s.head.v);
        let (mut reach, mut speed) = (0.0, 0.0);
        for i in 0..s.q.len() {
            let (w, b) = (self.modes.omegas[i], self.modes.gains[i]);
            if w == 0.0 {
                lin -= b * s.q[i];
                lin_rate -= b * s.q_dot[i];
            } else {
                let amplitude = (s.q[i] * s.q[i] + (s.q_dot[i] / w).powi(2)).sqrt();
                reach += b.abs() * amplitude;
                speed += b.abs() * amplitude * w;
            }
        }
        (lin, lin_rate, reach, speed)
    }
}

/// Follows the impact of `head` on the structure `modes` (moving at its `rates` at t = 0, the
/// head touching the tip) with contact law `law`; `t_scale` \[s\] is the shortest contact time
/// the set-up can have (each contact's first step is t_scale/1e4).
pub fn run_modes(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
) -> Result<ImpactOutcome, ImpactError> {
    let (outcome, _) = run_modes_inner(
        modes,
        head,
        law,
        t_scale,
        options,
        (0.0, ForceHold::Linear, EarlyStop::Never),
        None,
    )?;
    Ok(outcome)
}

/// [`run_modes`] with the hold's tolerance measured against at least `force_scale` \[N\]
/// (`tol` × max(largest force so far, `force_scale`)): a run that only has to tell how its
/// largest peak compares with a known force (a limit) needs its error small against that force,
/// not against the first milli-newtons of each onset. `force_scale` = 0 is [`run_modes`].
pub fn run_modes_against(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
    force_scale: f64,
) -> Result<ImpactOutcome, ImpactError> {
    let hold = (force_scale, ForceHold::Linear);
    Ok(run_held_against(modes, head, law, t_scale, options, hold, EarlyStop::Never)?.0)
}

/// [`run_modes_against`] with the force held quadratic over each step ([`ForceHold::Quadratic`]:
/// third order, the same tolerance on the hold's deviation met with far fewer steps).
pub fn run_modes_quadratic_against(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
    force_scale: f64,
) -> Result<ImpactOutcome, ImpactError> {
    let hold = (force_scale, ForceHold::Quadratic);
    Ok(run_held_against(modes, head, law, t_scale, options, hold, EarlyStop::Never)?.0)
}

/// The margin [`largest_peak_quadratic_against`] keeps between the energy bound on every later
/// contact and the largest peak so far (relative, in energy): far above the run's own energy
/// error at any accepted tolerance, so the full run's later peaks stay below the largest so far
/// too.
pub const SETTLE_MARGIN: f64 = 1e-3;

/// [`run_modes_against`] with the force held cubic over each step ([`ForceHold::Cubic`]:
/// fourth order, the same tolerance on the hold's deviation met with fewer steps than the
/// quadratic hold).
pub fn run_modes_cubic_against(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
    force_scale: f64,
) -> Result<ImpactOutcome, ImpactError> {
    let hold = (force_scale, ForceHold::Cubic);
    Ok(run_held_against(modes, head, law, t_scale, options, hold, EarlyStop::Never)?.0)
}

/// A run for its largest peak force ([`largest_peak_quadratic_against`]).
#[derive(Debug, Clone, PartialEq)]
pub struct LargestPeakRun {
    /// The contacts followed, in order; the largest peak among them is the run's largest.
    pub contacts: Vec<ContactEvent>,
    /// How the run ended.
    pub end: PeakRunEnd,
}

/// How a run for its largest peak ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PeakRunEnd {
    /// Followed to its end, as [`run_modes_quadratic_against`] would (the bodies parted for
    /// good, or the window or the step budget).
    Ended(RunEnd),
    /// Stopped in free flight at this time \[s\]: no later contact can pass the largest peak
    /// so far (the energy bound of [`largest_peak_quadratic_against`]), so the contacts after
    /// it were not followed.
    Settled(f64),
    /// Stopped at the end of the contact that reached the threshold force
    /// ([`threshold_cubic_against`]), at this time \[s\].
    Reached(f64),
    /// Stopped in free flight at this time \[s\]: every contact so far stayed below the
    /// threshold force and no later contact can reach it ([`threshold_cubic_against`]).
    StaysBelow(f64),
}

/// When a run may stop before the bodies part for good.
#[derive(Debug, Clone, Copy, PartialEq)]
enum EarlyStop {
    /// Never: every contact is followed.
    Never,
    /// Once no later contact can pass the largest peak so far.
    LargestKnown,
    /// Once a contact has reached this force \[N\], or no later contact can.
    Threshold(f64),
}

/// [`run_modes_quadratic_against`] for its largest peak alone, with the elastic law `law`: the
/// run stops in free flight once no later contact can pass the largest peak so far. The bound,
/// for a structure without rigid modes (a held joint) and the head moving away (ẋ_h ≤ 0):
/// energy is conserved, the head only ever speeds away (m_h ẍ_h = −f ≤ 0, so |ẋ_h| never falls),
/// and at a later peak the force stands still, so δ̇ = 0 and the tip moves with the head,
/// Σ bᵢ q̇ᵢ = ẋ_h, which needs the modes' kinetic energy ½ ẋ_h²/Σ bᵢ² at least (Cauchy–Schwarz
/// over the M-orthonormal modes); hence any later peak f holds U_c(δ(f)) + ½ R f² ≤ E_modes −
/// ½ ẋ_h²/Σ bᵢ², with E_modes the modes' energy now. The run stops when that is below the
/// largest stepped peak's energy by [`SETTLE_MARGIN`]. The contacts followed and the largest
/// peak are those of the full run bit for bit; with rigid modes (a free hub) the run is the full
/// one.
pub fn largest_peak_quadratic_against(
    modes: &TipModes,
    head: Head,
    law: &Hertz,
    t_scale: f64,
    options: &ModalOptions,
    force_scale: f64,
) -> Result<LargestPeakRun, ImpactError> {
    let hold = (force_scale, ForceHold::Quadratic);
    peak_run_held_against(
        modes,
        head,
        law,
        t_scale,
        options,
        hold,
        EarlyStop::LargestKnown,
    )
}

/// [`largest_peak_quadratic_against`] with the cubic hold ([`ForceHold::Cubic`]).
pub fn largest_peak_cubic_against(
    modes: &TipModes,
    head: Head,
    law: &Hertz,
    t_scale: f64,
    options: &ModalOptions,
    force_scale: f64,
) -> Result<LargestPeakRun, ImpactError> {
    let hold = (force_scale, ForceHold::Cubic);
    peak_run_held_against(
        modes,
        head,
        law,
        t_scale,
        options,
        hold,
        EarlyStop::LargestKnown,
    )
}

/// [`run_modes_cubic_against`] asked only whether any contact reaches the force `threshold`
/// \[N\] (> 0), with the elastic law `law`: the run stops at the end of the first contact whose
/// peak reaches it ([`PeakRunEnd::Reached`]), or in free flight once no later contact can reach
/// it ([`PeakRunEnd::StaysBelow`]: the energy bound of [`largest_peak_quadratic_against`] below
/// the threshold's energy U_c(δ(F)) + ½ R F² by [`SETTLE_MARGIN`]), else at the run's own end.
/// The contacts followed are the full run's first ones bit for bit, so the answer is the full
/// run's: it reaches the threshold exactly when its largest peak does.
pub fn threshold_cubic_against(
    modes: &TipModes,
    head: Head,
    law: &Hertz,
    t_scale: f64,
    options: &ModalOptions,
    force_scale: f64,
    threshold: f64,
) -> Result<LargestPeakRun, ImpactError> {
    if !(threshold.is_finite() && threshold > 0.0) {
        return Err(ImpactError::invalid("threshold", threshold, "> 0 N"));
    }
    let hold = (force_scale, ForceHold::Cubic);
    let stop = EarlyStop::Threshold(threshold);
    peak_run_held_against(modes, head, law, t_scale, options, hold, stop)
}

/// The run with the hold `hold.1` against `hold.0` \[N\], stopped early by `stop`, and how it
/// ended.
fn peak_run_held_against(
    modes: &TipModes,
    head: Head,
    law: &Hertz,
    t_scale: f64,
    options: &ModalOptions,
    hold: (f64, ForceHold),
    stop: EarlyStop,
) -> Result<LargestPeakRun, ImpactError> {
    let (outcome, stopped) = run_held_against(modes, head, law, t_scale, options, hold, stop)?;
    Ok(LargestPeakRun {
        contacts: outcome.contacts,
        end: stopped.unwrap_or(PeakRunEnd::Ended(outcome.ended)),
    })
}

/// The run with the hold `hold.1`, its tolerance measured against at least `hold.0` \[N\]
/// (checked: finite, ≥ 0), stopped early by `stop`; how it stopped, when it did.
fn run_held_against(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
    hold: (f64, ForceHold),
    stop: EarlyStop,
) -> Result<(ImpactOutcome, Option<PeakRunEnd>), ImpactError> {
    let (force_scale, hold) = hold;
    if !(force_scale.is_finite() && force_scale >= 0.0) {
        return Err(ImpactError::invalid("force scale", force_scale, "≥ 0 N"));
    }
    run_modes_inner(
        modes,
        head,
        law,
        t_scale,
        options,
        (force_scale, hold, stop),
        None,
    )
}

/// [`run_modes`] recording the force and indentation at every step of every contact (the
/// scheme holds the force linear between steps: these samples are the force the run used),
/// onsets and separations included.
pub fn run_modes_traced(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
) -> Result<(ImpactOutcome, ContactTrace), ImpactError> {
    let mut trace = ContactTrace::default();
    let (outcome, _) = run_modes_inner(
        modes,
        head,
        law,
        t_scale,
        options,
        (0.0, ForceHold::Linear, EarlyStop::Never),
        Some(&mut trace),
    )?;
    Ok((outcome, trace))
}

/// The run of [`run_modes`] and its variants: `(force_scale, hold, stop)` are the force \[N\]
/// the tolerance is measured against at least, how the force is held over a step, and when the
/// run may stop early (an elastic law only; [`largest_peak_quadratic_against`],
/// [`threshold_cubic_against`]), returning how it stopped when it did.
fn run_modes_inner(
    modes: &TipModes,
    head: Head,
    law: &dyn ContactLaw,
    t_scale: f64,
    options: &ModalOptions,
    (force_scale, hold, stop): (f64, ForceHold, EarlyStop),
    mut trace: Option<&mut ContactTrace>,
) -> Result<(ImpactOutcome, Option<PeakRunEnd>), ImpactError> {
    options.validate()?;
    if !(t_scale.is_finite() && t_scale > 0.0) {
        return Err(ImpactError::invalid("contact time scale", t_scale, "> 0 s"));
    }
    let int = Integrator {
        modes,
        law,
        m_h: head.mass,
        hold,
    };
    let n = modes.len();
    let mut s = Motion {
        t: 0.0,
        q: vec![0.0; n],
        q_dot: modes.rates.clone(),
        head,
        f: 0.0,
        delta: 0.0,
        delta_dot: 0.0,
    };
    s.delta_dot = {
        let w_dot: f64 = modes.gains.iter().zip(&s.q_dot).map(|(b, v)| b * v).sum();
        head.v - w_dot
    };
    if s.delta_dot <= 0.0 {
        return Err(ImpactError::invalid(
            "v0",
            s.delta_dot,
            "a head approaching the tip (δ̇ > 0 at the onset)",
        ));
    }
    let e0 = int.energy(&s);
    // each contact starts at t_scale/1e4 (the force's onset is not yet resolved by the
    // controller, which needs three samples) and grows by ≤ 2× per step from there
    let h_start = t_scale / 1e4;
    let h_min = t_scale * 1e-6;
    let mut cache = LevelCache {
        h_ref: h_start,
        levels: Vec::new(),
    };
    let mut contacts: Vec<ContactEvent> = Vec::new();
    let mut f_ref = 0.0_f64;
    // the hold's allowed deviation over a step h: tol × the largest force, and on steps longer
    // than the contact time scale tol × f × t_scale/h, so that the impulse error of a step stays
    // below tol f t_scale (long low-force tails: a damped law's slow release)
    // (and against `force_scale` at least)
    let allowed = |f: f64, h: f64| options.tol * f.max(force_scale) * (t_scale / h).min(1.0);
    let mut steps = 0usize;
    let window = options.window_s;
    let ended;
    // the largest stepped force so far and its indentation, and how the run stopped early
    let mut top = (0.0_f64, 0.0_f64);
    let mut stopped = None;
    // the storage of the last spent motion, for the next contact step
    let mut spare: Option<Buffers> = None;
    'run: loop {
        // ---- a contact, from its onset at s.t ----
        let onset = s.t;
        let mut samples: Vec<(f64, f64)> = vec![(s.t, s.f)];
        if let Some(trace) = trace.as_mut() {
            trace.push(s.t, s.f, s.delta);
        }
        let mut peak = (0.0_f64, s.t);
        let mut level = 0;
        loop {
            if steps >= options.max_steps {
                if contacts.is_empty() {
                    // no peak is known yet: an outcome would report a force it never computed
                    return Err(ImpactError::NotFinished {
                        design: "modal",
                        reason: format!(
                            "the step budget ({}) ran out {:.3e} s into the first contact; \
                             loosen the tolerance (now {:e})",
                            options.max_steps, s.t, options.tol
                        ),
                    });
                }
                ended = RunEnd::StepBudget(s.t);
                contacts.push(event(onset, peak, s.t - onset));
                break 'run;
            }
            // the window never cuts the first contact short
            if let Some(w) = window
                && s.t >= w
                && !contacts.is_empty()
            {
                ended = RunEnd::Window(w);
                contacts.push(event(onset, peak, s.t - onset));
                break 'run;
            }
            steps += 1;
            let k = cache.get(modes, level);
            let m = samples.len();
            // the quadratic hold bends through the sample before the step's start (none at a
            // contact's first step); its end force is sought from the samples' trend
            let before = (hold != ForceHold::Linear && m >= 2).then(|| Before {
                h0: s.t - samples[m - 2].0,
                f: samples[m - 2].1,
                earlier: (hold == ForceHold::Cubic && m >= 3)
                    .then(|| (s.t - samples[m - 3].0, samples[m - 3].1)),
            });
            let guess = match before {
                Some(_) if hold == ForceHold::Cubic && m >= 4 => cubic_extrapolation(&samples, k.h),
                Some(_) => extrapolated_force(&samples, k.h),
                None => s.f,
            };
            let next = int.step(&s, k, before, guess, spare.take().unwrap_or_default());
            if !(next.t > s.t && next.f.is_finite() && next.delta_dot.is_finite()) {
                return Err(ImpactError::NotFinished {
                    design: "modal",
                    reason: format!(
                        "the contact step at t = {:.6e} s lost finiteness or did not advance",
                        s.t
                    ),
                });
            }
            // reject a step whose force bends far more than the tolerance allows
            let bent = (level > -200)
                .then(|| hold_deviation(hold, &samples, k.h, next.f))
                .flatten();
            // the derivative the deviation was estimated from, over the samples the step control
            // reads once this step is accepted (the same points: the same number)
            let known_derivative = bent.map(|(_, derivative)| (samples.len() + 1, derivative));
            if let Some((deviation, _)) = bent
                && deviation > 4.0 * allowed(f_ref.max(next.f), k.h)
            {
                level -= 4;
                spare = Some(Buffers::of(next));
                continue;
            }
            // a damped law can hold the force at 0 while the bodies still overlap (damping
            // outpulling the elastic force); a step that starts and ends there must not jump
            // over the force's return
            if s.f == 0.0 && next.f == 0.0 && level > -200 && int.engages_within(&s, k.h) {
                level -= 4;
                spare = Some(Buffers::of(next));
                continue;
            }
            if next.f == 0.0 && next.delta <= 0.0 {
                // the gap closes within the step: shorten it to the separation
                let h_sep = separation_step(&int, &s, k.h, before);
                s = int.step_unloaded(&s, h_sep, before);
                s.delta = 0.0;
                samples.push((s.t, 0.0));
                if let Some(trace) = trace.as_mut() {
                    trace.push(s.t, 0.0, 0.0);
                }
                peak = max_peak(hold, &samples, peak);
                if peak.0 > 0.0 {
                    contacts.push(event(onset, peak, s.t - onset));
                }
                break;
            }
            spare = Some(Buffers::of(std::mem::replace(&mut s, next)));
            if s.f > top.0 {
                top = (s.f, s.delta);
            }
            samples.push((s.t, s.f));
            if let Some(trace) = trace.as_mut() {
                trace.push(s.t, s.f, s.delta);
            }
            f_ref = f_ref.max(s.f);
            peak = max_peak(hold, &samples, peak);
            // the next step from the force's curvature (its third derivative with the
            // quadratic hold)
            let m = samples.len();
            let h = k.h;
            let f_tol = f_ref.max(force_scale);
            let known = known_derivative.filter(|(at, _)| *at == m).map(|(_, d)| d);
            let ideal = match hold {
                ForceHold::Cubic if m >= 5 => {
                    // |f⁗| h⁴/16 ≤ tol f (the cubic's deviation with equal steps), and
                    // |f⁗| h⁵/16 ≤ tol f t_scale on steps longer than t_scale
                    let f4 = known.unwrap_or_else(|| fourth_derivative(&samples[m - 5..]).abs());
                    (f4 > 0.0).then(|| {
                        let by_force = (16.0 * options.tol * f_tol / f4).sqrt().sqrt();
                        // (X t_s)^{1/5} ≥ X^{1/4} exactly when X^{1/4} ≤ t_s
                        if by_force <= t_scale * (1.0 - 1e-12) {
                            return 0.9 * by_force;
                        }
                        let by_impulse = (16.0 * options.tol * f_tol * t_scale / f4).powf(0.2);
                        0.9 * by_force.min(by_impulse)
                    })
                }
                ForceHold::Quadratic | ForceHold::Cubic if m >= 4 => {
                    // |f‴| h³/12 ≤ tol f (the quadratic's deviation with h₀ ≈ h), and
                    // |f‴| h⁴/12 ≤ tol f t_scale on steps longer than t_scale
                    let f3 = known.unwrap_or_else(|| third_derivative(&samples[m - 4..]).abs());
                    (f3 > 0.0).then(|| {
                        let by_force = (12.0 * options.tol * f_tol / f3).cbrt();
                        // X^{1/4} t_s^{1/4} ≥ X^{1/3} exactly when X^{1/3} ≤ t_s (X = 12 tol
                        // f/f‴): below t_scale (less a margin far above both roots' rounding)
                        // the impulse's step is the longer, and its power is not needed
                        if by_force <= t_scale * (1.0 - 1e-12) {
                            return 0.9 * by_force;
                        }
                        let by_impulse = (12.0 * options.tol * f_tol * t_scale / f3).powf(0.25);
                        0.9 * by_force.min(by_impulse)
                    })
                }
                _ if m >= 3 => {
                    let (a, b, c) = (samples[m - 3], samples[m - 2], samples[m - 1]);
                    let (h0, h1) = (b.0 - a.0, c.0 - b.0);
                    let f2 = 2.0 * ((c.1 - b.1) / h1 - (b.1 - a.1) / h0) / (h0 + h1);
                    (f2 != 0.0).then(|| {
                        let by_force = (8.0 * options.tol * f_tol / f2.abs()).sqrt();
                        let by_impulse = (8.0 * options.tol * f_tol * t_scale / f2.abs()).cbrt();
                        0.9 * by_force.min(by_impulse)
                    })
                }
                _ => None,
            };
            if m >= 3 {
                let target = ideal.unwrap_or(2.0 * h).clamp(0.5 * h, 2.0 * h).max(h_min);
                level = cache.level_for(target).min(level + 4);
            }
            if samples.len() > 8 {
                samples.drain(..samples.len() - 5);
            }
        }
        if window.is_none() {
            ended = RunEnd::FirstSeparation;
            break;
        }
        stopped = match stop {
            EarlyStop::Never => None,
            // no later contact can pass the largest peak so far: the run's largest is known
            EarlyStop::LargestKnown => int
                .later_peak_energy(&s)
                .is_some_and(|later| later < (1.0 - SETTLE_MARGIN) * int.peak_energy(top))
                .then_some(PeakRunEnd::Settled(s.t)),
            // a contact reached the threshold, or no later contact can
            EarlyStop::Threshold(f) => {
                if contacts.last().is_some_and(|c| c.peak_force_n >= f) {
                    Some(PeakRunEnd::Reached(s.t))
                } else {
                    let at_f = int.peak_energy((f, law.elastic().indentation(f)));
                    int.later_peak_energy(&s)
                        .is_some_and(|later| later < (1.0 - SETTLE_MARGIN) * at_f)
                        .then_some(PeakRunEnd::StaysBelow(s.t))
                }
            }
        };
        if stopped.is_some() {
            ended = RunEnd::Window(s.t);
            break;
        }
        // ---- free flight, to the next onset or until parted for good ----
        loop {
            let (lin, lin_rate, reach, speed) = int.gap_bounds(&s);
            if lin_rate <= 0.0 && lin + reach < 0.0 {
                ended = RunEnd::PartedForGood(s.t);
                break 'run;
            }
            let w = window.unwrap_or(f64::INFINITY);
            if s.t >= w {
                ended = RunEnd::Window(w);
                break 'run;
            }
            if steps >= options.max_steps {
                ended = RunEnd::StepBudget(s.t);
                break 'run;
            }
            steps += 1;
            // the longer of two jumps that provably keep the gap open: the fastest rate the gap
            // can close at, and the modes' tangents with their curvature or swing
            let safe = (-s.delta / (lin_rate.abs() + speed)).max(int.flight_jump(&s));
            // a long jump must not overshoot the moment the bodies part for good (when they
            // move apart, the gap passes the tip's reach at a known time): its time is reported
            let parting = if lin_rate < 0.0 {
                (lin + reach) / -lin_rate + t_scale * 1e-6
            } else {
                f64::INFINITY
            };
            let jump = safe.max(t_scale / 100.0).min(parting).min(w - s.t);
            let next = int.step_unloaded(&s, jump, None);
            if next.delta > 0.0 {
                s = onset_in(&int, &s, jump);
                break;
            }
            s = next;
        }
    }
    let first = *contacts.first().ok_or(ImpactError::NotFinished {
        design: "CL",
        reason: "no contact".into(),
    })?;
    let overall = *contacts
        .iter()
        .max_by(|a, b| a.peak_force_n.total_cmp(&b.peak_force_n))
        .unwrap_or(&first);
    let out = ImpactOutcome {
        first,
        contacts,
        overall,
        ended,
        separation_rate_mps: s.delta_dot,
        energy_j: (e0, int.energy(&s)),
        work: steps,
    };
    if !(out.energy_j.1.is_finite() && out.overall.peak_force_n.is_finite()) {
        return Err(ImpactError::NotFinished {
            design: "CL",
            reason: "the integration lost finiteness".into(),
        });
    }
    Ok((out, stopped))
}

/// The first τ > 0 \[s\] at which c₀ + c₁ τ + c₂ τ² (c₂ ≥ 0) reaches 0, when it starts at or
/// below 0 and falls or stays below (+∞ when it never reaches it); 0 otherwise.
fn first_root(c0: f64, c1: f64, c2: f64) -> f64 {
    if c0 > 0.0 || (c0 == 0.0 && c1 >= 0.0) {
        return 0.0;
    }
    if c2 <= 0.0 {
        return if c1 > 0.0 { -c0 / c1 } else { f64::INFINITY };
    }
    let root = (c1 * c1 - 4.0 * c2 * c0).sqrt();
    if c1 < 0.0 {
        (root - c1) / (2.0 * c2)
    } else {
        -2.0 * c0 / (c1 + root)
    }
}

fn event(onset: f64, peak: (f64, f64), duration: f64) -> ContactEvent {
    ContactEvent {
        onset_s: onset,
        peak_force_n: peak.0,
        time_of_peak_s: peak.1,
        duration_s: duration,
    }
}

/// The deviation \[N\] of the force's hold over a step of length `h1` \[s\] ending at the force
/// `f1` \[N\], from the samples so far: the linear hold's h₁² |f″|/8 (f″ from the last two samples
/// and the step's end), the quadratic hold's |f‴| (h₀ + h₁) h₁²/24 (f‴ from the last three and
/// the step's end), the cubic hold's |f⁗| h₁² (h₀ + h₁)(h₀₀ + h₀ + h₁)/96 (f⁗ from the last four
/// and the step's end; with three, the quadratic's), each with the |derivative| it used; `None`
/// without enough samples.
fn hold_deviation(hold: ForceHold, samples: &[(f64, f64)], h1: f64, f1: f64) -> Option<(f64, f64)> {
    let m = samples.len();
    match hold {
        ForceHold::Linear => {
            let (t_a, f_a) = samples[m.checked_sub(2)?];
            let (t_b, f_b) = samples[m - 1];
            let h0 = t_b - t_a;
            let f2 = 2.0 * ((f1 - f_b) / h1 - (f_b - f_a) / h0) / (h0 + h1);
            Some((h1 * h1 * f2.abs() / 8.0, f2.abs()))
        }
        ForceHold::Cubic if m >= 4 => {
            let (a, b, c, d) = (
                samples[m - 4],
                samples[m - 3],
                samples[m - 2],
                samples[m - 1],
            );
            let (h0, h00) = (d.0 - c.0, c.0 - b.0);
            let f4 = fourth_derivative(&[a, b, c, d, (d.0 + h1, f1)]).abs();
            Some((f4 * h1 * h1 * (h0 + h1) * (h00 + h0 + h1) / 96.0, f4))
        }
        ForceHold::Quadratic | ForceHold::Cubic => {
            let a = samples[m.checked_sub(3)?];
            let (b, c) = (samples[m - 2], samples[m - 1]);
            let h0 = c.0 - b.0;
            let f3 = third_derivative(&[a, b, c, (c.0 + h1, f1)]).abs();
            Some((f3 * (h0 + h1) * h1 * h1 / 24.0, f3))
        }
    }
}

/// The force \[N\] a step of length `h` \[s\] is expected to end at: the polynomial through the
/// last three samples (two with fewer) extrapolated over h, never below 0 (the Newton
/// iteration's start; its error is of the order of the hold's deviation).
fn extrapolated_force(samples: &[(f64, f64)], h: f64) -> f64 {
    let m = samples.len();
    let (t0, f0) = samples[m - 1];
    let (t1, f1) = samples[m - 2];
    let slope = (f0 - f1) / (t0 - t1);
    let bend = match m.checked_sub(3).map(|i| samples[i]) {
        Some((t2, f2)) => (slope - (f1 - f2) / (t1 - t2)) / (t0 - t2),
        None => 0.0,
    };
    (f0 + h * slope + h * (h + t0 - t1) * bend).max(0.0)
}

/// The force \[N\] a step of length `h` \[s\] is expected to end at with the cubic hold: the
/// cubic through the last four samples extrapolated over h, never below 0.
fn cubic_extrapolation(samples: &[(f64, f64)], h: f64) -> f64 {
    let s = &samples[samples.len() - 4..];
    let t = s[3].0 + h;
    // Newton's form from the latest sample back
    let d = divided_differences(s);
    let (u3, u2, u1) = (t - s[3].0, t - s[2].0, t - s[1].0);
    (s[3].1 + u3 * (d[0][2] + u2 * (d[1][1] + u1 * d[2][0]))).max(0.0)
}

/// The divided differences of two to five samples (t \[s\], f \[N\]) of any spacing: entry
/// [k − 1][i] is f[tᵢ … t_{i+k}] = (f[t_{i+1} … t_{i+k}] − f[tᵢ … t_{i+k−1}])/(t_{i+k} − tᵢ),
/// k = 1 … n − 1.
fn divided_differences(s: &[(f64, f64)]) -> [[f64; 4]; 4] {
    let n = s.len();
    let mut d = [[0.0; 4]; 4];
    for i in 0..n - 1 {
        d[0][i] = (s[i + 1].1 - s[i].1) / (s[i + 1].0 - s[i].0);
    }
    for k in 2..n {
        for i in 0..n - k {
            d[k - 1][i] = (d[k - 2][i + 1] - d[k - 2][i]) / (s[i + k].0 - s[i].0);
        }
    }
    d
}

/// f⁗ \[N/s⁴\] from five samples (t \[s\], f \[N\]) of any spacing: 24 × their fourth divided
/// difference.
fn fourth_derivative(s: &[(f64, f64)]) -> f64 {
    // 24 f[t₀ … t₄], its last division scaled first as the derivative's
    let d = divided_differences(&s[..5]);
    24.0 * (d[2][1] - d[2][0]) / (s[4].0 - s[0].0)
}

/// f‴ \[N/s³\] from four samples (t \[s\], f \[N\]) of any spacing: 6 × their third divided
/// difference.
fn third_derivative(s: &[(f64, f64)]) -> f64 {
    // 6 f[t₀ … t₃], its last division scaled first as the derivative's
    let d = divided_differences(&s[..4]);
    6.0 * (d[1][1] - d[1][0]) / (s[3].0 - s[0].0)
}

/// The larger of `peak` and the latest local maximum of the samples (refined by the parabola
/// through the three samples around it; with the cubic hold and a fourth sample before them, by
/// the cubic through the four, so that the peak is as accurate as the hold).
fn max_peak(hold: ForceHold, samples: &[(f64, f64)], peak: (f64, f64)) -> (f64, f64) {
    let m = samples.len();
    if m < 3 {
        return peak;
    }
    let (a, b, c) = (samples[m - 3], samples[m - 2], samples[m - 1]);
    if !(b.1 > a.1 && b.1 >= c.1) {
        return peak;
    }
    let refined = match hold {
        ForceHold::Cubic if m >= 4 => cubic_vertex(samples[m - 4], a, b, c),
        _ => parabola_vertex(a, b, c),
    };
    if refined.1 > peak.0 {
        (refined.1, refined.0)
    } else {
        peak
    }
}

/// Vertex (t, f) of the parabola through three samples (any spacing), kept within [a, c].
fn parabola_vertex(a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> (f64, f64) {
    let (h0, h1) = (b.0 - a.0, c.0 - b.0);
    let d0 = (b.1 - a.1) / h0;
    let d1 = (c.1 - b.1) / h1;
    let curvature = (d1 - d0) / (h0 + h1); // f″/2
    if curvature >= 0.0 {
        return (b.0, b.1);
    }
    // f(t) = b + s (t − b.t) + curvature (t − b.t)², s the slope at b
    let slope = d0 + curvature * h0;
    let tau = (-slope / (2.0 * curvature)).clamp(-h0, h1);
    (b.0 + tau, b.1 + slope * tau + curvature * tau * tau)
}

/// The largest value (t, f) on [a, c] of the cubic through four samples (any spacing) whose
/// third, b, is at least its neighbours a and c: b, or the cubic's maximum between a and c.
fn cubic_vertex(z: (f64, f64), a: (f64, f64), b: (f64, f64), c: (f64, f64)) -> (f64, f64) {
    // f(b.t + τ) = b.f + c₁ τ + c₂ τ² + c₃ τ³ from Newton's form on the nodes 0, τ_a, τ_c, τ_z
    let (ta, tc, tz) = (a.0 - b.0, c.0 - b.0, z.0 - b.0);
    let d_ba = (a.1 - b.1) / ta;
    let d_ac = (c.1 - a.1) / (tc - ta);
    let d_cz = (z.1 - c.1) / (tz - tc);
    let d_bac = (d_ac - d_ba) / tc;
    let d_acz = (d_cz - d_ac) / (tz - ta);
    let d_bacz = (d_acz - d_bac) / tz;
    let c3 = d_bacz;
    let c2 = d_bac - c3 * (ta + tc);
    let c1 = d_ba - d_bac * ta + c3 * ta * tc;
    let value = |tau: f64| b.1 + tau * (c1 + tau * (c2 + tau * c3));
    // f′ = c₁ + 2c₂ τ + 3c₃ τ² = 0 within [τ_a, τ_c]
    let (qa, qb, qc) = (3.0 * c3, 2.0 * c2, c1);
    // (a tiny c₃ is safe: its far root falls outside, the product gives the near one)
    let roots: [f64; 2] = if qa == 0.0 {
        [-qc / qb, f64::NAN]
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < 0.0 {
            [f64::NAN; 2]
        } else {
            // the root without cancellation, and the other from the product
            let q = -0.5 * (qb + qb.signum() * disc.sqrt());
            [q / qa, if q != 0.0 { qc / q } else { f64::NAN }]
        }
    };
    roots
        .into_iter()
        .filter(|tau| tau.is_finite() && *tau > ta && *tau < tc)
        .map(|tau| (b.0 + tau, value(tau)))
        .fold(b, |best, p| if p.1 > best.1 { p } else { best })
}

/// The h′ ∈ (0, h] at which the gap closes, the force falling linearly from f₀ to 0 over h′
/// (Illinois regula falsi on δ(h′)).
fn separation_step(int: &Integrator<'_>, s: &Motion, h: f64, before: Option<Before>) -> f64 {
    let gap = |h: f64| int.unloaded_gap(s, h, before);
    illinois(gap, 0.0, s.delta, h, gap(h), 1e-13 * h)
}

/// The motion at the onset of contact inside a free jump of length `jump` from `s`.
///
/// A flight that starts on the surface (δ = 0: the bodies have just separated) has the trivial
/// root at its start; the onset sought is the next one, after the gap's dip below zero, which a
/// probe 1e-9 of the jump in finds. A gap already closing at the probe is a contact that never
/// opened: its onset is the probe, so the run advances.
fn onset_in(int: &Integrator<'_>, s: &Motion, jump: f64) -> Motion {
    let gap = |h: f64| int.free_gap(s, h);
    let (mut a, mut ga) = (0.0, s.delta);
    if ga >= 0.0 {
        a = 1e-9 * jump;
        ga = gap(a);
    }
    let h_on = if ga >= 0.0 {
        a
    } else {
        illinois(gap, a, ga, jump, gap(jump), 1e-13 * jump)
    };
    let mut at = int.step_unloaded(s, h_on, None);
    at.delta = 0.0;
    at
}

/// Root of g in [a, b] with g(a) and g(b) of opposite signs (Illinois regula falsi), to `tol`
/// in t between successive iterates.
fn illinois(
    g: impl Fn(f64) -> f64,
    mut a: f64,
    mut ga: f64,
    mut b: f64,
    mut gb: f64,
    tol: f64,
) -> f64 {
    if ga == 0.0 {
        return a;
    }
    if gb == 0.0 || ga * gb > 0.0 {
        return b;
    }
    for _ in 0..200 {
        let c = (a * gb - b * ga) / (gb - ga);
        let gc = g(c);
        if gc == 0.0 {
            return c;
        }
        let moved = (c - b).abs();
        if gc * gb < 0.0 {
            a = b;
            ga = gb;
        } else {
            ga *= 0.5;
        }
        b = c;
        gb = gc;
        if moved <= tol || (b - a).abs() <= tol {
            return b;
        }
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    /// ∫₀ʰ f(s) ds by composite Simpson on `n` (even) intervals.
    fn simpson(h: f64, n: usize, f: impl Fn(f64) -> f64) -> f64 {
        let dx = h / n as f64;
        let inner: f64 = (1..n)
            .map(|i| f(i as f64 * dx) * if i % 2 == 1 { 4.0 } else { 2.0 })
            .sum();
        (f(0.0) + f(h) + inner) * dx / 3.0
    }

    /// The step's per-mode coefficients are the Duhamel integrals they stand for: the response at
    /// h of q̈ + ω²q = g(τ) from rest, ∫₀ʰ sin(ω(h − s))/ω g(s) ds and ∫₀ʰ cos(ω(h − s)) g(s) ds,
    /// for the quadratic hold's τ(τ − h) (γ, γ_v) and the cubic hold's τ²(τ − h) (ε, ε_v), by
    /// Simpson's rule on 20 000 intervals, within 1e-10 of the largest over x = ωh from 1e-3 to
    /// 60 (the series below x = 1 and the closed forms above); and the two forms meet at x = 1.
    #[test]
    fn the_holds_coefficients_are_their_duhamel_integrals() {
        let h = 1e-3;
        for x in [1e-3, 0.05, 0.5, 0.999, 1.001, 2.0, 7.5, 20.0, 60.0] {
            let w = x / h;
            let c = mode_coefficients(w, h);
            let p = |g: &dyn Fn(f64) -> f64| simpson(h, 20_000, |s| (w * (h - s)).sin() / w * g(s));
            let v = |g: &dyn Fn(f64) -> f64| simpson(h, 20_000, |s| (w * (h - s)).cos() * g(s));
            let bend = |s: f64| s * (s - h);
            let twist = |s: f64| s * s * (s - h);
            for (ours, reference, scale) in [
                (c[7], p(&bend), h.powi(4)),
                (c[8], v(&bend), h.powi(3)),
                (c[9], p(&twist), h.powi(5)),
                (c[10], v(&twist), h.powi(4)),
            ] {
                assert!(
                    ((ours - reference) / scale).abs() < 1e-10,
                    "x = {x}: {ours:e} against {reference:e}"
                );
            }
        }
        // the series and the closed form of (sin x − x + x³/6)/x⁵ at the switch
        let below = quintic_response(1.0 - 1e-12, (1.0_f64 - 1e-12).sin());
        let above = quintic_response(1.0, 1.0_f64.sin());
        assert!((below / above - 1.0).abs() < 1e-13, "{below:e} {above:e}");
    }

    /// A small linear congruential generator in [0, 1) (reproducible, no dependency).
    fn uniform(seed: &mut u64) -> f64 {
        *seed = seed
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*seed >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The free flight's jump keeps the gap open: on 2 000 random structures (1–40 modes over
    /// six decades of ω, a rigid mode in some) and states (gaps from 0 to wide, the head
    /// towards or away), the exact free motion sampled at 400 points of each jump never
    /// closes the gap — and the jump is not idle (it beats the fastest-rate bound on most).
    #[test]
    fn the_flight_jump_never_closes_the_gap() {
        let law = Hertz::new(1e6, 1.5).unwrap();
        let mut seed = 7u64;
        let (mut longer, mut cases) = (0, 0);
        for _ in 0..2000 {
            let n = 1 + (uniform(&mut seed) * 40.0) as usize;
            let rigid = uniform(&mut seed) < 0.3;
            let mut omegas: Vec<f64> = (0..n)
                .map(|_| 10f64.powf(1.0 + 6.0 * uniform(&mut seed)))
                .collect();
            omegas.sort_by(f64::total_cmp);
            if rigid {
                omegas[0] = 0.0;
            }
            let gains: Vec<f64> = (0..n).map(|_| uniform(&mut seed) * 4.0 - 2.0).collect();
            let modes = TipModes {
                omegas: omegas.clone(),
                gains: gains.clone(),
                rates: vec![0.0; n],
                residual: 0.0,
            };
            let int = Integrator {
                modes: &modes,
                law: &law,
                m_h: 1.0,
                hold: ForceHold::Quadratic,
            };
            let q: Vec<f64> = (0..n).map(|_| (uniform(&mut seed) - 0.5) * 1e-3).collect();
            let q_dot: Vec<f64> = (0..n).map(|_| (uniform(&mut seed) - 0.5) * 0.1).collect();
            let w: f64 = gains.iter().zip(&q).map(|(b, q)| b * q).sum();
            let w_dot: f64 = gains.iter().zip(&q_dot).map(|(b, v)| b * v).sum();
            let gap = if uniform(&mut seed) < 0.2 {
                0.0
            } else {
                -1e-2 * 10f64.powf(-4.0 * uniform(&mut seed))
            };
            let v = (uniform(&mut seed) - 0.5) * 0.2;
            // at a zero gap the gap must be opening (the state right after a separation)
            if gap == 0.0 && v - w_dot >= 0.0 {
                continue;
            }
            let s = Motion {
                t: 0.0,
                q,
                q_dot,
                head: Head {
                    mass: 1.0,
                    x: w + gap,
                    v,
                },
                f: 0.0,
                delta: gap,
                delta_dot: v - w_dot,
            };
            let jump = int.flight_jump(&s);
            let (_, lin_rate, _, speed) = int.gap_bounds(&s);
            let rate_bound = -s.delta / (lin_rate.abs() + speed);
            cases += 1;
            if jump > rate_bound {
                longer += 1;
            }
            let horizon = jump.min(1e3);
            for j in 1..=400 {
                let m = int.free_motion(&s, horizon * j as f64 / 400.0);
                assert!(
                    m.delta <= 1e-12 * gap.abs().max(1e-9),
                    "gap {} closed at {} of the jump {jump:e} (modes {omegas:?})",
                    m.delta,
                    j
                );
            }
        }
        assert!(longer * 2 > cases, "{longer} of {cases}");
    }
}
