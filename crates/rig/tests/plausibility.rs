//! Plausibility warnings: the bundled scenes give none; each suspicious value gives one naming
//! its field, with the numbers recomputed here from the scene's own values.

mod common;

use flexrig_contact::Materials;
use flexrig_rig::plausibility::{Warning, warnings};
use flexrig_rig::{Override, scene_with_overrides};

fn warned(name: &str, sets: &[&str]) -> Vec<Warning> {
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let materials = Materials::bundled().unwrap();
    let scene = scene_with_overrides(&common::scene_text(name), &overrides, &materials).unwrap();
    warnings(&scene, &materials)
}

#[test]
fn the_bundled_scenes_are_plausible() {
    for name in [
        "cj_aluminium",
        "cj_iron",
        "cj_light_load",
        "cl_aluminium",
        "cl_iron",
        "cl_light_load",
    ] {
        assert_eq!(warned(name, &[]), vec![], "{name}");
    }
}

#[test]
fn a_release_angle_in_radians_is_suspected() {
    let w = warned("cj_aluminium", &["operator.start.release_angle_deg=0.52"]);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].field, "operator.start.release_angle_deg");
    // 0.52 rad = 29.79°
    assert!(w[0].message.contains("29.8°"), "{}", w[0].message);
    assert!(warned("cj_aluminium", &["operator.start.release_angle_deg=3.5"]).is_empty());
}

#[test]
fn an_exponent_changed_without_its_stiffness_is_suspected() {
    let w = warned("cj_aluminium", &["contact.n=1.5"]);
    let n = w
        .iter()
        .find(|w| w.field == "contact.n")
        .expect("a contact.n warning");
    // skinned aluminium: k = 7.359e7, n = 1.961 (paper §III-B); at 1 mm the force changes by
    // 1e-3^(1.5 - 1.961) = 24.1
    assert!(n.message.contains("×24.1"), "{}", n.message);
    // with both given, nothing to say
    assert!(
        warned("cj_aluminium", &["contact.n=1.5", "contact.k=1e7"])
            .iter()
            .all(|w| w.field != "contact.n")
    );
}

#[test]
fn an_indentation_deeper_than_the_block_is_suspected() {
    // The n = 1.961 stiffness with another exponent; lumped estimate ½ μ v² = k δ^(n+1)/(n+1)
    // with ½ μ v² ≈ 0.09 J: n = 2.5 gives δ ≈ 4 mm (no warning), n = 6 δ ≈ 70 mm, more than
    // half the 52.8 mm block.
    let deep = |w: &[Warning]| w.iter().any(|w| w.field == "operator.block_size_m");
    assert!(!deep(&warned("cj_aluminium", &["contact.n=2.5"])));
    let w = warned("cj_aluminium", &["contact.n=6"]);
    let block = w
        .iter()
        .find(|w| w.field == "operator.block_size_m")
        .expect("an indentation warning");
    assert!(block.message.contains("52.8 mm"), "{}", block.message);
}

#[test]
fn a_dome_radius_is_said_not_to_change_the_fitted_law() {
    let w = warned("cj_aluminium", &["robot.dome_radius_m=0.03"]);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].field, "robot.dome_radius_m");
    assert!(w[0].message.contains("0.0715"), "{}", w[0].message);
}

#[test]
fn a_joint_spring_left_behind_by_the_link_is_suspected() {
    // the bundled CJ spring is 3EI/L of the CL link (E = 1.5 GPa, w = 64.559 mm,
    // t = 2.5824 mm, L = 338.02 mm); at L = 0.5 m, 3EI/L = 0.83382 N·m/rad: +47.9 %
    let w = warned("cj_aluminium", &["robot.length_m=0.5"]);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].field, "robot.torsion_spring_nm_per_rad");
    let ei = 1.5e9 * 0.064559 * 0.0025824f64.powi(3) / 12.0;
    let matched = 3.0 * ei / 0.5;
    let percent = ((1.2334 / matched - 1.0) * 1000.0).round() / 10.0;
    assert!((percent - 47.9).abs() < 0.15, "{percent}");
    assert!(
        w[0].message.contains(&format!("{percent} %")),
        "{}",
        w[0].message
    );
    // the matched spring follows the link: the run equals one with 3EI/L given
    assert!(
        warned(
            "cj_aluminium",
            &[
                "robot.length_m=0.5",
                "robot.torsion_spring_nm_per_rad=matched"
            ]
        )
        .is_empty()
    );
    let materials = Materials::bundled().unwrap();
    let text = common::scene_text("cj_aluminium");
    let spring = |sets: &[&str]| {
        let o: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
        scene_with_overrides(&text, &o, &materials)
            .unwrap()
            .torsion_spring
    };
    let matched = spring(&[
        "robot.length_m=0.5",
        "robot.torsion_spring_nm_per_rad=matched",
    ]);
    assert!(
        (matched / (3.0 * ei / 0.5) - 1.0).abs() < 1e-12,
        "{matched}"
    );
    let e = scene_with_overrides(
        &text,
        &[Override::parse("robot.torsion_spring_nm_per_rad=stiff").unwrap()],
        &materials,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("\"matched\""), "{e}");
    // a CL scene ignores the CJ spring
    assert!(warned("cl_aluminium", &["robot.length_m=0.5"]).is_empty());
}

/// Regression: a swing step as long as a sizeable part of the swing ran without a word.
#[test]
fn a_swing_step_too_large_for_the_swing_is_suspected() {
    use flexrig_rig::canonical::compound_pendulum_period;
    use flexrig_rig::geometry::RigGeometry;
    let materials = Materials::bundled().unwrap();
    let scene = scene_with_overrides(&common::scene_text("cj_iron"), &[], &materials).unwrap();
    // the bound recomputed from the pendulum: T/4 over 20 steps
    let g = RigGeometry::of(&scene);
    let period = compound_pendulum_period(&g.operator, scene.file.gravity_mps2, 1e-6);
    let bound = period / 80.0;
    // an independent check of the period: 2π √(J/(m g l)) of the pendulum's own numbers
    let op = &g.operator;
    let small = 2.0
        * std::f64::consts::PI
        * (op.inertia_pivot / (op.mass * scene.file.gravity_mps2 * op.com_distance)).sqrt();
    assert!((period / small - 1.0).abs() < 1e-9, "{period} vs {small}");
    let below = format!("solver.swing_step_s={:e}", 0.9 * bound);
    assert!(warned("cj_iron", &[&below]).is_empty());
    let above = format!("solver.swing_step_s={:e}", 1.1 * bound);
    let w = warned("cj_iron", &[&above]);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].field, "solver.swing_step_s");
    assert!(
        w[0].message.contains("fewer than 20 steps"),
        "{}",
        w[0].message
    );
}

/// The robot's payload, link length and drive speed by the rule every front shares (a mass
/// above 200 kg, a length above 5 m, a tip speed |ω| L above 10 m/s): 40 rad/s on the 0.33802 m
/// link is 13.5208 m/s at the tip, and 40°/s would be 0.698132 rad/s.
#[test]
fn the_robots_masses_lengths_and_speeds_follow_the_shared_rule() {
    let w = warned("cj_aluminium", &["robot.payload_kg=412"]);
    assert_eq!(w.len(), 1, "{w:?}");
    assert_eq!(w[0].field, "robot.payload_kg");
    assert!(
        w[0].message.contains("412 g is 0.412 kg"),
        "{}",
        w[0].message
    );
    let w = warned(
        "rig_driven_cj",
        &[
            "robot.drive.command.profile.speed=40",
            "robot.drive.command.profile.ramp_time=0.05",
            "robot.drive.placement.settle=0.02",
        ],
    );
    let speed = w
        .iter()
        .find(|w| w.field == "robot.drive.command.profile.speed")
        .expect("a speed warning");
    assert!(
        speed.message.contains("13.5208 m/s") && speed.message.contains("0.698132 rad/s"),
        "{}",
        speed.message
    );
    assert!(warned("rig_driven_cj", &[]).is_empty());
}

#[test]
fn a_cl_run_past_its_first_contact_at_the_swing_step_of_one_contact_is_warned() {
    // the second contact of cl_iron (30°) is 126.6 N at the bundled 5e-4 s and 137.2 N at
    // 5e-6 s; 2e-5 s resolves it to 4e-4
    let flight = |w: &[Warning]| {
        w.iter()
            .filter(|w| w.field == "solver.swing_step_s")
            .map(|w| w.message.clone())
            .collect::<Vec<_>>()
    };
    let w = warned("cl_iron", &["stop.at=rebound"]);
    let m = flight(&w);
    assert_eq!(m.len(), 1, "{w:?}");
    assert!(
        m[0].contains("0.0005 s") && m[0].contains("at most 2e-5 s"),
        "{}",
        m[0]
    );
    assert_eq!(
        flight(&warned(
            "cl_iron",
            &["stop.at=rebound", "solver.swing_step_s=2e-5"]
        )),
        Vec::<String>::new()
    );
    // the first contact alone (the bundled stop) and the CJ, whose swing is adaptive: nothing
    assert_eq!(flight(&warned("cl_iron", &[])), Vec::<String>::new());
    assert_eq!(
        flight(&warned("cj_iron", &["stop.at=rebound"])),
        Vec::<String>::new()
    );
}
