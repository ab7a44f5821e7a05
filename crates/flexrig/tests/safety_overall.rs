//! The overall verdict of `flexrig safety`: the most restrictive method governs and is named,
//! a speed fails when any method fails it, the simulation runs by default whenever the design
//! is known, no default length changes an answer silently, and the energy method warns when its
//! answer needs a deflection the link cannot make. The governing speed is held against the
//! independent re-contact reference (scripts/reference_recontact.py, fixture
//! `tests/fixtures/recontact.json`).

use flexrig::safety::{
    ContactKind, ContactLaw, FeLink, MapJoint, RobotEffectiveMass, SafetyInput, SafetyMethod,
    SimulationSettings, default_methods, safety,
};
use serde_json::Value;

const FIXTURE: &str = include_str!("fixtures/recontact.json");

/// The light-payload hand on a soft CJ link of the re-contact fixture: m_r = 51 g, m_e = 10 g,
/// k_δ = 2e4 N/m, the skin k_c = 7.359e7 N/m², n = 2.
fn hand(methods: Vec<SafetyMethod>, speed: Option<f64>) -> SafetyInput {
    SafetyInput {
        region: "hands_and_fingers".into(),
        area: None,
        contact: ContactKind::Transient,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma: 1.0,
            m_r: 0.051,
            m_e: 0.01,
        }),
        k_delta: Some(2e4),
        law: ContactLaw::Hertz {
            k_c: 7.359e7,
            n: 2.0,
        },
        area_model: None,
        moving_mass: None,
        payload: 0.0,
        speed,
        methods,
        link: Some(FeLink::CompliantJoint),
        simulation: None,
        scene: None,
    }
}

fn reference_speed() -> f64 {
    let v: Value = serde_json::from_str(FIXTURE).unwrap();
    v["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["link"] == "cj" && c["m_e"].as_f64() == Some(0.01) && c["k_delta"] == 20000.0)
        .unwrap()["permissible_speed_mps"]
        .as_f64()
        .unwrap()
}

/// Without `--method` the hand's design is known (m_r, m_e, the CJ), so all three methods run;
/// the simulation's speed is the smallest and governs, within 1e-4 of the independent
/// re-contact reference (1.58256 m/s, against 6.4 m/s by the standard and 12.9 m/s by the energy
/// method); at 2 m/s the standard and the energy method pass and the simulation fails, so the
/// overall verdict is FAIL, failed by the simulation alone.
#[test]
fn the_most_restrictive_method_governs_and_one_failing_method_fails_the_speed() {
    let r = safety(&hand(Vec::new(), Some(2.0)), None).unwrap();
    let methods: Vec<SafetyMethod> = r.methods.iter().map(|m| m.method).collect();
    assert_eq!(
        methods,
        [
            SafetyMethod::Standard,
            SafetyMethod::Energy,
            SafetyMethod::Simulation
        ]
    );
    let o = &r.overall;
    assert_eq!(o.method, SafetyMethod::Simulation);
    let expected = reference_speed();
    let v = o.v_max_mps.value();
    assert!((v / expected - 1.0).abs() < 1e-4, "{v} against {expected}");
    for m in &r.methods {
        assert!(m.v_max_mps.value() >= v, "{:?} below the overall", m.method);
    }
    assert_eq!(o.pass, Some(false));
    assert_eq!(o.failed_by, [SafetyMethod::Simulation]);
    assert_eq!(o.speed_mps, Some(2.0));
    assert!(o.reason.contains("the simulation"), "{}", o.reason);
    // below the reference speed every method passes
    let r = safety(&hand(Vec::new(), Some(0.95 * expected)), None).unwrap();
    assert_eq!(r.overall.pass, Some(true));
    assert!(r.overall.failed_by.is_empty());
}

/// The default methods: the simulation joins whenever the link is known (a link kind, or γ of 1
/// or 2/3 with m_r and m_e), not with an effective mass alone.
#[test]
fn the_simulation_runs_by_default_when_the_design_is_known() {
    let mut i = hand(Vec::new(), None);
    assert!(default_methods(&i).contains(&SafetyMethod::Simulation));
    i.link = None;
    assert!(default_methods(&i).contains(&SafetyMethod::Simulation));
    i.m_eff = Some(RobotEffectiveMass::Prb {
        gamma: 0.8,
        m_r: 0.051,
        m_e: 0.01,
    });
    assert!(!default_methods(&i).contains(&SafetyMethod::Simulation));
    i.m_eff = Some(RobotEffectiveMass::Given(2.0));
    assert_eq!(
        default_methods(&i),
        [SafetyMethod::Standard, SafetyMethod::Energy]
    );
    let r = safety(&i, None).unwrap();
    assert_eq!(r.methods.len(), 2);
    // the standard and the energy method with the body's own spring agree: the tie goes to the
    // energy method, the more complete model
    i.law = ContactLaw::BodySpring;
    i.k_delta = None;
    let r = safety(&i, None).unwrap();
    let (a, b) = (
        r.methods[0].v_max_mps.value(),
        r.methods[1].v_max_mps.value(),
    );
    assert!((a / b - 1.0).abs() < 1e-12, "{a} vs {b}");
    assert_eq!(r.overall.method, SafetyMethod::Energy);
}

/// A free hub's rotor acts at the contact as J_R/L², so its answer depends on the length: no
/// default length is taken, the error names `--length`; given, the answer moves with it.
#[test]
fn a_free_hub_needs_the_length_it_depends_on() {
    let mut i = hand(vec![SafetyMethod::Simulation], None);
    i.simulation = Some(SimulationSettings {
        joint: MapJoint::FreeHub {
            rotor_inertia: 0.01,
        },
        ..SimulationSettings::DEFAULT
    });
    let e = safety(&i, None).unwrap_err().to_string();
    assert!(e.contains("--length"), "{e}");
    let at = |l: f64| {
        let mut i = i.clone();
        i.simulation = Some(SimulationSettings {
            length: Some(l),
            ..i.simulation.unwrap()
        });
        safety(&i, None).unwrap().overall.v_max_mps.value()
    };
    let (short, long) = (at(0.3), at(1.0));
    assert!(
        short < long,
        "a shorter link reflects more rotor: {short} vs {long}"
    );
}

/// The energy method's speed stores the limit's force in the link's spring: the test bed's iron
/// CL at the abdomen (220 N) needs F/k_δ = 220 N / k_δ, metres of deflection of a 0.338 m link,
/// and says so; the stiff hand design does not warn.
#[test]
fn the_energy_method_warns_when_its_speed_needs_a_deflection_longer_than_the_link() {
    let i = SafetyInput {
        region: "abdomen".into(),
        scene: Some("cl_iron".into()),
        methods: vec![SafetyMethod::Standard, SafetyMethod::Energy],
        ..hand(Vec::new(), None)
    };
    let i = SafetyInput {
        m_eff: None,
        k_delta: None,
        law: ContactLaw::BodySpring,
        link: None,
        ..i
    };
    let r = safety(&i, None).unwrap();
    let k = r.k_delta_n_per_m.unwrap();
    let deflection = r.force_limit_n / k;
    assert!(deflection > 0.338, "{deflection}");
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    let w = &r.warnings[0].message;
    assert_eq!(r.warnings[0].field, "--k-delta");
    assert!(
        w.contains("energy method") && w.contains(&flexrig_contact::validate::display(deflection)),
        "{w}"
    );
    let r = safety(&hand(vec![SafetyMethod::Energy], None), None).unwrap();
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
}

/// A chattering impact — the 10 g payload on a 10 N/m CL link against the hand, about 90
/// contacts — where at 4.747399787031045 m/s the tip re-engages the instant it separates: the
/// onset search must find the next contact after the gap's dip, not the separation itself (it
/// once stood still there until the step budget ran out, failing the safe-speed map's first
/// cell). The run now parts for good within a second of simulated time.
#[test]
fn a_tip_that_re_engages_as_it_separates_is_followed_to_the_end() {
    use flexrig::safety::simulation::FeImpact;
    let impact = FeImpact {
        m_h: 0.6,
        hertz: flexrig_contact::Hertz::new(7.359e7, 1.961).unwrap(),
        m_r: 0.051,
        m_e: 0.01,
        k_delta: 10.0,
        link: FeLink::CompliantLink,
        settings: SimulationSettings::DEFAULT,
    };
    let mut runs = impact.prepare(1.0).unwrap();
    let stop = std::sync::atomic::AtomicBool::new(false);
    let p = runs.impact_at(4.747399787031045, &stop).unwrap();
    assert!(p.contacts > 20, "{p:?}");
    assert!(p.parted_at_s > 0.0 && p.parted_at_s < 1.0, "{p:?}");
    assert!(p.peak_force_n.is_finite() && p.peak_force_n > 0.0, "{p:?}");
}

/// The report runs the default methods as `flexrig safety` does (no `--method` given) and leads
/// with the overall verdict.
#[test]
fn a_report_without_methods_runs_the_default_ones_and_leads_with_the_overall_verdict() {
    let dir = std::env::temp_dir().join(format!("flexrig-overall-{}", std::process::id()));
    let path = dir.join("hand.md");
    let (r, files) = flexrig::safety::report::write_report(
        &hand(Vec::new(), Some(2.0)),
        None,
        &path,
        false,
        &flexrig::CancelToken::new(),
    )
    .unwrap();
    assert_eq!(r.methods.len(), 3);
    let text = std::fs::read_to_string(&path).unwrap();
    let verdict = text.find("Overall: the permissible speed is").unwrap();
    assert!(verdict < text.find("## Inputs").unwrap());
    assert!(text[verdict..].contains("FAILS (failed by the simulation)"));
    for f in files {
        std::fs::remove_file(f).unwrap();
    }
    std::fs::remove_dir(&dir).unwrap();
}
