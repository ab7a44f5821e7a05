//! Cost of one free-mass impact (issue 14): `cargo bench -p flexrig-impact`.
use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_impact::eta::{EtaSettings, case_setup};
use flexrig_impact::{ClSolver, cj, cl};
use flexrig_lumped::fig6::Fig6Case;
use std::hint::black_box;

fn bench(c: &mut Criterion) {
    let headline = Fig6Case {
        m_h: 4.0,
        k_delta: 1e8,
        m_e: 0.1,
    };
    let soft = Fig6Case {
        k_delta: 2e2,
        ..headline
    };
    let s = case_setup(&headline, 1.0, &EtaSettings::DEFAULT).unwrap();
    c.bench_function("cj_headline_rtol1e-10", |b| {
        b.iter(|| cj::run_cj(black_box(&s), 1e-10).unwrap())
    });
    for (name, case, elements, steps, modes) in [
        ("cl_headline_16el_200", headline, 16, 200, None),
        ("cl_headline_64el_800", headline, 64, 800, None),
        ("cl_headline_32el_8modes_200", headline, 32, 200, Some(8)),
        ("cl_headline_32el_8modes_100", headline, 32, 100, Some(8)),
        ("cl_soft_128el_400", soft, 128, 400, None),
    ] {
        let s = case_setup(&case, 1.0, &EtaSettings::DEFAULT).unwrap();
        let solver = ClSolver {
            elements,
            steps_per_contact: steps,
            modes,
        };
        c.bench_function(name, |b| {
            b.iter(|| cl::run_cl(black_box(&s), &solver).unwrap())
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
