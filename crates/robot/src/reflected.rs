//! The reflected mass of the arm at a contact point along a direction: the mass that a person
//! struck at that point along that direction feels, the arm's joints behaving as the
//! [`JointModel`] says.
//!
//! # Formula
//!
//! With M(q) the joint-space mass matrix and J(q) the point's Jacobian (linear velocity in the
//! base frame, v = J q̇), the operational-space (Cartesian) inertia of the point is
//! Λ = (J M⁻¹ Jᵀ)⁻¹ (O. Khatib, "A unified approach for motion and force control of robot
//! manipulators: the operational space formulation", IEEE J. Robotics and Automation 3(1),
//! 1987), and the mass it reflects along a unit direction u is
//!
//! m_u = 1 / (uᵀ J M⁻¹ Jᵀ u)
//!
//! (S. Haddadin, A. Albu-Schäffer, G. Hirzinger, "Requirements for safe robots: measurements,
//! analysis and new insights", Int. J. Robotics Research 28(11–12), 2009, §3; the same
//! expression is the mass matrix's inverse projected on u, without forming Λ). The impulse p
//! along u at the contact changes the joint rates by M⁻¹ Jᵀ u p and the point's speed along u by
//! uᵀ J M⁻¹ Jᵀ u p, so 1/m_u is the point's mobility along u. It is computed with a Cholesky
//! factorisation M = L Lᵀ and one solve M x = Jᵀ u per point and direction, never an explicit
//! inverse: 1/m_u = (Jᵀu)ᵀ x.
//!
//! # Joint models
//!
//! - [`JointModel::Rigid`]: the links alone, M from the URDF's link inertias.
//! - [`JointModel::RigidWithArmature`]: a stiff drive train moves the rotor with the link, so
//!   the rotor inertia reflected through the gear, J_m N² (kg·m², or kg for a prismatic joint),
//!   adds to the diagonal of M (the usual armature model; rotor gyroscopic coupling neglected).
//! - [`JointModel::Elastic`]: series elastic actuators. During the impact's few milliseconds the
//!   joint spring decouples the rotor from the link: the link is struck and decelerates before
//!   the spring has deflected enough to pass any appreciable force to the rotor, so the rotor
//!   inertia does not take part and only the link inertias are reflected (Haddadin et al.,
//!   IJRR 2009, §3–4, who show the decoupling for the DLR lightweight robot's elastic joints;
//!   the same argument underlies the compliant-joint case of the flexrig paper, Eq. 10–14). The
//!   number is then the rigid one without armature; the model is named separately so that the
//!   choice is explicit where the mass is used.
//!
//! # When the point cannot move along u
//!
//! If Jᵀ u = 0 — no joint can move the point along u (a point on the base, or u along a
//! direction that the arm's Jacobian cannot reach at this posture) — the arm behaves as a wall
//! along u: the reflected mass is **+∞**, returned as `f64::INFINITY` (a documented value, not an
//! error; the impact code treats it as a wall). "Zero" means ‖Jᵀu‖ ≤ 1e-12 ‖J‖_F; close to such
//! a posture the mass is large and finite.

use nalgebra::{Matrix3xX, Unit, Vector3};

use crate::dynamics::{ContactPoint, Workspace, cholesky_solve, point_world};
use crate::error::RobotError;
use crate::model::Robot;

/// The relative size of ‖Jᵀu‖ against ‖J‖_F below which the point cannot move along u.
pub const WALL_TOLERANCE: f64 = 1e-12;

/// Below this speed (m/s) a contact point is taken to be at rest: no direction, no mass.
pub const REST_SPEED: f64 = 1e-9;

/// One contact point in motion at one posture ([`Posture::motion`]).
#[derive(Debug, Clone, PartialEq)]
pub struct PointSample {
    /// World position, m.
    pub position: Vector3<f64>,
    /// World velocity J q̇, m/s.
    pub velocity: Vector3<f64>,
    /// |velocity|, m/s.
    pub speed: f64,
    /// The contact direction (the velocity's direction); `None` when the point is at rest
    /// (speed ≤ [`REST_SPEED`]).
    pub direction: Option<Unit<Vector3<f64>>>,
    /// The reflected mass along the direction, kg (`f64::INFINITY`: the arm cannot move the
    /// point along it); `None` when the point is at rest.
    pub reflected_mass: Option<f64>,
}

/// How the joints behave on the impact's time scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointModel<'a> {
    /// Rigid joints, link inertias only.
    Rigid,
    /// Rigid joints with the rotor inertia reflected through the gear, J_m N² per joint
    /// (kg·m² for revolute joints, kg for prismatic ones; ≥ 0, in degree-of-freedom order).
    RigidWithArmature(&'a [f64]),
    /// Elastic joints (series elastic actuators): the rotors are decoupled on the impact's
    /// time scale and do not contribute; link inertias only.
    Elastic,
}

/// The direction along which the mass is reflected.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Direction<'a> {
    /// A unit vector in the base frame (its norm must be 1 within 1e-6; it is normalised).
    Along(Vector3<f64>),
    /// The direction of the point's own velocity J q̇ at these joint velocities (rad/s or m/s,
    /// degree-of-freedom order); refused if the point does not move.
    OfVelocity(&'a [f64]),
}

/// The arm at one posture with its mass matrix factored: position, Jacobian, velocity and
/// reflected mass of any number of contact points at the cost of one factorisation.
#[derive(Debug)]
pub struct Posture<'r, 'w> {
    robot: &'r Robot,
    ws: &'w mut Workspace,
}

impl<'r, 'w> Posture<'r, 'w> {
    /// Forward kinematics, the mass matrix (plus the armature of `joint_model`) and its
    /// Cholesky factor at `q` (rad or m).
    pub fn new(
        robot: &'r Robot,
        q: &[f64],
        joint_model: JointModel,
        ws: &'w mut Workspace,
    ) -> Result<Self, RobotError> {
        let armature = match joint_model {
            JointModel::RigidWithArmature(a) => {
                check_armature(robot, a)?;
                Some(a)
            }
            JointModel::Rigid | JointModel::Elastic => None,
        };
        robot.forward_kinematics(q, ws)?;
        robot.fill_mass_matrix(ws);
        robot.factor_mass_matrix(armature, ws)?;
        Ok(Posture { robot, ws })
    }

    /// The robot.
    pub fn robot(&self) -> &Robot {
        self.robot
    }

    /// The world position of the point, m.
    pub fn position(&self, point: &ContactPoint) -> Result<Vector3<f64>, RobotError> {
        self.robot.check_point(point)?;
        Ok(point_world(self.ws, point))
    }

    /// The point Jacobian (3 × dof, base frame).
    pub fn jacobian(&mut self, point: &ContactPoint) -> Result<&Matrix3xX<f64>, RobotError> {
        self.robot.check_point(point)?;
        self.robot.fill_point_jacobian(point, self.ws);
        Ok(&self.ws.jac)
    }

    /// The point's velocity J q̇ (m/s, base frame) at joint velocities `qdot` (rad/s or m/s).
    pub fn velocity(
        &mut self,
        point: &ContactPoint,
        qdot: &[f64],
    ) -> Result<Vector3<f64>, RobotError> {
        self.robot.check_vector("qdot", qdot, "rad/s or m/s")?;
        let j = self.jacobian(point)?;
        let mut v = Vector3::zeros();
        for (i, qd) in qdot.iter().enumerate() {
            v += j.column(i) * *qd;
        }
        Ok(v)
    }

    /// The inverse reflected mass uᵀ J M⁻¹ Jᵀ u (1/kg) along `direction`; 0 when the point
    /// cannot move along u (module documentation).
    pub fn inverse_reflected_mass(
        &mut self,
        point: &ContactPoint,
        direction: Direction,
    ) -> Result<f64, RobotError> {
        let u = self.unit_direction(point, direction)?;
        self.robot.fill_point_jacobian(point, self.ws);
        Ok(self.inverse_along(&u))
    }

    /// uᵀ J M⁻¹ Jᵀ u with the Jacobian already in the workspace.
    fn inverse_along(&mut self, u: &Vector3<f64>) -> f64 {
        let ws = &mut *self.ws;
        let n = ws.jac.ncols();
        let mut g2 = 0.0;
        for i in 0..n {
            let g = ws.jac.column(i).dot(u);
            ws.rhs[i] = g;
            g2 += g * g;
        }
        let j2 = ws.jac.norm_squared();
        if !(g2 > WALL_TOLERANCE * WALL_TOLERANCE * j2) {
            return 0.0;
        }
        cholesky_solve(ws);
        ws.rhs.dot(&ws.sol)
    }

    /// Everything about a contact point moving at joint velocities `qdot` (rad/s or m/s) at
    /// the cost of one Jacobian: position, velocity, speed, the contact direction (the
    /// velocity's) and the reflected mass along it; no direction and no mass when the point is
    /// at rest (speed ≤ [`REST_SPEED`]).
    pub fn motion(
        &mut self,
        point: &ContactPoint,
        qdot: &[f64],
    ) -> Result<PointSample, RobotError> {
        self.robot.check_point(point)?;
        self.robot.check_vector("qdot", qdot, "rad/s or m/s")?;
        self.robot.fill_point_jacobian(point, self.ws);
        let position = point_world(self.ws, point);
        let mut velocity = Vector3::zeros();
        for (i, qd) in qdot.iter().enumerate() {
            velocity += self.ws.jac.column(i) * *qd;
        }
        let speed = velocity.norm();
        let (direction, reflected_mass) = if speed > REST_SPEED {
            let u = Unit::new_unchecked(velocity / speed);
            let inv = self.inverse_along(&u);
            (
                Some(u),
                Some(if inv > 0.0 { 1.0 / inv } else { f64::INFINITY }),
            )
        } else {
            (None, None)
        };
        Ok(PointSample {
            position,
            velocity,
            speed,
            direction,
            reflected_mass,
        })
    }

    /// The reflected mass m_u = 1 / (uᵀ J M⁻¹ Jᵀ u), kg, along `direction`; `f64::INFINITY`
    /// when the point cannot move along u (module documentation).
    pub fn reflected_mass(
        &mut self,
        point: &ContactPoint,
        direction: Direction,
    ) -> Result<f64, RobotError> {
        let inv = self.inverse_reflected_mass(point, direction)?;
        Ok(if inv > 0.0 { 1.0 / inv } else { f64::INFINITY })
    }

    fn unit_direction(
        &mut self,
        point: &ContactPoint,
        direction: Direction,
    ) -> Result<Unit<Vector3<f64>>, RobotError> {
        match direction {
            Direction::Along(u) => {
                let norm = u.norm();
                if !((norm - 1.0).abs() <= 1e-6) {
                    return Err(RobotError::parameter(
                        "the norm of direction",
                        norm,
                        "a unit vector in the base frame (norm 1 within 1e-6)",
                    ));
                }
                self.robot.check_point(point)?;
                Ok(Unit::new_normalize(u))
            }
            Direction::OfVelocity(qdot) => {
                let v = self.velocity(point, qdot)?;
                let speed = v.norm();
                if !(speed > 0.0) {
                    return Err(RobotError::PointAtRest {
                        link: point.link().to_string(),
                        speed,
                    });
                }
                Ok(Unit::new_normalize(v))
            }
        }
    }
}

fn check_armature(robot: &Robot, armature: &[f64]) -> Result<(), RobotError> {
    robot.check_vector("armature", armature, "kg·m² or kg")?;
    for (i, a) in armature.iter().enumerate() {
        if *a < 0.0 {
            return Err(RobotError::parameter(
                format!("armature[{i}] ({})", robot.joints()[i].name()),
                a,
                "≥ 0 (the rotor inertia reflected through the gear, J_m N², kg·m² or kg)",
            ));
        }
    }
    Ok(())
}

/// The reflected mass (kg) of `robot` at joint positions `q` (rad or m), at `point`, along
/// `direction`, with joints behaving as `joint_model`: m_u = 1 / (uᵀ J M⁻¹ Jᵀ u) (module
/// documentation); `f64::INFINITY` when the point cannot move along u. For many points at one
/// posture, make one [`Posture`] and ask it for each.
pub fn reflected_mass(
    robot: &Robot,
    q: &[f64],
    point: &ContactPoint,
    direction: Direction,
    joint_model: JointModel,
    ws: &mut Workspace,
) -> Result<f64, RobotError> {
    Posture::new(robot, q, joint_model, ws)?.reflected_mass(point, direction)
}
