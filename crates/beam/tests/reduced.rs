//! The modal-reduced beam against the full linear finite-element model it is built from.

mod common;

use common::assert_rel;
use flexrig_beam::canonical::{self, CANTILEVER_BETA_L, beam_omega};
use flexrig_beam::*;

/// Full linear FE and reduced model stepped side by side under the same load history; returns
/// the largest |q_reduced − q_full| over the tip DOFs and the largest |q_full| of tip v.
fn side_by_side(
    model: &BeamModel,
    reduced: &ReducedModel,
    rho_inf: f64,
    steps: &[(f64, [f64; 3])],
) -> (f64, f64) {
    let tip = model.tip_node();
    let mut loads = NodalLoads::zeros(model);
    let mut full = State::at_rest(model, &loads).unwrap();
    let mut ws = Workspace::new(model);
    let mut red = ReducedState::at_rest(reduced, &loads).unwrap();
    let ga = GeneralizedAlpha::new(rho_inf).unwrap();
    let (mut diff, mut scale) = (0.0f64, 0.0f64);
    for (h, [fx, fy, m]) in steps {
        loads.set_force(tip, *fx, *fy).unwrap();
        loads.set_moment(tip, *m).unwrap();
        ga.step(model, &mut full, &mut ws, *h, &loads).unwrap();
        ga.step_reduced(reduced, &mut red, *h, &loads).unwrap();
        for d in 3 * tip..3 * tip + 3 {
            diff = diff.max((reduced.dof(&red, d).0 - full.q[d]).abs());
        }
        scale = scale.max(full.q[3 * tip + 1].abs());
    }
    (diff, scale)
}

/// A varied load history with a changing step (h and h/2 alternating in blocks).
fn varied_history(steps: usize) -> Vec<(f64, [f64; 3])> {
    (0..steps)
        .map(|k| {
            let t = k as f64 * 0.01;
            let h = if (k / 25) % 2 == 0 { 0.01 } else { 0.005 };
            (h, [0.3 * (3.0 * t).sin(), (7.0 * t).cos(), 0.2 * t.sin()])
        })
        .collect()
}

/// A half-sine tip force pulse of duration `duration` [s] (like a contact), stepped by `h` for
/// `steps` steps.
fn pulse(h: f64, steps: usize, duration: f64) -> Vec<(f64, [f64; 3])> {
    (1..=steps)
        .map(|k| {
            let t = k as f64 * h;
            let f = if t < duration {
                (std::f64::consts::PI * t / duration).sin()
            } else {
                0.0
            };
            (h, [0.0, f, 0.0])
        })
        .collect()
}

#[test]
fn with_every_mode_kept_the_reduced_model_is_the_full_linear_model() {
    let model = canonical::unit_cantilever(8, Kinematics::Linear).unwrap();
    let all = model.n_free();
    let tip = model.tip_node();
    // Correction shapes lie in the span of all modes: they must be dropped, not duplicated.
    let reduced = ReducedModel::new(&model, all, &[3 * tip, 3 * tip + 1]).unwrap();
    assert_eq!(reduced.n_coordinates(), all);
    for rho in [1.0, 0.6] {
        let (diff, scale) = side_by_side(&model, &reduced, rho, &varied_history(400));
        // Round-off of the dense eigen-decomposition: ω²_max/ω²_min ≈ 1e9 here (stiff axial
        // modes); measured 7e-10 relative.
        assert!(
            diff <= 1e-8 * scale,
            "ρ∞ = {rho}: reduced vs full {diff:.3e} (scale {scale:.3e})"
        );
    }
}

#[test]
fn kept_modes_are_exact_and_ascending() {
    let model = canonical::unit_cantilever_with_tip_mass(16, 0.5).unwrap();
    let tip = model.tip_node();
    let reduced = ReducedModel::new(&model, 3, &[3 * tip, 3 * tip + 1, 3 * tip + 2]).unwrap();
    let modes = modal_analysis(&model, 3, ModalDirection::All).unwrap();
    assert_eq!(reduced.n_coordinates(), 6);
    for i in 0..3 {
        assert_rel("kept ω", reduced.omegas()[i], modes.omegas[i], 1e-10);
    }
    assert!(reduced.omegas().windows(2).all(|w| w[0] <= w[1]));
}

#[test]
fn correction_shapes_give_the_exact_static_tip_response() {
    // q = Σ φᵢ φᵢᵀ F / ωᵢ² against PL³/3EI, PL²/2EI and ML²/2EI, ML/EI (Euler–Bernoulli).
    let model = canonical::unit_cantilever(16, Kinematics::Linear).unwrap();
    let tip = model.tip_node();
    let (p, m) = (0.7, -0.3);
    for modes in [1, 2] {
        let reduced = ReducedModel::new(&model, modes, &[3 * tip + 1, 3 * tip + 2]).unwrap();
        let static_q = |dof: usize| -> f64 {
            (0..reduced.n_coordinates())
                .map(|i| {
                    let s = reduced.shape(i);
                    s[dof] * (s[3 * tip + 1] * p + s[3 * tip + 2] * m) / reduced.omegas()[i].powi(2)
                })
                .sum()
        };
        assert_rel("tip v", static_q(3 * tip + 1), p / 3.0 + m / 2.0, 1e-10);
        assert_rel("tip θ", static_q(3 * tip + 2), p / 2.0 + m, 1e-10);
    }
}

#[test]
fn kept_modes_match_the_euler_bernoulli_frequencies() {
    let model = canonical::unit_cantilever(32, Kinematics::Linear).unwrap();
    let reduced = ReducedModel::new(&model, 2, &[]).unwrap();
    for (i, beta_l) in CANTILEVER_BETA_L.iter().take(2).enumerate() {
        assert_rel(
            "ω",
            reduced.omegas()[i],
            beam_omega(*beta_l, 1.0, 1.0, 1.0),
            1e-6,
        );
    }
}

#[test]
fn truncation_error_falls_with_modes_and_the_correction_shapes_cut_it() {
    // A contact-like half-sine pulse of 0.1 s (ω₃ of the unit cantilever ≈ 62 rad/s: the higher
    // modes respond quasi-statically), followed for 0.4 s.
    let model = canonical::unit_cantilever_with_tip_mass(16, 0.2).unwrap();
    let tip = model.tip_node();
    let history = pulse(1e-3, 500, 0.1);
    let error = |modes: usize, corrected: bool| {
        let dofs: &[usize] = if corrected { &[3 * tip + 1] } else { &[] };
        let reduced = ReducedModel::new(&model, modes, dofs).unwrap();
        let (diff, scale) = side_by_side(&model, &reduced, 1.0, &history);
        diff / scale
    };
    let plain: Vec<f64> = [2, 4, 8].iter().map(|&k| error(k, false)).collect();
    let corrected: Vec<f64> = [2, 4, 8].iter().map(|&k| error(k, true)).collect();
    // Measured (relative to the largest tip deflection), 2, 4, 8 modes: plain 1.2e-1, 1.2e-2,
    // 1.3e-3; corrected 1.6e-1, 3.9e-3, 8.6e-5. (Two modes miss the third, ω₃ T = 6.2, which the
    // pulse drives dynamically: no correction shape can stand in for a resonant mode.)
    for w in corrected.windows(2) {
        assert!(
            w[1] < 0.2 * w[0],
            "corrected errors do not fall: {corrected:?}"
        );
    }
    for (c, p) in corrected.iter().zip(&plain).skip(1) {
        assert!(
            *c < p / 3.0,
            "correction does not help: {corrected:?} vs {plain:?}"
        );
    }
    assert!(corrected[2] < 2e-4, "{corrected:?}");
}

#[test]
fn reduced_free_vibration_conserves_energy_at_rho_one() {
    // (ρ∞ < 1 is covered by the step-by-step equality with the full model, whose decay is tested
    // in dynamics.rs.)
    let model = canonical::unit_cantilever(16, Kinematics::Linear).unwrap();
    let tip = model.tip_node();
    let reduced = ReducedModel::new(&model, 4, &[3 * tip + 1]).unwrap();
    {
        let ga = GeneralizedAlpha::new(1.0).unwrap();
        let mut loads = NodalLoads::zeros(&model);
        let mut s = ReducedState::at_rest(&reduced, &loads).unwrap();
        loads.set_force(tip, 0.0, 5.0).unwrap();
        for _ in 0..20 {
            ga.step_reduced(&reduced, &mut s, 1e-2, &loads).unwrap();
        }
        loads.clear();
        ga.step_reduced(&reduced, &mut s, 1e-2, &loads).unwrap();
        let (t0, u0) = reduced.energy(&s);
        let e0 = t0 + u0;
        for _ in 0..10_000 {
            ga.step_reduced(&reduced, &mut s, 1e-2, &loads).unwrap();
            let (t, u) = reduced.energy(&s);
            assert!(((t + u) / e0 - 1.0).abs() < 1e-11, "{} vs {e0}", t + u);
        }
    }
}

#[test]
fn reduced_rayleigh_damping_decays_like_the_full_model() {
    let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 16, Kinematics::Linear);
    spec.damping = Rayleigh {
        alpha_mass: 0.3,
        beta_stiffness: 1e-3,
    };
    let model = BeamModel::new(spec).unwrap();
    let reduced = ReducedModel::new(&model, 24, &[3 * model.tip_node() + 1]).unwrap();
    let history: Vec<_> = (0..300)
        .map(|k| (2e-3, [0.0, if k < 50 { 1.0 } else { 0.0 }, 0.0]))
        .collect();
    let (diff, scale) = side_by_side(&model, &reduced, 0.9, &history);
    // Truncated at 24 of 48 coordinates: the remaining modes are far above 1/h.
    assert!(diff <= 1e-4 * scale, "{diff:.3e} vs {scale:.3e}");
}

#[test]
fn bad_reduction_input_names_the_field() {
    let model = canonical::unit_cantilever(4, Kinematics::Linear).unwrap();
    let err = |r: Result<ReducedModel, BeamError>| r.unwrap_err().to_string();
    assert!(err(ReducedModel::new(&model, 0, &[])).contains("modes"));
    assert!(err(ReducedModel::new(&model, 100, &[])).contains("modes"));
    assert!(err(ReducedModel::new(&model, 2, &[1])).contains("loaded DOF"));
    assert!(err(ReducedModel::new(&model, 2, &[15])).contains("loaded DOF"));
    let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 4, Kinematics::Linear);
    spec.root = RootSupport::Pinned {
        k_theta: 1.0,
        c_theta: 0.1,
    };
    let damped = BeamModel::new(spec).unwrap();
    assert!(err(ReducedModel::new(&damped, 2, &[])).contains("c_theta"));
    let reduced = ReducedModel::new(&model, 2, &[]).unwrap();
    let mut s = ReducedState::at_rest(&reduced, &NodalLoads::zeros(&model)).unwrap();
    let ga = GeneralizedAlpha::new(1.0).unwrap();
    let loads = NodalLoads::zeros(&model);
    for h in [0.0, -1.0, f64::NAN] {
        let e = ga.step_reduced(&reduced, &mut s, h, &loads).unwrap_err();
        assert!(e.to_string().contains("time step"), "{e}");
    }
    let other = canonical::unit_cantilever(5, Kinematics::Linear).unwrap();
    let e = ga
        .step_reduced(&reduced, &mut s, 1e-3, &NodalLoads::zeros(&other))
        .unwrap_err();
    assert!(e.to_string().contains("loads length"), "{e}");
}

#[test]
fn a_pinned_root_on_a_spring_reduces_too() {
    // Rigid-link-like beam on a root spring: the first mode is the spring mode ω² ≈ k/J_root.
    let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 8, Kinematics::Linear);
    spec.root = RootSupport::Pinned {
        k_theta: 2.0,
        c_theta: 0.0,
    };
    let model = BeamModel::new(spec).unwrap();
    let tip = model.tip_node();
    let reduced = ReducedModel::new(&model, 8, &[3 * tip + 1]).unwrap();
    let modes = modal_analysis(&model, 3, ModalDirection::All).unwrap();
    assert_rel("spring mode", reduced.omegas()[0], modes.omegas[0], 1e-10);
    let history = pulse(1e-3, 800, 0.1);
    let (diff, scale) = side_by_side(&model, &reduced, 1.0, &history);
    // Measured 4.1e-4 (8 modes and one correction shape of 24 DOFs).
    assert!(diff <= 1e-3 * scale, "{diff:.3e} vs {scale:.3e}");
}

#[test]
fn a_free_pinned_root_keeps_its_rigid_mode() {
    // K is singular (k_θ = 0): the correction shapes come from K + σM; the rigid mode stays ω = 0.
    let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 8, Kinematics::Linear);
    spec.root = RootSupport::Pinned {
        k_theta: 0.0,
        c_theta: 0.0,
    };
    let model = BeamModel::new(spec).unwrap();
    let tip = model.tip_node();
    let reduced = ReducedModel::new(&model, 2, &[3 * tip + 1]).unwrap();
    assert_eq!(reduced.n_coordinates(), 3);
    assert!(reduced.omegas()[0] < 1e-6, "{:?}", reduced.omegas());
    assert_rel(
        "first flexible mode (pinned–free, βL = 3.9266)",
        reduced.omegas()[1],
        beam_omega(3.926_602_312, 1.0, 1.0, 1.0),
        1e-4, // 8 elements: discretisation error 3.9e-5 (O(h⁴))
    );
}

#[test]
fn a_free_pinned_root_keeps_every_correction_whatever_the_mesh() {
    // Regression: with K singular the Cholesky of K could succeed on a round-off pivot (4 and 5
    // elements), the correction came out dominated by the rigid mode and was dropped.
    for elements in [4, 5, 8, 16] {
        let mut spec =
            BeamSpec::cantilever(1.0, canonical::unit_section(), elements, Kinematics::Linear);
        spec.root = RootSupport::Pinned {
            k_theta: 0.0,
            c_theta: 0.0,
        };
        let model = BeamModel::new(spec).unwrap();
        let tip = model.tip_node();
        let reduced = ReducedModel::new(&model, 2, &[3 * tip, 3 * tip + 1, 3 * tip + 2]).unwrap();
        assert_eq!(reduced.n_coordinates(), 5, "{elements} elements");
    }
}

#[test]
fn a_very_soft_root_spring_keeps_the_static_tip_response_exact() {
    // Regression: the correction was judged against a static shape dominated by the soft spring
    // mode and could be dropped; the elastic part of the tip deflection was then missing.
    for k_theta in [1e-6, 1e-3, 1.0, 1e6] {
        let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 16, Kinematics::Linear);
        spec.root = RootSupport::Pinned {
            k_theta,
            c_theta: 0.0,
        };
        let model = BeamModel::new(spec).unwrap();
        let tip = model.tip_node();
        // Hermite elements are exact for a tip load: v = P/k_θ · L + PL³/3EI (L = EI = P = 1).
        let full = 1.0 / k_theta + 1.0 / 3.0;
        let reduced = ReducedModel::new(&model, 2, &[3 * tip + 1]).unwrap();
        let static_tip: f64 = (0..reduced.n_coordinates())
            .map(|i| (reduced.shape(i)[3 * tip + 1] / reduced.omegas()[i]).powi(2))
            .sum();
        assert_eq!(
            reduced.n_coordinates(),
            3,
            "k_θ = {k_theta}: correction dropped"
        );
        // ω₁² of a soft spring mode (≈ 3 k_θ here) carries an absolute error ≈ 1e-12 from the
        // shifted eigenproblem (σ = 1 next to axial ω² ≈ 1e10), which 1/ω₁² amplifies: measured
        // total errors 7.3e-7 (k_θ = 1e-6), 2.2e-10 (1e-3), 9e-12 (1), 2e-12 (1e6).
        let omega1_sq = reduced.omegas()[0].powi(2);
        assert_rel(
            &format!("k_θ = {k_theta}: tip deflection"),
            static_tip,
            full,
            1e-10 + 5e-12 / omega1_sq,
        );
    }
}

#[test]
fn stiffness_damping_on_a_root_spring_is_refused_and_a_foreign_state_is_an_error() {
    let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 8, Kinematics::Linear);
    spec.root = RootSupport::Pinned {
        k_theta: 2.0,
        c_theta: 0.0,
    };
    spec.damping = Rayleigh {
        alpha_mass: 0.0,
        beta_stiffness: 1e-3,
    };
    let model = BeamModel::new(spec).unwrap();
    let e = ReducedModel::new(&model, 2, &[]).unwrap_err().to_string();
    assert!(e.contains("beta_stiffness"), "{e}");
    let clamped = canonical::unit_cantilever(8, Kinematics::Linear).unwrap();
    let two = ReducedModel::new(&clamped, 2, &[]).unwrap();
    let three = ReducedModel::new(&clamped, 3, &[]).unwrap();
    let loads = NodalLoads::zeros(&clamped);
    let mut s = ReducedState::at_rest(&two, &loads).unwrap();
    let e = GeneralizedAlpha::new(1.0)
        .unwrap()
        .step_reduced(&three, &mut s, 1e-3, &loads)
        .unwrap_err()
        .to_string();
    assert!(e.contains("reduced state length"), "{e}");
}
