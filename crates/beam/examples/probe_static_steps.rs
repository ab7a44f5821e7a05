use flexrig_beam::*;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let phi: f64 = a.get(1).map_or(5.0, |s| s.parse().unwrap());
    let n: usize = a.get(2).map_or(32, |s| s.parse().unwrap());
    for kin in [Kinematics::Ancf, Kinematics::Corotational] {
        let (model, loads) = canonical::elastica_problem_with(kin, phi, n).unwrap();
        for (steps, ad) in [(1, false), (10, false), (1, true), (10, true)] {
            let mut o = StaticOptions::new(steps, 30, 1e-10).unwrap();
            if ad { o = o.with_adaptive_steps(); }
            match solve_static(&model, &loads, &o) {
                Ok(s) => println!("{kin:?} steps {steps} adaptive {ad}: its {} tip {:.15e} res {:.2e}", s.iterations, s.node(n).1, s.residual),
                Err(e) => println!("{kin:?} steps {steps} adaptive {ad}: {e}"),
            }
        }
    }
}
