//! Wall time per call of the stages of one Newton iteration at 32 ANCF elements (the state after
//! 500 steps of the Exudyn comparison's transient): the least over 200 batches of 100 calls,
//! which a shared machine's load can only lengthen. `probe_stage_time [N]`
use flexrig_beam::assembly::{JacobianWeights, Kinematic, assemble, band_for};
use flexrig_beam::*;
use std::hint::black_box;
use std::time::Instant;

fn least<F: FnMut()>(mut f: F) -> f64 {
    let mut best = f64::INFINITY;
    for _ in 0..200 {
        let t0 = Instant::now();
        for _ in 0..100 {
            f();
        }
        best = best.min(t0.elapsed().as_secs_f64() / 100.0);
    }
    best * 1e9
}

fn main() {
    let n: usize = std::env::args().nth(1).map_or(32, |s| s.parse().unwrap());
    let (model, loads) = canonical::polypropylene_cantilever(n, Kinematics::Ancf).unwrap();
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
    let kin = Kinematic {
        q: &s.q,
        v: Some(&s.v),
        a: Some(&s.a),
    };
    let mut r = vec![0.0; model.n_dofs()];
    let mut band = band_for(&model);
    let res = least(|| {
        black_box(assemble(&model, kin, loads.as_slice(), &mut r, None));
    });
    let jac = least(|| {
        black_box(assemble(
            &model,
            kin,
            loads.as_slice(),
            &mut r,
            Some((&mut band, w)),
        ));
    });
    assemble(&model, kin, loads.as_slice(), &mut r, Some((&mut band, w)));
    let mut lu = band.clone();
    let fac = least(|| {
        lu.clone_from(&band);
        lu.factorize("probe").unwrap();
    });
    let rhs: Vec<f64> = r[model.n_fixed()..].to_vec();
    let mut x = rhs.clone();
    let sol = least(|| {
        x.copy_from_slice(&rhs);
        lu.solve_in_place(&mut x);
        black_box(x[0]);
    });
    let mut s2 = s.clone();
    let mut ws2 = ws.clone();
    let step = least(|| {
        s2.clone_from(&s);
        ga.step(&model, &mut s2, &mut ws2, 1e-3, &loads).unwrap();
    });
    println!(
        "ns per call: residual {res:.0}  residual+matrix {jac:.0}  factorize {fac:.0}  solve {sol:.0}  step {step:.0}"
    );
}
