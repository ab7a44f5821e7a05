//! Static solution: one banded solve K q = F for the linear model; Newton–Raphson with load
//! stepping for the large-deflection models (corotational, ANCF).
//!
//! Fixed load steps: for load levels λ_k = k/K (k = 1..K) solve r(q) = f_int(q) − λ_k F = 0 by
//! Newton, K_t Δq = −r (Δq scaled so no rotation changes by more than 0.5 rad), starting from
//! the secant predictor 2 q_{k−1} − q_{k−2} (from the second level on; from q_{k−1} if Newton
//! fails from the predictor) or the converged state of the previous level. Converged when
//! ‖r‖∞ ≤ tol·max(‖λ_k F‖∞, ‖f_int‖∞) (reactions excluded) or ‖Δq‖∞ ≤ 1e-3·tol·L.
//!
//! Adaptive load steps ([`StaticOptions::with_adaptive_steps`]): the first increment is 1/K of
//! the load (the full load for K = 1); a level whose Newton solve fails (no convergence within
//! the iteration limit, a non-finite residual or a singular tangent after the first iteration)
//! is tried again from the last converged state with half the increment, and after each
//! converged level the increment doubles (at most the load left; kept after a level that
//! needed a cut, and a last increment of up to 1.5 times the current one taken whole), the
//! next level starting from the secant
//! predictor q_k + (Δλ_{k+1}/Δλ_k)(q_k − q_{k−1}). The equilibrium reached is the same as with
//! fixed steps (the same Newton test at the full load); the number of Newton solves is what the
//! load needs rather than what was asked for. Below an increment of 2⁻³⁰ the solve stops with
//! the load level reached. Two checks keep a long increment from landing on another
//! equilibrium than the load path's: a converged level is tried again with half the increment
//! if its tangent stiffness is no longer positive definite while the last level's was (an
//! unstable equilibrium or a jump over a limit point or bifurcation; accepted once the
//! increment is down to 1/(32 K), as fine steps would cross it), and, corotational, if the two
//! nodal rotations of an element differ by π or more (the element is 2π-periodic in them, so
//! a node can converge turned by a full turn). Each level's Newton solve also stops when the
//! next increment, extrapolated at the rate of the last two, would pass the increment test.

use crate::BeamError;
use crate::assembly::{JacobianWeights, Kinematic, assemble, band_for};
use crate::model::{BeamModel, Kinematics, NodalLoads};

/// Largest change of a nodal rotation in one Newton iteration \[rad\]; larger corrections are
/// scaled down as a whole (damped Newton). The corotational element is 2π-periodic in the nodal
/// rotations, so an unlimited step can converge to a node turned by a full turn.
pub const MAX_ROTATION_INCREMENT: f64 = 0.5;

/// Scale factor s ≤ 1 so that s·Δq changes no rotation DOF by more than
/// [`MAX_ROTATION_INCREMENT`] (`dq` over the free DOFs, the first of which is global DOF `nfix`).
pub fn rotation_limiter(dq: &[f64], nfix: usize) -> f64 {
    let mut worst = 0.0f64;
    for (i, d) in dq.iter().enumerate() {
        if (i + nfix) % 3 == 2 {
            worst = worst.max(d.abs());
        }
    }
    if worst > MAX_ROTATION_INCREMENT {
        MAX_ROTATION_INCREMENT / worst
    } else {
        1.0
    }
}

/// Newton settings for the static solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticOptions {
    load_steps: usize,
    max_iterations: usize,
    tolerance: f64,
    adaptive: bool,
}

impl StaticOptions {
    /// `load_steps` ≥ 1 load increments, at most `max_iterations` ≥ 1 Newton iterations per
    /// increment, relative `tolerance` in (0, 1e-2].
    pub fn new(
        load_steps: usize,
        max_iterations: usize,
        tolerance: f64,
    ) -> Result<Self, BeamError> {
        if load_steps == 0 || load_steps > 1_000_000 {
            return Err(BeamError::invalid(
                "load-steps",
                load_steps,
                "an integer from 1 to 1000000",
            ));
        }
        if max_iterations == 0 {
            return Err(BeamError::invalid(
                "max_iterations",
                max_iterations,
                "an integer ≥ 1",
            ));
        }
        if !(tolerance > 0.0 && tolerance <= 1e-2) {
            return Err(BeamError::invalid(
                "tolerance",
                tolerance,
                "a number in (0, 1e-2]",
            ));
        }
        Ok(StaticOptions {
            load_steps,
            max_iterations,
            tolerance,
            adaptive: false,
        })
    }
    /// The same settings with adaptive load steps: the load steps are the first increment's
    /// count (1: the full load first), cut in half where Newton fails and doubled after each
    /// converged level (see the module documentation).
    pub fn with_adaptive_steps(self) -> Self {
        StaticOptions {
            adaptive: true,
            ..self
        }
    }
    /// Adaptive load steps from the full load, 30 iterations per level, tolerance 1e-10.
    pub fn adaptive() -> Self {
        StaticOptions {
            load_steps: 1,
            max_iterations: 30,
            tolerance: 1e-10,
            adaptive: true,
        }
    }
    /// Whether the load steps are adaptive.
    pub fn is_adaptive(&self) -> bool {
        self.adaptive
    }
    /// `load_steps` increments, 30 iterations, tolerance 1e-10.
    pub fn with_load_steps(load_steps: usize) -> Result<Self, BeamError> {
        Self::new(load_steps, 30, 1e-10)
    }
}

/// A converged static solution.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution {
    /// Displacements, one entry per DOF [m, rad] (ANCF: see [`Kinematics::Ancf`]).
    pub q: Vec<f64>,
    /// Total Newton iterations (1 for the linear model).
    pub iterations: usize,
    /// Final residual ‖r‖∞ over the free DOFs \[N\].
    pub residual: f64,
    /// Load level reached (1 when converged).
    pub load_level: f64,
    /// Reactions at the constrained root DOFs [N, N·m] (u, v, then θ when clamped).
    pub reactions: Vec<f64>,
    dofs_per_node: usize,
}

impl StaticSolution {
    /// (u, v, θ) of node `i` (ANCF: θ = atan2(r′ᵧ, r′ₓ)).
    pub fn node(&self, i: usize) -> (f64, f64, f64) {
        if self.dofs_per_node == 4 {
            let [u, v, t] = crate::assembly_ancf::node_uvt(&self.q, i);
            (u, v, t)
        } else {
            (self.q[3 * i], self.q[3 * i + 1], self.q[3 * i + 2])
        }
    }
}

/// Solves the static problem under the dead `loads`.
pub fn solve_static(
    model: &BeamModel,
    loads: &NodalLoads,
    options: &StaticOptions,
) -> Result<StaticSolution, BeamError> {
    let start = NodalLoads::zeros(model);
    solve_static_from(model, &start, &vec![0.0; model.n_dofs()], loads, options)
}

/// Smallest adaptive load increment, as a fraction of the load (2⁻³⁰ ≈ 9.3e-10).
const MIN_ADAPTIVE_INCREMENT: f64 = 1.0 / (1u64 << 30) as f64;

/// The fixed data of one static solve and its work arrays.
struct Newton<'a> {
    model: &'a BeamModel,
    options: &'a StaticOptions,
    nfix: usize,
    ancf: bool,
    /// Largest load magnitude (start and end, reactions excluded) \[N, N·m\].
    f_scale: f64,
    f_start: &'a [f64],
    f_full: &'a [f64],
    /// Loads of the current level.
    f: Vec<f64>,
    /// ANCF: the loads as generalized forces on the DOFs (for the internal-force scale).
    f_gen: Vec<f64>,
    r: Vec<f64>,
    dq: Vec<f64>,
    band: crate::banded::BandMatrix,
}

/// How the Newton solve of one load level ended.
struct Level {
    converged: bool,
    /// Whether the last tangent factorised was positive definite (its LDLᵀ factorisation).
    positive_definite: bool,
    iterations: usize,
    /// The last residual ‖r‖∞ over the free DOFs \[N\].
    residual: f64,
}

impl Newton<'_> {
    /// Sets the loads of level λ (linear between the start and the full loads).
    fn set_level(&mut self, lambda: f64) {
        for (i, f) in self.f.iter_mut().enumerate() {
            *f = self.f_start[i] + lambda * (self.f_full[i] - self.f_start[i]);
        }
    }

    /// ‖r‖∞ over the free DOFs.
    fn free_residual(&self) -> f64 {
        self.r[self.nfix..]
            .iter()
            .fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// Newton's iterations on the current level from `q` (overwritten with the last iterate).
    /// `soft`: a non-finite residual or a singular tangent ends the level as not converged
    /// (the caller tries again) instead of as an error; with `soft_after_first` only from the
    /// second iteration on. `rate_test`: also converged when the next increment, extrapolated
    /// at the rate of the last two (ρ = ‖Δq_k‖/‖Δq_{k−1}‖ < 0.1, from the second iteration on),
    /// ρ‖Δq_k‖, is below the increment test's 1e-3·tol·L (the iteration that would only
    /// confirm it is saved; quadratic convergence makes the true next increment smaller still).
    fn solve_level(
        &mut self,
        q: &mut [f64],
        soft: bool,
        soft_after_first: bool,
        rate_test: bool,
    ) -> Result<Level, BeamError> {
        let model = self.model;
        let nfix = self.nfix;
        let kinematics = model.kinematics();
        let w = JacobianWeights {
            stiffness: 1.0,
            velocity: 0.0,
            acceleration: 0.0,
        };
        let mut iterations = 0;
        let mut residual = 0.0;
        let mut positive_definite = false;
        let mut last_dmax = f64::INFINITY;
        let small = self.options.tolerance * 1e-3 * model.length();
        while iterations < self.options.max_iterations {
            let soft_now = soft || (soft_after_first && iterations > 0);
            let kin = Kinematic {
                q,
                v: None,
                a: None,
            };
            assemble(model, kin, &self.f, &mut self.r, Some((&mut self.band, w)));
            residual = self.free_residual();
            if !residual.is_finite() {
                if soft_now {
                    break;
                }
                return Err(BeamError::NonFinite {
                    what: "static residual".into(),
                });
            }
            if self.ancf {
                crate::assembly_ancf::generalized_loads(model, q, &self.f, &mut self.f_gen);
            } else {
                self.f_gen.copy_from_slice(&self.f);
            }
            let f_int_scale = self.r[nfix..]
                .iter()
                .zip(&self.f_gen[nfix..])
                .fold(0.0f64, |m, (ri, fi)| m.max((ri + fi).abs()));
            let scale = self.f_scale.max(f_int_scale);
            if (iterations > 0 && residual <= self.options.tolerance * scale) || scale == 0.0 {
                return Ok(Level {
                    converged: true,
                    positive_definite,
                    iterations,
                    residual,
                });
            }
            match self.band.factorize("tangent stiffness") {
                Err(_) if soft_now => break,
                other => other?,
            }
            positive_definite = self.band.is_ldlt();
            self.dq
                .iter_mut()
                .zip(&self.r[nfix..])
                .for_each(|(d, ri)| *d = -ri);
            self.band.solve_in_place(&mut self.dq);
            iterations += 1;
            let s = if kinematics == Kinematics::Corotational {
                rotation_limiter(&self.dq, nfix)
            } else {
                1.0
            };
            let mut dmax = 0.0f64;
            for (qi, d) in q[nfix..].iter_mut().zip(&self.dq) {
                *qi += s * d;
                dmax = dmax.max((s * d).abs());
            }
            if kinematics == Kinematics::Linear {
                return Ok(Level {
                    converged: true,
                    positive_definite,
                    iterations,
                    residual,
                });
            }
            let rate = dmax / last_dmax;
            last_dmax = dmax;
            if dmax <= small || (rate_test && iterations >= 2 && rate < 0.1 && dmax * rate <= small)
            {
                // increment at round-off level (or the next one would be): accept after one
                // last residual evaluation
                let kin = Kinematic {
                    q,
                    v: None,
                    a: None,
                };
                assemble(model, kin, &self.f, &mut self.r, None);
                return Ok(Level {
                    converged: true,
                    positive_definite,
                    iterations,
                    residual: self.free_residual(),
                });
            }
        }
        Ok(Level {
            converged: false,
            positive_definite: false,
            iterations,
            residual,
        })
    }
}

/// The error of a level that failed after the load level `reached`.
fn not_converged(reached: f64, level: &Level) -> BeamError {
    BeamError::NotConverged {
        solver: "corotational static solve".into(),
        load_level: reached,
        iterations: level.iterations,
        residual: level.residual,
    }
}

/// Continuation: from the equilibrium `q_start` under `start` to the equilibrium under `loads`,
/// with the loads interpolated linearly over the load steps (used to trace load paths).
pub fn solve_static_from(
    model: &BeamModel,
    start: &NodalLoads,
    q_start: &[f64],
    loads: &NodalLoads,
    options: &StaticOptions,
) -> Result<StaticSolution, BeamError> {
    loads.check(model)?;
    start.check(model)?;
    let n = model.n_dofs();
    if q_start.len() != n || q_start.iter().any(|x| !x.is_finite()) {
        return Err(BeamError::invalid(
            "q_start",
            format!("{} entries", q_start.len()),
            format!("{n} finite entries"),
        ));
    }
    let nfix = model.n_fixed();
    let ancf = model.kinematics() == Kinematics::Ancf;
    let f_start = start.as_slice();
    let f_full = loads.as_slice();
    // loads on the root node's constrained DOFs are taken by the support
    let skip = if ancf { 3 } else { nfix };
    let f_scale = f_full[skip..]
        .iter()
        .chain(&f_start[skip..])
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let mut newton = Newton {
        model,
        options,
        nfix,
        ancf,
        f_scale,
        f_start,
        f_full,
        f: vec![0.0; f_full.len()],
        f_gen: vec![0.0; n],
        r: vec![0.0; n],
        dq: vec![0.0; n - nfix],
        band: band_for(model),
    };
    let mut q = q_start.to_vec();
    let iterations = match model.kinematics() {
        Kinematics::Linear => {
            newton.set_level(1.0);
            newton.solve_level(&mut q, false, false, false)?.iterations
        }
        Kinematics::Corotational | Kinematics::Ancf if options.adaptive => {
            adaptive_levels(&mut newton, &mut q)?
        }
        Kinematics::Corotational | Kinematics::Ancf => fixed_levels(&mut newton, &mut q)?,
    };
    // Final residual and reactions.
    let mut r = newton.r;
    let kin = Kinematic {
        q: &q,
        v: None,
        a: None,
    };
    assemble(model, kin, f_full, &mut r, None);
    let residual = r[nfix..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    // (finite loads near f64::MAX can overflow the displacements of the linear solve)
    if !residual.is_finite() || q.iter().any(|x| !x.is_finite()) {
        return Err(BeamError::NonFinite {
            what: "static displacement".into(),
        });
    }
    let mut reactions = r[..nfix].to_vec();
    if ancf && nfix == 3 {
        // the r′ᵧ reaction Q is a moment Q/(∂θ/∂r′ᵧ) = Q |r′|²/r′ₓ (r′ᵧ = 0 at a clamped root)
        let (sx, _) = crate::assembly_ancf::slope(&q, 0);
        reactions[2] *= sx;
    }
    Ok(StaticSolution {
        reactions,
        dofs_per_node: model.dofs_per_node(),
        q,
        iterations,
        residual,
        load_level: 1.0,
    })
}

/// The fixed load levels k/K, k = 1..K (K the options' load steps); returns the total Newton
/// iterations.
fn fixed_levels(newton: &mut Newton, q: &mut [f64]) -> Result<usize, BeamError> {
    let steps = newton.options.load_steps;
    let nfix = newton.nfix;
    let mut total_iterations = 0;
    // the converged solutions of the last two load levels (secant predictor)
    let mut q_level = q.to_vec();
    let mut q_level_prev: Option<Vec<f64>> = None;
    let mut predicted = false;
    let mut step = 1;
    while step <= steps {
        newton.set_level(step as f64 / steps as f64);
        // Secant predictor (from the second level on): the load levels are equally spaced, so
        // q ≈ 2 q_k − q_{k−1}; Newton from there needs fewer iterations. If Newton fails from
        // it, the level is solved again from q_k.
        if !predicted && let Some(prev) = &q_level_prev {
            for i in nfix..q.len() {
                q[i] = 2.0 * q_level[i] - prev[i];
            }
            predicted = true;
        }
        let level = newton.solve_level(q, predicted, false, false)?;
        total_iterations += level.iterations;
        if !level.converged && predicted {
            // from the last converged level instead
            q.copy_from_slice(&q_level);
            q_level_prev = None;
            predicted = false;
            continue;
        }
        if !level.converged {
            // the level reached: the last converged one
            return Err(not_converged((step - 1) as f64 / steps as f64, &level));
        }
        let prev = q_level_prev.get_or_insert_with(|| vec![0.0; q.len()]);
        std::mem::swap(prev, &mut q_level);
        q_level.copy_from_slice(q);
        predicted = false;
        step += 1;
    }
    Ok(total_iterations)
}

/// Adaptive load levels (see the module documentation); returns the total Newton iterations.
fn adaptive_levels(newton: &mut Newton, q: &mut [f64]) -> Result<usize, BeamError> {
    let nfix = newton.nfix;
    let mut total_iterations = 0;
    // load level reached, the next increment and the last converged increment
    let mut lambda = 0.0f64;
    let mut increment = 1.0 / newton.options.load_steps as f64;
    let mut last_increment = 0.0f64;
    let mut q_level = q.to_vec();
    let mut q_level_prev = q.to_vec();
    // whether the last converged level's tangent was positive definite (the start's assumed),
    // and the increment below which a loss of definiteness is accepted
    let mut positive_definite = true;
    let guard = increment / 32.0;
    let mut failed_before = false;
    while lambda < 1.0 {
        // the load left when it is close to one increment (no sliver of a last level)
        let target = if lambda + 1.5 * increment >= 1.0 {
            1.0
        } else {
            lambda + increment
        };
        newton.set_level(target);
        let predicted = last_increment > 0.0;
        if predicted {
            // secant predictor along the last converged increment
            let c = (target - lambda) / last_increment;
            for i in nfix..q.len() {
                q[i] = q_level[i] + c * (q_level[i] - q_level_prev[i]);
            }
        }
        // from a converged state without predictor, a failure at the first iteration is the
        // structure's or the load's (a singular support, overflowing loads), not the step's
        let level = newton.solve_level(q, predicted, true, true)?;
        total_iterations += level.iterations;
        let step = target - lambda;
        let lost_definiteness =
            level.converged && positive_definite && !level.positive_definite && step > guard;
        let accepted = level.converged && !lost_definiteness && !full_turn(newton.model, q);
        if accepted {
            positive_definite = level.positive_definite;
            last_increment = step;
            lambda = target;
            std::mem::swap(&mut q_level_prev, &mut q_level);
            q_level.copy_from_slice(q);
            // longer only after a level that was not cut back
            let factor = if failed_before { 1.0 } else { 2.0 };
            increment = (factor * last_increment).min(1.0 - lambda);
            failed_before = false;
        } else {
            q.copy_from_slice(&q_level);
            increment = 0.5 * step;
            failed_before = true;
            if increment < MIN_ADAPTIVE_INCREMENT {
                return Err(not_converged(lambda, &level));
            }
        }
    }
    Ok(total_iterations)
}

/// Corotational: whether the nodal rotations of some element differ by π or more (a node turned
/// by a full turn against its neighbour: the element's energy is 2π-periodic in the nodal
/// rotations, so such a state is an equilibrium of the discrete model off the load path).
fn full_turn(model: &BeamModel, q: &[f64]) -> bool {
    model.kinematics() == Kinematics::Corotational
        && q.chunks_exact(3)
            .zip(q.chunks_exact(3).skip(1))
            .any(|(a, b)| (b[2] - a[2]).abs() >= std::f64::consts::PI)
}
