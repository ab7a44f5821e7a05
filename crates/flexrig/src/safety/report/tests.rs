use super::*;

/// The number in the report's limits row `label` (its "in the data file" cell).
fn cell(md: &str, label: &str) -> f64 {
    let row = md
        .lines()
        .find(|l| l.starts_with(&format!("| {label}")))
        .unwrap_or_else(|| panic!("no row {label} in\n{md}"));
    let value = row.split('|').nth(2).unwrap().trim();
    value
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("not a number in {row}"))
}

#[test]
fn every_table_value_round_trips_from_the_data_file_to_the_report() {
    // the data file parsed independently of the body model's loader
    let file: toml::Value =
        toml::from_str(flexrig_safety::BUNDLED_BODY_MODEL_TOML).expect("the data file parses");
    let regions = file["region"].as_array().unwrap();
    let mut checked = 0;
    for region in regions {
        let key = region["key"].as_str().unwrap();
        let permitted = region["transient_permitted"].as_bool().unwrap();
        let kind = if permitted {
            ContactKind::Transient
        } else {
            ContactKind::QuasiStatic
        };
        for area in region["area"].as_array().unwrap() {
            let name = area["name"].as_str().unwrap();
            let input = SafetyInput {
                region: key.into(),
                area: Some(name.into()),
                contact: kind,
                m_eff: Some(RobotEffectiveMass::Given(2.0)),
                k_delta: None,
                law: ContactLaw::BodySpring,
                area_model: Some(ContactAreaModel::Fixed { area_m2: 1e-4 }),
                moving_mass: None,
                payload: 0.0,
                speed: Some(0.2),
                methods: vec![SafetyMethod::Standard, SafetyMethod::Energy],
                link: None,
                simulation: None,
                scene: None,
            };
            let (_, doc, _) = report_document(&input, None, None).unwrap();
            let md = doc.markdown();
            let f = |k: &str| region[k].as_float().unwrap();
            assert_eq!(
                cell(&md, "body spring constant K"),
                f("spring_constant_n_per_mm")
            );
            assert_eq!(cell(&md, "effective body mass m_H"), f("effective_mass_kg"));
            assert_eq!(
                cell(&md, "maximum permissible force, quasi-static"),
                f("max_force_n")
            );
            assert_eq!(
                cell(&md, "maximum permissible pressure p_s"),
                area["max_pressure_n_per_cm2"].as_float().unwrap()
            );
            if permitted {
                assert_eq!(
                    cell(&md, "transient force multiplier F_T"),
                    f("transient_force_multiplier")
                );
                assert_eq!(
                    cell(&md, "transient pressure multiplier P_T"),
                    f("transient_pressure_multiplier")
                );
            }
            // the provenance as the file states it
            for k in ["title", "edition", "tables"] {
                assert!(md.contains(file["document"][k].as_str().unwrap()), "{k}");
            }
            assert!(md.contains(region["source"].as_str().unwrap()));
            assert!(md.contains("ISO/PAS 5672"));
            // and the HTML carries the same numbers
            let html = doc.html();
            assert!(html.contains(&format!("<td>{} N/mm</td>", f("spring_constant_n_per_mm"))));
            checked += 1;
        }
    }
    assert_eq!(checked, 29, "every specific area of Table A.2");
}

#[test]
fn the_simulation_trace_ends_on_the_methods_own_speed() {
    let input = SafetyInput {
        region: "hands_and_fingers".into(),
        area: None,
        contact: ContactKind::Transient,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma: 1.0,
            m_r: 0.051,
            m_e: 0.412,
        }),
        k_delta: Some(1e4),
        law: ContactLaw::Material("skinned_aluminium".into()),
        area_model: None,
        moving_mass: None,
        payload: 0.0,
        speed: Some(1.5),
        methods: vec![
            SafetyMethod::Standard,
            SafetyMethod::Energy,
            SafetyMethod::Simulation,
        ],
        link: None,
        simulation: None,
        scene: None,
    };
    let (r, doc, trace) = report_document(&input, None, None).unwrap();
    let sim = r
        .methods
        .iter()
        .find(|m| m.method == SafetyMethod::Simulation)
        .unwrap();
    assert!(trace.len() >= 3);
    // the traced search is the method's own: it ends on the method's speed, and it ran the
    // finite-element CJ (γ = 1 implies the compliant joint)
    let (again, steps, fe) = traced_simulation(&input, None).unwrap();
    assert_eq!(again, *sim);
    assert_eq!(steps, trace);
    assert_eq!(fe.link, FeLink::CompliantJoint);
    let last = trace.last().unwrap();
    assert!((last.speed_mps / sim.by_force_mps.value() - 1.0).abs() < 1e-6);
    let md = doc.markdown();
    assert!(md.contains("Method c: simulation"));
    assert!(md.contains("| iteration |"));
    assert!(md.contains("U(F_max) ="));
    assert!(md.contains("(Eq. A.5)"));
    assert!(figure_svg(&input, None, &r).unwrap().starts_with("<svg"));
}
