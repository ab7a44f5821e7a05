//! The rotor-inertia sweep (issue 14): its two ends against independent solutions — the held
//! joint (an infinite rotor), the head against the CJ's free tip mass in closed form and the
//! pinned CL beam by generalized-α (a vanishing rotor) — and its bad input.

use flexrig_impact::cl::run_cl;
use flexrig_impact::eta::{EtaSettings, case_setup};
use flexrig_impact::map::LogRange;
use flexrig_impact::rotor::{rotor_point, rotor_sweep};
use flexrig_impact::{ClSolver, Joint};
use flexrig_lumped::fig6::{K_C, M_R, V0, cases};

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// ρ = J_R/(m_r L²/3) = 1e8 is the held joint for every Fig. 6 case and exponent: CJ and CL
/// peaks within 1e-5 (the rotor's tip-equivalent mass, 3e8 kg, moves by m_h/M_R ≲ 3e-6 of the
/// tip during the contact; tolerances 1e-6).
#[test]
fn a_huge_rotor_is_the_held_joint() {
    let settings = EtaSettings::DEFAULT;
    let mut worst: f64 = 0.0;
    for case in cases() {
        for n in [1.0, 2.0] {
            let held = rotor_point(&case, n, None, &settings).unwrap();
            let heavy = rotor_point(&case, n, Some(1e8), &settings).unwrap();
            let e = rel(heavy.f_cj_n, held.f_cj_n).max(rel(heavy.f_cl_n, held.f_cl_n));
            worst = worst.max(e);
            assert!(e <= 1e-5, "{case:?} n {n}: {heavy:?} vs {held:?}");
        }
    }
    eprintln!("ρ = 1e8 against held: worst {worst:.1e}");
}

/// ρ = 1e-8: the CJ link pivots freely, so the head meets its tip mass M = m_e + m_r/3 alone:
/// the Hertz peak of two free masses, f = k δ_maxⁿ with k δ_max^{n+1}/(n + 1) = ½ μ v0²,
/// μ = m_h M/(m_h + M), within 1e-6 (the massless rotor's spring transmits ~M_R/M ≈ 1e-8).
#[test]
fn a_vanishing_rotor_frees_the_cj_tip_mass() {
    let mut worst: f64 = 0.0;
    for case in cases() {
        for n in [1.0, 2.0] {
            let point = rotor_point(&case, n, Some(1e-8), &EtaSettings::DEFAULT).unwrap();
            let m = case.m_e + M_R / 3.0;
            let mu = case.m_h * m / (case.m_h + m);
            let delta = ((n + 1.0) * mu * V0 * V0 / (2.0 * K_C)).powf(1.0 / (n + 1.0));
            let exact = K_C * delta.powf(n);
            let e = rel(point.f_cj_n, exact);
            worst = worst.max(e);
            assert!(e <= 1e-6, "{case:?} n {n}: {} vs {exact}", point.f_cj_n);
        }
    }
    eprintln!("CJ at ρ = 1e-8 against two free masses: worst {worst:.1e}");
}

/// ρ = 1e-6: the CL beam pinned at the hub, the modal path against generalized-α (128 uniform
/// elements, 800 steps per contact; the reference's own error is ≤ 8e-5 on these meshes) within
/// 2e-4, on a stiff and a soft link.
#[test]
fn a_vanishing_rotor_pins_the_cl_beam() {
    let solver = ClSolver {
        elements: 128,
        steps_per_contact: 800,
        modes: None,
    };
    for index in [0, 5] {
        let case = cases()[index];
        let point = rotor_point(&case, 1.0, Some(1e-6), &EtaSettings::DEFAULT).unwrap();
        let settings = EtaSettings {
            joint: Joint::FreeHub {
                rotor_inertia: 1e-6 * M_R / 3.0,
            },
            ..EtaSettings::DEFAULT
        };
        let setup = case_setup(&case, 1.0, &settings).unwrap();
        let reference = run_cl(&setup, &solver).unwrap().first.peak_force_n;
        assert!(
            rel(point.f_cl_n, reference) <= 2e-4,
            "{case:?}: {} vs {reference}",
            point.f_cl_n
        );
    }
}

/// The sweep: every case × exponent × ρ, then held, in that order; a range outside
/// [1e-9, 1e9] or with fewer than 2 points names the argument.
#[test]
fn the_sweep_covers_every_curve_and_refuses_bad_ranges() {
    let ratios = LogRange {
        from: 1e-3,
        to: 1e3,
        points: 3,
    };
    let points = rotor_sweep(&ratios, &[2.0], &EtaSettings::DEFAULT).unwrap();
    assert_eq!(points.len(), 8 * 4);
    for (i, p) in points.iter().enumerate() {
        match i % 4 {
            3 => assert_eq!(p.inertia_ratio, None),
            k => assert_eq!(
                p.inertia_ratio.map(f64::log10).map(f64::round),
                Some(3.0 * k as f64 - 3.0)
            ),
        }
        assert!(p.eta_fe.is_finite() && p.eta_fe > 0.0);
    }
    for bad in [
        LogRange {
            from: 1e-12,
            to: 1.0,
            points: 3,
        },
        LogRange {
            from: 1.0,
            to: 0.1,
            points: 3,
        },
        LogRange {
            from: 0.1,
            to: 1.0,
            points: 1,
        },
    ] {
        let e = rotor_sweep(&bad, &[1.0], &EtaSettings::DEFAULT).unwrap_err();
        assert!(e.to_string().contains("inertia_ratio"), "{e}");
    }
}
