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
//!
//! **One file, one concept** (about 1 500 lines): the generalized-α integrator — its parameters,
//! state and workspace, the predictor, the Newton loop and its stopping test, and the step with a
//! moving root, which share the step's private bookkeeping.

use crate::BeamError;
use crate::assembly::{JacobianWeights, Kinematic, assemble, band_for, kinetic_and_strain_energy};
use crate::banded::BandMatrix;
use crate::counters::StepCounters;
use crate::model::{BeamModel, Kinematics, NodalLoads};
use crate::node_load::NodeLoad;

/// A prescribed root rotation: the hub's (θ \[rad\], θ̇ [rad/s], θ̈ [rad/s²]) at a time \[s\]
/// ([`GeneralizedAlpha::step_with_root`]).
type RootPath<'a> = &'a dyn Fn(f64) -> [f64; 3];

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
    energy_conserving: bool,
    newton_method: NewtonMethod,
}

/// How a generalized-α step iterates (the ANCF and corotational models, and the linear one
/// under a motion-dependent node load; the linear model alone needs one solve).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NewtonMethod {
    /// [`NewtonMethod::Modified`] for the ANCF model (constant mass; its matrix is kept across
    /// steps), [`NewtonMethod::Full`] for the others. The default.
    #[default]
    Auto,
    /// A fresh iteration matrix (analytic Jacobian) in every iteration: quadratic
    /// convergence; the increment test ‖Δq‖∞ ≤ tol·L. The corotational default: its Newton
    /// error is then far below the tolerance, which the energy of long ρ∞ = 1 and 0.8 runs
    /// needs (`stress.rs`: the energy never above E₀ by more than 1e-12 E₀).
    Full,
    /// The iteration matrix kept while the corrections contract by [`MODIFIED_NEWTON_RATE`]
    /// per iteration and the iterations left can reach the tolerance at the rate measured;
    /// the same increment test. Corotational: half the instructions of full Newton on the
    /// step-load transient of [`crate::canonical::polypropylene_cantilever`] at 32 elements (1.08
    /// instead of 3.03 factorisations per step) and within 0.5 tol·L of the full Newton
    /// solution, but its Newton error (up to ≈ 0.3 tol per step) shows in the energy of long
    /// runs at the 1e-8 level.
    Modified,
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
            energy_conserving: false,
            newton_method: NewtonMethod::Auto,
        })
    }

    /// The energy-conserving midpoint step (ρ∞ = 1, no numerical dissipation) for the ANCF and
    /// linear models, see [`crate::energy_conserving`]: undamped free motion keeps
    /// T + U to the Newton tolerance for any h, second order in h.
    ///
    /// Newton tolerance 1e-9 L (tighter than generalized-α's 1e-6 L: the energy is kept to the
    /// Newton tolerance; measured |ΔE/E| ≤ 1.5e-9 over 10 s of the CL link's large free vibration
    /// at h = 5e-4 s, 1.2e-8 at 1e-8 L, 1.5e-6 at 1e-6 L, 4e-11 at 1e-10 L); change it with
    /// [`GeneralizedAlpha::with_newton`].
    pub fn energy_conserving() -> Self {
        let mut ga = GeneralizedAlpha::new(1.0).expect("ρ∞ = 1 is valid");
        ga.energy_conserving = true;
        ga.tolerance = 1e-9;
        ga
    }

    /// True for the energy-conserving step ([`GeneralizedAlpha::energy_conserving`]).
    pub fn is_energy_conserving(&self) -> bool {
        self.energy_conserving
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
    /// The Newton variant of the generalized-α step (not of the energy-conserving one).
    pub fn with_newton_method(mut self, method: NewtonMethod) -> Self {
        self.newton_method = method;
        self
    }
    /// The Newton variant.
    pub fn newton_method(&self) -> NewtonMethod {
        self.newton_method
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
/// [`Clone::clone_from`] copies into the target's buffers (no allocation once they are sized):
/// the cheap way to keep a state for taking a step again.
#[derive(Debug, PartialEq)]
pub struct State {
    /// Time t \[s\].
    pub t: f64,
    /// q [m, rad].
    pub q: Vec<f64>,
    /// q̇ [m/s, rad/s].
    pub v: Vec<f64>,
    /// q̈ [m/s², rad/s²].
    pub a: Vec<f64>,
    pub(crate) a_aux: Vec<f64>,
    pub(crate) a_aux_prev: Vec<f64>,
    pub(crate) h_prev: Option<f64>,
    pub(crate) f_prev: Vec<f64>,
    /// (node, force in (u, v, θ) terms) of the last motion-dependent node load.
    pub(crate) node_force_prev: (usize, [f64; 3]),
    pub(crate) external_work: f64,
    pub(crate) initial_energy: f64,
    /// 3, or 4 for ANCF.
    pub(crate) dofs_per_node: usize,
    /// Element (and root spring) strain energies at q (energy-conserving step; empty until
    /// first needed).
    pub(crate) element_energies: Vec<f64>,
}

impl Clone for State {
    fn clone(&self) -> Self {
        State {
            t: self.t,
            q: self.q.clone(),
            v: self.v.clone(),
            a: self.a.clone(),
            a_aux: self.a_aux.clone(),
            a_aux_prev: self.a_aux_prev.clone(),
            h_prev: self.h_prev,
            f_prev: self.f_prev.clone(),
            node_force_prev: self.node_force_prev,
            external_work: self.external_work,
            initial_energy: self.initial_energy,
            dofs_per_node: self.dofs_per_node,
            element_energies: self.element_energies.clone(),
        }
    }

    fn clone_from(&mut self, source: &Self) {
        self.t = source.t;
        self.q.clone_from(&source.q);
        self.v.clone_from(&source.v);
        self.a.clone_from(&source.a);
        self.a_aux.clone_from(&source.a_aux);
        self.a_aux_prev.clone_from(&source.a_aux_prev);
        self.h_prev = source.h_prev;
        self.f_prev.clone_from(&source.f_prev);
        self.node_force_prev = source.node_force_prev;
        self.external_work = source.external_work;
        self.initial_energy = source.initial_energy;
        self.dofs_per_node = source.dofs_per_node;
        self.element_energies.clone_from(&source.element_energies);
    }
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
                    format!("{n} entries ({} per node)", model.dofs_per_node()),
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
        State::with_free_accelerations(model, t0, (q0, v0, vec![0.0; n]), loads)
    }

    /// The undeformed link in rigid rotation about its root at t = `t0` \[s\]: every node turned
    /// by `angle` \[rad\] about z, moving at `rate` [rad/s] (node at x: u = x (cos θ − 1),
    /// v = x sin θ, θ; u̇ = −x sin θ θ̇, v̇ = x cos θ θ̇), the root's acceleration `accel`
    /// [rad/s²] when it is prescribed (a clamped root: the rotating clamp of
    /// [`GeneralizedAlpha::step_with_root`]; the root's angle, rate and acceleration are then
    /// those of the hub) and the free accelerations from M q̈ = F − f_int − f_in (a hub root:
    /// its angle is free, `accel` unused). Corotational elements only (a linear beam has
    /// strain in a rigid rotation).
    pub fn in_rigid_rotation(
        model: &BeamModel,
        [angle, rate, accel]: [f64; 3],
        t0: f64,
        loads: &NodalLoads,
    ) -> Result<Self, BeamError> {
        if model.kinematics() != Kinematics::Corotational {
            return Err(BeamError::invalid(
                "kinematics",
                format!("{:?}", model.kinematics()),
                "corotational (a link turned through a large angle)",
            ));
        }
        for (name, x) in [
            ("angle", angle),
            ("rate", rate),
            ("accel", accel),
            ("t0", t0),
        ] {
            if !x.is_finite() {
                return Err(BeamError::invalid(name, x, "a finite number"));
            }
        }
        loads.check(model)?;
        let n = model.n_dofs();
        let nfix = model.n_fixed();
        let (sin, cos) = angle.sin_cos();
        let mut q = vec![0.0; n];
        let mut v = vec![0.0; n];
        let mut a = vec![0.0; n];
        for i in 0..model.n_nodes() {
            let x = model.node_x(i);
            q[3 * i..3 * i + 3].copy_from_slice(&[x * (cos - 1.0), x * sin, angle]);
            v[3 * i..3 * i + 3].copy_from_slice(&[-x * sin * rate, x * cos * rate, rate]);
        }
        if nfix == 3 {
            a[2] = accel;
        }
        State::with_free_accelerations(model, t0, (q, v, a), loads)
    }

    /// The link in steady rotation about its root at t = `t0` \[s\]: turned by `angle` \[rad\]
    /// at the constant `rate` [rad/s] and stretched by its centrifugal tension, so that a
    /// steady start does not ring axially. The tension of a bar of mass per length ρA with
    /// point masses m_j at x_j, N(x) = ω² [ρA (L² − x²)/2 + Σ_{x_j ≥ x} m_j x_j], stretches it by
    /// u(x) = ∫₀ˣ N/EA (the elements' axial equilibrium to O(ω² h²); what is left rings at the
    /// ω⁴/ω_axial² level). Corotational elements only, as [`State::in_rigid_rotation`].
    pub fn in_steady_rotation(
        model: &BeamModel,
        [angle, rate]: [f64; 2],
        t0: f64,
        loads: &NodalLoads,
    ) -> Result<Self, BeamError> {
        let mut state = State::in_rigid_rotation(model, [angle, rate, 0.0], t0, loads)?;
        let section = model.section();
        let (rho_a, ea, l) = (section.rho_a(), section.ea(), model.length());
        let w2 = rate * rate;
        let tension = |x: f64| {
            let points: f64 = model
                .spec()
                .point_masses
                .iter()
                .map(|pm| (pm.node, pm.mass))
                .filter(|(node, _)| model.node_x(*node) >= x)
                .map(|(node, m)| m * model.node_x(node))
                .sum();
            w2 * (0.5 * rho_a * (l * l - x * x) + points)
        };
        let (sin, cos) = angle.sin_cos();
        let mut stretch = 0.0;
        for i in 0..model.n_nodes() {
            if i > 0 {
                // Simpson over the element
                let (a, b) = (model.node_x(i - 1), model.node_x(i));
                let mid = tension(0.5 * (a + b));
                stretch += (b - a) / 6.0 * (tension(a) + 4.0 * mid + tension(b)) / ea;
            }
            let r = model.node_x(i) + stretch;
            let x = model.node_x(i);
            let q = &mut state.q[3 * i..3 * i + 2];
            q[0] = r * cos - x;
            q[1] = r * sin;
            let v = &mut state.v[3 * i..3 * i + 2];
            v[0] = -r * sin * rate;
            v[1] = r * cos * rate;
        }
        let nfix = model.n_fixed();
        let mut a = state.a.clone();
        a[nfix..].fill(0.0);
        State::with_free_accelerations(model, t0, (state.q, state.v, a), loads)
    }

    /// The state at `t0` \[s\] with displacements and velocities `q`, `v` and the constrained
    /// entries of `a` given (prescribed root accelerations; the free entries are overwritten):
    /// the free accelerations solve M(q) q̈ = F − f_int − f_damp − g with the constrained
    /// ones moving the root, and the energy is counted from this state.
    fn with_free_accelerations(
        model: &BeamModel,
        t0: f64,
        (q, v, mut a): (Vec<f64>, Vec<f64>, Vec<f64>),
        loads: &NodalLoads,
    ) -> Result<Self, BeamError> {
        let nfix = model.n_fixed();
        a[nfix..].fill(0.0);
        let mut r = vec![0.0; model.n_dofs()];
        let mut band = band_for(model);
        let kin = Kinematic {
            q: &q,
            v: Some(&v),
            a: Some(&a),
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
        a[nfix..].copy_from_slice(&a_free);
        let (kinetic, strain) = kinetic_and_strain_energy(model, &q, &v);
        let initial_energy = kinetic + strain;
        Ok(State {
            t: t0,
            q,
            v,
            a_aux: a.clone(),
            a_aux_prev: Vec::new(),
            h_prev: None,
            a,
            f_prev: loads.as_slice().to_vec(),
            node_force_prev: (0, [0.0; 3]),
            external_work: 0.0,
            initial_energy,
            dofs_per_node: model.dofs_per_node(),
            element_energies: Vec::new(),
        })
    }

    /// The undeformed state at rest at t = 0 under `loads`.
    pub fn at_rest(model: &BeamModel, loads: &NodalLoads) -> Result<Self, BeamError> {
        let n = model.n_dofs();
        State::new(model, vec![0.0; n], vec![0.0; n], 0.0, loads)
    }

    /// (u, v, θ) of node `i` [m, m, rad] (ANCF: θ = atan2(r′ᵧ, r′ₓ)).
    pub fn node(&self, i: usize) -> (f64, f64, f64) {
        let [u, v, t] = node_values(self.dofs_per_node, &self.q, i);
        (u, v, t)
    }

    /// (u̇, v̇, θ̇) of node `i` [m/s, m/s, rad/s].
    pub fn node_velocity(&self, i: usize) -> [f64; 3] {
        if self.dofs_per_node == 4 {
            crate::assembly_ancf::node_uvt_rate(&self.q, &self.v, i)
        } else {
            node_dofs(&self.v, 3 * i)
        }
    }

    /// (ü, v̈, θ̈) of node `i` [m/s², m/s², rad/s²].
    pub fn node_acceleration(&self, i: usize) -> [f64; 3] {
        if self.dofs_per_node == 4 {
            crate::assembly_ancf::node_uvt_acceleration(&self.q, &self.v, &self.a, i)
        } else {
            node_dofs(&self.a, 3 * i)
        }
    }

    /// Energies of this state.
    pub fn energy(&self, model: &BeamModel) -> Energy {
        let (kinetic, strain) = kinetic_and_strain_energy(model, &self.q, &self.v);
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
    pub(crate) band: BandMatrix,
    pub(crate) r: Vec<f64>,
    pub(crate) q_new: Vec<f64>,
    pub(crate) v_new: Vec<f64>,
    pub(crate) a_new: Vec<f64>,
    pub(crate) ahat_new: Vec<f64>,
    /// â_n rescaled to the current step.
    pub(crate) a_aux: Vec<f64>,
    /// The step's increment Δq = q_{n+1} − q_n (the Newton unknown).
    pub(crate) dq_step: Vec<f64>,
    pub(crate) dq: Vec<f64>,
    /// (h, ρ∞, energy-conserving) of the factorisation held in `band`, if it may be reused.
    pub(crate) factored_for: Option<(f64, f64, bool)>,
    /// Element energies at q₁ (energy-conserving step).
    pub(crate) u1: Vec<f64>,
    /// Element energies at q₀ (energy-conserving step).
    pub(crate) u0: Vec<f64>,
    /// The dead loads averaged over the step (energy-conserving step).
    pub(crate) f_avg: Vec<f64>,
    /// Midpoint displacements (energy-conserving step).
    pub(crate) q_mid: Vec<f64>,
    /// The predictor of the last accepted step (tried first on the next one).
    pub(crate) last_predictor: Predictor,
    /// Work done so far (see [`StepCounters`]).
    pub(crate) counters: StepCounters,
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
            u1: vec![0.0; model.n_nodes()],
            u0: vec![0.0; model.n_nodes()],
            f_avg: vec![0.0; 3 * model.n_nodes()],
            q_mid: vec![0.0; n],
            last_predictor: Predictor::Extrapolated,
            counters: StepCounters::default(),
        }
    }

    /// The work counted since this workspace was made or its counters reset.
    pub fn counters(&self) -> StepCounters {
        self.counters
    }

    /// Sets the counters to zero.
    pub fn reset_counters(&mut self) {
        self.counters = StepCounters::default();
    }

    /// What this workspace carries from one step into the next (besides scratch space).
    pub fn memory(&self) -> StepMemory {
        StepMemory {
            predictor: self.last_predictor,
        }
    }

    /// Puts back a [`Workspace::memory`] (kept with a [`State`] to take a step again from that
    /// state as it was first taken) and drops any iteration matrix kept for reuse (it may be
    /// the abandoned step's): with the state restored, the step starts as the first try did
    /// (bit for bit for the models that build a fresh matrix every step, the corotational and
    /// the nonlinear ones under full Newton).
    pub fn restore_memory(&mut self, memory: StepMemory) {
        self.last_predictor = memory.predictor;
        self.factored_for = None;
    }
}

/// What a [`Workspace`] carries from one step into the next: the Newton predictor that
/// worked on the last step (tried first on the next).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepMemory {
    predictor: Predictor,
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

/// Modified Newton (ANCF, corotational, and the linear model with a motion-dependent node
/// load): the iteration matrix is rebuilt when a correction is larger than
/// this fraction of the previous one (slow linear contraction), and after a failed attempt.
pub const MODIFIED_NEWTON_RATE: f64 = 0.25;

/// Most halvings of one step before the step fails: the smallest piece is h/2¹⁰.
pub const MAX_STEP_HALVINGS: u32 = 10;

/// Iterations allowed from the extrapolated predictor before Newton restarts from the velocity
/// predictor (a smooth step needs one or two; many mean the extrapolation missed, e.g. after a
/// step load or with h far above the periods of the fast modes).
const EXTRAPOLATED_ITERATIONS: usize = 8;

/// Where Newton starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Predictor {
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
pub(crate) fn recoverable(e: &BeamError) -> bool {
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
        node_load: Option<&mut (dyn NodeLoad + 'l)>,
    ) -> Result<StepReport, BeamError> {
        self.step_inner(model, state, ws, h, (loads, None), node_load)
    }

    /// [`GeneralizedAlpha::step_with`] for a beam clamped to a hub whose rotation is
    /// prescribed (a rotating clamp, as in [`crate::rotating_clamp`]): `root(t)` gives the hub's
    /// angle θ \[rad\], rate θ̇ [rad/s] and acceleration θ̈ [rad/s²] at time t, and the root node
    /// is held at (u, v, θ) = (0, 0, θ(t)) with rates (0, 0, θ̇(t)) and accelerations
    /// (0, 0, θ̈(t)) at the end of the step (and of each piece of a split step). The model's root
    /// must be clamped and its elements corotational (large rotation of the hub); the torque
    /// the hub applies is [`root_reaction`]'s moment.
    #[allow(clippy::too_many_arguments)]
    pub fn step_with_root<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        h: f64,
        loads: &NodalLoads,
        node_load: Option<&mut (dyn NodeLoad + 'l)>,
        root: &dyn Fn(f64) -> [f64; 3],
    ) -> Result<StepReport, BeamError> {
        check_rotating_clamp(model)?;
        if self.energy_conserving {
            return Err(BeamError::invalid(
                "integrator",
                "energy-conserving",
                "generalized-α (the energy-conserving step has no prescribed root)",
            ));
        }
        self.step_inner(model, state, ws, h, (loads, Some(root)), node_load)
    }

    fn step_inner<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        h: f64,
        (loads, root): (&NodalLoads, Option<RootPath<'_>>),
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
        if self.energy_conserving && model.kinematics() == Kinematics::Corotational {
            return Err(BeamError::invalid(
                "kinematics",
                "corotational",
                "ancf or linear for the energy-conserving step (its mass must be constant)",
            ));
        }
        if ws.r.len() != model.n_dofs() || ws.f_avg.len() != 3 * model.n_nodes() {
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
            (loads, root),
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
            (&start, loads, root),
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
        (start, end, root): (&NodalLoads, &NodalLoads, Option<RootPath<'_>>),
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
        report: &mut StepReport,
    ) -> Result<(), BeamError> {
        let half = 0.5 * h;
        let middle = start.lerp(end, 0.5);
        for (from, to) in [(start, &middle), (&middle, end)] {
            match self.attempt(
                model,
                state,
                ws,
                half,
                (to, root),
                node_load.as_deref_mut(),
                report,
            ) {
                Ok(()) => report.substeps += 1,
                Err(e) if recoverable(&e) && depth < MAX_STEP_HALVINGS => self.take_in_halves(
                    model,
                    state,
                    ws,
                    (half, depth + 1),
                    (from, to, root),
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
        (loads, root): (&NodalLoads, Option<RootPath<'_>>),
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
        report: &mut StepReport,
    ) -> Result<(), BeamError> {
        // The predictor that worked on the last step goes first. (Going back to the
        // extrapolated one after the velocity one took over was measured to cost more: on the
        // step load of canonical::polypropylene_cantilever at 16 elements 4.92 against 4.83
        // iterations and 1.11 against 0.87 factorisations per step, ANCF; full Newton 3.31
        // against 3.03 iterations.)
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
            match self.newton(
                model,
                state,
                ws,
                (loads, root),
                node_load.as_deref_mut(),
                newton,
            ) {
                Ok((iterations, first, last)) => {
                    ws.last_predictor = predictor;
                    report.iterations += iterations;
                    report.first_correction = first;
                    report.last_correction = last;
                    return Ok(());
                }
                Err((iterations, e)) => {
                    // never reuse an iteration matrix across a failure
                    if model.kinematics() != Kinematics::Linear {
                        ws.factored_for = None;
                    }
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
    ///
    /// On an x86-64 processor with AVX2 the loop (the Newmark relations, the corrections) runs
    /// compiled for it: the same operations in the same order without fused multiply-adds,
    /// so the same results bit for bit.
    fn newton<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        (loads, root): (&NodalLoads, Option<RootPath<'_>>),
        node_load: Option<&mut (dyn NodeLoad + 'l)>,
        step: NewtonStep,
    ) -> Result<(usize, f64, f64), (usize, BeamError)> {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the processor has AVX2 (checked just above).
            return unsafe { self.newton_avx2(model, state, ws, (loads, root), node_load, step) };
        }
        self.newton_portable(model, state, ws, (loads, root), node_load, step)
    }

    /// [`GeneralizedAlpha::newton`] compiled for AVX2.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn newton_avx2<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        (loads, root): (&NodalLoads, Option<RootPath<'_>>),
        node_load: Option<&mut (dyn NodeLoad + 'l)>,
        step: NewtonStep,
    ) -> Result<(usize, f64, f64), (usize, BeamError)> {
        self.newton_portable(model, state, ws, (loads, root), node_load, step)
    }

    /// [`GeneralizedAlpha::newton`] for any processor.
    #[inline(always)]
    fn newton_portable<'l>(
        &self,
        model: &BeamModel,
        state: &mut State,
        ws: &mut Workspace,
        (loads, root): (&NodalLoads, Option<RootPath<'_>>),
        mut node_load: Option<&mut (dyn NodeLoad + 'l)>,
        step: NewtonStep,
    ) -> Result<(usize, f64, f64), (usize, BeamError)> {
        if self.energy_conserving {
            return self.newton_energy_conserving(model, state, ws, loads, node_load, step);
        }
        let NewtonStep {
            h,
            predictor,
            max_iterations,
        } = step;
        let (am, af, g, b) = (self.alpha_m, self.alpha_f, self.gamma, self.beta);
        let nfix = model.n_fixed();
        let n = model.n_dofs();
        let linear = model.kinematics() == Kinematics::Linear;
        let corotational = model.kinematics() == Kinematics::Corotational;
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
        predict(
            predictor,
            (h, b, ratio),
            state,
            &ws.a_aux[..n],
            &mut ws.dq_step[..n],
        );
        for ((qn, q0), d) in ws.q_new[..n]
            .iter_mut()
            .zip(&state.q[..n])
            .zip(&ws.dq_step[..n])
        {
            *qn = q0 + d;
        }
        // A prescribed root: its angle at t + h (its rate and acceleration below).
        let root = root.map(|f| f(t_new));
        if let Some([theta, _, _]) = root {
            if !root.iter().flatten().all(|x| x.is_finite()) {
                return Err((
                    0,
                    BeamError::NonFinite {
                        what: format!("hub motion at t = {t_new}"),
                    },
                ));
            }
            ws.dq_step[..3].copy_from_slice(&[0.0, 0.0, theta - state.q[2]]);
            ws.q_new[..3].copy_from_slice(&[0.0, 0.0, theta]);
        }
        let tol = self.tolerance * model.length();
        let mut iterations = 0;
        let mut last;
        let mut first = f64::INFINITY;
        // modified Newton (every iterating model): the iteration matrix is kept over the step's
        // iterations while the corrections contract by MODIFIED_NEWTON_RATE per iteration and
        // the iterations left can reach the tolerance at the rate measured. A corotational
        // step starts from a fresh matrix at its predictor (its mass matrix turns with the
        // nodes, and a step that depends only on the state, not on the workspace's history, is
        // reproducible bit for bit); an ANCF step from the one retained from the last step (its
        // mass is constant) for its first correction, then from a fresh one at that corrected
        // iterate (see below; the predictor's miss, ≈ 1e-3 on the slopes of the ringing modes,
        // is mostly linear, and a matrix at the predictor would sit that far from the solution).
        let modified = !single_solve
            && match self.newton_method {
                NewtonMethod::Modified => true,
                NewtonMethod::Full => false,
                NewtonMethod::Auto => model.kinematics() == Kinematics::Ancf,
            };
        let key = Some((h, self.rho_inf, false));
        let started_retained =
            modified && model.kinematics() == Kinematics::Ancf && ws.factored_for == key;
        let mut refactor = !single_solve && !started_retained;
        let mut previous = f64::INFINITY;
        let relations = NewmarkRelations {
            h,
            alpha_m: am,
            alpha_f: af,
            gamma: g,
            beta: b,
        };
        // â, q̇, q̈ at the predictor (the constrained DOFs keep these: their increments are
        // fixed; the free ones are updated with each correction below)
        relations.apply(state, ws, 0..n);
        if let Some([_, rate, accel]) = root {
            ws.v_new[..3].copy_from_slice(&[0.0, 0.0, rate]);
            ws.a_new[..3].copy_from_slice(&[0.0, 0.0, accel]);
            ws.ahat_new[..3].copy_from_slice(&[0.0, 0.0, accel]);
        }
        loop {
            let kin = Kinematic {
                q: &ws.q_new,
                v: Some(&ws.v_new),
                a: Some(&ws.a_new),
            };
            if iterations >= max_iterations {
                ws.counters.residuals += 1;
                assemble(model, kin, loads.as_slice(), &mut ws.r, None);
                node_residual(
                    node_load.as_deref_mut(),
                    t_new,
                    ws,
                    (nfix, model.dofs_per_node()),
                    None,
                    1.0,
                );
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
            let reuse = ws.factored_for == key && (single_solve || (modified && !refactor));
            if reuse {
                ws.counters.residuals += 1;
                assemble(model, kin, loads.as_slice(), &mut ws.r, None);
                if !single_solve {
                    node_residual(
                        node_load.as_deref_mut(),
                        t_new,
                        ws,
                        (nfix, model.dofs_per_node()),
                        None,
                        1.0,
                    );
                }
            } else {
                assemble(
                    model,
                    kin,
                    loads.as_slice(),
                    &mut ws.r,
                    Some((&mut ws.band, weights)),
                );
                node_residual(
                    node_load.as_deref_mut(),
                    t_new,
                    ws,
                    (nfix, model.dofs_per_node()),
                    Some(weights),
                    1.0,
                );
                ws.factored_for = None;
                ws.counters.tangents += 1;
                ws.counters.factorizations += 1;
                let factored = ws.band.factorize("generalized-α iteration matrix");
                if let Err(e) = factored {
                    return Err((iterations, e));
                }
                if single_solve || modified {
                    ws.factored_for = key;
                }
                refactor = false;
            }
            for (d, ri) in ws.dq.iter_mut().zip(&ws.r[nfix..]) {
                *d = -ri;
            }
            ws.band.solve_in_place(&mut ws.dq);
            ws.counters.iterations += 1;
            let s = if corotational {
                crate::statics::rotation_limiter(&ws.dq, nfix)
            } else {
                1.0
            };
            for (((step, qn), q0), d) in ws.dq_step[nfix..n]
                .iter_mut()
                .zip(&mut ws.q_new[nfix..n])
                .zip(&state.q[nfix..n])
                .zip(&ws.dq)
            {
                *step += s * d;
                *qn = q0 + *step;
            }
            relations.apply(state, ws, nfix..n);
            last = max_abs_scaled(&ws.dq, s);
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
            // modified Newton: a fresh iteration matrix once the contraction is slow
            if modified && reuse && iterations > 0 && last > MODIFIED_NEWTON_RATE * previous {
                refactor = true;
            }
            // ... and when the iterations left cannot reach the tolerance at the measured rate
            // (at MODIFIED_NEWTON_RATE after a fresh matrix): a small iteration budget gets full
            // Newton's quadratic convergence
            let rate = if reuse && iterations > 0 {
                last / previous
            } else {
                MODIFIED_NEWTON_RATE
            };
            let left = max_iterations.saturating_sub(iterations + 1);
            if modified && left > 0 && last * rate.min(1.0).powi(left as i32) > tol {
                refactor = true;
            }
            let converged = last <= tol;
            // ... and, on an ANCF step started from the matrix retained from the last step,
            // right after its first correction: that matrix's stiffness is a step out of date
            // (the stiff axial direction has turned with the beam), so it resolves the step's
            // linear part (the first correction, against the predictor's miss of the ringing
            // modes) but contracts only by ≈ 0.1–0.3 after; a matrix at the first corrected
            // iterate contracts quadratically from there. Measured on the step load of
            // `canonical::polypropylene_cantilever`, 32 elements, 1000 steps: 3.80 instead of
            // 4.86 iterations and 1.03 instead of 0.86 factorisations per step, the tip
            // within 0.13 instead of 0.20 tol·L of a tight (1e-10 L) full Newton solution.
            if started_retained && iterations == 0 && reuse && !converged {
                refactor = true;
            }
            previous = last;
            iterations += 1;
            if converged || single_solve {
                break;
            }
        }
        // A converged step that turns a node by more than the Newton limiter allows in one
        // iteration has not resolved the rotation: it may be a spurious root (a node turned by
        // 2π, or onto another branch of the 2π-periodic element); take it in smaller pieces.
        if corotational
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
        if ![&ws.q_new, &ws.v_new, &ws.a_new, &ws.ahat_new]
            .iter()
            .all(|x| all_finite(x))
        {
            return Err((
                iterations,
                BeamError::NonFinite {
                    what: "generalized-α state".into(),
                },
            ));
        }
        // The motion-dependent load at the accepted state (for the work done on the beam).
        let dpn = model.dofs_per_node();
        let node_force = node_load.map(|nl| {
            let i = nl.node();
            let (q, v) = node_motion(dpn, &ws.q_new, &ws.v_new, i);
            (i, nl.evaluate(t_new, q, v).force)
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
        state.external_work += step_work(
            dpn,
            (&state.q, &ws.q_new),
            (&state.f_prev, f),
            state.node_force_prev,
            node_force,
        );
        state.node_force_prev = node_force.unwrap_or((state.node_force_prev.0, [0.0; 3]));
        state.f_prev.copy_from_slice(f);
        // (the workspace's vectors are written in full before they are read on the next step:
        // exchanged, not copied)
        std::mem::swap(&mut state.q, &mut ws.q_new);
        std::mem::swap(&mut state.v, &mut ws.v_new);
        std::mem::swap(&mut state.a, &mut ws.a_new);
        // â_{n−1} ← â_n (rescaled to h), â_n ← â_{n+1}
        if state.a_aux_prev.len() == n {
            std::mem::swap(&mut state.a_aux_prev, &mut ws.a_aux);
        } else {
            state.a_aux_prev.clear();
            state.a_aux_prev.extend_from_slice(&ws.a_aux);
        }
        std::mem::swap(&mut state.a_aux, &mut ws.ahat_new);
        state.h_prev = Some(h);
        state.t = t_new;
        ws.counters.steps += 1;
        Ok((iterations, first, last))
    }
}

/// The generalized-α relations between the step's increment Δq = q_{n+1} − q_n and â_{n+1},
/// q̇_{n+1}, q̈_{n+1} (module docs), for a step `h` \[s\].
#[derive(Debug, Clone, Copy)]
struct NewmarkRelations {
    h: f64,
    alpha_m: f64,
    alpha_f: f64,
    gamma: f64,
    beta: f64,
}

impl NewmarkRelations {
    /// â_{n+1}, q̇_{n+1} and q̈_{n+1} of the DOFs `range` from the increment in `ws.dq_step`, the
    /// state at t_n and â_n (rescaled to h) in `ws.a_aux`, into the workspace. From Δq itself,
    /// not from q_{n+1} − q_n, which cancels to ε|q| and leaves ε|q|/(βh²) of noise in â at
    /// tiny h.
    #[inline(always)]
    fn apply(&self, state: &State, ws: &mut Workspace, range: std::ops::Range<usize>) {
        let NewmarkRelations {
            h,
            alpha_m: am,
            alpha_f: af,
            gamma: g,
            beta: b,
        } = *self;
        // (every slice cut to the range, so that the loop runs without bounds checks)
        let (dq, aux) = (&ws.dq_step[range.clone()], &ws.a_aux[range.clone()]);
        let (v0, a0) = (&state.v[range.clone()], &state.a[range.clone()]);
        let (ahat_new, v_new, a_new) = (
            &mut ws.ahat_new[range.clone()],
            &mut ws.v_new[range.clone()],
            &mut ws.a_new[range],
        );
        for i in 0..dq.len() {
            let ahat = (dq[i] - h * v0[i] - h * h * (0.5 - b) * aux[i]) / (b * h * h);
            ahat_new[i] = ahat;
            v_new[i] = v0[i] + h * ((1.0 - g) * aux[i] + g * ahat);
            a_new[i] = ((1.0 - am) * ahat + am * aux[i] - af * a0[i]) / (1.0 - af);
        }
    }
}

/// The predicted increment Δq of a step `h` \[s\] (Newmark β `b`, `ratio` = h over the last
/// step, 0 on the first) into `dq`, from the state at t_n and â_n (rescaled to h) `aux`.
#[inline(always)]
fn predict(
    predictor: Predictor,
    (h, b, ratio): (f64, f64, f64),
    state: &State,
    aux: &[f64],
    dq: &mut [f64],
) {
    let n = dq.len();
    let (v0, aux) = (&state.v[..n], &aux[..n]);
    match predictor {
        Predictor::Rest => dq.fill(0.0),
        Predictor::Velocity => {
            for (d, v) in dq.iter_mut().zip(v0) {
                *d = h * v;
            }
        }
        Predictor::Extrapolated if ratio > 0.0 => {
            // â_{n+1} extrapolated linearly from â_{n−1}, â_n
            let prev = &state.a_aux_prev[..n];
            for i in 0..n {
                let ahat = aux[i] + ratio * (aux[i] - prev[i]);
                dq[i] = h * v0[i] + h * h * ((0.5 - b) * aux[i] + b * ahat);
            }
        }
        Predictor::Extrapolated => {
            for i in 0..n {
                dq[i] = h * v0[i] + h * h * ((0.5 - b) * aux[i] + b * aux[i]);
            }
        }
    }
}

/// max |s xᵢ| (0 for an empty `x`; NaN entries are skipped, as `f64::max` does), in four
/// lanes: the maximum is exact, so the order does not matter, and four independent lanes do not
/// wait on one another.
#[inline(always)]
fn max_abs_scaled(x: &[f64], s: f64) -> f64 {
    let mut m = [0.0f64; 4];
    let (chunks, rest) = x.as_chunks::<4>();
    for c in chunks {
        for k in 0..4 {
            let a = (s * c[k]).abs();
            m[k] = if a > m[k] { a } else { m[k] };
        }
    }
    for &v in rest {
        let a = (s * v).abs();
        m[0] = if a > m[0] { a } else { m[0] };
    }
    m[0].max(m[1]).max(m[2].max(m[3]))
}

/// True if every entry of `x` is finite (checked in four lanes, without an early exit).
#[inline(always)]
fn all_finite(x: &[f64]) -> bool {
    let mut ok = [true; 4];
    let (chunks, rest) = x.as_chunks::<4>();
    for c in chunks {
        for k in 0..4 {
            ok[k] &= c[k].abs() < f64::INFINITY;
        }
    }
    rest.iter().all(|v| v.is_finite()) && ok.iter().all(|&o| o)
}

/// One Newton solve's settings.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NewtonStep {
    pub(crate) h: f64,
    pub(crate) predictor: Predictor,
    pub(crate) max_iterations: usize,
}

/// (x[k], x[k + 1], x[k + 2]).
pub(crate) fn node_dofs(x: &[f64], k: usize) -> [f64; 3] {
    [x[k], x[k + 1], x[k + 2]]
}

/// (u, v, θ) of node `i` from the DOF vector `q` (`dpn` DOFs per node).
pub(crate) fn node_values(dpn: usize, q: &[f64], i: usize) -> [f64; 3] {
    if dpn == 4 {
        crate::assembly_ancf::node_uvt(q, i)
    } else {
        node_dofs(q, 3 * i)
    }
}

/// ((u, v, θ), (u̇, v̇, θ̇)) of node `i`.
pub(crate) fn node_motion(dpn: usize, q: &[f64], v: &[f64], i: usize) -> ([f64; 3], [f64; 3]) {
    if dpn == 4 {
        (
            crate::assembly_ancf::node_uvt(q, i),
            crate::assembly_ancf::node_uvt_rate(q, v, i),
        )
    } else {
        (node_dofs(q, 3 * i), node_dofs(v, 3 * i))
    }
}

/// (Δu, Δv, Δθ) of node `i` from `q0` to `q1` (ANCF: Δθ is the angle between the slopes).
pub(crate) fn node_increment(dpn: usize, q0: &[f64], q1: &[f64], i: usize) -> [f64; 3] {
    if dpn == 4 {
        let (a, b) = (
            crate::assembly_ancf::slope(q0, i),
            crate::assembly_ancf::slope(q1, i),
        );
        [
            q1[4 * i] - q0[4 * i],
            q1[4 * i + 1] - q0[4 * i + 1],
            (a.0 * b.1 - a.1 * b.0).atan2(a.0 * b.0 + a.1 * b.1),
        ]
    } else {
        std::array::from_fn(|d| q1[3 * i + d] - q0[3 * i + d])
    }
}

/// Work of the dead loads (trapezoidal: ½ (F₀ + F₁)·Δ) and of the node load (½ (F₀ + F₁)·Δ of
/// its node) over a step from `q0` to `q1`, in node terms (u, v, θ).
pub(crate) fn step_work(
    dpn: usize,
    (q0, q1): (&[f64], &[f64]),
    (f0, f1): (&[f64], &[f64]),
    node_prev: (usize, [f64; 3]),
    node_new: Option<(usize, [f64; 3])>,
) -> f64 {
    let mut work = 0.0;
    let nodes = f1.len() / 3;
    for i in 0..nodes {
        if (0..3).all(|d| f0[3 * i + d] == 0.0 && f1[3 * i + d] == 0.0) {
            continue;
        }
        let dq = node_increment(dpn, q0, q1, i);
        for d in 0..3 {
            work += 0.5 * (f0[3 * i + d] + f1[3 * i + d]) * dq[d];
        }
    }
    let (i_prev, fp) = node_prev;
    let dq = node_increment(dpn, q0, q1, i_prev);
    work += 0.5 * (0..3).map(|d| fp[d] * dq[d]).sum::<f64>();
    if let Some((i_new, fnew)) = node_new {
        let dq = node_increment(dpn, q0, q1, i_new);
        work += 0.5 * (0..3).map(|d| fnew[d] * dq[d]).sum::<f64>();
    }
    work
}

/// The forces the supports apply to the beam at the root node's (u \[N\], v \[N\], θ [N·m])
/// in `state` under `loads`: the residual f_int + f_in − F of the root's rows (with a clamped
/// root that a hub turns, [`GeneralizedAlpha::step_with_root`], the third entry is the torque
/// the hub applies to the beam; with a pinned or hub root it includes the root spring, damper
/// and hub inertia on θ, which are not supports: use the first two only).
pub fn root_reaction(model: &BeamModel, state: &State, loads: &NodalLoads) -> [f64; 3] {
    let mut r = vec![0.0; state.q.len()];
    assemble(
        model,
        Kinematic {
            q: &state.q,
            v: Some(&state.v),
            a: Some(&state.a),
        },
        loads.as_slice(),
        &mut r,
        None,
    );
    [r[0], r[1], r[2]]
}

/// A beam that a hub turns by its clamped root: clamped, corotational (3 DOFs per node).
pub(crate) fn check_rotating_clamp(model: &BeamModel) -> Result<(), BeamError> {
    if model.root() != crate::model::RootSupport::Clamped {
        return Err(BeamError::invalid(
            "root",
            format!("{:?}", model.root()),
            "clamped (the hub's angle is prescribed)",
        ));
    }
    if model.kinematics() != Kinematics::Corotational {
        return Err(BeamError::invalid(
            "kinematics",
            format!("{:?}", model.kinematics()),
            "corotational (large rotation of the hub)",
        ));
    }
    Ok(())
}

/// Adds `scale` × the motion-dependent node load at the current iterate to the residual
/// (r −= scale·F) and, if `weights` is given, −scale·(c_q ∂F/∂q + c_v ∂F/∂q̇) to the iteration
/// matrix (free DOFs only). On an ANCF node F = (fx, fy, m) acts through the chain rule
/// Q = Jᵀ F, J = ∂(u, v, θ)/∂(u, v, r′ᵧ, r′ₓ), and the Jacobian gets
/// Jᵀ (∂F/∂q) J + m ∂²θ/∂r′² + Jᵀ (∂F/∂θ̇)(∂θ̇/∂r′) for c_q and Jᵀ (∂F/∂q̇) J for c_v.
pub(crate) fn node_residual<'l>(
    node_load: Option<&mut (dyn NodeLoad + 'l)>,
    t: f64,
    ws: &mut Workspace,
    (nfix, dpn): (usize, usize),
    weights: Option<JacobianWeights>,
    scale: f64,
) {
    let Some(nl) = node_load else {
        return;
    };
    let node = nl.node();
    let (q, v) = node_motion(dpn, &ws.q_new, &ws.v_new, node);
    let f = nl.evaluate(t, q, v);
    let k = dpn * node;
    if dpn == 3 {
        for i in 0..3 {
            ws.r[k + i] -= scale * f.force[i];
        }
    } else {
        use crate::assembly_ancf::{SLOPE_X, SLOPE_Y, slope};
        let (sx, sy) = slope(&ws.q_new, node);
        let (_, g, _) = crate::ancf::slope_angle(sx, sy);
        ws.r[k] -= scale * f.force[0];
        ws.r[k + 1] -= scale * f.force[1];
        ws.r[k + SLOPE_X] -= scale * f.force[2] * g[0];
        ws.r[k + SLOPE_Y] -= scale * f.force[2] * g[1];
    }
    if let Some(w) = weights {
        add_node_jacobian(ws, (nfix, dpn), node, &f, w, scale);
    }
}

/// Adds −scale·(c_q ∂Q/∂q + c_v ∂Q/∂q̇) of the node force `f` on `node` to the iteration matrix
/// (chain rule through θ = atan2(r′ᵧ, r′ₓ) on an ANCF node, at the iterate in `ws`).
pub(crate) fn add_node_jacobian(
    ws: &mut Workspace,
    (nfix, dpn): (usize, usize),
    node: usize,
    f: &crate::node_load::NodeForce,
    w: JacobianWeights,
    scale: f64,
) {
    let k = dpn * node;
    if dpn == 3 {
        for i in 0..3 {
            for j in 0..3 {
                let (gi, gj) = (k + i, k + j);
                if gi >= nfix && gj >= nfix {
                    ws.band.add(
                        gi - nfix,
                        gj - nfix,
                        -scale * (w.stiffness * f.d_dq[i][j] + w.velocity * f.d_dv[i][j]),
                    );
                }
            }
        }
        return;
    }
    // ANCF: J (3 × 4) over the node DOFs (u, v, r′ᵧ, r′ₓ − 1)
    use crate::assembly_ancf::{SLOPE_X, SLOPE_Y, slope};
    let (sx, sy) = slope(&ws.q_new, node);
    let (_, g, h) = crate::ancf::slope_angle(sx, sy);
    let mut jm = [[0.0; 4]; 3];
    jm[0][0] = 1.0;
    jm[1][1] = 1.0;
    jm[2][SLOPE_X] = g[0];
    jm[2][SLOPE_Y] = g[1];
    let mut hq = [[0.0; 4]; 4];
    let sd = [ws.v_new[k + SLOPE_X], ws.v_new[k + SLOPE_Y]];
    let slot = [SLOPE_X, SLOPE_Y];
    // ∂θ̇/∂r′ = H ṙ′
    let mut dthdot = [0.0; 4];
    for a in 0..2 {
        dthdot[slot[a]] = h[a][0] * sd[0] + h[a][1] * sd[1];
        for b in 0..2 {
            hq[slot[a]][slot[b]] = h[a][b];
        }
    }
    for a in 0..4 {
        for b in 0..4 {
            let (ga, gb) = (k + a, k + b);
            if ga < nfix || gb < nfix {
                continue;
            }
            let mut dq = f.force[2] * hq[a][b];
            let mut dv = 0.0;
            for i in 0..3 {
                for j in 0..3 {
                    dq += jm[i][a] * f.d_dq[i][j] * jm[j][b];
                    dv += jm[i][a] * f.d_dv[i][j] * jm[j][b];
                }
                dq += jm[i][a] * f.d_dv[i][2] * dthdot[b];
            }
            ws.band.add(
                ga - nfix,
                gb - nfix,
                -scale * (w.stiffness * dq + w.velocity * dv),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_processor_specific_newton_loop_gives_the_portable_steps_bit_for_bit() {
        // The dispatched Newton loop (AVX2 where the processor has it) against the portable
        // code, step by step from the same state and workspace on the step-load transient
        // (ANCF, whose retained matrix carries over, and corotational): identical states,
        // iterations and corrections, to the last bit.
        for kin in [Kinematics::Ancf, Kinematics::Corotational] {
            let (model, loads) = crate::canonical::polypropylene_cantilever(8, kin).unwrap();
            let ga = GeneralizedAlpha::new(0.9).unwrap();
            let mut state = State::at_rest(&model, &loads).unwrap();
            let mut ws = Workspace::new(&model);
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            for k in 0..60 {
                let newton = NewtonStep {
                    h: 1e-3,
                    predictor: Predictor::Velocity,
                    max_iterations: 25,
                };
                let (mut s2, mut w2) = (state.clone(), Workspace::new(&model));
                w2.band = ws.band.clone();
                w2.factored_for = ws.factored_for;
                let fast = ga.newton(&model, &mut state, &mut ws, (&loads, None), None, newton);
                let portable =
                    ga.newton_portable(&model, &mut s2, &mut w2, (&loads, None), None, newton);
                let (a, b) = (fast.unwrap(), portable.unwrap());
                assert_eq!(
                    (a.0, a.1.to_bits(), a.2.to_bits()),
                    (b.0, b.1.to_bits(), b.2.to_bits()),
                    "{kin:?} step {k}"
                );
                for (x, y) in [(&state.q, &s2.q), (&state.v, &s2.v), (&state.a, &s2.a)] {
                    assert_eq!(bits(x), bits(y), "{kin:?} step {k}");
                }
            }
            assert!(state.q.iter().any(|x| x.abs() > 1e-3), "the beam moved");
        }
    }
}
