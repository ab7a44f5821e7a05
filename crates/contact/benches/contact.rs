//! Hot paths of the contact crate: the Hertz force, the series-compliance force solve and the
//! force at a given energy (the core of the exact lumped peak).

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_contact::{ContactLaw, Hertz, SeriesCompliance};

fn bench(c: &mut Criterion) {
    let hertz = Hertz::new(7.359e7, 1.961).unwrap();
    c.bench_function("hertz_force", |b| {
        b.iter(|| black_box(&hertz).force(black_box(1.3e-3), 0.0))
    });
    for (name, k_delta) in [("stiff_link", 1e8), ("soft_link", 2e2)] {
        let series = SeriesCompliance::new(k_delta, Hertz::new(1e8, 2.0).unwrap()).unwrap();
        c.bench_function(&format!("series_force_{name}"), |b| {
            b.iter(|| black_box(&series).force(black_box(2.1e-3)))
        });
        c.bench_function(&format!("series_force_at_energy_{name}"), |b| {
            b.iter(|| black_box(&series).force_at_energy(black_box(3.7)))
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
