//! The body-model table: every value round-trips from the file unchanged (read independently with
//! `toml`), the values match the published tables as transcribed in docs/safety.md, and broken
//! tables are refused naming the region and the field.

use flexrig_safety::{BUNDLED_BODY_MODEL_TOML, BodyModel, ContactKind, SafetyError, TransientRule};
use toml::Value;

fn file() -> Value {
    toml::from_str(BUNDLED_BODY_MODEL_TOML).expect("the bundled table is valid TOML")
}

fn float(v: &Value, key: &str) -> f64 {
    v.get(key)
        .and_then(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
        .unwrap_or_else(|| panic!("{key} missing"))
}

#[test]
fn every_value_round_trips_unchanged() {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let raw = file();
    let regions = raw["region"].as_array().unwrap();
    assert_eq!(regions.len(), model.regions().len());
    for (r, region) in regions.iter().zip(model.regions()) {
        assert_eq!(r["key"].as_str().unwrap(), region.key());
        assert_eq!(r["name"].as_str().unwrap(), region.name());
        assert_eq!(
            float(r, "spring_constant_n_per_mm"),
            region.spring_constant_n_per_mm()
        );
        assert_eq!(
            float(r, "spring_constant_n_per_mm") * 1e3,
            region.spring_constant()
        );
        assert_eq!(float(r, "effective_mass_kg"), region.effective_mass_kg());
        assert_eq!(float(r, "max_force_n"), region.max_force_n());
        assert_eq!(r["source"].as_str().unwrap(), region.source());
        let permitted = r["transient_permitted"].as_bool().unwrap();
        match region.transient() {
            TransientRule::Permitted {
                force_multiplier,
                pressure_multiplier,
                max_force_n,
            } => {
                assert!(permitted);
                assert_eq!(float(r, "transient_force_multiplier"), *force_multiplier);
                assert_eq!(
                    float(r, "transient_pressure_multiplier"),
                    *pressure_multiplier
                );
                assert_eq!(
                    r.get("transient_max_force_n")
                        .map(|_| float(r, "transient_max_force_n")),
                    *max_force_n
                );
            }
            TransientRule::NotPermitted { clause } => {
                assert!(!permitted);
                assert_eq!(
                    r["transient_not_permitted_clause"].as_str().unwrap(),
                    clause
                );
            }
        }
        let areas = r["area"].as_array().unwrap();
        assert_eq!(areas.len(), region.areas().len());
        for (a, area) in areas.iter().zip(region.areas()) {
            assert_eq!(a["number"].as_integer().unwrap() as u32, area.number());
            assert_eq!(a["name"].as_str().unwrap(), area.name());
            assert_eq!(
                float(a, "max_pressure_n_per_cm2"),
                area.max_pressure_n_per_cm2()
            );
            assert_eq!(
                a.get("transient_max_pressure_n_per_cm2")
                    .map(|_| float(a, "transient_max_pressure_n_per_cm2")),
                area.transient_max_pressure_n_per_cm2()
            );
        }
    }
    let doc = &raw["document"];
    assert_eq!(doc["title"].as_str().unwrap(), model.provenance().title);
    assert_eq!(doc["edition"].as_str().unwrap(), model.provenance().edition);
    assert_eq!(doc["tables"].as_str().unwrap(), model.provenance().tables);
}

/// ISO/TS 15066:2016 Table A.3 and the force column of Table A.2, in the standard's region order,
/// as transcribed in docs/safety.md (checked against two or more public transcriptions).
const TABLE_A3_AND_FORCES: [(&str, f64, f64, f64); 12] = [
    ("Skull and forehead", 150.0, 4.4, 130.0),
    ("Face", 75.0, 4.4, 65.0),
    ("Neck", 50.0, 1.2, 150.0),
    ("Back and shoulders", 35.0, 40.0, 210.0),
    ("Chest", 25.0, 40.0, 140.0),
    ("Abdomen", 10.0, 40.0, 110.0),
    ("Pelvis", 25.0, 40.0, 180.0),
    ("Upper arms and elbow joints", 30.0, 3.0, 150.0),
    ("Lower arms and wrist joints", 40.0, 2.0, 160.0),
    ("Hands and fingers", 75.0, 0.6, 140.0),
    ("Thighs and knees", 50.0, 75.0, 220.0),
    ("Lower legs", 60.0, 75.0, 130.0),
];

/// Table A.2 quasi-static pressures [N/cm²] of the 29 areas, by number.
const TABLE_A2_PRESSURES: [f64; 29] = [
    130.0, 110.0, 110.0, 140.0, 210.0, 160.0, 210.0, 120.0, 170.0, 140.0, 210.0, 190.0, 220.0,
    190.0, 180.0, 180.0, 300.0, 270.0, 280.0, 220.0, 200.0, 260.0, 260.0, 200.0, 190.0, 250.0,
    220.0, 220.0, 210.0,
];

#[test]
fn values_match_the_published_tables() {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    assert_eq!(model.regions().len(), 12);
    assert_eq!(model.area_count(), 29);
    for (region, (name, k, m, f)) in model.regions().iter().zip(TABLE_A3_AND_FORCES) {
        assert_eq!(region.name(), name);
        assert_eq!(region.spring_constant_n_per_mm(), k, "{name} K");
        assert_eq!(region.effective_mass_kg(), m, "{name} m_H");
        assert_eq!(region.max_force_n(), f, "{name} F");
    }
    let mut seen = [false; 29];
    for region in model.regions() {
        for area in region.areas() {
            let i = area.number() as usize - 1;
            assert!(!seen[i], "area {} twice", area.number());
            seen[i] = true;
            assert_eq!(
                area.max_pressure_n_per_cm2(),
                TABLE_A2_PRESSURES[i],
                "{}",
                area.name()
            );
        }
    }
    assert!(seen.iter().all(|s| *s));
    // Transient contact: not permitted for head and face, factor 2 elsewhere (A.3.2).
    for region in model.regions() {
        let head = matches!(region.key(), "skull_and_forehead" | "face");
        match region.transient() {
            TransientRule::NotPermitted { clause } => {
                assert!(head, "{}", region.name());
                assert!(clause.contains("5.5.5.4"), "{clause}");
            }
            TransientRule::Permitted {
                force_multiplier,
                pressure_multiplier,
                max_force_n,
            } => {
                assert!(!head, "{}", region.name());
                assert_eq!(
                    (*force_multiplier, *pressure_multiplier, *max_force_n),
                    (2.0, 2.0, None)
                );
            }
        }
    }
}

#[test]
fn limits_in_si_units_and_the_transient_factor() {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let neck = model.region("Neck").unwrap();
    let muscle = neck.area("neck muscle").unwrap();
    let q = neck.limits(Some(muscle), ContactKind::QuasiStatic).unwrap();
    assert_eq!((q.force, q.pressure), (150.0, Some(140.0e4)));
    let t = neck.limits(Some(muscle), ContactKind::Transient).unwrap();
    assert_eq!((t.force, t.pressure), (300.0, Some(280.0e4)));
    assert_eq!(neck.human_mass(ContactKind::Transient), 1.2);
    assert_eq!(neck.human_mass(ContactKind::QuasiStatic), f64::INFINITY);
    let hand = model.region("hands_and_fingers").unwrap();
    assert_eq!(hand.most_sensitive_area().name(), "Back of the hand ND");
}

#[test]
fn transient_head_and_face_contact_is_refused_citing_the_clause() {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    for key in ["skull_and_forehead", "face"] {
        let region = model.region(key).unwrap();
        let area = &region.areas()[0];
        let err = region
            .limits(Some(area), ContactKind::Transient)
            .unwrap_err();
        assert!(
            matches!(err, SafetyError::ContactNotPermitted { .. }),
            "{err}"
        );
        let text = err.to_string();
        assert!(
            text.contains("5.5.5.4") && text.contains(region.name()),
            "{text}"
        );
        assert!(err.is_input_error());
        // Quasi-static contact is evaluated.
        assert_eq!(
            region
                .limits(Some(area), ContactKind::QuasiStatic)
                .unwrap()
                .force,
            region.max_force_n()
        );
    }
}

#[test]
fn unknown_region_and_area_list_the_known_ones() {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let e = model.region("elbow").unwrap_err().to_string();
    assert!(
        e.contains("elbow") && e.contains("hands_and_fingers"),
        "{e}"
    );
    let e = model
        .region("neck")
        .unwrap()
        .area("larynx")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("larynx") && e.contains("Seventh neck muscle"),
        "{e}"
    );
}

/// Edits the bundled table and loads it.
fn load_edited(edit: impl FnOnce(&mut Value)) -> Result<BodyModel, SafetyError> {
    let mut raw = file();
    edit(&mut raw);
    BodyModel::from_toml_str(&toml::to_string(&raw).unwrap())
}

fn region_mut<'a>(raw: &'a mut Value, key: &str) -> &'a mut toml::Table {
    raw["region"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|r| r["key"].as_str() == Some(key))
        .unwrap()
        .as_table_mut()
        .unwrap()
}

fn assert_names(err: SafetyError, region: &str, field: &str) {
    let text = err.to_string();
    assert!(text.contains(region) && text.contains(field), "{text}");
    assert!(err.is_input_error());
}

#[test]
fn a_user_table_in_the_same_format_loads() {
    let model = load_edited(|raw| {
        region_mut(raw, "neck").insert("transient_max_force_n".into(), Value::Float(250.0));
    })
    .unwrap();
    let neck = model.region("neck").unwrap();
    assert_eq!(neck.force_limit(ContactKind::Transient).unwrap(), 250.0);
}

#[test]
fn a_missing_field_is_refused_naming_region_and_field() {
    for field in [
        "max_force_n",
        "spring_constant_n_per_mm",
        "effective_mass_kg",
        "transient_permitted",
        "transient_force_multiplier",
        "source",
    ] {
        let err = load_edited(|raw| {
            region_mut(raw, "chest").remove(field);
        })
        .unwrap_err();
        assert!(matches!(err, SafetyError::MissingField { .. }), "{err}");
        assert_names(err, "chest", field);
    }
    let err = load_edited(|raw| {
        let areas = region_mut(raw, "pelvis")["area"].as_array_mut().unwrap();
        areas[0]
            .as_table_mut()
            .unwrap()
            .remove("max_pressure_n_per_cm2");
    })
    .unwrap_err();
    assert_names(err, "pelvis", "area[0].max_pressure_n_per_cm2");
    let err = load_edited(|raw| {
        region_mut(raw, "face").remove("transient_not_permitted_clause");
    })
    .unwrap_err();
    assert_names(err, "face", "transient_not_permitted_clause");
}

#[test]
fn a_negative_or_zero_limit_is_refused_naming_region_and_field() {
    for (field, value) in [
        ("max_force_n", -140.0),
        ("max_force_n", 0.0),
        ("spring_constant_n_per_mm", -75.0),
        ("effective_mass_kg", 0.0),
        ("transient_force_multiplier", -2.0),
    ] {
        let err = load_edited(|raw| {
            region_mut(raw, "hands_and_fingers").insert(field.into(), Value::Float(value));
        })
        .unwrap_err();
        assert!(matches!(err, SafetyError::InvalidField { .. }), "{err}");
        assert_names(err, "hands_and_fingers", field);
    }
    let err = load_edited(|raw| {
        let areas = region_mut(raw, "lower_legs")["area"]
            .as_array_mut()
            .unwrap();
        areas[1]
            .as_table_mut()
            .unwrap()
            .insert("max_pressure_n_per_cm2".into(), Value::Float(-210.0));
    })
    .unwrap_err();
    assert_names(err, "lower_legs", "area[1].max_pressure_n_per_cm2");
    assert!(err_text_has_value(
        load_edited(|raw| {
            region_mut(raw, "abdomen").insert("max_force_n".into(), Value::Float(-1.5));
        }),
        "-1.5"
    ));
}

fn err_text_has_value(r: Result<BodyModel, SafetyError>, value: &str) -> bool {
    r.unwrap_err().to_string().contains(value)
}

#[test]
fn contradictory_transient_fields_and_syntax_errors_are_refused() {
    let err = load_edited(|raw| {
        region_mut(raw, "face").insert("transient_force_multiplier".into(), Value::Float(2.0));
    })
    .unwrap_err();
    assert_names(err, "face", "transient_force_multiplier");
    let err = load_edited(|raw| {
        region_mut(raw, "neck").insert("max_forse_n".into(), Value::Float(2.0));
    })
    .unwrap_err();
    assert!(err.to_string().contains("max_forse_n"), "{err}");
    let err = load_edited(|raw| {
        let regions = raw["region"].as_array_mut().unwrap();
        let first = regions[0].clone();
        regions.push(first);
    })
    .unwrap_err();
    assert_names(err, "skull_and_forehead", "key");
    assert!(matches!(
        BodyModel::from_toml_str("[document]\ntitle = \"x\"\nedition = \"y\"\ntables = \"z\"\n"),
        Err(SafetyError::BodyModelSyntax(_))
    ));
    assert!(BodyModel::from_toml_str("not toml [").is_err());
}
