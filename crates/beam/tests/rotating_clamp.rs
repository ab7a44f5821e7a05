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

/// The generalized-α step with a prescribed root ([`GeneralizedAlpha::step_with_root`], what a
/// driven link in a larger simulation steps with) against the standalone rotating-clamp runner
/// (its own Newton loop over the same scheme) on a flexible beam spun up through large angles:
/// the hub-frame tip deflection and the hub torque agree to 1e-9 of their largest values.
#[test]
fn the_prescribed_root_step_matches_the_rotating_clamp_runner() {
    use flexrig_beam::{GeneralizedAlpha, NodalLoads, State, Workspace, root_reaction};
    let (l, rho_a, ei) = (1.0, 2.0, 50.0);
    let section = Section::from_stiffness(1e6, ei, rho_a).unwrap();
    let model = BeamModel::new(BeamSpec::cantilever(
        l,
        section,
        8,
        Kinematics::Corotational,
    ))
    .unwrap();
    let h = 1e-3;
    let options = RotatingClampOptions {
        max_step: h,
        rho_inf: 0.9,
        newton_tolerance: 1e-12,
        max_iterations: 30,
    };
    let reference = run_rotating_clamp(&model, &hub, 1.5, 0.05, &options).unwrap();
    let integrator = GeneralizedAlpha::new(0.9)
        .unwrap()
        .with_newton(30, 1e-12)
        .unwrap();
    let loads = NodalLoads::zeros(&model);
    let mut state = State::in_rigid_rotation(&model, hub(0.0), 0.0, &loads).unwrap();
    let mut ws = Workspace::new(&model);
    let (d_max, m_max) = reference.iter().fold((0.0f64, 0.0f64), |(d, m), s| {
        (
            d.max(s.tip_transverse_m.abs()),
            m.max(s.hub_torque_nm.abs()),
        )
    });
    assert!(d_max > 1e-3, "the beam bends: {d_max}");
    let tip = model.tip_node();
    for (k, s) in reference.iter().enumerate() {
        if k > 0 {
            for _ in 0..50 {
                integrator
                    .step_with_root(&model, &mut state, &mut ws, h, &loads, None, &hub)
                    .unwrap();
            }
        }
        let (u, v, _) = state.node(tip);
        let th = state.node(0).2;
        assert_eq!(th, hub(state.t)[0]);
        let (sin, cos) = th.sin_cos();
        let d = -sin * (l + u) + cos * v;
        let m = root_reaction(&model, &state, &loads)[2];
        assert!(
            (d - s.tip_transverse_m).abs() < 1e-9 * d_max,
            "t {}: {d} vs {}",
            s.t,
            s.tip_transverse_m
        );
        assert!(
            (m - s.hub_torque_nm).abs() < 1e-9 * m_max,
            "t {}: {m} vs {}",
            s.t,
            s.hub_torque_nm
        );
    }
}
