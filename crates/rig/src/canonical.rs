//! Canonical problems of the rig with their references, shared by the tests and
//! `flexrig validate`.

use crate::geometry::OperatorGeometry;
use crate::hinge::HingeState;
use crate::world::RapierRig;

/// Complete elliptic integral of the first kind K(k), by the arithmetic–geometric mean.
pub fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Period [s] of the compound pendulum released at rest from `theta0` [rad]:
/// T = 4 √(J/(M g l_c)) K(sin(θ₀/2)) (`docs/references.md`).
pub fn compound_pendulum_period(op: &OperatorGeometry, g: f64, theta0: f64) -> f64 {
    4.0 * (op.inertia_pivot / (op.mass * g * op.com_distance)).sqrt()
        * elliptic_k((0.5 * theta0).sin())
}

/// The operator pendulum alone on Rapier, released from `theta0` [rad] and stepped with `dt`
/// [s]: its mean period over `swings` swings [s] (turning points interpolated linearly) and the
/// largest relative energy error on the way.
pub fn simulated_pendulum(
    op: &OperatorGeometry,
    g: f64,
    theta0: f64,
    dt: f64,
    swings: usize,
) -> (f64, f64) {
    let mut rig = RapierRig::new(g, op, None);
    rig.set_state(
        HingeState {
            angle: -theta0,
            rate: 0.0,
        },
        None,
    );
    let energy = |s: HingeState| {
        0.5 * op.inertia_pivot * s.rate * s.rate
            + op.mass * g * op.com_distance * (1.0 - s.angle.cos())
    };
    let e0 = energy(rig.operator_state());
    let (mut t, mut prev) = (0.0, rig.operator_state());
    let mut crossings = Vec::new();
    let mut worst = 0.0f64;
    while crossings.len() <= swings {
        rig.apply_torques(0.0, 0.0);
        rig.step(dt);
        t += dt;
        let s = rig.operator_state();
        // The far turning point: the rate crosses zero downwards.
        if prev.rate > 0.0 && s.rate <= 0.0 {
            crossings.push(t - dt + dt * prev.rate / (prev.rate - s.rate));
        }
        worst = worst.max((energy(s) - e0).abs() / e0);
        prev = s;
    }
    ((crossings[swings] - crossings[0]) / swings as f64, worst)
}
