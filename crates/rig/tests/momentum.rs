//! Momentum balance through the contact: the change of each hinge's angular momentum equals the
//! angular impulse of the forces applied to it (contact, gravity, spring), step by step as the
//! integrator applies them. This pins the sign, the point of application and the inertia that
//! Rapier's multibody sees.

mod common;

use flexrig_contact::ContactSample;
use flexrig_contact::tolerance::assert_close;
use flexrig_rig::geometry::RigGeometry;
use flexrig_rig::{Frame, Recorder, RigError, RunOptions, Simulation};

#[derive(Default)]
struct Impulses {
    last: Option<(Option<ContactSample>, f64, f64)>,
    operator: f64,
    robot: f64,
    first: Option<(f64, f64)>,
    end: (f64, f64),
    pivot: flexrig_contact::math::Vector,
    gravity_torque_coefficient: f64,
    spring: f64,
}

impl Recorder for Impulses {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        let robot = f.robot.expect("CJ");
        if let Some((contact, op_angle, robot_angle)) = self.last {
            // Forces held over this step: the contact at its start, gravity and the spring at
            // the start configuration.
            if let Some(c) = contact {
                self.operator += (c.point - self.pivot).cross(c.force_on_block()).x * f.dt;
                self.robot += c.point.cross(c.force_on_dome()).z * f.dt;
            }
            self.operator -= self.gravity_torque_coefficient * op_angle.sin() * f.dt;
            self.robot -= self.spring * robot_angle * f.dt;
        }
        self.last = Some((f.contact, f.operator.angle, robot.angle));
        self.end = (f.operator.rate, robot.rate);
        Ok(())
    }
}

#[test]
fn angular_momentum_changes_by_the_applied_impulse() {
    for name in ["cj_aluminium", "cj_iron"] {
        let scene = common::scene(name, &[("from = \"release\"", "from = \"contact\"")]);
        let g = RigGeometry::of(&scene);
        let sim = Simulation::new(&scene, RunOptions::default()).unwrap();
        let mut rec = Impulses {
            pivot: g.operator.pivot,
            gravity_torque_coefficient: g.operator.mass
                * scene.file.gravity_mps2
                * g.operator.com_distance,
            spring: scene.torsion_spring,
            ..Impulses::default()
        };
        // The first frame's start state: operator at ω₀, robot at rest.
        let omega0 = g
            .operator
            .bottom_angular_speed(30f64.to_radians(), scene.file.gravity_mps2);
        rec.first = Some((omega0, 0.0));
        rec.last = Some((None, 0.0, 0.0));
        let summary = sim.run(&mut rec).unwrap();
        let (w_op, w_rob) = rec.end;
        assert_close(
            &format!("{name}: J_op Δω_op = contact + gravity impulse"),
            g.operator.inertia_pivot * (w_op - omega0),
            rec.operator,
            1e-9,
        );
        assert_close(
            &format!("{name}: J_rob Δω_rob = contact + spring impulse"),
            g.robot.inertia_axis * w_rob,
            rec.robot,
            1e-9,
        );
        assert!(summary.contact_steps > 100);
    }
}
