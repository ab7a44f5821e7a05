//! The bundled arm: the Universal Robots UR5 of `assets/robots/ur5.urdf` (BSD; provenance in
//! `assets/robots/README.md`), its swing `assets/robots/ur5_swing.csv` (a minimum-jerk move of
//! 1.5 s at 100 Hz: the shoulder pan 0 → 1.2 rad, the shoulder lift −1.5708 → −1 rad, the elbow
//! 1.5708 → 1 rad, wrist 1 −1.5708 → −1.2 rad, wrist 3 0 → 0.5 rad), and its default contact
//! points, compiled into the library so that `flexrig arm` answers from any directory.

use flexrig_robot::{Robot, Trajectory};

use crate::Error;
use crate::arm::judge::ArmPoint;

/// The UR5's URDF text.
pub const UR5_URDF: &str = include_str!("../../../../assets/robots/ur5.urdf");
/// Its swing's CSV text.
pub const UR5_SWING: &str = include_str!("../../../../assets/robots/ur5_swing.csv");
/// Where the files are in the repository (how the answers name them).
pub const UR5_URDF_PATH: &str = "assets/robots/ur5.urdf";
/// The swing's path in the repository.
pub const UR5_SWING_PATH: &str = "assets/robots/ur5_swing.csv";

/// The bundled UR5.
pub fn ur5() -> Result<Robot, Error> {
    Ok(Robot::from_urdf_str(UR5_URDF, UR5_URDF_PATH)?)
}

/// The bundled UR5's swing.
pub fn ur5_swing(robot: &Robot) -> Result<Trajectory, Error> {
    Ok(Trajectory::from_csv_str(robot, UR5_SWING, UR5_SWING_PATH)?)
}

/// The UR5's default contact points: a tool's tip 10 cm beyond the flange (`tool0`, whose z
/// axis points out of the flange), the wrist (the `wrist_2_link` frame's origin), the middle of
/// the forearm (0.2 m along `forearm_link`'s z, which runs from the elbow to the wrist) and the
/// elbow (the `forearm_link` frame's origin).
pub fn ur5_points() -> Vec<ArmPoint> {
    vec![
        ArmPoint {
            link: "tool0".into(),
            xyz: [0.0, 0.0, 0.1],
        },
        ArmPoint {
            link: "wrist_2_link".into(),
            xyz: [0.0; 3],
        },
        ArmPoint {
            link: "forearm_link".into(),
            xyz: [0.0, 0.0, 0.2],
        },
        ArmPoint {
            link: "forearm_link".into(),
            xyz: [0.0; 3],
        },
    ]
}

/// The arm and its trajectory as a front gives them: a URDF file and a trajectory CSV, or
/// neither (the bundled UR5 and its swing). Returns the robot, the trajectory, the default
/// contact points (the UR5's when bundled; none for a user's arm) and the names of the files.
pub fn load(
    urdf: Option<&std::path::Path>,
    trajectory: Option<&std::path::Path>,
) -> Result<(Robot, Trajectory, Vec<ArmPoint>, String, String), Error> {
    match (urdf, trajectory) {
        (None, None) => {
            let robot = ur5()?;
            let traj = ur5_swing(&robot)?;
            Ok((
                robot,
                traj,
                ur5_points(),
                UR5_URDF_PATH.into(),
                UR5_SWING_PATH.into(),
            ))
        }
        (Some(u), Some(t)) => {
            let robot = Robot::from_urdf_file(u)?;
            let traj = Trajectory::from_csv_file(&robot, t)?;
            Ok((
                robot,
                traj,
                Vec::new(),
                u.display().to_string(),
                t.display().to_string(),
            ))
        }
        (Some(u), None) => Err(Error::InvalidArgument {
            arg: "--trajectory".into(),
            value: "(missing)".into(),
            allowed: format!(
                "a trajectory CSV of the arm of {} (header time_s and one column per moving \
                 joint; docs/arm.md); without --urdf and --trajectory the bundled UR5 and its \
                 swing are judged",
                u.display()
            ),
        }),
        (None, Some(t)) => Err(Error::InvalidArgument {
            arg: "--urdf".into(),
            value: "(missing)".into(),
            allowed: format!(
                "the URDF of the arm that {} moves; without --urdf and --trajectory the bundled \
                 UR5 and its swing are judged",
                t.display()
            ),
        }),
    }
}
