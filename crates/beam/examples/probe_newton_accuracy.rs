//! How far the default Newton (modified, tolerance 1e-6 L) lands from a tight full Newton
//! (tolerance 1e-10 L) on the Exudyn comparison's step-load transient (h = 1 ms, ρ∞ = 0.9): the largest
//! deviation of the tip deflection over the run, relative to tol·L, and the work per step.
//!
//! `probe_newton_accuracy KIN N STEPS`
use flexrig_beam::*;

fn run(kin: Kinematics, n: usize, steps: usize, ga: &GeneralizedAlpha) -> (Vec<f64>, StepCounters) {
    let (model, loads) = canonical::polypropylene_cantilever(n, kin).unwrap();
    let mut s = State::at_rest(&model, &loads).unwrap();
    let mut ws = Workspace::new(&model);
    let mut tip = Vec::new();
    for _ in 0..steps {
        ga.step(&model, &mut s, &mut ws, 1e-3, &loads).unwrap();
        tip.push(s.node(n).1);
    }
    (tip, ws.counters())
}

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kin = Kinematics::parse("kinematics", &a[1]).unwrap();
    let n: usize = a[2].parse().unwrap();
    let steps: usize = a[3].parse().unwrap();
    let ga = GeneralizedAlpha::new(0.9)
        .unwrap()
        .with_newton_method(NewtonMethod::Modified);
    let full = ga.with_newton_method(NewtonMethod::Full);
    let tight = full.with_newton(40, 1e-10).unwrap();
    let (reference, _) = run(kin, n, steps, &tight);
    for (name, g) in [("modified 1e-6", ga), ("full 1e-6", full)] {
        let (tip, c) = run(kin, n, steps, &g);
        let dev = tip
            .iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        println!(
            "{name:<14} max |v − v_tight| = {:.2e} m = {:.2} tol·L; its/step {:.3}, LU/step {:.3}",
            dev,
            dev / (1e-6 * 0.3),
            c.iterations_per_step(),
            c.factorizations_per_step()
        );
    }
}
