//! flexrig-beam on its own: natural frequencies of the paper's polypropylene link with its
//! payload, and a large-deflection static solve.
//!
//! `cargo run -p flexrig-beam --example cantilever`

use flexrig_beam::{
    BeamModel, BeamSpec, Kinematics, Material, ModalDirection, NodalLoads, PointMass, Section,
    StaticOptions, modal_analysis, solve_static,
};

fn main() -> Result<(), flexrig_beam::BeamError> {
    let material = Material::new(1.5e9, 905.0)?;
    let section = Section::rectangular(&material, 0.064559, 0.0025824)?;
    let mut spec = BeamSpec::cantilever(0.33802, section, 16, Kinematics::Corotational);
    spec.point_masses.push(PointMass {
        node: 16,
        mass: 0.412,
        inertia: 0.0,
    });
    let model = BeamModel::new(spec)?;
    let modes = modal_analysis(&model, 3, ModalDirection::Transverse)?;
    println!("link with 412 g payload: f = {:?} Hz", modes.frequencies_hz);
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(model.tip_node(), 0.0, 2.0)?;
    let s = solve_static(&model, &loads, &StaticOptions::new(10, 30, 1e-10)?)?;
    let (u, v, theta) =
        s.q.chunks(3)
            .last()
            .map(|n| (n[0], n[1], n[2]))
            .unwrap_or_default();
    println!(
        "2 N tip load: u = {u:.4e} m, v = {v:.4e} m, θ = {theta:.4} rad ({} Newton iterations)",
        s.iterations
    );
    Ok(())
}
