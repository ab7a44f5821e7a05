use flexrig_beam::*;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let ne: usize = a[1].parse().unwrap();
    let rho: f64 = a[2].parse().unwrap();
    let h: f64 = a[3].parse().unwrap();
    let kin = if a.get(4).map_or(false, |s| s == "lin") {
        Kinematics::Linear
    } else {
        Kinematics::Corotational
    };
    let tipv: f64 = a.get(5).map_or(0.87, |s| s.parse().unwrap());
    let mat = Material::new(1.5e9, 905.0).unwrap();
    let sec = Section::rectangular(&mat, 0.064559, 0.0025824).unwrap();
    let mut spec = BeamSpec::cantilever(0.33802, sec, ne, kin);
    if a.get(6).map_or(false, |s| s == "lumped") {
        spec.mass = MassMatrix::Lumped;
    }
    spec.point_masses.push(PointMass {
        node: ne,
        mass: 0.412,
        inertia: 0.0,
    });
    let model = BeamModel::new(spec).unwrap();
    let loads = NodalLoads::zeros(&model);
    let n = model.n_dofs();
    let mut v0 = vec![0.0; n];
    v0[3 * ne + 1] = tipv; // impulsive tip velocity: every mode
    let mut s = State::new(&model, vec![0.0; n], v0, 0.0, &loads).unwrap();
    let mut ws = Workspace::new(&model);
    let ga = GeneralizedAlpha::new(rho).unwrap();
    let e = |s: &State| {
        let e = s.energy(&model);
        e.kinetic + e.strain
    };
    let e0 = e(&s);
    let steps = (10.0 / h) as usize;
    let mut its = 0;
    let mut sub = 0;
    for k in 0..steps {
        let r = ga.step(&model, &mut s, &mut ws, h, &loads).unwrap();
        its += r.iterations;
        sub += r.substeps - 1;
        if k % (steps / 10) == 0 {
            println!(
                "t {:.2} E/E0-1 {:.3e} tip v {:.4}",
                s.t,
                e(&s) / e0 - 1.0,
                s.q[3 * ne + 1]
            );
        }
    }
    println!(
        "end E/E0-1 {:.3e} its/step {:.2} extra substeps {}",
        e(&s) / e0 - 1.0,
        its as f64 / steps as f64,
        sub
    );
}
