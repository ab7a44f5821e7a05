//! The adaptive free flight (`solver.swing = "adaptive"`, the default) against the closed-form
//! compound pendulum: released at rest from θ₀ it reaches the bottom — where the block's face
//! touches the dome apex — after a quarter period, T/4 = √(J/(M g l_c)) K(sin(θ₀/2)), with the
//! energy speed ω_b = √(2 M g l_c (1 − cos θ₀)/J) (`docs/references.md`); in between,
//! sin(φ/2) = −k sn(K − ω₀ t, k) with k = sin(θ₀/2), ω₀ = √(M g l_c/J) (Jacobi's elliptic
//! sine, computed here by the descending Landen/AGM transformation, Abramowitz & Stegun 16.4).

mod common;

use flexrig_contact::tolerance::assert_close;
use flexrig_rig::canonical::{compound_pendulum_period, elliptic_k};
use flexrig_rig::geometry::RigGeometry;
use flexrig_rig::{
    Frame, NoRecorder, Recorder, RigError, RunOptions, RunSummary, Scene, Simulation, StepOutcome,
};

fn run(scene: &Scene) -> RunSummary {
    Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut NoRecorder)
        .unwrap()
}

fn released(name: &str, release_deg: f64, swing: &str) -> Scene {
    common::scene(
        name,
        &[
            (
                "release_angle_deg = 30.0",
                &format!("release_angle_deg = {release_deg:?}"),
            ),
            (
                "swing_step_s = 5e-4",
                &format!("swing_step_s = 5e-4\nswing = \"{swing}\""),
            ),
        ],
    )
}

/// Jacobi's elliptic sine sn(u, k) by the descending Landen (AGM) transformation
/// (Abramowitz & Stegun 16.4).
fn jacobi_sn(u: f64, k: f64) -> f64 {
    let mut a = vec![1.0f64];
    let mut c = vec![k];
    let mut b = (1.0 - k * k).sqrt();
    while c.last().unwrap().abs() > 1e-17 && a.len() < 40 {
        let (an, bn) = (*a.last().unwrap(), b);
        a.push(0.5 * (an + bn));
        c.push(0.5 * (an - bn));
        b = (an * bn).sqrt();
    }
    let n = a.len() - 1;
    let mut phi = 2f64.powi(n as i32) * a[n] * u;
    for i in (1..=n).rev() {
        phi = 0.5 * (phi + (c[i] / a[i] * phi.sin()).asin());
    }
    phi.sin()
}

#[test]
fn onset_time_and_impact_speed_match_the_elliptic_integral_and_the_energy() {
    for name in ["cj_aluminium", "cl_aluminium", "cj_iron"] {
        for release_deg in [10.0f64, 30.0, 90.0, 150.0] {
            let scene = released(name, release_deg, "adaptive");
            let g = RigGeometry::of(&scene);
            let gravity = scene.file.gravity_mps2;
            let theta0 = release_deg.to_radians();
            let quarter = 0.25 * compound_pendulum_period(&g.operator, gravity, theta0);
            let speed = g.operator.bottom_angular_speed(theta0, gravity) * g.operator.arm_length;
            let s = run(&scene);
            let fixed = run(&released(name, release_deg, "fixed"));
            let label = format!("{name}, θ₀ = {release_deg}°");
            println!(
                "{label}: onset {:.2e} (fixed {:.2e}), impact speed {:.2e} (fixed {:.2e}), \
                 {} steps before contact (fixed {})",
                s.onset_time_s / quarter - 1.0,
                fixed.onset_time_s / quarter - 1.0,
                s.impact_velocity_mps / speed - 1.0,
                fixed.impact_velocity_mps / speed - 1.0,
                s.steps - s.contact_steps,
                fixed.steps - fixed.contact_steps,
            );
            // measured ≤ 1e-12 (onset and speed) in 9 … 25 steps; fixed 5e-4 s steps: 3e-8 … 1e-6
            assert_close(
                &format!("{label}: onset time"),
                s.onset_time_s,
                quarter,
                1e-9,
            );
            assert_close(
                &format!("{label}: impact speed"),
                s.impact_velocity_mps,
                speed,
                1e-9,
            );
            // at or below the fixed swing's error
            assert!(
                (s.onset_time_s - quarter).abs() <= (fixed.onset_time_s - quarter).abs(),
                "{label}: onset error above the fixed swing's"
            );
            assert!(
                (s.impact_velocity_mps - speed).abs() <= (fixed.impact_velocity_mps - speed).abs(),
                "{label}: impact speed error above the fixed swing's"
            );
        }
    }
}

#[test]
fn the_steps_before_contact_do_not_grow_with_the_swing() {
    // A 10° release reaches the dome after 0.28 s, a 150° release after 0.49 s: 555 … 970
    // fixed swing steps, a few adaptive ones either way (measured 9 and 25).
    for release_deg in [10.0f64, 150.0] {
        let s = run(&released("cj_aluminium", release_deg, "adaptive"));
        let swing_steps = s.steps - s.contact_steps;
        assert!(
            swing_steps <= 40,
            "θ₀ = {release_deg}°: {swing_steps} steps before the contact"
        );
        let fixed = run(&released("cj_aluminium", release_deg, "fixed"));
        assert!(fixed.steps - fixed.contact_steps > 500);
    }
}

/// Every frame's samples and step, for consistency checks.
#[derive(Default)]
struct Frames {
    steps: usize,
    samples: Vec<flexrig_rig::sensors::SensorSample>,
    /// (t, dt, outcome) of each frame.
    times: Vec<(f64, f64, StepOutcome)>,
}

impl Recorder for Frames {
    fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
        self.steps += 1;
        self.samples.extend_from_slice(f.samples);
        self.times.push((f.t, f.dt, f.outcome));
        Ok(())
    }
}

#[test]
fn sensor_samples_of_the_free_swing_follow_the_elliptic_solution() {
    for name in ["cj_aluminium", "cl_aluminium"] {
        let scene = common::scene(name, &[]);
        let g = RigGeometry::of(&scene);
        let op = g.operator;
        let gravity = scene.file.gravity_mps2;
        let theta0 = 30f64.to_radians();
        let omega0 = (op.mass * gravity * op.com_distance / op.inertia_pivot).sqrt();
        let k = (0.5 * theta0).sin();
        let big_k = elliptic_k(k);
        let mut rec = Frames::default();
        let s = Simulation::new(&scene, RunOptions::default())
            .unwrap()
            .run(&mut rec)
            .unwrap();
        // The recorder saw every step and every sample, at the sampling rate without a gap.
        assert_eq!(rec.steps, s.steps);
        assert_eq!(rec.samples, s.samples);
        let period = 1.0 / scene.file.record.sample_rate_hz;
        for (i, sample) in s.samples.iter().enumerate() {
            assert_eq!(sample.t, i as f64 * period, "{name}: sample {i}");
        }
        assert!(s.samples.last().unwrap().t > s.duration_s - period);
        // Frames are consecutive steps.
        let mut t = 0.0;
        for &(t_end, dt, _) in &rec.times {
            assert_close(&format!("{name}: frame at {t_end}"), t + dt, t_end, 1e-12);
            t = t_end;
        }
        // The swing's samples against the elliptic solution (angle), and the accelerometer
        // against l (cos φ φ̈ − sin φ φ̇²) with φ̈ = −ω₀² sin φ and φ̇² = 2 ω₀² (cos φ − cos θ₀).
        let mut worst = (0.0f64, 0.0f64);
        let accel_scale = op.arm_length * omega0 * omega0;
        for sample in s.samples.iter().filter(|x| x.t < s.onset_time_s) {
            let phi = 2.0 * (-k * jacobi_sn(big_k - omega0 * sample.t, k)).asin();
            let rate2 = 2.0 * omega0 * omega0 * (phi.cos() - theta0.cos());
            let accel = op.arm_length
                * (-phi.cos() * omega0 * omega0 * phi.sin() - phi.sin() * rate2.max(0.0));
            worst.0 = worst.0.max((sample.operator_angle_rad - phi).abs());
            worst.1 = worst
                .1
                .max((sample.operator_accel_mps2 - accel).abs() / accel_scale);
            assert_eq!(sample.force_n, 0.0);
            assert_eq!(sample.robot_angle_rad, 0.0);
            assert_eq!(sample.link_tip_deflection_m, 0.0);
            assert_eq!(sample.load_accel_mps2, 0.0);
        }
        println!(
            "{name}: swing samples off the elliptic solution by {:.2e} rad, accelerometer {:.2e}",
            worst.0, worst.1
        );
        // measured 5.4e-12 rad and 5.6e-12
        assert!(worst.0 < 1e-10, "{name}: angle off by {:e} rad", worst.0);
        assert!(worst.1 < 1e-9, "{name}: acceleration off by {:e}", worst.1);
    }
}

#[test]
fn fixed_and_adaptive_swings_agree_through_the_contact() {
    // The same contact from either swing: the adaptive one hands Rapier the exact onset state,
    // the fixed one lands on it within its own O(h²) swing error (measured 1.5e-6 on the peak).
    for name in ["cj_aluminium", "cl_aluminium"] {
        let adaptive = run(&released(name, 30.0, "adaptive"));
        let fixed = run(&released(name, 30.0, "fixed"));
        assert_close(
            &format!("{name}: peak"),
            adaptive.peak_force_n,
            fixed.peak_force_n,
            1e-5,
        );
        assert_close(
            &format!("{name}: contact duration"),
            adaptive.contact_duration_s.unwrap(),
            fixed.contact_duration_s.unwrap(),
            1e-5,
        );
        let (before, after) = adaptive.energy_through_contact_j.unwrap();
        assert!(((after - before) / before).abs() < 1e-6, "{name}");
    }
}

#[test]
fn a_second_contact_after_the_free_flight_is_located() {
    // CJ for 1 s: the link, pushed away on its spring, and the pendulum meet again; between
    // the contacts both hinges fly freely (adaptive), and the second onset is located on the
    // gap as the first. Against the fixed swing: the same second contact within its swing error.
    let edit = [("at = \"separation\"", "at = \"duration\"\nduration_s = 1.0")];
    let adaptive = run(&common::scene("cj_aluminium", &edit));
    let mut fixed_edit = edit.to_vec();
    fixed_edit.push((
        "swing_step_s = 5e-4",
        "swing_step_s = 5e-4\nswing = \"fixed\"",
    ));
    let fixed = run(&common::scene("cj_aluminium", &fixed_edit));
    assert_eq!(adaptive.duration_s, 1.0);
    assert!(adaptive.contacts.len() >= 2, "{:?}", adaptive.contacts);
    assert_eq!(adaptive.contacts.len(), fixed.contacts.len());
    for (i, (a, f)) in adaptive.contacts.iter().zip(&fixed.contacts).enumerate() {
        println!(
            "contact {i}: onset {} vs {} s, peak {} vs {} N",
            a.onset_time_s, f.onset_time_s, a.peak_force_n, f.peak_force_n
        );
        assert!(
            (a.onset_time_s - f.onset_time_s).abs() < 1e-6,
            "contact {i}"
        );
        assert_close(
            &format!("contact {i}: peak"),
            a.peak_force_n,
            f.peak_force_n,
            1e-4,
        );
    }
    // The energy between and after the contacts: undamped, so the energy at the end of the
    // run is the initial one up to the contacts' own integration error.
    assert!(
        ((adaptive.energy_final_j - adaptive.energy_initial_j) / adaptive.energy_initial_j).abs()
            < 1e-5
    );
}

#[test]
fn an_unknown_swing_policy_is_refused_naming_the_field() {
    let text = common::scene_text("cj_aluminium").replace(
        "swing_step_s = 5e-4",
        "swing_step_s = 5e-4\nswing = \"rk4\"",
    );
    let e = Scene::from_toml_str(&text, &flexrig_contact::Materials::bundled().unwrap())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("rk4") && e.contains("adaptive") && e.contains("fixed"),
        "{e}"
    );
    assert!(e.contains("swing"), "{e}");
}

#[test]
fn the_swing_policy_can_be_set_from_the_command_line() {
    // `--set solver.swing=fixed` (a bare word is a string): the fixed swing's step count.
    let materials = flexrig_contact::Materials::bundled().unwrap();
    let text = common::scene_text("cj_aluminium");
    let fixed = flexrig_rig::scene_with_overrides(
        &text,
        &[flexrig_rig::Override::parse("solver.swing=fixed").unwrap()],
        &materials,
    )
    .unwrap();
    assert_eq!(fixed.file.solver.swing, flexrig_rig::SwingPolicy::Fixed);
    let s = run(&fixed);
    assert!(s.steps - s.contact_steps > 500, "{} swing steps", s.steps);
    let default = Scene::from_toml_str(&text, &materials).unwrap();
    assert_eq!(
        default.file.solver.swing,
        flexrig_rig::SwingPolicy::Adaptive
    );
}
