//! The compliant link's large-amplitude free vibration (probe_free.rs) with a choice of element
//! and integrator: `probe_ancf_free NE RHO|ec H [corot|ancf|lin] [TIP_V] [TOL] [T_END]`.
use flexrig_beam::*;
fn main() {
    let a: Vec<String> = std::env::args().collect();
    let ne: usize = a[1].parse().unwrap();
    let ga = if a[2] == "ec" {
        GeneralizedAlpha::energy_conserving()
    } else {
        GeneralizedAlpha::new(a[2].parse().unwrap()).unwrap()
    };
    let h: f64 = a[3].parse().unwrap();
    let kin = match a.get(4).map_or("ancf", |s| s.as_str()) {
        "lin" => Kinematics::Linear,
        "corot" => Kinematics::Corotational,
        _ => Kinematics::Ancf,
    };
    let tipv: f64 = a.get(5).map_or(0.87, |s| s.parse().unwrap());
    let tol: f64 = a.get(6).map_or(1e-6, |s| s.parse().unwrap());
    let t_end: f64 = a.get(7).map_or(10.0, |s| s.parse().unwrap());
    let ga = ga.with_newton(25, tol).unwrap();
    let mat = Material::new(1.5e9, 905.0).unwrap();
    let sec = Section::rectangular(&mat, 0.064559, 0.0025824).unwrap();
    let mut spec = BeamSpec::cantilever(0.33802, sec, ne, kin);
    spec.point_masses.push(PointMass {
        node: ne,
        mass: 0.412,
        inertia: 0.0,
    });
    let model = BeamModel::new(spec).unwrap();
    let loads = NodalLoads::zeros(&model);
    let n = model.n_dofs();
    let mut v0 = vec![0.0; n];
    v0[model.dofs_per_node() * ne + 1] = tipv;
    let mut s = State::new(&model, vec![0.0; n], v0, 0.0, &loads).unwrap();
    let mut ws = Workspace::new(&model);
    let e = |s: &State| {
        let e = s.energy(&model);
        e.kinetic + e.strain
    };
    let e0 = e(&s);
    let steps = (t_end / h).round() as usize;
    let mut its = 0;
    let mut sub = 0;
    let mut worst: f64 = 0.0;
    let t0 = std::time::Instant::now();
    for k in 0..steps {
        let r = ga.step(&model, &mut s, &mut ws, h, &loads).unwrap();
        its += r.iterations;
        sub += r.substeps - 1;
        worst = worst.max((e(&s) / e0 - 1.0).abs());
        if k % (steps / 5).max(1) == 0 {
            println!(
                "t {:.2} E/E0-1 {:.3e} tip {:?}",
                s.t,
                e(&s) / e0 - 1.0,
                s.node(ne)
            );
        }
    }
    println!(
        "end E/E0-1 {:.3e} worst {:.3e} its/step {:.2} extra substeps {} wall {:.3} s tip {:?}",
        e(&s) / e0 - 1.0,
        worst,
        its as f64 / steps as f64,
        sub,
        t0.elapsed().as_secs_f64(),
        s.node(ne)
    );
}
