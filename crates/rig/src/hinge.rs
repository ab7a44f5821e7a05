//! The state of a revolute joint of the rig (the operator's pivot, the robot axis, a drive's
//! rotor): the value the world, the coupling, the drive and the free flight hand each other.

/// Angle and rate of a hinge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HingeState {
    /// Joint angle \[rad\].
    pub angle: f64,
    /// Joint rate [rad/s].
    pub rate: f64,
}
