//! Transient dynamics: the generalized-α method with Chung–Hulbert parameters.
//!
//! Parameters from the spectral radius at infinite frequency ρ∞ ∈ [0, 1] (Chung & Hulbert 1993):
//! α_m = (2ρ∞ − 1)/(ρ∞ + 1), α_f = ρ∞/(ρ∞ + 1), γ = ½ − α_m + α_f, β = ¼(1 − α_m + α_f)².
//! ρ∞ = 1 gives α_m = α_f = ½, γ = ½, β = ¼: the average-acceleration (trapezoidal) Newmark rule.
//!
//! For a nonlinear (corotational, configuration-dependent inertia) model the equation of motion
//! is enforced at t_{n+1} with an auxiliary acceleration â (the form of Arnold & Brüls 2007,
//! identical to Chung–Hulbert for linear problems, second-order accurate):
//! r(q_{n+1}, q̇_{n+1}, q̈_{n+1}) = 0,
//! (1 − α_m) â_{n+1} + α_m â_n = (1 − α_f) q̈_{n+1} + α_f q̈_n,
//! q_{n+1} = q_n + h q̇_n + h² ((½ − β) â_n + β â_{n+1}),
//! q̇_{n+1} = q̇_n + h ((1 − γ) â_n + γ â_{n+1}).
//! Newton on the increment Δq = q_{n+1} − q_n (â, q̇, q̈ follow from Δq without cancelling
//! against q_n, so tiny steps keep their accuracy), corrections scaled so that no rotation
//! changes by more than [`crate::statics::MAX_ROTATION_INCREMENT`] per iteration (the
//! corotational forces and the inertia are 2π-periodic in the nodal rotations, and an unlimited
//! first iteration can land on a spurious solution with a node turned by 2π), with the analytic
//! Jacobian
//! S = ∂r/∂q + (γ/(βh)) ∂r/∂q̇ + ((1 − α_m)/((1 − α_f) β h²)) ∂r/∂q̈ (banded LU, O(N)).
//! The step h may change every step: â_n ≈ q̈(t_n + (α_m − α_f) h), so on a change from h to h′
//! its offset is rescaled, â_n ← q̈_n + (â_n − q̈_n) h′/h, which keeps second order even when
//! h changes every step (tested). The linear model needs one solve per step (started from
//! Δq = 0, which keeps round-off independent of h ≫ T) and reuses the factorisation while h is
//! unchanged. A failed step (Newton, singular or non-finite) leaves the [`State`] unchanged.

use crate::BeamError;
use crate::assembly::{
    JacobianWeights, Kinematic, assemble, band_for, kinetic_energy, strain_energy,
};
use crate::banded::BandMatrix;
use crate::model::{BeamModel, Kinematics, NodalLoads};
use crate::node_load::NodeLoad;

/// Generalized-α integrator settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GeneralizedAlpha {
    rho_inf: f64,
    alpha_m: f64,
    alpha_f: f64,
    gamma: f64,
    beta: f64,
    max_iterations: usize,
    tolerance: f64,
}

impl GeneralizedAlpha {
    /// Chung–Hulbert parameters for `rho_inf` ρ∞ ∈ [0, 1]; Newton: 25 iterations, increment
    /// tolerance 1e-6 L. Newton converges quadratically (analytic Jacobian), so accepting after
    /// a correction δ leaves an error ≈ C δ² (measured C ≈ 2 m⁻¹ on the CL link: ≈ 1e-13 m);
    /// the cheap predictor (â extrapolated) usually needs a single correction. Tighten with
    /// [`GeneralizedAlpha::with_newton`] for convergence studies.
    pub fn new(rho_inf: f64) -> Result<Self, BeamError> {
        if !(0.0..=1.0).contains(&rho_inf) {
            return Err(BeamError::invalid("rho_inf", rho_inf, "a number in [0, 1]"));
        }
        let alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
        let alpha_f = rho_inf / (rho_inf + 1.0);
        let gamma = 0.5 - alpha_m + alpha_f;
        let beta = 0.25 * (1.0 - alpha_m + alpha_f).powi(2);
        Ok(GeneralizedAlpha {
            rho_inf,
            alpha_m,
            alpha_f,
            gamma,
            beta,
            max_iterations: 25,
            tolerance: 1e-6,
        })
    }
    /// Newton settings: at most `max_iterations` ≥ 1, converged when ‖Δq‖∞ ≤ `tolerance`·L,
    /// `tolerance` in (0, 1e-3].
    pub fn with_newton(mut self, max_iterations: usize, tolerance: f64) -> Result<Self, BeamError> {
        if max_iterations == 0 {
            return Err(BeamError::invalid(
                "max_iterations",
                max_iterations,
                "an integer ≥ 1",
            ));
        }
        if !(tolerance > 0.0 && tolerance <= 1e-3) {
            return Err(BeamError::invalid(
                "tolerance",
                tolerance,
                "a number in (0, 1e-3]",
            ));
        }
        self.max_iterations = max_iterations;
        self.tolerance = tolerance;
        Ok(self)
    }
    /// (maximum Newton iterations, tolerance \[m or rad\] on a correction) for models of length
    /// 1 m; scale the tolerance by the length.
    pub(crate) fn newton_limits(&self) -> (usize, f64) {
        (self.max_iterations, self.tolerance)
    }
    /// ρ∞.
    pub fn rho_inf(&self) -> f64 {
        self.rho_inf
    }
    /// (α_m, α_f, γ, β).
    pub fn parameters(&self) -> (f64, f64, f64, f64) {
        (self.alpha_m, self.alpha_f, self.gamma, self.beta)
    }
}

/// The dynamic state: time, displacements, velocities, accelerations (one entry per DOF).
#[derive(Debug, Clone, PartialEq)]
pub struct State {
    /// Time t \[s\].
    pub t: f64,
    /// q [m, rad].
    pub q: Vec<f64>,
    /// q̇ [m/s, rad/s].
    pub v: Vec<f64>,
    /// q̈ [m/s², rad/s²].
    pub a: Vec<f64>,
    a_aux: Vec<f64>,
    a_aux_prev: Vec<f64>,
    h_prev: Option<f64>,
    f_prev: Vec<f64>,
    /// (first global DOF of the node, force) of the last motion-dependent node load.
    node_force_prev: (usize, [f64; 3]),
    external_work: f64,
    initial_energy: f64,
}

/// Energies of a state \[J\].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Energy {
    /// Kinetic energy ½ q̇ᵀ M q̇ (beam, point masses, hub).
    pub kinetic: f64,
    /// Strain energy (elements and root spring).
    pub strain: f64,
    /// Work of the external loads since the start (trapezoidal rule).
    pub external_work: f64,
    /// Energy lost since the start: E₀ + W − T − U (damping and numerical dissipation).
    pub dissipated: f64,
}

impl State {
    /// State at time `t0` with displacements `q0` and velocities `v0` (constrained entries must
    /// be 0) under `loads`; the acceleration solves M(q₀) q̈₀ = F − f_int − f_damp − g.
    pub fn new(
        model: &BeamModel,
        q0: Vec<f64>,
        v0: Vec<f64>,
        t0: f64,
        loads: &NodalLoads,
    ) -> Result<Self, BeamError> {
        loads.check(model)?;
        let n = model.n_dofs();
        for (name, x) in [("q0", &q0), ("v0", &v0)] {
            if x.len() != n {
                return Err(BeamError::invalid(
                    format!("{name} length"),
                    x.len(),
                    format!("{n} entries (3 per node)"),
                ));
            }
            if let Some(i) = x.iter().position(|v| !v.is_finite()) {
                return Err(BeamError::invalid(
                    format!("{name}[{i}]"),
                    x[i],
                    "a finite number",
                ));
            }
            if let Some(i) = x[..model.n_fixed()].iter().position(|v| *v != 0.0) {
                return Err(BeamError::invalid(
                    format!("{name}[{i}]"),
                    x[i],
                    "0 (a constrained root DOF)",
                ));
            }
        }
        if !t0.is_finite() {
            return Err(BeamError::invalid("t0", t0, "a finite number"));
        }
        let nfix = model.n_fixed();
        let zeros = vec![0.0; n];
        let mut r = vec![0.0; n];
        let mut band = band_for(model);
        let kin = Kinematic {
            q: &q0,
            v: Some(&v0),
            a: Some(&zeros),
        };
        let w = JacobianWeights {
            stiffness: 0.0,
            velocity: 0.0,
            acceleration: 1.0,
        };
        assemble(model, kin, loads.as_slice(), &mut r, Some((&mut band, w)));
        band.factorize("mass matrix")?;
        let mut a_free: Vec<f64> = r[nfix..].iter().map(|x| -x).collect();
        band.solve_in_place(&mut a_free);
        let mut a = vec![0.0; n];
        a[nfix..].copy_from_slice(&a_free);
        let initial_energy = kinetic_energy(model, &q0, &v0) + strain_energy(model, &q0);
        Ok(State {
            t: t0,
            q: q0,
            v: v0,
            a_aux: a.clone(),
            a_aux_prev: Vec::new(),
            h_prev: None,
            a,
            f_prev: loads.as_slice().to_vec(),
            node_force_prev: (0, [0.0; 3]),
            external_work: 0.0,
            initial_energy,
        })
    }

    /// The undeformed state at rest at t = 0 under `loads`.
    pub fn at_rest(model: &BeamModel, loads: &NodalLoads) -> Result<Self, BeamError> {
        let n = model.n_dofs();
        State::new(model, vec![0.0; n], vec![0.0; n], 0.0, loads)
    }

    /// (u, v, θ) of node `i`.
    pub fn node(&self, i: usize) -> (f64, f64, f64) {
        (self.q[3 * i], self.q[3 * i + 1], self.q[3 * i + 2])
    }

    /// Energies of this state.
    pub fn energy(&self, model: &BeamModel) -> Energy {
        let kinetic = kinetic_energy(model, &self.q, &self.v);
        let strain = strain_energy(model, &self.q);
        Energy {
            kinetic,
            strain,
            external_work: self.external_work,
            dissipated: self.initial_energy + self.external_work - kinetic - strain,
        }
    }
}

/// Scratch memory reused between steps.
#[derive(Debug, Clone)]
pub struct Workspace {
    band: BandMatrix,
    r: Vec<f64>,
    q_new: Vec<f64>,
    v_new: Vec<f64>,
    a_new: Vec<f64>,
    ahat_new: Vec<f64>,
    /// â_n rescaled to the current step.
    a_aux: Vec<f64>,
    /// The step's increment Δq = q_{n+1} − q_n (the Newton unknown).
    dq_step: Vec<f64>,
    dq: Vec<f64>,
    factored_for: Option<(f64, f64)>,
    /// The predictor of the last accepted step (tried first on the next one).
    last_predictor: Predictor,
}

impl Workspace {
    /// Scratch for `model`.
    pub fn new(model: &BeamModel) -> Self {
        let n = model.n_dofs();
        Workspace {
            band: band_for(model),
            r: vec![0.0; n],
            q_new: vec![0.0; n],
            v_new: vec![0.0; n],
            a_new: vec![0.0; n],
            ahat_new: vec![0.0; n],
            a_aux: vec![0.0; n],
            dq_step: vec![0.0; n],
            dq: vec![0.0; model.n_free()],
            factored_for: None,
            last_predictor: Predictor::Extrapolated,
        }
    }
}

/// What one step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Newton iterations (linear solves) used, failed attempts included.
    pub iterations: usize,
    /// ‖Δq‖∞ of the first Newton correction of the accepted attempt (the predictor error)
    /// [m or rad].
    pub first_correction: f64,
    /// ‖Δq‖∞ of the last Newton correction [m or rad].
    pub last_correction: f64,
    /// Pieces the step was taken in: 1 when whole, more when Newton failed on it and the step
    /// was halved (recursively) and taken in halves.
    pub substeps: usize,
    /// Attempts that Newton abandoned (restarted from another predictor or halved).
    pub rejected: usize,
}

/// Most halvings of one step before the step fails: the smallest piece is h/2¹⁰.
pub const MAX_STEP_HALVINGS: u32 = 10;

/// Iterations allowed from the extrapolated predictor before Newton restarts from the velocity
/// predictor (a smooth step needs one or two; many mean the extrapolation missed, e.g. after a
/// step load or with h far above the periods of the fast modes).
const EXTRAPOLATED_ITERATIONS: usize = 8;

/// Where Newton starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Predictor {
    /// â_{n+1} extrapolated linearly from â_{n−1}, â_n (â_n on the first step): close for a
    /// smooth motion, so usually a single correction.
    Extrapolated,
    /// Δq = h q̇_n (zero acceleration): never far off, whatever the fast modes did.
    Velocity,
    /// Δq = 0: the linear model's start (its single solve is exact from any start, and the
    /// extrapolated Δq, O(h²|â|), would leave a round-off error ≈ ε κ h²|â| when h ≫ T).
    Rest,
}

/// True for failures that a smaller step can cure.
fn recoverable(e: &BeamError) -> bool {
    matches!(
        e,
        BeamError::NotConverged { .. } | BeamError::NonFinite { .. } | BeamError::Singular { .. }
    )
}

impl GeneralizedAlpha {
    /// Advances `state` by `h` \[s\] (> 0, finite) with the loads `loads` acting at t + h.
    pub fn step(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        h: f64,
        loads: &NodalLoads,
    ) -> Result<StepReport, BeamError> {
        self.step_with(model, state, ws, h, loads, None)
    }

    /// Advances `state` by `h` \[s\] with the dead loads `loads` acting at t + h and, if given,
    /// the motion-dependent `node_load` treated implicitly (in the residual and the iteration
    /// matrix, see [`crate::node_load`]).
    ///
    /// Newton starts from the extrapolated predictor; if it does not converge within a few
    /// iterations it restarts from Δq = h q̇_n; if that fails too (no convergence, a singular
    /// iteration matrix or a non-finite state), the step is taken as two halves, each with the
    /// same strategy, down to h/2¹⁰ ([`MAX_STEP_HALVINGS`]). Within a split step the dead
    /// loads are interpolated linearly from those of the previous step, and the node load is
    /// evaluated at each piece's end time. A step that fails even so returns
    /// [`BeamError::StepFailed`] and leaves `state` unchanged.
    pub fn step_with<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        h: f64,
        loads: &NodalLoads,
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
    ) -> Result<StepReport, BeamError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(BeamError::invalid("time step", h, "a finite number > 0"));
        }
        loads.check(model)?;
        if let Some(nl) = node_load.as_deref()
            && nl.node() > model.tip_node()
        {
            return Err(BeamError::invalid(
                "node load node",
                nl.node(),
                format!("a node index from 0 to {} (the tip)", model.tip_node()),
            ));
        }
        if ws.r.len() != model.n_dofs() {
            *ws = Workspace::new(model);
        }
        let mut report = StepReport {
            substeps: 1,
            ..StepReport::default()
        };
        match self.attempt(
            model,
            state,
            ws,
            h,
            loads,
            node_load.as_deref_mut(),
            &mut report,
        ) {
            Ok(()) => return Ok(report),
            Err(e) if !recoverable(&e) => return Err(e),
            Err(_) => {}
        }
        let saved = state.clone();
        let t_end = state.t + h;
        let start = NodalLoads::from_values(state.f_prev.clone());
        report.substeps = 0;
        let split = self.take_in_halves(
            model,
            state,
            ws,
            (h, 1),
            (&start, loads),
            node_load,
            &mut report,
        );
        match split {
            Ok(()) => {
                // the pieces' times add up to t + h only up to round-off
                state.t = t_end;
                Ok(report)
            }
            Err(cause) => {
                *state = saved;
                Err(BeamError::StepFailed {
                    t: state.t,
                    h,
                    halvings: MAX_STEP_HALVINGS,
                    cause: Box::new(cause),
                })
            }
        }
    }

    /// Takes a step of `h` (at halving depth `depth`) as two halves, each halved again on a
    /// recoverable failure; dead loads linear from `start` to `end` over the step.
    #[allow(clippy::too_many_arguments)]
    fn take_in_halves<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        (h, depth): (f64, u32),
        (start, end): (&NodalLoads, &NodalLoads),
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
        report: &mut StepReport,
    ) -> Result<(), BeamError> {
        let half = 0.5 * h;
        let middle = start.lerp(end, 0.5);
        for (from, to) in [(start, &middle), (&middle, end)] {
            match self.attempt(model, state, ws, half, to, node_load.as_deref_mut(), report) {
                Ok(()) => report.substeps += 1,
                Err(e) if recoverable(&e) && depth < MAX_STEP_HALVINGS => self.take_in_halves(
                    model,
                    state,
                    ws,
                    (half, depth + 1),
                    (from, to),
                    node_load.as_deref_mut(),
                    report,
                )?,
                Err(e) => return Err(e),
            }
        }
        Ok(())
    }

    /// One try at the whole step `h`: Newton from the first predictor, then (nonlinear model)
    /// once more from the velocity predictor. On success `state` is advanced.
    #[allow(clippy::too_many_arguments)]
    fn attempt<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        h: f64,
        loads: &NodalLoads,
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
        report: &mut StepReport,
    ) -> Result<(), BeamError> {
        // The predictor that worked on the last step goes first.
        let extrapolated = (
            Predictor::Extrapolated,
            self.max_iterations.min(EXTRAPOLATED_ITERATIONS),
        );
        let velocity = (Predictor::Velocity, self.max_iterations);
        let plan = if model.kinematics() == Kinematics::Linear {
            [Some((Predictor::Rest, self.max_iterations)), None]
        } else if ws.last_predictor == Predictor::Velocity {
            [Some(velocity), Some(extrapolated)]
        } else {
            [Some(extrapolated), Some(velocity)]
        };
        let mut failure = None;
        for (predictor, max_iterations) in plan.into_iter().flatten() {
            let newton = NewtonStep {
                h,
                predictor,
                max_iterations,
            };
            match self.newton(model, state, ws, loads, node_load.as_deref_mut(), newton) {
                Ok((iterations, first, last)) => {
                    ws.last_predictor = predictor;
                    report.iterations += iterations;
                    report.first_correction = first;
                    report.last_correction = last;
                    return Ok(());
                }
                Err((iterations, e)) => {
                    report.iterations += iterations;
                    report.rejected += 1;
                    if !recoverable(&e) {
                        return Err(e);
                    }
                    failure = Some(e);
                }
            }
        }
        Err(failure.expect("the plan has at least one predictor"))
    }

    /// Newton iterations for one step; on success the state is advanced and (iterations, first
    /// correction, last correction) returned; on failure the state is unchanged and the
    /// iterations spent are returned with the error.
    fn newton<'l>(
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
        let (am, af, g, b) = (self.alpha_m, self.alpha_f, self.gamma, self.beta);
        let nfix = model.n_fixed();
        let n = model.n_dofs();
        let linear = model.kinematics() == Kinematics::Linear;
        // A motion-dependent load makes even the linear model nonlinear: iterate, refactor.
        let single_solve = linear && node_load.is_none();
        let t_new = state.t + h;
        let weights = JacobianWeights {
            stiffness: 1.0,
            velocity: g / (b * h),
            acceleration: (1.0 - am) / ((1.0 - af) * b * h * h),
        };
        // `state` is written only when the step is accepted: a failed step leaves it unchanged.
        // â_n approximates q̈(t_n + (α_m − α_f) h): rescale its offset from q̈_n when h changes
        // (into the workspace).
        ws.a_aux.copy_from_slice(&state.a_aux);
        if let Some(hp) = state.h_prev
            && hp != h
        {
            let r = h / hp;
            for (ah, a) in ws.a_aux.iter_mut().zip(&state.a) {
                *ah = a + (*ah - a) * r;
            }
        }
        let ratio = match state.h_prev {
            Some(hp) if state.a_aux_prev.len() == n => h / hp,
            _ => 0.0,
        };
        for i in 0..n {
            ws.dq_step[i] = match predictor {
                Predictor::Rest => 0.0,
                Predictor::Velocity => h * state.v[i],
                Predictor::Extrapolated => {
                    let ahat = if ratio > 0.0 {
                        ws.a_aux[i] + ratio * (ws.a_aux[i] - state.a_aux_prev[i])
                    } else {
                        ws.a_aux[i]
                    };
                    h * state.v[i] + h * h * ((0.5 - b) * ws.a_aux[i] + b * ahat)
                }
            };
            ws.q_new[i] = state.q[i] + ws.dq_step[i];
        }
        let tol = self.tolerance * model.length();
        let mut iterations = 0;
        let mut last = f64::INFINITY;
        let mut first = f64::INFINITY;
        loop {
            // Newmark relations: â, q̇, q̈ from the increment Δq = q_{n+1} − q_n (not from
            // q_{n+1} − q_n, which cancels to ε|q| and leaves ε|q|/(βh²) of noise in â at tiny h).
            for i in 0..n {
                let ahat = (ws.dq_step[i] - h * state.v[i] - h * h * (0.5 - b) * ws.a_aux[i])
                    / (b * h * h);
                ws.ahat_new[i] = ahat;
                ws.v_new[i] = state.v[i] + h * ((1.0 - g) * ws.a_aux[i] + g * ahat);
                ws.a_new[i] = ((1.0 - am) * ahat + am * ws.a_aux[i] - af * state.a[i]) / (1.0 - af);
            }
            if iterations > 0 && (last <= tol || (single_solve && iterations == 1)) {
                break;
            }
            let kin = Kinematic {
                q: &ws.q_new,
                v: Some(&ws.v_new),
                a: Some(&ws.a_new),
            };
            if iterations >= max_iterations {
                assemble(model, kin, loads.as_slice(), &mut ws.r, None);
                node_residual(node_load.as_deref_mut(), t_new, ws, nfix, None);
                let residual = ws.r[nfix..].iter().fold(0.0f64, |m, x| m.max(x.abs()));
                return Err((
                    iterations,
                    BeamError::NotConverged {
                        solver: "generalized-α step".into(),
                        load_level: 1.0,
                        iterations,
                        residual,
                    },
                ));
            }
            let reuse = single_solve && ws.factored_for == Some((h, self.rho_inf));
            if reuse {
                assemble(model, kin, loads.as_slice(), &mut ws.r, None);
            } else {
                assemble(
                    model,
                    kin,
                    loads.as_slice(),
                    &mut ws.r,
                    Some((&mut ws.band, weights)),
                );
                node_residual(node_load.as_deref_mut(), t_new, ws, nfix, Some(weights));
                ws.factored_for = None;
                if let Err(e) = ws.band.factorize("generalized-α iteration matrix") {
                    return Err((iterations, e));
                }
                if single_solve {
                    ws.factored_for = Some((h, self.rho_inf));
                }
            }
            for (d, ri) in ws.dq.iter_mut().zip(&ws.r[nfix..]) {
                *d = -ri;
            }
            ws.band.solve_in_place(&mut ws.dq);
            let s = if linear {
                1.0
            } else {
                crate::statics::rotation_limiter(&ws.dq, nfix)
            };
            last = 0.0;
            for (i, d) in (nfix..n).zip(&ws.dq) {
                ws.dq_step[i] += s * d;
                ws.q_new[i] = state.q[i] + ws.dq_step[i];
                last = last.max((s * d).abs());
            }
            if !last.is_finite() {
                return Err((
                    iterations,
                    BeamError::NonFinite {
                        what: "generalized-α displacement".into(),
                    },
                ));
            }
            if iterations == 0 {
                first = last;
            }
            iterations += 1;
        }
        // A converged step that turns a node by more than the Newton limiter allows in one
        // iteration has not resolved the rotation: it may be a spurious root (a node turned by
        // 2π, or onto another branch of the 2π-periodic element); take it in smaller pieces.
        if !linear
            && let Some(i) = (nfix..n)
                .filter(|i| i % 3 == 2)
                .find(|&i| ws.dq_step[i].abs() > crate::statics::MAX_ROTATION_INCREMENT)
        {
            return Err((
                iterations,
                BeamError::NotConverged {
                    solver: format!(
                        "generalized-α step (node {} turned by {:.3} rad in one step)",
                        i / 3,
                        ws.dq_step[i]
                    ),
                    load_level: 1.0,
                    iterations,
                    residual: 0.0,
                },
            ));
        }
        // A step so small or so large that h² under- or overflows gives inf/NaN in â, q̇, q̈.
        if [&ws.q_new, &ws.v_new, &ws.a_new, &ws.ahat_new]
            .iter()
            .any(|x| x.iter().any(|v| !v.is_finite()))
        {
            return Err((
                iterations,
                BeamError::NonFinite {
                    what: "generalized-α state".into(),
                },
            ));
        }
        // The motion-dependent load at the accepted state (for the work done on the beam).
        let node_force = node_load.map(|nl| {
            let k = 3 * nl.node();
            let f = nl.evaluate(t_new, node_dofs(&ws.q_new, k), node_dofs(&ws.v_new, k));
            (k, f.force)
        });
        if let Some((_, f)) = node_force
            && !f.iter().all(|x| x.is_finite())
        {
            return Err((
                iterations,
                BeamError::NonFinite {
                    what: "node load".into(),
                },
            ));
        }
        // Accept.
        let f = loads.as_slice();
        let mut work = 0.0;
        for i in 0..n {
            work += 0.5 * (state.f_prev[i] + f[i]) * ws.dq_step[i];
        }
        let (k_prev, f_prev_node) = state.node_force_prev;
        let (k_new, f_new_node) = node_force.unwrap_or((k_prev, [0.0; 3]));
        for d in 0..3 {
            work += 0.5 * f_prev_node[d] * ws.dq_step[k_prev + d];
            work += 0.5 * f_new_node[d] * ws.dq_step[k_new + d];
        }
        state.node_force_prev = (k_new, f_new_node);
        state.external_work += work;
        state.f_prev.copy_from_slice(f);
        state.q.copy_from_slice(&ws.q_new);
        state.v.copy_from_slice(&ws.v_new);
        state.a.copy_from_slice(&ws.a_new);
        // â_{n−1} ← â_n (rescaled to h), â_n ← â_{n+1}
        state.a_aux_prev.clear();
        state.a_aux_prev.extend_from_slice(&ws.a_aux);
        state.a_aux.copy_from_slice(&ws.ahat_new);
        state.h_prev = Some(h);
        state.t = t_new;
        Ok((iterations, first, last))
    }
}

/// One Newton solve's settings.
#[derive(Debug, Clone, Copy)]
struct NewtonStep {
    h: f64,
    predictor: Predictor,
    max_iterations: usize,
}

/// (x[k], x[k + 1], x[k + 2]).
fn node_dofs(x: &[f64], k: usize) -> [f64; 3] {
    [x[k], x[k + 1], x[k + 2]]
}

/// Adds the motion-dependent node load at the current iterate to the residual (r −= F) and, if
/// `weights` is given, −(c_q ∂F/∂q + c_v ∂F/∂q̇) to the iteration matrix (free DOFs only).
fn node_residual<'l>(
    node_load: Option<&mut (dyn NodeLoad + 'l)>,
    t: f64,
    ws: &mut Workspace,
    nfix: usize,
    weights: Option<JacobianWeights>,
) {
    let Some(nl) = node_load else {
        return;
    };
    let k = 3 * nl.node();
    let f = nl.evaluate(t, node_dofs(&ws.q_new, k), node_dofs(&ws.v_new, k));
    for i in 0..3 {
        ws.r[k + i] -= f.force[i];
    }
    if let Some(w) = weights {
        for i in 0..3 {
            for j in 0..3 {
                let (gi, gj) = (k + i, k + j);
                if gi >= nfix && gj >= nfix {
                    ws.band.add(
                        gi - nfix,
                        gj - nfix,
                        -(w.stiffness * f.d_dq[i][j] + w.velocity * f.d_dv[i][j]),
                    );
                }
            }
        }
    }
}
