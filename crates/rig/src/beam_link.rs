//! The compliant link (CL): a flexrig-beam finite-element beam clamped at the robot axis, bending
//! in the horizontal plane (its local x along the world x, its transverse v along the world y),
//! with the payload as a point mass at the tip node and the dome rigidly attached to the tip
//! section. It advances with the same step as the Rapier world, either with every FE degree of
//! freedom or, as the shortcut for small deflections, modal-reduced (the scene's
//! `solver.beam`).

use flexrig_beam::{
    BeamModel, BeamSpec, GeneralizedAlpha, Kinematics, Material, NodalLoads, NodeLoad, PointMass,
    ReducedModel, ReducedState, RootSupport, Section, State, StepMemory, Workspace,
};
use flexrig_contact::BodyKinematics;
use flexrig_contact::math::Vector;

use crate::RigError;
use crate::coupling::section_kinematics;
use crate::hinge::HingeState;
use crate::joint_drive::{HubLaw, JointDrive};
use crate::scene::{BeamSolverSpec, Scene};

/// Which beam stands for the robot link.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LinkVariant {
    /// The compliant link: the scene's beam clamped at the robot axis (design `cl`).
    Compliant,
    /// A compliant joint built from the FE beam: EI and EA multiplied by `stiffness_factor`,
    /// pinned at the axis on the scene's torsion spring k_θr — the cross-check of the Rapier CJ.
    StiffOnTorsionSpring {
        /// Factor on EI and EA (e.g. 1e4).
        stiffness_factor: f64,
    },
    /// The scene's beam on a free pin at the robot axis (no spring, no hub inertia): the
    /// free-hub reference of a compliant link on a torque-free drive.
    FreePin,
}

/// The FE link with its state and scratch space.
#[derive(Debug, Clone)]
pub struct BeamLink {
    model: BeamModel,
    dynamics: LinkDynamics,
    integrator: GeneralizedAlpha,
    loads: NodalLoads,
    tip: usize,
    /// The motor's hub the link is clamped to (`robot.drive`), or `None`: the test bed's fixed
    /// axis.
    hub: Option<DrivenHub>,
}

/// The hub of a driven compliant link (corotational elements: the link turns through large
/// angles).
#[derive(Debug, Clone)]
enum DrivenHub {
    /// An ideal position source: the clamped root turns as the command says (a rotating clamp,
    /// [`GeneralizedAlpha::step_with_root`]); the motor's torque is the root's reaction plus
    /// the rotor's J_m N² θ̈ and the friction's c_m N² θ̇.
    Prescribed(Box<JointDrive>),
    /// A hub of the rotor's inertia J_m N² pinned at the axis (flexrig-beam's
    /// `RootSupport::Hub`), turned by the drive's torque: the law of the step folded into the
    /// hub's torsion spring and damper to ground and a moment ([`HubLaw`]).
    Free {
        /// J_m N² [kg·m²].
        inertia: f64,
        /// c_m N² [N·m·s/rad].
        friction: f64,
        /// The law of the next step.
        law: HubLaw,
    },
}

/// The link as a step found it, to take the step again ([`BeamLink::save`],
/// [`BeamLink::restore`]): the beam's state with its workspace's memory of the last step, the
/// hub's support and law, and the hub's moment; not the model and the scratch space, which a
/// step does not change (or rebuilds from these).
#[derive(Debug, Clone)]
pub struct LinkCheckpoint {
    dynamics: SavedDynamics,
    root: RootSupport,
    law: Option<HubLaw>,
    hub_moment: f64,
}

/// The state part of a [`LinkCheckpoint`].
#[derive(Debug, Clone)]
enum SavedDynamics {
    Full(Box<(State, StepMemory)>),
    Modal(ReducedState),
}

/// Every FE DOF, or the modal-reduced linear beam.
#[derive(Debug, Clone)]
enum LinkDynamics {
    Full(Box<(State, Workspace)>),
    Modal {
        reduced: Box<ReducedModel>,
        state: ReducedState,
    },
}

impl BeamLink {
    /// The link of `scene`, at rest: clamped at the axis ([`LinkVariant::Compliant`]) or, for the
    /// CJ cross-check, stiffened and pinned on the scene's torsion spring; solved as the scene's
    /// `solver.beam` says (the modal model keeps the tip u, v, θ correction shapes, where the
    /// contact force and moment act).
    pub fn new(scene: &Scene, rho_inf: f64, variant: LinkVariant) -> Result<Self, RigError> {
        let r = &scene.file.robot;
        let driven = match (variant, scene.drive.as_ref()) {
            (LinkVariant::Compliant, d) => d,
            (LinkVariant::StiffOnTorsionSpring { .. } | LinkVariant::FreePin, Some(_)) => {
                return Err(crate::error::invalid(
                    "robot.drive",
                    "a drive",
                    "none for the FE cross-checks (the stiffened joint, the free pin)",
                ));
            }
            (LinkVariant::StiffOnTorsionSpring { .. } | LinkVariant::FreePin, None) => None,
        };
        let solver = match (driven, scene.file.solver.beam) {
            // a driven link turns through large angles: corotational elements
            (Some(_), BeamSolverSpec::Auto {}) => BeamSolverSpec::Corotational {},
            (_, solver) => solver.resolve(scene.file.stop),
        };
        let kinematics = match solver {
            BeamSolverSpec::Auto {} => unreachable!("resolved above"),
            BeamSolverSpec::Corotational {} => Kinematics::Corotational,
            BeamSolverSpec::Ancf {} => Kinematics::Ancf,
            BeamSolverSpec::Linear {} | BeamSolverSpec::Modal { .. } => Kinematics::Linear,
        };
        let material = Material::new(r.youngs_modulus_pa, r.density_kg_m3)?;
        let section = Section::rectangular(&material, r.width_m, r.thickness_m)?;
        let mut spec = BeamSpec::cantilever(r.length_m, section, r.beam_elements, kinematics);
        if let LinkVariant::StiffOnTorsionSpring { stiffness_factor } = variant {
            spec.section = Section::from_stiffness(
                section.ea() * stiffness_factor,
                section.ei() * stiffness_factor,
                section.rho_a(),
            )?;
            spec.root = RootSupport::Pinned {
                k_theta: scene.torsion_spring,
                c_theta: 0.0,
            };
        }
        if variant == LinkVariant::FreePin {
            spec.root = RootSupport::Pinned {
                k_theta: 0.0,
                c_theta: 0.0,
            };
        }
        spec.point_masses.push(PointMass {
            node: r.beam_elements,
            mass: r.payload_kg,
            inertia: 0.0,
        });
        let hub = driven.map(|d| match d.is_prescribed() {
            true => DrivenHub::Prescribed(Box::new(d.clone())),
            false => DrivenHub::Free {
                inertia: d.inertia(),
                friction: d.friction(),
                law: HubLaw {
                    stiffness: 0.0,
                    damping: 0.0,
                    moment: 0.0,
                },
            },
        });
        if let Some(DrivenHub::Free { inertia, .. }) = &hub {
            spec.root = RootSupport::Hub {
                inertia: *inertia,
                k_theta: 0.0,
                c_theta: driven.map_or(0.0, |d| d.friction()),
            };
        }
        let model = BeamModel::new(spec)?;
        let loads = NodalLoads::zeros(&model);
        let tip = model.tip_node();
        let dynamics = match (solver, driven) {
            (BeamSolverSpec::Corotational {}, Some(d)) => {
                let (start, _, _) = d.initial();
                let accel = d.prescribed(0.0).map_or(0.0, |(_, a)| a);
                LinkDynamics::Full(Box::new((
                    State::in_rigid_rotation(
                        &model,
                        [start.angle, start.rate, accel],
                        0.0,
                        &loads,
                    )?,
                    Workspace::new(&model),
                )))
            }
            (_, Some(_)) => {
                return Err(crate::error::invalid(
                    "solver.beam",
                    format!("{solver:?}"),
                    "\"auto\" or \"corotational\" for a driven compliant link (the motor turns \
                     it through large angles)",
                ));
            }
            (solver, None) => match solver {
                BeamSolverSpec::Modal { modes } => {
                    let reduced =
                        ReducedModel::new(&model, modes, &[3 * tip, 3 * tip + 1, 3 * tip + 2])?;
                    LinkDynamics::Modal {
                        state: ReducedState::at_rest(&reduced, &loads)?,
                        reduced: Box::new(reduced),
                    }
                }
                _ => LinkDynamics::Full(Box::new((
                    State::at_rest(&model, &loads)?,
                    Workspace::new(&model),
                ))),
            },
        };
        // ANCF at ρ∞ = 1: the energy-conserving midpoint step (generalized-α's trapezoidal
        // rule does not bound the energy of its stiff axial modes).
        let integrator = if kinematics == Kinematics::Ancf && rho_inf == 1.0 {
            GeneralizedAlpha::energy_conserving()
        } else {
            GeneralizedAlpha::new(rho_inf)?
        };
        Ok(BeamLink {
            integrator,
            tip,
            model,
            dynamics,
            loads,
            hub,
        })
    }

    /// (q, v, a) of node `node`'s u \[m\], v \[m\], θ \[rad\] (and their rates) for every
    /// element type (ANCF: θ from the slope).
    fn node_motion(&self, node: usize) -> [(f64, f64, f64); 3] {
        match &self.dynamics {
            LinkDynamics::Full(full) => {
                let state = &full.0;
                let (u, v, t) = state.node(node);
                let rate = state.node_velocity(node);
                let acc = state.node_acceleration(node);
                [
                    (u, rate[0], acc[0]),
                    (v, rate[1], acc[1]),
                    (t, rate[2], acc[2]),
                ]
            }
            LinkDynamics::Modal { reduced, state } => {
                let i = 3 * node;
                [
                    reduced.dof(state, i),
                    reduced.dof(state, i + 1),
                    reduced.dof(state, i + 2),
                ]
            }
        }
    }

    /// (q, v, a) of the tip's u, v, θ.
    fn tip_dofs(&self) -> [(f64, f64, f64); 3] {
        self.node_motion(self.tip)
    }

    /// Sets the beam's clock to `t` \[s\] (its state is unchanged): the beam at rest does not
    /// move while the free flight carries the rig to the contact, and its motion-dependent loads
    /// are evaluated at the rig's time.
    pub fn set_time(&mut self, t: f64) {
        match &mut self.dynamics {
            LinkDynamics::Full(full) => full.0.t = t,
            LinkDynamics::Modal { state, .. } => state.t = t,
        }
    }

    /// The beam model.
    pub fn model(&self) -> &BeamModel {
        &self.model
    }

    /// Number of coordinates advanced per step: every free FE DOF, or the modal coordinates.
    pub fn n_coordinates(&self) -> usize {
        match &self.dynamics {
            LinkDynamics::Full(_) => self.model.n_free(),
            LinkDynamics::Modal { reduced, .. } => reduced.n_coordinates(),
        }
    }

    /// Pose and velocity of the tip section (frame origin at the tip node on the beam axis).
    pub fn tip_kinematics(&self) -> BodyKinematics {
        let [u, v, theta] = self.tip_dofs();
        section_kinematics(
            self.model.length(),
            [u.0, v.0, theta.0],
            [u.1, v.1, theta.1],
        )
    }

    /// Index of the tip node.
    pub fn tip_node(&self) -> usize {
        self.tip
    }

    /// Transverse (y) displacement, velocity and acceleration of the tip [m, m/s, m/s²].
    pub fn tip_transverse(&self) -> (f64, f64, f64) {
        self.tip_dofs()[1]
    }

    /// Kinetic plus strain energy of the link \[J\] (a driven link's hub: without the rotor's
    /// kinetic energy and the loop's spring folded into the hub's support, which the drive
    /// accounts for).
    pub fn energy(&self) -> f64 {
        match &self.dynamics {
            LinkDynamics::Full(full) => {
                let e = full.0.energy(&self.model);
                let (k, _, j) = self.model.root().spring_damper_inertia();
                let hub = match self.hub {
                    Some(DrivenHub::Free { .. }) => {
                        let (angle, rate, _) = self.node_motion(0)[2];
                        0.5 * j * rate * rate + 0.5 * k * angle * angle
                    }
                    _ => 0.0,
                };
                e.kinetic + e.strain - hub
            }
            LinkDynamics::Modal { reduced, state } => {
                let (kinetic, strain) = reduced.energy(state);
                kinetic + strain
            }
        }
    }

    /// World positions of the nodes (for the 3D view) \[m\].
    pub fn node_positions(&self) -> Vec<Vector> {
        let displacement = |n: usize| -> (f64, f64) {
            match &self.dynamics {
                LinkDynamics::Full(full) => {
                    let (u, v, _) = full.0.node(n);
                    (u, v)
                }
                LinkDynamics::Modal { reduced, state } => {
                    (reduced.dof(state, 3 * n).0, reduced.dof(state, 3 * n + 1).0)
                }
            }
        };
        (0..self.model.n_nodes())
            .map(|n| {
                let (u, v) = displacement(n);
                Vector::new(self.model.node_x(n) + u, v, 0.0)
            })
            .collect()
    }

    /// Advances by `dt` \[s\] with the motion-dependent `tip_load` (the contact) treated
    /// implicitly at the end of the step (see [`crate::coupling`]): generalized-α enforces the
    /// equation of motion at t + dt, so the contact force enters at the same time level as the
    /// beam's own forces, with its stiffness and damping in the Newton iteration matrix (the
    /// ANCF link's energy-conserving midpoint step averages it over the step, as velocity
    /// Verlet does for the operator).
    ///
    /// A driven link: a prescribed hub turns the clamped root as commanded; a free hub takes
    /// the law set by [`BeamLink::set_hub_law`].
    pub fn step(&mut self, dt: f64, tip_load: &mut dyn NodeLoad) -> Result<(), RigError> {
        match &mut self.dynamics {
            LinkDynamics::Full(full) if matches!(self.hub, Some(DrivenHub::Prescribed(_))) => {
                let Some(DrivenHub::Prescribed(drive)) = &self.hub else {
                    unreachable!("matched above")
                };
                let (state, workspace) = &mut **full;
                let root = |t: f64| match drive.prescribed(t) {
                    Some((s, accel)) => [s.angle, s.rate, accel],
                    None => [f64::NAN; 3],
                };
                self.integrator.step_with_root(
                    &self.model,
                    state,
                    workspace,
                    dt,
                    &self.loads,
                    Some(tip_load),
                    &root,
                )?;
            }
            LinkDynamics::Full(full) => {
                let (state, workspace) = &mut **full;
                self.integrator.step_with(
                    &self.model,
                    state,
                    workspace,
                    dt,
                    &self.loads,
                    Some(tip_load),
                )?;
            }
            LinkDynamics::Modal { reduced, state } => {
                self.integrator.step_reduced_with(
                    reduced,
                    state,
                    dt,
                    &self.loads,
                    Some(tip_load),
                )?;
            }
        }
        Ok(())
    }
}

impl BeamLink {
    /// Sets the drive's law on a free hub for the next step: the stiffness and the damping
    /// (with the drive's friction) become the hub's torsion spring and damper to ground, the
    /// moment the root node's nodal moment. No effect on a link without a free hub.
    pub fn set_hub_law(&mut self, law: HubLaw) -> Result<(), RigError> {
        let Some(DrivenHub::Free {
            inertia, friction, ..
        }) = self.hub
        else {
            return Ok(());
        };
        self.set_root(RootSupport::Hub {
            inertia,
            k_theta: law.stiffness,
            c_theta: law.damping + friction,
        })?;
        self.loads.set_moment(0, law.moment)?;
        if let Some(DrivenHub::Free { law: l, .. }) = &mut self.hub {
            *l = law;
        }
        Ok(())
    }

    /// Rebuilds the model with the root support `root` (and a fresh workspace) if it has
    /// another.
    fn set_root(&mut self, root: RootSupport) -> Result<(), RigError> {
        if self.model.root() != root {
            let mut spec = self.model.spec().clone();
            spec.root = root;
            self.model = BeamModel::new(spec)?;
            if let LinkDynamics::Full(full) = &mut self.dynamics {
                full.1 = Workspace::new(&self.model);
            }
        }
        Ok(())
    }

    /// Keeps what a step changes in `into` (its buffers reused: no allocation once sized), so
    /// that [`BeamLink::restore`] can take the step again from here.
    pub fn save(&self, into: &mut Option<LinkCheckpoint>) {
        let c = into.get_or_insert_with(|| LinkCheckpoint {
            dynamics: self.saved_dynamics(),
            root: RootSupport::Clamped,
            law: None,
            hub_moment: 0.0,
        });
        match (&mut c.dynamics, &self.dynamics) {
            (SavedDynamics::Full(saved), LinkDynamics::Full(full)) => {
                saved.0.clone_from(&full.0);
                saved.1 = full.1.memory();
            }
            (SavedDynamics::Modal(saved), LinkDynamics::Modal { state, .. }) => {
                saved.clone_from(state)
            }
            (saved, _) => *saved = self.saved_dynamics(),
        }
        c.root = self.model.root();
        c.law = self.hub_law();
        c.hub_moment = self.loads.as_slice()[2];
    }

    /// The state part of a new [`LinkCheckpoint`].
    fn saved_dynamics(&self) -> SavedDynamics {
        match &self.dynamics {
            LinkDynamics::Full(full) => {
                SavedDynamics::Full(Box::new((full.0.clone(), full.1.memory())))
            }
            LinkDynamics::Modal { state, .. } => SavedDynamics::Modal(state.clone()),
        }
    }

    /// Puts the link back as [`BeamLink::save`] kept it: its state, its workspace's memory of
    /// the last step, the hub's support, law and moment.
    pub fn restore(&mut self, from: &LinkCheckpoint) -> Result<(), RigError> {
        self.set_root(from.root)?;
        match (&mut self.dynamics, &from.dynamics) {
            (LinkDynamics::Full(full), SavedDynamics::Full(saved)) => {
                full.0.clone_from(&saved.0);
                full.1.restore_memory(saved.1);
            }
            (LinkDynamics::Modal { state, .. }, SavedDynamics::Modal(saved)) => {
                state.clone_from(saved);
            }
            _ => unreachable!("a checkpoint of another link"),
        }
        self.loads.set_moment(0, from.hub_moment)?;
        if let (Some(DrivenHub::Free { law, .. }), Some(saved)) = (&mut self.hub, from.law) {
            *law = saved;
        }
        Ok(())
    }

    /// The drive's law on a free hub (the last set), or `None` (a prescribed or no hub).
    pub fn hub_law(&self) -> Option<HubLaw> {
        match &self.hub {
            Some(DrivenHub::Free { law, .. }) => Some(*law),
            _ => None,
        }
    }

    /// Sets the law at the start on a free hub and takes the start's accelerations again
    /// under it (the link in rigid rotation as built, its hub loaded by the drive at t = 0).
    pub fn start_hub_law(&mut self, law: HubLaw) -> Result<(), RigError> {
        self.set_hub_law(law)?;
        let (hub, _) = self.hub_motion();
        if let LinkDynamics::Full(full) = &mut self.dynamics {
            full.0 = State::in_rigid_rotation(
                &self.model,
                [hub.angle, hub.rate, 0.0],
                full.0.t,
                &self.loads,
            )?;
        }
        Ok(())
    }

    /// The hub's (root node's) angle and rate and its angular acceleration (rig convention,
    /// about +z) [rad, rad/s, rad/s²].
    pub fn hub_motion(&self) -> (HingeState, f64) {
        let (angle, rate, accel) = self.node_motion(0)[2];
        (HingeState { angle, rate }, accel)
    }

    /// The torque [N·m] about +z the hub applies to the link at the root: the clamped root's
    /// reaction (prescribed hub), or, on a free hub, the drive's law less the rotor's inertia
    /// and the friction (what the root's rotation row carries).
    pub fn root_moment(&self) -> f64 {
        match (&self.dynamics, &self.hub) {
            (LinkDynamics::Full(full), Some(DrivenHub::Prescribed(_))) => {
                flexrig_beam::root_reaction(&self.model, &full.0, &self.loads)[2]
            }
            (
                LinkDynamics::Full(full),
                Some(DrivenHub::Free {
                    inertia,
                    friction,
                    law,
                }),
            ) => {
                let (hub, accel) = self.hub_motion();
                let _ = full;
                law.torque(hub.angle, hub.rate) - friction * hub.rate - inertia * accel
            }
            _ => 0.0,
        }
    }

    /// Transverse deflection of the tip in the hub's frame \[m\] (positive about +z from the
    /// hub's line: d = −sin θ (L + u) + cos θ v, θ the root node's angle).
    pub fn tip_deflection_in_hub_frame(&self) -> f64 {
        let theta = self.node_motion(0)[2].0;
        let [u, v, _] = self.tip_dofs();
        let (sin, cos) = theta.sin_cos();
        -sin * (self.model.length() + u.0) + cos * v.0
    }
}
