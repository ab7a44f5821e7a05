//! `--set PATH=VALUE` overrides: the same validation as the file, errors name the path.

mod common;

use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, Override, RigError, RunOptions, Scene, scene_with_overrides};

fn with(name: &str, sets: &[&str]) -> Result<Scene, RigError> {
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    scene_with_overrides(
        &common::scene_text(name),
        &overrides,
        &Materials::bundled().unwrap(),
    )
}

fn peak(scene: &Scene) -> f64 {
    flexrig_rig::Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut NoRecorder)
        .unwrap()
        .peak_force_n
}

#[test]
fn an_override_is_the_same_as_editing_the_file() {
    let set = with(
        "cj_aluminium",
        &[
            "robot.payload_kg=0.2",
            "operator.start.release_angle_deg=45",
            "operator.start.from=contact",
        ],
    )
    .unwrap();
    let edited = common::scene(
        "cj_aluminium",
        &[
            ("payload_kg = 0.412", "payload_kg = 0.2"),
            (
                "start = { from = \"release\", release_angle_deg = 30.0 }",
                "start = { from = \"contact\", release_angle_deg = 45.0 }",
            ),
        ],
    );
    assert_eq!(set.file, edited.file);
    assert_eq!(peak(&set), peak(&edited));
    // a design switch and an inline table
    let cl = with(
        "cj_aluminium",
        &[
            "robot.design=cl",
            "solver.beam={ model = \"modal\", modes = 8 }",
        ],
    )
    .unwrap();
    assert_eq!(cl.file.robot.design, flexrig_rig::Design::Cl);
}

#[test]
fn bad_overrides_name_the_path() {
    for (set, path) in [
        ("robot.payload_kg=-1", "robot.payload_kg"),
        ("robot.payload_kg=heavy", "robot.payload_kg"),
        ("robot.no_such_field=1", "robot.no_such_field"),
        ("robot.design=wobbly", "robot.design"),
        ("robot.payload_kg.x=1", "robot.payload_kg"),
        ("solver.contact_steps=0.5", "solver.contact_steps"),
        (
            "operator.start.release_angle_deg=400",
            "operator.start.release_angle_deg",
        ),
    ] {
        let e = with("cj_aluminium", &[set]).unwrap_err();
        let m = e.to_string();
        assert!(m.contains(path), "{set}: {m}");
        assert!(e.is_input_error(), "{set}: {m}");
    }
    assert!(Override::parse("robot.payload_kg").is_err());
}

#[test]
fn a_very_deep_override_path_is_refused_not_a_stack_overflow() {
    // Regression: `--set a.a.a…=1` with thousands of levels overflowed the stack (run) or
    // exhausted the memory (experiment) while the tables were built and serialised.
    let deep = format!("{}x=1", "robot.".repeat(20_000));
    let e = Override::parse(&deep).unwrap_err();
    let m = e.to_string();
    assert!(e.is_input_error(), "{m}");
    assert!(m.contains("--set") && m.contains("levels"), "{m}");
    assert!(m.len() < 600, "{} characters", m.len());
    // the bound is above every real field and refuses one level more
    let at_bound = format!(
        "{}x=1",
        "a.".repeat(flexrig_rig::overrides::MAX_PATH_DEPTH - 1)
    );
    assert!(Override::parse(&at_bound).is_ok());
    let over = format!("{}x=1", "a.".repeat(flexrig_rig::overrides::MAX_PATH_DEPTH));
    assert!(Override::parse(&over).is_err());
    // a path built in code (as the Python front does) meets the same bound when applied
    let o = Override::new(&"robot.".repeat(5_000), toml::Value::Integer(1));
    let e = scene_with_overrides(
        &common::scene_text("cj_aluminium"),
        &[o],
        &Materials::bundled().unwrap(),
    )
    .unwrap_err();
    assert!(e.is_input_error(), "{e}");
}

#[test]
fn a_very_deep_override_value_is_refused_naming_the_path() {
    // Regression: a value nesting arrays thousands deep (from Python: a cyclic or very deep
    // list) reached the serialiser. (2000 levels: deep enough to be refused, shallow enough for
    // the test's own recursive drop.)
    let mut v = toml::Value::Integer(1);
    for _ in 0..2_000 {
        v = toml::Value::Array(vec![v]);
    }
    let e = scene_with_overrides(
        &common::scene_text("cj_aluminium"),
        &[Override::new("robot.payload_kg", v)],
        &Materials::bundled().unwrap(),
    )
    .unwrap_err();
    let m = e.to_string();
    assert!(
        m.contains("robot.payload_kg") && m.contains("levels deep"),
        "{m}"
    );
    // the depth counter stops at its limit instead of walking the whole value
    let mut wide = toml::Value::Integer(0);
    for _ in 0..3 {
        wide = toml::Value::Array(vec![wide.clone(), wide]);
    }
    assert_eq!(flexrig_rig::overrides::value_depth(&wide, 8), 3);
    assert_eq!(
        flexrig_rig::overrides::value_depth(&toml::Value::Float(1.0), 8),
        0
    );
}

#[test]
fn a_wrong_type_is_said_in_the_scene_files_words() {
    // Regression: "expected struct RobotSpec", "internally tagged enum Start", "expected usize"
    for (set, words) in [
        ("robot=1", "a table of fields"),
        ("operator.start=\"contact\"", "{ from = \"release\""),
        ("robot.beam_elements=-3", "a whole number"),
        ("stop.at=1", "a name"),
        ("contact.damping=\"none\"", "{ model = \"none\" }"),
    ] {
        let m = with("cj_aluminium", &[set]).unwrap_err().to_string();
        assert!(m.contains(words), "{set}: {m}");
        for rust in [
            "struct ",
            "usize",
            "enum ",
            "variant identifier",
            "f64",
            "Spec",
        ] {
            assert!(!m.contains(rust), "{set}: {m}");
        }
    }
    // a range says its unit and plain bounds, and spots millimetres
    let m = with("cj_aluminium", &["robot.length_m=338"])
        .unwrap_err()
        .to_string();
    assert!(
        m.contains("[0.01, 10] m") && m.contains("millimetres"),
        "{m}"
    );
    let m = with("cj_aluminium", &["robot.payload_kg=1e300"])
        .unwrap_err()
        .to_string();
    assert!(m.contains("1e300") && m.contains("[0, 10000] kg"), "{m}");
}
