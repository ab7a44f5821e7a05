//! Contact laws against analytic references and finite differences.

use flexrig_contact::tolerance::{assert_abs, assert_close, central_difference};
use flexrig_contact::{
    AdamsImpact, ContactLaw, DampedHertz, DampingModel, Hertz, cubic_step, cubic_step_slope,
};

/// ∫₀^x g(s) ds by composite 5-point Gauss–Legendre on the substitution s = x u² (smooth for the
/// power laws met here, whose derivatives are singular at 0).
fn integrate_from_zero(g: impl Fn(f64) -> f64, x: f64) -> f64 {
    const NODES: [f64; 5] = [
        -0.906_179_845_938_664,
        -0.538_469_310_105_683,
        0.0,
        0.538_469_310_105_683,
        0.906_179_845_938_664,
    ];
    const WEIGHTS: [f64; 5] = [
        0.236_926_885_056_189,
        0.478_628_670_499_366,
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
    ];
    let panels = 400;
    let mut sum = 0.0;
    for p in 0..panels {
        let (a, b) = (p as f64 / panels as f64, (p + 1) as f64 / panels as f64);
        for (xi, w) in NODES.iter().zip(WEIGHTS) {
            let u = 0.5 * (a + b) + 0.5 * (b - a) * xi;
            sum += 0.5 * (b - a) * w * g(x * u * u) * 2.0 * x * u;
        }
    }
    sum
}

#[test]
fn hertz_force_energy_and_indentation() {
    for (k, n) in [
        (1.311e7, 1.817),
        (7.359e7, 1.961),
        (9.642e7, 2.002),
        (5e7, 1.5),
        (1e5, 1.0),
    ] {
        let h = Hertz::new(k, n).unwrap();
        for delta in [1e-6, 3e-4, 2e-3] {
            let f = h.force(delta, 0.0);
            assert_close("indentation(force(δ))", h.indentation(f), delta, 1e-14);
            let quad = integrate_from_zero(|s| h.force(s, 0.0), delta);
            assert_close(
                "energy vs quadrature of the force",
                h.energy(delta),
                quad,
                1e-10,
            );
            let fd = central_difference(|d| h.force(d, 0.0), delta, 1e-6);
            assert_close(
                "stiffness vs finite difference",
                h.stiffness(delta, 0.0),
                fd,
                1e-8,
            );
            // Damping-free laws ignore the rate.
            assert_eq!(h.force(delta, 5.0), f);
        }
        assert_eq!(h.force(-1e-3, 1.0), 0.0);
        assert_eq!(h.force(0.0, 1.0), 0.0);
        assert_eq!(h.energy(-1.0), 0.0);
        assert_eq!(h.stiffness(-1.0, 0.0), 0.0);
    }
}

#[test]
fn hertz_sphere_on_flat_peak_matches_closed_form() {
    // n = 3/2: δ_max = (5 m v²/(4k))^{2/5} (references.md, "Contact").
    let (k, m, v) = (3.7e9, 0.75, 1.3);
    let h = Hertz::new(k, 1.5).unwrap();
    let reference = (5.0 * m * v * v / (4.0 * k)).powf(0.4);
    assert_close("δ_max, n = 3/2", h.peak_indentation(m, v), reference, 1e-14);
}

#[test]
fn damped_hertz_derivatives_and_no_adhesion() {
    let h = Hertz::new(7.359e7, 1.961).unwrap();
    let laws = [
        DampedHertz::hunt_crossley(h, 0.6, 1.2).unwrap(),
        DampedHertz::lankarani_nikravesh(h, 0.3, 0.8).unwrap(),
        DampedHertz::new(h, 0.4).unwrap(),
    ];
    for law in laws {
        for (delta, rate) in [(1e-4, 0.5), (8e-4, -0.3), (2e-3, 1.5)] {
            let fd_k = central_difference(|d| law.force(d, rate), delta, 1e-6);
            let fd_c = central_difference(|r| law.force(delta, r), rate, 1e-6);
            assert_close("∂f/∂δ", law.stiffness(delta, rate), fd_k, 1e-7);
            assert_close("∂f/∂δ̇", law.damping(delta, rate), fd_c, 1e-7);
            assert_close(
                "elastic part",
                law.elastic_energy(delta),
                h.energy(delta),
                1e-15,
            );
        }
        // Fast separation: 1 + χ δ̇ < 0 would pull; the law clamps to zero, derivatives too.
        let pulling = -2.0 / law.chi().max(1e-9);
        assert_eq!(law.force(1e-3, pulling), 0.0);
        assert_eq!(law.stiffness(1e-3, pulling), 0.0);
        assert_eq!(law.damping(1e-3, pulling), 0.0);
    }
}

#[test]
fn restitution_formulas() {
    let h = Hertz::new(1e8, 1.5).unwrap();
    let hc = DampedHertz::hunt_crossley(h, 0.8, 2.0).unwrap();
    assert_close(
        "Hunt–Crossley χ = 3(1−e)/(2v0)",
        hc.chi(),
        3.0 * 0.2 / 4.0,
        1e-15,
    );
    assert_eq!(hc.model(), DampingModel::HuntCrossley);
    let ln = DampedHertz::lankarani_nikravesh(h, 0.8, 2.0).unwrap();
    assert_close(
        "Lankarani–Nikravesh χ = 3(1−e²)/(4v0)",
        ln.chi(),
        3.0 * 0.36 / 8.0,
        1e-15,
    );
    // e = 1 is elastic.
    assert_eq!(DampedHertz::hunt_crossley(h, 1.0, 2.0).unwrap().chi(), 0.0);
    assert!(DampedHertz::hunt_crossley(h, 1.2, 2.0).is_err());
    assert!(DampedHertz::lankarani_nikravesh(h, 0.5, 0.0).is_err());
    assert!(DampedHertz::new(h, -1.0).is_err());
}

#[test]
fn adams_step_and_impact() {
    // STEP end values, midpoint, C¹ continuity at the ends.
    assert_eq!(cubic_step(-1.0, 0.0, 2.0, 1.0, 5.0), 2.0);
    assert_eq!(cubic_step(2.0, 0.0, 2.0, 1.0, 5.0), 5.0);
    assert_close(
        "STEP midpoint",
        cubic_step(0.5, 0.0, 2.0, 1.0, 5.0),
        3.5,
        1e-15,
    );
    assert_abs(
        "STEP slope at x0",
        cubic_step_slope(1e-12, 0.0, 2.0, 1.0, 5.0),
        0.0,
        1e-10,
    );
    for x in [0.1, 0.37, 0.8] {
        let fd = central_difference(|s| cubic_step(s, 0.0, 2.0, 1.0, 5.0), x, 1e-6);
        assert_close(
            "STEP slope",
            cubic_step_slope(x, 0.0, 2.0, 1.0, 5.0),
            fd,
            1e-8,
        );
    }
    let law = AdamsImpact::new(1e8, 2.2, 1e3, 1e-4).unwrap();
    // Full damping beyond d, ramped below it.
    assert_eq!(law.damping_coefficient(2e-4), 1e3);
    assert_close("half ramp", law.damping_coefficient(5e-5), 500.0, 1e-12);
    for (delta, rate) in [(2e-5, 0.7), (6e-5, -0.2), (3e-4, 0.9)] {
        let fd_k = central_difference(|d| law.force(d, rate), delta, 1e-6);
        let fd_c = central_difference(|r| law.force(delta, r), rate, 1e-6);
        assert_close("IMPACT ∂f/∂δ", law.stiffness(delta, rate), fd_k, 1e-6);
        assert_close("IMPACT ∂f/∂δ̇", law.damping(delta, rate), fd_c, 1e-7);
    }
    // No force outside contact, none adhesive, and continuous at first touch (c(0) = 0).
    assert_eq!(law.force(-1e-6, 10.0), 0.0);
    assert_eq!(law.force(3e-4, -1e6), 0.0);
    assert!(law.force(1e-12, 100.0) < 1e-9);
    assert!(AdamsImpact::new(1e8, 2.2, -1.0, 1e-4).is_err());
    assert!(AdamsImpact::new(1e8, 2.2, 1.0, 0.0).is_err());
}

#[test]
fn invalid_parameters_name_the_field() {
    let e = Hertz::new(-5.0, 2.0).unwrap_err().to_string();
    assert!(e.contains("k_c") && e.contains("-5"), "{e}");
    let e = Hertz::new(1e7, 0.0).unwrap_err().to_string();
    assert!(e.contains("n = 0") && e.contains("(0, 10]"), "{e}");
    let e = Hertz::new(f64::NAN, 2.0).unwrap_err().to_string();
    assert!(e.contains("NaN"), "{e}");
    let e = AdamsImpact::new(1e8, 20.0, 1.0, 1.0)
        .unwrap_err()
        .to_string();
    assert!(e.contains("exponent"), "{e}");
}
