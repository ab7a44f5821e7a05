use rapier3d_f64::prelude::*;
use rapier3d_f64::parry::mass_properties::MassProperties;

fn main() {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9.81);
    world.integration_parameters.dt = 1e-4;
    world.integration_parameters.num_solver_iterations = 1;
    world.integration_parameters.max_ccd_substeps = 0;
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    // point mass 1 kg at 0.3 m below the pivot (pivot at origin)
    let l = 0.3;
    let mp = MassProperties::new(Vector::ZERO, 1.0, Vector::new(1e-12, 1e-12, 1e-12));
    let arm = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.0, -l))
            .additional_mass_properties(mp)
            .can_sleep(false),
    );
    let joint = RevoluteJointBuilder::new(Vector::X)
        .local_anchor1(Vector::ZERO)
        .local_anchor2(Vector::new(0.0, 0.0, l));
    let h = world.insert_multibody_joint(ground, arm, joint).unwrap();
    let theta0: f64 = 30f64.to_radians();
    {
        let (mb, link_id) = world.multibody_joints.get_mut(h).unwrap();
        println!("ndofs {} link {}", mb.ndofs(), link_id);
        mb.damping_mut().fill(0.0);
        let mut disp = vec![0.0; mb.ndofs()];
        let a = mb.link(link_id).unwrap().assembly_id(); disp[a] = theta0;
        mb.apply_displacements(&disp);
        mb.forward_kinematics(&world.bodies, true);
        mb.update_rigid_bodies(&mut world.bodies, true);
    }
    println!("pos {:?}", world.bodies[arm].translation());
    let mut prev_v = 0.0;
    let mut crossings = vec![];
    let mut t = 0.0;
    for _ in 0..200000 {
        world.step();
        t += 1e-4;
        let v = world.bodies[arm].angvel().x;
        if prev_v > 0.0 && v <= 0.0 { crossings.push(t); }
        prev_v = v;
        if crossings.len() >= 3 { break; }
    }
    println!("crossings {:?}", crossings);
    let (mb, link_id) = world.multibody_joints.get(h).unwrap();
    println!("coords {:?} damping {:?}", mb.link(link_id).unwrap().joint().coords(), mb.damping());
}
