//! The drive's commanded motions against their own definitions: the speed is the derivative of
//! the angle and the acceleration that of the speed (central differences), the ramps reach
//! their speed with the angle their integral gives, the spin-up profile is Kane, Ryan &
//! Banerjee's formula, and the specs survive a serde round trip.

use flexrig_impact::drive::{Drive, DriveCommand, Motor, Profile, TorqueProfile, spin_up};

fn check_derivatives(p: &Profile, t_end: f64) {
    let h = 1e-5 * t_end;
    for k in 1..200 {
        let t = t_end * k as f64 / 200.0;
        let (a, w, al) = p.at(t);
        let (a1, w1, _) = p.at(t + h);
        let (a0, w0, _) = p.at(t - h);
        let dw = (a1 - a0) / (2.0 * h);
        let dal = (w1 - w0) / (2.0 * h);
        let scale = p.final_speed().abs();
        // the trapezoid's corner has a jump in α: skip the points next to it
        if matches!(p, Profile::Trapezoid { .. }) && (t - p.ramp_end()).abs() <= 2.0 * h {
            continue;
        }
        assert!(
            (dw - w).abs() < 1e-6 * scale,
            "{p:?} t {t}: ω {w} vs dφ/dt {dw}"
        );
        assert!(
            (dal - al).abs() < 1e-5 * scale / p.ramp_end().max(1e-3),
            "{p:?} t {t}: α {al} vs dω/dt {dal}"
        );
        assert!(a.is_finite());
    }
}

#[test]
fn every_profile_is_consistent_in_angle_speed_and_acceleration() {
    for p in [
        Profile::Steady { speed: 2.0 },
        Profile::SmoothRamp {
            speed: 2.0,
            ramp_time: 0.5,
        },
        Profile::Trapezoid {
            speed: -1.5,
            acceleration: 7.5,
        },
        Profile::SpinUp {
            speed: 6.0,
            time: 15.0,
        },
    ] {
        check_derivatives(&p, 2.5 * p.ramp_end().max(1.0));
        // past the ramp: constant speed, φ = ω (t − T/2) for the symmetric ramps
        let t = 3.0 * p.ramp_end() + 1.0;
        let (phi, w, al) = p.at(t);
        assert_eq!((w, al), (p.final_speed(), 0.0));
        let expected = p.final_speed() * (t - 0.5 * p.ramp_end());
        assert!(
            (phi - expected).abs() < 1e-12 * expected.abs().max(1.0),
            "{p:?}"
        );
    }
}

#[test]
fn the_spin_up_profile_is_kane_ryan_and_banerjees() {
    // θ = (ω_s/T_s)[t²/2 + (T_s/2π)²(cos(2πt/T_s) − 1)], written out here
    let (ws, ts) = (6.0, 15.0);
    for k in 0..=40 {
        let t = 20.0 * k as f64 / 40.0;
        let theta = if t < ts {
            ws / ts
                * (t * t / 2.0
                    + (ts / (2.0 * std::f64::consts::PI)).powi(2)
                        * ((2.0 * std::f64::consts::PI * t / ts).cos() - 1.0))
        } else {
            ws * (t - ts / 2.0)
        };
        assert!((spin_up(ws, ts, t).0 - theta).abs() < 1e-12 * theta.abs().max(1.0));
    }
}

#[test]
fn torque_tables_interpolate_and_specs_round_trip() {
    let table = TorqueProfile::Table {
        times: vec![0.0, 1.0, 3.0],
        torques: vec![1.0, 3.0, -1.0],
    };
    assert_eq!(table.at(-1.0), 1.0);
    assert_eq!(table.at(0.5), 2.0);
    assert_eq!(table.at(2.0), 1.0);
    assert_eq!(table.at(9.0), -1.0);
    let bad = TorqueProfile::Table {
        times: vec![0.0, 0.0],
        torques: vec![1.0, 2.0],
    };
    assert!(
        bad.validate()
            .unwrap_err()
            .to_string()
            .contains("drive.command.torque.times[1]")
    );
    let drive = Drive::new(
        Motor::new(1e-4, 50.0, 1e-5).unwrap(),
        DriveCommand::OpenLoop {
            torque: table,
            initial_speed: 0.5,
        },
    )
    .unwrap();
    let text = serde_json::to_string(&drive).unwrap();
    let back: Drive = serde_json::from_str(&text).unwrap();
    assert_eq!(back, drive);
}
