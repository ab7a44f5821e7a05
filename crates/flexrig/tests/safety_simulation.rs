//! The simulation method of `flexrig safety` runs the finite-element impact of the safe-speed
//! maps: with a linear contact (n = 1, the body region's own spring) and a rigid link on a
//! free hub it converges to the standard's formula (the robot is then one rigid body of tip
//! mass m_e + m_r/3 + J_R/L²), transient and clamped, CJ and CL; and at a map's design it is
//! the map's cell.

use flexrig::CancelToken;
use flexrig::safety::map::{MapAxis, MapMethod, MapParameter, SafetyMapInput, safety_map};
use flexrig::safety::{
    ContactKind, ContactLaw, FeLink, MapJoint, RobotEffectiveMass, SafetyInput, SafetyMethod,
    SimulationSettings, safety,
};
use flexrig_safety::BodyModel;

const M_R: f64 = 2.0;
const M_E: f64 = 1.0;
const J_R: f64 = 0.05;

fn input(region: &str, contact: ContactKind, link: FeLink, joint: MapJoint) -> SafetyInput {
    SafetyInput {
        region: region.into(),
        area: None,
        contact,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma: 1.0,
            m_r: M_R,
            m_e: M_E,
        }),
        k_delta: None,
        law: ContactLaw::BodySpring,
        area_model: None,
        moving_mass: None,
        payload: 0.0,
        speed: None,
        methods: vec![SafetyMethod::Simulation],
        link: Some(link),
        simulation: Some(SimulationSettings {
            joint,
            length: Some(1.0),
            ..SimulationSettings::DEFAULT
        }),
        scene: None,
    }
}

/// The standard's v = F_max/√(μK) (Eq. A.5) with m_R = m_e + m_r/3 + J_R/L² (L = 1 m) by hand.
fn standard_by_hand(region: &str, contact: ContactKind) -> f64 {
    let model = BodyModel::iso_ts_15066_2016().unwrap();
    let r = model.region(region).unwrap();
    let limits = r.limits(None, contact).unwrap();
    let m_robot = M_E + M_R / 3.0 + J_R;
    let m_h = r.human_mass(contact);
    let mu = if m_h.is_finite() {
        1.0 / (1.0 / m_h + 1.0 / m_robot)
    } else {
        m_robot
    };
    limits.force / (mu * r.spring_constant()).sqrt()
}

/// Transient (chest, hand) and clamped (chest, quasi-static, m_h = 1e9 kg) contact, CJ and CL,
/// free hub, n = 1, rigid link (k_δ = 1e12 N/m): the simulated speed is the standard's within
/// 1e-6. What separates them: the root search (1e-6 on the bracket, the last iterate far
/// closer), the CJ's DOP853 (1e-10) and the CL's force hold (1e-6 per step), the link's
/// energy share K/k_δ ≤ 7.5e-8 and the clamped body's m_R/m_h ≤ 2e-9.
#[test]
fn with_n_1_and_a_rigid_link_the_simulation_converges_to_the_standard_formula() {
    let joint = MapJoint::FreeHub { rotor_inertia: J_R };
    for (region, contact) in [
        ("chest", ContactKind::Transient),
        ("hands_and_fingers", ContactKind::Transient),
        ("chest", ContactKind::QuasiStatic),
    ] {
        let expected = standard_by_hand(region, contact);
        for link in [FeLink::CompliantJoint, FeLink::CompliantLink] {
            let r = safety(&input(region, contact, link, joint), None).unwrap();
            let v = r.methods[0].by_force_mps.value();
            let err = (v / expected - 1.0).abs();
            assert!(
                err < 1e-6,
                "{region} {contact:?} {link:?}: {v} against {expected} ({err:e})"
            );
        }
    }
}

/// A held joint cannot clamp (no bounded peak): refused naming --contact; a γ that implies no
/// link needs --link.
#[test]
fn clamping_needs_the_free_hub_and_the_link_must_be_known() {
    let mut i = input(
        "chest",
        ContactKind::QuasiStatic,
        FeLink::CompliantJoint,
        MapJoint::Held,
    );
    let e = safety(&i, None).unwrap_err().to_string();
    assert!(e.contains("--contact") && e.contains("free-hub"), "{e}");
    i.contact = ContactKind::Transient;
    i.link = None;
    i.m_eff = Some(RobotEffectiveMass::Prb {
        gamma: 0.5,
        m_r: M_R,
        m_e: M_E,
    });
    let e = safety(&i, None).unwrap_err().to_string();
    assert!(e.contains("--link"), "{e}");
}

/// The single-point simulation at a design of a simulated map equals the map's cell bit for
/// bit (CJ and CL): the same finite-element impact, the same lumped start, the same search of
/// the governing limit. The map searches only the limit that governs (the smaller of F_max and
/// the pressure's force f_p) and reports the other as at least the governing speed; the
/// single point searches both, and its other speed is indeed no lower. Both ways: the dome's
/// Hertz sphere (f_p above the hand's 280 N: the force governs) and a fixed 0.5 cm² (f_p =
/// 380 N/cm² × 0.5 cm² = 190 N: the pressure governs).
#[test]
fn the_single_point_simulation_is_the_maps_cell() {
    use flexrig::safety::ContactAreaModel;
    use flexrig::safety::map::LimitSpeed;
    use flexrig_safety::GoverningLimit;
    for (area_model, governs) in [
        (None, GoverningLimit::Force),
        (
            Some(ContactAreaModel::Fixed { area_m2: 0.5e-4 }),
            GoverningLimit::Pressure,
        ),
    ] {
        let map_input = SafetyMapInput {
            region: "hands_and_fingers".into(),
            area: None,
            contact: ContactKind::Transient,
            m_r: Some(0.051),
            m_e: None,
            k_delta: None,
            law: ContactLaw::Material("skinned_aluminium".into()),
            area_model,
            x: MapAxis {
                parameter: MapParameter::Payload,
                values: vec![0.412, 0.6],
                names: Vec::new(),
            },
            y: MapAxis {
                parameter: MapParameter::LinkStiffness,
                values: vec![1e4, 3e4],
                names: Vec::new(),
            },
            method: MapMethod::Simulation,
            simulation: SimulationSettings::DEFAULT,
            speed: None,
        };
        let map = safety_map(&map_input, None, &CancelToken::new()).unwrap();
        for cell in &map.cells {
            for (link, gamma, design) in [
                (FeLink::CompliantJoint, 1.0, cell.cj.unwrap()),
                (FeLink::CompliantLink, 2.0 / 3.0, cell.cl.unwrap()),
            ] {
                let single = SafetyInput {
                    region: "hands_and_fingers".into(),
                    area: None,
                    contact: ContactKind::Transient,
                    m_eff: Some(RobotEffectiveMass::Prb {
                        gamma,
                        m_r: cell.m_r_kg,
                        m_e: cell.m_e_kg,
                    }),
                    k_delta: cell.k_delta_n_per_m,
                    law: ContactLaw::Material("skinned_aluminium".into()),
                    area_model,
                    moving_mass: None,
                    payload: 0.0,
                    speed: None,
                    methods: vec![SafetyMethod::Simulation],
                    link: Some(link),
                    simulation: None,
                    scene: None,
                };
                let m = safety(&single, None).unwrap().methods[0];
                assert_eq!(m.v_max_mps, design.v_max_mps, "{link:?} {cell:?}");
                assert_eq!(m.governing, governs, "{link:?} {cell:?}");
                assert_eq!(design.governing, governs, "{link:?} {cell:?}");
                let v_max = m.v_max_mps.value();
                let bound = LimitSpeed::AtLeast { at_least: v_max };
                let (searched, other, single_other) = match governs {
                    GoverningLimit::Force => (
                        design.by_force_mps,
                        design.by_pressure_mps.unwrap(),
                        m.by_pressure_mps.unwrap().value(),
                    ),
                    GoverningLimit::Pressure => (
                        design.by_pressure_mps.unwrap(),
                        design.by_force_mps,
                        m.by_force_mps.value(),
                    ),
                };
                assert_eq!(
                    searched,
                    LimitSpeed::Known(m.v_max_mps),
                    "{link:?} {cell:?}"
                );
                assert_eq!(other, bound, "{link:?} {cell:?}");
                assert!(single_other >= v_max, "{link:?}: {single_other} < {v_max}");
            }
        }
    }
}

/// The pressure's scan may start where the force's found its last speed below the force limit:
/// a larger force f₂ ≥ F is first reached no lower than F is. Started there, it finds the same
/// speed, bit for bit, as the scan from f₂'s own energy floor (both on the one grid, the runs at
/// equal speeds equal), with no more new search runs (fewer before the screen, which now
/// decides the low speeds the chained scan skips at a tenth of a run each); and a speed asked
/// again is not run again.
#[test]
fn the_larger_forces_scan_from_the_smaller_ones_end_finds_the_same_speed() {
    use flexrig::safety::simulation::{FeImpact, smallest_speed_on_grid};
    use std::sync::atomic::AtomicBool;
    let stop = AtomicBool::new(false);
    // the hand struck by a light payload on a soft CJ (docs/safety.md, "Every contact counts")
    let impact = FeImpact {
        m_h: 0.6,
        hertz: flexrig_contact::Hertz::new(7.359e7, 2.0).unwrap(),
        m_r: 0.051,
        m_e: 0.05,
        k_delta: 2e4,
        link: FeLink::CompliantJoint,
        settings: SimulationSettings::DEFAULT,
    };
    let (f1, f2, rtol) = (280.0, 600.0, 1e-6);
    let mut chained = impact.prepare(1.0).unwrap().against(f1);
    let first = smallest_speed_on_grid(&mut chained, f1, None, rtol, &stop, None).unwrap();
    // the searches' own runs (the screens' are a tenth of the work each)
    let searches = |r: &flexrig::safety::simulation::FeRuns| r.runs - r.screens;
    let before = searches(&chained);
    let second = smallest_speed_on_grid(&mut chained, f2, first.below, rtol, &stop, None).unwrap();
    let chained_new_runs = searches(&chained) - before;
    let mut alone = impact.prepare(1.0).unwrap().against(f1);
    let own = smallest_speed_on_grid(&mut alone, f2, None, rtol, &stop, None).unwrap();
    assert!(first.speed.is_finite() && first.speed < second.speed);
    assert_eq!(second.speed.to_bits(), own.speed.to_bits());
    assert!(
        chained_new_runs <= searches(&alone),
        "{chained_new_runs} new runs after the force's scan, {} alone",
        searches(&alone)
    );
    let runs = chained.runs;
    let again = chained.peak(second.speed, &stop).unwrap();
    assert_eq!(chained.runs, runs);
    assert!(again >= f2, "the root's run reaches the force: {again} N");
}

/// The screen changes how many runs a search takes, never its answer: on the hand's designs (a
/// soft CJ, a CL of the map's rattling corner, a middling and a stiff CL) the screened search
/// finds the speed, bit for bit, of the scan written out here without it — the search's own run
/// at every grid speed from the energy floor up to the first that reaches the limit, then the
/// refinement — and the screen decided speeds on the way (it is not idle).
#[test]
fn the_screen_leaves_the_searchs_speed_bit_for_bit() {
    use flexrig::safety::simulation::{
        FeImpact, REFINE_RUNS, grid_index_at_or_below, grid_speed, refine, smallest_speed_on_grid,
    };
    use std::sync::atomic::AtomicBool;
    let stop = AtomicBool::new(false);
    let (force, rtol) = (280.0, 1e-6);
    let mut screened_steps = 0;
    for (m_e, k_delta, link) in [
        (0.05, 2e4, FeLink::CompliantJoint),
        (0.01, 16.102_620_275_609_397, FeLink::CompliantLink),
        (0.1, 2e3, FeLink::CompliantLink),
        (1.0, 1e5, FeLink::CompliantLink),
    ] {
        let impact = FeImpact {
            m_h: 0.6,
            hertz: flexrig_contact::Hertz::new(7.359e7, 1.961).unwrap(),
            m_r: 0.051,
            m_e,
            k_delta,
            link,
            settings: SimulationSettings::DEFAULT,
        };
        let mut runs = impact.prepare(1.0).unwrap().against(force);
        let mut trace = Vec::new();
        let ours =
            smallest_speed_on_grid(&mut runs, force, None, rtol, &stop, Some(&mut trace)).unwrap();
        screened_steps += trace.iter().filter(|s| s.screened).count();
        // the unscreened scan, on runs of its own
        let mut plain = impact.prepare(1.0).unwrap().against(force);
        let mut k = grid_index_at_or_below(plain.energy_floor(force));
        let mut ratio =
            |v: f64| -> Result<f64, flexrig::Error> { Ok(plain.peak(v, &stop)? / force) };
        let mut r_below = ratio(grid_speed(k)).unwrap();
        assert!(r_below < 1.0, "{m_e} {k_delta}");
        let r_above = loop {
            let r = ratio(grid_speed(k + 1)).unwrap();
            if r >= 1.0 {
                break r;
            }
            k += 1;
            r_below = r;
        };
        let theirs = refine(
            (grid_speed(k), r_below),
            (grid_speed(k + 1), r_above),
            rtol,
            REFINE_RUNS,
            &mut ratio,
        )
        .unwrap();
        assert_eq!(
            ours.speed.to_bits(),
            theirs.to_bits(),
            "{m_e} {k_delta} {link:?}"
        );
        assert_eq!(ours.below, Some(k), "{m_e} {k_delta} {link:?}");
    }
    assert!(screened_steps >= 20, "{screened_steps} speeds screened");
}

/// A screen that passes a speed the search does not is caught at the last speed below the
/// limit, and the scan is done again without it: on a ratio v/2.05 whose screen wrongly says
/// "below" up to 2.2 m/s, the screened scan finds the unscreened scan's speed, 2.05 m/s, not
/// the 2.28 m/s the wrong screen alone would give; a truthful screen finds it with fewer
/// searches.
#[test]
fn a_screen_that_errs_never_sets_the_speed() {
    use flexrig::safety::simulation::{GridRun, grid_index_at_or_below, scan_grid};
    // the ratio v/2.05 (searches counted); the liar's screen says "below" up to 2.2 m/s
    fn run(
        liar: bool,
        searches: &mut usize,
    ) -> impl FnMut(f64, GridRun) -> Result<Option<f64>, flexrig::Error> + '_ {
        move |v, run| {
            let truth = v / 2.05;
            Ok(match run {
                GridRun::Search => {
                    *searches += 1;
                    Some(truth)
                }
                GridRun::Screen(_) if liar && v < 2.2 => Some(0.1),
                GridRun::Screen(margin) => (truth < margin).then_some(truth),
            })
        }
    }
    let start = grid_index_at_or_below(1.0);
    let (mut searches, rtol) = (0, 1e-9);
    let plain = scan_grid(start, rtol, None, &mut run(false, &mut searches)).unwrap();
    let plain_searches = std::mem::take(&mut searches);
    let wrong = scan_grid(start, rtol, Some(0.65), &mut run(true, &mut searches)).unwrap();
    searches = 0;
    let truthful = scan_grid(start, rtol, Some(0.65), &mut run(false, &mut searches)).unwrap();
    assert!((plain.speed / 2.05 - 1.0).abs() < 1e-8, "{plain:?}");
    assert_eq!(wrong, plain);
    assert_eq!(truthful, plain);
    assert!(searches < plain_searches, "{searches} vs {plain_searches}");
}

/// The refinement stops after its budget of runs on a ratio that is not smooth on the bracket,
/// at the conservative end: the highest speed run below the limit, below every speed run that
/// reached it. A smooth ratio converges well within the budget, at its crossing.
#[test]
fn the_refinement_keeps_to_its_budget_at_the_conservative_end() {
    use flexrig::safety::simulation::{REFINE_RUNS, refine};
    // smooth: ln ratio linear in ln v, the crossing at 1.02 m/s
    let mut runs = 0;
    let smooth = refine(
        (1.0, 1.0 / 1.02),
        (1.05, 1.05 / 1.02),
        1e-6,
        REFINE_RUNS,
        &mut |v| {
            runs += 1;
            Ok(v / 1.02)
        },
    )
    .unwrap();
    assert!(runs <= 3, "{runs}");
    assert!(
        (1.02 * (1.0 - 1e-12)..=1.02 * (1.0 + 1e-6)).contains(&smooth),
        "{smooth}"
    );
    // a rattle-like ratio: above or below the limit by ±20 % at speeds 1e-7 apart
    let mut tried: Vec<(f64, f64)> = Vec::new();
    let rough = refine((1.0, 0.9), (1.05, 1.1), 1e-6, REFINE_RUNS, &mut |v: f64| {
        let r = 1.0 + 0.2 * (1e7 * v).sin();
        tried.push((v, r));
        Ok(r)
    })
    .unwrap();
    assert_eq!(tried.len(), REFINE_RUNS);
    let below = tried
        .iter()
        .filter(|t| t.1 < 1.0)
        .map(|t| t.0)
        .fold(1.0, f64::max);
    let reached = tried
        .iter()
        .filter(|t| t.1 >= 1.0)
        .map(|t| t.0)
        .fold(1.05, f64::min);
    assert_eq!(rough.to_bits(), below.to_bits(), "{tried:?}");
    assert!(rough < reached, "{rough} vs {tried:?}");
}
