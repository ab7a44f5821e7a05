//! Helpers shared by the robot crate's tests: the bundled arms and postures inside the limits.
#![allow(dead_code)]

use std::path::PathBuf;

use flexrig_robot::Robot;

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A bundled arm by file stem (`ur5`, `panda`).
pub fn bundled(name: &str) -> Robot {
    Robot::from_urdf_file(root().join(format!("assets/robots/{name}.urdf"))).unwrap()
}

/// A test URDF by file name in tests/data.
pub fn test_data(name: &str) -> Robot {
    Robot::from_urdf_file(
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("tests/data")
            .join(name),
    )
    .unwrap()
}

/// A deterministic posture inside the limits (clamped to ±π): a fraction of each range.
pub fn posture(robot: &Robot, seed: u64) -> Vec<f64> {
    let mut state = seed
        .wrapping_mul(6364136223846793005)
        .wrapping_add(1442695040888963407);
    robot
        .joints()
        .iter()
        .map(|j| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let s = (state >> 11) as f64 / (1u64 << 53) as f64;
            let lo = j.lower().max(-std::f64::consts::PI);
            let hi = j.upper().min(std::f64::consts::PI);
            lo + (hi - lo) * s
        })
        .collect()
}

/// A deterministic vector in [-1, 1)ⁿ.
pub fn vector(n: usize, seed: u64) -> Vec<f64> {
    let mut state = seed ^ 0x9E3779B97F4A7C15;
    (0..n)
        .map(|_| {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            2.0 * ((state >> 11) as f64 / (1u64 << 53) as f64) - 1.0
        })
        .collect()
}
