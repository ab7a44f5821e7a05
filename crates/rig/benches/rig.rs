//! Whole scenes from release to separation, with the adaptive free flight (the default) and the
//! fixed-step swing (`solver.swing = "fixed"`):
//!
//! - Rapier's contact (`solver.contact = "fixed"`, set here: the bundled CJ takes the adaptive
//!   contact by default) at the bundled 800 steps per contact and at 100;
//! - the cheapest contact steps at a peak error ≤ 1e-3 and ≤ 1e-4 against a converged run
//!   (12 800 steps per contact; `cargo run --release -p flexrig-rig --example work_error`):
//!   CJ 40 (6.8e-4) and 140 (5.6e-5), CL (16 corotational elements) 25 (8.7e-4) and 100
//!   (5.2e-5);
//! - the CL link as the modal-reduced beam (8 modes; tests/modal_link.rs for its accuracy).
//!
//! - the CJ's contact integrated adaptively (`solver.contact = "adaptive"`) at tolerances 1e-4
//!   (peak error 4e-6, the cheapest at ≤ 1e-3 and ≤ 1e-4) and 1e-8 (1e-7), with the bundled
//!   50 kHz sensors and at 1 Hz (`_sensors1hz`; also for the Rapier contact at 40 steps).
//!
//! Names: `{scene}[_modal8]_release_to_separation_{contact steps}[_fixed]`; the names without
//! `_fixed` are those of the earlier benches (they now take the default, adaptive swing);
//! `{scene}_release_to_separation_adaptive_contact_rtol{tolerance}[_sensors1hz]`.

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, RunOptions, Scene, Simulation};

fn scene(name: &str, contact_steps: usize, extra: &str) -> Scene {
    let path = format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap().replace(
        "contact_steps = 800",
        &format!("contact_steps = {contact_steps}\ncontact = \"fixed\"{extra}"),
    );
    Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap()
}

fn bench_scene(c: &mut Criterion, label: &str, s: &Scene) {
    c.bench_function(label, |b| {
        b.iter(|| {
            Simulation::new(black_box(s), RunOptions::default())
                .unwrap()
                .run(&mut NoRecorder)
                .unwrap()
        })
    });
}

/// A scene, its contact steps and its beam variants (label, solver lines).
type Case<'a> = (&'a str, &'a [usize], &'a [(&'a str, &'a str)]);

fn bench(c: &mut Criterion) {
    let modal = "\nbeam = { model = \"modal\", modes = 8 }";
    let fixed = "\nswing = \"fixed\"";
    let cases: [Case; 2] = [
        ("cj_aluminium", &[40, 100, 140, 800], &[("", "")]),
        (
            "cl_aluminium",
            &[25, 100, 800],
            &[("", ""), ("_modal8", modal)],
        ),
    ];
    for (name, steps, beams) in cases {
        for &(label, beam) in beams {
            for &n in steps {
                for (swing_label, swing) in [("", ""), ("_fixed", fixed)] {
                    let s = scene(name, n, &format!("{beam}{swing}"));
                    bench_scene(
                        c,
                        &format!("{name}{label}_release_to_separation_{n}{swing_label}"),
                        &s,
                    );
                }
            }
        }
    }
}

/// The CJ with its contact integrated adaptively, and the sensors at 1 Hz.
fn bench_adaptive_contact(c: &mut Criterion) {
    let slow = |s: String| s.replace("sample_rate_hz = 50000.0", "sample_rate_hz = 1.0");
    let cj = |extra: &str, sensors_1hz: bool| {
        let path = format!(
            "{}/../../assets/scenes/cj_aluminium.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        let mut text = std::fs::read_to_string(path)
            .unwrap()
            .replace("contact_steps = 800", extra);
        if sensors_1hz {
            text = slow(text);
        }
        Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap()
    };
    bench_scene(
        c,
        "cj_aluminium_release_to_separation_40_sensors1hz",
        &cj("contact_steps = 40\ncontact = \"fixed\"", true),
    );
    for rtol in ["1e-4", "1e-8"] {
        let solver = format!("contact_steps = 800\ncontact = \"adaptive\"\ncontact_rtol = {rtol}");
        for (suffix, sensors_1hz) in [("", false), ("_sensors1hz", true)] {
            bench_scene(
                c,
                &format!("cj_aluminium_release_to_separation_adaptive_contact_rtol{rtol}{suffix}"),
                &cj(&solver, sensors_1hz),
            );
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = bench, bench_adaptive_contact
}
criterion_main!(benches);
