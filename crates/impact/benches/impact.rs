//! Cost of one free-mass impact and of a map (issue 14): `cargo bench -p flexrig-impact`.
use criterion::{Criterion, criterion_group, criterion_main};
use flexrig_impact::cl_modal::{run_cl_modal, run_on_modes, run_placed};
use flexrig_impact::eta::{ClMethod, EtaSettings, case_setup};
use flexrig_impact::graded::{GradedMesh, cl_tip_modes};
use flexrig_impact::map::{LogRange, MapSpec, eta_map};
use flexrig_impact::modal_run::ModalOptions;
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
    let heavy = Fig6Case {
        m_h: 1000.0,
        ..headline
    };
    let s = case_setup(&headline, 1.0, &EtaSettings::DEFAULT).unwrap();
    c.bench_function("cj_headline_rtol1e-10", |b| {
        b.iter(|| cj::run_cj(black_box(&s), 1e-10).unwrap())
    });
    // the reference method: generalized-α on a uniform mesh
    for (name, case, elements, steps, modes) in [
        ("cl_headline_16el_200", headline, 16, 200, None),
        ("cl_headline_64el_800", headline, 64, 800, None),
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
    // the fast path: graded-mesh modes + exact modal integration, whole impact incl. the
    // eigen-solve, at the map's tolerance (1e-5) and the table's (1e-6)
    for (name, case, n, tol) in [
        ("modal_cl_headline_n1_tol1e-5", headline, 1.0, 1e-5),
        ("modal_cl_headline_n1_tol1e-6", headline, 1.0, 1e-6),
        ("modal_cl_soft_n1_tol1e-5", soft, 1.0, 1e-5),
        ("modal_cl_soft_n2_tol1e-5", soft, 2.0, 1e-5),
        ("modal_cl_heavy_n1_tol1e-5", heavy, 1.0, 1e-5),
    ] {
        let s = case_setup(&case, n, &EtaSettings::DEFAULT).unwrap();
        let options = ModalOptions {
            tol,
            ..ModalOptions::DEFAULT
        };
        c.bench_function(name, |b| {
            b.iter(|| run_cl_modal(black_box(&s), &GradedMesh::DEFAULT, &options).unwrap())
        });
    }
    let s = case_setup(&soft, 1.0, &EtaSettings::DEFAULT).unwrap();
    c.bench_function("modal_cl_soft_eigen_only", |b| {
        b.iter(|| cl_tip_modes(black_box(&s), &GradedMesh::DEFAULT).unwrap())
    });
    let modes = cl_tip_modes(&s, &GradedMesh::DEFAULT).unwrap();
    let options = ModalOptions {
        tol: 1e-5,
        ..ModalOptions::DEFAULT
    };
    c.bench_function("modal_cl_soft_n1_integration_only", |b| {
        b.iter(|| run_on_modes(black_box(&s), &modes, &options).unwrap())
    });
    c.bench_function("placed_headline_tol1e-5", |b| {
        let s = case_setup(&headline, 1.0, &EtaSettings::DEFAULT).unwrap();
        b.iter(|| run_placed(black_box(&s), &options).unwrap())
    });
    // a 10 × 10 map (CJ, CL, placed, γ_eff per point) on the rayon pool
    let spec = MapSpec {
        m_h: 4.0,
        n: 2.0,
        mass_ratio: LogRange {
            from: 1e-3,
            to: 1e2,
            points: 10,
        },
        stiffness_ratio: LogRange {
            from: 1e-7,
            to: 1.0,
            points: 10,
        },
    };
    let settings = EtaSettings {
        method: ClMethod::Modal {
            mesh: GradedMesh::DEFAULT,
            tol: 1e-5,
        },
        ..EtaSettings::DEFAULT
    };
    c.bench_function("eta_map_10x10_mh4_n2", |b| {
        b.iter(|| eta_map(black_box(&spec), &settings).unwrap())
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = bench
}
criterion_main!(benches);
