//! Every contact counts: a light payload on a soft link (held joint) strikes a free hand again,
//! and the later contact is the larger one. The permissible speed of the simulation method and
//! the contacts it sees are held against an independent computation written from the equations
//! (`scripts/reference_recontact.py`: scipy's DOP853 with event location on the CJ's two masses
//! and on the CL's analytic clamped-free beam modes; fixture `tests/fixtures/recontact.json`).

use flexrig::safety::{
    ContactKind, ContactLaw, FeLink, RobotEffectiveMass, SafetyInput, SafetyMethod,
    SimulationSettings, safety,
};
use serde_json::Value;

const FIXTURE: &str = include_str!("fixtures/recontact.json");

fn input(case: &Value, speed: Option<f64>) -> SafetyInput {
    let f = |k: &str| case[k].as_f64().unwrap();
    SafetyInput {
        region: case["region"].as_str().unwrap().into(),
        area: None,
        contact: ContactKind::Transient,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma: if case["link"] == "cj" { 1.0 } else { 2.0 / 3.0 },
            m_r: f("m_r"),
            m_e: f("m_e"),
        }),
        k_delta: Some(f("k_delta")),
        law: ContactLaw::Hertz {
            k_c: f("k_c"),
            n: f("n"),
        },
        area_model: None,
        moving_mass: None,
        payload: 0.0,
        speed,
        methods: vec![SafetyMethod::Simulation],
        link: Some(if case["link"] == "cj" {
            FeLink::CompliantJoint
        } else {
            FeLink::CompliantLink
        }),
        simulation: Some(SimulationSettings::DEFAULT),
        scene: None,
    }
}

fn cases() -> Vec<Value> {
    let v: Value = serde_json::from_str(FIXTURE).unwrap();
    v["cases"].as_array().unwrap().clone()
}

/// The permissible speed within 1e-3 of the independent computation's (which scans by 2 % steps
/// from its own energy floor and refines by brentq), CJ and CL; a direct run at that speed
/// reaches the limit within 1e-4, in the contact the answer names.
#[test]
fn with_recontact_the_permissible_speed_matches_an_independent_computation() {
    for case in cases() {
        let link = case["link"].as_str().unwrap();
        let expected = case["permissible_speed_mps"].as_f64().unwrap();
        let limit = case["force_limit_n"].as_f64().unwrap();
        let r = safety(&input(&case, None), None).unwrap();
        let m = &r.methods[0];
        let v = m.v_max_mps.value();
        let err = (v / expected - 1.0).abs();
        assert!(err < 1e-3, "{link}: {v} m/s against {expected} ({err:e})");
        let at = m.governing_contact.expect("the contact at the limit");
        let reach = (at.peak_force_n / limit - 1.0).abs();
        assert!(reach < 1e-4, "{link}: {} N at v_max ({reach:e})", at.peak_force_n);
    }
}

/// At 2 and 3 m/s every contact's peak agrees with the reference's within 1e-4 (the largest
/// one, and which one it is); the verdict fails whenever the largest exceeds the limit.
#[test]
fn every_contact_is_followed_and_the_verdict_fails_on_any_contact_over_the_limit() {
    for case in cases() {
        let link = case["link"].as_str().unwrap();
        let limit = case["force_limit_n"].as_f64().unwrap();
        for (speed, at) in case["at_speed"].as_object().unwrap() {
            let speed: f64 = speed.parse().unwrap();
            let contacts = at["contacts"].as_array().unwrap();
            let peaks: Vec<f64> = contacts
                .iter()
                .map(|c| c["peak_force_n"].as_f64().unwrap())
                .collect();
            let (index, largest) = peaks
                .iter()
                .copied()
                .enumerate()
                .fold((0, 0.0), |b, (i, p)| if p > b.1 { (i, p) } else { b });
            let r = safety(&input(&case, Some(speed)), None).unwrap();
            let v = r.methods[0].verdict.unwrap();
            let c = v.governing_contact.unwrap();
            let err = (c.peak_force_n / largest - 1.0).abs();
            assert!(
                err < 1e-4,
                "{link} at {speed}: {} N against {largest} ({err:e})",
                c.peak_force_n
            );
            assert_eq!(c.contact, index + 1, "{link} at {speed}: the governing contact");
            assert_eq!(c.contacts, peaks.len(), "{link} at {speed}: contacts");
            assert_eq!(v.pass, largest <= limit, "{link} at {speed}");
            assert!(!v.pass || v.peak_force_n <= limit);
        }
    }
}
