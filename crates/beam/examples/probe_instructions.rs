//! One workload per call, for instruction counts under `valgrind --tool=callgrind` (a
//! load-independent cost measure on a shared machine) or for timing from outside:
//!
//! * `probe_instructions transient KIN N [STEPS]`: the Exudyn comparison's step load (L 0.3 m, 25 × 1 mm,
//!   E 1.5 GPa, ρ 900, tip load P = EI/L² from rest), generalized-α ρ∞ = 0.9, h = 1 ms,
//!   STEPS steps (default 1000), KIN ancf|corotational, METHOD auto (default), modified or full:
//!   `probe_instructions transient KIN N [STEPS [METHOD]]`;
//! * `probe_instructions static KIN N [fixed|adaptive [unit|peer]]`: the elastica PL²/EI = 5,
//!   10 load steps (`adaptive`: adaptive load steps from the full load), on the unit cantilever
//!   (EA L²/EI = 1e7, the default) or the Exudyn comparison's (`peer`: L 0.3 m, 25 × 1 mm,
//!   E 1.5 GPa, EA L²/EI = 1.08e6, the problem of scripts/peers/exudyn_ancf_steps.py);
//! * `probe_instructions modes N`: the first 4 transverse modes of the linear CL link.
//!
//! Prints the tip deflection (and the modes' ω₁) so the work cannot be optimised away.
use flexrig_beam::*;

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let n: usize = a[a.len().min(3) - 1].parse().unwrap_or(32);
    match a[1].as_str() {
        "transient" => {
            let kin = Kinematics::parse("kinematics", &a[2]).unwrap();
            let n: usize = a[3].parse().unwrap();
            let steps: usize = a.get(4).map_or(1000, |s| s.parse().unwrap());
            let method = match a.get(5).map(String::as_str) {
                Some("full") => NewtonMethod::Full,
                Some("modified") => NewtonMethod::Modified,
                _ => NewtonMethod::Auto,
            };
            let ga = GeneralizedAlpha::new(0.9)
                .unwrap()
                .with_newton_method(method);
            let (model, loads) = canonical::polypropylene_cantilever(n, kin).unwrap();
            let mut s = State::at_rest(&model, &loads).unwrap();
            let mut ws = Workspace::new(&model);
            let mut its = 0;
            for _ in 0..steps {
                its += ga
                    .step(&model, &mut s, &mut ws, 1e-3, &loads)
                    .unwrap()
                    .iterations;
            }
            println!(
                "tip v {:.15e} iterations/step {:.3}",
                s.node(n).1,
                its as f64 / steps as f64
            );
        }
        "static" => {
            let kin = Kinematics::parse("kinematics", &a[2]).unwrap();
            let n: usize = a[3].parse().unwrap();
            let (model, loads) = if a.get(5).map(String::as_str) == Some("peer") {
                let (model, _) = canonical::polypropylene_cantilever(n, kin).unwrap();
                let mut loads = NodalLoads::zeros(&model);
                let p = 5.0 * model.section().ei() / model.length().powi(2);
                loads.set_force(n, 0.0, p).unwrap();
                (model, loads)
            } else {
                canonical::elastica_problem_with(kin, 5.0, n).unwrap()
            };
            let opts = if a.get(4).map(String::as_str) == Some("adaptive") {
                StaticOptions::adaptive()
            } else {
                StaticOptions::with_load_steps(10).unwrap()
            };
            let sol = solve_static(&model, &loads, &opts).unwrap();
            println!("tip v {:.15e} iterations {}", sol.node(n).1, sol.iterations);
        }
        "modes" => {
            let mat = Material::new(1.5e9, 905.0).unwrap();
            let sec = Section::rectangular(&mat, 0.064, 0.0026).unwrap();
            let spec = BeamSpec::cantilever(0.34, sec, n, Kinematics::Linear);
            let model = BeamModel::new(spec).unwrap();
            let r = modal_analysis(&model, 4, ModalDirection::Transverse).unwrap();
            println!("omega1 {:.15e}", r.omegas[0]);
        }
        other => panic!("unknown workload {other}"),
    }
}
