//! The arm judged along its path: 1 000 samples × 10 contact points × 1 body region (the
//! performance floor: ≤ 1 s on 2 cores), the bundled UR5 on a minimum-jerk move of 1.5 s with
//! the swing's end postures, for the default question (rigid, the body's spring, the free drive)
//! and a compliant one (a CJ of k_δ = 2e4 N/m with the fitted skinned-aluminium skin), on the
//! 1 % mass grid (the compliant one also on the 5 % grid). `cargo bench --workspace --bench arm`.

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig::arm::{
    ArmDrive, ArmInput, ArmJoints, ArmPoint, Trajectory, bundled, judge, simulation_settings,
};
use flexrig::safety::{ContactKind, ContactLaw, FeLink};

fn points() -> Vec<ArmPoint> {
    let mut p = bundled::ur5_points();
    for (link, xyz) in [
        ("upper_arm_link", [0.0, 0.0, 0.2]),
        ("upper_arm_link", [0.0, 0.0, 0.4]),
        ("wrist_1_link", [0.0; 3]),
        ("wrist_3_link", [0.0; 3]),
        ("tool0", [0.0; 3]),
        ("forearm_link", [0.0, 0.0, 0.35]),
    ] {
        p.push(ArmPoint {
            link: link.into(),
            xyz,
        });
    }
    p
}

fn input(law: ContactLaw, k_delta: Option<f64>) -> ArmInput {
    ArmInput {
        points: points(),
        joints: ArmJoints::Rigid,
        speed_scale: 1.0,
        mass_step: 0.01,
        region: "chest".into(),
        area: None,
        contact: ContactKind::Transient,
        law,
        area_model: None,
        link: FeLink::CompliantJoint,
        k_delta,
        link_mass: None,
        simulation: simulation_settings(ArmDrive::Free, 1e-6, 1e-6),
        methods: vec![],
    }
}

fn bench(c: &mut Criterion) {
    let robot = bundled::ur5().unwrap();
    let swing = bundled::ur5_swing(&robot).unwrap();
    let (q0, q1) = (
        swing.positions()[0].clone(),
        swing.positions()[swing.len() - 1].clone(),
    );
    let n = 1000;
    let times: Vec<f64> = (0..n).map(|i| 1.5 * i as f64 / (n - 1) as f64).collect();
    let positions = times
        .iter()
        .map(|t| {
            let s = t / 1.5;
            let h = s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
            q0.iter().zip(&q1).map(|(a, b)| a + (b - a) * h).collect()
        })
        .collect();
    let traj = Trajectory::new(&robot, times, positions).unwrap();
    let mut g = c.benchmark_group("arm");
    g.sample_size(10);
    for (name, arm) in [
        (
            "1000 x 10 x 1, rigid, body spring",
            input(ContactLaw::BodySpring, None),
        ),
        (
            "1000 x 10 x 1, CJ 2e4 N/m, skinned aluminium",
            input(ContactLaw::Material("skinned_aluminium".into()), Some(2e4)),
        ),
        (
            "1000 x 10 x 1, CJ 2e4 N/m, skinned aluminium, 5 % mass grid",
            ArmInput {
                mass_step: 0.05,
                ..input(ContactLaw::Material("skinned_aluminium".into()), Some(2e4))
            },
        ),
    ] {
        let r = judge(&robot, &traj, &arm, None).unwrap();
        eprintln!(
            "{name}: {} distinct masses, scale factor {:?}",
            r.masses.len(),
            r.speed_scale_factor
        );
        g.bench_function(name, |b| {
            b.iter(|| judge(&robot, &traj, &arm, None).unwrap())
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
