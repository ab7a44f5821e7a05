//! The cost of MCAP logging: a whole CJ scene (release to separation) without a recorder and
//! with the MCAP recorder writing to memory (uncompressed indexed chunks, as to a file).

use std::hint::black_box;
use std::io::Cursor;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig::log::mcap::McapRecorder;
use flexrig::testbed::scenes::BUNDLED_SCENES;
use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, RunOptions, Scene, Simulation};

fn bench(c: &mut Criterion) {
    let materials = Materials::bundled().unwrap();
    for name in ["cj_aluminium", "cl_aluminium"] {
        let text = BUNDLED_SCENES.iter().find(|(n, _)| *n == name).unwrap().1;
        let scene = Scene::from_toml_str(text, &materials).unwrap();
        c.bench_function(&format!("{name}_open_and_close_log"), |b| {
            b.iter(|| {
                let log = McapRecorder::new(Cursor::new(Vec::new()), &scene, text).unwrap();
                log.finish(None).unwrap();
            })
        });
        c.bench_function(&format!("{name}_no_log"), |b| {
            b.iter(|| {
                Simulation::new(black_box(&scene), RunOptions::default())
                    .unwrap()
                    .run(&mut NoRecorder)
                    .unwrap()
            })
        });
        c.bench_function(&format!("{name}_mcap_log"), |b| {
            b.iter(|| {
                let mut log = McapRecorder::new(Cursor::new(Vec::new()), &scene, text).unwrap();
                let s = Simulation::new(black_box(&scene), RunOptions::default())
                    .unwrap()
                    .run(&mut log)
                    .unwrap();
                log.write_summary(&s).unwrap();
                log.finish(None).unwrap();
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
