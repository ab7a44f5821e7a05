//! The spin-up beam benchmark (Simo & Vu-Quoc's 10 m beam, the one often credited to Kane, Ryan & Banerjee 1987): the corotational FE beam on a
//! rotating clamp against the independent elastica reference (Ritz on the section angle,
//! DOP853), the reference's own convergence, and the linear model's known failure.

use flexrig_impact::spin_up::{SpinUp, spin_up_fe, spin_up_linear, spin_up_reference};

#[test]
fn the_reference_converges_in_its_modes() {
    let spec = SpinUp::simo_vu_quoc(6.0);
    let r5 = spin_up_reference(&spec, 5, 1e-10).unwrap();
    let r6 = spin_up_reference(&spec, 6, 1e-10).unwrap();
    let r7 = spin_up_reference(&spec, 7, 1e-10).unwrap();
    let (d56, d67) = (r5.difference(&r7), r6.difference(&r7));
    eprintln!(
        "max {:.9} m; 5 vs 7 modes {d56:.2e}, 6 vs 7 {d67:.2e}",
        r7.max_abs()
    );
    assert!(d56 <= 1e-5 && d67 <= 5e-7, "{d56} {d67}");
    assert!(d67 < 0.2 * d56);
}

#[test]
fn the_fe_beam_on_a_rotating_clamp_matches_the_reference() {
    for omega_s in [6.0, 4.0] {
        let spec = SpinUp::simo_vu_quoc(omega_s);
        let reference = spin_up_reference(&spec, 6, 1e-10).unwrap();
        let e16 = spin_up_fe(&spec, 16, 1e-3).unwrap().difference(&reference);
        let e32 = spin_up_fe(&spec, 32, 1e-3).unwrap().difference(&reference);
        eprintln!(
            "ω_s = {omega_s}: max {:.6} m; FE 16 elements {e16:.2e}, 32 elements {e32:.2e} \
             of the max",
            reference.max_abs()
        );
        // floor: 1 % of the largest deflection at every reported time; converging at ≈ h²
        assert!(e16 <= 1e-2 && e32 <= 1e-3, "{e16} {e32}");
        assert!(e32 < 0.4 * e16, "{e16} {e32}");
    }
}

#[test]
fn the_linear_beam_in_the_rotating_frame_diverges_at_6_rad_per_s() {
    let spec = SpinUp::simo_vu_quoc(6.0);
    let reference = spin_up_reference(&spec, 6, 1e-10).unwrap();
    let linear = spin_up_linear(&spec, 6, 1e-10).unwrap();
    let at = |s: &flexrig_impact::spin_up::SpinUpSeries, t: f64| {
        s.tip_deflection_m[(t / spec.sample_every).round() as usize]
    };
    // slow at first (θ̇ small): the two agree
    assert!((at(&linear, 1.0) - at(&reference, 1.0)).abs() < 1e-3 * reference.max_abs());
    // past θ̇ = ω₁ = 3.80 rad/s the linear beam has a negative stiffness and runs away
    let end = at(&linear, 20.0).abs();
    eprintln!(
        "linear at 20 s: {end:.3e} m; nonlinear max {:.3} m",
        reference.max_abs()
    );
    assert!(end > 1e3 * reference.max_abs());
    assert!(linear.tip_deflection_m.iter().all(|d| d.is_finite()));
}

#[test]
fn bad_spin_up_input_names_the_field() {
    let mut spec = SpinUp::simo_vu_quoc(6.0);
    spec.omega_s = f64::NAN;
    let e = spin_up_reference(&spec, 6, 1e-10).unwrap_err().to_string();
    assert!(e.contains("omega_s"), "{e}");
    let e = spin_up_reference(&SpinUp::simo_vu_quoc(6.0), 1, 1e-10)
        .unwrap_err()
        .to_string();
    assert!(e.contains("modes"), "{e}");
    let mut spec = SpinUp::simo_vu_quoc(6.0);
    spec.ei = -1.0;
    let e = spin_up_fe(&spec, 16, 1e-3).unwrap_err().to_string();
    assert!(e.contains("ei"), "{e}");
    let e = spin_up_fe(&SpinUp::simo_vu_quoc(6.0), 0, 1e-3)
        .unwrap_err()
        .to_string();
    assert!(e.contains("elements"), "{e}");
}

#[test]
fn the_fe_beam_converges_to_the_inextensible_reference_at_second_order() {
    // with EA × 1000 the FE beam is as inextensible as the reference: the 32- and 64-element
    // series extrapolated at second order (4 f₆₄ − f₃₂)/3 meet it
    let mut spec = SpinUp::simo_vu_quoc(6.0);
    let reference = spin_up_reference(&spec, 7, 1e-11).unwrap();
    spec.ea *= 1e3;
    let f32 = spin_up_fe(&spec, 32, 1e-3).unwrap();
    let f64 = spin_up_fe(&spec, 64, 1e-3).unwrap();
    let extrapolated = flexrig_impact::spin_up::SpinUpSeries {
        t: f64.t.clone(),
        tip_deflection_m: f32
            .tip_deflection_m
            .iter()
            .zip(&f64.tip_deflection_m)
            .map(|(a, b)| (4.0 * b - a) / 3.0)
            .collect(),
    };
    let (e32, e64, e) = (
        f32.difference(&reference),
        f64.difference(&reference),
        extrapolated.difference(&reference),
    );
    eprintln!("32 elements {e32:.2e}, 64 {e64:.2e}, extrapolated {e:.2e}");
    assert!(e64 < 0.35 * e32 && e < 5e-5, "{e32} {e64} {e}");
}

/// The two beams by name: Simo & Vu-Quoc's EA = 2.8e7 N, EI = 1.4e4 N·m², ρA = 1.2 kg/m over
/// 10 m, and Kane, Ryan & Banerjee's aluminium (E = 6.8952e10 Pa, ρ = 2766.67 kg/m³,
/// A = 7.2968e-5 m², I = 8.2189e-9 m⁴) over 8 m; their first clamped bending frequencies
/// 1.8751² √(EI/(ρA L⁴)) = 3.80 and 2.91 rad/s, so both spin-ups (6 and 4 rad/s) pass them.
#[test]
fn the_named_beams_have_their_published_parameters() {
    let first =
        |s: &SpinUp| 1.875_104_068_7_f64.powi(2) * (s.ei / (s.rho_a * s.length.powi(4))).sqrt();
    let simo = SpinUp::simo_vu_quoc(6.0);
    assert_eq!((simo.length, simo.ea, simo.ei), (10.0, 2.8e7, 1.4e4));
    assert!((simo.rho_a - 1.2).abs() < 1e-12);
    assert!((first(&simo) - 3.80).abs() < 5e-3, "{}", first(&simo));
    let kane = SpinUp::kane_ryan_banerjee(4.0);
    assert_eq!(kane.length, 8.0);
    assert!((kane.ei - 566.71).abs() < 0.01, "{}", kane.ei);
    assert!((kane.rho_a - 0.201_88).abs() < 1e-5, "{}", kane.rho_a);
    assert!((first(&kane) - 2.91).abs() < 5e-3, "{}", first(&kane));
}

/// Kane, Ryan & Banerjee's beam at 4 rad/s: the FE beam follows the reference (1 % of the max
/// at every reported time), the reference converges in its modes, and the linear model (no
/// geometric stiffening) runs away past the first frequency — the paper's point.
#[test]
fn kane_ryan_banerjee_beam_fe_follows_the_reference_and_the_linear_beam_fails() {
    let spec = SpinUp::kane_ryan_banerjee(4.0);
    let r4 = spin_up_reference(&spec, 4, 1e-9).unwrap();
    let r5 = spin_up_reference(&spec, 5, 1e-9).unwrap();
    let fe = spin_up_fe(&spec, 16, 1e-3).unwrap();
    let linear = spin_up_linear(&spec, 4, 1e-8).unwrap();
    let (modes, e16) = (r4.difference(&r5), fe.difference(&r5));
    eprintln!(
        "Kane: max {:.6} m; 4 vs 5 modes {modes:.2e}; FE 16 elements {e16:.2e}",
        r5.max_abs()
    );
    assert!(modes <= 1e-4 && e16 <= 1e-2, "{modes} {e16}");
    assert!(linear.tip_deflection_m.last().unwrap().abs() > 1e3 * r5.max_abs());
}

/// Regression: sample spacings whose times k × Δ are not exactly Δ apart once stopped the
/// reference ("the step size fell below the resolution of t"): a step capped at Δ ended a
/// rounding error short of the sample time.
#[test]
fn any_sample_spacing_reaches_every_sample_time() {
    for (duration, every, modes) in [(1.0, 0.01, 2), (1.0, 0.005, 4), (30.0, 0.02, 2)] {
        let spec = SpinUp {
            t_end: duration,
            sample_every: every,
            ..SpinUp::simo_vu_quoc(6.0)
        };
        let r = spin_up_reference(&spec, modes, 1e-8).unwrap();
        assert_eq!(r.t.len(), (duration / every).round() as usize + 1);
        let l = spin_up_linear(&spec, modes, 1e-8).unwrap();
        assert_eq!(l.t.len(), r.t.len());
    }
    // and a failure of the reference's integration is not called an impact
    let e = flexrig_impact::ImpactError::Unfinished {
        what: "spin-up reference",
        reason: "x".into(),
    }
    .to_string();
    assert!(
        e.starts_with("the spin-up reference did not finish") && !e.contains("impact"),
        "{e}"
    );
}

/// A set stop flag stops each solution at its next step with `Interrupted`.
#[test]
fn a_stop_flag_interrupts_each_solution() {
    use flexrig_impact::spin_up::{
        spin_up_fe_until, spin_up_linear_until, spin_up_reference_until,
    };
    use std::sync::atomic::AtomicBool;
    let stop = AtomicBool::new(true);
    let spec = SpinUp::simo_vu_quoc(6.0);
    let interrupted = |r: Result<_, flexrig_impact::ImpactError>| {
        matches!(r, Err(flexrig_impact::ImpactError::Interrupted))
    };
    assert!(interrupted(spin_up_reference_until(
        &spec, 12, 1e-12, &stop
    )));
    assert!(interrupted(spin_up_linear_until(&spec, 12, 1e-12, &stop)));
    assert!(interrupted(spin_up_fe_until(&spec, 1000, 1e-5, &stop)));
}
