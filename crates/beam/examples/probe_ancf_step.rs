//! The polypropylene cantilever's transient: L 0.3 m, E 1.5 GPa, 25 × 1 mm, ρ 900, clamped, step tip load P = EI/L²
//! from rest, 1000 steps. `probe_ancf_step NE RHO|ec H [ancf|corot] [TOL] [T_END]`
use flexrig_beam::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ne: usize = args.get(1).map_or(32, |s| s.parse().unwrap());
    let ga = match args.get(2).map_or("0.9", |s| s.as_str()) {
        "ec" => GeneralizedAlpha::energy_conserving(),
        r => GeneralizedAlpha::new(r.parse().unwrap()).unwrap(),
    };
    let h: f64 = args.get(3).map_or(1e-3, |s| s.parse().unwrap());
    let kin = match args.get(4).map_or("ancf", |s| s.as_str()) {
        "corot" => Kinematics::Corotational,
        _ => Kinematics::Ancf,
    };
    let tol: f64 = args.get(5).map_or(1e-6, |s| s.parse().unwrap());
    let t_end: f64 = args.get(6).map_or(1.0, |s| s.parse().unwrap());
    let ga = ga.with_newton(25, tol).unwrap();
    let mat = Material::new(1.5e9, 900.0).unwrap();
    let sec = Section::rectangular(&mat, 0.025, 0.001).unwrap();
    let l = 0.3;
    let model = BeamModel::new(BeamSpec::cantilever(l, sec, ne, kin)).unwrap();
    let mut loads = NodalLoads::zeros(&model);
    loads
        .set_force(model.tip_node(), 0.0, sec.ei() / (l * l))
        .unwrap();
    let t0 = std::time::Instant::now();
    let mut best = f64::INFINITY;
    let mut out = None;
    for _rep in 0..3 {
        let t0r = std::time::Instant::now();
        let mut state = State::at_rest(&model, &loads).unwrap();
        let mut ws = Workspace::new(&model);
        let mut its = 0;
        let mut rej = 0;
        let nsteps = (t_end / h).round() as usize;
        for _ in 0..nsteps {
            let r = ga.step(&model, &mut state, &mut ws, h, &loads).unwrap();
            its += r.iterations;
            rej += r.rejected;
        }
        best = best.min(t0r.elapsed().as_secs_f64());
        let e = state.energy(&model);
        out = Some((
            state.node(model.tip_node()),
            its as f64 / nsteps as f64,
            rej,
            e,
        ));
    }
    let (tip, its, rej, e) = out.unwrap();
    println!(
        "tip {:.12e} {:.12e} {:.12e} its/step {:.2} rejected {} best {:.4} s (total {:.2}) dissipated/W {:.3e}",
        tip.0,
        tip.1,
        tip.2,
        its,
        rej,
        best,
        t0.elapsed().as_secs_f64(),
        e.dissipated / e.external_work
    );
}
