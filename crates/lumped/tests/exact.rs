//! The exact (energy) peak against the n = 1 closed form and independent high-precision values.

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
    // samples::HIGH_PRECISION_PEAKS: 50-digit mpmath values by quadrature and findroot.
    for (model, reference) in samples::high_precision_peaks().unwrap() {
        let peak = peak_exact(&model);
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
