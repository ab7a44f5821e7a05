//! Micro-timings of one ANCF iteration: assembly with and without the iteration matrix, LU, solve.
use flexrig_beam::assembly::{JacobianWeights, Kinematic, assemble, band_for};
use flexrig_beam::*;
use std::time::Instant;
fn main() {
    let ne: usize = std::env::args().nth(1).map_or(32, |s| s.parse().unwrap());
    for kin in [Kinematics::Ancf, Kinematics::Corotational] {
        let mat = Material::new(1.5e9, 900.0).unwrap();
        let sec = Section::rectangular(&mat, 0.025, 0.001).unwrap();
        let model = BeamModel::new(BeamSpec::cantilever(0.3, sec, ne, kin)).unwrap();
        let n = model.n_dofs();
        let q: Vec<f64> = (0..n).map(|i| 1e-3 * ((i as f64) * 0.37).sin()).collect();
        let v = q.clone();
        let a = q.clone();
        let f = vec![0.0; 3 * model.n_nodes()];
        let mut r = vec![0.0; n];
        let mut band = band_for(&model);
        let w = JacobianWeights {
            stiffness: 1.0,
            velocity: 1e3,
            acceleration: 1e6,
        };
        let kinm = Kinematic {
            q: &q,
            v: Some(&v),
            a: Some(&a),
        };
        let reps = 20000;
        let t0 = Instant::now();
        for _ in 0..reps {
            assemble(&model, kinm, &f, &mut r, Some((&mut band, w)));
        }
        let t_jac = t0.elapsed().as_secs_f64() / reps as f64;
        let t0 = Instant::now();
        for _ in 0..reps {
            assemble(&model, kinm, &f, &mut r, None);
        }
        let t_res = t0.elapsed().as_secs_f64() / reps as f64;
        assemble(&model, kinm, &f, &mut r, Some((&mut band, w)));
        let t0 = Instant::now();
        let mut b2 = band.clone();
        for _ in 0..reps {
            b2 = band.clone();
            b2.factorize("x").unwrap();
        }
        let t_lu = t0.elapsed().as_secs_f64() / reps as f64;
        let mut x = r[model.n_fixed()..].to_vec();
        let t0 = Instant::now();
        for _ in 0..reps {
            b2.solve_in_place(&mut x);
        }
        let t_solve = t0.elapsed().as_secs_f64() / reps as f64;
        println!(
            "{kin:?} {ne} el: assemble+jac {:.2} us, residual {:.2} us, LU {:.2} us, solve {:.2} us",
            t_jac * 1e6,
            t_res * 1e6,
            t_lu * 1e6,
            t_solve * 1e6
        );
    }
}
