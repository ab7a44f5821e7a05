//! Every contact of the swing counts in a test-bed scene's verdict: on `cj_iron` the heavy
//! operator's block drives on after the first contact while the light CJ link swings back on its
//! spring and strikes it again, harder. The permissible speed for the hand (280 N) is set by that
//! second contact. Checked against the rig's independent reference (its two hinges as an ODE
//! by DOP853 at 1e-13, no Rapier: crates/rig/tests/support/two_hinges.rs) followed through every
//! contact of the swing: the reference's largest peak crosses the limit within 1e-3 of the
//! reported speed, stays below it at every lower speed of a 2 % grid, and its first contact
//! alone stays well below the limit at the reported speed.
//!
//! The CL test bed follows every contact too: `cl_light_load`'s 100 g payload flies off on the
//! soft beam and strikes the block twice more; the verdict's speed is held against the rig run
//! with the other beam element (ANCF, stepped by the energy-conserving midpoint rule instead of
//! the corotational element's trapezoidal generalized-α) at a quarter of the verdict's swing step
//! after a contact, every contact of the swing.

#[path = "../../rig/tests/support/two_hinges.rs"]
mod two_hinges;

use flexrig::safety::{ContactKind, ContactLaw, SafetyInput, SafetyMethod, safety};
use flexrig_contact::Materials;
use flexrig_rig::Scene;
use flexrig_rig::geometry::RigGeometry;
use two_hinges::{TwoHinges, reference_contacts};

/// The reference's contacts of `scene` with its operator reaching the dome at `v` [m/s]
/// (released at rest from the angle the energy gives: J ω² / 2 = M g l_c (1 − cos θ₀)).
fn reference_at(scene: &Scene, v: f64) -> Vec<two_hinges::ReferenceContact> {
    let g = RigGeometry::of(scene);
    let op = &g.operator;
    let omega = v / op.arm_length;
    let cos_theta = 1.0
        - op.inertia_pivot * omega * omega
            / (2.0 * op.mass * scene.file.gravity_mps2 * op.com_distance);
    let system = TwoHinges::new(scene);
    reference_contacts(&system, [-cos_theta.acos(), 0.0, 0.0, 0.0], 5.0)
}

/// The simulation method alone on the test-bed scene `scene` for the body region `region`.
fn simulated(scene: &str, region: &str) -> SafetyInput {
    SafetyInput {
        region: region.into(),
        area: None,
        contact: ContactKind::Transient,
        m_eff: None,
        k_delta: None,
        law: ContactLaw::BodySpring,
        area_model: None,
        moving_mass: None,
        payload: 0.0,
        speed: None,
        methods: vec![SafetyMethod::Simulation],
        link: None,
        simulation: None,
        scene: Some(scene.into()),
    }
}

fn largest(contacts: &[two_hinges::ReferenceContact]) -> f64 {
    contacts.iter().map(|c| c.1).fold(0.0, f64::max)
}

#[test]
fn a_later_contact_of_the_swing_sets_the_test_beds_permissible_speed() {
    let report = safety(&simulated("cj_iron", "hands_and_fingers"), None).unwrap();
    let sim = report.scene.clone().unwrap();
    let limit = report.force_limit_n;
    let v = sim.by_force_mps;
    let at_root = sim.contacts_at_root.unwrap();
    println!("v = {v} m/s, {at_root:?}");
    assert_eq!((at_root.governing, at_root.contacts), (2, 2));
    assert!(matches!(at_root.ended, flexrig_impact::RunEnd::Rebound(_)));

    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/scenes/cj_iron.toml"),
    )
    .unwrap();
    let scene = Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap();
    let below = largest(&reference_at(&scene, v * (1.0 - 1e-3)));
    let above = largest(&reference_at(&scene, v * (1.0 + 1e-3)));
    println!("reference: {below} N at 0.999 v, {above} N at 1.001 v");
    assert!(
        below < limit && above >= limit,
        "{below} / {above} N around {limit} N"
    );
    // the smallest crossing: below the limit at every lower speed of a 2 % grid
    for k in 1..50 {
        let u = v * k as f64 / 50.0;
        let p = largest(&reference_at(&scene, u));
        assert!(p < limit, "{p} N at {u} m/s, below the reported {v} m/s");
    }
    // a direct run of the scene released from the reported angle, every contact of the swing,
    // reaches the limit (1e-4)
    let angle = sim.release_angle_at_root_deg.unwrap();
    let direct = flexrig_rig::scene_with_overrides(
        &text,
        &[
            flexrig_rig::Override::new(
                "operator.start.release_angle_deg",
                toml::Value::Float(angle),
            ),
            flexrig_rig::Override::new("stop.at", toml::Value::String("rebound".into())),
        ],
        &Materials::bundled().unwrap(),
    )
    .unwrap();
    let run = flexrig_rig::Simulation::new(&direct, flexrig_rig::RunOptions::default())
        .unwrap()
        .run(&mut flexrig_rig::NoRecorder)
        .unwrap();
    let top = run
        .contacts
        .iter()
        .map(|c| c.peak_force_n)
        .fold(0.0, f64::max);
    assert!((top / limit - 1.0).abs() < 1e-4, "direct run: {top} N");
    // the first contact alone would have allowed a faster speed
    let first = reference_at(&scene, v)[0].1;
    assert!(first < 0.9 * limit, "first contact {first} N");
}

/// `cl_light_load` released so that the block reaches the dome at `v` [m/s], every contact of
/// the swing, its beam `model` stepped at `swing_step` \[s\] after a contact and `contact_steps`
/// per contact; the largest peak force \[N\] and the number of contacts.
fn cl_run(
    tb: &flexrig::safety::test_bed::TestBedScene,
    text: &str,
    v: f64,
    model: &str,
    swing_step: f64,
    contact_steps: i64,
) -> (f64, usize) {
    let angle = tb.release_angle_for(v).unwrap();
    let scene = flexrig_rig::scene_with_overrides(
        text,
        &[
            flexrig_rig::Override::new(
                "operator.start.release_angle_deg",
                toml::Value::Float(angle),
            ),
            flexrig_rig::Override::new("stop.at", toml::Value::String("rebound".into())),
            flexrig_rig::Override::new("solver.beam.model", toml::Value::String(model.into())),
            flexrig_rig::Override::new("solver.swing_step_s", toml::Value::Float(swing_step)),
            flexrig_rig::Override::new("solver.contact_steps", toml::Value::Integer(contact_steps)),
        ],
        &Materials::bundled().unwrap(),
    )
    .unwrap();
    let run = flexrig_rig::Simulation::new(&scene, flexrig_rig::RunOptions::default())
        .unwrap()
        .run(&mut flexrig_rig::NoRecorder)
        .unwrap();
    let top = run
        .contacts
        .iter()
        .map(|c| c.peak_force_n)
        .fold(0.0, f64::max);
    (top, run.contacts.len())
}

#[test]
fn the_cl_test_beds_permissible_speed_holds_over_every_contact_with_the_other_beam_element() {
    let report = safety(&simulated("cl_light_load", "chest"), None).unwrap();
    let sim = report.scene.clone().unwrap();
    let limit = report.force_limit_n;
    let v = sim.by_force_mps;
    let at_root = sim.contacts_at_root.unwrap();
    println!("v = {v} m/s, {at_root:?}, {:?}", sim.notes);
    assert!(sim.limit_reached);
    assert!(at_root.contacts >= 2, "{at_root:?}");
    assert!(matches!(at_root.ended, flexrig_impact::RunEnd::Rebound(_)));
    let h = flexrig::safety::test_bed::CL_FLIGHT_STEP_S;

    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../assets/scenes/cl_light_load.toml"),
    )
    .unwrap();
    let tb = flexrig::safety::test_bed::TestBedScene::parse("cl_light_load", &text).unwrap();
    // the other element at a quarter of the step after a contact, twice the contact steps
    let (below, n_below) = cl_run(&tb, &text, v * (1.0 - 1e-3), "ancf", h / 4.0, 1600);
    let (above, n_above) = cl_run(&tb, &text, v * (1.0 + 1e-3), "ancf", h / 4.0, 1600);
    println!("ANCF: {below} N ({n_below} contacts) at 0.999 v, {above} N ({n_above}) at 1.001 v");
    assert!(
        below < limit && above >= limit,
        "{below} / {above} N around {limit} N"
    );
    // the smallest crossing: below the limit on a grid of lower speeds from the energy floor
    // (below it no contact can reach the limit) up to the reported speed
    let floor = tb.energy_floor(limit).unwrap();
    assert!(floor < v, "{floor} vs {v}");
    for k in 0..10 {
        let u = floor + (v - floor) * k as f64 / 10.0;
        let (p, n) = cl_run(&tb, &text, u, "ancf", h / 2.0, 800);
        println!("ANCF at {u} m/s: {p} N, {n} contacts");
        assert!(p < limit, "{p} N at {u} m/s, below the reported {v} m/s");
    }
    // a direct run with the verdict's own element and steps reaches the limit (1e-4)
    let (top, _) = cl_run(&tb, &text, v, "corotational", h, 800);
    assert!((top / limit - 1.0).abs() < 1e-4, "direct run: {top} N");
}
