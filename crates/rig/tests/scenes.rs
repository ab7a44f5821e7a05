//! The bundled scenes load and are consistent with the paper; bad scenes are rejected with the
//! field path, the value and what is allowed.

mod common;

use flexrig_contact::Materials;
use flexrig_contact::tolerance::assert_close;
use flexrig_rig::{Design, Scene};

#[test]
fn bundled_scenes_match_the_paper() {
    for name in [
        "cj_aluminium",
        "cj_iron",
        "cl_aluminium",
        "cl_iron",
        "cj_light_load",
        "cl_light_load",
    ] {
        let s = common::scene(name, &[]);
        // §VI: m_r = 51 g, m_e = 412 g, k_θr = 1.2334 N·m/rad, w/t = 25, and Eq. 3 (k_θr = 3EI/L).
        assert_close(&format!("{name}: m_r"), s.link_mass_kg, 0.051, 2e-4);
        // The light-load scenes are the paper's ADAMS study (Fig. 9b): m_e = 0.1 kg.
        let payload = if name.ends_with("light_load") {
            0.1
        } else {
            0.412
        };
        assert_eq!(s.file.robot.payload_kg, payload);
        assert_close(
            &format!("{name}: w/t"),
            s.file.robot.width_m / s.file.robot.thickness_m,
            25.0,
            1e-4,
        );
        assert_close(
            &format!("{name}: Eq. 3"),
            3.0 * s.link_ei / s.file.robot.length_m,
            1.2334,
            5e-4,
        );
        assert_eq!(s.torsion_spring, 1.2334);
        assert_eq!(s.file.robot.dome_radius_m, 0.0715);
        let expected_mass = if name.ends_with("iron") { 4.008 } else { 0.398 };
        assert_eq!(s.block_mass_kg, expected_mass);
        let expected_design = if name.starts_with("cj") {
            Design::Cj
        } else {
            Design::Cl
        };
        assert_eq!(s.file.robot.design, expected_design);
    }
}

#[test]
fn bad_scenes_name_the_field() {
    let m = Materials::bundled().unwrap();
    let text = common::scene_text("cj_aluminium");
    let cases = [
        (
            "release_angle_deg = 30.0",
            "release_angle_deg = 0.0",
            "operator.start.release_angle_deg",
        ),
        (
            "release_angle_deg = 30.0",
            "release_angle_deg = 200.0",
            "(0, 170]",
        ),
        (
            "arm_length_m = 0.30",
            "arm_length_m = -0.3",
            "operator.arm_length_m",
        ),
        (
            "thickness_m = 0.0025824",
            "thickness_m = 0.0",
            "robot.thickness_m",
        ),
        (
            "block_material = \"skinned_aluminium\"",
            "block_material = \"steel\"",
            "operator.block_material",
        ),
        (
            "contact_steps = 800",
            "contact_steps = 2",
            "solver.contact_steps",
        ),
        (
            "swing_step_s = 5e-4",
            "swing_step_s = nan",
            "solver.swing_step_s",
        ),
        (
            "sample_rate_hz = 50000.0",
            "sample_rate_hz = -1.0",
            "record.sample_rate_hz",
        ),
        (
            "beam_elements = 16",
            "beam_elements = 0",
            "robot.beam_elements",
        ),
        (
            "damping = { model = \"none\" }",
            "damping = { model = \"hunt_crossley\", restitution = 1.5 }",
            "contact.damping.restitution",
        ),
        (
            "damping = { model = \"none\" }",
            "n = -1.0\ndamping = { model = \"none\" }",
            "contact.n",
        ),
    ];
    for (from, to, expect) in cases {
        assert!(text.contains(from), "{from}");
        let e = Scene::from_toml_str(&text.replace(from, to), &m).unwrap_err();
        assert!(e.is_input_error(), "{e}");
        assert!(e.to_string().contains(expect), "{to}: {e}");
    }
    // Unknown keys and a wrong design are syntax errors naming the key.
    let e = Scene::from_toml_str(&text.replace("design = \"cj\"", "design = \"soft\""), &m)
        .unwrap_err();
    assert!(
        e.to_string().contains("soft") || e.to_string().contains("design"),
        "{e}"
    );
    let e = Scene::from_toml_str(
        &text.replace("payload_kg = 0.412", "payload_kg = 0.412\ncolour = 1"),
        &m,
    )
    .unwrap_err();
    assert!(e.to_string().contains("colour"), "{e}");
}

#[test]
fn a_field_the_beam_model_does_not_take_is_a_scene_error() {
    let text = common::scene_text("cl_aluminium").replace(
        "contact_steps = 800",
        "contact_steps = 800\nbeam = { model = \"linear\", modes = 4 }",
    );
    let e = Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap_err();
    assert!(e.to_string().contains("modes"), "{e}");
}

#[test]
fn a_field_the_damping_model_does_not_take_is_a_scene_error() {
    let text = common::scene_text("cl_aluminium").replace(
        "damping = { model = \"none\" }",
        "damping = { model = \"none\", restitution = 0.5 }",
    );
    let e = Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap_err();
    assert!(e.to_string().contains("restitution"), "{e}");
}
