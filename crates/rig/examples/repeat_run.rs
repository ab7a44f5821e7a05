//! Runs a scene file N times in one process, for profilers (`perf record`, `valgrind
//! --tool=callgrind`: instructions per run = total / N): `cargo run --release -p flexrig-rig
//! --example repeat_run -- SCENE.toml N [lean|full]`. Prints the mean wall clock per run and the
//! summary; `lean` samples lean (`Simulation::with_lean_samples`, as `flexrig run` does), `full`
//! (the default) computes every sensor sample.
use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, RunOptions, Scene, Simulation};

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: repeat_run SCENE.toml N");
    let n: usize = args.next().and_then(|s| s.parse().ok()).unwrap_or(1000);
    let lean = args.next().as_deref() == Some("lean");
    let text = std::fs::read_to_string(&path).expect("readable scene file");
    let scene = Scene::from_toml_str(&text, &Materials::bundled().expect("bundled materials"))
        .expect("a valid scene");
    let start = std::time::Instant::now();
    let mut last = None;
    for _ in 0..n.max(1) {
        last = Some(
            Simulation::new(&scene, RunOptions::default())
                .map(|sim| if lean { sim.with_lean_samples() } else { sim })
                .and_then(|sim| sim.run(&mut NoRecorder))
                .expect("the run finishes"),
        );
    }
    let s = last.expect("at least one run");
    println!(
        "{:.3e} s per run; peak {:.12} N at {:.9e} s, {} steps ({} in contact)",
        start.elapsed().as_secs_f64() / n.max(1) as f64,
        s.peak_force_n,
        s.time_of_peak_s,
        s.steps,
        s.contact_steps
    );
}
