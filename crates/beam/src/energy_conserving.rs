//! The energy-conserving midpoint step (Simo & Tarnow 1992, Gonzalez 1996) for models with a
//! constant mass matrix: ANCF and linear.
//!
//! With the unknown increment Δq = q₁ − q₀ over a step h:
//! q̇₁ = 2Δq/h − q̇₀ (trapezoidal velocity), q_mid = q₀ + Δq/2, q̇_mid = Δq/h,
//! M (q̇₁ − q̇₀)/h + a₀ M q̇_mid + a₁ K_m(q_mid) q̇_mid + f̄(q₀, q₁) + f̄_root = F̄,
//! where f̄ is the element-by-element discrete gradient of the strain energy,
//! f̄ = ∇U(q_mid) + [U(q₁) − U(q₀) − ∇U(q_mid)·Δq] W Δq / (Δqᵀ W Δq) (see
//! [`crate::assembly_ancf`]), so f̄·Δq = U(q₁) − U(q₀) exactly, and F̄ = ½(F₀ + F₁) the dead and
//! motion-dependent loads averaged over the step (a moment through the discrete gradient of the
//! node angle on an ANCF node, so its work is ½(m₀ + m₁)(θ₁ − θ₀) exactly). Multiplying by Δq:
//! T₁ − T₀ + U₁ − U₀ = F̄·Δq − h q̇_midᵀ C q̇_mid:
//! undamped free motion conserves T + U to the Newton tolerance, whatever h and however large
//! the rotations — the trapezoidal rule (generalized-α at ρ∞ = 1) only does so for a quadratic U,
//! and drifts as O(h²) (amplitude³) for the nonlinear beam. The scheme is second order in h and
//! implicit; it does not damp unresolved high modes (use ρ∞ < 1 for that).
//!
//! Newton: iteration matrix ∂f̄/∂Δq + (1/h) C + (2/h²) M with the exact derivative of each
//! element's discrete gradient, ½ H(q_mid) + W Δq ∂cᵀ + c W (c the Gonzalez coefficient; not
//! symmetric, so LU), which keeps Newton quadratic even when h spans many periods of the stiff
//! axial modes (the root spring's correction derivative is left out); the node load adds
//! −(½ ∂F/∂q + (1/h) ∂F/∂q̇). The matrix is reused across iterations and steps while the
//! corrections contract fast (modified Newton). The state's acceleration follows the trapezoidal rule,
//! q̈₁ = 2(q̇₁ − q̇₀)/h − q̈₀.

use crate::BeamError;
use crate::assembly::{JacobianWeights, Kinematic, assemble};
use crate::assembly_ancf::{Discrete, assemble_ancf, discrete_angle_gradient, slope};
use crate::dynamics::{
    GeneralizedAlpha, MODIFIED_NEWTON_RATE, NewtonStep, Predictor, State, Workspace,
    add_node_jacobian, node_motion, step_work,
};
use crate::model::{BeamModel, Kinematics, NodalLoads};
use crate::node_load::NodeLoad;

impl GeneralizedAlpha {
    /// Newton iterations of one energy-conserving step (same contract as the generalized-α
    /// Newton: on success the state is advanced and (iterations, first, last correction)
    /// returned; on failure the state is unchanged).
    pub(crate) fn newton_energy_conserving<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        loads: &NodalLoads,
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
        step: NewtonStep,
    ) -> Result<(usize, f64, f64), (usize, BeamError)> {
        let NewtonStep {
            h,
            predictor,
            max_iterations,
        } = step;
        let nfix = model.n_fixed();
        let n = model.n_dofs();
        let dpn = model.dofs_per_node();
        let ancf = model.kinematics() == Kinematics::Ancf;
        let tol = self.newton_limits().1 * model.length();
        let t_new = state.t + h;
        let weights = JacobianWeights {
            stiffness: 0.5,
            velocity: 1.0 / h,
            acceleration: 2.0 / (h * h),
        };
        let f1 = loads.as_slice();
        for (i, fa) in ws.f_avg.iter_mut().enumerate() {
            *fa = 0.5 * (state.f_prev[i] + f1[i]);
        }
        if ancf {
            crate::assembly_ancf::strain_energies_ancf(model, &state.q, &mut ws.u0);
        }
        for i in 0..n {
            ws.dq_step[i] = match predictor {
                Predictor::Rest => 0.0,
                Predictor::Velocity => h * state.v[i],
                Predictor::Extrapolated => h * state.v[i] + 0.5 * h * h * state.a[i],
            };
        }
        let key = Some((h, 1.0, true));
        let mut refactor = ws.factored_for != key;
        let mut iterations = 0;
        let mut last = f64::INFINITY;
        let mut first = f64::INFINITY;
        let mut previous = f64::INFINITY;
        loop {
            for i in 0..n {
                let d = ws.dq_step[i];
                ws.q_new[i] = state.q[i] + d;
                ws.q_mid[i] = state.q[i] + 0.5 * d;
                ws.v_new[i] = 2.0 * d / h - state.v[i];
                // q̇_mid and (q̇₁ − q̇₀)/h (the residual's velocity and acceleration)
                ws.ahat_new[i] = d / h;
                ws.a_new[i] = (ws.v_new[i] - state.v[i]) / h;
            }
            if iterations > 0 && last <= tol {
                break;
            }
            if iterations >= max_iterations {
                let residual = ws.r[nfix..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
                return Err((
                    iterations,
                    BeamError::NotConverged {
                        solver: "energy-conserving step".into(),
                        load_level: 1.0,
                        iterations,
                        residual,
                    },
                ));
            }
            let jac = refactor || ws.factored_for != key;
            let kin = Kinematic {
                q: &ws.q_mid,
                v: Some(&ws.ahat_new),
                a: Some(&ws.a_new),
            };
            let band = if jac {
                Some((&mut ws.band, weights))
            } else {
                None
            };
            if jac {
                ws.counters.tangents += 1;
            } else {
                ws.counters.residuals += 1;
            }
            if ancf {
                let mut dg = Discrete {
                    q0: &state.q,
                    q1: &ws.q_new,
                    u0: &ws.u0,
                    u1: &mut ws.u1,
                };
                assemble_ancf(model, kin, &ws.f_avg, &mut ws.r, band, Some(&mut dg));
            } else {
                assemble(model, kin, &ws.f_avg, &mut ws.r, band);
            }
            node_load_averaged(
                node_load.as_deref_mut(),
                (t_new, h),
                state,
                ws,
                (nfix, dpn),
                jac,
            )
            .map_err(|e| (iterations, e))?;
            if jac {
                ws.factored_for = None;
                ws.counters.factorizations += 1;
                let factored = ws.band.factorize("energy-conserving iteration matrix");
                if let Err(e) = factored {
                    return Err((iterations, e));
                }
                ws.factored_for = key;
                refactor = false;
            }
            for (d, ri) in ws.dq.iter_mut().zip(&ws.r[nfix..]) {
                *d = -ri;
            }
            ws.band.solve_in_place(&mut ws.dq);
            ws.counters.iterations += 1;
            // A correction that turns a slope (ANCF) or a rotation by more than the limiter
            // allows is scaled down: from a poor start (a predictor deep inside a stiff contact)
            // an unlimited Newton can run away by kilometres.
            let scale = correction_limiter(&ws.dq, nfix, dpn, model.length());
            last = 0.0;
            for (i, d) in (nfix..n).zip(&ws.dq) {
                ws.dq_step[i] += scale * d;
                last = last.max((scale * d).abs());
            }
            if !last.is_finite() {
                ws.factored_for = None;
                return Err((
                    iterations,
                    BeamError::NonFinite {
                        what: "energy-conserving displacement".into(),
                    },
                ));
            }
            if iterations == 0 {
                first = last;
            }
            if !jac && iterations > 0 && last > MODIFIED_NEWTON_RATE * previous {
                refactor = true;
            }
            previous = last;
            iterations += 1;
        }
        if [&ws.q_new, &ws.v_new]
            .iter()
            .any(|x| x.iter().any(|v| !v.is_finite()))
        {
            return Err((
                iterations,
                BeamError::NonFinite {
                    what: "energy-conserving state".into(),
                },
            ));
        }
        // The node load at the accepted state (its force was evaluated at the last iterate,
        // which differs from the accepted one by the last correction: re-evaluate).
        let node_force = node_load.map(|nl| {
            let i = nl.node();
            let (q, v) = node_motion(dpn, &ws.q_new, &ws.v_new, i);
            (i, nl.evaluate(t_new, q, v).force)
        });
        // Accept.
        state.external_work += step_work(
            dpn,
            (&state.q, &ws.q_new),
            (&state.f_prev, f1),
            state.node_force_prev,
            node_force,
        );
        state.node_force_prev = node_force.unwrap_or((state.node_force_prev.0, [0.0; 3]));
        state.f_prev.copy_from_slice(f1);
        for i in 0..n {
            let a1 = 2.0 * (ws.v_new[i] - state.v[i]) / h - state.a[i];
            state.a[i] = a1;
        }
        state.q.copy_from_slice(&ws.q_new);
        state.v.copy_from_slice(&ws.v_new);
        state.a_aux_prev.clear();
        state.a_aux_prev.extend_from_slice(&state.a_aux);
        state.a_aux.copy_from_slice(&state.a);
        state.h_prev = Some(h);
        state.t = t_new;
        ws.counters.steps += 1;
        Ok((iterations, first, last))
    }
}

/// The motion-dependent node load averaged over the step, ½(F₀ + F₁), into the residual
/// (a moment on an ANCF node through the discrete gradient of θ) and, if `jac`, ½ of its
/// derivatives at the end of the step into the iteration matrix.
fn node_load_averaged<'l>(
    node_load: Option<&mut (dyn NodeLoad + 'l)>,
    (t, h): (f64, f64),
    state: &State,
    ws: &mut Workspace,
    (nfix, dpn): (usize, usize),
    jac: bool,
) -> Result<(), BeamError> {
    let Some(nl) = node_load else {
        return Ok(());
    };
    let node = nl.node();
    let (q, v) = node_motion(dpn, &ws.q_new, &ws.v_new, node);
    let f = nl.evaluate(t, q, v);
    if !f.is_finite() {
        return Err(BeamError::NonFinite {
            what: "node load".into(),
        });
    }
    let (i_prev, f_prev) = state.node_force_prev;
    // ½ F₀ acts on the node it acted on; ½ F₁ on the current node
    for (i, force) in [(i_prev, f_prev), (node, f.force)] {
        let k = dpn * i;
        if dpn == 3 {
            for d in 0..3 {
                ws.r[k + d] -= 0.5 * force[d];
            }
        } else {
            use crate::assembly_ancf::{SLOPE_X, SLOPE_Y};
            let (g, _) = discrete_angle_gradient(slope(&state.q, i), slope(&ws.q_new, i));
            ws.r[k] -= 0.5 * force[0];
            ws.r[k + 1] -= 0.5 * force[1];
            ws.r[k + SLOPE_X] -= 0.5 * force[2] * g[0];
            ws.r[k + SLOPE_Y] -= 0.5 * force[2] * g[1];
        }
    }
    if jac {
        // c_q = 1 on q₁ and c_v = 2/h on q̇₁, times ½: the weights (½, 1/h)
        let w = JacobianWeights {
            stiffness: 1.0,
            velocity: 2.0 / h,
            acceleration: 0.0,
        };
        add_node_jacobian(ws, (nfix, dpn), node, &f, w, 0.5);
    }
    Ok(())
}

/// Scale s ≤ 1 so that s·Δq turns no slope (ANCF: r′ components; 3-DOF nodes: θ) by more than
/// [`crate::statics::MAX_ROTATION_INCREMENT`] and moves no node by more than a tenth of the beam
/// length (`dq` over the free DOFs, the first of which is global DOF `nfix`).
fn correction_limiter(dq: &[f64], nfix: usize, dofs_per_node: usize, length: f64) -> f64 {
    let (mut turn, mut shift) = (0.0f64, 0.0f64);
    for (i, d) in dq.iter().enumerate() {
        let c = (i + nfix) % dofs_per_node;
        if c >= 2 {
            turn = turn.max(d.abs());
        } else {
            shift = shift.max(d.abs());
        }
    }
    let mut s = 1.0f64;
    if turn > crate::statics::MAX_ROTATION_INCREMENT {
        s = s.min(crate::statics::MAX_ROTATION_INCREMENT / turn);
    }
    if shift > 0.1 * length {
        s = s.min(0.1 * length / shift);
    }
    s
}
