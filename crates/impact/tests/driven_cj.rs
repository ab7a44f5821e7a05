//! The driven CJ strike against an independent solution of the same equations (a fixed-step RK4
//! written here from the equations of motion in joint angles, with its onset, peaks and
//! separation bisected on single RK4 steps), the held-joint and free-hub limits against the
//! free-mass impact ([`flexrig_impact::cj::run_cj`]), the energy balance, and bad input.

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::cj::run_cj;
use flexrig_impact::drive::{
    Drive, DriveCommand, Gains, HeadSupport, Motor, Person, Placement, Profile, TorqueProfile,
};
use flexrig_impact::driven_cj::{CjSettings, run_driven_cj};
use flexrig_impact::{DriveNote, DrivenStrike, Joint, LinkParams};

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

// ---------------------------------------------------------------------------------------------
// The independent solution: joint angles φ_m (motor, after the gear), φ_l (link), head x_h.
//   J_m N² φ̈_m = τ_j − c_m N² φ̇_m − k_θ (φ_m − φ_l)
//   J_l φ̈_l   = k_θ (φ_m − φ_l) − L f,      J_l = (m_e + m_r/3) L², k_θ = k_δ L²
//   m_h ẍ_h   = f − k_n (x_h − L φ_c) − c_n ẋ_h
//   f = k_c ⟨L φ_l − x_h⟩ⁿ
// τ_j = sat(K_p (φ_c − φ_m) + K_d (ω_c − φ̇_m) + K_i ∫(φ_c − φ_m) dt), or N τ_m(t), or (prescribed
// φ_m) not integrated.
// ---------------------------------------------------------------------------------------------

#[derive(Clone, Copy)]
enum Ref {
    Trajectory(Profile),
    Pd {
        profile: Profile,
        kp: f64,
        kd: f64,
        ki: f64,
        limit: f64,
    },
    Torque(f64, f64), // τ_m, pulse duration
}

struct Rig {
    j_m: f64, // J_m N²
    c_m: f64, // c_m N²
    n: f64,
    j_l: f64,
    k_theta: f64,
    l: f64,
    m_h: Option<f64>,
    k_n: f64,
    c_n: f64,
    x_c: f64,
    kc: f64,
    nc: f64,
    drive: Ref,
    /// The drive's branch: the current step's midpoint.
    mid: std::cell::Cell<f64>,
}

type S = [f64; 7]; // φ_m, ω_m, φ_l, ω_l, x_h, v_h, ∫e

impl Rig {
    fn motor(&self, t: f64, s: &S) -> (f64, f64) {
        match self.drive {
            Ref::Trajectory(p) => {
                let (a, b, _) = p.at_in(t, self.mid.get());
                (a, b)
            }
            _ => (s[0], s[1]),
        }
    }
    fn force(&self, s: &S) -> f64 {
        let d = self.l * s[2] - s[4];
        if d > 0.0 {
            self.kc * d.powf(self.nc)
        } else {
            0.0
        }
    }
    fn rhs(&self, t: f64, s: &S) -> S {
        let f = self.force(s);
        let (pm, wm) = self.motor(t, s);
        let spring = self.k_theta * (pm - s[2]);
        let (tau, z) = match self.drive {
            Ref::Trajectory(_) => (0.0, 0.0),
            Ref::Pd {
                profile,
                kp,
                kd,
                ki,
                limit,
            } => {
                let (pc, wc, _) = profile.at_in(t, self.mid.get());
                let raw = kp * (pc - s[0]) + kd * (wc - s[1]) + ki * s[6];
                (raw.clamp(-limit, limit), pc - s[0])
            }
            Ref::Torque(tm, dur) => (
                if self.mid.get() < dur {
                    self.n * tm
                } else {
                    0.0
                },
                0.0,
            ),
        };
        let acc_m = match self.drive {
            Ref::Trajectory(_) => 0.0,
            _ => (tau - self.c_m * wm - spring) / self.j_m,
        };
        let acc_h = match self.m_h {
            Some(m) => (f - self.k_n * (s[4] - self.x_c) - self.c_n * s[5]) / m,
            None => 0.0,
        };
        [
            s[1],
            acc_m,
            s[3],
            (spring - self.l * f) / self.j_l,
            s[5],
            acc_h,
            z,
        ]
    }
    fn rk4(&self, t: f64, s: &S, h: f64) -> S {
        self.mid.set(t + 0.5 * h);
        let add = |a: &S, k: &S, c: f64| -> S { std::array::from_fn(|i| a[i] + c * k[i]) };
        let k1 = self.rhs(t, s);
        let k2 = self.rhs(t + 0.5 * h, &add(s, &k1, 0.5 * h));
        let k3 = self.rhs(t + 0.5 * h, &add(s, &k2, 0.5 * h));
        let k4 = self.rhs(t + h, &add(s, &k3, h));
        std::array::from_fn(|i| s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]))
    }
    fn gap(&self, s: &S) -> f64 {
        self.l * s[2] - s[4]
    }
    fn rate(&self, s: &S) -> f64 {
        self.l * s[3] - s[5]
    }
    /// The sub-step s ∈ (0, h] from (t, y) at which g(state) crosses 0 (bisection).
    fn bisect(&self, t: f64, y: &S, h: f64, g: impl Fn(&S) -> f64) -> f64 {
        let (mut a, mut b) = (0.0, h);
        let ga = g(y);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if m == a || m == b {
                break;
            }
            if (g(&self.rk4(t, y, m)) > 0.0) == (ga > 0.0) {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    }

    /// (onset, peak force, time of peak, separation).
    fn solve(&self, y0: S, h_approach: f64, h_contact: f64) -> (f64, f64, f64, f64) {
        let (mut t, mut y) = (0.0, y0);
        // approach (t = k h exactly, so that the drive's corners fall on steps)
        let mut k = 0u64;
        loop {
            let next = self.rk4(t, &y, h_approach);
            if self.gap(&next) >= 0.0 {
                let s = self.bisect(t, &y, h_approach, |z| self.gap(z));
                y = self.rk4(t, &y, s);
                t += s;
                break;
            }
            y = next;
            k += 1;
            t = k as f64 * h_approach;
        }
        let onset = t;
        let mut peak = (0.0_f64, t);
        loop {
            let next = self.rk4(t, &y, h_contact);
            if self.rate(&y) > 0.0 && self.rate(&next) <= 0.0 {
                let s = self.bisect(t, &y, h_contact, |z| self.rate(z));
                let f = self.force(&self.rk4(t, &y, s));
                if f > peak.0 {
                    peak = (f, t + s);
                }
            }
            if self.gap(&next) <= 0.0 {
                let s = self.bisect(t, &y, h_contact, |z| self.gap(z));
                return (onset, peak.0, peak.1, t + s);
            }
            y = next;
            t += h_contact;
        }
    }
}

fn rig_for(strike: &DrivenStrike) -> (Rig, S) {
    let link = strike.link;
    let l = link.length;
    let motor = strike.drive.motor();
    let nn = motor.gear_ratio;
    let drive = match strike.drive.command() {
        DriveCommand::Trajectory { profile } => Ref::Trajectory(*profile),
        DriveCommand::Controller {
            profile,
            gains,
            torque_limit,
        } => Ref::Pd {
            profile: *profile,
            kp: gains.kp,
            kd: gains.kd,
            ki: gains.ki,
            limit: torque_limit.map_or(f64::INFINITY, |x| x * nn),
        },
        DriveCommand::OpenLoop { torque, .. } => match torque {
            TorqueProfile::Pulse { torque, duration } => Ref::Torque(*torque, *duration),
            TorqueProfile::Constant { torque } => Ref::Torque(*torque, f64::INFINITY),
            _ => unreachable!(),
        },
    };
    let phi_c = strike.placement.angle(&strike.drive).unwrap();
    let (m_h, k_n, c_n) = match strike.person.support {
        HeadSupport::Free => (Some(strike.person.m_h), 0.0, 0.0),
        HeadSupport::Neck { stiffness, damping } => (Some(strike.person.m_h), stiffness, damping),
        HeadSupport::Wall => (None, 0.0, 0.0),
    };
    let rig = Rig {
        j_m: motor.rotor_inertia * nn * nn,
        c_m: motor.friction * nn * nn,
        n: nn,
        j_l: (link.m_e + link.m_r / 3.0) * l * l,
        k_theta: link.k_delta * l * l,
        l,
        m_h,
        k_n,
        c_n,
        x_c: l * phi_c,
        kc: strike.person.contact.k(),
        nc: strike.person.contact.n(),
        drive,
        mid: std::cell::Cell::new(0.0),
    };
    let y0 = [0.0, 0.0, 0.0, 0.0, l * phi_c, 0.0, 0.0];
    (rig, y0)
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn check_against_rk4(strike: &DrivenStrike, h_approach: f64, h_contact: f64) {
    let out = run_driven_cj(strike, &CjSettings::DEFAULT).unwrap();
    let (rig, y0) = rig_for(strike);
    let (onset, peak, t_peak, t_sep) = rig.solve(y0, h_approach, h_contact);
    let c = out.contact;
    let d = c.duration_s;
    let errors = [
        rel(c.peak_force_n, peak),
        (c.time_of_peak_s - c.onset_s - (t_peak - onset)).abs() / d,
        rel(d, t_sep - onset),
        (c.onset_s - onset).abs() / d,
    ];
    eprintln!(
        "peak {:.9} N (rk4 {peak:.9}), duration {d:.6e} s, onset {:.9} s, pre-deflection \
         {:.3e} m, errors {errors:?}",
        c.peak_force_n, c.onset_s, out.pre_impact_deflection_m
    );
    for e in errors {
        assert!(e <= 1e-6, "{errors:?}");
    }
}

#[test]
fn a_pd_controlled_cj_swinging_into_a_free_head_matches_rk4() {
    // the Fig. 6 soft link with a light payload, n = 2; the drive ramps to 2 rad/s in 0.5 s
    let strike = DrivenStrike {
        link: link(2e2, 0.1),
        drive: Drive::controller(
            Motor::new(1e-4, 50.0, 0.0).unwrap(),
            Profile::SmoothRamp {
                speed: 2.0,
                ramp_time: 0.5,
            },
            Gains {
                kp: 500.0,
                kd: 40.0,
                ki: 0.0,
            },
            None,
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::AfterRamp { settle: 0.3 },
        horizon_s: 5.0,
    };
    check_against_rk4(&strike, 2e-5, 2e-8);
}

#[test]
fn a_prescribed_trapezoid_into_a_head_on_a_neck_matches_rk4() {
    // stiffer link (k_δ = 1e4), n = 1.5, neck spring and damper
    let strike = DrivenStrike {
        link: link(1e4, 1.0),
        drive: Drive::trajectory(
            Motor::new(2e-4, 100.0, 1e-4).unwrap(),
            Profile::Trapezoid {
                speed: 1.5,
                acceleration: 7.5,
            },
        )
        .unwrap(),
        person: person(
            4.0,
            HeadSupport::Neck {
                stiffness: 2e4,
                damping: 50.0,
            },
            1.5,
        ),
        placement: Placement::Angle { angle: 0.4 },
        horizon_s: 5.0,
    };
    // the trapezoid's corner (0.2 s) falls on a step of 1e-5
    check_against_rk4(&strike, 1e-5, 2e-8);
}

#[test]
fn a_velocity_pi_loop_at_its_torque_limit_against_a_wall_matches_rk4() {
    let strike = DrivenStrike {
        link: link(2e3, 0.5),
        drive: Drive::controller(
            Motor::new(1e-4, 80.0, 2e-4).unwrap(),
            Profile::SmoothRamp {
                speed: 1.0,
                ramp_time: 0.2,
            },
            Gains::velocity_pi(30.0, 300.0),
            Some(0.2),
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Wall, 2.0),
        placement: Placement::Angle { angle: 0.35 },
        horizon_s: 5.0,
    };
    let out = run_driven_cj(&strike, &CjSettings::DEFAULT).unwrap();
    assert!(
        out.notes
            .iter()
            .any(|n| matches!(n, DriveNote::TorqueLimitReached { .. })),
        "{:?}",
        out.notes
    );
    check_against_rk4(&strike, 1e-5, 2e-8);
}

#[test]
fn an_open_loop_torque_pulse_matches_rk4() {
    let strike = DrivenStrike {
        link: link(5e2, 0.2),
        drive: Drive::new(
            Motor::new(3e-4, 60.0, 0.0).unwrap(),
            DriveCommand::OpenLoop {
                torque: TorqueProfile::Pulse {
                    torque: 0.05,
                    duration: 0.3,
                },
                initial_speed: 0.0,
            },
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::Angle { angle: 0.6 },
        horizon_s: 5.0,
    };
    check_against_rk4(&strike, 1e-5, 2e-8);
}

// ---------------------------------------------------------------------------------------------
// Limits: a prescribed constant speed is the held joint; a torque-free rotor the free hub.
// ---------------------------------------------------------------------------------------------

const CASES: [(f64, f64, f64, f64); 6] = [
    (4.0, 1e8, 0.1, 1.0),
    (4.0, 1e8, 0.1, 2.0),
    (1000.0, 1e8, 0.1, 1.0),
    (1000.0, 1e8, 10.0, 2.0),
    (4.0, 2e2, 0.1, 1.0),
    (1000.0, 2e2, 10.0, 2.0),
];

fn steady_strike(m_h: f64, k_delta: f64, m_e: f64, n: f64, drive: Drive) -> DrivenStrike {
    DrivenStrike {
        link: link(k_delta, m_e),
        drive,
        person: person(m_h, HeadSupport::Free, n),
        placement: Placement::Angle { angle: 0.0 },
        horizon_s: 1.0,
    }
}

fn compare(driven: &flexrig_impact::DrivenOutcome, free: &flexrig_impact::ImpactOutcome) -> f64 {
    let d = free.first.duration_s;
    [
        rel(driven.contact.peak_force_n, free.first.peak_force_n),
        (driven.contact.time_of_peak_s - free.first.time_of_peak_s).abs() / d,
        rel(driven.contact.duration_s, d),
    ]
    .into_iter()
    .fold(0.0, f64::max)
}

#[test]
fn a_prescribed_constant_speed_is_the_held_joint() {
    for (m_h, k_delta, m_e, n) in CASES {
        let drive = Drive::trajectory(
            Motor::new(1e-3, 100.0, 0.0).unwrap(),
            Profile::Steady { speed: 2.0 },
        )
        .unwrap();
        let driven = run_driven_cj(
            &steady_strike(m_h, k_delta, m_e, n, drive),
            &CjSettings::DEFAULT,
        )
        .unwrap();
        let held = run_cj(&common::setup(m_h, k_delta, m_e, n, Joint::Held), 1e-10).unwrap();
        let e = compare(&driven, &held);
        eprintln!("held {m_h} {k_delta} {m_e} {n}: {e:.2e}");
        assert!(e <= 1e-6, "{e}");
        assert!(driven.pre_impact_deflection_m.abs() < 1e-15);
    }
}

#[test]
fn a_torque_free_rotor_is_the_free_hub() {
    for (m_h, k_delta, m_e, n) in CASES {
        for j_r in [1e-6, 1.0] {
            // J_m N² = J_R with N = 10
            let drive =
                Drive::torque_free(Motor::new(j_r / 100.0, 10.0, 0.0).unwrap(), 2.0).unwrap();
            let driven = run_driven_cj(
                &steady_strike(m_h, k_delta, m_e, n, drive),
                &CjSettings::DEFAULT,
            )
            .unwrap();
            let free = run_cj(
                &common::setup(m_h, k_delta, m_e, n, Joint::FreeHub { rotor_inertia: j_r }),
                1e-10,
            )
            .unwrap();
            let e = compare(&driven, &free);
            eprintln!("free {m_h} {k_delta} {m_e} {n} J_R {j_r}: {e:.2e}");
            assert!(e <= 1e-6, "{e}");
        }
    }
}

#[test]
fn a_stiffening_position_loop_tends_to_the_held_joint() {
    // held reference: the headline case, soft enough that the loop's bandwidth matters
    let (m_h, k_delta, m_e, n) = (1000.0, 1e8, 0.1, 1.0);
    let held = run_cj(&common::setup(m_h, k_delta, m_e, n, Joint::Held), 1e-10).unwrap();
    let mut last = f64::INFINITY;
    for kp in [1e6, 1e8, 1e10] {
        let drive = Drive::controller(
            Motor::new(1e-3, 100.0, 0.0).unwrap(),
            Profile::Steady { speed: 2.0 },
            Gains {
                kp,
                kd: 2.0 * (kp * 10.0).sqrt(),
                ki: 0.0,
            },
            None,
        )
        .unwrap();
        let out = run_driven_cj(
            &steady_strike(m_h, k_delta, m_e, n, drive),
            &CjSettings::DEFAULT,
        )
        .unwrap();
        let e = rel(out.contact.peak_force_n, held.first.peak_force_n);
        eprintln!(
            "K_p {kp:e}: peak {:.3} N, {e:.2e} from held",
            out.contact.peak_force_n
        );
        assert!(
            e < last,
            "not converging to the held joint: {e} after {last}"
        );
        last = e;
    }
    assert!(last < 1e-2, "{last}");
}

// ---------------------------------------------------------------------------------------------
// Energy balance and bad input
// ---------------------------------------------------------------------------------------------

#[test]
fn the_motor_work_balances_the_energy_through_the_contact() {
    for damping in [
        DampingSpec::NONE,
        DampingSpec::HuntCrossley { restitution: 0.6 },
    ] {
        let mut p = person(
            4.0,
            HeadSupport::Neck {
                stiffness: 1e4,
                damping: 30.0,
            },
            1.8,
        );
        p.damping = damping;
        let strike = DrivenStrike {
            link: link(1e5, 0.3),
            drive: Drive::controller(
                Motor::new(2e-4, 100.0, 5e-4).unwrap(),
                Profile::SmoothRamp {
                    speed: 1.5,
                    ramp_time: 0.3,
                },
                Gains {
                    kp: 2e3,
                    kd: 100.0,
                    ki: 1e3,
                },
                Some(1.0),
            )
            .unwrap(),
            person: p,
            placement: Placement::AfterRamp { settle: 0.2 },
            horizon_s: 5.0,
        };
        let out = run_driven_cj(&strike, &CjSettings::DEFAULT).unwrap();
        let e = out.energy;
        eprintln!("{e:?}");
        assert!(e.motor_work_j.abs() > 1e-6 * e.impact_energy_j);
        assert!(
            e.residual_j.abs() <= 1e-6 * e.impact_energy_j,
            "{} of {}",
            e.residual_j,
            e.impact_energy_j
        );
    }
}

fn expect_field(result: Result<impl std::fmt::Debug, flexrig_impact::ImpactError>, field: &str) {
    let err = result.unwrap_err();
    let text = err.to_string();
    assert!(err.is_input_error(), "{text}");
    assert!(text.contains(field), "{text} should name {field}");
}

#[test]
fn bad_drive_input_is_an_error_naming_the_field() {
    expect_field(Motor::new(-1e-3, 10.0, 0.0), "drive.motor.rotor_inertia");
    expect_field(Motor::new(1e-3, 0.0, 0.0), "drive.motor.gear_ratio");
    expect_field(Motor::new(1e-3, f64::NAN, 0.0), "drive.motor.gear_ratio");
    expect_field(Motor::new(1e-3, 10.0, -1.0), "drive.motor.friction");
    let motor = Motor::new(1e-3, 10.0, 0.0).unwrap();
    expect_field(
        Drive::trajectory(
            motor,
            Profile::SmoothRamp {
                speed: 1.0,
                ramp_time: 0.0,
            },
        ),
        "drive.command.profile.ramp_time",
    );
    expect_field(
        Drive::controller(
            motor,
            Profile::Steady { speed: 1.0 },
            Gains::position_pd(-1.0, 1.0),
            None,
        ),
        "drive.command.gains.kp",
    );
    expect_field(
        Drive::controller(
            motor,
            Profile::Steady { speed: 1.0 },
            Gains::position_pd(1.0, 1.0),
            Some(0.0),
        ),
        "drive.command.torque_limit",
    );
    // the commanded trajectory never reaches a person behind the link
    let strike = DrivenStrike {
        link: link(1e3, 0.1),
        drive: Drive::trajectory(
            motor,
            Profile::SmoothRamp {
                speed: 1.0,
                ramp_time: 0.2,
            },
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::Angle { angle: -0.5 },
        horizon_s: 2.0,
    };
    expect_field(run_driven_cj(&strike, &CjSettings::DEFAULT), "placement");
    // from the TOML of a scene's [drive] table: a negative inertia names the field
    let text = r#"
        motor = { rotor_inertia = -1.0, gear_ratio = 10.0 }
        command = { command = "trajectory", profile = { profile = "steady", speed = 1.0 } }
    "#;
    let parsed: Result<Drive, _> = toml::from_str(text);
    assert!(
        parsed
            .unwrap_err()
            .to_string()
            .contains("drive.motor.rotor_inertia"),
        "the scene error names the field"
    );
    let good: Drive = toml::from_str(&text.replace("-1.0", "1e-4")).unwrap();
    assert_eq!(good.motor().gear_ratio, 10.0);
}

#[test]
fn a_torque_limit_that_cannot_hold_the_speed_is_reported_or_an_error() {
    // friction c_m N² ω = 0.01 · 100 · 1 = 1 N·m at the joint, limit 0.005 · 10 = 0.05 N·m
    let strike = |angle: f64, horizon: f64| DrivenStrike {
        link: link(1e3, 0.1),
        drive: Drive::controller(
            Motor::new(1e-3, 10.0, 0.01).unwrap(),
            Profile::SmoothRamp {
                speed: 1.0,
                ramp_time: 0.2,
            },
            Gains::velocity_pi(5.0, 50.0),
            Some(0.005),
        )
        .unwrap(),
        person: person(4.0, HeadSupport::Free, 2.0),
        placement: Placement::Angle { angle },
        horizon_s: horizon,
    };
    // near: it arrives, slower than commanded, and says so
    let out = run_driven_cj(&strike(0.01, 5.0), &CjSettings::DEFAULT).unwrap();
    assert!(
        out.notes
            .iter()
            .any(|n| matches!(n, DriveNote::TorqueLimitReached { .. }))
    );
    assert!(
        out.notes
            .iter()
            .any(|n| matches!(n, DriveNote::ArrivalOffCommand { actual_mps, commanded_mps }
                if actual_mps < commanded_mps))
    );
    assert!(out.contact.peak_force_n.is_finite() && out.contact.peak_force_n > 0.0);
    // far: it never gets there; the error says why
    let err = run_driven_cj(&strike(1.0, 3.0), &CjSettings::DEFAULT).unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("torque limit") && text.contains("horizon_s"),
        "{text}"
    );
}
