//! Against Pinocchio: mass matrices, contact-point positions and Jacobians, and reflected masses
//! (rigid, with armature, along the point's velocity) on the bundled UR5 and Panda, the 9-joint
//! Panda with prismatic fingers and a made-up tree with rpy everywhere.
//!
//! The fixture `tests/data/pinocchio_reference.json` was made by
//! `scripts/reflected_mass_pinocchio.py` (Pinocchio 4.1.0 from PyPI's `pin`, NumPy 2.4) from the
//! same URDF files: its own CRBA, its frame Jacobian at an operational frame on the contact
//! point, and numpy's LU solve. Tolerances: reflected masses 1e-9 relative (the requirement);
//! mass-matrix entries 1e-10 of the matrix's largest entry; positions 1e-12 m; Jacobian entries
//! 1e-12 of the largest.

use std::path::PathBuf;

use flexrig_contact::tolerance::relative_error;
use flexrig_robot::{ContactPoint, Direction, JointModel, Posture, Robot};
use nalgebra::Vector3;
use serde_json::Value;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn matches_pinocchio_on_real_arms_and_a_tree() {
    let text = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/pinocchio_reference.json"),
    )
    .unwrap();
    let doc: Value = serde_json::from_str(&text).unwrap();
    let mut real_arms = 0;
    for r in doc["robots"].as_array().unwrap() {
        let path = r["urdf"].as_str().unwrap();
        if path.starts_with("assets/robots/") {
            real_arms += 1;
        }
        let robot = Robot::from_urdf_file(root().join(path)).unwrap();
        let names: Vec<&str> = r["joint_names"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        assert_eq!(names.len(), robot.dof(), "{path}");
        // Pinocchio's joint k is our joint perm[k].
        let perm: Vec<usize> = names
            .iter()
            .map(|n| robot.joint_index(n).unwrap())
            .collect();
        let to_ours = |v: &[f64]| {
            let mut out = vec![0.0; v.len()];
            for (k, x) in v.iter().enumerate() {
                out[perm[k]] = *x;
            }
            out
        };
        let mut ws = robot.workspace();
        let (mut worst_m, mut worst_mass_matrix, mut worst_jac, mut worst_pos) =
            (0.0f64, 0.0f64, 0.0f64, 0.0f64);
        let mut count = 0;
        for pose in r["poses"].as_array().unwrap() {
            let q = to_ours(&floats(&pose["q"]));
            let qdot = to_ours(&floats(&pose["qdot"]));
            let armature = to_ours(&floats(&pose["armature"]));
            let m = robot.mass_matrix(&q, &mut ws).unwrap();
            let rows = pose["mass_matrix"].as_array().unwrap();
            let scale = m.amax();
            for (a, row) in rows.iter().enumerate() {
                for (b, x) in floats(row).iter().enumerate() {
                    let err = (m[(perm[a], perm[b])] - x).abs() / scale;
                    worst_mass_matrix = worst_mass_matrix.max(err);
                    assert!(
                        err <= 1e-10,
                        "{path}: M[{a}][{b}] {} vs {x}",
                        m[(perm[a], perm[b])]
                    );
                }
            }
            for case in pose["cases"].as_array().unwrap() {
                let p = floats(&case["point"]);
                let cp =
                    ContactPoint::new(&robot, case["link"].as_str().unwrap(), [p[0], p[1], p[2]])
                        .unwrap();
                let u = Vector3::from_vec(floats(&case["direction"]));
                let mut rigid = Posture::new(&robot, &q, JointModel::Rigid, &mut ws).unwrap();
                let x = rigid.position(&cp).unwrap();
                let x_ref = Vector3::from_vec(floats(&case["position"]));
                worst_pos = worst_pos.max((x - x_ref).amax());
                assert!(
                    (x - x_ref).amax() <= 1e-12,
                    "{path}: position {x} vs {x_ref}"
                );
                let jac = rigid.jacobian(&cp).unwrap().clone();
                let jac_scale = jac.amax().max(1e-3);
                for (row, jr) in case["jacobian"].as_array().unwrap().iter().enumerate() {
                    for (k, val) in floats(jr).iter().enumerate() {
                        let err = (jac[(row, perm[k])] - val).abs() / jac_scale;
                        worst_jac = worst_jac.max(err);
                        assert!(err <= 1e-12, "{path}: J[{row}][{k}]");
                    }
                }
                let checks = [
                    (
                        "rigid",
                        rigid.reflected_mass(&cp, Direction::Along(u)).unwrap(),
                        case["m_rigid"].as_f64().unwrap(),
                    ),
                    (
                        "rigid along the velocity",
                        rigid
                            .reflected_mass(&cp, Direction::OfVelocity(&qdot))
                            .unwrap(),
                        case["m_rigid_along_velocity"].as_f64().unwrap(),
                    ),
                    (
                        "with armature",
                        Posture::new(
                            &robot,
                            &q,
                            JointModel::RigidWithArmature(&armature),
                            &mut ws,
                        )
                        .unwrap()
                        .reflected_mass(&cp, Direction::Along(u))
                        .unwrap(),
                        case["m_armature"].as_f64().unwrap(),
                    ),
                ];
                for (what, value, reference) in checks {
                    let err = relative_error(value, reference, f64::MIN_POSITIVE);
                    worst_m = worst_m.max(err);
                    count += 1;
                    assert!(
                        value.is_finite() && err <= 1e-9,
                        "{path}: {what} at {}: {value} vs Pinocchio {reference} (rel. {err:e})",
                        cp.link()
                    );
                }
            }
        }
        eprintln!(
            "{path}: {count} reflected masses, worst relative error {worst_m:.2e}; mass matrix \
             {worst_mass_matrix:.2e} of its largest entry; Jacobian {worst_jac:.2e}; position \
             {worst_pos:.2e} m"
        );
    }
    assert_eq!(real_arms, 2, "UR5 and Panda");
}
