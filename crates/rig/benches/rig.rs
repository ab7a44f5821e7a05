//! Whole scenes from release to separation, with the adaptive free flight (the default) and the
//! fixed-step swing (`solver.swing = "fixed"`):
//!
//! - the bundled settings (800 steps per contact) and 100 steps per contact;
//! - the cheapest contact steps at a peak error ≤ 1e-3 and ≤ 1e-4 against a converged run
//!   (12 800 steps per contact; `cargo run --release -p flexrig-rig --example work_error`):
//!   CJ 40 (6.8e-4) and 140 (5.6e-5), CL (16 corotational elements) 25 (8.7e-4) and 100
//!   (5.2e-5);
//! - the CL link as the modal-reduced beam (8 modes; tests/modal_link.rs for its accuracy).
//!
//! Names: `{scene}[_modal8]_release_to_separation_{contact steps}[_fixed]`; the names without
//! `_fixed` are those of the earlier benches (they now take the default, adaptive swing).

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
        &format!("contact_steps = {contact_steps}{extra}"),
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

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = bench
}
criterion_main!(benches);
