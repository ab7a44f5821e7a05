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
