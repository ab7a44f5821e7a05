//! A measured impact, judged (`flexrig::safety::measured`), against independent references: a
//! sampled half-sine's HIC against its closed form (derived below), its force, energy and
//! verdict by hand; a driven run's own exported trace read back gives the run's severity; bad
//! CSV files are refused naming the line; areas with their units and the warnings about
//! implausible ones; the transferred energy of each method's verdict against Eq. A.1–A.2 and the
//! energy balance of series springs.

use std::f64::consts::PI;
use std::path::PathBuf;

use flexrig::CancelToken;
use flexrig::driven::scene::{DrivenScene, run};
use flexrig::driven::strike::trace_text;
use flexrig::safety::measured::{
    EnergyBasis, TraceInput, area_warnings, judge_trace, measured_severity, parse_area,
    parse_trace_csv, read_trace,
};
use flexrig::safety::{
    ContactAreaModel, ContactKind, ContactLaw, RobotEffectiveMass, SafetyInput, SafetyMethod,
    safety,
};
use flexrig_contact::tolerance::assert_close;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("flexrig-measured-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// HIC of the half-sine a(t) = A sin(πt/T) (A in g, T in s) with windows up to `window` s, in
/// closed form. A window centred on the peak with half-width φ in phase (Δ = 2φT/π) has
/// ∫a dt = (2AT/π) sin φ, so its mean is A sin φ/φ and HIC(φ) = Δ (A sin φ/φ)^2.5 =
/// (2T/π) A^2.5 sin^2.5 φ / φ^1.5; d ln HIC/dφ = 2.5 cot φ − 1.5/φ vanishes at tan φ = 5φ/3
/// (φ* ≈ 1.0528, found here by bisection) and is positive below: the best window is φ*, or the
/// longest allowed, φ = πΔ_max/(2T), when that is shorter. (A centred window beats a shifted
/// one of the same length: the pulse is symmetric and concave.)
fn half_sine_hic(a_g: f64, t: f64, window: f64) -> f64 {
    let (mut lo, mut hi) = (0.5, 1.5);
    let g = |p: f64| p.tan() - 5.0 * p / 3.0;
    assert!(g(lo) < 0.0 && g(hi) > 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let phi = lo.min(PI * window / (2.0 * t));
    (2.0 * t / PI) * a_g.powf(2.5) * phi.sin().powf(2.5) / phi.powf(1.5)
}

/// A half-sine pulse of force `f0` \[N\], acceleration `a_g` \[g\] and indentation `d_mm` \[mm\]
/// over `t_ms` \[ms\], `intervals` + 1 samples, in the units of the header.
fn half_sine_csv(f0: f64, a_g: f64, d_mm: f64, t_ms: f64, intervals: usize) -> String {
    let mut text = String::from("# a half-sine pulse\nt [ms], F [N], a [g], delta [mm]\n");
    for i in 0..=intervals {
        let t = t_ms * i as f64 / intervals as f64;
        let s = (PI * i as f64 / intervals as f64).sin();
        text.push_str(&format!(
            "{t:?}, {:?}, {:?}, {:?}\n",
            f0 * s,
            a_g * s,
            d_mm * s
        ));
    }
    text
}

#[test]
fn a_sampled_half_sine_has_the_closed_form_hic_force_and_energy() {
    // T = 30 ms: HIC15's window binds (15 ms < 0.670 T = 20.1 ms), HIC36's does not
    let (f0, a_g, d_mm, t_ms) = (250.0, 60.0, 2.0, 30.0);
    let dir = scratch("half_sine");
    let path = dir.join("half_sine.csv");
    std::fs::write(&path, half_sine_csv(f0, a_g, d_mm, t_ms, 4000)).unwrap();
    let input = TraceInput {
        trace: path.clone(),
        region: "chest".into(),
        area: None,
        contact: ContactKind::Transient,
        area_model: Some(ContactAreaModel::Fixed { area_m2: 2e-4 }),
    };
    let r = judge_trace(&input, None).unwrap();
    let s = &r.severity;
    let t = t_ms * 1e-3;
    for (name, hic, window) in [("HIC15", s.hic15, 0.015), ("HIC36", s.hic36, 0.036)] {
        assert_close(name, hic.unwrap().hic, half_sine_hic(a_g, t, window), 1e-6);
    }
    let h15 = s.hic15.unwrap();
    assert_close("HIC15 window", h15.t2_s - h15.t1_s, 0.015, 1e-9);
    assert_close("peak force", s.peak_force_n, f0, 1e-15);
    assert_close("time of the peak", s.time_of_peak_force_s, 0.5 * t, 1e-12);
    assert_close(
        "peak acceleration",
        s.peak_acceleration_g.unwrap(),
        a_g,
        1e-15,
    );
    // f = (F0/D) δ on loading: ∫₀^D f dδ = F0 D/2, exact for the trapezoid on a straight line
    assert_eq!(s.energy_transferred_from, EnergyBasis::ForceAndIndentation);
    assert_close(
        "energy",
        s.energy_transferred_j,
        0.5 * f0 * d_mm * 1e-3,
        1e-12,
    );
    assert!(s.contact_work_j.unwrap().abs() < 1e-12 * s.energy_transferred_j);
    // chest (Table A.2): transient 2 × 140 N; sternum 2 × 120 N/cm²; A = 2 cm²
    assert_eq!(r.force_limit_n, 280.0);
    assert_close("margin", r.verdict.force_margin, 1.0 - f0 / 280.0, 1e-15);
    assert_close(
        "pressure margin",
        r.verdict.pressure_margin.unwrap(),
        1.0 - f0 / 2e-4 / 240e4,
        1e-15,
    );
    assert!(r.verdict.pass && r.verdict.pressure_assessed);
    // the standard's energy at the force limit: F²/(2K), K = 25 N/mm
    assert_close(
        "energy limit",
        r.energy_limit_j,
        280.0f64.powi(2) / 5e4,
        1e-15,
    );
    // the same pulse at 300 N fails; without an indentation the energy is F²/(2K)
    let text = half_sine_csv(300.0, a_g, d_mm, t_ms, 400);
    let no_delta: String = text
        .lines()
        .map(|l| match l.rsplit_once(',') {
            Some((head, _)) if !l.starts_with('#') => format!("{head}\n"),
            _ => format!("{l}\n"),
        })
        .collect();
    std::fs::write(&path, no_delta).unwrap();
    let r = judge_trace(&input, None).unwrap();
    assert!(!r.verdict.pass && r.verdict.force_margin < 0.0);
    assert_eq!(
        r.severity.energy_transferred_from,
        EnergyBasis::BodySpringAtPeakForce
    );
    assert_close(
        "body-spring energy",
        r.severity.energy_transferred_j,
        300.0f64.powi(2) / 5e4,
        1e-15,
    );
    assert!(r.severity.contact_work_j.is_none());
    // a dome needs the indentation: refused naming the area model
    let e = judge_trace(
        &TraceInput {
            area_model: Some(ContactAreaModel::HertzSphere { radius_m: 0.0715 }),
            ..input.clone()
        },
        None,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("--area-model") && e.contains("indentation"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_severity_of_a_driven_runs_exported_trace_is_the_runs_severity() {
    for text in [
        include_str!("../../../assets/scenes/driven_cj_free_head.toml"),
        include_str!("../../../assets/scenes/driven_cl_free_head.toml"),
    ] {
        let scene = DrivenScene::parse(text).unwrap();
        let done = run(&scene, &CancelToken::new()).unwrap();
        let expected = done.summary.severity.clone().expect("a severity");
        assert!(expected.hic15.is_some() && expected.pressure.len() == 2);
        // the existing export (`flexrig strike --trace-every … --out`), read back as it is
        let dir = scratch("driven");
        let path = dir.join("strike_trace.csv");
        std::fs::write(&path, trace_text(&done.outcome.trace)).unwrap();
        let trace = read_trace("--trace", &path).unwrap();
        assert_eq!(trace.times_s.len(), done.outcome.trace.len());
        assert_eq!(
            trace.ignored_columns,
            [
                "hub_angle_rad",
                "hub_speed_rad_s",
                "tip_deflection_m",
                "joint_torque_nm",
                "head_position_m"
            ]
        );
        let areas = ContactAreaModel::dome_models_for_exponent(
            flexrig::shared::severity::paper_dome_radius_m().unwrap(),
            scene.strike.person.contact.n(),
        );
        let measured = measured_severity(&trace, &areas, 25e3, "--area-model").unwrap();
        assert_eq!(measured.as_run_severity().unwrap(), expected);
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn a_bad_csv_is_refused_naming_the_line() {
    let cases: [(&str, &[&str]); 12] = [
        ("t, F [N]\n0, 1\n", &["line 1", "\"t\"", "no unit", "[s]"]),
        ("t [s], F [lbf]\n0, 1\n", &["line 1", "lbf", "N, kN"]),
        (
            "t [s], F [N]\n0, 1\n0.001, x\n",
            &["line 3", "F [N]", "\"x\""],
        ),
        (
            "t [s], F [N]\n0, 1\n0.001, nan\n",
            &["line 3", "not a finite"],
        ),
        (
            "t [s], F [N]\n0, 1\n# note\n0, 2\n",
            &["line 4", "line 2", "increase strictly"],
        ),
        (
            "t [s], F [N]\n0, 1, 2\n",
            &["line 2", "3 fields", "2 columns"],
        ),
        ("t [s], a [g]\n0, 1\n", &["line 1", "no force column"]),
        ("time [s], force [N]\n0, 1\n", &["1 sample", "at least two"]),
        ("0, 1\n0.1, 2\n", &["line 1", "header"]),
        ("\u{feff}# only a comment\n\n", &["no header"]),
        ("t [s], F [N], f [kN]\n", &["line 1", "two force columns"]),
        ("t [ms], F [N]\n1, 1\n2, 1\nx\n", &["line 4", "1 fields"]),
    ];
    for (text, expected) in cases {
        let e = parse_trace_csv(text).unwrap_err();
        for part in expected {
            assert!(e.contains(part), "{text:?}: {e:?} lacks {part:?}");
        }
    }
    // the accepted header forms, and the units converted to SI
    let t = parse_trace_csv(
        "time (ms), contact force [kN], head_acceleration_mps2, indentation [um], note\n\
         0, 0.5, -9.5, 10, a\n2, 1, 3, 20, b\n",
    )
    .unwrap();
    assert_eq!(t.times_s, [0.0, 2e-3]);
    assert_eq!(t.force_n, [500.0, 1000.0]);
    assert_eq!(t.acceleration_mps2.unwrap(), [-9.5, 3.0]);
    assert_eq!(t.indentation_m.unwrap(), [10.0 * 1e-6, 20.0 * 1e-6]);
    assert_eq!(t.ignored_columns, ["note"]);
    // a missing file names it
    let e = read_trace("--trace", std::path::Path::new("no/such/trace.csv"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no/such/trace.csv"), "{e}");
}

#[test]
fn areas_carry_their_unit_and_implausible_ones_are_warned_about() {
    assert_eq!(parse_area("--contact-area", "1cm2").unwrap(), 1e-4);
    assert_eq!(parse_area("--contact-area", "1 cm²").unwrap(), 1e-4);
    assert_eq!(parse_area("--contact-area", "1e-4m2").unwrap(), 1e-4);
    assert_close(
        "mm²",
        parse_area("--contact-area", "100mm2").unwrap(),
        1e-4,
        1e-15,
    );
    for bad in ["1", "1e-4", "-1cm2", "0cm2", "cm2", "1 acre", "infm2"] {
        let e = parse_area("--contact-area", bad).unwrap_err().to_string();
        assert!(
            e.contains("--contact-area") && e.contains("1cm2"),
            "{bad}: {e}"
        );
    }
    let warned = |m: ContactAreaModel| area_warnings(Some(&m), "--contact-area", "--radius");
    assert!(warned(ContactAreaModel::Fixed { area_m2: 1e-4 }).is_empty());
    assert!(warned(ContactAreaModel::Fixed { area_m2: 99e-4 }).is_empty());
    assert!(warned(ContactAreaModel::Fixed { area_m2: 0.02e-4 }).is_empty());
    let w = warned(ContactAreaModel::Fixed { area_m2: 1.0 });
    assert!(w.len() == 1 && w[0].message.contains("10000 cm²"), "{w:?}");
    let w = warned(ContactAreaModel::Fixed { area_m2: 1e-8 });
    assert!(w.len() == 1 && w[0].field == "--contact-area", "{w:?}");
    let w = warned(ContactAreaModel::HertzSphere { radius_m: 71.5 });
    assert!(w.len() == 1 && w[0].field == "--radius", "{w:?}");
    assert!(warned(ContactAreaModel::ThinLayer { radius_m: 0.0715 }).is_empty());
}

fn chest(law: ContactLaw, k_delta: Option<f64>, area: Option<ContactAreaModel>) -> SafetyInput {
    SafetyInput {
        region: "chest".into(),
        area: None,
        contact: ContactKind::Transient,
        m_eff: Some(RobotEffectiveMass::Given(3.0)),
        k_delta,
        law,
        area_model: area,
        moving_mass: None,
        payload: 0.0,
        speed: Some(0.8),
        methods: vec![SafetyMethod::Standard, SafetyMethod::Energy],
        link: None,
        simulation: None,
        scene: None,
    }
}

#[test]
fn every_method_states_the_transferred_energy_and_whether_it_judged_the_pressure() {
    // chest: m_H = 40 kg, K = 25 N/mm, 280 N; m_R = 3 kg
    let mu = 1.0 / (1.0 / 40.0 + 1.0 / 3.0);
    let v: f64 = 0.8;
    let hertz = ContactLaw::Hertz {
        k_c: 7.359e7,
        n: 1.961,
    };
    let r = safety(&chest(hertz.clone(), Some(2e4), None), None).unwrap();
    let standard = &r.methods[0];
    // Eq. A.2: the standard's body spring takes the whole ½ μ v²; at v_max F²/(2K) (Eq. A.1)
    let sv = standard.verdict.unwrap();
    assert_close("standard", sv.energy_transferred_j, 0.5 * mu * v * v, 1e-12);
    assert_close(
        "standard at v_max",
        standard.energy_transferred_at_v_max_j.unwrap(),
        280.0f64.powi(2) / 5e4,
        1e-12,
    );
    // the energy method: the skin's share of ½ μ v², the link spring holding F²/(2k_δ)
    let energy = &r.methods[1];
    let ev = energy.verdict.unwrap();
    assert_close(
        "skin + link",
        ev.energy_transferred_j + ev.peak_force_n.powi(2) / 4e4,
        0.5 * mu * v * v,
        1e-9,
    );
    // without a contact geometry neither judges the pressure
    assert!(!standard.pressure_assessed && !energy.pressure_assessed);
    // the skin's dome: the energy method judges it, the standard's formula needs a fixed area
    let dome = Some(ContactAreaModel::HertzSphere { radius_m: 0.0715 });
    let r = safety(&chest(hertz, None, dome), None).unwrap();
    assert!(!r.methods[0].pressure_assessed && r.methods[1].pressure_assessed);
    let fixed = Some(ContactAreaModel::Fixed { area_m2: 1e-4 });
    let r = safety(&chest(ContactLaw::BodySpring, None, fixed), None).unwrap();
    assert!(r.methods.iter().all(|m| m.pressure_assessed));
    // a linear contact has no geometry: a dome's area model is refused, naming the flag
    let e = safety(&chest(ContactLaw::BodySpring, None, dome), None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("--area-model") && e.contains("n > 1"), "{e}");
    // an implausible area is warned about
    let huge = Some(ContactAreaModel::Fixed { area_m2: 1.0 });
    let r = safety(&chest(ContactLaw::BodySpring, None, huge), None).unwrap();
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
}
