//! One row of the beam work–precision table (the polypropylene cantilever's transient): L 0.3 m, E 1.5 GPa,
//! 25 × 1 mm, ρ 900 kg/m³, clamped, step tip load P = EI/L² from rest, t = 1 s.
//!
//! `wp_transient KIN INTEGRATOR ELEMENTS H REPEATS [TOL]` with KIN ancf|corotational, INTEGRATOR a
//! ρ∞ (generalized-α) or `ec` (energy-conserving); prints one JSON line with the best wall time of
//! REPEATS runs, Newton iterations per step and the tip deflection every 1 ms (for the error
//! against a converged reference, see scripts/work_precision_beam.py).
use flexrig_beam::*;
use std::time::Instant;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kin = Kinematics::parse("kinematics", &a[1]).unwrap();
    let ga = match a[2].as_str() {
        "ec" => GeneralizedAlpha::energy_conserving(),
        r => GeneralizedAlpha::new(r.parse().unwrap()).unwrap(),
    };
    let ne: usize = a[3].parse().unwrap();
    let h: f64 = a[4].parse().unwrap();
    let repeats: usize = a[5].parse().unwrap();
    let tol: f64 = a.get(6).map_or(1e-6, |s| s.parse().unwrap());
    let ga = ga.with_newton(25, tol).unwrap();
    let mat = Material::new(1.5e9, 900.0).unwrap();
    let sec = Section::rectangular(&mat, 0.025, 0.001).unwrap();
    let model = BeamModel::new(BeamSpec::cantilever(0.3, sec, ne, kin)).unwrap();
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(ne, 0.0, sec.ei() / 0.09).unwrap();
    let steps = (1.0 / h).round() as usize;
    let every = ((1e-3 / h).round() as usize).max(1);
    let mut best = f64::INFINITY;
    let mut trajectory = Vec::new();
    let mut its = 0;
    for rep in 0..repeats.max(1) {
        let record = rep == 0;
        let t0 = Instant::now();
        let mut s = State::at_rest(&model, &loads).unwrap();
        let mut ws = Workspace::new(&model);
        let mut n_it = 0;
        for k in 1..=steps {
            n_it += ga
                .step(&model, &mut s, &mut ws, h, &loads)
                .unwrap()
                .iterations;
            if record && k % every == 0 {
                trajectory.push(s.node(ne).1);
            }
        }
        let dt = t0.elapsed().as_secs_f64();
        if !record || repeats == 1 {
            best = best.min(dt);
        }
        its = n_it;
    }
    let tv: Vec<String> = trajectory.iter().map(|v| format!("{v:.15e}")).collect();
    println!(
        "{{\"model\": \"{}\", \"integrator\": \"{}\", \"elements\": {ne}, \"h\": {h:e}, \"tol\": {tol:e}, \"seconds\": {best:.6e}, \"iterations_per_step\": {:.3}, \"tip_v\": [{}]}}",
        a[1],
        a[2],
        its as f64 / steps as f64,
        tv.join(", ")
    );
}
