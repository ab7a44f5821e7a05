//! Stability over parameter decades: no panic, no NaN, and the time integration agrees with the
//! exact energy solution (masses 1 g … 1000 kg, stiffnesses 1e2 … 1e10, n ∈ [1, 3], speeds
//! 1 mm/s … 10 m/s).

use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::ode::{Formulation, OdeOptions, integrate};
use flexrig_lumped::{ImpactModel, peak_exact};
use proptest::prelude::*;

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

/// Impacts over the decades of the module docs: (m_h, m_eff, k_δ, k_c, n, v0) as a model.
fn impacts() -> impl Strategy<Value = ImpactModel> {
    (
        log_uniform(1e-3, 1e3),
        log_uniform(1e-3, 1e3),
        log_uniform(1e2, 1e10),
        log_uniform(1e2, 1e10),
        1.0f64..3.0,
        log_uniform(1e-3, 10.0),
    )
        .prop_map(|(m_h, m_eff, k_delta, k_c, n, v0)| {
            let spring = SeriesCompliance::new(k_delta, Hertz::new(k_c, n).unwrap()).unwrap();
            ImpactModel::new(m_h, m_eff, spring, v0).unwrap()
        })
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 400,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261121),
        ..ProptestConfig::default()
    })]

    #[test]
    fn ode_agrees_with_exact_over_decades(model in impacts()) {
        let v0 = model.v0();
        let exact = peak_exact(&model);
        prop_assert!(exact.f_max.is_finite() && exact.f_max > 0.0);
        prop_assert!(exact.delta_max.is_finite() && exact.delta_max > 0.0);
        let sol = integrate(&model, &OdeOptions::new(1e-11).unwrap()).unwrap();
        let err = (sol.peak.f_max - exact.f_max).abs() / exact.f_max;
        prop_assert!(err < 1e-8, "peak error {err:e}");
        let t = sol.contact_duration.unwrap();
        prop_assert!(t.is_finite() && (t - 2.0 * sol.t_peak).abs() < 1e-7 * t);
        let rebound = sol.separation_speed.unwrap();
        prop_assert!((rebound - v0).abs() < 1e-8 * v0, "rebound {rebound} vs {v0}");
    }

    #[test]
    fn displacement_state_agrees_with_exact_over_decades(model in impacts()) {
        // The warm-started Newton solve of the series compliance (linearised start, integer
        // powers, stop at |step| ≤ 1e-8 δ_c) must not cost accuracy anywhere.
        let v0 = model.v0();
        let exact = peak_exact(&model).f_max;
        let options = OdeOptions::new(1e-12).unwrap().formulation(Formulation::Displacement);
        let sol = integrate(&model, &options).unwrap();
        let err = (sol.peak.f_max - exact).abs() / exact;
        prop_assert!(err < 1e-8, "peak error {err:e}");
        let rebound = sol.separation_speed.unwrap();
        prop_assert!((rebound - v0).abs() < 1e-8 * v0, "rebound {rebound} vs {v0}");
    }
}
