//! The exact (energy) peak against the n = 1 closed form and independent high-precision values.
// The reference values are kept with all the digits the independent source printed.
#![allow(clippy::excessive_precision)]

use flexrig_contact::tolerance::assert_close;
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::{ImpactModel, LumpedError, peak_analytic, peak_exact, samples};

fn model(m_h: f64, m_eff: f64, k_delta: f64, k_c: f64, n: f64, v0: f64) -> ImpactModel {
    let spring = SeriesCompliance::new(k_delta, Hertz::new(k_c, n).unwrap()).unwrap();
    ImpactModel::new(m_h, m_eff, spring, v0).unwrap()
}

#[test]
fn exact_equals_the_closed_form_for_a_linear_contact() {
    // Eq. 13 over k_δ/k_c from 1e-8 to 1e8 and masses over decades.
    for ratio in [1e-8, 1e-6, 1e-3, 1.0, 1e3, 1e8] {
        for (m_h, m_eff, v0) in [(4.0, 3.4333, 2.0), (1000.0, 0.1, 0.01), (0.001, 500.0, 9.0)] {
            let m = model(m_h, m_eff, 1e6 * ratio, 1e6, 1.0, v0);
            let exact = peak_exact(&m);
            let analytic = peak_analytic(&m).unwrap();
            assert_close(
                "f_max exact vs Eq. 13",
                exact.f_max,
                analytic.peak.f_max,
                1e-12,
            );
            assert_close(
                "δ_max exact vs Eq. 13",
                exact.delta_max,
                analytic.peak.delta_max,
                1e-12,
            );
        }
    }
}

#[test]
fn exact_matches_independent_high_precision_values() {
    // From scripts/reference_exact.py: mpmath at 50 digits, U(f) by tanh-sinh quadrature of the
    // work of the force and the root of U(f) = μ v0²/2 by findroot (another method than the
    // closed-form antiderivative and Newton used here). Columns: m_h, m_eff, k_δ, k_c, n, v0, f_max.
    let table: [(f64, f64, f64, f64, f64, f64, f64); 8] = [
        (
            4.0,
            10.0 / 3.0 + 0.1,
            1e8,
            1e8,
            2.0,
            2.0,
            2296.617005700095672426137,
        ),
        (
            4.0,
            10.0 / 3.0 + 0.1,
            1e8,
            1e8,
            1.5,
            2.0,
            5847.789870245047887188035,
        ),
        (
            4.0,
            20.0 / 9.0 + 0.1,
            2e2,
            1e8,
            2.0,
            2.0,
            34.24504981478450701721317,
        ),
        (
            1000.0,
            10.0 / 3.0 + 0.1,
            1e8,
            1e8,
            2.5,
            2.0,
            1862.770268477948318160946,
        ),
        (
            0.398,
            0.429,
            6.0,
            7.359e7,
            1.961,
            0.9,
            1.001497720973772587892669,
        ),
        (
            4.008,
            0.429,
            6.0,
            9.642e7,
            2.002,
            0.9,
            1.372112708700056584262454,
        ),
        (
            0.039,
            0.1,
            1e2,
            1.311e7,
            1.817,
            1.5,
            2.505447899271634783196705,
        ),
        (1.0, 1.0, 1e-2, 1e4, 3.0, 1.0, 0.07066272066547139108705697),
    ];
    for (m_h, m_eff, k_delta, k_c, n, v0, reference) in table {
        let peak = peak_exact(&model(m_h, m_eff, k_delta, k_c, n, v0));
        assert_close("f_max vs 50-digit reference", peak.f_max, reference, 1e-12);
    }
}

#[test]
fn exact_matches_the_reference_notes() {
    for case in samples::peak_references().unwrap() {
        let peak = peak_exact(&case.model);
        assert_close(case.name, peak.f_max, case.f_max, case.reference_accuracy);
    }
}

#[test]
fn peak_state_is_consistent() {
    let m = model(4.0, 2.3222, 2e2, 1e8, 2.0, 2.0);
    let p = peak_exact(&m);
    let spring = m.spring();
    assert_close(
        "δ_max = δ(f_max)",
        p.delta_max,
        spring.displacement(p.f_max),
        1e-15,
    );
    assert_close(
        "stored energy",
        spring.energy(p.f_max),
        m.impact_energy(),
        1e-13,
    );
    assert_close(
        "δ_l + δ_c",
        p.link_deflection_max + p.indentation_max,
        p.delta_max,
        1e-15,
    );
}

#[test]
fn analytic_refuses_a_nonlinear_contact() {
    let err = peak_analytic(&model(4.0, 1.0, 1e8, 1e8, 2.0, 2.0)).unwrap_err();
    assert!(matches!(
        err,
        LumpedError::NotApplicable {
            method: "analytic",
            ..
        }
    ));
    assert!(
        err.to_string().contains("n = 2") && err.is_input_error(),
        "{err}"
    );
}

#[test]
fn invalid_models_name_the_field() {
    let spring = SeriesCompliance::new(1e8, Hertz::new(1e8, 2.0).unwrap()).unwrap();
    for (m_h, m_eff, v0, field) in [
        (0.0, 1.0, 1.0, "m_h"),
        (1.0, -1.0, 1.0, "m_eff"),
        (1.0, 1.0, f64::NAN, "v0"),
        (f64::INFINITY, 1.0, 1.0, "m_h"),
    ] {
        let e = ImpactModel::new(m_h, m_eff, spring, v0)
            .unwrap_err()
            .to_string();
        assert!(e.contains(field), "{e}");
    }
}
