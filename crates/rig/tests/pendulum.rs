//! The operator pendulum alone against the elliptic-integral period, and its energy over many
//! swings (Rapier multibody joint, symplectic Euler at the default swing step).

mod common;

use flexrig_contact::tolerance::assert_close;
use flexrig_rig::canonical::{compound_pendulum_period, simulated_pendulum};
use flexrig_rig::geometry::RigGeometry;

#[test]
fn period_matches_the_elliptic_integral_and_energy_stays_bounded() {
    let scene = common::scene("cj_aluminium", &[]);
    let op = RigGeometry::of(&scene).operator;
    let g = scene.file.gravity_mps2;
    let dt = scene.file.solver.swing_step_s;
    for release_deg in [10.0f64, 30.0, 90.0, 150.0] {
        let theta0 = release_deg.to_radians();
        let (period, energy_error) = simulated_pendulum(&op, g, theta0, dt, 20);
        assert_close(
            &format!("period, θ₀ = {release_deg}°"),
            period,
            compound_pendulum_period(&op, g, theta0),
            1e-6,
        );
        assert!(
            energy_error < 2e-3,
            "θ₀ = {release_deg}°: energy error {energy_error:e} over 20 swings"
        );
    }
}
