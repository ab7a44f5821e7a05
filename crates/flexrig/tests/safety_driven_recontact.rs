//! Every contact of a driven scene counts in the safety verdict: a light link on a soft torsion
//! spring, its hub turned at a constant commanded speed, strikes a free hand (the region's
//! 0.6 kg), bounces back and strikes it again harder (its contact sequence is checked against
//! an independent solution of the exact geometry in crates/impact/tests/driven_recontact.rs).
//! The permissible speed is where the largest contact reaches the hand's limit; a run at that
//! speed reaches it (1e-4), a run 0.1 % slower stays below it, and the first contact alone
//! would have allowed a faster, unsafe speed.

use std::sync::atomic::AtomicBool;

#[path = "../../impact/tests/support/driven_cj_reference.rs"]
mod driven_cj_reference;

use flexrig::safety::{ContactKind, ContactLaw, SafetyInput, SafetyMethod, safety};

const LIGHT_CJ_HAND: &str = r#"
name = "light_cj_hand"
design = "cj"
horizon_s = 5.0
link_model = "exact"
[link]
m_r = 0.3
length = 0.5
k_delta = 2000.0
m_e = 0.02
[drive.motor]
rotor_inertia = 0.0
gear_ratio = 1.0
friction = 0.0
[drive.command]
command = "trajectory"
[drive.command.profile]
profile = "steady"
speed = 3.0
[person]
m_h = 0.6
speed = 0.0
[person.support]
support = "free"
[person.contact]
k = 1e6
n = 1.5
[placement]
placement = "angle"
angle = 0.05
[dome]
radius_m = 0.0715
standoff_m = 0.030
"#;

/// The safety question of the LIGHT_CJ_HAND scene written to a scratch directory named by
/// `tag`: the hand region, the simulation method.
fn hand_scene_input(tag: &str) -> (std::path::PathBuf, SafetyInput) {
    let dir = std::env::temp_dir().join(format!("flexrig-driven-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("light_cj_hand.toml");
    std::fs::write(&path, LIGHT_CJ_HAND).unwrap();
    let input = SafetyInput {
        region: "hands_and_fingers".into(),
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
        scene: Some(path.to_str().unwrap().to_string()),
    };
    (dir, input)
}

#[test]
fn the_largest_of_several_driven_contacts_sets_the_permissible_speed() {
    let (dir, input) = hand_scene_input("recontact");
    let given = input.scene.clone().unwrap();
    let report = safety(&input, None).unwrap();
    let sim = report.scene.clone().unwrap();
    let limit = report.force_limit_n;
    let v = sim.by_force_mps;
    assert!(v.is_finite() && v > 0.0, "{v}");
    let contacts = sim.contacts_at_root.unwrap();
    assert!(
        contacts.governing > 1 && contacts.contacts > 1,
        "a later contact governs: {contacts:?}"
    );
    assert!(matches!(
        contacts.ended,
        flexrig_impact::RunEnd::PartedForGood(_)
    ));
    // a direct run of the same scene with the region's person
    let scene = flexrig::safety::scene::load(&given).unwrap();
    let mut judged = scene.clone();
    judged.scene.strike.person.m_h = 0.6;
    let settings = flexrig::safety::SimulationSettings::DEFAULT;
    let stop = AtomicBool::new(false);
    let largest = |v: f64| {
        judged
            .run_at(v, &settings, &stop)
            .unwrap()
            .largest_contact()
            .1
            .peak_force_n
    };
    let at = largest(v);
    assert!(
        (at / limit - 1.0).abs() < 1e-4,
        "{at} N at {v} m/s vs {limit} N"
    );
    assert!(largest(0.999 * v) < limit);
    // the first contact alone would pass a faster speed
    let first = |v: f64| {
        judged
            .run_at(v, &settings, &stop)
            .unwrap()
            .contact
            .peak_force_n
    };
    assert!(first(v) < 0.9 * limit, "first contact {} N", first(v));
    std::fs::remove_dir_all(&dir).ok();
}

/// The largest peak \[N\] of every contact by the independent solution
/// (crates/impact/tests/support/driven_cj_reference.rs, the same design as LIGHT_CJ_HAND) at
/// commanded tip speed `v` [m/s].
fn reference_largest(v: f64) -> f64 {
    let omega = v / driven_cj_reference::L;
    driven_cj_reference::reference(omega, 5.0)
        .iter()
        .map(|c| c.1)
        .fold(0.0, f64::max)
}

#[test]
fn the_driven_permissible_speed_agrees_with_the_independent_solution_of_every_contact() {
    let (dir, input) = hand_scene_input("reference");
    let report = safety(&input, None).unwrap();
    let v = report.scene.unwrap().by_force_mps;
    let limit = report.force_limit_n;
    // the reference crosses the limit within 1e-3 of the reported speed ...
    let (below, above) = (
        reference_largest(v * (1.0 - 1e-3)),
        reference_largest(v * (1.0 + 1e-3)),
    );
    println!("v = {v} m/s: reference {below} N at 0.999 v, {above} N at 1.001 v");
    assert!(
        below < limit && above >= limit,
        "{below} / {above} N around {limit} N"
    );
    // ... and stays below it at every lower speed of a 2.5 % grid (the smallest crossing)
    for k in 1..40 {
        let u = v * k as f64 / 40.0;
        let p = reference_largest(u);
        assert!(p < limit, "{p} N at {u} m/s, below the reported {v} m/s");
    }
    std::fs::remove_dir_all(&dir).ok();
}
