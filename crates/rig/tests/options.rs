//! Scene options: the general initial swing, damped contact laws.

mod common;

use flexrig_contact::tolerance::assert_close;
use flexrig_rig::{NoRecorder, RunOptions, RunSummary, Scene, Simulation};

fn run(scene: &Scene) -> RunSummary {
    Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut NoRecorder)
        .unwrap()
}

#[test]
fn moving_start_at_rest_is_a_release() {
    let release = run(&common::scene("cj_aluminium", &[]));
    let moving = run(&common::scene(
        "cj_aluminium",
        &[(
            "{ from = \"release\", release_angle_deg = 30.0 }",
            "{ from = \"moving\", angle_deg = -30.0, angular_velocity_rad_s = 0.0 }",
        )],
    ));
    assert_eq!(release.peak_force_n, moving.peak_force_n);
    // The integrated swing reaches the speed of the compound pendulum's energy balance.
    let scene = common::scene("cj_aluminium", &[]);
    let g = flexrig_rig::geometry::RigGeometry::of(&scene).operator;
    let v = g.bottom_angular_speed(30f64.to_radians(), 9.81) * g.arm_length;
    assert_close(
        "impact speed of the 30° release",
        release.impact_velocity_mps,
        v,
        1e-5,
    );
    // Swinging away first at 1 rad/s from −10°: it comes back at the energy speed
    // ω_b² = ω² + 2 M g l_c (1 − cos φ)/J.
    let scene = common::scene(
        "cj_aluminium",
        &[(
            "{ from = \"release\", release_angle_deg = 30.0 }",
            "{ from = \"moving\", angle_deg = -10.0, angular_velocity_rad_s = -1.0 }",
        )],
    );
    let g = flexrig_rig::geometry::RigGeometry::of(&scene).operator;
    let expected = flexrig_rig::geometry::rate_at_bottom(
        g.mass,
        g.com_distance,
        g.inertia_pivot,
        9.81,
        10f64.to_radians(),
        1.0,
    ) * g.arm_length;
    let s = run(&scene);
    assert_close(
        "impact speed after swinging away",
        s.impact_velocity_mps,
        expected,
        2e-4,
    );
    // Elastic contact: the bodies part at the approach speed.
    assert_close(
        "restitution of the undamped law",
        s.separation_velocity_mps.unwrap(),
        s.impact_velocity_mps,
        1e-3,
    );
}

#[test]
fn damped_laws_dissipate_and_lower_the_restitution() {
    for (damping, low, high) in [
        (
            "{ model = \"hunt_crossley\", restitution = 0.8 }",
            0.75,
            0.85,
        ),
        (
            "{ model = \"lankarani_nikravesh\", restitution = 0.8 }",
            0.75,
            0.85,
        ),
        (
            "{ model = \"adams_impact\", c_max_n_s_per_m = 200.0, depth_m = 1e-4 }",
            0.05,
            0.99,
        ),
    ] {
        let list = [
            ("from = \"release\"", "from = \"contact\""),
            (
                "damping = { model = \"none\" }",
                format!("damping = {damping}").leak() as &str,
            ),
        ];
        let s = run(&common::scene("cj_aluminium", &list));
        let e = s.separation_velocity_mps.unwrap() / s.impact_velocity_mps;
        assert!((low..high).contains(&e), "{damping}: restitution {e}");
        let (before, after) = s.energy_through_contact_j.unwrap();
        assert!(after < before, "{damping}: energy {before} -> {after}");
    }
    let e = flexrig_contact::Materials::bundled().unwrap();
    let text = common::scene_text("cj_aluminium").replace(
        "damping = { model = \"none\" }",
        "damping = { model = \"adams_impact\", c_max_n_s_per_m = 1.0, depth_m = 0.0 }",
    );
    let err = Scene::from_toml_str(&text, &e).unwrap_err().to_string();
    assert!(err.contains("contact.damping.depth_m"), "{err}");
}

#[test]
fn after_separation_the_swing_step_returns() {
    // A 1 s run with Rapier's contact: one contact, then the free swing at the swing step
    // (5e-4 s), not at the contact step (6e-6 s): far fewer than 1 s / 6e-6 s steps.
    let fixed = (
        "contact_steps = 800",
        "contact_steps = 800\ncontact = \"fixed\"",
    );
    let scene = common::scene(
        "cj_aluminium",
        &[
            ("at = \"separation\"", "at = \"duration\"\nduration_s = 1.0"),
            fixed,
        ],
    );
    let s = run(&scene);
    assert!(s.duration_s >= 1.0);
    assert!(
        s.steps < 5_000,
        "{} steps, {} in contact",
        s.steps,
        s.contact_steps
    );
    assert!(s.contact_steps >= 700, "{} contact steps", s.contact_steps);
    // A second contact follows within the second; the summary keeps the first one.
    let first = run(&common::scene("cj_aluminium", &[fixed]));
    assert_eq!(s.contact_duration_s, first.contact_duration_s);
    assert_eq!(s.peak_force_n, first.peak_force_n);
}
