use super::*;

fn input(method: MapMethod) -> SafetyMapInput {
    SafetyMapInput {
        region: "hands_and_fingers".into(),
        area: None,
        contact: ContactKind::Transient,
        m_r: Some(0.051),
        m_e: None,
        k_delta: None,
        law: ContactLaw::Material("skinned_aluminium".into()),
        area_model: None,
        x: parse_axis("--x", "m-e=0.05:2:3:log").unwrap(),
        y: parse_axis("--y", "k-delta=100:1e5:3:log").unwrap(),
        method,
        simulation: SimulationSettings::DEFAULT,
        speed: Some(1.0),
    }
}

#[test]
fn axes_parse_the_range_syntax_and_refuse_bad_text_naming_the_flag() {
    let a = parse_axis("--x", "k-delta=10:1e7:7:log").unwrap();
    assert_eq!(a.parameter, MapParameter::LinkStiffness);
    assert_eq!(a.values.len(), 7);
    assert_eq!(a.values[0], 10.0);
    assert_eq!(a.values[6], 1e7);
    assert!((a.values[1] / 10.0 - 10.0).abs() < 1e-12);
    let l = parse_axis("--y", "m_e=0.1,0.2,0.5").unwrap();
    assert_eq!(l.values, vec![0.1, 0.2, 0.5]);
    for bad_text in [
        "k-delta",
        "speed=1:2:3",
        "m-e=0:1:3",
        "m-e=1:0.5:3:log",
        "m-e=1:2:1",
        "m-e=1:2:x",
        "m-e=-1:2:3:log",
    ] {
        let e = parse_axis("--x", bad_text).unwrap_err();
        assert!(e.to_string().contains("--x"), "{bad_text}: {e}");
    }
}

#[test]
fn a_region_axis_cell_is_the_single_point_answer_for_its_region() {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let mut i = input(MapMethod::Energy);
    i.region = String::new();
    i.law = ContactLaw::BodySpring;
    i.m_e = Some(0.2);
    i.x = parse_axis("--x", "m-r=0.5:5:3:log").unwrap();
    i.y = parse_axis("--y", "region=all").unwrap();
    let map = safety_map(&i, Some(&model), &CancelToken::new()).unwrap();
    let keys: Vec<&str> = model.regions().iter().map(|r| r.key()).collect();
    assert_eq!(map.input.y.names, keys);
    assert_eq!(map.cells.len(), 3 * keys.len());
    for c in &map.cells {
        let key = c.region.as_deref().unwrap();
        assert_eq!(map.input.y.region_at(c.y), Some(key));
        let region = model.region(key).unwrap();
        match region.force_limit(ContactKind::Transient) {
            Err(_) => {
                let e = c.error.as_deref().unwrap();
                assert!(e.contains("5.5.5.4"), "{key}: {e}");
                assert!(c.cj.is_none() && c.force_limit_n.is_none());
            }
            Ok(f) => {
                assert_eq!(c.force_limit_n, Some(f), "{key}");
                assert_eq!(c.k_c, region.spring_constant(), "{key}");
                for (gamma, design) in [(GAMMA_CJ, c.cj), (GAMMA_CL, c.cl)] {
                    let single = safety(
                        &SafetyInput {
                            region: key.into(),
                            area: None,
                            contact: ContactKind::Transient,
                            m_eff: Some(RobotEffectiveMass::Prb {
                                gamma,
                                m_r: c.x,
                                m_e: 0.2,
                            }),
                            k_delta: None,
                            law: ContactLaw::BodySpring,
                            area_model: None,
                            moving_mass: None,
                            payload: 0.0,
                            speed: None,
                            methods: vec![SafetyMethod::Energy],
                            link: None,
                            simulation: None,
                            scene: None,
                        },
                        Some(&model),
                    )
                    .unwrap();
                    let d = design.unwrap();
                    assert_eq!(d.v_max_mps, single.methods[0].v_max_mps, "{key}");
                }
            }
        }
    }
    // the CSV names the region, the figure draws it
    let text = csv(&map);
    assert!(text.lines().nth(1).unwrap().contains(keys[0]), "{text}");
    let figure = svg(&map, 500.0).unwrap();
    assert!(figure.contains("hands and fingers"));
    // --region and --area are refused beside a region axis, an unknown key names the flag
    let mut j = i.clone();
    j.region = "chest".into();
    let e = safety_map(&j, Some(&model), &CancelToken::new()).unwrap_err();
    assert!(e.to_string().contains("--region"), "{e}");
    let mut j = i.clone();
    j.y = parse_axis("--y", "region=chest,elbow").unwrap();
    let e = safety_map(&j, Some(&model), &CancelToken::new()).unwrap_err();
    assert!(
        e.to_string().contains("--y") && e.to_string().contains("elbow"),
        "{e}"
    );
}

#[test]
fn a_cancelled_map_stops_with_interrupted() {
    let cancel = CancelToken::new();
    cancel.cancel();
    let mut i = input(MapMethod::Energy);
    i.x = parse_axis("--x", "m-e=0.05:2:20:log").unwrap();
    let e = safety_map(&i, None, &cancel).unwrap_err();
    assert_eq!(e.kind(), crate::ErrorKind::Interrupted, "{e}");
}

/// The map's figure read back: its region, limits, link mass and method are the inputs that
/// ran, every symbol set with a real subscript (no literal `v_max`), text ≥ 8 pt at one and
/// two columns.
#[test]
fn the_figure_says_the_inputs_that_ran() {
    use crate::plots::inspect::{min_text_pt, texts, texts_outside};
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let map = safety_map(&input(MapMethod::Energy), Some(&model), &CancelToken::new()).unwrap();
    for width in [252.0, 504.0] {
        let figure = svg(&map, width).unwrap();
        // the title's lines broken to the width, read as one text
        let text = texts(&figure).join(" ");
        assert!(
            texts_outside(&figure).is_empty(),
            "{:?}",
            texts_outside(&figure)
        );
        for label in [
            "hands and fingers",
            "F_max = 280 N",
            "p_max = 380 N/cm²",
            "m_r = 0.051 kg",
            "lumped energy method (CJ: m_eff = m_e + m_r/3",
            "v_max [m/s]",
            "payload m_e [kg]",
            "link stiffness k_δ [N/m]",
        ] {
            assert!(text.contains(label), "{label} at {width} pt:\n{text}");
        }
        // each symbol a subscript, not a literal underscore
        for literal in ["v_max", "F_max", "p_max", "m_eff"] {
            assert!(!figure.contains(literal), "literal {literal} at {width} pt");
        }
        assert!(min_text_pt(&figure).unwrap() >= crate::plots::MIN_TEXT_PT - 1e-3);
    }
}

#[test]
fn every_lumped_cell_is_the_single_point_answer_bit_for_bit() {
    let input = input(MapMethod::Energy);
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let map = safety_map(&input, Some(&model), &CancelToken::new()).unwrap();
    assert_eq!(map.cells.len(), 9);
    for c in &map.cells {
        for (gamma, design) in [(GAMMA_CJ, c.cj.unwrap()), (GAMMA_CL, c.cl.unwrap())] {
            let single = safety(
                &SafetyInput {
                    region: "hands_and_fingers".into(),
                    area: None,
                    contact: ContactKind::Transient,
                    m_eff: Some(RobotEffectiveMass::Prb {
                        gamma,
                        m_r: 0.051,
                        m_e: c.x,
                    }),
                    k_delta: Some(c.y),
                    law: ContactLaw::Material("skinned_aluminium".into()),
                    area_model: None,
                    moving_mass: None,
                    payload: 0.0,
                    link: None,
                    simulation: None,
                    scene: None,
                    speed: None,
                    methods: vec![SafetyMethod::Energy],
                },
                None,
            )
            .unwrap();
            let m = &single.methods[0];
            assert_eq!(
                design.v_max_mps.value().to_bits(),
                m.v_max_mps.value().to_bits()
            );
            assert_eq!(design.m_eff_kg.to_bits(), m.robot_mass_kg.to_bits());
        }
    }
}
