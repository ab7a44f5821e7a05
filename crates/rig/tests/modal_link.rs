//! The modal-reduced CL beam (scene `solver.beam = { model = "modal", modes = k }`) against the
//! full finite-element beam: linear (truncation only) and corotational (truncation plus the
//! geometric nonlinearity the reduction drops).

mod common;

use flexrig_contact::Materials;
use flexrig_contact::tolerance::{assert_close, relative_error};
use flexrig_rig::{NoRecorder, RunOptions, RunSummary, Scene, Simulation};

fn run(scene: &Scene) -> RunSummary {
    Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut NoRecorder)
        .unwrap()
}

/// `name` started at contact, run to separation, with the beam solved by `beam` (TOML).
fn cl(name: &str, beam: &str) -> RunSummary {
    let solver = format!("contact_steps = 800\nbeam = {beam}");
    run(&common::scene(
        name,
        &[
            ("from = \"release\"", "from = \"contact\""),
            ("contact_steps = 800", &solver),
        ],
    ))
}

fn modal(name: &str, modes: usize) -> RunSummary {
    cl(name, &format!("{{ model = \"modal\", modes = {modes} }}"))
}

const SCENES: [&str; 3] = ["cl_aluminium", "cl_iron", "cl_light_load"];

#[test]
fn modal_link_converges_to_the_full_linear_fe_link_with_modes() {
    // Same contact steps, same scheme: the only difference is the truncation. Measured peak and
    // duration errors (Al, Fe, light load): 2 modes ≤ 5.4e-3; 8 modes ≤ 1.2e-5 (peak),
    // 6.3e-5 (duration); 12 modes ≤ 3.2e-7 (peak), 3e-8 (duration).
    for name in SCENES {
        let full = cl(name, "{ model = \"linear\" }");
        let errors = |m: &RunSummary| {
            (
                relative_error(m.peak_force_n, full.peak_force_n, 0.0),
                relative_error(
                    m.contact_duration_s.unwrap(),
                    full.contact_duration_s.unwrap(),
                    0.0,
                ),
            )
        };
        let (p8, d8) = errors(&modal(name, 8));
        let (p12, d12) = errors(&modal(name, 12));
        assert!(p8 < 5e-5 && d8 < 2e-4, "{name}, 8 modes: {p8:.2e} {d8:.2e}");
        assert!(
            p12 < 3e-6 && d12 < 3e-6,
            "{name}, 12 modes: {p12:.2e} {d12:.2e}"
        );
    }
}

#[test]
fn geometric_nonlinearity_is_negligible_at_these_impacts() {
    // The tip turns by a few mrad: corotational vs linear measured 3.7e-7 (Al), 3.6e-6 (Fe),
    // 2.8e-6 (light load) on the peak force.
    for name in SCENES {
        let corot = cl(name, "{ model = \"corotational\" }");
        let linear = cl(name, "{ model = \"linear\" }");
        assert_close(
            &format!("{name}: linear vs corotational peak"),
            linear.peak_force_n,
            corot.peak_force_n,
            2e-5,
        );
    }
}

#[test]
fn modal_link_conserves_energy_through_contact() {
    // No damping anywhere, ρ∞ = 1: the energy before contact must be there after separation.
    for name in SCENES {
        let m = modal(name, 8);
        let (before, after) = m.energy_through_contact_j.unwrap();
        assert_close(
            &format!("{name}: energy through contact"),
            after,
            before,
            1e-5,
        );
    }
}

#[test]
fn modal_count_out_of_range_is_a_scene_error() {
    for (modes, ok) in [(0, false), (1, true), (48, true), (49, false)] {
        let text = common::scene_text("cl_aluminium").replace(
            "contact_steps = 800",
            &format!("contact_steps = 800\nbeam = {{ model = \"modal\", modes = {modes} }}"),
        );
        let r = Scene::from_toml_str(&text, &Materials::bundled().unwrap());
        match (r, ok) {
            (Ok(_), true) => {}
            (Err(e), false) => {
                let msg = e.to_string();
                assert!(
                    msg.contains("solver.beam.modes") && msg.contains(&modes.to_string()),
                    "{msg}"
                );
            }
            (r, _) => panic!("modes = {modes}: {r:?}"),
        }
    }
}
