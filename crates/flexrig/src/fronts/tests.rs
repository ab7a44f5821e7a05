use super::*;

fn arg_of(e: Error) -> String {
    match e {
        Error::InvalidArgument { arg, .. } => arg,
        other => panic!("not an argument error: {other}"),
    }
}

#[test]
fn damping_options_go_with_their_model_and_are_named() {
    let stray = damping_spec(DampingModel::None, Some(0.5), None, None).unwrap_err();
    assert_eq!(arg_of(stray), "--restitution");
    let missing = damping_spec(DampingModel::AdamsImpact, None, Some(1e3), None).unwrap_err();
    assert!(missing.to_string().contains("needs --depth"), "{missing}");
    let out_of_range = damping_spec(DampingModel::HuntCrossley, Some(1.5), None, None).unwrap_err();
    assert_eq!(arg_of(out_of_range), "--restitution");
    assert_eq!(
        damping_spec(DampingModel::LankaraniNikravesh, Some(0.8), None, None).unwrap(),
        DampingSpec::LankaraniNikravesh { restitution: 0.8 }
    );
    for m in DampingModel::ALL {
        assert_eq!(DampingModel::parse(m.name()).unwrap(), m);
        assert_eq!(DampingModel::parse(&m.name().replace('-', "_")).unwrap(), m);
    }
    assert_eq!(
        arg_of(DampingModel::parse("viscous").unwrap_err()),
        "--damping"
    );
}

#[test]
fn the_joint_and_ranges_are_checked_by_flag() {
    assert_eq!(joint(JointKind::Held, None).unwrap(), Joint::Held);
    assert_eq!(
        arg_of(joint(JointKind::Held, Some(1.0)).unwrap_err()),
        "--rotor-inertia"
    );
    assert_eq!(
        arg_of(joint(JointKind::FreeHub, None).unwrap_err()),
        "--joint"
    );
    let r = parse_range("--ratio", "1e-3:1e2", 5).unwrap();
    assert_eq!((r.from, r.to, r.points), (1e-3, 1e2, 5));
    assert_eq!(
        arg_of(parse_range("--ratio", "1e-3", 5).unwrap_err()),
        "--ratio"
    );
    assert_eq!(
        arg_of(eta_rotor_inputs("1e-3:1", 1, &[2.0]).unwrap_err()),
        "--points"
    );
    assert_eq!(
        arg_of(eta_rotor_inputs("1e-3:1", 4, &[4.0]).unwrap_err()),
        "--n"
    );
    assert_eq!(
        arg_of(eta_map_specs(&[], 2.0, "1e-3:1", "1e-7:1", 4).unwrap_err()),
        "--m-h"
    );
}

#[test]
fn eta_options_of_the_other_method_are_refused() {
    let base = EtaInputs {
        joint: JointKind::Held,
        rotor_inertia: None,
        alpha: false,
        tol: None,
        zone_elements: None,
        window_periods: None,
        elements: Some(64),
        steps_per_contact: None,
        modes: None,
        length: 1.0,
        damping: DampingSpec::NONE,
        design: flexrig_lumped::fig6::Fig6Design::PAPER,
    };
    assert_eq!(arg_of(eta_settings(&base).unwrap_err()), "--elements");
    let alpha = eta_settings(&EtaInputs {
        alpha: true,
        ..base.clone()
    })
    .unwrap();
    assert!(matches!(alpha.method, ClMethod::Alpha(s) if s.elements == 64));
}

#[test]
fn the_impact_report_holds_the_closed_form() {
    // n = 1: f_max = v0 √(k_o μ) with k_o = k_δ k_c/(k_δ + k_c) (paper Eq. 13)
    let input = crate::lumped::impact::ImpactInput {
        m_h: 4.0,
        m_eff: crate::lumped::impact::EffectiveMass::Prb {
            gamma: 2.0 / 3.0,
            m_r: 10.0,
            m_e: 0.1,
        },
        k_delta: 1e8,
        k_c: 1e8,
        n: 1.0,
        v0: 2.0,
    };
    let method =
        impact_method("analytic", crate::lumped::impact::Formulation::Auto, 1e-10).unwrap();
    let r = crate::lumped::impact::solve(&input, method).unwrap();
    let report = impact_report(&r, method);
    let m_eff = 0.1 + 10.0 * (2.0 / 3.0) / 3.0;
    let mu: f64 = 4.0 * m_eff / (4.0 + m_eff);
    let f = 2.0 * (0.5e8 * mu).sqrt();
    let got = report["f_max_n"].as_f64().unwrap();
    assert!((got - f).abs() <= 1e-12 * f, "{got} vs {f}");
    assert!((report["m_eff_kg"].as_f64().unwrap() - m_eff).abs() <= 1e-15 * m_eff);
    assert_eq!(report["method"], "analytic");
    assert!(report.get("rhs_evals").is_none() && report.get("k_o_n_per_m").is_some());
    assert_eq!(
        arg_of(impact_method("rk4", crate::lumped::impact::Formulation::Auto, 1e-10).unwrap_err()),
        "--method"
    );
    assert_eq!(
        arg_of(formulation("implicit").unwrap_err()),
        "--formulation"
    );
}
