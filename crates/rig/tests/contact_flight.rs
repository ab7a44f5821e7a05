//! The adaptive contact (`solver.contact = "adaptive"`, the CJ's default) against Rapier's contact
//! (`"fixed"`) at a fine step: every reported quantity of the contact, the sensors, the stop at the peak, a run
//! that starts in contact, and the scenes it does not take.

mod common;

use flexrig_rig::{NoRecorder, RigError, RunOptions, RunSummary, Scene, Simulation};

fn run(scene: &Scene) -> RunSummary {
    Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut NoRecorder)
        .unwrap()
}

fn with_contact(name: &str, steps: usize, adaptive: bool, edits: &[(&str, &str)]) -> Scene {
    let solver = if adaptive {
        format!("contact_steps = {steps}\ncontact = \"adaptive\"")
    } else {
        format!("contact_steps = {steps}\ncontact = \"fixed\"")
    };
    let mut all: Vec<(&str, &str)> = edits.to_vec();
    all.push(("contact_steps = 800", &solver));
    common::scene(name, &all)
}

fn close(what: &str, a: f64, b: f64, rel: f64) {
    assert!(
        (a - b).abs() <= rel * b.abs(),
        "{what}: {a} vs {b} (relative {:e}, allowed {rel:e})",
        (a / b - 1.0).abs()
    );
}

#[test]
fn every_quantity_of_the_contact_agrees_with_the_rapier_contact_at_a_fine_step() {
    // Rapier at 3200 steps per contact is second order with C ≈ 1.1/N² on the peak (≈ 1e-7);
    // the adaptive contact at its default tolerance is within 1e-7 of the reference ODE.
    for name in ["cj_aluminium", "cj_iron"] {
        let fixed = run(&with_contact(name, 3200, false, &[]));
        let a = run(&with_contact(name, 3200, true, &[]));
        println!(
            "{name}: steps {} ({} in contact) against {} ({})",
            a.steps, a.contact_steps, fixed.steps, fixed.contact_steps
        );
        close("peak", a.peak_force_n, fixed.peak_force_n, 5e-7);
        // 1e-9 s (the golden-section search resolves ~1e-10 s; Rapier's parabola vertex)
        close("time of peak", a.time_of_peak_s, fixed.time_of_peak_s, 4e-9);
        close("onset", a.onset_time_s, fixed.onset_time_s, 1e-12);
        close(
            "impact speed",
            a.impact_velocity_mps,
            fixed.impact_velocity_mps,
            1e-12,
        );
        close(
            "largest indentation",
            a.max_indentation_m,
            fixed.max_indentation_m,
            5e-7,
        );
        close("impulse", a.impulse_n_s, fixed.impulse_n_s, 1e-6);
        close(
            "duration",
            a.contact_duration_s.unwrap(),
            fixed.contact_duration_s.unwrap(),
            1e-6,
        );
        // Rapier's separation speed is read at the end of the separation step: first order in
        // the step (cj_aluminium: 1.5e-6 at 800 steps, 4e-8 at 12 800)
        close(
            "separation speed",
            a.separation_velocity_mps.unwrap(),
            fixed.separation_velocity_mps.unwrap(),
            5e-6,
        );
        let (before, after) = a.energy_through_contact_j.unwrap();
        close(
            "energy before",
            before,
            fixed.energy_through_contact_j.unwrap().0,
            1e-12,
        );
        // undamped: conserved through the contact to the tolerance
        close("energy through the contact", after, before, 1e-7);
        assert!(a.contact_steps < 30, "{} contact steps", a.contact_steps);
    }
}

#[test]
fn the_sensors_read_the_contact_force_and_the_stop_at_the_peak_lands_after_it() {
    // 50 kHz sensors: the largest sampled force is below the peak and within the variation of
    // the force over one sample period around it; the sampled force agrees with the Rapier
    // contact's (linear between its fine steps) at the same instants.
    let a = run(&with_contact("cj_aluminium", 3200, true, &[]));
    let fixed = run(&with_contact("cj_aluminium", 3200, false, &[]));
    let largest = a.samples.iter().map(|s| s.force_n).fold(0.0, f64::max);
    assert!(largest <= a.peak_force_n, "{largest} > {}", a.peak_force_n);
    close("largest sample", largest, a.peak_force_n, 2e-3);
    let mut worst: f64 = 0.0;
    for (s, r) in a.samples.iter().zip(&fixed.samples) {
        assert_eq!(s.t, r.t);
        worst = worst.max((s.force_n - r.force_n).abs());
    }
    println!("largest difference of the sampled forces {worst:e} N");
    assert!(worst < 2e-3 * a.peak_force_n, "{worst}");
    // stop at the peak: the same peak, the run ends in contact right after it
    let stopped = run(&with_contact(
        "cj_aluminium",
        3200,
        true,
        &[("at = \"separation\"", "at = \"peak\"")],
    ));
    assert_eq!(stopped.peak_force_n, a.peak_force_n);
    assert!(stopped.contact_duration_s.is_none());
    assert!(stopped.duration_s > stopped.time_of_peak_s);
    assert!(stopped.duration_s < a.onset_time_s + a.contact_duration_s.unwrap());
}

#[test]
fn a_run_that_starts_in_contact_and_a_run_to_a_duration_with_several_contacts() {
    let start = [("from = \"release\"", "from = \"contact\"")];
    let a = run(&with_contact("cj_aluminium", 3200, true, &start));
    let fixed = run(&with_contact("cj_aluminium", 3200, false, &start));
    close("peak", a.peak_force_n, fixed.peak_force_n, 5e-7);
    close(
        "impact speed",
        a.impact_velocity_mps,
        fixed.impact_velocity_mps,
        1e-12,
    );
    // 1.5 s: the pendulum swings back and strikes again; every contact as with Rapier
    let long = [("at = \"separation\"", "at = \"duration\"\nduration_s = 1.5")];
    let a = run(&with_contact("cj_aluminium", 800, true, &long));
    let fixed = run(&with_contact("cj_aluminium", 3200, false, &long));
    assert_eq!(a.contacts.len(), fixed.contacts.len());
    assert!(a.contacts.len() >= 2, "{} contacts", a.contacts.len());
    for (x, y) in a.contacts.iter().zip(&fixed.contacts) {
        close("peak", x.peak_force_n, y.peak_force_n, 2e-6);
        close("onset", x.onset_time_s, y.onset_time_s, 1e-7);
    }
}

#[test]
fn scenes_the_adaptive_contact_does_not_take_are_refused_naming_the_field() {
    let materials = flexrig_contact::Materials::bundled().unwrap();
    let cases = [
        (
            "cl_aluminium",
            "contact_steps = 800\ncontact = \"adaptive\"",
            "robot.design",
        ),
        (
            "cj_aluminium",
            "contact_steps = 800\ncontact = \"adaptive\"\nswing = \"fixed\"",
            "solver.swing",
        ),
        (
            "cj_aluminium",
            "contact_steps = 800\ncontact = \"adaptive\"\ncontact_rtol = 0.5",
            "solver.contact_rtol",
        ),
    ];
    for (name, solver, names) in cases {
        let text = common::scene_text(name).replace("contact_steps = 800", solver);
        let e = Scene::from_toml_str(&text, &materials).unwrap_err();
        let field = if names == "solver.contact_rtol" {
            "solver.contact_rtol"
        } else {
            "solver.contact"
        };
        assert!(
            matches!(&e, RigError::InvalidScene { field: f, .. } if f == field),
            "{name}: {e}"
        );
        let message = e.to_string();
        assert!(message.contains(names), "{name}: {message}");
    }
}
