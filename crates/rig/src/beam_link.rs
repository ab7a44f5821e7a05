//! The compliant link (CL): a flexrig-beam finite-element beam clamped at the robot axis, bending
//! in the horizontal plane (its local x along the world x, its transverse v along the world y),
//! with the payload as a point mass at the tip node and the dome rigidly attached to the tip
//! section. It advances with the same step as the Rapier world, either with every FE degree of
//! freedom or, as the shortcut for small deflections, modal-reduced (the scene's
//! `solver.beam`).

use flexrig_beam::{
    BeamModel, BeamSpec, GeneralizedAlpha, Kinematics, Material, NodalLoads, NodeLoad, PointMass,
    ReducedModel, ReducedState, RootSupport, Section, State, Workspace,
};
use flexrig_contact::BodyKinematics;
use flexrig_contact::math::Vector;

use crate::RigError;
use crate::coupling::section_kinematics;
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
}

/// The FE link with its state and scratch space.
#[derive(Debug, Clone)]
pub struct BeamLink {
    model: BeamModel,
    dynamics: LinkDynamics,
    integrator: GeneralizedAlpha,
    loads: NodalLoads,
    tip: usize,
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
        let solver = scene.file.solver.beam.resolve(scene.file.stop);
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
        spec.point_masses.push(PointMass {
            node: r.beam_elements,
            mass: r.payload_kg,
            inertia: 0.0,
        });
        let model = BeamModel::new(spec)?;
        let loads = NodalLoads::zeros(&model);
        let tip = model.tip_node();
        let dynamics = match solver {
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

    /// Kinetic plus strain energy \[J\].
    pub fn energy(&self) -> f64 {
        match &self.dynamics {
            LinkDynamics::Full(full) => {
                let e = full.0.energy(&self.model);
                e.kinetic + e.strain
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
    pub fn step(&mut self, dt: f64, tip_load: &mut dyn NodeLoad) -> Result<(), RigError> {
        match &mut self.dynamics {
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
