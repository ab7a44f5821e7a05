//! Reflected mass: closed forms for single bodies, invariances (sign of u, where the base is,
//! which link names the point, the speed of the motion along which it is taken), the quadratic
//! form against an explicit Λ⁻¹ = J M⁻¹ Jᵀ (test-only explicit inverse), armature and elastic
//! joints, walls, and the refusals.

mod common;

use common::{bundled, posture, test_data, vector};
use flexrig_robot::{
    ContactPoint, Direction, JointModel, Posture, Robot, RobotError, reflected_mass,
};
use nalgebra::{Rotation3, Vector3};

fn one_link(joint: &str, com: f64, mass: f64, izz: f64) -> Robot {
    let urdf = format!(
        r#"<robot name="one">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="{com} 0 0" rpy="0.3 0.2 0.1"/><mass value="{mass}"/>
    <inertia ixx="{izz}" ixy="0" ixz="0" iyy="{izz}" iyz="0" izz="{izz}"/></inertial></link>
  <joint name="j" type="{joint}"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1"/></joint>
</robot>"#
    );
    Robot::from_urdf_str(&urdf, "one.urdf").unwrap()
}

#[test]
fn a_single_link_at_its_centre_of_mass_along_its_motion_reflects_its_mass() {
    // Prismatic: every point moves with the body; along the axis the mass is m at any point.
    let robot = one_link("prismatic", 0.4, 2.7, 0.05);
    let mut ws = robot.workspace();
    for point in [[0.4, 0.0, 0.0], [1.0, -2.0, 0.3]] {
        let cp = ContactPoint::new(&robot, "arm", point).unwrap();
        let m = reflected_mass(
            &robot,
            &[0.2],
            &cp,
            Direction::Along(Vector3::z()),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        assert!((m - 2.7).abs() <= 1e-14 * 2.7, "{m}");
        // Obliquely at angle θ to the axis: m / cos²θ.
        let th: f64 = 0.6;
        let u = Vector3::new(th.sin(), 0.0, th.cos());
        let m = reflected_mass(
            &robot,
            &[0.2],
            &cp,
            Direction::Along(u),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        assert!((m - 2.7 / th.cos().powi(2)).abs() <= 1e-13 * m, "{m}");
    }
    // Revolute, a point mass: its mass at the centre of mass along the motion; with inertia
    // I_c about the axis, (I_c + m r²) / d² at distance d.
    let (r, m, i) = (0.4, 2.7, 0.05);
    for (izz, d) in [(0.0, r), (i, r), (i, 0.9)] {
        let robot = one_link("revolute", r, m, izz);
        let mut ws = robot.workspace();
        let q: f64 = 0.5;
        let cp = ContactPoint::new(&robot, "arm", [d, 0.0, 0.0]).unwrap();
        let tangent = Vector3::new(-q.sin(), q.cos(), 0.0);
        let value = reflected_mass(
            &robot,
            &[q],
            &cp,
            Direction::Along(tangent),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        let reference = (izz + m * r * r) / (d * d);
        assert!(
            (value - reference).abs() <= 1e-13 * reference,
            "{value} vs {reference}"
        );
    }
}

#[test]
fn walls_are_infinite() {
    let robot = one_link("revolute", 0.4, 2.7, 0.05);
    let mut ws = robot.workspace();
    // Radially and along the axis, the joint cannot move the point.
    let cp = ContactPoint::new(&robot, "arm", [0.8, 0.0, 0.0]).unwrap();
    for u in [Vector3::x(), Vector3::z()] {
        let m = reflected_mass(
            &robot,
            &[0.0],
            &cp,
            Direction::Along(u),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        assert_eq!(m, f64::INFINITY);
    }
    // A point on the base never moves.
    let base = ContactPoint::new(&robot, "base", [0.1, 0.2, 0.3]).unwrap();
    let m = reflected_mass(
        &robot,
        &[0.0],
        &base,
        Direction::Along(Vector3::y()),
        JointModel::Rigid,
        &mut ws,
    )
    .unwrap();
    assert_eq!(m, f64::INFINITY);
    // The UR5 stretched out (shoulder lift and elbow at 0, the wrists' offsets aside) is still
    // finite sideways.
    let ur5 = bundled("ur5");
    let mut ws = ur5.workspace();
    let tool = ContactPoint::new(&ur5, "tool0", [0.0, 0.0, 0.0]).unwrap();
    let q = [0.0; 6];
    let m = reflected_mass(
        &ur5,
        &q,
        &tool,
        Direction::Along(Vector3::y()),
        JointModel::Rigid,
        &mut ws,
    )
    .unwrap();
    assert!(m.is_finite() && m > 0.0);
}

/// 1/m_u = uᵀ Λ⁻¹ u with Λ⁻¹ = J M⁻¹ Jᵀ formed with an explicit inverse (test only).
#[test]
fn reflected_mass_is_the_quadratic_form_of_the_inverse_operational_space_inertia() {
    for robot in [bundled("ur5"), bundled("panda"), test_data("tree_rpy.urdf")] {
        let mut ws = robot.workspace();
        for seed in 0..6 {
            let q = posture(&robot, seed);
            let moving: Vec<_> = robot.links().iter().filter(|l| l.body() > 0).collect();
            let link = moving[moving.len() - 1 - seed as usize % 3];
            let cp = ContactPoint::new(&robot, link.name(), [0.05, -0.02, 0.03]).unwrap();
            let m = robot.mass_matrix(&q, &mut ws).unwrap();
            let j = robot.point_jacobian(&q, &cp, &mut ws).unwrap();
            let lambda_inv = &j * m.try_inverse().unwrap() * j.transpose();
            let d = vector(3, seed);
            let u = Vector3::new(d[0], d[1], d[2]).normalize();
            let reference = 1.0 / (u.transpose() * lambda_inv * u)[(0, 0)];
            let mut p = Posture::new(&robot, &q, JointModel::Rigid, &mut ws).unwrap();
            let value = p.reflected_mass(&cp, Direction::Along(u)).unwrap();
            assert!(
                (value - reference).abs() <= 1e-10 * reference,
                "{value} vs {reference}"
            );
            // Invariant under u → −u, and under the speed of the motion it is taken along.
            let minus = p.reflected_mass(&cp, Direction::Along(-u)).unwrap();
            assert!((minus - value).abs() <= 1e-14 * value);
            let qd = vector(robot.dof(), seed + 50);
            let qd2: Vec<f64> = qd.iter().map(|x| 3.5 * x).collect();
            let a = p.reflected_mass(&cp, Direction::OfVelocity(&qd)).unwrap();
            let b = p.reflected_mass(&cp, Direction::OfVelocity(&qd2)).unwrap();
            assert!((a - b).abs() <= 1e-13 * a);
        }
    }
}

#[test]
fn moving_the_base_rotates_the_direction_and_nothing_else() {
    let text = std::fs::read_to_string(common::root().join("assets/robots/panda.urdf")).unwrap();
    let (xyz, rpy) = ([0.3, -1.2, 0.8], [0.4, -0.9, 2.1]);
    let moved = text.replace(
        "<robot name=\"panda\">",
        &format!(
            "<robot name=\"panda\"><link name=\"world\"/><joint name=\"mount\" type=\"fixed\">\
             <parent link=\"world\"/><child link=\"panda_link0\"/><origin xyz=\"{} {} {}\" \
             rpy=\"{} {} {}\"/></joint>",
            xyz[0], xyz[1], xyz[2], rpy[0], rpy[1], rpy[2]
        ),
    );
    let a = Robot::from_urdf_str(&text, "panda.urdf").unwrap();
    let b = Robot::from_urdf_str(&moved, "panda_mounted.urdf").unwrap();
    let rot = Rotation3::from_euler_angles(rpy[0], rpy[1], rpy[2]);
    let (mut wa, mut wb) = (a.workspace(), b.workspace());
    for seed in 0..5 {
        let q = posture(&a, seed);
        let d = vector(3, seed + 7);
        let u = Vector3::new(d[0], d[1], d[2]).normalize();
        for link in ["panda_link5", "panda_hand_tcp"] {
            let ca = ContactPoint::new(&a, link, [0.01, 0.02, 0.03]).unwrap();
            let cb = ContactPoint::new(&b, link, [0.01, 0.02, 0.03]).unwrap();
            let ma = reflected_mass(&a, &q, &ca, Direction::Along(u), JointModel::Rigid, &mut wa)
                .unwrap();
            let mb = reflected_mass(
                &b,
                &q,
                &cb,
                Direction::Along(rot * u),
                JointModel::Rigid,
                &mut wb,
            )
            .unwrap();
            assert!((ma - mb).abs() <= 1e-12 * ma, "{link}: {ma} vs {mb}");
        }
    }
}

#[test]
fn the_same_point_named_on_a_merged_link_gives_the_same_mass() {
    // panda_hand_tcp sits 0.1034 m along panda_hand's z axis (a fixed joint).
    let robot = bundled("panda");
    let mut ws = robot.workspace();
    let tcp = ContactPoint::new(&robot, "panda_hand_tcp", [0.0, 0.0, 0.0]).unwrap();
    let hand = ContactPoint::new(&robot, "panda_hand", [0.0, 0.0, 0.1034]).unwrap();
    for seed in 0..4 {
        let q = posture(&robot, seed);
        let xa = robot.point_position(&q, &tcp, &mut ws).unwrap();
        let xb = robot.point_position(&q, &hand, &mut ws).unwrap();
        assert!((xa - xb).amax() <= 1e-15);
        let u = Vector3::new(0.6, 0.0, 0.8);
        let ma = reflected_mass(
            &robot,
            &q,
            &tcp,
            Direction::Along(u),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        let mb = reflected_mass(
            &robot,
            &q,
            &hand,
            Direction::Along(u),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        assert!((ma - mb).abs() <= 1e-13 * ma);
    }
}

#[test]
fn armature_adds_to_the_diagonal_and_elastic_joints_decouple_it() {
    let robot = bundled("ur5");
    let mut ws = robot.workspace();
    let armature = [0.4, 0.4, 0.25, 0.05, 0.05, 0.05];
    let tool = ContactPoint::new(&robot, "tool0", [0.0, 0.0, 0.0]).unwrap();
    for seed in 0..5 {
        let q = posture(&robot, seed);
        let d = vector(3, seed);
        let u = Vector3::new(d[0], d[1], d[2]).normalize();
        let rigid = reflected_mass(
            &robot,
            &q,
            &tool,
            Direction::Along(u),
            JointModel::Rigid,
            &mut ws,
        )
        .unwrap();
        let elastic = reflected_mass(
            &robot,
            &q,
            &tool,
            Direction::Along(u),
            JointModel::Elastic,
            &mut ws,
        )
        .unwrap();
        let geared = reflected_mass(
            &robot,
            &q,
            &tool,
            Direction::Along(u),
            JointModel::RigidWithArmature(&armature),
            &mut ws,
        )
        .unwrap();
        assert_eq!(rigid, elastic);
        assert!(geared > rigid, "the rotors add mass: {geared} vs {rigid}");
        // Against M + diag(armature) with an explicit inverse.
        let mut m = robot.mass_matrix(&q, &mut ws).unwrap();
        for (i, a) in armature.iter().enumerate() {
            m[(i, i)] += a;
        }
        let j = robot.point_jacobian(&q, &tool, &mut ws).unwrap();
        let reference =
            1.0 / (u.transpose() * &j * m.try_inverse().unwrap() * j.transpose() * u)[(0, 0)];
        assert!((geared - reference).abs() <= 1e-10 * reference);
        // Zero armature is the rigid arm.
        let zero = reflected_mass(
            &robot,
            &q,
            &tool,
            Direction::Along(u),
            JointModel::RigidWithArmature(&[0.0; 6]),
            &mut ws,
        )
        .unwrap();
        assert_eq!(zero, rigid);
    }
}

#[test]
fn bad_arguments_are_refused_with_the_field_and_the_allowed_values() {
    let robot = bundled("ur5");
    let mut ws = robot.workspace();
    let tool = ContactPoint::new(&robot, "tool0", [0.0, 0.0, 0.0]).unwrap();
    let q = [0.1; 6];
    let call = |q: &[f64], d: Direction, jm: JointModel, ws: &mut flexrig_robot::Workspace| {
        reflected_mass(&robot, q, &tool, d, jm, ws)
            .unwrap_err()
            .to_string()
    };
    let e = call(
        &[0.1; 5],
        Direction::Along(Vector3::x()),
        JointModel::Rigid,
        &mut ws,
    );
    assert!(
        e.contains("the length of q = 5") && e.contains("6 moving joints"),
        "{e}"
    );
    let mut bad = q;
    bad[2] = f64::NAN;
    let e = call(
        &bad,
        Direction::Along(Vector3::x()),
        JointModel::Rigid,
        &mut ws,
    );
    assert!(e.contains("q[2] (elbow_joint) = NaN"), "{e}");
    let e = call(
        &q,
        Direction::Along(Vector3::new(1.0, 1.0, 0.0)),
        JointModel::Rigid,
        &mut ws,
    );
    assert!(
        e.contains("norm of direction") && e.contains("unit vector"),
        "{e}"
    );
    let e = call(
        &q,
        Direction::OfVelocity(&[0.0; 6]),
        JointModel::Rigid,
        &mut ws,
    );
    assert!(e.contains("does not move") && e.contains("tool0"), "{e}");
    let e = call(
        &q,
        Direction::Along(Vector3::x()),
        JointModel::RigidWithArmature(&[0.1, 0.1, -0.1, 0.1, 0.1, 0.1]),
        &mut ws,
    );
    assert!(
        e.contains("armature[2] (elbow_joint) = -0.1") && e.contains("≥ 0"),
        "{e}"
    );
    let e = ContactPoint::new(&robot, "hand", [0.0; 3])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("no link \"hand\"") && e.contains("wrist_3_link"),
        "{e}"
    );
    let e = ContactPoint::new(&robot, "tool0", [0.0, f64::INFINITY, 0.0]).unwrap_err();
    assert!(matches!(e, RobotError::Parameter { .. }), "{e}");
    // A point of another robot, and a workspace of another robot.
    let panda = bundled("panda");
    let other = ContactPoint::new(&panda, "panda_link7", [0.0; 3]).unwrap();
    assert!(
        reflected_mass(
            &robot,
            &q,
            &other,
            Direction::Along(Vector3::x()),
            JointModel::Rigid,
            &mut ws
        )
        .is_err()
    );
    let mut pws = panda.workspace();
    let e = reflected_mass(
        &robot,
        &q,
        &tool,
        Direction::Along(Vector3::x()),
        JointModel::Rigid,
        &mut pws,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("workspace"), "{e}");
}

#[test]
fn a_joint_that_moves_no_inertia_is_refused_by_name() {
    // A point mass on the axis of the second joint: that joint moves nothing.
    let urdf = r#"<robot name="degenerate">
  <link name="base"/>
  <link name="a"><inertial><origin xyz="0.5 0 0"/><mass value="1"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="b"><inertial><mass value="1"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link>
  <joint name="j1" type="continuous"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/></joint>
  <joint name="spin" type="continuous"><parent link="a"/><child link="b"/>
    <origin xyz="1 0 0"/><axis xyz="1 0 0"/></joint>
</robot>"#;
    let robot = Robot::from_urdf_str(urdf, "degenerate.urdf").unwrap();
    let mut ws = robot.workspace();
    let cp = ContactPoint::new(&robot, "b", [0.0; 3]).unwrap();
    let e = reflected_mass(
        &robot,
        &[0.0, 0.0],
        &cp,
        Direction::Along(Vector3::y()),
        JointModel::Rigid,
        &mut ws,
    )
    .unwrap_err();
    assert!(
        matches!(&e, RobotError::NotPositiveDefinite { joint, .. } if joint == "spin"),
        "{e}"
    );
    // Armature on that joint makes it well posed again.
    let m = reflected_mass(
        &robot,
        &[0.0, 0.0],
        &cp,
        Direction::Along(Vector3::y()),
        JointModel::RigidWithArmature(&[0.0, 0.1]),
        &mut ws,
    )
    .unwrap();
    // The point mass at 1 m on the first joint with the first link: (0.01 + 0.25 + 1) / 1².
    assert!((m - 1.26).abs() <= 1e-13, "{m}");
}
