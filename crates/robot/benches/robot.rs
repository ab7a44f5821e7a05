//! Reflected mass along a trajectory: 1 000 samples × 10 contact points on the bundled Panda
//! (7 joints) and UR5 (6 joints), rigid joints — per sample the forward kinematics, the mass
//! matrix (CRBA), its Cholesky factor, the finite-difference joint velocities, and per point the
//! position, Jacobian, velocity, direction and one solve. Also the mass matrix alone and one
//! reflected mass from scratch.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_robot::{ContactPoint, Direction, JointModel, Robot, Trajectory, reflected_mass};
use nalgebra::Vector3;

fn arm(name: &str) -> Robot {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/robots/");
    Robot::from_urdf_file(format!("{path}{name}.urdf")).unwrap()
}

/// 1 000 samples of a smooth motion through the middle of every joint's range.
fn trajectory(robot: &Robot) -> Trajectory {
    let n = 1000;
    let times: Vec<f64> = (0..n).map(|k| k as f64 * 2e-3).collect();
    let positions = times
        .iter()
        .map(|t| {
            robot
                .joints()
                .iter()
                .enumerate()
                .map(|(i, j)| {
                    let mid = 0.5 * (j.lower().max(-3.0) + j.upper().min(3.0));
                    let half = 0.25 * (j.upper().min(3.0) - j.lower().max(-3.0));
                    mid + half * (3.0 * t + i as f64).sin()
                })
                .collect()
        })
        .collect();
    Trajectory::new(robot, times, positions).unwrap()
}

/// Ten points spread over the moving links.
fn points(robot: &Robot) -> Vec<ContactPoint> {
    let moving: Vec<_> = robot.links().iter().filter(|l| l.body() > 0).collect();
    (0..10)
        .map(|k| {
            let link = moving[moving.len() - 1 - k % moving.len()];
            let s = 0.01 * k as f64;
            ContactPoint::new(robot, link.name(), [s, -s, 0.05]).unwrap()
        })
        .collect()
}

fn bench(c: &mut Criterion) {
    for name in ["panda", "ur5"] {
        let robot = arm(name);
        let traj = trajectory(&robot);
        let pts = points(&robot);
        c.bench_function(&format!("{name}_trajectory_1000x10_reflected_mass"), |b| {
            b.iter(|| {
                black_box(
                    traj.evaluate(&robot, black_box(&pts), JointModel::Rigid)
                        .unwrap(),
                )
            })
        });
        let mut ws = robot.workspace();
        let q = &traj.positions()[123];
        c.bench_function(&format!("{name}_mass_matrix"), |b| {
            b.iter(|| black_box(robot.mass_matrix(black_box(q), &mut ws).unwrap()))
        });
        let u = Vector3::new(0.6, 0.0, 0.8);
        c.bench_function(&format!("{name}_reflected_mass_one_point"), |b| {
            b.iter(|| {
                black_box(
                    reflected_mass(
                        &robot,
                        black_box(q),
                        &pts[0],
                        Direction::Along(u),
                        JointModel::Rigid,
                        &mut ws,
                    )
                    .unwrap(),
                )
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
