//! The exact modal integrator and the graded-mesh CL (issue 14's fast path) against independent
//! solutions: DOP853 and a fixed-step RK4 for the CJ (first and later contacts), flexrig-beam's
//! uniform-mesh modal analysis and the analytic cantilever for the graded mesh, the
//! generalized-α full FE model for the CL, and convergence in tolerance and mesh.

use flexrig_impact::chain::{BETA_1, Chain};
use flexrig_impact::cj::run_cj;
use flexrig_impact::cl::run_cl;
use flexrig_impact::cl_modal::{head_at_onset, run_cj_modal, run_cl_modal, run_on_modes};
use flexrig_impact::eta::{EtaSettings, case_setup};
use flexrig_impact::graded::{GradedMesh, cl_matrices, cl_tip_modes};
use flexrig_impact::horizon::run_window;
use flexrig_impact::modal_run::{
    ModalOptions, run_modes_cubic_against, run_modes_quadratic_against,
};
use flexrig_impact::tip_modes::TipModes;
use flexrig_impact::{ClSolver, FreeMassImpact, ImpactOutcome, Joint, RunEnd};

mod common;
use common::setup;

fn opts(tol: f64) -> ModalOptions {
    ModalOptions {
        tol,
        ..ModalOptions::DEFAULT
    }
}

/// (m_h \[kg\], k_δ \[N/m\], m_e \[kg\], n) of the tests against DOP853: light and heavy head,
/// stiff and soft link, linear and n = 2 contact.
const DOP853_CASES: [(f64, f64, f64, f64); 4] = [
    (4.0, 1e8, 0.1, 1.0),
    (4.0, 2e2, 10.0, 2.0),
    (1000.0, 1e8, 0.1, 1.0),
    (1000.0, 2e2, 0.1, 2.0),
];

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The CJ through the modal integrator (one mode held, two with a free hub) against DOP853 at
/// rtol 1e-12: peak and duration of the first contact within 1e-6 (issue 14's CJ floor).
#[test]
fn the_modal_cj_matches_dop853() {
    let mut worst: f64 = 0.0;
    for joint in [Joint::Held, Joint::FreeHub { rotor_inertia: 0.3 }] {
        for (m_h, k, m_e, n) in DOP853_CASES {
            let s = setup(m_h, k, m_e, n, joint);
            let reference = run_cj(&s, 1e-12).unwrap().first;
            let ours = run_cj_modal(&s, &opts(1e-9)).unwrap().first;
            let e = rel(ours.peak_force_n, reference.peak_force_n)
                .max(rel(ours.duration_s, reference.duration_s));
            worst = worst.max(e);
            assert!(
                e <= 1e-6,
                "{joint:?} {m_h} {k} {m_e} {n}: {ours:?} vs {reference:?}"
            );
        }
    }
    eprintln!("modal CJ vs DOP853: worst relative difference {worst:.1e}");
}

/// Every contact of a chattering CJ (held, soft link, light payload) against a fixed-step RK4
/// of the same ODE continued through the separations (h = t_c/4000): onsets and peaks within
/// 1e-6, and the run ends with the bodies parted for good.
#[test]
fn later_contacts_of_the_cj_match_rk4() {
    let s = setup(4.0, 2e2, 0.1, 1.0, Joint::Held);
    let window = 2.0;
    let ours = run_cj_modal(
        &s,
        &ModalOptions {
            tol: 1e-10,
            window_s: Some(window),
            max_steps: 10_000_000,
        },
    )
    .unwrap();
    assert_matches_rk4(&s, &ours);
}

/// Every contact (onset \[s\], peak \[N\]) of the held CJ `s` by a fixed-step RK4 of (x_h, v_h,
/// w, ẇ) continued through the separations (h = t_c/4000), up to `until` \[s\].
fn rk4_contacts(s: &FreeMassImpact, until: f64) -> Vec<(f64, f64)> {
    let (m_h, m) = (s.m_h, s.link.cj_tip_mass());
    let (k, kc) = (s.link.k_delta, s.contact.k());
    let force = |y: &[f64; 4]| (y[0] - y[2]).max(0.0) * kc;
    let rhs = |y: &[f64; 4]| {
        let f = force(y);
        [y[1], -f / m_h, y[3], (f - k * y[2]) / m]
    };
    let h = s.payload_contact_time() / 4000.0;
    let mut y = [0.0, s.v0, 0.0, 0.0];
    let mut t = 0.0;
    let mut contacts: Vec<(f64, f64)> = Vec::new(); // (onset, peak)
    let mut in_contact = true;
    contacts.push((0.0, 0.0));
    while t < until {
        let add = |y: &[f64; 4], k: &[f64; 4], c: f64| std::array::from_fn(|i| y[i] + c * k[i]);
        let k1 = rhs(&y);
        let k2 = rhs(&add(&y, &k1, 0.5 * h));
        let k3 = rhs(&add(&y, &k2, 0.5 * h));
        let k4 = rhs(&add(&y, &k3, h));
        let gap0 = y[0] - y[2];
        y = std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
        t += h;
        let gap = y[0] - y[2];
        if !in_contact && gap > 0.0 {
            in_contact = true;
            contacts.push((t - h * gap / (gap - gap0), 0.0));
        } else if in_contact && gap <= 0.0 {
            in_contact = false;
        }
        if in_contact {
            let last = contacts.last_mut().unwrap();
            last.1 = last.1.max(force(&y));
        }
    }
    contacts
}

/// The graded-mesh assembly on a uniform mesh is flexrig-beam's model (frequencies to 1e-9),
/// and the graded mesh reproduces the analytic cantilever's first three frequencies
/// β_i² √(EI/ρA)/L² (β = 1.8751, 4.6941, 7.8548) to 1e-7, 1e-6, 1e-5, converging as h⁴.
#[test]
fn the_graded_mesh_is_flexrig_beams_element_and_the_analytic_cantilever() {
    let s = setup(4.0, 2e2, 0.0, 1.0, Joint::Held);
    // uniform: 16 elements of L/16
    let lengths = vec![1.0 / 16.0; 16];
    let flexrig_impact::graded::LinkMatrices { k, m, tip, v0 } = cl_matrices(&s, &lengths).unwrap();
    let ours = TipModes::from_matrices(&k, &m, tip, &v0, f64::INFINITY, 1.0).unwrap();
    let model = flexrig_impact::cl::cl_beam(&s, 16).unwrap();
    let beam =
        flexrig_beam::modal_analysis(&model, 10, flexrig_beam::ModalDirection::Transverse).unwrap();
    for i in 0..10 {
        assert!(rel(ours.omegas[i], beam.omegas[i]) <= 1e-9, "mode {i}");
        let phi_tip = beam.shapes[i][3 * model.tip_node() + 1];
        assert!(
            rel(ours.gains[i].abs(), phi_tip.abs()) <= 1e-8,
            "mode {i} at the tip"
        );
    }
    // graded, every mode kept; the root elements L/24 and L/48: the Hermite cubic's O(h⁴)
    let scale = (s.link.ei() / s.link.rho_a()).sqrt();
    let betas = [BETA_1, 4.694_091_132_974, 7.854_757_438_238];
    let errors = |min_elements: usize| -> Vec<f64> {
        let mesh = GradedMesh {
            mode_cut: f64::INFINITY,
            min_elements,
            ..GradedMesh::DEFAULT
        };
        let graded = cl_tip_modes(&s, &mesh).unwrap();
        (0..3)
            .map(|i| rel(graded.omegas[i], betas[i] * betas[i] * scale))
            .collect()
    };
    let (coarse, fine) = (errors(24), errors(48));
    eprintln!("graded mesh vs the analytic cantilever, modes 1–3: L/24 {coarse:?}, L/48 {fine:?}");
    // mode 1 sits at the round-off floor of the dense solve on a graded mesh (≈ 4e-8: the
    // tip elements of L/500 make K + σM ill-conditioned); modes 2 and 3 show the O(h⁴)
    for i in 0..3 {
        assert!(
            coarse[i] <= [1e-7, 1e-6, 1e-5][i],
            "mode {}: {:.1e}",
            i + 1,
            coarse[i]
        );
        assert!(
            fine[i] <= [1e-7, 1e-7, 1e-6][i],
            "mode {}: {:.1e}",
            i + 1,
            fine[i]
        );
    }
    for i in 1..3 {
        assert!(
            coarse[i] / fine[i] >= 10.0,
            "mode {}: order 4 expected",
            i + 1
        );
    }
    let graded = cl_tip_modes(
        &s,
        &GradedMesh {
            mode_cut: f64::INFINITY,
            ..GradedMesh::DEFAULT
        },
    )
    .unwrap();
    // static tip compliance: 1/k_δ for the Hermite element (exact), here to the round-off of
    // the dense solve on the graded mesh
    let e = rel(graded.static_compliance(), 1.0 / s.link.k_delta);
    assert!(e <= 1e-6, "{e:.1e}");
    // the placed model: the same static compliance, and for m_e = 0 the cantilever's ω₁
    let placed = Chain::placed(&s).tip_modes(&s, 0.0).unwrap();
    assert!(rel(placed.static_compliance(), 1.0 / s.link.k_delta) <= 1e-12);
    assert!(rel(placed.omegas[0], graded.omegas[0]) <= 1e-6);
}

/// The fast CL against the generalized-α full FE model on a uniform mesh (the reference method;
/// 128 elements, 800 steps per contact): first-contact peaks within 1e-4, held and free hub,
/// rigid and soft links.
#[test]
fn the_modal_cl_matches_the_full_fe_model() {
    let solver = ClSolver {
        elements: 128,
        steps_per_contact: 800,
        modes: None,
    };
    let mut worst: f64 = 0.0;
    for (m_h, k, m_e, n, joint) in [
        (4.0, 1e8, 0.1, 1.0, Joint::Held),
        (4.0, 2e2, 0.1, 1.0, Joint::Held),
        (1000.0, 2e2, 10.0, 2.0, Joint::Held),
        (1000.0, 1e8, 0.1, 1.0, Joint::FreeHub { rotor_inertia: 1.0 }),
        (
            4.0,
            2e2,
            0.1,
            2.0,
            Joint::FreeHub {
                rotor_inertia: 1e-3,
            },
        ),
    ] {
        let s = setup(m_h, k, m_e, n, joint);
        let fe = run_cl(&s, &solver).unwrap().first;
        let ours = run_cl_modal(&s, &GradedMesh::DEFAULT, &opts(1e-6))
            .unwrap()
            .first;
        let e = rel(ours.peak_force_n, fe.peak_force_n);
        worst = worst.max(e);
        assert!(
            e <= 1e-4,
            "{m_h} {k} {m_e} {n} {joint:?}: {ours:?} vs {fe:?}"
        );
        assert!(
            rel(ours.duration_s, fe.duration_s) <= 1e-3,
            "{ours:?} vs {fe:?}"
        );
    }
    eprintln!("modal CL vs generalized-α FE: worst {worst:.1e}");
}

/// η_FE of the sixteen Fig. 6 cases converged to ≤ 1e-4 (issue 14's floor) in the tolerance
/// (1e-6 against 1e-8) and in the mesh (8 against 24 elements per tip zone, and every mode kept
/// against the cut-off at 60 π/t_c).
#[test]
fn eta_fe_converges_in_tolerance_and_mesh() {
    let fine_mesh = GradedMesh {
        zone_elements: 24.0,
        ratio: 1.08,
        min_elements: 48,
        mode_cut: f64::INFINITY,
    };
    let mut worst: f64 = 0.0;
    for case in flexrig_lumped::fig6::cases() {
        for n in [1.0, 2.0] {
            let s = case_setup(&case, n, &EtaSettings::DEFAULT).unwrap();
            let default = run_cl_modal(&s, &GradedMesh::DEFAULT, &opts(1e-6)).unwrap();
            let fine = run_cl_modal(&s, &fine_mesh, &opts(1e-8)).unwrap();
            let e = rel(default.first.peak_force_n, fine.first.peak_force_n);
            worst = worst.max(e);
            assert!(e <= 1e-4, "{case:?} n = {n}: {e:.1e}");
        }
    }
    eprintln!("η_FE: default vs fine tolerance and mesh, worst {worst:.1e}");
}

/// A huge rotor is the held joint (1e-6), and the CL's modes do not depend on L (1e-9).
#[test]
fn the_modal_cl_joins_the_joints_and_ignores_the_length() {
    let held = setup(4.0, 1e8, 0.1, 1.0, Joint::Held);
    let hub = FreeMassImpact {
        joint: Joint::FreeHub { rotor_inertia: 1e9 },
        ..held
    };
    let a = run_cl_modal(&held, &GradedMesh::DEFAULT, &opts(1e-8))
        .unwrap()
        .first;
    let b = run_cl_modal(&hub, &GradedMesh::DEFAULT, &opts(1e-8))
        .unwrap()
        .first;
    assert!(
        rel(a.peak_force_n, b.peak_force_n) <= 1e-6,
        "{a:?} vs {b:?}"
    );
    let mut long = held;
    long.link.length = 3.7;
    let c = run_cl_modal(&long, &GradedMesh::DEFAULT, &opts(1e-8))
        .unwrap()
        .first;
    assert!(
        rel(a.peak_force_n, c.peak_force_n) <= 1e-9,
        "{a:?} vs {c:?}"
    );
}

/// A window: every contact of the chattering soft CL, energy kept through them all, the runs at
/// tol and tol/10 agree up to a stated horizon, and a longer window adds nothing once the bodies
/// have parted for good.
#[test]
fn a_window_reports_every_contact_up_to_its_converged_horizon() {
    let s = setup(4.0, 2e2, 0.1, 2.0, Joint::Held);
    let modes = cl_tip_modes(&s, &GradedMesh::DEFAULT).unwrap();
    let options = ModalOptions {
        tol: 1e-6,
        window_s: Some(3.0),
        max_steps: 2_000_000,
    };
    let report = run_window(&s, &modes, &options).unwrap();
    let o = &report.outcome;
    assert!(o.contacts.len() >= 3, "{:?}", o.contacts);
    assert!(report.converged_contacts >= 1 && report.horizon_s > 0.0);
    assert!(rel(o.energy_j.1, o.energy_j.0) <= 1e-5, "{:?}", o.energy_j);
    for pair in o.contacts.windows(2) {
        assert!(pair[1].onset_s >= pair[0].onset_s + pair[0].duration_s);
    }
    if let RunEnd::PartedForGood(t) = o.ended {
        let longer = run_on_modes(
            &s,
            &modes,
            &ModalOptions {
                tol: options.tol / 10.0,
                window_s: Some(3.0 * t + 10.0),
                ..options
            },
        )
        .unwrap();
        assert_eq!(longer.contacts, o.contacts);
    }
}

/// Bad modal settings name the field.
#[test]
fn bad_modal_settings_name_the_field() {
    let s = setup(4.0, 1e8, 0.1, 1.0, Joint::Held);
    for (mesh, field) in [
        (
            GradedMesh {
                zone_elements: 0.0,
                ..GradedMesh::DEFAULT
            },
            "zone_elements",
        ),
        (
            GradedMesh {
                ratio: f64::NAN,
                ..GradedMesh::DEFAULT
            },
            "ratio",
        ),
        (
            GradedMesh {
                mode_cut: 0.5,
                ..GradedMesh::DEFAULT
            },
            "mode_cut",
        ),
    ] {
        let e = run_cl_modal(&s, &mesh, &opts(1e-6))
            .unwrap_err()
            .to_string();
        assert!(e.contains(field), "{e}");
    }
    // a step budget too small for the first contact is an error, not a peak of 0
    let tight = ModalOptions {
        max_steps: 100,
        ..opts(1e-10)
    };
    let e = run_cl_modal(&s, &GradedMesh::DEFAULT, &tight)
        .unwrap_err()
        .to_string();
    assert!(e.contains("step budget"), "{e}");
    for (o, field) in [
        (opts(0.0), "tol"),
        (
            ModalOptions {
                window_s: Some(-1.0),
                ..ModalOptions::DEFAULT
            },
            "window",
        ),
    ] {
        let e = run_cj_modal(&s, &o).unwrap_err().to_string();
        assert!(e.contains(field), "{e}");
    }
}

/// One of the modal runs against a force scale (a hold of [`flexrig_impact::modal_run`]).
type HeldRun = fn(
    &flexrig_impact::tip_modes::TipModes,
    flexrig_impact::modal_run::Head,
    &dyn flexrig_contact::ContactLaw,
    f64,
    &ModalOptions,
    f64,
) -> Result<ImpactOutcome, flexrig_impact::ImpactError>;

/// The CJ's modal run with the force held by `run`'s hold over each step.
fn run_cj_held(s: &FreeMassImpact, options: &ModalOptions, run: HeldRun) -> ImpactOutcome {
    let modes = Chain::cj(s).tip_modes(s, 0.0).unwrap();
    run(
        &modes,
        head_at_onset(s),
        &*s.law().unwrap(),
        s.payload_contact_time(),
        options,
        0.0,
    )
    .unwrap()
}

/// The CJ's modal run with the force held quadratic over each step.
fn run_cj_quadratic(s: &FreeMassImpact, options: &ModalOptions) -> ImpactOutcome {
    run_cj_held(s, options, run_modes_quadratic_against)
}

/// The CJ's modal run with the force held cubic over each step.
fn run_cj_cubic(s: &FreeMassImpact, options: &ModalOptions) -> ImpactOutcome {
    run_cj_held(s, options, run_modes_cubic_against)
}

/// Every DOP853 case, held and free hub, both runs at tol 1e-9: the case, the first contact's
/// relative peak and duration error of `ours` against DOP853 (rtol 1e-12), and the steps of
/// `ours` and of `other`.
fn first_contacts_against_dop853(
    ours: impl Fn(&FreeMassImpact, &ModalOptions) -> ImpactOutcome,
    other: impl Fn(&FreeMassImpact, &ModalOptions) -> ImpactOutcome,
) -> Vec<(String, f64, usize, usize)> {
    let mut out = Vec::new();
    for joint in [Joint::Held, Joint::FreeHub { rotor_inertia: 0.3 }] {
        for (m_h, k, m_e, n) in DOP853_CASES {
            let s = setup(m_h, k, m_e, n, joint);
            let reference = run_cj(&s, 1e-12).unwrap().first;
            let (run, other_run) = (ours(&s, &opts(1e-9)), other(&s, &opts(1e-9)));
            let first = run.first;
            let e = rel(first.peak_force_n, reference.peak_force_n)
                .max(rel(first.duration_s, reference.duration_s));
            let case = format!("{joint:?} {m_h} {k} {m_e} {n}: {first:?} vs {reference:?}");
            out.push((case, e, run.work, other_run.work));
        }
    }
    out
}

/// The quadratic hold on the cases of the linear hold's DOP853 test (held and free hub, linear
/// and n = 2 contact, light and heavy head): peak and duration within the same 1e-6 at the same
/// tolerance, with fewer than a third of the linear hold's steps.
#[test]
fn the_quadratic_hold_matches_dop853_with_fewer_steps() {
    let mut worst: f64 = 0.0;
    let linear = |s: &FreeMassImpact, o: &ModalOptions| run_cj_modal(s, o).unwrap();
    for (case, e, quadratic, linear) in first_contacts_against_dop853(run_cj_quadratic, linear) {
        worst = worst.max(e);
        assert!(e <= 1e-6, "{case}");
        assert!(
            3 * quadratic < linear,
            "{case}: {quadratic} steps against the linear hold's {linear}"
        );
    }
    eprintln!("quadratic-hold CJ vs DOP853: worst relative difference {worst:.1e}");
}

/// The cubic hold on the same cases: peak and duration within the same 1e-6 of DOP853 (rtol
/// 1e-12) at the same tolerance, with fewer steps than the quadratic hold.
#[test]
fn the_cubic_hold_matches_dop853_with_fewer_steps_than_the_quadratic() {
    let mut worst: f64 = 0.0;
    let (mut cubic_steps, mut quadratic_steps) = (0, 0);
    for (case, e, cubic, quadratic) in first_contacts_against_dop853(run_cj_cubic, run_cj_quadratic)
    {
        worst = worst.max(e);
        assert!(e <= 1e-6, "{case}");
        assert!(
            cubic < quadratic,
            "{case}: {cubic} steps against the quadratic hold's {quadratic}"
        );
        cubic_steps += cubic;
        quadratic_steps += quadratic;
    }
    eprintln!(
        "cubic-hold CJ vs DOP853: worst relative difference {worst:.1e}, {cubic_steps} steps \
         against the quadratic hold's {quadratic_steps}"
    );
}

/// The chattering CJ of the RK4 test run by `run` at tol 1e-10 over a 2 s window, against RK4
/// ([`assert_matches_rk4`]).
fn chattering_cj_matches_rk4(run: impl Fn(&FreeMassImpact, &ModalOptions) -> ImpactOutcome) {
    let s = setup(4.0, 2e2, 0.1, 1.0, Joint::Held);
    let options = ModalOptions {
        tol: 1e-10,
        window_s: Some(2.0),
        max_steps: 10_000_000,
    };
    assert_matches_rk4(&s, &run(&s, &options));
}

/// The chattering CJ of the RK4 test with the cubic hold: every onset and peak within the same
/// bars, the energy through all contacts, the bodies parted for good.
#[test]
fn later_contacts_of_the_cubic_hold_match_rk4() {
    chattering_cj_matches_rk4(run_cj_cubic);
}

/// The chattering CJ of the RK4 test with the quadratic hold: every onset and peak within the
/// same bars, the energy through all contacts, the bodies parted for good.
#[test]
fn later_contacts_of_the_quadratic_hold_match_rk4() {
    chattering_cj_matches_rk4(run_cj_quadratic);
}

/// The order of each hold: the first contact's peak and duration error against DOP853 (rtol
/// 1e-13) over the tolerances 1e-5 … 1e-8 falls as steps⁻² with the linear hold, steps⁻³ with
/// the quadratic one and steps⁻⁴ with the cubic one (least-squares slopes of ln error on ln
/// steps, n = 2 contact on a soft CJ).
#[test]
fn the_linear_hold_is_second_order_the_quadratic_third_and_the_cubic_fourth() {
    let s = setup(4.0, 2e2, 10.0, 2.0, Joint::Held);
    let reference = run_cj(&s, 1e-13).unwrap().first;
    let error = |o: &flexrig_impact::ImpactOutcome| {
        rel(o.first.peak_force_n, reference.peak_force_n)
            .max(rel(o.first.duration_s, reference.duration_s))
    };
    let slope = |points: &[(f64, f64)]| {
        let n = points.len() as f64;
        let (mx, my) = points
            .iter()
            .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
        let sxy: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
        sxy / sxx
    };
    let (mut linear, mut quadratic, mut cubic) = (Vec::new(), Vec::new(), Vec::new());
    for tol in [1e-5, 1e-6, 1e-7, 1e-8] {
        let l = run_cj_modal(&s, &opts(tol)).unwrap();
        let q = run_cj_quadratic(&s, &opts(tol));
        let c = run_cj_cubic(&s, &opts(tol));
        linear.push(((l.work as f64).ln(), error(&l).ln()));
        quadratic.push(((q.work as f64).ln(), error(&q).ln()));
        cubic.push(((c.work as f64).ln(), error(&c).ln()));
    }
    let (p_lin, p_quad, p_cub) = (-slope(&linear), -slope(&quadratic), -slope(&cubic));
    eprintln!(
        "order: linear hold {p_lin:.2}, quadratic hold {p_quad:.2}, cubic hold {p_cub:.2}; \
         {linear:?} {quadratic:?} {cubic:?}"
    );
    assert!((3.5..=4.6).contains(&p_cub), "cubic hold: order {p_cub}");
    assert!((1.7..=2.4).contains(&p_lin), "linear hold: order {p_lin}");
    assert!(
        (2.7..=3.5).contains(&p_quad),
        "quadratic hold: order {p_quad}"
    );
}

/// Every contact of `ours` (a run that parted for good) against the RK4 reference of the same
/// setup `s`: as many contacts (two at least: a chattering case), each peak within 1e-6 (the RK4
/// peak is the largest sample: within (ω h)²/8 ≈ 1e-7 of the true peak), each onset within 1e-6
/// of the run's length, and the energy through all contacts within 1e-8.
fn assert_matches_rk4(s: &FreeMassImpact, ours: &ImpactOutcome) {
    let RunEnd::PartedForGood(parted) = ours.ended else {
        panic!("{:?}", ours.ended)
    };
    let contacts = rk4_contacts(s, parted * 1.2);
    assert_eq!(
        contacts.len(),
        ours.contacts.len(),
        "{contacts:?} vs {:?}",
        ours.contacts
    );
    assert!(contacts.len() >= 2, "a chattering case: {contacts:?}");
    for (r, o) in contacts.iter().zip(&ours.contacts) {
        assert!(rel(o.peak_force_n, r.1) <= 1e-6, "{o:?} vs {r:?}");
        assert!(
            (o.onset_s - r.0).abs() <= 1e-6 * parted.max(1e-3),
            "{o:?} vs {r:?}"
        );
    }
    assert!(
        rel(ours.energy_j.1, ours.energy_j.0) <= 1e-8,
        "{:?}",
        ours.energy_j
    );
}

/// The hand's design of the safe-speed map (m_h = 0.6 kg, skinned aluminium k_c = 7.359e7,
/// n = 1.961, m_r = 0.051 kg, L = 1 m) with payload `m_e` \[kg\], stiffness `k_delta` \[N/m\] and
/// speed `v0` [m/s].
fn hand(m_e: f64, k_delta: f64, v0: f64, joint: Joint) -> FreeMassImpact {
    FreeMassImpact {
        m_h: 0.6,
        v0,
        link: flexrig_impact::LinkParams {
            m_r: 0.051,
            length: 1.0,
            k_delta,
            m_e,
        },
        joint,
        contact: flexrig_contact::Hertz::new(7.359e7, 1.961).unwrap(),
        damping: flexrig_contact::DampingSpec::NONE,
    }
}

/// The hand's link by its modes: the CL's on the graded mesh, or the CJ's rigid link on its
/// spring.
fn hand_modes(s: &FreeMassImpact, cl: bool) -> TipModes {
    if cl {
        cl_tip_modes(s, &GradedMesh::DEFAULT).unwrap()
    } else {
        Chain::cj(s).tip_modes(s, 0.0).unwrap()
    }
}

/// The largest peak force \[N\] over `contacts`.
fn largest_peak(contacts: &[flexrig_impact::setup::ContactEvent]) -> f64 {
    contacts.iter().map(|c| c.peak_force_n).fold(0.0, f64::max)
}

/// A run for its largest peak alone stops once no later contact can pass the largest so far:
/// on held CJs and CLs of the map's hand (the rattling corner, m_e = 0.01 kg on k_δ = 10 N/m,
/// included) at speeds across its limits, the largest peak is the full run's bit for bit, the
/// contacts it followed are the full run's first ones, most runs stop early (the bound is not
/// idle), and a free hub (rigid modes) is always followed to its end.
#[test]
fn a_settled_run_keeps_the_full_runs_largest_peak() {
    use flexrig_impact::modal_run::{PeakRunEnd, largest_peak_quadratic_against};
    let options = ModalOptions {
        tol: 1e-7,
        window_s: Some(1e6),
        max_steps: 20_000_000,
    };
    let (mut runs, mut settled) = (0, 0);
    for joint in [
        Joint::Held,
        Joint::FreeHub {
            rotor_inertia: 1e-3,
        },
    ] {
        for (m_e, k_delta) in [
            (0.01, 10.0),
            (0.01, 2e4),
            (0.1, 2e3),
            (1.0, 1e5),
            (5.0, 1e7),
        ] {
            for v0 in [0.8, 1.5, 3.0] {
                let s = hand(m_e, k_delta, v0, joint);
                for cl in [false, true] {
                    let modes = hand_modes(&s, cl);
                    let (head, t_scale) = (head_at_onset(&s), s.payload_contact_time());
                    let full = run_modes_quadratic_against(
                        &modes, head, &s.contact, t_scale, &options, 280.0,
                    )
                    .unwrap();
                    let ours = largest_peak_quadratic_against(
                        &modes, head, &s.contact, t_scale, &options, 280.0,
                    )
                    .unwrap();
                    let at = format!("{joint:?} cl {cl} m_e {m_e} k {k_delta} v {v0}");
                    assert_eq!(
                        largest_peak(&ours.contacts),
                        largest_peak(&full.contacts),
                        "{at}"
                    );
                    assert_eq!(
                        ours.contacts[..],
                        full.contacts[..ours.contacts.len()],
                        "{at}"
                    );
                    runs += 1;
                    match ours.end {
                        PeakRunEnd::Settled(t) => {
                            assert!(matches!(joint, Joint::Held), "{at}");
                            assert!(ours.contacts.len() <= full.contacts.len(), "{at}: {t}");
                            settled += 1;
                        }
                        PeakRunEnd::Ended(end) => assert_eq!(end, full.ended, "{at}"),
                        other => panic!("{at}: a largest-peak run ended as {other:?}"),
                    }
                }
            }
        }
    }
    eprintln!("{settled} of {runs} runs stopped at their settled peak");
    assert!(settled >= runs / 4, "{settled} of {runs}");
}

/// A run asked only whether a contact reaches a threshold force answers as the full run does:
/// on held CJs and CLs of the map's hand (the rattling corner included) and a free hub, at
/// speeds across its limits and thresholds on both sides of each run's largest peak, the
/// contacts it followed are the full run's first ones bit for bit; it stops at the first contact
/// whose peak reaches the threshold exactly when the full run has one (and at that contact),
/// else it keeps every peak below it; it stops early often (the energy bound is not idle), and
/// only with a held joint when below.
#[test]
fn a_threshold_run_answers_as_the_full_run() {
    use flexrig_impact::modal_run::{PeakRunEnd, threshold_cubic_against};
    let options = ModalOptions {
        tol: 1e-6,
        window_s: Some(1e6),
        max_steps: 20_000_000,
    };
    let (mut runs, mut early) = (0, 0);
    for joint in [
        Joint::Held,
        Joint::FreeHub {
            rotor_inertia: 1e-3,
        },
    ] {
        for (m_e, k_delta) in [(0.01, 10.0), (0.01, 2e4), (0.1, 2e3), (1.0, 1e5)] {
            for v0 in [0.8, 3.0] {
                let s = hand(m_e, k_delta, v0, joint);
                for cl in [false, true] {
                    let modes = hand_modes(&s, cl);
                    let (head, t_scale) = (head_at_onset(&s), s.payload_contact_time());
                    let full =
                        run_modes_cubic_against(&modes, head, &s.contact, t_scale, &options, 280.0)
                            .unwrap();
                    let largest = largest_peak(&full.contacts);
                    for threshold in [0.5 * largest, largest, 1.01 * largest, 280.0] {
                        let ours = threshold_cubic_against(
                            &modes, head, &s.contact, t_scale, &options, 280.0, threshold,
                        )
                        .unwrap();
                        let at =
                            format!("{joint:?} cl {cl} m_e {m_e} k {k_delta} v {v0} F {threshold}");
                        let n = ours.contacts.len();
                        assert_eq!(ours.contacts[..], full.contacts[..n], "{at}");
                        let first_reaching = full
                            .contacts
                            .iter()
                            .position(|c| c.peak_force_n >= threshold);
                        runs += 1;
                        match ours.end {
                            PeakRunEnd::Reached(_) => {
                                assert_eq!(first_reaching, Some(n - 1), "{at}");
                                early += usize::from(n < full.contacts.len());
                            }
                            PeakRunEnd::StaysBelow(_) => {
                                assert_eq!(first_reaching, None, "{at}");
                                assert!(matches!(joint, Joint::Held), "{at}");
                                assert!(n <= full.contacts.len(), "{at}");
                                early += usize::from(n < full.contacts.len());
                            }
                            PeakRunEnd::Ended(end) => {
                                assert_eq!(first_reaching, None, "{at}");
                                assert_eq!(end, full.ended, "{at}");
                                assert_eq!(n, full.contacts.len(), "{at}");
                            }
                            PeakRunEnd::Settled(_) => panic!("{at}: a threshold run never settles"),
                        }
                    }
                }
            }
        }
    }
    eprintln!("{early} of {runs} threshold runs stopped early");
    assert!(early >= runs / 4, "{early} of {runs}");
}

/// A threshold must be a positive force: the error names it.
#[test]
fn a_threshold_run_refuses_a_threshold_that_is_not_a_force() {
    use flexrig_impact::modal_run::threshold_cubic_against;
    let s = hand(0.1, 2e3, 1.0, Joint::Held);
    let modes = Chain::cj(&s).tip_modes(&s, 0.0).unwrap();
    let (head, t_scale) = (head_at_onset(&s), s.payload_contact_time());
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = threshold_cubic_against(
            &modes,
            head,
            &s.contact,
            t_scale,
            &ModalOptions::DEFAULT,
            0.0,
            bad,
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("threshold"), "{e}");
    }
}
