//! The driven CL strike (FE modes on the graded mesh, exact two-port modal integration): the
//! held and free-hub limits against the free-mass CL of the modal path, convergence in mesh and
//! tolerance, the energy balance with every dissipation, the drive's pre-bending against the
//! quasi-static cantilever, and bad input.

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::cl_modal::run_cl_modal;
use flexrig_impact::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl};
use flexrig_impact::graded::GradedMesh;
use flexrig_impact::modal_run::ModalOptions;
use flexrig_impact::{DrivenOutcome, DrivenStrike, ImpactOutcome, Joint, LinkParams};

mod common;

fn link(k_delta: f64, m_e: f64) -> LinkParams {
    LinkParams {
        m_r: 10.0,
        length: 1.0,
        k_delta,
        m_e,
    }
}

fn person(m_h: f64, support: HeadSupport, n: f64) -> Person {
    Person {
        m_h,
        support,
        contact: Hertz::new(1e8, n).unwrap(),
        damping: DampingSpec::NONE,
        speed: 0.0,
    }
}

fn all_modes() -> GradedMesh {
    GradedMesh {
        mode_cut: f64::INFINITY,
        ..GradedMesh::DEFAULT
    }
}

fn settings(tol: f64) -> ClDriveSettings {
    ClDriveSettings {
        mesh: all_modes(),
        tol,
        ..ClDriveSettings::DEFAULT
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn compare(d: &DrivenOutcome, o: &ImpactOutcome) -> f64 {
    let dur = o.first.duration_s;
    // the time of a flat peak (heavy head, n = 2) is ill-conditioned: 10× the allowance
    let e = [
        rel(d.contact.peak_force_n, o.first.peak_force_n),
        0.1 * (d.contact.time_of_peak_s - o.first.time_of_peak_s).abs() / dur,
        rel(d.contact.duration_s, dur),
    ];
    e.into_iter().fold(0.0, f64::max)
}

const CASES: [(f64, f64, f64, f64); 4] = [
    (4.0, 1e8, 0.1, 1.0),
    (1000.0, 1e8, 10.0, 2.0),
    (4.0, 2e2, 0.1, 1.0),
    (1000.0, 2e2, 10.0, 2.0),
];

fn steady(m_h: f64, k_delta: f64, m_e: f64, n: f64, drive: Drive) -> DrivenStrike {
    DrivenStrike {
        link: link(k_delta, m_e),
        drive,
        person: person(m_h, HeadSupport::Free, n),
        placement: Placement::Angle { angle: 0.0 },
        horizon_s: 1.0,
    }
}

#[test]
fn a_prescribed_constant_speed_is_the_held_cl_and_a_torque_free_rotor_the_free_hub() {
    let modal = ModalOptions {
        tol: 1e-8,
        ..ModalOptions::DEFAULT
    };
    for (m_h, k_delta, m_e, n) in CASES {
        let drive = Drive::trajectory(
            Motor::new(1e-3, 100.0, 0.0).unwrap(),
            Profile::Steady { speed: 2.0 },
        )
        .unwrap();
        let d = run_driven_cl(&steady(m_h, k_delta, m_e, n, drive), &settings(1e-8)).unwrap();
        let held = run_cl_modal(
            &common::setup(m_h, k_delta, m_e, n, Joint::Held),
            &all_modes(),
            &modal,
        )
        .unwrap();
        let e_held = compare(&d, &held);
        let j_r = 0.5;
        let drive = Drive::torque_free(Motor::new(j_r / 100.0, 10.0, 0.0).unwrap(), 2.0).unwrap();
        let d = run_driven_cl(&steady(m_h, k_delta, m_e, n, drive), &settings(1e-8)).unwrap();
        let free = run_cl_modal(
            &common::setup(m_h, k_delta, m_e, n, Joint::FreeHub { rotor_inertia: j_r }),
            &all_modes(),
            &modal,
        )
        .unwrap();
        let e_free = compare(&d, &free);
        eprintln!("{m_h} {k_delta} {m_e} {n}: held {e_held:.2e}, free hub {e_free:.2e}");
        assert!(e_held <= 1e-6 && e_free <= 1e-6, "{e_held} {e_free}");
        assert!(d.pre_impact_deflection_m.abs() < 1e-12);
    }
}

fn ramp_strike() -> DrivenStrike {
    // the Fig. 6 soft link, light payload, n = 2, a PD loop ramping to 2 rad/s in 0.5 s
    DrivenStrike {
        link: link(2e2, 0.1),
        drive: Drive::controller(
            Motor::new(1e-4, 50.0, 1e-5).unwrap(),
            Profile::SmoothRamp {
                speed: 2.0,
                ramp_time: 0.5,
            },
            Gains {
                kp: 500.0,
                kd: 40.0,
                ki: 0.0,
            },
            Some(1.0),
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::AfterRamp { settle: 0.3 },
        horizon_s: 5.0,
    }
}

#[test]
fn the_driven_cl_converges_in_mesh_and_step() {
    let strike = ramp_strike();
    let coarse = run_driven_cl(&strike, &ClDriveSettings::DEFAULT).unwrap();
    let fine_step = run_driven_cl(
        &strike,
        &ClDriveSettings {
            tol: 1e-8,
            approach_tol: 1e-7,
            ..ClDriveSettings::DEFAULT
        },
    )
    .unwrap();
    let fine_mesh = run_driven_cl(
        &strike,
        &ClDriveSettings {
            mesh: GradedMesh {
                zone_elements: 16.0,
                ratio: 1.08,
                min_elements: 96,
                ..ClDriveSettings::DEFAULT.mesh
            },
            ..ClDriveSettings::DEFAULT
        },
    )
    .unwrap();
    let pick = |o: &DrivenOutcome| {
        [
            o.contact.peak_force_n,
            o.contact.time_of_peak_s - o.contact.onset_s,
            o.contact.duration_s,
            o.pre_impact_deflection_m,
        ]
    };
    let (c, s, m) = (pick(&coarse), pick(&fine_step), pick(&fine_mesh));
    eprintln!("default {c:?}\nstep    {s:?}\nmesh    {m:?}");
    for i in 0..4 {
        let scale = if i == 1 { c[2] } else { s[i].abs() };
        // the duration of this long push (the whole soft link behind the payload) ends in a
        // slow release: its time converges in the mesh to 2.5e-5 (documented), the rest to 1e-5
        let allowed = if i == 2 { 1e-4 } else { 1e-5 };
        assert!(
            (c[i] - s[i]).abs() <= 1e-5 * scale,
            "step: {i} {} {}",
            c[i],
            s[i]
        );
        assert!(
            (c[i] - m[i]).abs() <= allowed * scale,
            "mesh: {i} {} {}",
            c[i],
            m[i]
        );
    }
    assert!(
        coarse.pre_impact_deflection_m > 0.0,
        "a link that decelerated into the contact"
    );
}

#[test]
fn the_motor_work_balances_the_energy_through_the_contact() {
    let mut strikes = Vec::new();
    // a PD loop with friction into a damped head on a neck, Hunt–Crossley contact
    let mut s = ramp_strike();
    s.link = link(1e5, 0.3);
    s.person = Person {
        damping: DampingSpec::HuntCrossley { restitution: 0.6 },
        ..person(
            4.0,
            HeadSupport::Neck {
                stiffness: 1e4,
                damping: 30.0,
            },
            1.8,
        )
    };
    strikes.push(s);
    // a prescribed trajectory still accelerating at the contact, into a wall
    strikes.push(DrivenStrike {
        link: link(1e4, 0.5),
        drive: Drive::trajectory(
            Motor::new(2e-4, 100.0, 1e-4).unwrap(),
            Profile::Trapezoid {
                speed: 1.5,
                acceleration: 3.0,
            },
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Wall, 2.0),
        placement: Placement::Angle { angle: 0.3 },
        horizon_s: 5.0,
    });
    // the bundled scenes: a PD loop at its torque limit, stiff link, free head and wall
    strikes.push(bundled_cl(HeadSupport::Free));
    strikes.push(bundled_cl(HeadSupport::Wall));
    for strike in &strikes {
        let out = run_driven_cl(strike, &ClDriveSettings::DEFAULT).unwrap();
        let e = out.energy;
        eprintln!("{e:?}");
        assert!(e.motor_work_j.abs() > 1e-4 * e.impact_energy_j);
        assert!(
            e.residual_j.abs() <= 1e-6 * e.impact_energy_j,
            "{} of {}",
            e.residual_j,
            e.impact_energy_j
        );
    }
}

#[test]
fn a_slow_ramp_bends_the_link_as_the_quasi_static_cantilever() {
    // contact at the ramp's middle, where the acceleration is largest and steady
    // (dα/dt = 0): the beam lags by the static deflection under its inertia load
    // ρA α x and the payload's m_e α L: w = −α (11 ρA L⁴/120 + m_e L⁴/3)/EI
    let (k_delta, m_e, speed, ramp) = (2e2, 0.1, 1.0, 30.0);
    let l = link(k_delta, m_e);
    let profile = Profile::SmoothRamp {
        speed,
        ramp_time: ramp,
    };
    let (angle, _, alpha) = profile.at(0.5 * ramp);
    let strike = DrivenStrike {
        link: l,
        drive: Drive::trajectory(Motor::new(1e-3, 10.0, 0.0).unwrap(), profile).unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::Angle { angle },
        horizon_s: 2.0 * ramp,
    };
    let out = run_driven_cl(&strike, &ClDriveSettings::DEFAULT).unwrap();
    let quasi = -alpha * (11.0 * l.rho_a() * 1.0 / 120.0 + m_e / 3.0) / l.ei();
    eprintln!(
        "pre-impact deflection {:.6e} m, quasi-static {quasi:.6e} m, onset {:.3} s",
        out.pre_impact_deflection_m, out.contact.onset_s
    );
    // the ramp's time scale (30 s) against the link's period (0.77 s): within 1e-3
    assert!(rel(out.pre_impact_deflection_m, quasi) < 1e-3);
}

#[test]
fn bad_input_is_an_error_naming_the_field() {
    let mut strike = ramp_strike();
    strike.placement = Placement::Angle { angle: -1.0 };
    let e = run_driven_cl(&strike, &ClDriveSettings::DEFAULT).unwrap_err();
    assert!(
        e.is_input_error() && e.to_string().contains("placement"),
        "{e}"
    );
    let e = run_driven_cl(
        &ramp_strike(),
        &ClDriveSettings {
            tol: 0.0,
            ..ClDriveSettings::DEFAULT
        },
    )
    .unwrap_err();
    assert!(e.to_string().contains("tol"), "{e}");
    // a torque limit that cannot move the link: never arrives, and says why
    let mut strike = ramp_strike();
    strike.drive = Drive::controller(
        Motor::new(1e-4, 50.0, 1e-2).unwrap(),
        Profile::SmoothRamp {
            speed: 2.0,
            ramp_time: 0.5,
        },
        Gains::velocity_pi(40.0, 500.0),
        Some(1e-3),
    )
    .unwrap();
    strike.horizon_s = 2.0;
    let e = run_driven_cl(&strike, &ClDriveSettings::DEFAULT).unwrap_err();
    let text = e.to_string();
    assert!(
        text.contains("torque limit") && text.contains("horizon_s"),
        "{text}"
    );
}

/// The bundled driven CL scenes (assets/scenes/driven_cl_{free_head,wall}.toml: the Fig. 6
/// stiff link, PD ramp to 2 rad/s, n = 2) at the default settings against a finer step and a
/// finer mesh, and their approach against the rigid link.
fn bundled_cl(support: HeadSupport) -> DrivenStrike {
    let mut s = ramp_strike();
    s.link = link(1e8, 0.1);
    s.person = person(4.0, support, 2.0);
    s
}

#[test]
fn the_bundled_driven_cl_scenes_converge_in_mesh_and_step() {
    let mut worst = 0.0f64;
    for support in [HeadSupport::Free, HeadSupport::Wall] {
        let strike = bundled_cl(support);
        let coarse = run_driven_cl(&strike, &ClDriveSettings::DEFAULT).unwrap();
        let fine_step = run_driven_cl(
            &strike,
            &ClDriveSettings {
                tol: 1e-8,
                approach_tol: 1e-7,
                ..ClDriveSettings::DEFAULT
            },
        )
        .unwrap();
        let fine_mesh = run_driven_cl(
            &strike,
            &ClDriveSettings {
                mesh: GradedMesh {
                    zone_elements: 16.0,
                    ratio: 1.08,
                    min_elements: 96,
                    ..ClDriveSettings::DEFAULT.mesh
                },
                ..ClDriveSettings::DEFAULT
            },
        )
        .unwrap();
        let pick = |o: &DrivenOutcome| {
            [
                o.contact.peak_force_n,
                o.contact.time_of_peak_s - o.contact.onset_s,
                o.contact.duration_s,
                o.pre_impact_deflection_m,
                o.approach_speed_mps,
            ]
        };
        let (c, s, m) = (pick(&coarse), pick(&fine_step), pick(&fine_mesh));
        eprintln!("{support:?}\ndefault {c:?}\nstep    {s:?}\nmesh    {m:?}");
        // the approach against the rigid link under the same loop (the stiff link's own motion,
        // its pre-bend of 6e-9 m and its ringing, is far below 1e-5 of the speed)
        let (onset, speed) = rigid_pd_arrival(&strike);
        let (e_on, e_v) = (
            (coarse.contact.onset_s - onset).abs() / onset,
            rel(coarse.approach_speed_mps, speed),
        );
        eprintln!(
            "  rigid link: onset {onset:.10e} s ({e_on:.2e}), speed {speed:.10e} m/s ({e_v:.2e})"
        );
        assert!(e_on <= 1e-5 && e_v <= 1e-5, "{e_on} {e_v}");
        for i in 0..5 {
            // times against the duration; the pre-impact deflection against the contact's
            // static deflection scale f_max/k_δ
            let scale = match i {
                1 => c[2],
                3 => c[0] / 1e8,
                _ => s[i].abs(),
            };
            let (es, em) = ((c[i] - s[i]).abs() / scale, (c[i] - m[i]).abs() / scale);
            eprintln!("  quantity {i}: step {es:.2e}, mesh {em:.2e}");
            worst = worst.max(es).max(em);
        }
    }
    assert!(
        worst <= 1e-5,
        "largest difference {worst:.2e} of the floor's 1e-5"
    );
}

#[test]
fn the_root_moment_of_a_slow_ramp_is_the_rigid_links_inertia_torque() {
    // Quasi-static: in a slow ramp the beam turns as a rigid body (its lag ∝ α̈ is negligible at
    // the ramp's middle), so the moment the hub passes to the beam's root is the rate of the
    // link's angular momentum, M = α (m_r/3 + m_e) L², independent of the FE model and of the
    // hub's balance that the trace's moment comes from. Both drives: a prescribed trajectory
    // and a stiff PD loop (its small lag does not change α to first order).
    let (k_delta, m_e, speed, ramp) = (2e2, 0.1, 1.0, 30.0);
    let l = link(k_delta, m_e);
    let profile = Profile::SmoothRamp {
        speed,
        ramp_time: ramp,
    };
    let (angle, _, alpha) = profile.at(0.5 * ramp);
    let motor = Motor::new(1e-3, 10.0, 0.0).unwrap();
    let drives = [
        Drive::trajectory(motor, profile).unwrap(),
        Drive::controller(
            motor,
            profile,
            Gains {
                kp: 1e5,
                kd: 2e3,
                ki: 0.0,
            },
            None,
        )
        .unwrap(),
    ];
    let expected = alpha * (l.m_r / 3.0 + m_e) * l.length * l.length;
    for drive in drives {
        let strike = DrivenStrike {
            link: l,
            drive,
            person: person(4.0, HeadSupport::Free, 2.0),
            placement: Placement::Angle { angle },
            horizon_s: 2.0 * ramp,
        };
        let out = run_driven_cl(
            &strike,
            &ClDriveSettings {
                trace_every: Some(1e-3),
                ..ClDriveSettings::DEFAULT
            },
        )
        .unwrap();
        let onset = out
            .trace
            .iter()
            .find(|s| s.t >= out.contact.onset_s)
            .unwrap();
        eprintln!(
            "root moment at the onset {:.9e} N·m, rigid-link inertia torque {expected:.9e} N·m: {:.2e}",
            onset.moment_nm,
            rel(onset.moment_nm, expected)
        );
        assert!(rel(onset.moment_nm, expected) < 1e-3);
    }
}

/// The rigid link (J = J_m N² + m_r L²/3 + m_e L²) under the strike's PD loop with its torque
/// limit and friction, written from the equations: J θ̈ = sat(K_p e_φ + K_d e_ω) − c θ̇, by RK4 at
/// 1.6e-6 s (converged to 1e-11), the arrival θ = φ_person interpolated cubically (Hermite) in
/// the step. Returns (onset [s], tip speed [m/s]).
fn rigid_pd_arrival(strike: &DrivenStrike) -> (f64, f64) {
    use flexrig_impact::drive::DriveCommand;
    let DriveCommand::Controller {
        profile,
        gains,
        torque_limit,
    } = strike.drive.command()
    else {
        panic!("a controller")
    };
    let motor = strike.drive.motor();
    let l = strike.link;
    let j =
        motor.reflected_inertia() + l.m_r * l.length * l.length / 3.0 + l.m_e * l.length.powi(2);
    let c = motor.reflected_friction();
    let limit = torque_limit.map_or(f64::INFINITY, |t| t * motor.gear_ratio);
    let target = strike.placement.angle(&strike.drive).unwrap();
    let acc = |t: f64, th: f64, om: f64| {
        let (p, w, _) = profile.at(t);
        let tau = (gains.kp * (p - th) + gains.kd * (w - om)).clamp(-limit, limit);
        (tau - c * om) / j
    };
    let h = 1.6e-6;
    let (mut t, mut th, mut om) = (0.0, 0.0, 0.0);
    loop {
        let k1 = (om, acc(t, th, om));
        let k2 = (
            om + 0.5 * h * k1.1,
            acc(t + 0.5 * h, th + 0.5 * h * k1.0, om + 0.5 * h * k1.1),
        );
        let k3 = (
            om + 0.5 * h * k2.1,
            acc(t + 0.5 * h, th + 0.5 * h * k2.0, om + 0.5 * h * k2.1),
        );
        let k4 = (om + h * k3.1, acc(t + h, th + h * k3.0, om + h * k3.1));
        let th1 = th + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
        let om1 = om + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        if th1 >= target {
            // the cubic Hermite through (θ, ω) at both ends, its root by bisection
            let (a0, a1) = (acc(t, th, om), acc(t + h, th1, om1));
            let pos = |s: f64| {
                let (h00, h10, h01, h11) = (
                    2.0 * s.powi(3) - 3.0 * s * s + 1.0,
                    s.powi(3) - 2.0 * s * s + s,
                    -2.0 * s.powi(3) + 3.0 * s * s,
                    s.powi(3) - s * s,
                );
                h00 * th + h10 * h * om + h01 * th1 + h11 * h * om1
            };
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if pos(mid) < target {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let s = 0.5 * (lo + hi);
            // the speed's own cubic Hermite (ω and α at both ends)
            let speed = (2.0 * s.powi(3) - 3.0 * s * s + 1.0) * om
                + (s.powi(3) - 2.0 * s * s + s) * h * a0
                + (-2.0 * s.powi(3) + 3.0 * s * s) * om1
                + (s.powi(3) - s * s) * h * a1;
            return (t + s * h, speed * l.length);
        }
        t += h;
        th = th1;
        om = om1;
    }
}

#[test]
fn a_free_rotor_on_a_fine_mesh_turns_as_the_rigid_link() {
    // an open-loop torque from rest on the stiff link: the hub's rigid mode must stay at ω = 0
    // on any mesh (taken from the whole link's pencil it was 0.38 rad/s at L/96, the arrival
    // 2.3 % late); against the rigid link θ = ½ (N τ_m / J) t²
    use flexrig_impact::drive::{DriveCommand, TorqueProfile};
    let motor = Motor::new(1e-4, 50.0, 0.0).unwrap();
    let strike = DrivenStrike {
        link: link(1e8, 0.1),
        drive: Drive::new(
            motor,
            DriveCommand::OpenLoop {
                torque: TorqueProfile::Constant { torque: 0.02 },
                initial_speed: 0.0,
            },
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::Angle { angle: 0.5 },
        horizon_s: 5.0,
    };
    let j = motor.reflected_inertia() + 10.0 / 3.0 + 0.1;
    let alpha = 0.02 * 50.0 / j;
    let onset = (2.0 * 0.5 / alpha).sqrt();
    for min_elements in [24, 96, 192] {
        let out = run_driven_cl(
            &strike,
            &ClDriveSettings {
                mesh: GradedMesh {
                    min_elements,
                    ..ClDriveSettings::DEFAULT.mesh
                },
                ..ClDriveSettings::DEFAULT
            },
        )
        .unwrap();
        let (e_on, e_v) = (
            rel(out.contact.onset_s, onset),
            rel(out.approach_speed_mps, alpha * onset),
        );
        eprintln!("L/{min_elements}: onset {e_on:.2e}, speed {e_v:.2e}");
        // the torque's step at t = 0 rings the link: its tip speed ±1e-5 of the rigid one
        assert!(e_on <= 1e-7 && e_v <= 3e-5, "{e_on} {e_v}");
    }
}
