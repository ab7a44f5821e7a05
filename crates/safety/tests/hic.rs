//! HIC against independent references: the half-sine closed form (derived in the test, φ* by
//! bisection) checked by brute force over the analytic integral; a triangle pulse whose optimum
//! lies strictly inside segments (closed form); the n = 1 lumped impact; random traces against a
//! brute-force search over a refined grid.

use flexrig_contact::tolerance::{assert_close, relative_error};
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::ode::{OdeOptions, integrate};
use flexrig_lumped::{ImpactModel, peak_analytic};
use flexrig_safety::{HicWindow, STANDARD_GRAVITY, SafetyError, hic, hic_half_sine};
use std::f64::consts::PI;

/// φ* of tan φ = 5φ/3 by bisection on (0.5, 1.5) — independent of the library's Newton.
fn phi_star() -> f64 {
    let g = |p: f64| p.tan() - 5.0 * p / 3.0;
    let (mut a, mut b) = (0.5, 1.5);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if g(m) < 0.0 { a = m } else { b = m }
    }
    0.5 * (a + b)
}

/// Closed form derived here: HIC(φ) = (2T/π) A^2.5 sin^2.5 φ / φ^1.5 with φ = min(φ*, πW/(2T)).
fn half_sine_reference(a_g: f64, t: f64, w: f64) -> f64 {
    let phi = phi_star().min(PI * w / (2.0 * t));
    2.0 * t / PI * a_g.powf(2.5) * phi.sin().powf(2.5) / phi.powf(1.5)
}

/// Brute force: every window between points of a fine grid, with the exact integral of the sine.
fn half_sine_brute_force(a_g: f64, t: f64, w: f64, m: usize) -> f64 {
    let cum = |x: f64| a_g * t / PI * (1.0 - (PI * x / t).cos());
    let grid: Vec<f64> = (0..=m).map(|i| t * i as f64 / m as f64).collect();
    let mut best = 0.0_f64;
    for i in 0..=m {
        for j in i + 1..=m {
            let dt = grid[j] - grid[i];
            if dt > w * (1.0 + 1e-12) {
                break;
            }
            let v = (cum(grid[j]) - cum(grid[i])).powf(2.5) / dt.powf(1.5);
            best = best.max(v);
        }
        // The window of exactly the limit, which a grid may miss by one step.
        if grid[i] + w <= t {
            best = best.max((cum(grid[i] + w) - cum(grid[i])).powf(2.5) / w.powf(1.5));
        }
    }
    best
}

fn sampled_half_sine(a: f64, t: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    let times: Vec<f64> = (0..n).map(|i| t * i as f64 / (n - 1) as f64).collect();
    let acc = times.iter().map(|&x| a * (PI * x / t).sin()).collect();
    (times, acc)
}

#[test]
fn half_sine_closed_form_matches_brute_force_integration() {
    let a_g = 80.0;
    // (duration, window): free optimum (window does not bind) and window-limited.
    for (t, w) in [
        (0.010, 0.015),
        (0.050, 0.015),
        (0.040, 0.036),
        (0.060, 0.036),
    ] {
        let reference = half_sine_reference(a_g, t, w);
        let brute = half_sine_brute_force(a_g, t, w, 3000);
        assert!(
            relative_error(brute, reference, 1e-300) < 2e-6,
            "T = {t}: brute {brute} vs {reference}"
        );
        assert!(
            brute <= reference * (1.0 + 1e-12),
            "brute force exceeds the closed form"
        );
        let window = if w == 0.015 {
            HicWindow::Hic15
        } else {
            HicWindow::Hic36
        };
        let library = hic_half_sine(a_g * STANDARD_GRAVITY, t, window).unwrap();
        assert_close("hic_half_sine", library, reference, 1e-13);
    }
    // The optimal free window is 2φ*/π ≈ 0.67023 of the pulse, never the whole pulse: at its
    // ends a(t) = 0.6 × the window mean (cos φ* = 0.6 sin φ*/φ*).
    assert_close("2φ*/π", 2.0 * phi_star() / PI, 0.670_23, 1e-5);
    let whole_pulse = 0.010 * (2.0 * a_g / PI).powf(2.5);
    assert!(half_sine_reference(a_g, 0.010, 0.015) > whole_pulse);
}

#[test]
fn sampled_half_sine_hic_is_within_1e_6_of_the_closed_form() {
    let a = 60.0 * STANDARD_GRAVITY;
    for (t, window) in [
        (0.010, HicWindow::Hic15),
        (0.050, HicWindow::Hic15),
        (0.030, HicWindow::Hic36),
    ] {
        let (times, acc) = sampled_half_sine(a, t, 4001);
        let r = hic(&times, &acc, window).unwrap();
        let w = window.max_duration().unwrap();
        let reference = half_sine_reference(60.0, t, w);
        assert_close("HIC of the sampled half-sine", r.hic, reference, 1e-6);
        // The window is centred on the peak.
        assert!((r.t1 + r.t2 - t).abs() < 1e-5 * t, "{r:?}");
        assert!(r.t2 - r.t1 <= w * (1.0 + 1e-12));
    }
}

#[test]
fn triangle_pulse_optimum_strictly_inside_segments_is_found_exactly() {
    // a(t) = A (1 − |t − T/2|/(T/2)), three samples. Symmetric window of half-width w:
    // HIC(w) = 2 A^2.5 w (1 − w/T)^2.5, maximal at w = 2T/7 (t₁ inside the first segment).
    let (a_g, t) = (50.0, 0.02);
    let times = [0.0, 0.5 * t, t];
    let acc = [0.0, a_g * STANDARD_GRAVITY, 0.0];
    let reference = |w: f64| 2.0 * a_g.powf(2.5) * w * (1.0 - w / t).powf(2.5);
    let r = hic(&times, &acc, HicWindow::Custom(1.0)).unwrap();
    assert_close(
        "triangle HIC (free)",
        r.hic,
        reference(2.0 * t / 7.0),
        1e-12,
    );
    assert_close("t1", r.t1, 0.5 * t - 2.0 * t / 7.0, 1e-12);
    // Window-limited: w = W/2.
    let wmax = 0.004;
    let r = hic(&times, &acc, HicWindow::Custom(wmax)).unwrap();
    assert_close(
        "triangle HIC (limited)",
        r.hic,
        reference(0.5 * wmax),
        1e-12,
    );
}

#[test]
fn lumped_linear_impact_hic_matches_the_half_sine_closed_form() {
    // Head m_h = 4.4 kg struck by m_eff = 2 kg through k_o: with n = 1 the force is a half sine
    // of duration π√(μ/k_o) and the head's acceleration is f/m_h.
    let (m_h, m_eff, v0) = (4.4, 2.0, 1.0);
    let spring = SeriesCompliance::new(1e6, Hertz::new(150e3, 1.0).unwrap()).unwrap();
    let model = ImpactModel::new(m_h, m_eff, spring, v0).unwrap();
    let analytic = peak_analytic(&model).unwrap();
    let k_o: f64 = 150e3 * 1e6 / (150e3 + 1e6);
    let mu = m_h * m_eff / (m_h + m_eff);
    assert_close(
        "contact duration",
        analytic.contact_duration,
        PI * (mu / k_o).sqrt(),
        1e-14,
    );
    let (f_max, t_c) = (analytic.peak.f_max, analytic.contact_duration);
    // The time-integrated force is that half sine (8th-order integration, rtol 1e-12).
    let ode = integrate(&model, &OdeOptions::new(1e-12).unwrap().record_trace(true)).unwrap();
    assert!(ode.trace.len() > 5);
    for p in &ode.trace {
        let half_sine = f_max * (PI * p.t / t_c).sin().max(0.0);
        assert!(
            (p.force - half_sine).abs() <= 1e-8 * f_max,
            "t = {}: {} vs {half_sine}",
            p.t,
            p.force
        );
    }
    let (times, force) = sampled_half_sine(f_max, t_c, 4001);
    let acc: Vec<f64> = force.iter().map(|f| f / m_h).collect();
    for window in [HicWindow::Hic15, HicWindow::Hic36] {
        let r = hic(&times, &acc, window).unwrap();
        let reference = half_sine_reference(
            f_max / m_h / STANDARD_GRAVITY,
            t_c,
            window.max_duration().unwrap(),
        );
        assert_close("HIC of the lumped impact", r.hic, reference, 1e-6);
    }
}

/// Deterministic pseudo-random numbers in [0, 1) (64-bit LCG).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Brute force over a refined grid of the piecewise-linear interpolant (each segment cut in
/// `sub` pieces); the integral of a linear piece is exact by the trapezoid rule.
fn refined_brute_force(times: &[f64], acc_g: &[f64], w: f64, sub: usize) -> f64 {
    let mut t = vec![times[0]];
    let mut a = vec![acc_g[0]];
    for k in 0..times.len() - 1 {
        for s in 1..=sub {
            let f = s as f64 / sub as f64;
            t.push(times[k] + f * (times[k + 1] - times[k]));
            a.push(acc_g[k] + f * (acc_g[k + 1] - acc_g[k]));
        }
    }
    let mut cum = vec![0.0];
    for k in 1..t.len() {
        cum.push(cum[k - 1] + 0.5 * (t[k] - t[k - 1]) * (a[k] + a[k - 1]));
    }
    let mut best = 0.0_f64;
    for i in 0..t.len() {
        for j in i + 1..t.len() {
            let dt = t[j] - t[i];
            if dt > w {
                break;
            }
            let integral = cum[j] - cum[i];
            if integral > 0.0 {
                best = best.max(integral.powf(2.5) / dt.powf(1.5));
            }
        }
        // The window of exactly the limit starting at this grid point.
        if t[i] + w <= times[times.len() - 1] {
            let integral = integral_of_interpolant(times, acc_g, t[i], t[i] + w);
            if integral > 0.0 {
                best = best.max(integral.powf(2.5) / w.powf(1.5));
            }
        }
    }
    best
}

#[test]
fn random_traces_agree_with_a_refined_brute_force_search() {
    let mut rng = Lcg(7);
    for case in 0..40 {
        let n = 4 + (rng.next() * 12.0) as usize;
        let mut times = vec![0.0];
        for _ in 1..n {
            times.push(times.last().unwrap() + 0.001 + 0.004 * rng.next());
        }
        let acc_g: Vec<f64> = (0..n).map(|_| 150.0 * rng.next() - 20.0).collect();
        let acc: Vec<f64> = acc_g.iter().map(|a| a * STANDARD_GRAVITY).collect();
        let w = 0.003 + 0.02 * rng.next();
        let r = hic(&times, &acc, HicWindow::Custom(w)).unwrap();
        let brute = refined_brute_force(&times, &acc_g, w, 60);
        // The exact maximum bounds every grid window and is approached by the refined grid.
        assert!(
            r.hic >= brute * (1.0 - 1e-12),
            "case {case}: {} < {brute}",
            r.hic
        );
        assert!(
            relative_error(brute, r.hic, 1e-300) < 2e-3,
            "case {case}: {} vs {brute}",
            r.hic
        );
        // The reported window is valid and its HIC is the reported value.
        assert!(r.t1 >= times[0] && r.t2 <= times[n - 1] && r.t2 - r.t1 <= w * (1.0 + 1e-12));
        let integral = integral_of_interpolant(&times, &acc_g, r.t1, r.t2);
        assert_close(
            "HIC at the reported window",
            integral.powf(2.5) / (r.t2 - r.t1).powf(1.5),
            r.hic,
            1e-9,
        );
    }
}

fn integral_of_interpolant(times: &[f64], a: &[f64], t1: f64, t2: f64) -> f64 {
    let at = |t: f64| {
        let k = times.partition_point(|&x| x <= t).clamp(1, times.len() - 1) - 1;
        a[k] + (a[k + 1] - a[k]) * (t - times[k]) / (times[k + 1] - times[k])
    };
    let mut pts = vec![t1];
    pts.extend(times.iter().copied().filter(|&x| x > t1 && x < t2));
    pts.push(t2);
    pts.windows(2)
        .map(|p| 0.5 * (p[1] - p[0]) * (at(p[0]) + at(p[1])))
        .sum()
}

#[test]
fn bad_traces_are_refused_naming_the_problem() {
    let t = [0.0, 0.001, 0.002];
    let e = hic(&t, &[1.0, 2.0], HicWindow::Hic15).unwrap_err();
    assert!(
        matches!(e, SafetyError::InvalidTrace { .. }) && e.to_string().contains("same length"),
        "{e}"
    );
    let e = hic(&[0.0, 0.002, 0.001], &[1.0, 2.0, 3.0], HicWindow::Hic15).unwrap_err();
    assert!(e.to_string().contains("increase strictly"), "{e}");
    let e = hic(&t, &[1.0, f64::NAN, 3.0], HicWindow::Hic15).unwrap_err();
    assert!(e.to_string().contains("sample 1"), "{e}");
    let e = hic(&t, &[1.0, 2.0, 3.0], HicWindow::Custom(-0.01)).unwrap_err();
    assert!(e.to_string().contains("hic_window"), "{e}");
    // A trace of decelerations only has no positive window.
    let r = hic(&t, &[-1.0, -2.0, -3.0], HicWindow::Hic15).unwrap();
    assert_eq!(r.hic, 0.0);
}
