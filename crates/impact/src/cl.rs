//! The compliant link under a free head: a linear Euler–Bernoulli beam (flexrig-beam,
//! Hermite-cubic elements, consistent mass), clamped at the joint (held) or on a hub of the
//! rotor's inertia (free hub), with the payload m_e as a point mass at the tip.
//!
//! Each step of size h: the head drifts by velocity Verlet, x_h(t) = x_n + v_n τ + ½ a_n τ²; the
//! beam takes a generalized-α step at ρ∞ = 1 (the trapezoidal rule: no numerical dissipation for
//! the linear beam) with the contact force f = k_c ⟨x_h(t) − w⟩ⁿ on the tip *implicit* in its
//! Newton iteration ([`HeadContact`], stiffness ∂f/∂w on the tip's transverse DOF); then the
//! head's rate is completed with the force at t + h. Second order in h for the peak force and
//! the energy (the rig's coupling, `flexrig_rig::coupling`, with a free mass for the pendulum).
//! The peak is the largest local maximum of the force samples, refined by the parabola through
//! the three samples around it; the separation is located by linear interpolation of the gap.

use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_beam::{
    BeamModel, BeamSpec, GeneralizedAlpha, Kinematics, NodalLoads, NodeForce, NodeLoad, PointMass,
    ReducedModel, ReducedState, RootSupport, Section, State, Workspace,
};
use flexrig_contact::ContactLaw;

use crate::ImpactError;
use crate::setup::{ClSolver, ContactEvent, FreeMassImpact, ImpactOutcome, Joint};
use crate::severity::ContactTrace;

/// The head over one step from its state at `t0`: position x \[m\], speed v \[m/s\] and
/// acceleration a [m/s²] (velocity Verlet's drift).
#[derive(Debug, Clone, Copy)]
struct HeadMotion {
    t0: f64,
    x: f64,
    v: f64,
    a: f64,
}

impl HeadMotion {
    fn at(&self, t: f64) -> (f64, f64) {
        let tau = t - self.t0;
        (
            self.x + tau * (self.v + 0.5 * tau * self.a),
            self.v + tau * self.a,
        )
    }
}

/// The head's contact as a load on the tip node: F_v = f(x_h − w, ẋ_h − ẇ), ∂F_v/∂w = −∂f/∂δ.
struct HeadContact<'a> {
    law: &'a dyn ContactLaw,
    head: HeadMotion,
    tip: usize,
}

impl NodeLoad for HeadContact<'_> {
    fn node(&self) -> usize {
        self.tip
    }

    fn evaluate(&mut self, t: f64, q: [f64; 3], v: [f64; 3]) -> NodeForce {
        let (x_h, v_h) = self.head.at(t);
        let (delta, rate) = (x_h - q[1], v_h - v[1]);
        let mut out = NodeForce::ZERO;
        out.force[1] = self.law.force(delta, rate);
        out.d_dq[1][1] = -self.law.stiffness(delta, rate);
        out.d_dv[1][1] = -self.law.damping(delta, rate);
        out
    }
}

/// The beam model of the CL link with `elements` elements.
pub fn cl_beam(setup: &FreeMassImpact, elements: usize) -> Result<BeamModel, ImpactError> {
    let link = setup.link;
    let l = link.length;
    // the linear beam's axial DOFs are uncoupled from bending and never loaded: any EA will do
    let section = Section::from_stiffness(1e4 * link.ei() / (l * l), link.ei(), link.rho_a())?;
    let mut spec = BeamSpec::cantilever(l, section, elements, Kinematics::Linear);
    if let Joint::FreeHub { rotor_inertia } = setup.joint {
        spec.root = RootSupport::Hub {
            inertia: rotor_inertia,
            k_theta: 0.0,
            c_theta: 0.0,
        };
    }
    if link.m_e > 0.0 {
        spec.point_masses.push(PointMass {
            node: elements,
            mass: link.m_e,
            inertia: 0.0,
        });
    }
    Ok(BeamModel::new(spec)?)
}

/// The CL link's first bending mode seen from the tip, for the joint held: the modal mass
/// m₁ = 1/φ₁(tip)² of the mass-normalised mode and k₁ = ω₁² m₁ (a one-mode model of the beam;
/// the slow limit of the impact, contact time ≫ 2π/ω₁).
pub fn first_mode_at_tip(
    setup: &FreeMassImpact,
    elements: usize,
) -> Result<crate::cj::TipOscillator, ImpactError> {
    let held = FreeMassImpact {
        joint: Joint::Held,
        ..*setup
    };
    let model = cl_beam(&held, elements)?;
    let modes = flexrig_beam::modal_analysis(&model, 1, flexrig_beam::ModalDirection::Transverse)?;
    let phi_tip = modes.shapes[0][3 * model.tip_node() + 1];
    let m_tip = 1.0 / (phi_tip * phi_tip);
    Ok(crate::cj::TipOscillator {
        m_tip,
        k: modes.omegas[0] * modes.omegas[0] * m_tip,
    })
}

/// The beam as the step loop sees it: the full FE model or its modal reduction.
enum Beam {
    Full {
        model: BeamModel,
        state: Box<State>,
        workspace: Box<Workspace>,
        loads: NodalLoads,
    },
    Reduced {
        model: ReducedModel,
        state: ReducedState,
        loads: NodalLoads,
    },
}

impl Beam {
    /// The beam at t = 0, at rest or (free hub) in rigid rotation with the tip at −`tip_speed`.
    fn new(
        setup: &FreeMassImpact,
        solver: &ClSolver,
        tip_speed: f64,
    ) -> Result<(Beam, usize, f64), ImpactError> {
        let model = cl_beam(setup, solver.elements)?;
        let tip = model.tip_node();
        let length = model.length();
        let loads = NodalLoads::zeros(&model);
        let omega = -tip_speed / length;
        let Some(modes) = solver.modes else {
            let mut v0 = vec![0.0; model.n_dofs()];
            for i in 0..=tip {
                v0[3 * i + 1] = omega * model.node_x(i);
                v0[3 * i + 2] = omega;
            }
            for x in &mut v0[..model.n_fixed()] {
                *x = 0.0;
            }
            let state = Box::new(State::new(
                &model,
                vec![0.0; model.n_dofs()],
                v0,
                0.0,
                &loads,
            )?);
            let workspace = Box::new(Workspace::new(&model));
            return Ok((
                Beam::Full {
                    model,
                    state,
                    workspace,
                    loads,
                },
                tip,
                length,
            ));
        };
        let reduced = ReducedModel::new(&model, modes, &[3 * tip + 1])?;
        let mut state = ReducedState::at_rest(&reduced, &loads)?;
        if omega != 0.0 {
            // the rigid rotation is the hub's zero-frequency mode: η̇₀ = ω/φ₀(θ)
            let rigid = reduced.shape(0);
            let theta = rigid[3 * tip + 2];
            if reduced.omegas()[0] != 0.0 || theta == 0.0 {
                return Err(ImpactError::invalid(
                    "modes",
                    modes,
                    "a free hub's reduced beam needs its rigid mode first",
                ));
            }
            state.eta_dot[0] = omega / theta;
        }
        Ok((
            Beam::Reduced {
                model: reduced,
                state,
                loads,
            },
            tip,
            length,
        ))
    }

    fn step(
        &mut self,
        integrator: &GeneralizedAlpha,
        h: f64,
        contact: &mut HeadContact<'_>,
    ) -> Result<(), ImpactError> {
        match self {
            Beam::Full {
                model,
                state,
                workspace,
                loads,
            } => {
                integrator.step_with(model, state, workspace, h, loads, Some(contact))?;
            }
            Beam::Reduced {
                model,
                state,
                loads,
            } => {
                integrator.step_reduced_with(model, state, h, loads, Some(contact))?;
            }
        }
        Ok(())
    }

    fn time(&self) -> f64 {
        match self {
            Beam::Full { state, .. } => state.t,
            Beam::Reduced { state, .. } => state.t,
        }
    }

    /// Tip deflection \[m\] and rate [m/s].
    fn tip(&self, tip: usize) -> (f64, f64) {
        match self {
            Beam::Full { state, .. } => (state.node(tip).1, state.node_velocity(tip)[1]),
            Beam::Reduced { model, state, .. } => {
                let (w, v, _) = model.dof(state, 3 * tip + 1);
                (w, v)
            }
        }
    }

    /// Kinetic plus strain energy \[J\].
    fn energy(&self) -> f64 {
        match self {
            Beam::Full { model, state, .. } => {
                let e = state.energy(model);
                e.kinetic + e.strain
            }
            Beam::Reduced { model, state, .. } => {
                let (t, u) = model.energy(state);
                t + u
            }
        }
    }
}

/// Runs the CL impact from the onset (t = 0) to the separation of the first contact.
pub fn run_cl(setup: &FreeMassImpact, solver: &ClSolver) -> Result<ImpactOutcome, ImpactError> {
    run_cl_until(setup, solver, &AtomicBool::new(false))
}

/// Steps between two looks at the stop flag of [`run_cl_until`] (a few milliseconds of the
/// finest meshes' steps).
const STOP_CHECK_STEPS: usize = 16;

/// [`run_cl`], stopping with [`ImpactError::Interrupted`] within [`STOP_CHECK_STEPS`] steps
/// once `stop` is set (a fine mesh's case runs for tens of seconds: Ctrl-C must reach the step
/// loop, not only the next case).
pub fn run_cl_until(
    setup: &FreeMassImpact,
    solver: &ClSolver,
    stop: &AtomicBool,
) -> Result<ImpactOutcome, ImpactError> {
    run_cl_inner(setup, solver, stop, None)
}

/// [`run_cl_until`] with the contact's force and indentation at every step (the separation
/// interpolated linearly, as the run locates it).
pub fn run_cl_traced_until(
    setup: &FreeMassImpact,
    solver: &ClSolver,
    stop: &AtomicBool,
) -> Result<(ImpactOutcome, ContactTrace), ImpactError> {
    let mut trace = ContactTrace::default();
    let outcome = run_cl_inner(setup, solver, stop, Some(&mut trace))?;
    Ok((outcome, trace))
}

fn run_cl_inner(
    setup: &FreeMassImpact,
    solver: &ClSolver,
    stop: &AtomicBool,
    mut trace: Option<&mut ContactTrace>,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    solver.validate()?;
    let (head_speed, tip_speed) = match setup.joint {
        Joint::Held => (setup.v0, 0.0),
        Joint::FreeHub { .. } => (0.0, setup.v0),
    };
    let (mut beam, tip, length) = Beam::new(setup, solver, tip_speed)?;
    let t_contact = setup.payload_contact_time();
    let h = t_contact / solver.steps_per_contact as f64;
    let x_scale = setup.v0 * t_contact;
    // Newton to 1e-9 of the indentation scale (the tolerance is relative to L)
    let tolerance = (1e-9 * x_scale / length).clamp(1e-300, 1e-3);
    let integrator = GeneralizedAlpha::new(1.0)?.with_newton(50, tolerance)?;
    let law = setup.law()?;
    let mut head = HeadMotion {
        t0: 0.0,
        x: 0.0,
        v: head_speed,
        a: 0.0,
    };
    let energy = |beam: &Beam, head: &HeadMotion, delta: f64| {
        0.5 * setup.m_h * head.v * head.v + beam.energy() + law.elastic_energy(delta)
    };
    let e0 = energy(&beam, &head, 0.0);
    // force samples (t, f) of the last three steps, for the peak
    let mut history: [(f64, f64); 3] = [(0.0, 0.0); 3];
    let mut peak = (0.0_f64, 0.0_f64);
    let max_steps = 400 * solver.steps_per_contact;
    let mut gap_prev = 0.0;
    if let Some(trace) = trace.as_mut() {
        trace.push(0.0, 0.0, 0.0);
    }
    for step in 1..=max_steps {
        if step % STOP_CHECK_STEPS == 0 && stop.load(Ordering::Relaxed) {
            return Err(ImpactError::Interrupted);
        }
        let mut contact = HeadContact {
            law: &*law,
            head,
            tip,
        };
        beam.step(&integrator, h, &mut contact)?;
        let t = beam.time();
        // the force the beam's Newton converged on: the head's predicted speed in its rate
        let (x_h, v_h) = head.at(t);
        let (w, w_dot) = beam.tip(tip);
        let delta = x_h - w;
        let f = law.force(delta, v_h - w_dot);
        let a_new = -f / setup.m_h;
        head = HeadMotion {
            t0: t,
            x: x_h,
            v: head.v + 0.5 * h * (head.a + a_new),
            a: a_new,
        };
        history = [history[1], history[2], (t, f)];
        if step >= 2 && history[1].1 > history[0].1 && history[1].1 >= history[2].1 {
            let refined = parabola_peak(&history);
            if refined.1 > peak.0 {
                peak = (refined.1, refined.0);
            }
        }
        if delta <= 0.0 {
            // the gap crossed 0 within this step: linear interpolation of the separation
            let t_sep = t - h * delta / (delta - gap_prev);
            if let Some(trace) = trace.as_mut() {
                trace.push(t_sep, 0.0, 0.0);
            }
            return Ok(ImpactOutcome::first_only(
                ContactEvent {
                    onset_s: 0.0,
                    peak_force_n: peak.0,
                    time_of_peak_s: peak.1,
                    duration_s: t_sep,
                },
                head.v - w_dot,
                (e0, energy(&beam, &head, 0.0)),
                step,
            ));
        }
        gap_prev = delta;
        if let Some(trace) = trace.as_mut() {
            trace.push(t, f, delta);
        }
    }
    Err(ImpactError::NotFinished {
        design: "CL",
        reason: format!(
            "no separation within {max_steps} steps (400 contact times of the payload); \
             a long push of the link: use fewer steps_per_contact"
        ),
    })
}

/// Vertex (t, f) of the parabola through three equally spaced samples.
fn parabola_peak(s: &[(f64, f64); 3]) -> (f64, f64) {
    let (f0, f1, f2) = (s[0].1, s[1].1, s[2].1);
    let curvature = f0 - 2.0 * f1 + f2;
    if curvature >= 0.0 {
        return (s[1].0, f1);
    }
    let h = s[1].0 - s[0].0;
    let offset = 0.5 * (f0 - f2) / curvature; // in steps, within [−½, ½]
    (s[1].0 + offset * h, f1 - 0.25 * (f0 - f2) * offset)
}
