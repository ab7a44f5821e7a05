use flexrig::arm::*;
use flexrig::safety::*;
use flexrig::safety::simulation::FeLink;
#[test]
fn explore() {
    let robot = bundled::ur5().unwrap();
    let traj = bundled::ur5_swing(&robot).unwrap();
    for (step, kd, law) in [(0.01, None, ContactLaw::BodySpring), (0.01, Some(1e5), ContactLaw::Material("skinned_aluminium".into())), (0.0, None, ContactLaw::BodySpring)] {
        let input = ArmInput { points: bundled::ur5_points(), joints: ArmJoints::Rigid, speed_scale: 1.0, mass_step: step,
            region: "chest".into(), area: None, contact: ContactKind::Transient, law, area_model: None,
            link: FeLink::CompliantJoint, k_delta: kd, link_mass: None, simulation: SimulationSettings::DEFAULT, methods: vec![] };
        let t = std::time::Instant::now();
        let r = judge(&robot, &traj, &input, None).unwrap();
        println!("step {step} kd {kd:?}: {:?} masses {} range {:.3}..{:.3} max_ratio {} scale {:?} link_mass {}", t.elapsed(), r.masses.len(), r.masses[0].effective_mass_kg, r.masses.last().unwrap().effective_mass_kg, r.max_ratio, r.speed_scale_factor, r.link_mass_kg);
        let g = r.governing.as_ref().unwrap();
        println!("  gov sample {} point {} speed {} m_u {} v {:?} {:?}", g.sample, g.label, g.speed_mps, g.reflected_mass_kg, g.v_max_mps, g.method);

    }
}
