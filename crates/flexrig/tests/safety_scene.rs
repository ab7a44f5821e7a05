//! The simulation method of `flexrig safety --scene`: the permissible commanded speed of a driven
//! scene, found by a root search on the drive's speed. A link held at constant speed into a free
//! body on a linear contact is the standard's formula with μ = m_H (the robot's mass infinite);
//! the bundled scenes' speeds are converged (halving the root tolerance and the run's own
//! tolerance moves them by less than 1e-4); a wall is quasi-static contact, a free head
//! transient, and a transient head contact is refused with the clause.

use flexrig::safety::{
    ContactKind, ContactLaw, GoverningLimit, SafetyInput, SafetyMethod, SimulationSettings, safety,
};
use flexrig_safety::BodyModel;

fn input(scene: &str, region: &str, methods: Vec<SafetyMethod>) -> SafetyInput {
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
        methods,
        link: None,
        simulation: None,
        scene: Some(scene.into()),
    }
}

/// A driven CJ held at constant speed (an ideal position source in steady motion) with a link
/// 4e5 times stiffer than the contact, into a free chest of Table A.3's m_H = 40 kg on its
/// body spring K = 25 N/mm (n = 1).
const HELD_CJ_CHEST: &str = r#"
name = "held_cj_chest"
design = "cj"
horizon_s = 20.0
[link]
m_r = 1.0
length = 1.0
k_delta = 1e10
m_e = 0.1
[drive.motor]
rotor_inertia = 1e-4
gear_ratio = 50.0
friction = 0.0
[drive.command]
command = "trajectory"
[drive.command.profile]
profile = "steady"
speed = 0.5
[person]
m_h = 40.0
speed = 0.0
[person.support]
support = "free"
[person.contact]
k = 25000.0
n = 1.0
[placement]
placement = "angle"
angle = 1e-3
"#;

#[test]
fn a_held_link_on_a_linear_contact_gives_the_standards_speed_with_an_infinite_robot_mass() {
    // The hub moves at v whatever the contact does and the link is rigid up to k_δ: the chest
    // (m_H, spring K in series with k_δ) is struck by a body of infinite mass, so the peak force
    // is v √(m_H k_s), k_s = K k_δ/(K + k_δ) (the standard's Eq. A.5 with μ = m_H). Departures:
    // the link's vibration (K/k_δ = 2.5e-6 of the force, (ω/ω_link)² ≈ 1e-8) and the root
    // search's 1e-8: tolerance 1e-5.
    let dir = std::env::temp_dir().join(format!("flexrig_safety_scene_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("held_cj_chest.toml");
    std::fs::write(&path, HELD_CJ_CHEST).unwrap();
    let mut i = input(
        path.to_str().unwrap(),
        "chest",
        vec![SafetyMethod::Simulation],
    );
    i.simulation = Some(SimulationSettings {
        root_rtol: 1e-8,
        ..SimulationSettings::DEFAULT
    });
    let r = safety(&i, None).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let chest = model.region("chest").unwrap();
    let f_max = chest.force_limit(ContactKind::Transient).unwrap();
    let (k, k_delta) = (chest.spring_constant(), 1e10);
    let k_s = k * k_delta / (k + k_delta);
    let expected = f_max / (chest.effective_mass_kg() * k_s).sqrt();
    let sc = r.scene.as_ref().unwrap();
    let rel = (sc.by_force_mps / expected - 1.0).abs();
    assert!(rel < 1e-5, "{} vs {expected}: {rel:e}", sc.by_force_mps);
    assert_eq!(r.contact, ContactKind::Transient);
    assert_eq!(r.force_limit_n, f_max);
    // the run at the root reaches the limit
    assert!((sc.peak_force_at_root_n / f_max - 1.0).abs() < 1e-6);
}

fn converged(scene: &str, region: &str) -> (f64, f64, f64) {
    let run = |halve: f64| {
        let mut i = input(scene, region, vec![SafetyMethod::Simulation]);
        let d = SimulationSettings::DEFAULT;
        i.simulation = Some(SimulationSettings {
            tol: d.tol * halve,
            cj_rtol: d.cj_rtol * halve,
            root_rtol: d.root_rtol * halve,
            ..d
        });
        let r = safety(&i, None).unwrap();
        (r.scene.unwrap().by_force_mps, r.force_limit_n)
    };
    let (v, f) = run(1.0);
    let (v_half, _) = run(0.5);
    (v, v_half, f)
}

#[test]
fn the_driven_cj_wall_speed_is_converged_and_quasi_static() {
    let (v, v_half, f) = converged("driven_cj_wall", "chest");
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let chest = model.region("chest").unwrap();
    assert_eq!(f, chest.force_limit(ContactKind::QuasiStatic).unwrap());
    assert!(v > 0.0 && v.is_finite(), "{v}");
    assert!((v_half / v - 1.0).abs() < 1e-4, "{v} vs {v_half}");
}

#[test]
fn the_driven_cl_free_head_speed_is_converged_and_transient() {
    let (v, v_half, f) = converged("driven_cl_free_head", "chest");
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let chest = model.region("chest").unwrap();
    assert_eq!(f, chest.force_limit(ContactKind::Transient).unwrap());
    assert!(v > 0.0 && v.is_finite(), "{v}");
    assert!((v_half / v - 1.0).abs() < 1e-4, "{v} vs {v_half}");
}

#[test]
fn a_free_head_scene_on_the_skull_is_refused_with_the_clause() {
    let i = input(
        "driven_cj_free_head",
        "skull_and_forehead",
        vec![SafetyMethod::Simulation],
    );
    let e = safety(&i, None).unwrap_err().to_string();
    assert!(e.contains("5.5.5.4"), "{e}");
}

#[test]
fn a_scene_without_a_drive_or_with_design_flags_is_refused_naming_the_flag() {
    let e = safety(
        &input("cj_aluminium", "chest", vec![SafetyMethod::Energy]),
        None,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("--scene") && e.contains("[drive]"), "{e}");
    let mut i = input("driven_cj_wall", "chest", vec![SafetyMethod::Energy]);
    i.k_delta = Some(5.0);
    let e = safety(&i, None).unwrap_err().to_string();
    assert!(e.contains("--k-delta"), "{e}");
}

#[test]
fn the_scene_report_lists_the_search_and_ends_on_the_methods_speed() {
    let i = input(
        "driven_cj_wall",
        "chest",
        vec![
            SafetyMethod::Standard,
            SafetyMethod::Energy,
            SafetyMethod::Simulation,
        ],
    );
    let (r, doc, trace) = flexrig::safety_report::report_document(&i, None, None).unwrap();
    let md = doc.markdown();
    assert!(md.contains("driven_cj_wall"), "{md}");
    let sim = r
        .methods
        .iter()
        .find(|m| m.method == SafetyMethod::Simulation)
        .unwrap();
    assert_eq!(sim.governing, GoverningLimit::Force);
    let last = trace.last().unwrap();
    let v = sim.by_force_mps.value();
    assert!((last.speed_mps / v - 1.0).abs() < 1e-5, "{last:?} vs {v}");
    assert!((last.ratio - 1.0).abs() < 1e-5, "{last:?}");
}
