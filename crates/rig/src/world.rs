//! The Rapier world of the test bed: the operator pendulum (and, for CJ, the rigid robot link) as
//! reduced-coordinate (multibody) revolute joints on a fixed ground, with the pitfalls of
//! `notes/rapier.md` avoided: default joint damping zeroed, one solver iteration (plain
//! symplectic Euler: substeps would hold our forces constant over a step while moving the
//! bodies, which gains energy), no CCD, no sleeping, exact masses (no colliders; explicit mass
//! properties), the spring torque applied by us each step.

use flexrig_contact::BodyKinematics;
use flexrig_contact::math::{Pose, Vector};
use rapier3d_f64::glamx::DQuat;
use rapier3d_f64::parry::mass_properties::MassProperties;
use rapier3d_f64::prelude::{
    MultibodyJointHandle, PhysicsWorld, RevoluteJointBuilder, RigidBodyBuilder, RigidBodyHandle,
};

use crate::geometry::{OperatorGeometry, RobotGeometry};
pub use crate::hinge::HingeState;

/// A revolute joint of the world, with its axis.
#[derive(Debug, Clone, Copy)]
struct Hinge {
    body: RigidBodyHandle,
    joint: MultibodyJointHandle,
    axis: Vector,
    pivot: Vector,
}

/// The Rapier side of the rig.
pub struct RapierRig {
    world: PhysicsWorld,
    operator: Hinge,
    robot: Option<Hinge>,
    /// The drive's rotor on the robot axis (CJ with a motor that is not a prescribed trajectory).
    rotor: Option<Hinge>,
    /// The torque about the operator's pivot applied over the next step \[N·m\].
    operator_torque: f64,
    /// Whether [`Self::step`] leaves the world alone while it is at rest in equilibrium (true but
    /// in the test that compares a run with and without).
    skip_rest: bool,
}

impl std::fmt::Debug for RapierRig {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RapierRig").finish_non_exhaustive()
    }
}

impl RapierRig {
    /// The operator on its pivot (axis x) and, if `robot` is given, the rigid robot link on the
    /// robot axis (z through the origin).
    pub fn new(gravity: f64, operator: &OperatorGeometry, robot: Option<&RobotGeometry>) -> Self {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, 0.0, -gravity);
        let p = &mut world.integration_parameters;
        p.num_solver_iterations = 1;
        p.max_ccd_substeps = 0;
        let ground = world.insert_body(RigidBodyBuilder::fixed());

        let op_body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(operator.pivot)
                .additional_mass_properties(MassProperties::new(
                    Vector::new(0.0, 0.0, -operator.com_distance),
                    operator.mass,
                    operator.inertia_com,
                ))
                .can_sleep(false),
        );
        let op_joint = world
            .insert_multibody_joint(
                ground,
                op_body,
                RevoluteJointBuilder::new(Vector::X).local_anchor1(operator.pivot),
            )
            .expect("a joint between the ground and a new body forms no cycle");
        let operator_hinge = Hinge {
            body: op_body,
            joint: op_joint,
            axis: Vector::X,
            pivot: operator.pivot,
        };

        let robot_hinge = robot.map(|r| {
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .additional_mass_properties(MassProperties::new(
                        Vector::new(r.com_x, 0.0, 0.0),
                        r.link_mass + r.payload,
                        r.inertia_com,
                    ))
                    .can_sleep(false),
            );
            let joint = world
                .insert_multibody_joint(ground, body, RevoluteJointBuilder::new(Vector::Z))
                .expect("a joint between the ground and a new body forms no cycle");
            Hinge {
                body,
                joint,
                axis: Vector::Z,
                pivot: Vector::ZERO,
            }
        });
        let mut rig = RapierRig {
            world,
            operator: operator_hinge,
            robot: robot_hinge,
            rotor: None,
            operator_torque: 0.0,
            skip_rest: true,
        };
        rig.settle_multibody();
        rig
    }

    /// Adds the drive's rotor: a body turning about the robot axis (z through the origin) with
    /// moment of inertia `inertia` [kg·m²] about it (J_m N², the rotor as the joint sees it; its
    /// mass sits on the axis and does not enter the rotation).
    pub fn add_rotor(&mut self, inertia: f64) {
        let ground = self.world.insert_body(RigidBodyBuilder::fixed());
        let body = self.world.insert_body(
            RigidBodyBuilder::dynamic()
                .additional_mass_properties(MassProperties::new(
                    Vector::ZERO,
                    1.0,
                    Vector::new(inertia, inertia, inertia),
                ))
                .can_sleep(false),
        );
        let joint = self
            .world
            .insert_multibody_joint(ground, body, RevoluteJointBuilder::new(Vector::Z))
            .expect("a joint between the ground and a new body forms no cycle");
        let (mb, _) = self
            .world
            .multibody_joints
            .get_mut(joint)
            .expect("the rotor joint exists");
        mb.forward_kinematics(&self.world.bodies, true);
        mb.damping_mut().fill(0.0);
        self.rotor = Some(Hinge {
            body,
            joint,
            axis: Vector::Z,
            pivot: Vector::ZERO,
        });
    }

    /// Sets the rotor's hinge (if there is one) to `s`.
    pub fn set_rotor_state(&mut self, s: HingeState) {
        if let Some(h) = self.rotor {
            self.set_hinge(h.joint, s);
        }
    }

    /// The rotor's angle and rate (Rapier's: the rate half a step behind).
    pub fn rotor_state(&self) -> Option<HingeState> {
        self.rotor.as_ref().map(|h| self.hinge_state(h))
    }

    /// Applies `torque` [N·m] about the robot axis to the rotor over the next step (last step's
    /// cleared).
    pub fn apply_rotor_torque(&mut self, torque: f64) {
        if let Some(h) = self.rotor {
            let body = &mut self.world.bodies[h.body];
            body.reset_forces(false);
            body.reset_torques(false);
            body.add_torque(h.axis * torque, false);
        }
    }

    fn set_hinge(&mut self, joint: MultibodyJointHandle, s: HingeState) {
        let (mb, link) = self
            .world
            .multibody_joints
            .get_mut(joint)
            .expect("the joint exists");
        let a = mb.link(link).expect("the link exists").assembly_id();
        let current = mb.link(link).expect("the link exists").joint().coords()[3];
        let mut disp = vec![0.0; mb.ndofs()];
        disp[a] = s.angle - current;
        mb.apply_displacements(&disp);
        mb.generalized_velocity_mut()[a] = s.rate;
        mb.forward_kinematics(&self.world.bodies, true);
        mb.update_rigid_bodies(&mut self.world.bodies, true);
    }

    /// Brings the multibody to its final number of degrees of freedom and zeroes Rapier's hidden
    /// default joint damping (0.1 per DoF).
    fn settle_multibody(&mut self) {
        let (mb, _) = self
            .world
            .multibody_joints
            .get_mut(self.operator.joint)
            .expect("the operator joint exists");
        mb.forward_kinematics(&self.world.bodies, true);
        mb.damping_mut().fill(0.0);
    }

    /// Sets the hinge of the operator (and of the robot) to the given angle and rate.
    pub fn set_state(&mut self, operator: HingeState, robot: Option<HingeState>) {
        let mut targets = vec![(self.operator.joint, operator)];
        if let (Some(h), Some(s)) = (self.robot, robot) {
            targets.push((h.joint, s));
        }
        for (joint, s) in targets {
            self.set_hinge(joint, s);
        }
    }

    fn hinge_state(&self, hinge: &Hinge) -> HingeState {
        let (mb, link) = self
            .world
            .multibody_joints
            .get(hinge.joint)
            .expect("the joint exists");
        let l = mb.link(link).expect("the link exists");
        HingeState {
            angle: l.joint().coords()[3],
            rate: mb.generalized_velocity()[l.assembly_id()],
        }
    }

    /// Operator angle (from the vertical, positive towards the robot) and rate.
    pub fn operator_state(&self) -> HingeState {
        self.hinge_state(&self.operator)
    }

    /// Robot angle and rate (CJ only).
    pub fn robot_state(&self) -> Option<HingeState> {
        self.robot.as_ref().map(|h| self.hinge_state(h))
    }

    fn kinematics(&self, hinge: &Hinge) -> BodyKinematics {
        Self::kinematics_at(hinge, self.hinge_state(hinge))
    }

    fn kinematics_at(hinge: &Hinge, s: HingeState) -> BodyKinematics {
        BodyKinematics {
            pose: Pose::from_parts(hinge.pivot, DQuat::from_axis_angle(hinge.axis, s.angle)),
            reference_point: hinge.pivot,
            linvel: Vector::ZERO,
            angvel: hinge.axis * s.rate,
        }
    }

    /// Pose and velocity of the operator body (frame origin at the pivot).
    pub fn operator_kinematics(&self) -> BodyKinematics {
        self.kinematics(&self.operator)
    }

    /// Pose and velocity the operator body would have in the hinge state `s`.
    pub fn operator_kinematics_at(&self, s: HingeState) -> BodyKinematics {
        Self::kinematics_at(&self.operator, s)
    }

    /// Pose and velocity the robot body would have in the hinge state `s` (CJ only; the robot
    /// axis).
    pub fn robot_kinematics_at(&self, s: HingeState) -> BodyKinematics {
        let hinge = self.robot.unwrap_or(Hinge {
            body: self.operator.body,
            joint: self.operator.joint,
            axis: Vector::Z,
            pivot: Vector::ZERO,
        });
        Self::kinematics_at(&hinge, s)
    }

    /// Pose and velocity of the robot body (frame origin on the axis), CJ only.
    pub fn robot_kinematics(&self) -> Option<BodyKinematics> {
        self.robot.as_ref().map(|h| self.kinematics(h))
    }

    /// Clears last step's forces, then applies the torques `operator_torque` about the operator's
    /// pivot axis and `robot_torque` about the robot axis (CJ) [N·m], held over the next step
    /// (Rapier adds gravity itself).
    pub fn apply_torques(&mut self, operator_torque: f64, robot_torque: f64) {
        self.operator_torque = operator_torque;
        let hinges = [Some(self.operator), self.robot];
        for (hinge, torque) in hinges.into_iter().zip([operator_torque, robot_torque]) {
            if let Some(h) = hinge {
                let body = &mut self.world.bodies[h.body];
                body.reset_forces(false);
                body.reset_torques(false);
                body.add_torque(h.axis * torque, false);
            }
        }
    }

    /// Advances the world by `dt` \[s\] (symplectic Euler). A world at rest in equilibrium
    /// ([`Self::at_rest_in_equilibrium`]) is left as it is: Rapier's step would leave it bit for
    /// bit the same (tested), so the step is skipped (the driven link's approach, with the
    /// operator hanging at rest, steps Rapier thousands of times for nothing).
    pub fn step(&mut self, dt: f64) {
        if self.skip_rest && self.at_rest_in_equilibrium() {
            return;
        }
        self.world.integration_parameters.dt = dt;
        self.world.step();
    }

    /// True when the world holds the operator alone (no rigid robot link, no rotor), hanging
    /// straight down (angle 0, where gravity's moment about the pivot vanishes) at rest with no
    /// torque applied: the exact equilibrium, which a step leaves unchanged. The angle and the
    /// rate are the positive zero (a step turns a rate of −0 into +0).
    pub(crate) fn at_rest_in_equilibrium(&self) -> bool {
        let s = self.operator_state();
        self.robot.is_none()
            && self.rotor.is_none()
            && self.operator_torque == 0.0
            && s.angle.to_bits() == 0
            && s.rate.to_bits() == 0
    }

    /// Makes [`Self::step`] step Rapier even at rest (to compare a run with the skip).
    #[cfg(test)]
    pub(crate) fn step_even_at_rest(&mut self) {
        self.skip_rest = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An operator of the given pivot, arm and masses (a rod with the block at its end).
    fn operator(pivot: Vector, arm: f64, arm_mass: f64, block_mass: f64) -> OperatorGeometry {
        let mass = arm_mass + block_mass;
        let com = (0.5 * arm_mass * arm + block_mass * arm) / mass;
        let inertia_pivot = arm_mass * arm * arm / 3.0 + block_mass * arm * arm;
        let about_com = inertia_pivot - mass * com * com;
        OperatorGeometry {
            pivot,
            arm_length: arm,
            mass,
            com_distance: com,
            inertia_pivot,
            inertia_com: Vector::new(about_com, about_com, 1e-4 * block_mass),
            block_half_extents: Vector::splat(0.0264),
            block_center_local: Vector::new(0.0, 0.0, -arm),
        }
    }

    /// The skip is exact: Rapier's own step leaves the operator hanging at rest (angle and rate
    /// zero, no torque, of either sign) bit for bit as it was, over many steps of different
    /// sizes, for pivots off the origin, light and heavy pendulums and Earth's and other
    /// gravities. A rate of −0 becomes +0 in a step, so the skip waits for that step.
    #[test]
    fn a_step_leaves_the_operator_at_rest_in_equilibrium_bit_for_bit() {
        let pivots = [
            Vector::new(0.33802, -0.0979, 0.30),
            Vector::new(0.1, -0.05, 0.3),
            Vector::new(-1.7, 3.1, 0.9),
        ];
        let mut cases = 0;
        for (pivot, (arm, arm_mass, block_mass)) in
            pivots
                .into_iter()
                .zip([(0.30, 0.030, 0.3978), (0.45, 0.2, 2.5), (0.12, 0.01, 0.05)])
        {
            for gravity in [9.81, 1.62, 24.8] {
                for zero in [0.0, -0.0] {
                    let mut rig =
                        RapierRig::new(gravity, &operator(pivot, arm, arm_mass, block_mass), None);
                    rig.step_even_at_rest();
                    let rest = HingeState {
                        angle: zero,
                        rate: zero,
                    };
                    rig.set_state(rest, None);
                    let set = rig.operator_state();
                    rig.apply_torques(zero, 0.0);
                    assert_eq!(rig.at_rest_in_equilibrium(), set.rate.to_bits() == 0);
                    rig.step(6e-4);
                    let start = rig.operator_state();
                    assert_eq!((start.angle.to_bits(), start.rate.to_bits()), (0, 0));
                    for k in 0..500 {
                        let torque = if k % 2 == 0 { zero } else { -zero };
                        rig.apply_torques(torque, 0.0);
                        assert!(rig.at_rest_in_equilibrium());
                        rig.step([6e-4, 1e-5, 4.36e-6, 2e-3][k % 4]);
                        let s = rig.operator_state();
                        assert_eq!(
                            (s.angle.to_bits(), s.rate.to_bits()),
                            (start.angle.to_bits(), start.rate.to_bits()),
                            "pivot {pivot:?}, g {gravity}, step {k}: {s:?} from {start:?}"
                        );
                    }
                    cases += 1;
                }
            }
        }
        assert_eq!(cases, 18);
    }

    /// The skip's condition holds only in the equilibrium: off it (an angle, a rate or a torque
    /// however small) Rapier steps the operator, and it moves.
    #[test]
    fn out_of_equilibrium_the_operator_is_stepped() {
        let op = operator(Vector::new(0.33802, -0.0979, 0.30), 0.30, 0.030, 0.3978);
        for (angle, rate, torque) in [(1e-12, 0.0, 0.0), (0.0, 1e-12, 0.0), (0.0, 0.0, 1e-12)] {
            let mut rig = RapierRig::new(9.81, &op, None);
            rig.set_state(HingeState { angle, rate }, None);
            rig.apply_torques(torque, 0.0);
            assert!(!rig.at_rest_in_equilibrium());
            let before = rig.operator_state();
            for _ in 0..10 {
                rig.apply_torques(torque, 0.0);
                rig.step(6e-4);
            }
            let after = rig.operator_state();
            assert!(
                after.angle != before.angle && after.rate != before.rate,
                "{before:?} → {after:?} (angle {angle}, rate {rate}, torque {torque})"
            );
        }
    }
}
