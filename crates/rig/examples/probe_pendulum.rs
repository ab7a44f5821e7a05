//! Probe: a multibody revolute pendulum on rapier3d-f64 — set-up order, joint coordinates,
//! initial velocity and the period at dt = 1e-4 (compare `T = 4 √(l/g) K(sin(θ0/2))`).
use rapier3d_f64::parry::mass_properties::MassProperties;
use rapier3d_f64::prelude::*;

fn main() {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9.81);
    world.integration_parameters.dt = 1e-4;
    world.integration_parameters.num_solver_iterations = 1;
    world.integration_parameters.max_ccd_substeps = 0;
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    let l = 0.3;
    let mp = MassProperties::new(Vector::new(0.0, 0.0, -l), 1.0, Vector::splat(1e-12));
    let arm = world.insert_body(
        RigidBodyBuilder::dynamic()
            .additional_mass_properties(mp)
            .can_sleep(false),
    );
    let joint = RevoluteJointBuilder::new(Vector::X);
    let h = world.insert_multibody_joint(ground, arm, joint).unwrap();
    {
        let (mb, link_id) = world.multibody_joints.get_mut(h).unwrap();
        mb.forward_kinematics(&world.bodies, true);
        println!("ndofs after fk {} ", mb.ndofs());
        mb.damping_mut().fill(0.0);
        let a = mb.link(link_id).unwrap().assembly_id();
        let mut disp = vec![0.0; mb.ndofs()];
        disp[a] = -30f64.to_radians();
        mb.apply_displacements(&disp);
        mb.generalized_velocity_mut()[a] = 0.0;
        mb.forward_kinematics(&world.bodies, true);
        mb.update_rigid_bodies(&mut world.bodies, true);
    }
    println!("com {:?}", world.bodies[arm].center_of_mass());
    let mut prev = 0.0;
    let mut t = 0.0;
    for _ in 0..40000 {
        world.step();
        t += 1e-4;
        let (mb, link_id) = world.multibody_joints.get(h).unwrap();
        let a = mb.link(link_id).unwrap().assembly_id();
        let w = mb.generalized_velocity()[a];
        if prev < 0.0 && w >= 0.0 {
            println!(
                "velocity sign change at {t:.4} damping {:?}",
                mb.damping().as_slice()
            );
        }
        prev = w;
    }
}
