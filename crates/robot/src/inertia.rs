//! Rigid-body inertia: mass, centre of mass and rotational inertia about the centre of mass, in
//! one frame; moving it to another frame and combining bodies (parallel-axis theorem).

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};

/// The pose given by a URDF `<origin xyz rpy>`: translation `xyz` (m), then the fixed-axis
/// roll–pitch–yaw rotation `rpy` (rad), R = Rz(yaw) · Ry(pitch) · Rx(roll) (URDF convention).
pub fn pose_from_xyz_rpy(xyz: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    let rotation = Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]);
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_rotation_matrix(&rotation),
    )
}

/// Inertia of a rigid body expressed in one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidInertia {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass in the frame, m.
    pub com: Vector3<f64>,
    /// Rotational inertia about the centre of mass, axes of the frame, kg·m².
    pub inertia: Matrix3<f64>,
}

impl RigidInertia {
    /// No mass at all (the neutral element of [`RigidInertia::combined`]).
    pub fn zero() -> Self {
        RigidInertia {
            mass: 0.0,
            com: Vector3::zeros(),
            inertia: Matrix3::zeros(),
        }
    }

    /// The same body expressed in the frame in which `pose` places this body's frame:
    /// c' = R c + p, I' = R I Rᵀ.
    pub fn transformed(&self, pose: &Isometry3<f64>) -> Self {
        let r = pose.rotation.to_rotation_matrix().into_inner();
        RigidInertia {
            mass: self.mass,
            com: (pose * nalgebra::Point3::from(self.com)).coords,
            inertia: r * self.inertia * r.transpose(),
        }
    }

    /// Two bodies rigidly joined, both expressed in the same frame: m = m₁ + m₂,
    /// c = (m₁c₁ + m₂c₂)/m, I = Σ Iₖ + mₖ(|dₖ|² 1 − dₖdₖᵀ) with dₖ = cₖ − c (parallel axes).
    pub fn combined(&self, other: &RigidInertia) -> Self {
        let mass = self.mass + other.mass;
        if mass == 0.0 {
            return RigidInertia {
                mass: 0.0,
                com: Vector3::zeros(),
                inertia: self.inertia + other.inertia,
            };
        }
        let com = (self.com * self.mass + other.com * other.mass) / mass;
        let inertia = self.inertia
            + parallel_axis(self.mass, &(self.com - com))
            + other.inertia
            + parallel_axis(other.mass, &(other.com - com));
        RigidInertia { mass, com, inertia }
    }
}

/// The parallel-axis term m(|d|² 1 − d dᵀ), kg·m².
pub fn parallel_axis(mass: f64, d: &Vector3<f64>) -> Matrix3<f64> {
    mass * (Matrix3::identity() * d.norm_squared() - d * d.transpose())
}

/// Why an inertia tensor is not one of a physical body, if it is not: its principal moments
/// must be non-negative and satisfy the triangle inequality (each at most the sum of the other
/// two), both up to a relative round-off tolerance of 1e-10 of the largest moment.
pub fn inertia_problem(inertia: &Matrix3<f64>) -> Option<String> {
    let eig = nalgebra::SymmetricEigen::new(*inertia).eigenvalues;
    let mut e = [eig[0], eig[1], eig[2]];
    e.sort_by(f64::total_cmp);
    let tol = 1e-10 * e[2].abs();
    if e[0] < -tol {
        return Some(format!(
            "the inertia tensor is not positive semi-definite: its principal moments are \
             {:e}, {:e}, {:e} kg·m²; all must be ≥ 0",
            e[0], e[1], e[2]
        ));
    }
    if e[0] + e[1] < e[2] - tol {
        return Some(format!(
            "the inertia tensor violates the triangle inequality: its principal moments {:e} + \
             {:e} < {:e} kg·m² (no rigid body has them; each must be at most the sum of the \
             other two)",
            e[0], e[1], e[2]
        ));
    }
    None
}
