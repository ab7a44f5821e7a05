//! Permissible speed: the standard's formula against hand arithmetic, the energy method's identity
//! with it (n = 1, k_c = K, rigid link), the energy method against the lumped crate's exact peak,
//! the pressure limit against an independent bisection, verdicts and refusals.

use flexrig_contact::tolerance::assert_close;
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::{ImpactModel, peak_exact};
use flexrig_safety::{
    BodyModel, ContactAreaModel, ContactKind, EnergyContact, GoverningLimit, Limits, LinkStiffness,
    PressureCrossing, RobotMass, SafetyError, StandardContact, speed_map,
};

fn model() -> BodyModel {
    BodyModel::iso_ts_15066_2016().unwrap()
}

#[test]
fn standard_formula_matches_hand_arithmetic() {
    // Hands and fingers, transient: F = 2 × 140 N, K = 75 N/mm, m_H = 0.6 kg;
    // robot M = 20 kg, m_L = 1 kg → m_R = 11 kg (Eq. A.4); μ = 0.6·11/11.6 kg (Eq. A.3).
    // v = 280/√(0.568965517… · 75000) = 1.35556… m/s (Eq. A.6), computed by hand:
    // μ = 6.6/11.6 = 0.5689655172413793, μk = 42672.41379310345, √ = 206.5730225…
    let model = model();
    let hand = model.region("hands_and_fingers").unwrap();
    let m_r = RobotMass {
        total_moving_mass: 20.0,
        payload: 1.0,
    }
    .effective()
    .unwrap();
    assert_eq!(m_r, 11.0);
    let pad = hand.area("Forefinger pad D").unwrap();
    let contact = StandardContact {
        region: hand,
        area: Some((pad, 1e-4)),
        robot_mass: m_r,
        kind: ContactKind::Transient,
    };
    let v = contact.permissible_speed().unwrap();
    assert_close("μ", v.reduced_mass, 6.6 / 11.6, 1e-15);
    assert_close(
        "v by force",
        v.by_force,
        280.0 / (42672.41379310345_f64).sqrt(),
        1e-14,
    );
    // Pressure form: p A = 2 × 300 N/cm² × 1 cm² = 600 N > 280 N, so the force governs.
    assert_close(
        "v by pressure",
        v.by_pressure.unwrap(),
        600.0 / (42672.41379310345_f64).sqrt(),
        1e-14,
    );
    assert_eq!(v.governing, GoverningLimit::Force);
    // With 0.4 cm² the pressure force is 240 N and the pressure governs.
    let small = StandardContact {
        area: Some((pad, 0.4e-4)),
        ..contact
    };
    let v = small.permissible_speed().unwrap();
    assert_eq!(v.governing, GoverningLimit::Pressure);
    assert_close(
        "v_max",
        v.v_max,
        240.0 / (42672.41379310345_f64).sqrt(),
        1e-14,
    );
    // Quasi-static (clamped): μ = m_R, quasi-static limits.
    let clamp = StandardContact {
        kind: ContactKind::QuasiStatic,
        ..contact
    };
    let v = clamp.permissible_speed().unwrap();
    assert_close(
        "clamped v",
        v.by_force,
        140.0 / (11.0_f64 * 75e3).sqrt(),
        1e-14,
    );
}

#[test]
fn identity_with_the_standard_formula() {
    // n = 1, k_c = K·1000 N/m, rigid link, fixed area: the energy method is the standard's
    // formula (Eq. 13 with k_o = K), for every region, both contact kinds, several robot masses.
    let model = model();
    for region in model.regions() {
        for kind in [ContactKind::Transient, ContactKind::QuasiStatic] {
            for m_r in [0.3, 2.0, 11.0, 75.0] {
                for area in region.areas() {
                    let a = 1.3e-4;
                    let standard = StandardContact {
                        region,
                        area: Some((area, a)),
                        robot_mass: m_r,
                        kind,
                    };
                    let limits = match region.limits(Some(area), kind) {
                        Ok(l) => l,
                        Err(SafetyError::ContactNotPermitted { .. }) => {
                            assert!(standard.permissible_speed().is_err());
                            continue;
                        }
                        Err(e) => panic!("{e}"),
                    };
                    let hertz = Hertz::new(region.spring_constant(), 1.0).unwrap();
                    let energy = EnergyContact::for_region(
                        region,
                        kind,
                        m_r,
                        hertz,
                        LinkStiffness::Rigid,
                        Some(ContactAreaModel::Fixed { area_m2: a }),
                    )
                    .unwrap();
                    let s = standard.permissible_speed().unwrap();
                    let e = energy.permissible_speed(limits).unwrap();
                    assert_close("μ", e.reduced_mass, s.reduced_mass, 1e-15);
                    assert_close("v by force", e.by_force, s.by_force, 1e-12);
                    assert_close(
                        "v by pressure",
                        e.by_pressure.unwrap(),
                        s.by_pressure.unwrap(),
                        1e-12,
                    );
                    assert_eq!(e.governing, s.governing);
                    for v in [0.1, 0.7, 2.5] {
                        assert_close(
                            "peak force at v",
                            energy.peak_force(v).unwrap(),
                            standard.peak_force(v).unwrap(),
                            1e-12,
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn energy_method_peak_force_equals_the_lumped_exact_peak() {
    // Paper's skinned aluminium (n = 1.961) with a compliant link, against flexrig-lumped's
    // peak_exact through its own ImpactModel.
    let hertz = Hertz::new(7.359e7, 1.961).unwrap();
    for k_delta in [2e2, 1e4, 1e8] {
        let contact =
            EnergyContact::new(4.0, 0.117, hertz, LinkStiffness::Finite(k_delta), None).unwrap();
        for v in [0.3, 1.0, 2.0] {
            let spring = SeriesCompliance::new(k_delta, hertz).unwrap();
            let lumped = peak_exact(&ImpactModel::new(4.0, 0.117, spring, v).unwrap());
            assert_close(
                "peak force",
                contact.peak_force(v).unwrap(),
                lumped.f_max,
                1e-12,
            );
            // And back: the speed that gives this force.
            assert_close(
                "speed at force",
                contact.speed_at_force(lumped.f_max),
                v,
                1e-12,
            );
        }
    }
    // Rigid link: closed form f = ((n+1)E)^{n/(n+1)} k^{1/(n+1)} against the lumped solve with a
    // very stiff link (k_δ = 1e16 N/m changes f by < 1e-10 relative here).
    let rigid = EnergyContact::new(4.0, 0.117, hertz, LinkStiffness::Rigid, None).unwrap();
    let spring = SeriesCompliance::new(1e16, hertz).unwrap();
    let lumped = peak_exact(&ImpactModel::new(4.0, 0.117, spring, 1.5).unwrap());
    assert_close(
        "rigid link",
        rigid.peak_force(1.5).unwrap(),
        lumped.f_max,
        1e-9,
    );
}

/// Independent bisection of f/A(δ_c(f)) = p over f (monotone for n > 1).
fn bisect_force_at_pressure(k: f64, n: f64, area: impl Fn(f64) -> f64, p: f64) -> f64 {
    let pressure = |f: f64| f / area((f / k).powf(1.0 / n));
    let (mut a, mut b) = (1e-9_f64, 1e9_f64);
    for _ in 0..300 {
        let m = (a * b).sqrt();
        if pressure(m) < p { a = m } else { b = m }
    }
    (a * b).sqrt()
}

#[test]
fn pressure_limited_force_agrees_with_independent_bisection() {
    let (k, n, r) = (7.359e7, 1.961, 0.0715);
    let hertz = Hertz::new(k, n).unwrap();
    let pi = std::f64::consts::PI;
    for p in [1.0e6, 2.8e6, 6.0e6] {
        let hz = EnergyContact::new(
            4.0,
            1.0,
            hertz,
            LinkStiffness::Rigid,
            Some(ContactAreaModel::HertzSphere { radius_m: r }),
        )
        .unwrap();
        let thin = EnergyContact::new(
            4.0,
            1.0,
            hertz,
            LinkStiffness::Rigid,
            Some(ContactAreaModel::ThinLayer { radius_m: r }),
        )
        .unwrap();
        let ref_hz = bisect_force_at_pressure(k, n, |d| pi * r * d, p);
        // The cap's projected area saturates at πR² once δ_c ≥ R.
        let ref_thin = bisect_force_at_pressure(k, n, |d| pi * d.min(r) * (2.0 * r - d.min(r)), p);
        match (
            hz.force_at_pressure(p).unwrap(),
            thin.force_at_pressure(p).unwrap(),
        ) {
            (PressureCrossing::AtForce(fh), PressureCrossing::AtForce(ft)) => {
                assert_close("Hertz area force", fh, ref_hz, 1e-12);
                assert_close("thin-layer force", ft, ref_thin, 1e-12);
                assert_close(
                    "pressure at that force",
                    thin.pressure_at_force(ft).unwrap(),
                    p,
                    1e-12,
                );
                // About twice the area allows a larger force: at small δ_c, f_thin/f_Hertz →
                // 2^{n/(n−1)} ≈ 4.2; less at large δ_c, where the cap's area falls below 2πRδ_c.
                assert!(
                    ft > 2.0 * fh && ft < 2f64.powf(n / (n - 1.0)) * fh,
                    "{ft} vs {fh}"
                );
            }
            other => panic!("{other:?}"),
        }
    }
    // n = 1 with the Hertz area: the pressure k_c/(πR) does not depend on the force.
    let linear = Hertz::new(1e5, 1.0).unwrap();
    let c = EnergyContact::new(
        4.0,
        1.0,
        linear,
        LinkStiffness::Rigid,
        Some(ContactAreaModel::HertzSphere { radius_m: r }),
    )
    .unwrap();
    let p_const = 1e5 / (pi * r);
    assert_eq!(
        c.force_at_pressure(1.01 * p_const),
        Some(PressureCrossing::Never)
    );
    assert_eq!(
        c.force_at_pressure(0.99 * p_const),
        Some(PressureCrossing::Always)
    );
}

#[test]
fn link_compliance_raises_the_permissible_speed() {
    // Same contact and limits; the softer link stores energy too, so a higher speed is allowed:
    // v² ∝ U(F) = F²/(2k_δ) + F δ_c/(n+1).
    let model = model();
    let hand = model.region("hands_and_fingers").unwrap();
    let area = hand.most_sensitive_area();
    let limits = hand.limits(Some(area), ContactKind::Transient).unwrap();
    let hertz = Hertz::new(7.359e7, 1.961).unwrap();
    let dome = Some(ContactAreaModel::HertzSphere { radius_m: 0.0715 });
    let mut last = 0.0;
    for link in [
        LinkStiffness::Rigid,
        LinkStiffness::Finite(1e6),
        LinkStiffness::Finite(1e4),
        LinkStiffness::Finite(2e2),
    ] {
        let c = EnergyContact::for_region(hand, ContactKind::Transient, 0.117, hertz, link, dome)
            .unwrap();
        let v = c.permissible_speed(limits).unwrap();
        assert!(v.v_max > last, "{link:?}: {} ≤ {last}", v.v_max);
        last = v.v_max;
        // At v_max the governing limit is met exactly.
        let verdict = c.verdict(v.v_max, limits).unwrap();
        assert!(verdict.pass);
        match v.governing {
            GoverningLimit::Force => {
                assert_close("force at v_max", verdict.peak_force, limits.force, 1e-10)
            }
            GoverningLimit::Pressure => assert_close(
                "pressure at v_max",
                verdict.peak_pressure.unwrap(),
                limits.pressure.unwrap(),
                1e-10,
            ),
        }
        let over = c.verdict(1.01 * v.v_max, limits).unwrap();
        assert!(!over.pass && over.speed_margin < 0.0);
        assert!(over.force_margin < 0.0 || over.pressure_margin.unwrap() < 0.0);
    }
}

#[test]
fn refusals_and_bad_input() {
    let model = model();
    let face = model.region("face").unwrap();
    let standard = StandardContact {
        region: face,
        area: None,
        robot_mass: 5.0,
        kind: ContactKind::Transient,
    };
    let e = standard.permissible_speed().unwrap_err();
    assert!(
        matches!(e, SafetyError::ContactNotPermitted { .. }) && e.to_string().contains("5.5.5.4"),
        "{e}"
    );
    assert!(standard.verdict(0.1).is_err());
    let skin = Hertz::new(7.359e7, 1.961).unwrap();
    let e = EnergyContact::for_region(
        face,
        ContactKind::Transient,
        5.0,
        skin,
        LinkStiffness::Rigid,
        None,
    )
    .unwrap_err();
    assert!(matches!(e, SafetyError::ContactNotPermitted { .. }), "{e}");
    assert!(
        EnergyContact::for_region(
            face,
            ContactKind::QuasiStatic,
            5.0,
            skin,
            LinkStiffness::Rigid,
            None
        )
        .is_ok()
    );
    let neck = model.region("neck").unwrap();
    let bad = StandardContact {
        region: neck,
        area: None,
        robot_mass: -1.0,
        kind: ContactKind::Transient,
    };
    assert!(
        bad.permissible_speed()
            .unwrap_err()
            .to_string()
            .contains("robot_mass")
    );
    let e = RobotMass {
        total_moving_mass: 0.0,
        payload: 0.0,
    }
    .effective()
    .unwrap_err();
    assert!(e.to_string().contains("M/2 + m_L"), "{e}");
    let hertz = Hertz::new(1e5, 1.0).unwrap();
    let e = EnergyContact::new(4.0, 1.0, hertz, LinkStiffness::Finite(-5.0), None).unwrap_err();
    assert!(e.to_string().contains("k_delta"), "{e}");
    let e = EnergyContact::new(
        4.0,
        1.0,
        hertz,
        LinkStiffness::Rigid,
        Some(ContactAreaModel::ThinLayer { radius_m: 0.0 }),
    )
    .unwrap_err();
    assert!(e.to_string().contains("radius_m"), "{e}");
    let c = EnergyContact::new(f64::INFINITY, 1.0, hertz, LinkStiffness::Rigid, None).unwrap();
    assert_eq!(c.reduced_mass(), 1.0);
    assert!(c.peak_force(-1.0).is_err());
    assert!(
        c.permissible_speed(Limits {
            force: 0.0,
            pressure: None
        })
        .is_err()
    );
}

#[test]
fn speed_map_is_row_major_and_matches_single_evaluations() {
    let model = model();
    let hand = model.region("hands_and_fingers").unwrap();
    let limits = hand
        .limits(Some(hand.most_sensitive_area()), ContactKind::Transient)
        .unwrap();
    let hertz = Hertz::new(7.359e7, 1.961).unwrap();
    let base = EnergyContact::for_region(
        hand,
        ContactKind::Transient,
        1.0,
        hertz,
        LinkStiffness::Rigid,
        Some(ContactAreaModel::ThinLayer { radius_m: 0.0715 }),
    )
    .unwrap();
    let masses = [0.1, 1.0, 10.0];
    let links = [LinkStiffness::Rigid, LinkStiffness::Finite(1e3)];
    let map = speed_map(&base, limits, &masses, &links).unwrap();
    assert_eq!(map.len(), 6);
    for (r, &m) in masses.iter().enumerate() {
        for (c, &l) in links.iter().enumerate() {
            let single = base
                .with_robot_mass(m)
                .unwrap()
                .with_link(l)
                .unwrap()
                .permissible_speed(limits)
                .unwrap();
            assert_eq!(map[r * links.len() + c], single);
        }
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(400))]
    /// Force → speed (closed form) → force (energy solve) returns the force, for any skin law,
    /// link, masses and force in the physical ranges.
    #[test]
    fn speed_at_force_inverts_peak_force(
        log_k in 4.0f64..9.0,
        n in 1.0f64..2.5,
        log_kd in 1.0f64..10.0,
        rigid in proptest::bool::ANY,
        m_h in 0.5f64..80.0,
        m_eff in 0.05f64..50.0,
        log_f in 0.0f64..4.0,
    ) {
        let hertz = Hertz::new(10f64.powf(log_k), n).unwrap();
        let link = if rigid { LinkStiffness::Rigid } else { LinkStiffness::Finite(10f64.powf(log_kd)) };
        let c = EnergyContact::new(m_h, m_eff, hertz, link, None).unwrap();
        let f = 10f64.powf(log_f);
        let v = c.speed_at_force(f);
        proptest::prop_assert!(v.is_finite() && v > 0.0);
        let back = c.peak_force(v).unwrap();
        proptest::prop_assert!((back - f).abs() <= 1e-10 * f, "{} vs {}", back, f);
    }
}
