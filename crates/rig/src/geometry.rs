//! The test bed's geometry, masses and inertias, derived once from a [`Scene`].
//!
//! Default layout (`docs/scenes.md`): the robot axis is the world z axis (vertical) through the
//! origin and the link lies along +x, so gravity (−z) does not load its spring; the dome apex sits
//! at (L, −a, 0), facing −y. The operator pendulum turns about an axis parallel to x through
//! the pivot (L, −a − b/2, l), its arm hanging along −z; at the bottom of the swing the block's
//! +y face (size b along y) touches the apex, so the strike is horizontal, along +y.
//!
//! Idealisations: the link is a slender rod (J = m_r L²/3 about the axis; its width adds
//! m_r w²/12, under 1 % here); the payload (sensor and dome included) is a point mass at the tip;
//! the operator arm is a uniform rod from the pivot to the block centre.

use flexrig_contact::math::Vector;

use crate::scene::Scene;
pub use crate::scene::rate_at_bottom;

/// The operator pendulum.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OperatorGeometry {
    /// Pivot [m, world].
    pub pivot: Vector,
    /// Pivot to block centre l \[m\].
    pub arm_length: f64,
    /// Total mass M \[kg\].
    pub mass: f64,
    /// Pivot to centre of mass l_c \[m\].
    pub com_distance: f64,
    /// Moment of inertia about the pivot axis J [kg·m²].
    pub inertia_pivot: f64,
    /// Principal moments of inertia about the centre of mass (x, y, z body axes) [kg·m²].
    pub inertia_com: Vector,
    /// Block half extents \[m\].
    pub block_half_extents: Vector,
    /// Block centre in the operator body frame (origin at the pivot) \[m\].
    pub block_center_local: Vector,
}

impl OperatorGeometry {
    /// Angular speed [rad/s] at the bottom of a swing released at rest from `angle_rad`:
    /// ω² = 2 M g l_c (1 − cos θ₀)/J.
    pub fn bottom_angular_speed(&self, angle_rad: f64, gravity: f64) -> f64 {
        rate_at_bottom(
            self.mass,
            self.com_distance,
            self.inertia_pivot,
            gravity,
            angle_rad,
            0.0,
        )
    }

    /// Mass \[kg\] the pendulum presents to a horizontal force at the contact height (l below the
    /// pivot): J/l².
    pub fn effective_mass(&self) -> f64 {
        self.inertia_pivot / (self.arm_length * self.arm_length)
    }
}

/// The robot link (rigid, for CJ) with its payload and dome.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotGeometry {
    /// Link length L \[m\].
    pub length: f64,
    /// Link mass m_r \[kg\].
    pub link_mass: f64,
    /// Payload m_e \[kg\].
    pub payload: f64,
    /// Moment of inertia about the robot axis, m_r L²/3 + m_e L² [kg·m²].
    pub inertia_axis: f64,
    /// Centre of mass along the link \[m\].
    pub com_x: f64,
    /// Principal moments of inertia about the centre of mass [kg·m²].
    pub inertia_com: Vector,
    /// Dome radius \[m\].
    pub dome_radius: f64,
    /// Dome ball centre in the robot body frame (origin on the axis) \[m\].
    pub dome_center_local: Vector,
}

impl RobotGeometry {
    /// Mass \[kg\] the rigid link presents at its tip to a force along y: J/L² = m_e + m_r/3
    /// (Eq. 5 with γ = 1).
    pub fn effective_mass(&self) -> f64 {
        self.inertia_axis / (self.length * self.length)
    }
}

/// Both parts of the rig.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigGeometry {
    /// The operator pendulum.
    pub operator: OperatorGeometry,
    /// The robot link.
    pub robot: RobotGeometry,
}

impl RigGeometry {
    /// The geometry of `scene`.
    pub fn of(scene: &Scene) -> Self {
        let r = &scene.file.robot;
        let (length, m_r, m_e) = (r.length_m, scene.link_mass_kg, r.payload_kg);
        let inertia_axis = m_r * length * length / 3.0 + m_e * length * length;
        let mass_r = m_r + m_e;
        let com_x = (m_r * 0.5 * length + m_e * length) / mass_r;
        let i_z = inertia_axis - mass_r * com_x * com_x;
        let i_x = m_r * (r.width_m.powi(2) + r.thickness_m.powi(2)) / 12.0;
        let standoff = r.dome_standoff_m;
        let robot = RobotGeometry {
            length,
            link_mass: m_r,
            payload: m_e,
            inertia_axis,
            com_x,
            inertia_com: Vector::new(i_x.max(1e-12 * i_z), i_z, i_z),
            dome_radius: r.dome_radius_m,
            dome_center_local: Vector::new(length, -standoff + r.dome_radius_m, 0.0),
        };

        let op = &scene.file.operator;
        let (l, m_a, m_b) = (op.arm_length_m, op.arm_mass_kg, scene.block_mass_kg);
        let [sx, sy, sz] = op.block_size_m;
        let mass = m_a + m_b;
        let com_distance = (m_a * 0.5 * l + m_b * l) / mass;
        let inertia_pivot = m_a * l * l / 3.0 + m_b * (l * l + (sy * sy + sz * sz) / 12.0);
        // About the centre of mass: x (the pivot axis) by the parallel-axis theorem; y like x with
        // the block's x size; z along the arm (the block only).
        let i_x = inertia_pivot - mass * com_distance * com_distance;
        let i_y = m_a * l * l / 3.0 + m_b * (l * l + (sx * sx + sz * sz) / 12.0)
            - mass * com_distance * com_distance;
        let i_z = m_b * (sx * sx + sy * sy) / 12.0;
        let operator = OperatorGeometry {
            pivot: Vector::new(length, -standoff - 0.5 * sy, l),
            arm_length: l,
            mass,
            com_distance,
            inertia_pivot,
            inertia_com: Vector::new(i_x, i_y, i_z),
            block_half_extents: Vector::new(0.5 * sx, 0.5 * sy, 0.5 * sz),
            block_center_local: Vector::new(0.0, 0.0, -l),
        };
        RigGeometry { operator, robot }
    }
}
