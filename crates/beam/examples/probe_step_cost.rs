//! Work per step of the Exudyn comparison's step-load transient (L 0.3 m, 25 × 1 mm, E 1.5 GPa, ρ 900,
//! P = EI/L² at the tip from rest, h = 1 ms, 1000 steps, generalized-α ρ∞ = 0.9): Newton
//! iterations, residual and iteration-matrix assemblies and factorisations per step
//! ([`StepCounters`]), and the wall time of the run (best of `REPEATS`).
//!
//! `probe_step_cost [REPEATS]`
use flexrig_beam::*;
use std::time::Instant;

fn main() {
    let repeats: usize = std::env::args().nth(1).map_or(3, |s| s.parse().unwrap());
    let ga = GeneralizedAlpha::new(0.9).unwrap();
    println!(
        "kinematics     N  its/step  res/step  jac/step  LU/step  tip v [m]          ms (best of {repeats})"
    );
    for kin in [Kinematics::Ancf, Kinematics::Corotational] {
        for n in [8usize, 16, 32, 64] {
            let (model, loads) = canonical::polypropylene_cantilever(n, kin).unwrap();
            let mut best = f64::INFINITY;
            let mut c = StepCounters::default();
            let mut tip = 0.0;
            for _ in 0..repeats {
                let t0 = Instant::now();
                let mut s = State::at_rest(&model, &loads).unwrap();
                let mut ws = Workspace::new(&model);
                for _ in 0..1000 {
                    ga.step(&model, &mut s, &mut ws, 1e-3, &loads).unwrap();
                }
                best = best.min(t0.elapsed().as_secs_f64());
                c = ws.counters();
                tip = s.node(n).1;
            }
            let per = |x: usize| x as f64 / c.steps as f64;
            println!(
                "{:<12} {n:>3}  {:>8.3}  {:>8.3}  {:>8.3}  {:>7.3}  {tip:.15e}  {:.2}",
                format!("{kin:?}"),
                c.iterations_per_step(),
                per(c.residuals),
                per(c.tangents),
                c.factorizations_per_step(),
                best * 1e3
            );
        }
    }
}
