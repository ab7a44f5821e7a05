//! Criterion benchmarks of the beam solvers (figures in docs/performance-beam.md).
//!
//! * `transient/corotational_32_x1000`: 1000 generalized-α steps (ρ∞ = 0.8, h = 1e-4 s) of the
//!   CL link (polypropylene, L = 0.34 m, 64 × 2.6 mm, 0.1 kg tip payload), 32 corotational
//!   elements, free vibration started with a tip speed of 1 m/s in the first mode.
//! * `static/elastica_PL2_EI_5_32`: the corotational large-deflection static solve, PL²/EI = 5,
//!   32 elements, 10 load steps.
//! * `step_scaling/N`: cost of one corotational transient step for N = 8 … 512.
//! * `modal/linear_32`: the first 4 bending modes with 32 elements (dense faer eigensolver).
//! * `transient/linear_32_x1000` and `transient/modal8_32_x1000`: the same 1000 steps with the
//!   linear beam and with the modal-reduced one (8 modes + tip u, v, θ correction shapes).
//! * `polypropylene/…`: the thin polypropylene cantilever of the Exudyn comparison (canonical::polypropylene_cantilever: L 0.3 m, 25 × 1 mm,
//!   E 1.5 GPa, ρ 900): the ANCF element alone (force; force and tangent), the elastica
//!   PL²/EI = 5 with 32 ANCF elements (10 load steps), and the step-load transient (P = EI/L²
//!   from rest, h = 1e-3 s, 1000 steps, generalized-α ρ∞ = 0.9 or the energy-conserving step)
//!   with ANCF and corotational elements at N = 4 … 64; the error of each row is in
//!   docs/performance-beam.md (scripts/work_precision_beam.py; Exudyn side by side:
//!   scripts/peers/exudyn_ancf_cable.py).
//! * `stage/…`: the stages of one Newton iteration at 32 elements (residual, residual with the
//!   iteration matrix, banded LU, solve).

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use flexrig_beam::canonical::{self, elastica_problem};
use flexrig_beam::*;

fn link(elements: usize) -> BeamModel {
    let mat = Material::new(1.5e9, 905.0).unwrap();
    let sec = Section::rectangular(&mat, 0.064, 0.0026).unwrap();
    let mut spec = BeamSpec::cantilever(0.34, sec, elements, Kinematics::Corotational);
    spec.point_masses.push(PointMass {
        node: elements,
        mass: 0.1,
        inertia: 0.0,
    });
    BeamModel::new(spec).unwrap()
}

fn start(model: &BeamModel) -> State {
    let r = modal_analysis(model, 1, ModalDirection::Transverse).unwrap();
    let phi = &r.shapes[0];
    let s = 1.0 / phi[3 * model.tip_node() + 1];
    let v: Vec<f64> = phi.iter().map(|x| x * s).collect();
    let loads = NodalLoads::zeros(model);
    State::new(model, vec![0.0; model.n_dofs()], v, 0.0, &loads).unwrap()
}

/// 1000 steps of h = 1e-4 s (ρ∞ = 0.8) of `model` from its first-mode swing.
fn thousand_steps(c: &mut Criterion, name: &str, model: &BeamModel) {
    let s0 = start(model);
    let loads = NodalLoads::zeros(model);
    let ga = GeneralizedAlpha::new(0.8).unwrap();
    let tip_v = 3 * model.tip_node() + 1;
    c.bench_function(name, |b| {
        b.iter(|| {
            let mut s = s0.clone();
            let mut ws = Workspace::new(model);
            for _ in 0..1000 {
                ga.step(model, &mut s, &mut ws, 1e-4, &loads).unwrap();
            }
            black_box(s.q[tip_v])
        })
    });
}

fn transient(c: &mut Criterion) {
    thousand_steps(c, "transient/corotational_32_x1000", &link(32));
}

fn reduced(c: &mut Criterion) {
    let model = link(32).with_kinematics(Kinematics::Linear);
    thousand_steps(c, "transient/linear_32_x1000", &model);
    let loads = NodalLoads::zeros(&model);
    let ga = GeneralizedAlpha::new(0.8).unwrap();
    let tip = model.tip_node();
    let red = ReducedModel::new(&model, 8, &[3 * tip, 3 * tip + 1, 3 * tip + 2]).unwrap();
    c.bench_function("transient/modal8_32_x1000", |b| {
        b.iter(|| {
            let mut s = ReducedState::at_rest(&red, &loads).unwrap();
            for _ in 0..1000 {
                ga.step_reduced(&red, &mut s, 1e-4, &loads).unwrap();
            }
            black_box(red.dof(&s, 3 * tip + 1).0)
        })
    });
}

fn statics(c: &mut Criterion) {
    let (model, loads) = elastica_problem(5.0, 32).unwrap();
    let opts = StaticOptions::with_load_steps(10).unwrap();
    c.bench_function("static/elastica_PL2_EI_5_32", |b| {
        b.iter(|| black_box(solve_static(&model, &loads, &opts).unwrap().iterations))
    });
    let adaptive = StaticOptions::adaptive();
    c.bench_function("static/elastica_PL2_EI_5_32_adaptive", |b| {
        b.iter(|| black_box(solve_static(&model, &loads, &adaptive).unwrap().iterations))
    });
}

fn scaling(c: &mut Criterion) {
    let mut g = c.benchmark_group("step_scaling");
    for n in [8usize, 16, 32, 64, 128, 256, 512] {
        let model = link(n);
        let s0 = start(&model);
        let loads = NodalLoads::zeros(&model);
        let ga = GeneralizedAlpha::new(0.8).unwrap();
        g.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            let mut s = s0.clone();
            let mut ws = Workspace::new(&model);
            let mut k = 0;
            b.iter(|| {
                // restart every 1000 steps so the state stays in the same regime
                if k == 1000 {
                    s = s0.clone();
                    k = 0;
                }
                k += 1;
                black_box(
                    ga.step(&model, &mut s, &mut ws, 1e-4, &loads)
                        .unwrap()
                        .iterations,
                )
            })
        });
    }
    g.finish();
}

fn modal(c: &mut Criterion) {
    let model = link(32).with_kinematics(Kinematics::Linear);
    c.bench_function("modal/linear_32", |b| {
        b.iter(|| {
            black_box(
                modal_analysis(&model, 4, ModalDirection::Transverse)
                    .unwrap()
                    .omegas[0],
            )
        })
    });
}

fn polypropylene(c: &mut Criterion) {
    use flexrig_beam::ancf::{AncfElement, Vector8, Want};
    let mut g = c.benchmark_group("polypropylene");
    let el = AncfElement::new(0.3 / 32.0, 37500.0, 3.125e-3);
    let d = Vector8::from_column_slice(&[1e-4, 2e-3, -1e-3, 0.2, -3e-4, 9e-3, -2e-2, 0.25]);
    g.bench_function("ancf_element_force", |b| {
        b.iter(|| black_box(el.evaluate(black_box(&d), Want::Force).force[3]))
    });
    g.bench_function("ancf_element_tangent", |b| {
        b.iter(|| black_box(el.evaluate(black_box(&d), Want::Tangent).tangent[(3, 3)]))
    });
    let (model, loads) = canonical::elastica_problem_with(Kinematics::Ancf, 5.0, 32).unwrap();
    let opts = StaticOptions::with_load_steps(10).unwrap();
    g.bench_function("static_elastica_PL2_EI_5_32_ancf", |b| {
        b.iter(|| black_box(solve_static(&model, &loads, &opts).unwrap().iterations))
    });
    let adaptive = StaticOptions::adaptive();
    g.bench_function("static_elastica_PL2_EI_5_32_ancf_adaptive", |b| {
        b.iter(|| black_box(solve_static(&model, &loads, &adaptive).unwrap().iterations))
    });
    g.sample_size(10);
    for (kin, integrator, n) in [
        (Kinematics::Ancf, "0.9", 4usize),
        (Kinematics::Ancf, "0.9", 8),
        (Kinematics::Ancf, "0.9", 16),
        (Kinematics::Ancf, "0.9", 32),
        (Kinematics::Ancf, "0.9", 64),
        (Kinematics::Ancf, "ec", 8),
        (Kinematics::Corotational, "0.9", 8),
        (Kinematics::Corotational, "0.9", 16),
        (Kinematics::Corotational, "0.9", 32),
        (Kinematics::Corotational, "0.9", 64),
    ] {
        let (model, loads) = canonical::polypropylene_cantilever(n, kin).unwrap();
        let ga = if integrator == "ec" {
            GeneralizedAlpha::energy_conserving()
        } else {
            GeneralizedAlpha::new(0.9).unwrap()
        };
        let name = format!(
            "transient_{}_{}_{n}_h1e-3_x1000",
            if kin == Kinematics::Ancf {
                "ancf"
            } else {
                "corotational"
            },
            if integrator == "ec" { "ec" } else { "rho0.9" }
        );
        g.bench_function(name, |b| {
            b.iter(|| {
                let mut s = State::at_rest(&model, &loads).unwrap();
                let mut ws = Workspace::new(&model);
                for _ in 0..1000 {
                    ga.step(&model, &mut s, &mut ws, 1e-3, &loads).unwrap();
                }
                black_box(s.node(n).1)
            })
        });
    }
    g.finish();
}

/// The stages of one Newton iteration of the Exudyn comparison's transient at 32 elements, at the state
/// after 500 steps (tip at ≈ 0.5 L): the residual alone, the residual with the iteration matrix
/// (cleared and scattered into the band), the banded LU and one solve. A step's cost is about
/// Σ count × these unit costs, the counts from `Workspace::counters` (examples/probe_step_cost).
fn stages(c: &mut Criterion) {
    use flexrig_beam::assembly::{JacobianWeights, Kinematic, assemble, band_for};
    let mut g = c.benchmark_group("stage");
    for kin in [Kinematics::Ancf, Kinematics::Corotational] {
        let name = if kin == Kinematics::Ancf {
            "ancf"
        } else {
            "corotational"
        };
        let (model, loads) = canonical::polypropylene_cantilever(32, kin).unwrap();
        let ga = GeneralizedAlpha::new(0.9).unwrap();
        let mut s = State::at_rest(&model, &loads).unwrap();
        let mut ws = Workspace::new(&model);
        for _ in 0..500 {
            ga.step(&model, &mut s, &mut ws, 1e-3, &loads).unwrap();
        }
        let (am, af, gm, b) = ga.parameters();
        let h = 1e-3;
        let w = JacobianWeights {
            stiffness: 1.0,
            velocity: gm / (b * h),
            acceleration: (1.0 - am) / ((1.0 - af) * b * h * h),
        };
        let kinm = Kinematic {
            q: &s.q,
            v: Some(&s.v),
            a: Some(&s.a),
        };
        let mut r = vec![0.0; model.n_dofs()];
        let mut band = band_for(&model);
        g.bench_function(format!("{name}_32/residual"), |bch| {
            bch.iter(|| black_box(assemble(&model, kinm, loads.as_slice(), &mut r, None)))
        });
        g.bench_function(format!("{name}_32/residual_and_matrix"), |bch| {
            bch.iter(|| {
                black_box(assemble(
                    &model,
                    kinm,
                    loads.as_slice(),
                    &mut r,
                    Some((&mut band, w)),
                ))
            })
        });
        assemble(&model, kinm, loads.as_slice(), &mut r, Some((&mut band, w)));
        let mut lu = band.clone();
        g.bench_function(format!("{name}_32/factorize"), |bch| {
            bch.iter(|| {
                lu.clone_from(&band);
                lu.factorize("bench").unwrap();
                black_box(lu.n())
            })
        });
        let rhs: Vec<f64> = r[model.n_fixed()..].to_vec();
        let mut x = rhs.clone();
        // (ANCF: the symmetric positive definite matrix takes the LDLᵀ path; the pivoting LU
        // of the same matrix alongside, for the comparison)
        g.bench_function(format!("{name}_32/solve"), |bch| {
            bch.iter(|| {
                x.copy_from_slice(&rhs);
                lu.solve_in_place(&mut x);
                black_box(x[0])
            })
        });
        let mut pivoting = band.clone();
        g.bench_function(format!("{name}_32/factorize_lu"), |bch| {
            bch.iter(|| {
                pivoting.clone_from(&band);
                pivoting.factorize_lu("bench").unwrap();
                black_box(pivoting.n())
            })
        });
        g.bench_function(format!("{name}_32/solve_lu"), |bch| {
            bch.iter(|| {
                x.copy_from_slice(&rhs);
                pivoting.solve_in_place(&mut x);
                black_box(x[0])
            })
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    transient,
    reduced,
    statics,
    scaling,
    modal,
    polypropylene,
    stages
);
criterion_main!(benches);
