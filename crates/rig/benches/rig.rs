//! Whole scenes from release to separation: the bundled settings and the coarsest contact step
//! that keeps the peak within 1e-3 of the converged value (100 steps per contact: 1.1e-4 for CJ,
//! 5.5e-5 for CL; see tests/contact.rs for the convergence study), and the CL link as the
//! modal-reduced beam (8 modes; tests/modal_link.rs for its accuracy).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_contact::Materials;
use flexrig_rig::{NoRecorder, RunOptions, Scene, Simulation};

fn scene(name: &str, contact_steps: usize, beam: &str) -> Scene {
    let path = format!(
        "{}/../../assets/scenes/{name}.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(path).unwrap().replace(
        "contact_steps = 800",
        &format!("contact_steps = {contact_steps}{beam}"),
    );
    Scene::from_toml_str(&text, &Materials::bundled().unwrap()).unwrap()
}

fn bench(c: &mut Criterion) {
    for name in ["cj_aluminium", "cl_aluminium"] {
        let modal = "\nbeam = { model = \"modal\", modes = 8 }";
        let beams: &[(&str, &str)] = if name.starts_with("cl") {
            &[("", ""), ("_modal8", modal)]
        } else {
            &[("", "")]
        };
        for (steps, (label, beam)) in [100, 800]
            .into_iter()
            .flat_map(|s| beams.iter().map(move |b| (s, *b)))
        {
            let s = scene(name, steps, beam);
            c.bench_function(
                &format!("{name}{label}_release_to_separation_{steps}"),
                |b| {
                    b.iter(|| {
                        Simulation::new(black_box(&s), RunOptions::default())
                            .unwrap()
                            .run(&mut NoRecorder)
                            .unwrap()
                    })
                },
            );
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
