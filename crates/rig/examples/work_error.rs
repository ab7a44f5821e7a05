//! Work against error of a whole scene, release → separation: for each swing policy and number of
//! contact steps (and, for the CJ, the adaptive contact at each tolerance), the peak-force error
//! against a converged run of the same scene (12 800 steps per contact, adaptive swing), the
//! steps (swing and contact) and the median wall clock of the in-process run. `cargo run --release -p flexrig-rig --example work_error -- [SCENE …]`
//! (default: cj_aluminium cl_aluminium).

use std::time::Instant;

use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, RunOptions, RunSummary, Scene, Simulation};

/// The scene with Rapier's contact at `contact_steps` per contact.
fn scene(name: &str, swing: &str, contact_steps: usize) -> Scene {
    scene_with(name, swing, contact_steps, "\ncontact = \"fixed\"")
}

/// The scene with the adaptive contact at relative tolerance `rtol`.
fn adaptive_contact(name: &str, rtol: f64) -> Scene {
    scene_with(
        name,
        "adaptive",
        800,
        &format!("\ncontact = \"adaptive\"\ncontact_rtol = {rtol:e}"),
    )
}

fn scene_with(name: &str, swing: &str, contact_steps: usize, extra: &str) -> Scene {
    let path = format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path)
        .expect("a bundled scene")
        .replace(
            "sample_rate_hz = 50000.0",
            &format!(
                "sample_rate_hz = {}",
                std::env::var("SAMPLE_RATE").unwrap_or("50000.0".into())
            ),
        )
        .replace(
            "contact_steps = 800",
            &format!("contact_steps = {contact_steps}\nswing = \"{swing}\"{extra}"),
        );
    Scene::from_toml_str(&text, &Materials::bundled().expect("bundled materials"))
        .expect("a valid scene")
}

/// A run as `flexrig run` makes it (lean sampling: the swing's samples nobody reads are not
/// computed; FULL_SAMPLES=1 computes every one, as before).
fn run(s: &Scene) -> RunSummary {
    let full = std::env::var_os("FULL_SAMPLES").is_some();
    Simulation::new(s, RunOptions::default())
        .map(|sim| if full { sim } else { sim.with_lean_samples() })
        .and_then(|sim| sim.run(&mut NoRecorder))
        .expect("the run finishes")
}

/// Median wall clock \[s\] of `run(s)` over enough repetitions for about 0.3 s.
fn median_time(s: &Scene) -> f64 {
    let t0 = Instant::now();
    run(s);
    let once = t0.elapsed().as_secs_f64();
    let reps = ((0.3 / once) as usize).clamp(5, 400);
    let mut times: Vec<f64> = (0..reps)
        .map(|_| {
            let t = Instant::now();
            std::hint::black_box(run(std::hint::black_box(s)));
            t.elapsed().as_secs_f64()
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[reps / 2]
}

const STEPS: [usize; 13] = [10, 15, 20, 25, 30, 40, 50, 70, 100, 140, 200, 400, 800];

/// Tolerances of the adaptive contact, coarse to fine.
const RTOLS: [f64; 10] = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11];

/// True for a scene whose contact can be integrated adaptively (the CJ).
fn has_adaptive_contact(name: &str) -> bool {
    name.starts_with("cj")
}

/// `--json --target T SCENE_PATH_OR_NAME`: for each swing policy, the cheapest contact steps
/// with a peak error ≤ T (and ≤ T at the next finer setting), as JSON lines (read by
/// scripts/peers/mujoco_testbed.py; `SAMPLE_RATE=HZ` sets the sensor rate).
fn cheapest(name: &str, target: f64) {
    let reference = run(&scene(name, "adaptive", 12_800)).peak_force_n;
    for swing in ["fixed", "adaptive"] {
        for (i, &n) in STEPS.iter().enumerate() {
            let s = scene(name, swing, n);
            let summary = run(&s);
            let error = (summary.peak_force_n / reference - 1.0).abs();
            // counted when the next finer setting also reaches the target (no lucky hit)
            let finer = STEPS.get(i + 1).map_or(0.0, |&m| {
                (run(&scene(name, swing, m)).peak_force_n / reference - 1.0).abs()
            });
            if error <= target && finer <= target {
                println!(
                    "{{\"swing\": \"{swing}\", \"contact_steps\": {n}, \"error\": {error:e}, \
                     \"steps\": {}, \"contact_steps_taken\": {}, \"peak_n\": {}, \
                     \"converged_peak_n\": {reference}, \"median_s\": {:e}, \"cheapest\": true}}",
                    summary.steps,
                    summary.contact_steps,
                    summary.peak_force_n,
                    median_time(&s)
                );
                break;
            }
        }
    }
    if !has_adaptive_contact(name) {
        return;
    }
    for (i, &rtol) in RTOLS.iter().enumerate() {
        let s = adaptive_contact(name, rtol);
        let summary = run(&s);
        let error = (summary.peak_force_n / reference - 1.0).abs();
        let finer = RTOLS.get(i + 1).map_or(0.0, |&r| {
            (run(&adaptive_contact(name, r)).peak_force_n / reference - 1.0).abs()
        });
        if error <= target && finer <= target {
            println!(
                "{{\"swing\": \"adaptive\", \"contact\": \"adaptive\", \"contact_rtol\": {rtol:e}, \
                 \"error\": {error:e}, \"steps\": {}, \"contact_steps_taken\": {}, \
                 \"peak_n\": {}, \"converged_peak_n\": {reference}, \"median_s\": {:e}, \
                 \"cheapest\": true}}",
                summary.steps,
                summary.contact_steps,
                summary.peak_force_n,
                median_time(&s)
            );
            break;
        }
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--json") {
        let target: f64 = args
            .get(2)
            .and_then(|t| t.parse().ok())
            .expect("usage: work_error --json --target T SCENE");
        let name = args
            .get(3)
            .expect("usage: work_error --json --target T SCENE");
        let name = std::path::Path::new(name)
            .file_stem()
            .and_then(|s| s.to_str())
            .expect("a scene name");
        cheapest(name, target);
        return;
    }
    let mut names = args;
    if names.is_empty() {
        names = vec!["cj_aluminium".into(), "cl_aluminium".into()];
    }
    for name in &names {
        let reference = run(&scene(name, "adaptive", 12_800)).peak_force_n;
        println!("{name}: converged peak {reference} N (12 800 steps per contact)");
        println!("swing     steps/contact  peak error  swing steps  contact steps  median [ms]");
        for swing in ["fixed", "adaptive"] {
            for n in STEPS {
                let s = scene(name, swing, n);
                let summary = run(&s);
                let error = (summary.peak_force_n / reference - 1.0).abs();
                println!(
                    "{swing:9} {n:>13}  {error:10.2e}  {:>11}  {:>13}  {:>11.3}",
                    summary.steps - summary.contact_steps,
                    summary.contact_steps,
                    1e3 * median_time(&s)
                );
            }
        }
        if has_adaptive_contact(name) {
            println!("adaptive contact: rtol  peak error  swing steps  contact steps  median [ms]");
            for rtol in RTOLS {
                let s = adaptive_contact(name, rtol);
                let summary = run(&s);
                let error = (summary.peak_force_n / reference - 1.0).abs();
                println!(
                    "{rtol:>22.0e}  {error:10.2e}  {:>11}  {:>13}  {:>11.3}",
                    summary.steps - summary.contact_steps,
                    summary.contact_steps,
                    1e3 * median_time(&s)
                );
            }
        }
    }
}
