//! The independent reference of the compliant-joint rig (see crates/rig/tests/reference.rs): its
//! two hinges (operator φ, robot ψ) as a reduced-coordinate ODE integrated by DOP853 at rtol
//! 1e-13, with the same dome–block geometry and contact law — no Rapier, no fixed steps. Shared
//! by the rig's tests and flexrig's test-bed safety tests (included by path).

#![allow(dead_code)]

use flexrig_contact::math::{Pose, Rotation, Vector};
use flexrig_contact::{BodyKinematics, ContactCallback, ContactSample, DomeBlockContact};
use flexrig_lumped::ode::dop853::{Dop853, Dop853Options, OdeSystem};
use flexrig_rig::Scene;
use flexrig_rig::geometry::RigGeometry;

/// The rig's two hinges as an ODE, y = (φ, φ̇, ψ, ψ̇).
pub struct TwoHinges {
    pub geometry: RigGeometry,
    pub gravity: f64,
    pub spring: f64,
    pub contact: DomeBlockContact,
}

impl TwoHinges {
    pub fn new(scene: &Scene) -> Self {
        let geometry = RigGeometry::of(scene);
        let op = &geometry.operator;
        let v_impact = scene
            .file
            .operator
            .start
            .initial_swing(
                op.mass,
                op.com_distance,
                op.inertia_pivot,
                scene.file.gravity_mps2,
            )
            .rate_at_contact
            * op.arm_length;
        let contact = DomeBlockContact::new(
            geometry.robot.dome_radius,
            Pose::from_translation(geometry.robot.dome_center_local),
            op.block_half_extents,
            Pose::from_translation(op.block_center_local),
            scene.contact_law(v_impact).unwrap(),
        )
        .unwrap();
        TwoHinges {
            geometry,
            gravity: scene.file.gravity_mps2,
            spring: scene.torsion_spring,
            contact,
        }
    }

    fn bodies(&self, y: &[f64; 4]) -> (BodyKinematics, BodyKinematics) {
        let pivot = self.geometry.operator.pivot;
        let block = BodyKinematics {
            pose: Pose::from_parts(pivot, Rotation::from_axis_angle(Vector::X, y[0])),
            reference_point: pivot,
            linvel: Vector::ZERO,
            angvel: Vector::X * y[1],
        };
        let dome = BodyKinematics {
            pose: Pose::from_parts(Vector::ZERO, Rotation::from_rotation_z(y[2])),
            reference_point: Vector::ZERO,
            linvel: Vector::ZERO,
            angvel: Vector::Z * y[3],
        };
        (dome, block)
    }

    pub fn contact_at(&self, y: &[f64; 4]) -> Option<ContactSample> {
        let (dome, block) = self.bodies(y);
        self.contact.evaluate(&dome, &block)
    }
}

impl OdeSystem<4> for TwoHinges {
    fn rhs(&self, _t: f64, y: &[f64; 4]) -> [f64; 4] {
        let op = &self.geometry.operator;
        let mut tau_op = -op.mass * self.gravity * op.com_distance * y[0].sin();
        let mut tau_rob = -self.spring * y[2];
        if let Some(c) = self.contact_at(y) {
            tau_op += (c.point - op.pivot).cross(c.force_on_block()).x;
            tau_rob += c.point.cross(c.force_on_dome()).z;
        }
        [
            y[1],
            tau_op / op.inertia_pivot,
            y[3],
            tau_rob / self.geometry.robot.inertia_axis,
        ]
    }
}

/// The maximum of `g` on [a, b] by golden-section search: (g, t).
pub fn golden_max(g: impl Fn(f64) -> f64, a: f64, b: f64) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut lo, mut hi) = (a, b);
    for _ in 0..200 {
        let (x1, x2) = (hi - r * (hi - lo), lo + r * (hi - lo));
        if g(x1) < g(x2) {
            lo = x1;
        } else {
            hi = x2;
        }
    }
    let t = 0.5 * (lo + hi);
    (g(t), t)
}

/// The reference peak force \[N\] and its time \[s\] from the state `y0` at t = 0: the largest
/// force on the dense output of the two steps around the first decrease.
pub fn reference_peak(system: &TwoHinges, y0: [f64; 4]) -> (f64, f64) {
    let options = Dop853Options {
        rtol: 1e-13,
        atol: [1e-15, 1e-13, 1e-15, 1e-13],
        first_step: None,
        max_step: 1e-4,
        max_steps: 10_000_000,
    };
    let mut ode = Dop853::new(system, 0.0, y0, options);
    let force = |y: &[f64; 4]| system.contact_at(y).map_or(0.0, |c| c.force);
    let mut previous_force = force(&y0);
    let mut previous_step = None;
    loop {
        ode.step(system).unwrap();
        let dense = ode.dense_output(system);
        let f = force(ode.y());
        if f < previous_force && previous_force > 0.0 {
            let last = golden_max(|t| force(&dense.eval(t)), dense.t_start(), dense.t_end());
            let before = previous_step.map_or(
                (0.0, 0.0),
                |d: flexrig_lumped::ode::dop853::DenseOutput<4>| {
                    golden_max(|t| force(&d.eval(t)), d.t_start(), d.t_end())
                },
            );
            return if last.0 >= before.0 { last } else { before };
        }
        previous_force = f;
        previous_step = Some(dense);
    }
}

/// One contact of the reference: (onset \[s\], peak force \[N\], time of the peak \[s\]).
pub type ReferenceContact = (f64, f64, f64);

/// Every contact of the swing from the state `y0` at t = 0, until the operator, out of contact
/// and having moved away from the dome, turns back (its rate's sign again that of the first
/// onset), or `t_end` \[s\]: each contact's onset (the start of the step it began in, refined by
/// bisection on sampled points of the dense output), its peak (the largest force on the dense output of its steps,
/// by golden-section search within each step) and its time.
pub fn reference_contacts(system: &TwoHinges, y0: [f64; 4], t_end: f64) -> Vec<ReferenceContact> {
    let options = Dop853Options {
        rtol: 1e-13,
        atol: [1e-15, 1e-13, 1e-15, 1e-13],
        first_step: None,
        max_step: 1e-4,
        max_steps: 50_000_000,
    };
    let mut ode = Dop853::new(system, 0.0, y0, options);
    let force = |y: &[f64; 4]| system.contact_at(y).map_or(0.0, |c| c.force);
    let mut contacts: Vec<ReferenceContact> = Vec::new();
    let mut open: Option<ReferenceContact> = None;
    let mut towards: Option<f64> = None;
    let mut away = false;
    while ode.t() < t_end {
        ode.step(system).unwrap();
        let dense = ode.dense_output(system);
        let (t0, t1) = (dense.t_start(), dense.t_end());
        let touching = force(&dense.eval(t0)) > 0.0
            || force(ode.y()) > 0.0
            || (1..16).any(|k| force(&dense.eval(t0 + (t1 - t0) * k as f64 / 16.0)) > 0.0);
        if touching {
            let (f, t) = golden_max(|t| force(&dense.eval(t)), t0, t1);
            let c = open.get_or_insert_with(|| {
                // the onset: bisection for the first touch in the step
                let (mut a, mut b) = (t0, t1);
                for _ in 0..60 {
                    let m = 0.5 * (a + b);
                    if first_touch_before(&dense, &force, t0, m) {
                        b = m;
                    } else {
                        a = m;
                    }
                }
                (b, 0.0, b)
            });
            if f > c.1 {
                c.1 = f;
                c.2 = t;
            }
            towards.get_or_insert(ode.y()[1].signum());
            away = false;
        }
        if force(ode.y()) == 0.0
            && let Some(c) = open.take()
        {
            contacts.push(c);
        }
        if open.is_none()
            && let Some(s) = towards
        {
            if ode.y()[1] * s < 0.0 {
                away = true;
            } else if away {
                break;
            }
        }
    }
    if let Some(c) = open {
        contacts.push(c);
    }
    contacts
}

/// Whether the force is positive anywhere on [t0, m] of the step's dense output (sampled).
fn first_touch_before(
    dense: &flexrig_lumped::ode::dop853::DenseOutput<4>,
    force: &dyn Fn(&[f64; 4]) -> f64,
    t0: f64,
    m: f64,
) -> bool {
    (0..=32).any(|k| force(&dense.eval(t0 + (m - t0) * k as f64 / 32.0)) > 0.0)
}
