//! flexrig-robot: a real arm from URDF, its multibody dynamics and the reflected mass at a
//! contact — the mass that strikes a person (no impact inside: the library joins it with the
//! compliant impact).
//!
//! - [`Robot::from_urdf_file`]: links, joints (revolute, continuous, prismatic, fixed), inertias
//!   in their `<inertial><origin>` frames (rpy rotations), limits, axes, origins; fixed joints
//!   merged into their parent (parallel-axis theorem). Unsupported or broken input (mimic
//!   joints, closed loops, floating/planar joints, moving links without mass, cycles, several
//!   roots, unknown link names, NaN/inf, non-physical inertias, negative masses, oversized files)
//!   is refused with a [`RobotError`] naming the element and its line.
//! - [`Robot::forward_kinematics`], [`Robot::mass_matrix`] (composite-rigid-body algorithm),
//!   [`Robot::point_jacobian`], with a reusable [`Workspace`].
//! - [`reflected_mass`] and [`Posture`]: m_u = 1 / (uᵀ J M⁻¹ Jᵀ u) (Khatib 1987; Haddadin et
//!   al. 2009) at a [`ContactPoint`] along a [`Direction`] for a [`JointModel`] (rigid, rigid
//!   with armature J_m N², elastic joints), by a Cholesky solve; `f64::INFINITY` when the arm
//!   cannot move the point along u.
//! - [`Trajectory`]: time and joint positions from CSV (or memory), joint velocities by
//!   second-order finite differences, and for each sample and contact point the position,
//!   velocity, contact direction and reflected mass ([`Trajectory::evaluate`]).
//!
//! - [`canonical`]: problems with closed-form references (the planar two-link arm), shared by
//!   tests, benches and validation.
//!
//! Units are SI: m, kg, s, rad; inertias kg·m².
//!
//! ```
//! use flexrig_robot::{ContactPoint, Direction, JointModel, Robot, reflected_mass};
//! // One link of 2 kg on a revolute joint about z; its centre of mass 0.5 m along x.
//! let urdf = r#"<robot name="one">
//!   <link name="base"/>
//!   <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
//!     <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
//!   <joint name="j" type="continuous"><parent link="base"/><child link="arm"/>
//!     <axis xyz="0 0 1"/></joint>
//! </robot>"#;
//! let robot = Robot::from_urdf_str(urdf, "one.urdf")?;
//! let mut ws = robot.workspace();
//! let tip = ContactPoint::new(&robot, "arm", [1.0, 0.0, 0.0])?;
//! let y = nalgebra::Vector3::y();
//! // A point mass m at r = 0.5 m struck at d = 1 m reflects m r²/d² = 0.5 kg.
//! let m = reflected_mass(&robot, &[0.0], &tip, Direction::Along(y), JointModel::Rigid, &mut ws)?;
//! assert!((m - 0.5).abs() < 1e-12);
//! // Along the link, the joint cannot move the point: a wall.
//! let x = nalgebra::Vector3::x();
//! let wall = reflected_mass(&robot, &[0.0], &tip, Direction::Along(x), JointModel::Rigid, &mut ws)?;
//! assert!(wall.is_infinite());
//! # Ok::<(), flexrig_robot::RobotError>(())
//! ```

pub mod canonical;
mod dynamics;
mod error;
mod inertia;
mod model;
mod reflected;
mod trajectory;
mod urdf;

pub use dynamics::{ContactPoint, Workspace};
pub use error::RobotError;
pub use inertia::{RigidInertia, inertia_problem, parallel_axis, pose_from_xyz_rpy};
pub use model::{Body, Joint, LinkFrame, Robot};
pub use reflected::{
    Direction, JointModel, PointSample, Posture, REST_SPEED, WALL_TOLERANCE, reflected_mass,
};
pub use trajectory::{MAX_CSV_BYTES, MAX_SAMPLES, Sample, Trajectory};
pub use urdf::{JointKind, MAX_JOINTS, MAX_LINKS, MAX_URDF_BYTES, MAX_XML_DEPTH, MAX_XML_TAGS};
