//! `flexrig spin-up` at its defaults (the reference, the FE beam, the linear model, the CSV,
//! JSON and SVG written), and with Kane, Ryan & Banerjee's beam: floor ≤ 2 s
//! (`cargo bench -p flexrig --bench spin_up`; docs/driven.md, docs/performance.md).
use criterion::{Criterion, criterion_group, criterion_main};
use flexrig::CancelToken;
use flexrig::driven::spin_up::{SpinUpCase, run};

fn bench(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("flexrig-bench-spin-up-{}", std::process::id()));
    for (name, case) in [
        ("simo_vu_quoc", SpinUpCase::SimoVuQuoc),
        ("kane", SpinUpCase::Kane),
    ] {
        let options = case.options();
        c.bench_function(&format!("spin_up_defaults_{name}"), |b| {
            b.iter(|| run(&options, &dir, &CancelToken::new()).unwrap())
        });
    }
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
