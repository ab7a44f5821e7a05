//! The static elastica of the Exudyn comparison's cantilever (L 0.3 m, E 1.5 GPa, 25 × 1 mm, clamped, dead
//! tip load P = α EI/L², 10 load steps) for the side-by-side peer timing
//! (scripts/peers/exudyn_ancf_cable.py).
//!
//! `wp_static KIN ELEMENTS ALPHA REPEATS [adaptive]` prints one JSON line: the tip (u, v, θ),
//! the Newton iterations and the best wall time of REPEATS solves (`adaptive`: adaptive load
//! steps from the full load instead of 10 fixed ones).
use flexrig_beam::*;
use std::time::Instant;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let kin = Kinematics::parse("kinematics", &a[1]).unwrap();
    let ne: usize = a[2].parse().unwrap();
    let alpha: f64 = a[3].parse().unwrap();
    let repeats: usize = a[4].parse().unwrap();
    let (model, _) = canonical::polypropylene_cantilever(ne, kin).unwrap();
    let mut loads = NodalLoads::zeros(&model);
    let ei = model.section().ei();
    loads.set_force(ne, 0.0, alpha * ei / 0.09).unwrap();
    let opts = if a.get(5).map(String::as_str) == Some("adaptive") {
        StaticOptions::adaptive()
    } else {
        StaticOptions::with_load_steps(10).unwrap()
    };
    let mut best = f64::INFINITY;
    let mut sol = None;
    for _ in 0..repeats.max(1) {
        let t0 = Instant::now();
        let s = solve_static(&model, &loads, &opts).unwrap();
        best = best.min(t0.elapsed().as_secs_f64());
        sol = Some(s);
    }
    let s = sol.unwrap();
    let (u, v, th) = s.node(ne);
    println!(
        "{{\"model\": \"{}\", \"elements\": {ne}, \"alpha\": {alpha}, \"u\": {u:.15e}, \"v\": {v:.15e}, \"theta\": {th:.15e}, \"iterations\": {}, \"seconds\": {best:.6e}}}",
        a[1], s.iterations
    );
}
