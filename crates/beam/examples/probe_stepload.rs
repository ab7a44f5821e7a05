use flexrig_beam::*;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let ne: usize = args.get(1).map_or(64, |s| s.parse().unwrap());
    let rho: f64 = args.get(2).map_or(0.9, |s| s.parse().unwrap());
    let h: f64 = args.get(3).map_or(1e-3, |s| s.parse().unwrap());
    let mat = Material::new(1.5e9, 900.0).unwrap();
    let sec = Section::rectangular(&mat, 0.025, 0.001).unwrap();
    let l = 0.3;
    let model = BeamModel::new(BeamSpec::cantilever(l, sec, ne, Kinematics::Corotational)).unwrap();
    let mut loads = NodalLoads::zeros(&model);
    let p = sec.ei() / (l * l);
    loads.set_force(model.tip_node(), 0.0, p).unwrap();
    let mut state = State::at_rest(&model, &loads).unwrap();
    let mut ws = Workspace::new(&model);
    let ga = GeneralizedAlpha::new(rho)
        .unwrap()
        .with_newton(
            args.get(4).map_or(25, |s| s.parse().unwrap()),
            args.get(5).map_or(1e-6, |s| s.parse().unwrap()),
        )
        .unwrap();
    let mut its = 0;
    let mut mind = f64::MAX;
    let mut maxd = f64::MIN;
    let nsteps = (1.0 / h).round() as usize;
    for k in 0..nsteps {
        match ga.step(&model, &mut state, &mut ws, h, &loads) {
            Ok(r) => {
                its += r.iterations;
                let e = state.energy(&model);
                mind = mind.min(e.dissipated / e.external_work.abs().max(1e-300));
                maxd = maxd.max(e.dissipated / e.external_work.abs().max(1e-300));
                if k < 5 {
                    println!(
                        "step {k}: it {} first {:e} last {:e}",
                        r.iterations, r.first_correction, r.last_correction
                    );
                }
            }
            Err(e) => {
                println!("step {k}: {e}");
                return;
            }
        }
    }
    let tip = state.node(model.tip_node());
    println!(
        "ok: tip {:?} iterations {} dissipated/W in [{:e}, {:e}]",
        tip, its, mind, maxd
    );
}
