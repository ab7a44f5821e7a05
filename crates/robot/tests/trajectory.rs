//! Trajectories: the finite-difference joint velocities (exact for quadratics on a non-uniform
//! grid, second order on a smooth motion), speed scaling, the evaluation along the bundled
//! trajectories against direct calls, and the refusals of bad CSVs with their line numbers.

mod common;

use common::{bundled, root};
use flexrig_robot::{
    ContactPoint, Direction, JointModel, Robot, RobotError, Trajectory, reflected_mass,
};

fn one_joint() -> Robot {
    let urdf = r#"<robot name="one">
  <link name="base"/>
  <link name="arm"><inertial><origin xyz="0.5 0 0"/><mass value="2"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 0 1"/><limit lower="-10" upper="10"/></joint>
</robot>"#;
    Robot::from_urdf_str(urdf, "one.urdf").unwrap()
}

#[test]
fn velocities_are_exact_for_quadratics_on_a_non_uniform_grid() {
    let robot = one_joint();
    let times = vec![0.0, 0.1, 0.13, 0.3, 0.31, 0.5];
    let q = |t: f64| 0.3 - 1.7 * t + 4.2 * t * t;
    let qd = |t: f64| -1.7 + 8.4 * t;
    let traj = Trajectory::new(
        &robot,
        times.clone(),
        times.iter().map(|&t| vec![q(t)]).collect(),
    )
    .unwrap();
    for (v, t) in traj.velocities().iter().zip(&times) {
        assert!(
            (v[0] - qd(*t)).abs() <= 1e-12,
            "t = {t}: {} vs {}",
            v[0],
            qd(*t)
        );
    }
}

#[test]
fn velocities_converge_at_second_order() {
    let robot = one_joint();
    let error = |n: usize| {
        let times: Vec<f64> = (0..=n).map(|k| k as f64 / n as f64).collect();
        let traj = Trajectory::new(
            &robot,
            times.clone(),
            times.iter().map(|t| vec![t.sin() * 2.0]).collect(),
        )
        .unwrap();
        traj.velocities()
            .iter()
            .zip(&times)
            .map(|(v, t)| (v[0] - 2.0 * t.cos()).abs())
            .fold(0.0, f64::max)
    };
    let (e1, e2) = (error(50), error(100));
    let order = (e1 / e2).log2();
    assert!((order - 2.0).abs() < 0.1, "observed order {order}");
}

#[test]
fn speed_scaling_scales_velocities_and_keeps_the_reflected_mass() {
    let robot = bundled("panda");
    let traj =
        Trajectory::from_csv_file(&robot, root().join("assets/robots/panda_swing.csv")).unwrap();
    let fast = traj.with_speed_scale(2.0).unwrap();
    let tcp = [ContactPoint::new(&robot, "panda_hand_tcp", [0.0; 3]).unwrap()];
    let a = traj.evaluate(&robot, &tcp, JointModel::Rigid).unwrap();
    let b = fast.evaluate(&robot, &tcp, JointModel::Rigid).unwrap();
    for (sa, sb) in a.iter().zip(&b) {
        assert!((sb.time - sa.time / 2.0).abs() <= 1e-15);
        for (x, y) in sa.qdot.iter().zip(&sb.qdot) {
            assert!((y - 2.0 * x).abs() <= 1e-12 * (1.0 + x.abs()));
        }
        let (pa, pb) = (&sa.points[0], &sb.points[0]);
        assert!((pb.speed - 2.0 * pa.speed).abs() <= 1e-12 * (1.0 + pa.speed));
        if let (Some(ma), Some(mb)) = (pa.reflected_mass, pb.reflected_mass) {
            assert!((ma - mb).abs() <= 1e-9 * ma, "{ma} vs {mb}");
        }
    }
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = traj.with_speed_scale(bad).unwrap_err().to_string();
        assert!(e.contains("speed_scale") && e.contains("> 0"), "{e}");
    }
}

#[test]
fn bundled_trajectories_evaluate_like_direct_calls() {
    for (arm, points) in [
        (
            "ur5",
            vec![
                ("tool0", [0.0, 0.0, 0.0]),
                ("forearm_link", [0.0, 0.0, 0.2]),
                ("wrist_2_link", [0.0, 0.05, 0.0]),
            ],
        ),
        (
            "panda",
            vec![
                ("panda_hand_tcp", [0.0, 0.0, 0.0]),
                ("panda_link4", [0.0, 0.0, 0.0]),
                ("panda_link6", [0.05, 0.0, 0.0]),
            ],
        ),
    ] {
        let robot = bundled(arm);
        let traj = Trajectory::from_csv_file(
            &robot,
            root().join(format!("assets/robots/{arm}_swing.csv")),
        )
        .unwrap();
        assert_eq!(traj.len(), 151);
        let cps: Vec<ContactPoint> = points
            .iter()
            .map(|(l, p)| ContactPoint::new(&robot, l, *p).unwrap())
            .collect();
        let samples = traj.evaluate(&robot, &cps, JointModel::Rigid).unwrap();
        let mut ws = robot.workspace();
        let mut moving = 0;
        for s in &samples {
            for (cp, ps) in cps.iter().zip(&s.points) {
                let x = robot.point_position(&s.q, cp, &mut ws).unwrap();
                assert!((x - ps.position).amax() <= 1e-15);
                let j = robot.point_jacobian(&s.q, cp, &mut ws).unwrap();
                let v = &j * nalgebra::DVector::from_column_slice(&s.qdot);
                assert!((v - ps.velocity).amax() <= 1e-14);
                assert!((ps.speed - ps.velocity.norm()).abs() <= 1e-15);
                match (ps.direction, ps.reflected_mass) {
                    (Some(u), Some(m)) => {
                        moving += 1;
                        let direct = reflected_mass(
                            &robot,
                            &s.q,
                            cp,
                            Direction::OfVelocity(&s.qdot),
                            JointModel::Rigid,
                            &mut ws,
                        )
                        .unwrap();
                        assert!((m - direct).abs() <= 1e-12 * m, "{m} vs {direct}");
                        assert!((u.into_inner() - ps.velocity / ps.speed).amax() <= 1e-15);
                        assert!(m > 0.0 && m < robot.moving_mass() * 100.0, "{m}");
                    }
                    (None, None) => assert!(ps.speed <= flexrig_robot::REST_SPEED),
                    other => panic!("direction and mass must come together: {other:?}"),
                }
            }
        }
        assert!(moving >= samples.len() * 3 - 6, "{arm}: {moving}");
    }
}

fn csv_err(text: &str) -> String {
    let robot = one_joint();
    let e = Trajectory::from_csv_str(&robot, text, "t.csv").unwrap_err();
    assert!(matches!(e, RobotError::Csv { .. }));
    e.to_string()
}

#[test]
fn bad_csvs_are_refused_with_their_line() {
    let good = "# a comment\ntime_s,j\n0,0\n0.1,0.1\n\n0.2,0.2\n";
    assert_eq!(
        Trajectory::from_csv_str(&one_joint(), good, "t.csv")
            .unwrap()
            .len(),
        3
    );
    let m = csv_err("time_s,j\n0,0\n0.1,0.1\n0.1,0.2\n");
    assert!(
        m.contains("t.csv, line 4") && m.contains("does not increase") && m.contains("strictly"),
        "{m}"
    );
    let m = csv_err("time_s,j\n0,0\n0.2,0.1\n0.1,0.2\n");
    assert!(
        m.contains("line 4") && m.contains("does not increase"),
        "{m}"
    );
    let m = csv_err("time_s,j\n0,0\n0.1,0.1,3\n0.2,0.2\n");
    assert!(
        m.contains("line 3") && m.contains("3 columns, the header has 2"),
        "{m}"
    );
    let m = csv_err("time_s,j\n0,0\n0.1,NaN\n0.2,0.2\n");
    assert!(
        m.contains("line 3") && m.contains("column \"j\"") && m.contains("not a finite number"),
        "{m}"
    );
    let m = csv_err("time_s,j\n0,0\n0.1,abc\n0.2,0.2\n");
    assert!(m.contains("line 3") && m.contains("\"abc\""), "{m}");
    let m = csv_err("time_s,k\n0,0\n");
    assert!(
        m.contains("line 1")
            && m.contains("column \"k\" is not a moving joint")
            && m.contains("are j"),
        "{m}"
    );
    let m = csv_err("time_s,arm\n0,0\n");
    assert!(m.contains("(it is a link name)"), "{m}");
    let m = csv_err("time_s,j,j\n0,0,0\n");
    assert!(m.contains("appears twice"), "{m}");
    let m = csv_err("time_s\n0\n0.1\n0.2\n");
    assert!(m.contains("lacks the joints j"), "{m}");
    let m = csv_err("t,j\n0,0\n");
    assert!(m.contains("first column must be \"time_s\""), "{m}");
    let m = csv_err("time_s,j\n0,0\n0.1,10.5\n0.2,0.2\n");
    assert!(
        m.contains("line 3")
            && m.contains("outside its limits [-10, 10] rad")
            && m.contains("URDF line 5"),
        "{m}"
    );
    let m = csv_err("time_s,j\n0,0\n0.1,0.1\n");
    assert!(m.contains("2 samples; at least 3"), "{m}");
    let m = csv_err("# only a comment\n");
    assert!(m.contains("no header"), "{m}");
    let many = format!(
        "time_s,j\n{}",
        (0..=flexrig_robot::MAX_SAMPLES)
            .map(|k| format!("{k},0\n"))
            .collect::<String>()
    );
    let m = csv_err(&many);
    assert!(
        m.contains("line 1000002") && m.contains("more than 1000000 samples"),
        "{m}"
    );
    let e = Trajectory::from_csv_file(&one_joint(), root().join("no/such.csv")).unwrap_err();
    assert!(matches!(e, RobotError::Io { .. }));
    // In memory: the sample is named.
    let e = Trajectory::new(&one_joint(), vec![0.0, 1.0, 1.0], vec![vec![0.0]; 3]).unwrap_err();
    assert!(e.to_string().contains("trajectory sample 2"), "{e}");
}
