//! Stability over the rig's parameter range: release angles 1° … 170° and operator/robot mass
//! ratios 1e-3 … 1e3 — either a result within the declared tolerance (energy through the contact,
//! momentum) or a clear error; never a panic or a NaN.

mod common;

use flexrig_rig::{NoRecorder, RunOptions, Simulation};

#[test]
fn release_angles_from_1_to_170_degrees() {
    for angle in [1.0, 5.0, 30.0, 90.0, 150.0, 170.0] {
        let scene = common::scene(
            "cj_iron",
            &[(
                "release_angle_deg = 30.0",
                &format!("release_angle_deg = {angle}"),
            )],
        );
        let s = Simulation::new(&scene, RunOptions::default())
            .unwrap()
            .run(&mut NoRecorder)
            .unwrap_or_else(|e| panic!("{angle}°: {e}"));
        assert!(
            s.peak_force_n.is_finite() && s.peak_force_n > 0.0,
            "{angle}°"
        );
        let (before, after) = s.energy_through_contact_j.unwrap();
        assert!(
            ((after - before) / before).abs() < 1e-4,
            "{angle}°: energy {before} -> {after}"
        );
        // Faster impacts, harder hits.
        assert!(s.impact_velocity_mps > 0.0);
    }
}

#[test]
fn mass_ratios_from_1e_minus_3_to_1e3() {
    // Operator block mass against the robot's 0.429 kg tip mass.
    for (design, block) in [
        ("cj", 4e-4),
        ("cj", 0.4),
        ("cj", 400.0),
        ("cl", 4e-4),
        ("cl", 400.0),
    ] {
        let scene = common::scene(
            &format!("{design}_aluminium"),
            &[(
                "block_size_m = [0.0528, 0.0528, 0.0528]",
                &format!("block_size_m = [0.0528, 0.0528, 0.0528]\nblock_mass_kg = {block}"),
            )],
        );
        match Simulation::new(&scene, RunOptions::default()).and_then(|s| s.run(&mut NoRecorder)) {
            Ok(s) => {
                assert!(
                    s.peak_force_n.is_finite() && s.peak_force_n > 0.0,
                    "{design} {block}"
                );
                let (before, after) = s.energy_through_contact_j.unwrap();
                assert!(
                    ((after - before) / before).abs() < 1e-4,
                    "{design} {block}: {before} -> {after}"
                );
            }
            Err(e) => {
                // A clear error is acceptable; it must say what happened.
                let text = e.to_string();
                assert!(
                    !text.is_empty() && !text.contains("NaN"),
                    "{design} {block}: {text}"
                );
            }
        }
    }
}
