//! Canonical problems with closed-form references, shared by the tests, the benches and (later)
//! the library's validation: each gives the robot and its reference numbers.

use crate::error::RobotError;
use crate::model::Robot;

/// The planar elbow arm: two links turning about parallel z axes, the second hinged at the end
/// of the first (M. W. Spong, S. Hutchinson, M. Vidyasagar, *Robot Modeling and Control*,
/// Wiley 2006, §7.3.3). Link k has length `l_k` (m), mass `m_k` (kg), its centre of mass `lc_k`
/// (m) along it, and the inertia `i_k` (kg·m²) about the z axis through its centre of mass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarTwoLink {
    /// Length of link 1 (shoulder to elbow), m.
    pub l1: f64,
    /// Length of link 2 (elbow to tip), m.
    pub l2: f64,
    /// Centre of mass of link 1 from the shoulder, m.
    pub lc1: f64,
    /// Centre of mass of link 2 from the elbow, m.
    pub lc2: f64,
    /// Mass of link 1, kg.
    pub m1: f64,
    /// Mass of link 2, kg.
    pub m2: f64,
    /// Inertia of link 1 about z through its centre of mass, kg·m².
    pub i1: f64,
    /// Inertia of link 2 about z through its centre of mass, kg·m².
    pub i2: f64,
}

impl PlanarTwoLink {
    /// An arm of human-forearm size, the one the tests use: l = 0.7, 0.5 m; centres of mass at
    /// 0.31, 0.22 m; 3.2, 1.9 kg; 0.11, 0.043 kg·m².
    pub fn example() -> Self {
        PlanarTwoLink {
            l1: 0.7,
            l2: 0.5,
            lc1: 0.31,
            lc2: 0.22,
            m1: 3.2,
            m2: 1.9,
            i1: 0.11,
            i2: 0.043,
        }
    }

    /// Its URDF: links `link1`, `link2` along x, continuous joints `shoulder` and `elbow` about
    /// z; the tip is (l2, 0, 0) on `link2`.
    pub fn urdf(&self) -> String {
        let PlanarTwoLink {
            l1,
            lc1,
            lc2,
            m1,
            m2,
            i1,
            i2,
            ..
        } = *self;
        format!(
            r#"<robot name="planar_two_link">
  <link name="base"/>
  <link name="link1"><inertial><origin xyz="{lc1} 0 0"/><mass value="{m1}"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="{i1}" iyz="0" izz="{i1}"/></inertial></link>
  <link name="link2"><inertial><origin xyz="{lc2} 0 0"/><mass value="{m2}"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="{i2}" iyz="0" izz="{i2}"/></inertial></link>
  <joint name="shoulder" type="continuous"><parent link="base"/><child link="link1"/>
    <axis xyz="0 0 1"/></joint>
  <joint name="elbow" type="continuous"><parent link="link1"/><child link="link2"/>
    <origin xyz="{l1} 0 0"/><axis xyz="0 0 1"/></joint>
</robot>"#
        )
    }

    /// The robot, loaded from [`PlanarTwoLink::urdf`] (its checks refuse non-physical values).
    pub fn robot(&self) -> Result<Robot, RobotError> {
        Robot::from_urdf_str(&self.urdf(), "planar_two_link.urdf")
    }

    /// The textbook mass matrix at (q1, q2) (rad): M11 = m1 lc1² + m2 (l1² + lc2² +
    /// 2 l1 lc2 cos q2) + I1 + I2, M12 = m2 (lc2² + l1 lc2 cos q2) + I2, M22 = m2 lc2² + I2.
    pub fn mass_matrix(&self, q: [f64; 2]) -> [[f64; 2]; 2] {
        let c2 = q[1].cos();
        let m11 = self.m1 * self.lc1 * self.lc1
            + self.m2 * (self.l1 * self.l1 + self.lc2 * self.lc2 + 2.0 * self.l1 * self.lc2 * c2)
            + self.i1
            + self.i2;
        let m12 = self.m2 * (self.lc2 * self.lc2 + self.l1 * self.lc2 * c2) + self.i2;
        let m22 = self.m2 * self.lc2 * self.lc2 + self.i2;
        [[m11, m12], [m12, m22]]
    }

    /// The tip's reflected mass (kg) along the in-plane unit direction `u` at (q1, q2): with
    /// J = [[−l1 s1 − l2 s12, −l2 s12], [l1 c1 + l2 c12, l2 c12]] and M⁻¹ by the 2 × 2 adjugate,
    /// 1 / (uᵀ J M⁻¹ Jᵀ u); `f64::INFINITY` where Jᵀu = 0 exactly.
    pub fn tip_reflected_mass(&self, q: [f64; 2], u: [f64; 2]) -> f64 {
        let (s1, c1) = q[0].sin_cos();
        let (s12, c12) = (q[0] + q[1]).sin_cos();
        let j = [
            [-self.l1 * s1 - self.l2 * s12, -self.l2 * s12],
            [self.l1 * c1 + self.l2 * c12, self.l2 * c12],
        ];
        let m = self.mass_matrix(q);
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let g = [
            j[0][0] * u[0] + j[1][0] * u[1],
            j[0][1] * u[0] + j[1][1] * u[1],
        ];
        let inv = (g[0] * (m[1][1] * g[0] - m[0][1] * g[1])
            + g[1] * (-m[1][0] * g[0] + m[0][0] * g[1]))
            / det;
        if inv == 0.0 { f64::INFINITY } else { 1.0 / inv }
    }
}
