//! Cost of a driven strike from the drive's start to the separation:
//! `cargo bench -p flexrig-impact --bench driven`.
use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::driven_cj::{CjSettings, run_driven_cj};
use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl};
use flexrig_impact::{DrivenStrike, LinkParams};
use std::hint::black_box;

/// The Fig. 6 link (m_r = 10 kg, L = 1 m) with `k_delta` and a 0.1 kg payload, a PD loop ramping
/// to 2 rad/s in 0.5 s, into a free 4 kg head 0.3 s after the ramp (n = 2).
fn ramp(k_delta: f64) -> DrivenStrike {
    DrivenStrike {
        link: LinkParams {
            m_r: 10.0,
            length: 1.0,
            k_delta,
            m_e: 0.1,
        },
        drive: Drive::controller(
            Motor::new(1e-4, 50.0, 1e-5).unwrap(),
            Profile::SmoothRamp {
                speed: 2.0,
                ramp_time: 0.5,
            },
            Gains::position_pd(500.0, 40.0),
            Some(1.0),
        )
        .unwrap(),
        person: Person {
            m_h: 4.0,
            support: HeadSupport::Free,
            contact: Hertz::new(1e8, 2.0).unwrap(),
            damping: DampingSpec::NONE,
            speed: 0.0,
        },
        placement: Placement::AfterRamp { settle: 0.3 },
        horizon_s: 5.0,
    }
}

/// The test bed's link (m_r = 51 g, L = 0.33802 m, k_θr = 1.2334 N·m/rad, 412 g payload)
/// ramped by a prescribed trajectory to 1 m/s at the tip in 0.5 s, into a free 4 kg head 0.1 s
/// later with the skinned-aluminium dome (the exact link's bent case,
/// crates/impact/tests/exact_link.rs `short_ramp_bent`).
fn test_bed_ramp() -> DrivenStrike {
    let l = 0.33802;
    DrivenStrike {
        link: LinkParams {
            m_r: 0.051,
            length: l,
            k_delta: 1.2334 / (l * l),
            m_e: 0.412,
        },
        drive: Drive::trajectory(
            Motor::new(1e-5, 50.0, 0.0).unwrap(),
            Profile::SmoothRamp {
                speed: 1.0 / l,
                ramp_time: 0.5,
            },
        )
        .unwrap(),
        person: Person {
            m_h: 4.0,
            support: HeadSupport::Free,
            contact: Hertz::new(7.359e7, 1.961).unwrap(),
            damping: DampingSpec::NONE,
            speed: 0.0,
        },
        placement: Placement::AfterRamp { settle: 0.1 },
        horizon_s: 5.0,
    }
}

fn bench(c: &mut Criterion) {
    // the bundled scene (assets/drives/cl_free_head.toml) by the default model
    let s = ramp(1e8);
    c.bench_function("exact_cl_bundled_free_head_from_rest", |b| {
        b.iter(|| run_exact_cl(black_box(&s), &ExactSettings::DEFAULT).unwrap())
    });
    let s = test_bed_ramp();
    c.bench_function("exact_cl_test_bed_from_rest_fast", |b| {
        b.iter(|| run_exact_cl(black_box(&s), &ExactSettings::FAST).unwrap())
    });
    c.bench_function("exact_cl_test_bed_from_rest", |b| {
        b.iter(|| run_exact_cl(black_box(&s), &ExactSettings::DEFAULT).unwrap())
    });
    let s = ramp(1e8);
    c.bench_function("exact_cl_stiff_from_rest_fast", |b| {
        b.iter(|| run_exact_cl(black_box(&s), &ExactSettings::FAST).unwrap())
    });
    for (name, k_delta) in [("soft", 2e2), ("stiff", 1e8)] {
        let s = ramp(k_delta);
        c.bench_function(&format!("driven_cl_{name}_from_rest"), |b| {
            b.iter(|| run_driven_cl(black_box(&s), &ClDriveSettings::DEFAULT).unwrap())
        });
        c.bench_function(&format!("driven_cj_{name}_from_rest"), |b| {
            b.iter(|| run_driven_cj(black_box(&s), &CjSettings::DEFAULT).unwrap())
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
