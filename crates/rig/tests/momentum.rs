//! Momentum balance through the contact: each hinge moves as the velocity-Verlet step of the
//! torques applied to it (contact, gravity, spring) — the angle by φ' = φ + h ω + (h²/2) a, the
//! synchronised rate by ω' = ω + (h/2)(a + a') — step by step, with a = τ/J computed here from
//! the logged contact and the geometry. This pins the sign, the point of application and the
//! inertia that Rapier's multibody sees, and that the angular momentum changes by the trapezoidal
//! impulse of the torques.

mod common;

use flexrig_contact::math::Vector;
use flexrig_contact::tolerance::assert_close;
use flexrig_rig::geometry::RigGeometry;
use flexrig_rig::{Frame, Recorder, RigError, RunOptions, Simulation};

/// (operator angle, rate, acceleration), (robot angle, rate, acceleration).
type Hinges = ([f64; 3], [f64; 3]);

struct Balance {
    geometry: RigGeometry,
    gravity: f64,
    spring: f64,
    last: Option<Hinges>,
    /// Worst |angle − velocity-Verlet angle| over the steps \[rad\].
    angle_error: f64,
    /// Worst |J Δω − trapezoidal impulse| relative to the impulse of the contact.
    impulse: [f64; 2],
    change: [f64; 2],
}

impl Balance {
    fn hinges(&self, f: &Frame<'_>) -> Hinges {
        let op = &self.geometry.operator;
        let robot = f.robot.expect("CJ");
        let mut tau_op = -op.mass * self.gravity * op.com_distance * f.operator.angle.sin();
        let mut tau_rob = -self.spring * robot.angle;
        if let Some(c) = f.contact {
            tau_op += (c.point - op.pivot).cross(c.force_on_block()).x;
            tau_rob += c.point.cross(c.force_on_dome()).z;
        }
        (
            [f.operator.angle, f.operator.rate, tau_op / op.inertia_pivot],
            [
                robot.angle,
                robot.rate,
                tau_rob / self.geometry.robot.inertia_axis,
            ],
        )
    }
}

impl Recorder for Balance {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        let now = self.hinges(f);
        if let Some(before) = self.last {
            let h = f.dt;
            let inertia = [
                self.geometry.operator.inertia_pivot,
                self.geometry.robot.inertia_axis,
            ];
            for (k, (b, n)) in [(before.0, now.0), (before.1, now.1)].iter().enumerate() {
                let angle = b[0] + h * b[1] + 0.5 * h * h * b[2];
                self.angle_error = self.angle_error.max((n[0] - angle).abs());
                self.impulse[k] += inertia[k] * 0.5 * h * (b[2] + n[2]);
                self.change[k] += inertia[k] * (n[1] - b[1]);
            }
        }
        self.last = Some(now);
        Ok(())
    }
}

#[test]
fn angular_momentum_changes_by_the_applied_impulse() {
    for name in ["cj_aluminium", "cj_iron"] {
        // Rapier's contact (the CJ's default is the adaptive one, which Rapier does not step)
        let scene = common::scene(
            name,
            &[
                ("from = \"release\"", "from = \"contact\""),
                (
                    "contact_steps = 800",
                    "contact_steps = 800\ncontact = \"fixed\"",
                ),
            ],
        );
        let geometry = RigGeometry::of(&scene);
        let sim = Simulation::new(&scene, RunOptions::default()).unwrap();
        let mut rec = Balance {
            geometry,
            gravity: scene.file.gravity_mps2,
            spring: scene.torsion_spring,
            last: None,
            angle_error: 0.0,
            impulse: [0.0; 2],
            change: [0.0; 2],
        };
        // The start state as the first frame's predecessor: at contact, operator at the
        // energy speed of the 30° release, robot at rest, no force yet.
        let omega0 = geometry
            .operator
            .bottom_angular_speed(30f64.to_radians(), scene.file.gravity_mps2);
        rec.last = Some(([0.0, omega0, 0.0], [0.0, 0.0, 0.0]));
        let summary = sim.run(&mut rec).unwrap();
        // Rapier's angle is the velocity-Verlet angle of our torques: measured ≤ 1e-15 rad.
        assert!(
            rec.angle_error < 1e-12,
            "{name}: angle off the velocity-Verlet step by {:e} rad",
            rec.angle_error
        );
        for (k, hinge) in ["operator", "robot"].iter().enumerate() {
            assert_close(
                &format!("{name}: {hinge} J Δω = trapezoidal impulse of the torques"),
                rec.change[k],
                rec.impulse[k],
                1e-9,
            );
        }
        // and the contact impulse reported is the one applied: the robot's angular momentum
        // after separation is the contact's angular impulse plus the spring's (small).
        let arm = Vector::new(geometry.robot.length, 0.0, 0.0).length();
        assert!(
            (rec.change[1] / arm / summary.impulse_n_s - 1.0).abs() < 0.05,
            "{name}: robot momentum {} vs contact impulse {} N·s at the arm {arm} m",
            rec.change[1],
            summary.impulse_n_s
        );
        assert!(summary.contact_steps > 100);
    }
}
