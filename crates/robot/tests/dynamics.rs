//! The mass matrix and the point Jacobian against methods written independently of the crate's
//! composite-rigid-body algorithm and Jacobian:
//! - the mass matrix from the kinetic energy of probe joint velocities, T = ½ Σ_bodies
//!   (m |v_c|² + ωᵀ I ω), with the body velocities from a forward velocity recursion and the
//!   poses from a homogeneous-matrix forward kinematics with Rodrigues' formula (both here);
//!   M_ii = 2 T(e_i), M_ij = T(e_i + e_j) − T(e_i) − T(e_j); 1e-12 of the largest entry;
//! - the Jacobian by central finite differences of the point's position (h = 1e-6 rad or m,
//!   truncation ≈ h² ≈ 1e-12 m, round-off ≈ 1e-16/h ≈ 1e-10): 1e-8 m/rad;
//! - fixed-joint merging against the same arm with the fixed joints made moving (at q = 0, with
//!   their rates zero, the two are the same body): 1e-12 relative.

mod common;

use common::{bundled, posture, test_data, vector};
use flexrig_robot::{ContactPoint, JointKind, Robot};
use nalgebra::{DMatrix, Matrix3, Matrix4, Vector3};

/// Rodrigues: rotation by angle about the unit axis.
fn rodrigues(axis: &Vector3<f64>, angle: f64) -> Matrix3<f64> {
    let k = axis.cross_matrix();
    Matrix3::identity() + angle.sin() * k + (1.0 - angle.cos()) * k * k
}

/// World homogeneous transform of every body (0 = base), own code.
fn own_poses(robot: &Robot, q: &[f64]) -> Vec<Matrix4<f64>> {
    let mut poses = vec![Matrix4::identity(); robot.dof() + 1];
    for (i, j) in robot.joints().iter().enumerate() {
        let mut motion = Matrix4::identity();
        let a = j.axis().into_inner();
        match j.kind() {
            JointKind::Prismatic => {
                motion.fixed_view_mut::<3, 1>(0, 3).copy_from(&(a * q[i]));
            }
            _ => {
                motion
                    .fixed_view_mut::<3, 3>(0, 0)
                    .copy_from(&rodrigues(&a, q[i]));
            }
        }
        poses[i + 1] = poses[j.parent_body()] * j.origin().to_homogeneous() * motion;
    }
    poses
}

/// Kinetic energy at joint rates `qd`, by a forward velocity recursion (own code).
fn kinetic_energy(robot: &Robot, poses: &[Matrix4<f64>], qd: &[f64]) -> f64 {
    let n = robot.dof();
    let mut omega = vec![Vector3::zeros(); n + 1];
    let mut v_origin = vec![Vector3::zeros(); n + 1];
    let origin = |b: usize| poses[b].fixed_view::<3, 1>(0, 3).into_owned();
    let rot = |b: usize| poses[b].fixed_view::<3, 3>(0, 0).into_owned();
    let mut t = 0.0;
    for (i, j) in robot.joints().iter().enumerate() {
        let b = i + 1;
        let p = j.parent_body();
        let a = rot(b) * j.axis().into_inner();
        // The parent's motion carried to this body's origin, plus the joint's own.
        let v_here = v_origin[p] + omega[p].cross(&(origin(b) - origin(p)));
        match j.kind() {
            JointKind::Prismatic => {
                omega[b] = omega[p];
                v_origin[b] = v_here + a * qd[i];
            }
            _ => {
                omega[b] = omega[p] + a * qd[i];
                v_origin[b] = v_here;
            }
        }
        let body = robot.bodies()[b].inertia();
        let c = rot(b) * body.com + origin(b);
        let v_c = v_origin[b] + omega[b].cross(&(c - origin(b)));
        let i_world = rot(b) * body.inertia * rot(b).transpose();
        t += 0.5 * (body.mass * v_c.norm_squared() + omega[b].dot(&(i_world * omega[b])));
    }
    t
}

fn energy_mass_matrix(robot: &Robot, q: &[f64]) -> DMatrix<f64> {
    let n = robot.dof();
    let poses = own_poses(robot, q);
    let unit = |i: usize| {
        let mut e = vec![0.0; n];
        e[i] = 1.0;
        e
    };
    let ti: Vec<f64> = (0..n)
        .map(|i| kinetic_energy(robot, &poses, &unit(i)))
        .collect();
    let mut m = DMatrix::zeros(n, n);
    for i in 0..n {
        m[(i, i)] = 2.0 * ti[i];
        for k in 0..i {
            let mut e = unit(i);
            e[k] = 1.0;
            let v = kinetic_energy(robot, &poses, &e) - ti[i] - ti[k];
            m[(i, k)] = v;
            m[(k, i)] = v;
        }
    }
    m
}

fn arms() -> Vec<(&'static str, Robot)> {
    vec![
        ("ur5", bundled("ur5")),
        ("panda", bundled("panda")),
        ("panda_fingers", test_data("panda_fingers.urdf")),
        ("tree_rpy", test_data("tree_rpy.urdf")),
    ]
}

#[test]
fn mass_matrix_equals_the_kinetic_energy_of_probe_velocities() {
    for (name, robot) in arms() {
        let mut ws = robot.workspace();
        for seed in 0..8 {
            let q = posture(&robot, seed);
            let crba = robot.mass_matrix(&q, &mut ws).unwrap();
            let energy = energy_mass_matrix(&robot, &q);
            let err = (&crba - &energy).amax() / energy.amax();
            assert!(err <= 1e-12, "{name} seed {seed}: relative {err:e}");
            // Symmetric positive definite.
            assert_eq!(crba, crba.transpose());
            assert!(crba.clone().cholesky().is_some(), "{name}");
        }
    }
}

#[test]
fn jacobian_equals_finite_differences_of_forward_kinematics() {
    let h = 1e-6;
    for (name, robot) in arms() {
        let mut ws = robot.workspace();
        for (k, link) in robot.links().iter().enumerate() {
            let p = vector(3, k as u64);
            let cp = ContactPoint::new(&robot, link.name(), [0.1 * p[0], 0.1 * p[1], 0.1 * p[2]])
                .unwrap();
            let q = posture(&robot, 100 + k as u64);
            let jac = robot.point_jacobian(&q, &cp, &mut ws).unwrap();
            for i in 0..robot.dof() {
                let mut qp = q.clone();
                let mut qm = q.clone();
                qp[i] += h;
                qm[i] -= h;
                let xp = robot.point_position(&qp, &cp, &mut ws).unwrap();
                let xm = robot.point_position(&qm, &cp, &mut ws).unwrap();
                let fd = (xp - xm) / (2.0 * h);
                let err = (fd - jac.column(i)).amax();
                assert!(
                    err <= 1e-8,
                    "{name} link {} joint {i}: {err:e}",
                    link.name()
                );
            }
        }
    }
}

/// Turns the named fixed joints of a URDF text into revolute joints about z (limits ±1 rad).
fn unfix(text: &str, joints: &[&str]) -> String {
    let mut out = text.to_string();
    for j in joints {
        let from = format!("name=\"{j}\" type=\"fixed\">");
        let to = format!(
            "name=\"{j}\" type=\"revolute\"><axis xyz=\"0 0 1\"/><limit lower=\"-1\" \
             upper=\"1\"/>"
        );
        assert!(out.contains(&from), "{j}");
        out = out.replace(&from, &to);
    }
    out
}

fn check_merge(merged: &Robot, unmerged: &Robot, q_merged: &[f64]) {
    // Unmerged positions: the merged ones by name, the extra joints at 0.
    let q_full: Vec<f64> = unmerged
        .joints()
        .iter()
        .map(|j| merged.joint_index(j.name()).map_or(0.0, |i| q_merged[i]))
        .collect();
    let mut wm = merged.workspace();
    let mut wu = unmerged.workspace();
    let m = merged.mass_matrix(q_merged, &mut wm).unwrap();
    let full = unmerged.mass_matrix(&q_full, &mut wu).unwrap();
    for (a, ja) in merged.joints().iter().enumerate() {
        for (b, jb) in merged.joints().iter().enumerate() {
            let (ua, ub) = (
                unmerged.joint_index(ja.name()).unwrap(),
                unmerged.joint_index(jb.name()).unwrap(),
            );
            let err = (m[(a, b)] - full[(ua, ub)]).abs() / m.amax();
            assert!(
                err <= 1e-12,
                "M[{a}][{b}] {} vs {}",
                m[(a, b)],
                full[(ua, ub)]
            );
        }
    }
    assert!(
        (merged.moving_mass() - unmerged.moving_mass()).abs() <= 1e-12 * unmerged.moving_mass()
    );
}

#[test]
fn fixed_joint_merging_equals_the_unmerged_chain() {
    // The bundled Panda (fingers fixed) against the Panda with prismatic fingers at q = 0.
    let merged = bundled("panda");
    let unmerged = test_data("panda_fingers.urdf");
    assert_eq!((merged.dof(), unmerged.dof()), (7, 9));
    for seed in 0..4 {
        check_merge(&merged, &unmerged, &posture(&merged, seed));
    }
    // The made-up tree with its two massive fixed links made revolute.
    let path = common::root().join("crates/robot/tests/data/tree_rpy.urdf");
    let text = std::fs::read_to_string(path).unwrap();
    let merged = Robot::from_urdf_str(&text, "tree_rpy.urdf").unwrap();
    let unmerged = Robot::from_urdf_str(
        &unfix(&text, &["l2_tool_joint", "l3_pad_joint"]),
        "tree_rpy_unfixed.urdf",
    )
    .unwrap();
    assert_eq!((merged.dof(), unmerged.dof()), (4, 6));
    for seed in 0..4 {
        check_merge(&merged, &unmerged, &posture(&merged, seed));
    }
}

/// Spong, Hutchinson, Vidyasagar, *Robot Modeling and Control* (2006), §7.3.3: the planar
/// elbow arm's mass matrix and its tip's reflected mass in closed form
/// (`flexrig_robot::canonical::PlanarTwoLink`: the textbook formulas and a 2 × 2 adjugate).
#[test]
fn planar_two_link_arm_matches_the_textbook_mass_matrix() {
    let arm = flexrig_robot::canonical::PlanarTwoLink::example();
    let robot = arm.robot().unwrap();
    let mut ws = robot.workspace();
    let tip = ContactPoint::new(&robot, "link2", [arm.l2, 0.0, 0.0]).unwrap();
    for (q1, q2) in [(0.0, 0.0), (0.3, 1.1), (-1.2, 2.5), (2.0, -0.4)] {
        let m = robot.mass_matrix(&[q1, q2], &mut ws).unwrap();
        let r = arm.mass_matrix([q1, q2]);
        for a in 0..2 {
            for b in 0..2 {
                assert!(
                    (m[(a, b)] - r[a][b]).abs() <= 1e-13 * r[0][0],
                    "{m} vs {r:?}"
                );
            }
        }
        for angle in [0.0f64, 0.7, 1.9, 3.0] {
            let u = [angle.cos(), angle.sin()];
            let reference = arm.tip_reflected_mass([q1, q2], u);
            let value = flexrig_robot::reflected_mass(
                &robot,
                &[q1, q2],
                &tip,
                flexrig_robot::Direction::Along(Vector3::new(u[0], u[1], 0.0)),
                flexrig_robot::JointModel::Rigid,
                &mut ws,
            )
            .unwrap();
            if reference.is_infinite() {
                // Stretched out along x and struck along x: a wall.
                assert_eq!((q1, q2, angle), (0.0, 0.0, 0.0));
                assert_eq!(value, f64::INFINITY);
            } else {
                assert!(
                    (value - reference).abs() <= 1e-12 * reference,
                    "q = ({q1}, {q2}), u angle {angle}: {value} vs {reference}"
                );
            }
        }
    }
}
