//! Series compliance (paper Eq. 6–9) against closed forms, quadrature and finite differences,
//! over the stiffness ratios and exponents the issue asks for.

use flexrig_contact::tolerance::{assert_close, central_difference};
use flexrig_contact::{Hertz, SeriesCompliance};
use proptest::prelude::*;

fn series(k_delta: f64, k_c: f64, n: f64) -> SeriesCompliance {
    SeriesCompliance::new(k_delta, Hertz::new(k_c, n).unwrap()).unwrap()
}

#[test]
fn linear_contact_is_the_closed_form() {
    let s = series(2e2, 1e8, 1.0);
    let k_o = 2e2 * 1e8 / (2e2 + 1e8);
    assert_close("f = k_o δ", s.force(0.01), k_o * 0.01, 1e-15);
    assert_close("k_o (Eq. 9)", s.overall_stiffness(3.0), k_o, 1e-15);
}

#[test]
fn energy_is_the_integral_of_force_over_displacement() {
    // U(f(δ)) = ∫₀^δ f(s) ds, with the integral by composite Simpson on a graded mesh (an
    // independent path: it only calls the force solve).
    for (k_delta, k_c, n) in [
        (1e8, 1e8, 2.0),
        (2e2, 1e8, 2.0),
        (1e4, 7.359e7, 1.961),
        (1e6, 1e5, 1.5),
    ] {
        let s = series(k_delta, k_c, n);
        let delta = 1e-3;
        let m = 4000;
        let mut sum = 0.0;
        for i in 0..m {
            let (u0, u1) = (i as f64 / m as f64, (i + 1) as f64 / m as f64);
            let um = 0.5 * (u0 + u1);
            let g = |u: f64| s.force(delta * u * u) * 2.0 * delta * u;
            sum += (u1 - u0) / 6.0 * (g(u0) + 4.0 * g(um) + g(u1));
        }
        let f = s.force(delta);
        assert_close("U(f(δ)) vs ∫ f dδ", s.energy(f), sum, 1e-9);
    }
}

#[test]
fn tangents_match_finite_differences() {
    for (k_delta, k_c, n) in [(1e8, 1e8, 2.0), (2e2, 1e8, 2.0), (3e5, 1.311e7, 1.817)] {
        let s = series(k_delta, k_c, n);
        for f in [1e-2, 10.0, 2e3] {
            let fd = central_difference(|x| s.displacement(x), f, 1e-6);
            assert_close("dδ/df", s.compliance(f), fd, 1e-8);
            let fd = central_difference(|x| s.energy(x), f, 1e-6);
            assert_close("dU/df", s.energy_slope(f), fd, 1e-8);
            // dU/df = f dδ/df: the work of the force.
            assert_close(
                "dU/df = f δ'(f)",
                s.energy_slope(f),
                f * s.compliance(f),
                1e-14,
            );
        }
    }
}

#[test]
fn no_force_without_compression() {
    let s = series(1e3, 1e8, 2.0);
    assert_eq!(s.force(0.0), 0.0);
    assert_eq!(s.force(-1.0), 0.0);
    assert_eq!(s.force(f64::NAN), 0.0);
    assert_eq!(s.energy(0.0), 0.0);
    assert_eq!(s.force_at_energy(0.0).force, 0.0);
}

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 2000,
        rng_seed: proptest::test_runner::RngSeed::Fixed(20261121),
        ..ProptestConfig::default()
    })]

    /// δ(f(δ)) = δ to round-off for n ∈ [1, 3] and k_δ/k_c from 1e-8 to 1e8.
    #[test]
    fn force_inverts_displacement(
        k_c in log_uniform(1e2, 1e10),
        ratio in log_uniform(1e-8, 1e8),
        n in 1.0f64..3.0,
        delta in log_uniform(1e-9, 1e-1),
    ) {
        let s = series(ratio * k_c, k_c, n);
        let solve = s.solve_force(delta);
        prop_assert!(solve.force.is_finite() && solve.force > 0.0);
        let back = s.displacement(solve.force);
        prop_assert!(((back - delta) / delta).abs() < 1e-13,
            "δ = {delta:e}, back = {back:e}, iterations {}", solve.iterations);
        prop_assert!(solve.iterations <= 12, "{} iterations", solve.iterations);
    }

    /// U(f(E)) = E to round-off over the same ranges and impact energies 1e-9 … 1e4 J.
    #[test]
    fn force_at_energy_inverts_energy(
        k_c in log_uniform(1e2, 1e10),
        ratio in log_uniform(1e-8, 1e8),
        n in 1.0f64..3.0,
        energy in log_uniform(1e-9, 1e4),
    ) {
        let s = series(ratio * k_c, k_c, n);
        let solve = s.force_at_energy(energy);
        prop_assert!(solve.force.is_finite() && solve.force > 0.0);
        let back = s.energy(solve.force);
        prop_assert!(((back - energy) / energy).abs() < 1e-13,
            "E = {energy:e}, back = {back:e}, iterations {}", solve.iterations);
        prop_assert!(solve.iterations <= 12, "{} iterations", solve.iterations);
    }
}
