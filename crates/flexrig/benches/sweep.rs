//! The overhead of the sweep machinery (overrides on the parsed base, validation and budget,
//! the row) against the run itself: a CJ point from contact to the peak, run directly and as
//! a sweep point (the target: ≤ 5 %).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig::study::{Dimension, Sweep, SweepOptions};
use flexrig::testbed::scenes::BUNDLED_SCENES;
use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, Override, RunOptions, Simulation, scene_with_overrides};

fn bench(c: &mut Criterion) {
    let text = BUNDLED_SCENES
        .iter()
        .find(|(n, _)| *n == "cj_iron")
        .unwrap()
        .1;
    let sets = [
        "operator.start.from=contact",
        "stop={ at = \"peak\" }",
        "operator.start.release_angle_deg=35",
    ];
    let overrides: Vec<Override> = sets.iter().map(|s| Override::parse(s).unwrap()).collect();
    let scene = scene_with_overrides(text, &overrides, &Materials::bundled().unwrap()).unwrap();
    c.bench_function("cj_iron_contact_to_peak_run_only", |b| {
        b.iter(|| {
            Simulation::new(black_box(&scene), RunOptions::default())
                .unwrap()
                .run(&mut NoRecorder)
                .unwrap()
        })
    });
    let dims: Vec<Dimension> = sets
        .iter()
        .map(|s| Dimension::parse(s, &|_| Ok(String::new())).unwrap())
        .collect();
    let sweep = Sweep::new(text, dims, false).unwrap();
    let options = SweepOptions::default();
    let base: toml::Table = toml::from_str(text).unwrap();
    let materials = Materials::bundled().unwrap();
    c.bench_function("sweep_point_scene_build_only", |b| {
        b.iter(|| flexrig_rig::scene_from_table(black_box(&base), &overrides, &materials).unwrap())
    });
    c.bench_function("cj_iron_contact_to_peak_as_a_sweep_point", |b| {
        b.iter(|| sweep.run_point(black_box(0), &options))
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
