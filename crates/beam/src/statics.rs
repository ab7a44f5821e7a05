//! Static solution: one banded solve K q = F for the linear model; Newton–Raphson with load
//! stepping for the corotational model.
//!
//! Corotational: for load levels λ_k = k/K (k = 1..K) solve r(q) = f_int(q) − λ_k F = 0 by
//! Newton, K_t Δq = −r (Δq scaled so no rotation changes by more than 0.5 rad), starting from
//! the secant predictor 2 q_{k−1} − q_{k−2} (from the second level on; from q_{k−1} if Newton
//! fails from the predictor) or the converged state of the previous level. Converged when
//! ‖r‖∞ ≤ tol·max(‖λ_k F‖∞, ‖f_int‖∞) (reactions excluded) or ‖Δq‖∞ ≤ 1e-3·tol·L.

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
        })
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
    let mut q = q_start.to_vec();
    let f_start = start.as_slice();
    let mut r = vec![0.0; n];
    let mut band = band_for(model);
    let w = JacobianWeights {
        stiffness: 1.0,
        velocity: 0.0,
        acceleration: 0.0,
    };
    let steps = match model.kinematics() {
        Kinematics::Linear => 1,
        Kinematics::Corotational | Kinematics::Ancf => options.load_steps,
    };
    let ancf = model.kinematics() == Kinematics::Ancf;
    let f_full = loads.as_slice();
    // loads on the root node's constrained DOFs are taken by the support
    let skip = if ancf { 3 } else { nfix };
    let f_scale = f_full[skip..]
        .iter()
        .chain(&f_start[skip..])
        .fold(0.0f64, |m, x| m.max(x.abs()));
    let mut f = vec![0.0; f_full.len()];
    // ANCF: the loads as generalized forces on the DOFs (for the internal-force scale)
    let mut f_gen = vec![0.0; n];
    let mut total_iterations = 0;
    let mut residual = 0.0;
    let mut dq = vec![0.0; n - nfix];
    // the converged solutions of the last two load levels (secant predictor)
    let mut q_level = q.clone();
    let mut q_level_prev: Option<Vec<f64>> = None;
    let mut predicted = false;
    let mut step = 1;
    while step <= steps {
        let lambda = step as f64 / steps as f64;
        for i in 0..f.len() {
            f[i] = f_start[i] + lambda * (f_full[i] - f_start[i]);
        }
        // Secant predictor (nonlinear models, from the second level on): the load levels are
        // equally spaced, so q ≈ 2 q_k − q_{k−1}; Newton from there needs fewer iterations. If
        // Newton fails from it, the level is solved again from q_k.
        if !predicted
            && model.kinematics() != Kinematics::Linear
            && let Some(prev) = &q_level_prev
        {
            for i in nfix..n {
                q[i] = 2.0 * q_level[i] - prev[i];
            }
            predicted = true;
        }
        let mut converged = false;
        let mut iterations = 0;
        while iterations < options.max_iterations {
            let kin = Kinematic {
                q: &q,
                v: None,
                a: None,
            };
            assemble(model, kin, &f, &mut r, Some((&mut band, w)));
            residual = r[nfix..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
            if !residual.is_finite() {
                if predicted {
                    break;
                }
                return Err(BeamError::NonFinite {
                    what: "static residual".into(),
                });
            }
            if ancf {
                crate::assembly_ancf::generalized_loads(model, &q, &f, &mut f_gen);
            } else {
                f_gen.copy_from_slice(&f);
            }
            let f_int_scale = r[nfix..]
                .iter()
                .zip(&f_gen[nfix..])
                .fold(0.0f64, |m, (ri, fi)| m.max((ri + fi).abs()));
            let scale = f_scale.max(f_int_scale);
            if iterations > 0 && residual <= options.tolerance * scale {
                converged = true;
                break;
            }
            if scale == 0.0 {
                converged = true;
                break;
            }
            match band.factorize("tangent stiffness") {
                Err(_) if predicted => break,
                other => other?,
            }
            dq.iter_mut().zip(&r[nfix..]).for_each(|(d, ri)| *d = -ri);
            band.solve_in_place(&mut dq);
            iterations += 1;
            let s = if model.kinematics() == Kinematics::Corotational {
                rotation_limiter(&dq, nfix)
            } else {
                1.0
            };
            let mut dmax = 0.0f64;
            for (qi, d) in q[nfix..].iter_mut().zip(&dq) {
                *qi += s * d;
                dmax = dmax.max((s * d).abs());
            }
            if model.kinematics() == Kinematics::Linear {
                converged = true;
                break;
            }
            if dmax <= options.tolerance * 1e-3 * model.length() {
                // increment at round-off level: accept after one last residual evaluation
                let kin = Kinematic {
                    q: &q,
                    v: None,
                    a: None,
                };
                assemble(model, kin, &f, &mut r, None);
                residual = r[nfix..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
                converged = true;
                break;
            }
        }
        total_iterations += iterations;
        if !converged && predicted {
            // from the last converged level instead
            q.copy_from_slice(&q_level);
            q_level_prev = None;
            predicted = false;
            continue;
        }
        if !converged {
            return Err(BeamError::NotConverged {
                solver: "corotational static solve".into(),
                // the level reached: the last converged one
                load_level: (step - 1) as f64 / steps as f64,
                iterations,
                residual,
            });
        }
        q_level_prev = Some(std::mem::replace(&mut q_level, q.clone()));
        predicted = false;
        step += 1;
    }
    // Final residual and reactions.
    let kin = Kinematic {
        q: &q,
        v: None,
        a: None,
    };
    assemble(model, kin, f_full, &mut r, None);
    residual = r[nfix..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
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
        iterations: total_iterations,
        residual,
        load_level: 1.0,
    })
}
