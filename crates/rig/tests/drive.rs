//! A motor on the robot joint of the test bed (`[robot.drive]`), CJ: checked against analytic
//! solutions (a constant-speed trajectory leaves the series spring unloaded; a constant
//! acceleration loads it as (J_l α/k)(1 − cos ω_l t)), the conservation of energy (the motor's
//! work less the friction equals the change of the mechanical energy), the test bed itself (a
//! drive held at rest is the fixed axis, bit for bit), and the bundled test-bed scenes, which
//! must run bit-identically with the drive code in place (the CL scenes to round-off, see the
//! test).

mod common;

use flexrig_contact::Materials;
use flexrig_rig::{
    DriveFrame, Frame, RigError, RunOptions, RunSummary, Scene, Simulation, run::Recorder,
};

/// The bundled test-bed scenes' results before the drive existed (`flexrig run --json` of the
/// main branch at the drive's start): peak force, time of peak, onset, duration, impulse, final
/// energy (as IEEE-754 bits) and the number of steps — with Rapier's contact, which those
/// results were of (the CJ now takes the adaptive contact by default; that one is held against
/// the independent two-hinge reference in tests/reference.rs).
const GOLDEN: [(&str, [u64; 6], usize); 6] = [
    (
        "cj_aluminium",
        [
            0x406674e5e7bafd1c,
            0x3fd1f60e132cdf9d,
            0x3fd1d28bf3e47003,
            0x3f71bfe2c6872300,
            0x3fd7ead355fa7e19,
            0x3fc4d7f6340e2c7f,
        ],
        760,
    ),
    (
        "cj_iron",
        [
            0x4070e9b15ddf3960,
            0x3fd226c22347b492,
            0x3fd1faf5b05d184b,
            0x3f75e86f240bc840,
            0x3fe6000cbc0489c7,
            0x3ff96125a816942c,
        ],
        759,
    ),
    (
        "cj_light_load",
        [
            0x4059daaa8d0d53c4,
            0x3fd1ed58f038942f,
            0x3fd1d28bf3e47003,
            0x3f6acd749c608200,
            0x3fc4ca217b680f6b,
            0x3fc4d7f6334fd489,
        ],
        761,
    ),
    (
        "cl_aluminium",
        [
            0x40663b73edd1242c,
            0x3fd1f5e4e4e334ed,
            0x3fd1d28bf3e47003,
            0x3f71bb3352b78d00,
            0x3fd79ee98cd47f23,
            0x3fc4d7f62c6d559b,
        ],
        760,
    ),
    (
        "cl_iron",
        [
            0x40709de21a166266,
            0x3fd2266c62b0e5e6,
            0x3fd1faf5b05d184b,
            0x3f75f73d45871740,
            0x3fe58f3997512037,
            0x3ff96125a3809550,
        ],
        761,
    ),
    (
        "cl_light_load",
        [
            0x405830d6ab781fb5,
            0x3fd1ec87d30718f0,
            0x3fd1d28bf3e47003,
            0x3f6a4e86c01c3280,
            0x3fc306b3e1b7fc63,
            0x3fc4d7f627d9544e,
        ],
        747,
    ),
];

/// Keeps every frame's time, energy and drive channels.
#[derive(Default)]
struct Keep(Vec<(f64, f64, DriveFrame)>);

impl Recorder for Keep {
    fn frame(&mut self, frame: &Frame<'_>) -> Result<(), RigError> {
        if let Some(d) = frame.drive {
            self.0.push((frame.t, frame.energy, d));
        }
        Ok(())
    }
}

fn parse(text: &str) -> Result<Scene, RigError> {
    Scene::from_toml_str(text, &Materials::bundled().unwrap())
}

fn run(scene: &Scene) -> RunSummary {
    run_keeping(scene).0
}

/// The run's summary and the drive's channels of every frame.
fn run_keeping(scene: &Scene) -> (RunSummary, Keep) {
    let mut keep = Keep::default();
    let s = Simulation::new(scene, RunOptions::default())
        .unwrap()
        .run(&mut keep)
        .unwrap();
    (s, keep)
}

/// The bundled driven scene with its `[robot.drive.*]` tables replaced by `drive` (TOML
/// tables under `robot.drive`) and the other `edits` applied.
fn driven_text(drive: &str, edits: &[(&str, &str)]) -> String {
    let text = common::scene_text("rig_driven_cj");
    let start = text.find("[robot.drive.motor]").unwrap();
    let end = text.find("[contact]").unwrap();
    let mut text = format!("{}{drive}\n{}", &text[..start], &text[end..]);
    for (from, to) in edits {
        assert!(text.contains(from), "no {from:?} to replace");
        text = text.replace(from, to);
    }
    text
}

const MOTOR: &str =
    "[robot.drive.motor]\nrotor_inertia = 1.9424e-5\ngear_ratio = 10.0\nfriction = 1e-5\n";

/// Steps `scene` to `t_end` \[s\] (no contact needed), keeping the drive's channels.
fn frames_to(scene: &Scene, t_end: f64) -> (Vec<(f64, f64, DriveFrame)>, f64) {
    let mut sim = Simulation::new(scene, RunOptions::default()).unwrap();
    let inertia = sim.geometry().robot.inertia_axis;
    let mut keep = Keep::default();
    while sim.time() < t_end {
        sim.step(&mut keep).unwrap();
    }
    (keep.0, inertia)
}

#[test]
fn the_bundled_test_bed_scenes_run_bit_identically() {
    for (name, bits, steps) in GOLDEN {
        let scene = common::scene(
            name,
            &[(
                "contact_steps = 800",
                "contact_steps = 800\ncontact = \"fixed\"",
            )],
        );
        assert!(scene.drive.is_none());
        let s = run(&scene);
        let got = [
            s.peak_force_n,
            s.time_of_peak_s,
            s.onset_time_s,
            s.contact_duration_s.unwrap(),
            s.impulse_n_s,
            s.energy_final_j,
        ];
        for (i, (g, b)) in got.iter().zip(bits).enumerate() {
            if name.starts_with("cl_") {
                // The CL's beam solve moved from a pivoting LU to an LDLᵀ factorisation after
                // these values were recorded: the same equations, round-off apart.
                let want = f64::from_bits(b);
                assert!(
                    (g - want).abs() <= 1e-12 * want.abs(),
                    "{name}: quantity {i}: {g} vs {want}"
                );
            } else {
                assert_eq!(
                    g.to_bits(),
                    b,
                    "{name}: quantity {i}: {g} vs {}",
                    f64::from_bits(b)
                );
            }
        }
        assert_eq!(s.steps, steps, "{name}");
        assert!(s.drive.is_none());
    }
}

/// (a) An ideal position source at constant speed, everything in steady motion at t = 0: the
/// series spring stays unloaded, the link follows the command exactly and the motor supplies
/// the friction torque c_m N² ω — analytic, to round-off.
#[test]
fn a_constant_speed_trajectory_leaves_the_spring_unloaded() {
    let drive = format!(
        "{MOTOR}[robot.drive.command]\ncommand = \"trajectory\"\n[robot.drive.command.profile]\n\
         profile = \"steady\"\nspeed = 2.0\n[robot.drive.placement]\nplacement = \"angle\"\n\
         angle = 1.2\n"
    );
    let scene = parse(&driven_text(&drive, &[])).unwrap();
    let (frames, _) = frames_to(&scene, 0.4);
    assert!(frames.len() > 1000);
    let c_j = 1e-5 * 100.0;
    for (t, _, d) in &frames {
        assert!((d.commanded_angle_rad - 2.0 * t).abs() <= 1e-12, "t = {t}");
        assert!(
            (d.link_angle_rad - d.commanded_angle_rad).abs() <= 1e-12,
            "t = {t}: link {} vs {}",
            d.link_angle_rad,
            d.commanded_angle_rad
        );
        assert!((d.link_speed_rad_s - 2.0).abs() <= 1e-12);
        assert!(d.spring_moment_nm.abs() <= 1e-12);
        assert!((d.joint_torque_nm - c_j * 2.0).abs() <= 1e-12);
    }
}

/// (a) A PD loop holding a constant speed against the friction, everything in steady motion at
/// t = 0: the loop's preload is the lag e = c_m N² ω/K_p, so the motor runs that far behind the
/// command, the spring stays unloaded and the joint torque is c_m N² ω — analytic, to round-off.
#[test]
fn a_pd_loop_at_constant_speed_lags_by_the_friction_over_its_gain() {
    let (kp, speed) = (50.0, 2.0);
    let drive = format!(
        "{MOTOR}[robot.drive.command]\ncommand = \"controller\"\n[robot.drive.command.profile]\n\
         profile = \"steady\"\nspeed = {speed:.1}\n[robot.drive.command.gains]\nkp = {kp:.1}\nkd = 1.2\n\
         [robot.drive.placement]\nplacement = \"angle\"\nangle = 1.2\n"
    );
    let scene = parse(&driven_text(&drive, &[])).unwrap();
    let (frames, _) = frames_to(&scene, 0.4);
    let c_j = 1e-5 * 100.0;
    let lag = c_j * speed / kp;
    for (t, _, d) in &frames {
        let behind = d.commanded_angle_rad - d.motor_angle_rad;
        assert!((behind - lag).abs() <= 1e-12, "t = {t}: {behind} vs {lag}");
        assert!((d.link_angle_rad - d.motor_angle_rad).abs() <= 1e-12);
        assert!((d.motor_speed_rad_s - speed).abs() <= 1e-12);
        assert!((d.joint_torque_nm - c_j * speed).abs() <= 1e-12);
        assert!((d.motor_torque_nm - c_j * speed / 10.0).abs() <= 1e-13);
    }
}

/// (a) A trapezoidal profile from rest: during the constant acceleration α the link on the
/// spring k lags by d(t) = (J_l α/k)(1 − cos ω_l t), ω_l = √(k/J_l) (the hub prescribed,
/// J_l d̈ + k d = J_l α, d(0) = ḋ(0) = 0). The rig's d = (spring moment)/k within 1e-5 of
/// J_l α/k at every step (the velocity-Verlet step of 1e-4 s: phase error ≈ (ω_l h)²/24 per
/// radian).
#[test]
fn a_constant_acceleration_loads_the_spring_as_the_analytic_solution() {
    let alpha = 10.0;
    let drive = format!(
        "{MOTOR}[robot.drive.command]\ncommand = \"trajectory\"\n[robot.drive.command.profile]\n\
         profile = \"trapezoid\"\nspeed = 2.0\nacceleration = {alpha}\n[robot.drive.placement]\n\
         placement = \"angle\"\nangle = 1.5\n"
    );
    let scene = parse(&driven_text(&drive, &[])).unwrap();
    let k = scene.torsion_spring;
    let (frames, j_l) = frames_to(&scene, 0.2);
    let static_lag = j_l * alpha / k;
    let omega = (k / j_l).sqrt();
    let mut worst: f64 = 0.0;
    let mut n = 0;
    for (t, _, d) in frames.iter().filter(|(t, _, _)| *t <= 0.2 - 1e-9) {
        let exact = static_lag * (1.0 - (omega * t).cos());
        let got = d.spring_moment_nm / k;
        worst = worst.max((got - exact).abs() / static_lag);
        n += 1;
        // the hub follows the command exactly
        assert!((d.motor_angle_rad - 0.5 * alpha * t * t).abs() <= 1e-12);
    }
    assert!(n > 1000);
    eprintln!(
        "constant acceleration: J_l α/k = {static_lag:.6e} rad, worst error {worst:.3e} of it over {n} steps"
    );
    assert!(worst <= 1e-5, "worst {worst:e}");
}

/// (b) The motor's work less the friction's equals the change of the mechanical energy
/// (operator, rotor, spring, link, contact) at every step of the bundled driven strike: PD
/// ramp, contact with the hanging block, separation.
#[test]
fn the_motor_work_balances_the_energy() {
    let (s, keep) = run_keeping(&common::scene("rig_driven_cj", &[]));
    let d = s.drive.unwrap();
    let e0 = s.energy_initial_j;
    let mut worst: f64 = 0.0;
    for (_, e, f) in &keep.0 {
        worst = worst.max((e - e0 - (f.motor_work_j - f.friction_dissipated_j)).abs());
    }
    let change = s.energy_final_j - e0;
    let net = d.motor_work_j - d.friction_dissipated_j;
    eprintln!(
        "driven CJ: motor work {:.6e} J, friction {:.6e} J, energy change {change:.6e} J, end residual {:.3e} J, worst residual {worst:.3e} J ({:.3e} of the work); peak {:.3} N",
        d.motor_work_j,
        d.friction_dissipated_j,
        net - change,
        worst / d.motor_work_j,
        s.peak_force_n
    );
    assert!(d.motor_work_j > 0.0 && d.friction_dissipated_j > 0.0);
    assert!((net - change).abs() <= 1e-4 * d.motor_work_j);
    assert!(worst <= 1e-4 * d.motor_work_j);
    let (link, commanded) = (
        d.link_speed_at_onset_rad_s.unwrap(),
        d.commanded_speed_at_onset_rad_s.unwrap(),
    );
    eprintln!("link speed at the onset {link:.6} rad/s, commanded {commanded:.6} rad/s");
    assert!(link > 0.0 && commanded > 0.0);
}

fn held(extra: &str) -> String {
    format!(
        "{}\n[robot.drive.motor]\nrotor_inertia = 1.9424e-5\ngear_ratio = 10.0\nfriction = 1e-5\n{extra}\n[robot.drive.placement]\nplacement = \"angle\"\nangle = 0.0\n",
        common::scene_text("cj_light_load")
    )
}

/// (c) A drive held infinitely stiff at rest (an ideal position source standing still) is the
/// test bed's fixed axis: the same run as the test bed stepped by Rapier (`solver.swing =
/// "fixed"`), bit for bit, and the default (adaptive) test bed within 1e-5 (peak, duration).
/// PD loops holding the rotor give the held drive's peak within 1e-6 (the test bed's soft
/// spring: the contact is over before the joint is loaded, docs/driven.md), at the same swing
/// step.
#[test]
fn a_drive_held_at_rest_is_the_test_bed() {
    let fixed_bed = common::scene_text("cj_light_load").replace(
        "contact_steps = 800",
        "contact_steps = 800\nswing = \"fixed\"",
    );
    let bed_fixed = run(&parse(&fixed_bed).unwrap());
    let bed = run(&common::scene("cj_light_load", &[]));
    let hold = "[robot.drive.command]\ncommand = \"trajectory\"\n[robot.drive.command.profile]\nprofile = \"steady\"\nspeed = 0.0\n";
    let s = run(&parse(&held(hold)).unwrap());
    assert_eq!(s.peak_force_n.to_bits(), bed_fixed.peak_force_n.to_bits());
    assert_eq!(
        s.contact_duration_s.unwrap().to_bits(),
        bed_fixed.contact_duration_s.unwrap().to_bits()
    );
    let rel = |a: f64, b: f64| (a / b - 1.0).abs();
    let peak = rel(s.peak_force_n, bed.peak_force_n);
    let duration = rel(
        s.contact_duration_s.unwrap(),
        bed.contact_duration_s.unwrap(),
    );
    eprintln!("held drive vs adaptive test bed: peak {peak:.3e}, duration {duration:.3e}");
    assert!(peak <= 1e-5 && duration <= 1e-5);
    // a finer swing step for the explicit loop, the held drive at the same step
    let fine = |t: String| t.replace("swing_step_s = 5e-4", "swing_step_s = 5e-5");
    let held_fine = run(&parse(&fine(held(hold))).unwrap());
    let j_r: f64 = 1.9424e-5 * 100.0;
    for kp in [1e2_f64, 1e3, 1e4] {
        let kd = 2.0 * (kp * j_r).sqrt();
        let pd = format!(
            "[robot.drive.command]\ncommand = \"controller\"\n[robot.drive.command.profile]\nprofile = \"steady\"\nspeed = 0.0\n[robot.drive.command.gains]\nkp = {kp:.1}\nkd = {kd}\n"
        );
        let s = run(&parse(&fine(held(&pd))).unwrap());
        let dev = rel(s.peak_force_n, held_fine.peak_force_n);
        let dur = rel(
            s.contact_duration_s.unwrap(),
            held_fine.contact_duration_s.unwrap(),
        );
        eprintln!(
            "PD K_p = {kp:e}: peak {:.6} N, {dev:.3e} (duration {dur:.3e}) from the held drive",
            s.peak_force_n
        );
        assert!(dev <= 1e-6 && dur <= 1e-6, "K_p = {kp}: {dev}, {dur}");
    }
}

fn field_of(text: &str) -> String {
    match parse(text) {
        Err(RigError::InvalidScene { field, .. }) => field,
        Err(e) => format!("other error: {e}"),
        Ok(_) => "accepted".into(),
    }
}

#[test]
fn bad_drive_input_names_the_scene_field() {
    let bundled = common::scene_text("rig_driven_cj");
    let cases = [
        (
            "gear_ratio = 10.0",
            "gear_ratio = 0.0",
            "robot.drive.motor.gear_ratio",
        ),
        (
            "rotor_inertia = 1.9424e-5",
            "rotor_inertia = -1.0",
            "robot.drive.motor.rotor_inertia",
        ),
        ("kp = 50.0", "kp = -1.0", "robot.drive.command.gains.kp"),
        (
            "torque_limit = 0.2",
            "torque_limit = 0.0",
            "robot.drive.command.torque_limit",
        ),
        (
            "ramp_time = 1.5",
            "ramp_time = 0.0",
            "robot.drive.command.profile.ramp_time",
        ),
        (
            "settle = 0.2",
            "settle = -1.0",
            "robot.drive.placement.settle",
        ),
        (
            "speed = 2.6365",
            "speed = -2.6365",
            "robot.drive.command.profile.speed",
        ),
    ];
    for (from, to, field) in cases {
        assert!(bundled.contains(from));
        let text = bundled.replace(from, to);
        assert_eq!(field_of(&text), field, "{to}");
    }
    let placed = bundled.replace(
        "placement = \"after_ramp\"   # or placement = \"angle\" with angle = joint travel to the block [rad]\nsettle = 0.2",
        "placement = \"angle\"\nangle = -0.5",
    );
    assert_eq!(field_of(&placed), "robot.drive.placement.angle");
    // an unknown key is a syntax error that names it
    match parse(&bundled.replace("friction = 1e-5", "friction = 1e-5\nbacklash = 0.1")) {
        Err(RigError::SceneSyntax(m)) => assert!(m.contains("backlash"), "{m}"),
        other => panic!("{other:?}"),
    }
    // the operator may hang at the bottom only when the robot comes to it
    let text = common::scene_text("cj_light_load").replace(
        "start = { from = \"release\", release_angle_deg = 30.0 }",
        "start = { from = \"moving\", angle_deg = 0.0, angular_velocity_rad_s = 0.0 }",
    );
    assert_eq!(field_of(&text), "operator.start.angle_deg");
}

/// A torque limit too small to bring the link to the block: after 60 s of simulated time the
/// run stops with an error that says how far and how fast the drive has moved the link and
/// names the limit. With the joint torque at its limit N τ_m,max against the viscous friction
/// N² c_m ω, the link can turn no faster than the terminal speed τ_m,max / (N c_m) (the
/// friction of the hub's own inertia's approach to it): 1e-6 / (10 · 1e-5) = 0.01 rad/s.
#[test]
fn a_drive_too_weak_to_reach_the_block_says_so() {
    let scene = common::scene(
        "rig_driven_cl",
        &[("torque_limit = 0.2", "torque_limit = 1e-6")],
    );
    let sim = Simulation::new(&scene, RunOptions::default()).unwrap();
    let limit = match sim.run(&mut Keep::default()) {
        Err(RigError::NotReached { what, limit }) => {
            assert_eq!(what, "contact");
            limit
        }
        other => panic!("{other:?}"),
    };
    assert!(
        limit.contains("robot.drive.command.torque_limit = 1e-6 N·m"),
        "{limit}"
    );
    let number_after = |key: &str| -> f64 {
        let rest =
            &limit[limit.find(key).unwrap_or_else(|| panic!("{key}: {limit}")) + key.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let (travel, to_block) = (number_after("moved the link "), number_after(" of the "));
    let speed = number_after("turns it at ");
    eprintln!("{limit}");
    assert!(travel > 0.0 && travel < to_block, "{travel} of {to_block}");
    assert!(speed > 0.0 && speed <= 0.01, "{speed} rad/s");
}

/// The time at the torque limit in the summary is the time of the steps whose torque ends at
/// the limit (the frames a log carries), and 0 for the bundled drive, whose limit the command
/// never needs (its largest torque stays below it).
#[test]
fn the_summary_counts_the_time_at_the_torque_limit() {
    let s = run(&common::scene("rig_driven_cj", &[]));
    let d = s.drive.unwrap();
    assert!(
        d.peak_joint_torque_nm < 2.0 && d.time_at_torque_limit_s == 0.0,
        "{d:?}"
    );

    let edit = ("torque_limit = 0.2", "torque_limit = 0.004");
    let (s, keep) = run_keeping(&common::scene("rig_driven_cj", &[edit]));
    let d = s.drive.unwrap();
    let limit = 0.004 * 10.0;
    let mut at_limit = 0.0;
    let mut t_before = 0.0;
    for (t, _, f) in &keep.0 {
        if f.joint_torque_nm.abs() >= limit * (1.0 - 1e-12) {
            at_limit += t - t_before;
        }
        t_before = *t;
    }
    eprintln!(
        "at the limit for {} s (frames: {at_limit} s)",
        d.time_at_torque_limit_s
    );
    assert!(d.time_at_torque_limit_s > 0.1, "{d:?}");
    assert!(
        (d.time_at_torque_limit_s - at_limit).abs() <= 1e-9 * s.duration_s,
        "{at_limit}"
    );
}
