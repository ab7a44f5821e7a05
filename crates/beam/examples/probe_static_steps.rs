use flexrig_beam::*;
fn run(what: &str, model: &BeamModel, loads: &NodalLoads, n: usize) {
    let fx = solve_static(model, loads, &StaticOptions::new(50, 30, 1e-10).unwrap());
    let ad = solve_static(model, loads, &StaticOptions::adaptive());
    match (fx, ad) {
        (Ok(a), Ok(b)) => {
            let d = a.q.iter().zip(&b.q).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            println!("{what}: its {} -> {} maxdiff {d:.2e} tip {:?}{}", a.iterations, b.iterations, b.node(n), if d > 1e-10 {" !!!"} else {""});
        }
        (a, b) => println!("{what}: fixed {:?} adaptive {:?} !!!", a.map(|s| s.iterations), b.map(|s| s.iterations)),
    }
}
fn main() {
    for kin in [Kinematics::Ancf, Kinematics::Corotational] {
        for slender in [5.0, 2.0] {
            for n in [8usize, 32] {
                let mat = Material::new(210e9, 7850.0).unwrap();
                let sec = Section::rectangular(&mat, 0.02, 1.0 / slender).unwrap();
                let m = BeamModel::new(BeamSpec::cantilever(1.0, sec, n, kin)).unwrap();
                let mut loads = NodalLoads::zeros(&m);
                loads.set_force(n, 0.0, 5.0 * m.section().ei()).unwrap();
                run(&format!("{kin:?} stubby L/t {slender} n {n}"), &m, &loads, n);
            }
        }
        for n in [4usize, 16, 64] {
            for ml in [1.0, 3.14159, 6.2832, 12.0] {
                let m = canonical::unit_cantilever(n, kin).unwrap();
                let mut loads = NodalLoads::zeros(&m);
                loads.set_moment(n, ml).unwrap();
                run(&format!("{kin:?} moment {ml} n {n}"), &m, &loads, n);
            }
            for p in [-1.0, -3.0, -10.0] {
                let m = canonical::unit_cantilever(n, kin).unwrap();
                let mut loads = NodalLoads::zeros(&m);
                loads.set_force(n, p, 0.01).unwrap();
                run(&format!("{kin:?} compression {p} n {n}"), &m, &loads, n);
            }
        }
    }
}
