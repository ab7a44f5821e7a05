//! Permissible-speed maps with the energy method (target: a 30 × 30 map well under 1 s), and
//! HIC of a sampled half-sine.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_contact::Hertz;
use flexrig_lumped::prb::PrbLink;
use flexrig_safety::{
    BodyModel, ContactAreaModel, ContactKind, EnergyContact, HicWindow, LinkStiffness, hic,
    speed_map,
};

/// Log-spaced values from `lo` to `hi`.
fn logspace(lo: f64, hi: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect()
}

fn bench(c: &mut Criterion) {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let hand = model.region("hands_and_fingers").unwrap();
    let area = hand.most_sensitive_area();
    let limits = hand.limits(Some(area), ContactKind::Transient).unwrap();
    // The paper's skinned aluminium against the 71.5 mm dome (§III-B), thin-layer area.
    let skin = Hertz::new(7.359e7, 1.961).unwrap();
    let dome = Some(ContactAreaModel::ThinLayer { radius_m: 0.0715 });
    let payloads = logspace(0.01, 5.0, 30);
    let links: Vec<LinkStiffness> = logspace(1e1, 1e7, 30)
        .into_iter()
        .map(LinkStiffness::Finite)
        .collect();
    // CJ: rigid link on a torsion spring, γ = 1; CL: compliant link, γ = 2/3 (Eq. 5); the test
    // bed's link m_r = 51 g.
    for (name, gamma) in [("cj", 1.0), ("cl", 2.0 / 3.0)] {
        let masses: Vec<f64> = payloads
            .iter()
            .map(|&m_e| PrbLink::new(gamma, 0.051, m_e).unwrap().effective_mass())
            .collect();
        let base = EnergyContact::for_region(
            hand,
            ContactKind::Transient,
            masses[0],
            skin,
            links[0],
            dome,
        )
        .unwrap();
        c.bench_function(&format!("speed_map_30x30_{name}"), |b| {
            b.iter(|| speed_map(black_box(&base), limits, &masses, &links).unwrap())
        });
    }
    let n = 1001;
    let t: Vec<f64> = (0..n).map(|i| 0.02 * i as f64 / (n - 1) as f64).collect();
    let a: Vec<f64> = t
        .iter()
        .map(|&x| 500.0 * (std::f64::consts::PI * x / 0.02).sin())
        .collect();
    c.bench_function("hic15_half_sine_1001_samples", |b| {
        b.iter(|| hic(black_box(&t), black_box(&a), HicWindow::Hic15).unwrap())
    });
    // The exact search's cost on a long trace (16385 samples of a 20 ms half-sine; before its
    // branch and bound over the window ends this took about 10 s).
    let n = 16385;
    let t: Vec<f64> = (0..n).map(|i| 0.02 * i as f64 / (n - 1) as f64).collect();
    let a: Vec<f64> = t
        .iter()
        .map(|&x| 500.0 * (std::f64::consts::PI * x / 0.02).sin())
        .collect();
    c.bench_function("hic36_half_sine_16385_samples", |b| {
        b.iter(|| hic(black_box(&t), black_box(&a), HicWindow::Hic36).unwrap())
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
