//! The rotating clamp against rigid-body mechanics: a very stiff beam follows its hub, its tip
//! stays on the hub's line and the hub takes the torque J θ̈ of a rigid rod (J = ρA L³/3); a
//! hub that is not clamped or not corotational is refused.

use flexrig_beam::rotating_clamp::{RotatingClampOptions, run_rotating_clamp};
use flexrig_beam::{BeamModel, BeamSpec, Kinematics, Section};

/// θ = (ω_s/T)[t²/2 + (T/2π)²(cos(2πt/T) − 1)], the spin-up profile, for t < T.
fn hub(t: f64) -> [f64; 3] {
    let (w_s, t_s) = (2.0, 2.0);
    let (c, w) = (w_s / t_s, 2.0 * std::f64::consts::PI / t_s);
    let (s, co) = (w * t).sin_cos();
    [
        c * (0.5 * t * t + (co - 1.0) / (w * w)),
        c * (t - s / w),
        c * (1.0 - co),
    ]
}

#[test]
fn a_stiff_beam_turns_with_its_hub_as_a_rigid_rod() {
    let (l, rho_a, ei) = (1.0, 2.0, 1e8);
    let section = Section::from_stiffness(1e12, ei, rho_a).unwrap();
    let model = BeamModel::new(BeamSpec::cantilever(
        l,
        section,
        8,
        Kinematics::Corotational,
    ))
    .unwrap();
    let options = RotatingClampOptions {
        max_step: 1e-3,
        ..RotatingClampOptions::DEFAULT
    };
    let out = run_rotating_clamp(&model, &hub, 1.5, 0.05, &options).unwrap();
    let j = rho_a * l.powi(3) / 3.0;
    let torque_max = j * 2.0 * 2.0 / 2.0;
    for s in &out {
        let [th, _, al] = hub(s.t);
        assert!((s.hub_angle - th).abs() < 1e-15);
        // static deflection under the inertia load ρA α x: 11 ρA α L⁴/(120 EI) ≈ 4e-8 m
        assert!(s.tip_transverse_m.abs() < 1e-7, "{}", s.tip_transverse_m);
        assert!(
            (s.hub_torque_nm - j * al).abs() < 1e-5 * torque_max,
            "t {}: {} vs {}",
            s.t,
            s.hub_torque_nm,
            j * al
        );
    }
    assert_eq!(out.len(), 31);
}

#[test]
fn only_a_clamped_corotational_beam_is_accepted() {
    let section = Section::from_stiffness(1e6, 1e3, 1.0).unwrap();
    let linear = BeamModel::new(BeamSpec::cantilever(1.0, section, 4, Kinematics::Linear)).unwrap();
    let e = run_rotating_clamp(&linear, &hub, 1.0, 0.1, &RotatingClampOptions::DEFAULT)
        .unwrap_err()
        .to_string();
    assert!(e.contains("kinematics"), "{e}");
    let corot = linear.with_kinematics(Kinematics::Corotational);
    let e = run_rotating_clamp(&corot, &hub, -1.0, 0.1, &RotatingClampOptions::DEFAULT)
        .unwrap_err()
        .to_string();
    assert!(e.contains("t_end"), "{e}");
}
