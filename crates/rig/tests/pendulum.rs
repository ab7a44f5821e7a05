//! The operator pendulum alone against the elliptic-integral period, and its energy over many
//! swings (Rapier multibody joint, symplectic Euler at the default swing step).

mod common;

use flexrig_contact::tolerance::assert_close;
use flexrig_rig::geometry::RigGeometry;
use flexrig_rig::world::{HingeState, RapierRig};

/// Complete elliptic integral of the first kind K(k) by the arithmetic–geometric mean.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..40 {
        let (an, bn) = (0.5 * (a + b), (a * b).sqrt());
        a = an;
        b = bn;
    }
    std::f64::consts::PI / (2.0 * a)
}

#[test]
fn period_matches_the_elliptic_integral_and_energy_stays_bounded() {
    let scene = common::scene("cj_aluminium", &[]);
    let geometry = RigGeometry::of(&scene);
    let op = geometry.operator;
    let g = scene.file.gravity_mps2;
    let dt = scene.file.solver.swing_step_s;
    for release_deg in [10.0f64, 30.0, 90.0, 150.0] {
        let theta0 = release_deg.to_radians();
        // Compound pendulum: T = 4 √(J/(M g l_c)) K(sin(θ₀/2)) (references.md).
        let period = 4.0
            * (op.inertia_pivot / (op.mass * g * op.com_distance)).sqrt()
            * elliptic_k((0.5 * theta0).sin());
        let mut rig = RapierRig::new(g, &op, None);
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
        while crossings.len() < 21 {
            rig.apply_loads(None, 0.0);
            rig.step(dt);
            t += dt;
            let s = rig.operator_state();
            // Turning points on the release side: the rate crosses zero from − to +... use the
            // downward crossings of the rate (far turning point), interpolated linearly.
            if prev.rate > 0.0 && s.rate <= 0.0 {
                crossings.push(t - dt + dt * prev.rate / (prev.rate - s.rate));
            }
            worst = worst.max((energy(s) - e0).abs() / e0);
            prev = s;
        }
        let measured = (crossings[20] - crossings[0]) / 20.0;
        assert_close(
            &format!("period, θ₀ = {release_deg}°"),
            measured,
            period,
            1e-6,
        );
        assert!(
            worst < 2e-3,
            "θ₀ = {release_deg}°: energy error {worst:e} over 20 swings"
        );
    }
}
