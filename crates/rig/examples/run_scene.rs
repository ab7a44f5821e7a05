//! Runs a scene file and prints the summary: `cargo run -p flexrig-rig --example run_scene -- FILE`.
use flexrig_rig::{NoRecorder, run_scene_text};

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: run_scene SCENE.toml");
    let text = std::fs::read_to_string(&path).expect("readable scene file");
    match run_scene_text(&text, &mut NoRecorder) {
        Ok(s) => {
            if let Some((a, b)) = s.energy_through_contact_j {
                println!(
                    "energy through contact: {a:.12e} -> {b:.12e} ({:.3e})",
                    (b - a) / a
                );
            }
            let duration = s
                .contact_duration_s
                .map_or("(stopped before separation)".to_string(), |d| {
                    format!("{d:.6e} s")
                });
            println!(
                "{}: peak {:.6} N at {:.6} s, v {:.6} m/s, duration {}, δmax {:.4e}, steps {} ({} in contact, dt {:.3e}), E {:.6e} -> {:.6e}, impulse {:.6e}",
                s.scene,
                s.peak_force_n,
                s.time_of_peak_s,
                s.impact_velocity_mps,
                duration,
                s.max_indentation_m,
                s.steps,
                s.contact_steps,
                s.contact_step_s,
                s.energy_initial_j,
                s.energy_final_j,
                s.impulse_n_s
            )
        }
        Err(e) => println!("error: {e}"),
    }
}
