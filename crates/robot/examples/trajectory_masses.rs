//! The bundled Panda along its bundled trajectory: for ten contact points, the largest speed and
//! the reflected mass along the velocity at that moment (rigid joints, and with an armature).
//!
//! ```sh
//! cargo run --release -p flexrig-robot --example trajectory_masses            # the table
//! cargo run --release -p flexrig-robot --example trajectory_masses -- 200     # + 200 timed repeats
//! ```
//! With a repeat count it evaluates the 1 000-sample × 10-point benchmark trajectory that many
//! times (for `perf stat`: CPU time per evaluation, independent of the machine's other load).

use flexrig_robot::{ContactPoint, JointModel, Robot, Trajectory};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let assets = concat!(env!("CARGO_MANIFEST_DIR"), "/../../assets/robots");
    let robot = Robot::from_urdf_file(format!("{assets}/panda.urdf"))?;
    let traj = Trajectory::from_csv_file(&robot, format!("{assets}/panda_swing.csv"))?;
    let points: Vec<ContactPoint> = [
        ("panda_hand_tcp", [0.0, 0.0, 0.0]),
        ("panda_hand", [0.0, 0.05, 0.05]),
        ("panda_link7", [0.0, 0.0, 0.05]),
        ("panda_link6", [0.08, 0.0, 0.0]),
        ("panda_link5", [0.0, 0.05, -0.15]),
        ("panda_link5", [0.0, 0.0, -0.25]),
        ("panda_link4", [-0.08, 0.08, 0.0]),
        ("panda_link4", [0.0, 0.0, 0.05]),
        ("panda_link3", [0.08, 0.0, 0.0]),
        ("panda_link2", [0.0, -0.15, 0.0]),
    ]
    .iter()
    .map(|(l, p)| ContactPoint::new(&robot, l, *p))
    .collect::<Result<_, _>>()?;
    let armature = [0.3, 0.3, 0.3, 0.3, 0.1, 0.1, 0.1];
    let rigid = traj.evaluate(&robot, &points, JointModel::Rigid)?;
    let geared = traj.evaluate(&robot, &points, JointModel::RigidWithArmature(&armature))?;
    println!("point                      peak speed  at t     m_u rigid  m_u armature");
    println!("                           m/s         s        kg         kg");
    for (k, p) in points.iter().enumerate() {
        let (s, _) = rigid
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.points[k].speed.total_cmp(&b.1.points[k].speed))
            .unwrap();
        let a = &rigid[s].points[k];
        let b = &geared[s].points[k];
        println!(
            "{:<14} {:>5.2} {:>5.2} {:>5.2}  {:>6.3}  {:>5.2}  {:>9.3}  {:>9.3}",
            p.link(),
            p.point_in_link().x,
            p.point_in_link().y,
            p.point_in_link().z,
            a.speed,
            rigid[s].time,
            a.reflected_mass.unwrap_or(f64::NAN),
            b.reflected_mass.unwrap_or(f64::NAN),
        );
    }
    let repeats: usize = std::env::args().nth(1).map_or(Ok(0), |a| a.parse())?;
    if repeats > 0 {
        // The benchmark's trajectory: 1 000 samples, 2 ms apart.
        let times: Vec<f64> = (0..1000).map(|k| k as f64 * 2e-3).collect();
        let positions = times
            .iter()
            .map(|t| {
                robot
                    .joints()
                    .iter()
                    .enumerate()
                    .map(|(i, j)| {
                        let (lo, hi) = (j.lower().max(-3.0), j.upper().min(3.0));
                        0.5 * (lo + hi) + 0.25 * (hi - lo) * (3.0 * t + i as f64).sin()
                    })
                    .collect()
            })
            .collect();
        let bench = Trajectory::new(&robot, times, positions)?;
        let start = std::time::Instant::now();
        let mut sum = 0.0;
        for _ in 0..repeats {
            let s = bench.evaluate(&robot, &points, JointModel::Rigid)?;
            sum += s[500].points[0].reflected_mass.unwrap_or(0.0);
        }
        println!(
            "{repeats} evaluations of 1000 samples x 10 points: {:.3} ms each (wall; checksum {sum:.6})",
            start.elapsed().as_secs_f64() * 1e3 / repeats as f64
        );
    }
    Ok(())
}
