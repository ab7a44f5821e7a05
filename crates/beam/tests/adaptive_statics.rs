//! Adaptive load steps of the static solve: the same equilibrium as fine fixed load steps (to
//! the Newton tolerance times the length), for the corotational and the ANCF elements, meshes
//! of 1 to 128 elements and loads far beyond the elastica table; the jumps a long increment can
//! make (past a bifurcation, a node turned by a full turn) are caught; a solve that cannot
//! converge is a clear error with the load level reached.

mod common;
use common::assert_rel;

use flexrig_beam::canonical::{ELASTICA, elastica_problem_with, unit_cantilever};
use flexrig_beam::*;
use std::f64::consts::PI;

const MODELS: [Kinematics; 2] = [Kinematics::Ancf, Kinematics::Corotational];

/// max |a − b| over the displacements.
fn max_difference(a: &StaticSolution, b: &StaticSolution) -> f64 {
    a.q.iter()
        .zip(&b.q)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

fn fixed(steps: usize) -> StaticOptions {
    StaticOptions::with_load_steps(steps).unwrap()
}

#[test]
fn adaptive_steps_reach_the_fixed_step_equilibrium_for_every_model_mesh_and_load() {
    // The Newton test is the same at the full load, so both end within round-off of the same
    // equilibrium: within tol·L = 1e-10 (measured ≤ 6.4e-11, corotational, one element,
    // PL²/EI = 200; ≤ 1e-13 for 8 elements and more).
    for kin in MODELS {
        for n in [1, 2, 4, 8, 32, 128] {
            for phi in [-5.0, 0.1, 1.0, 5.0, 10.0, 20.0, 200.0] {
                let (m, l) = elastica_problem_with(kin, phi, n).unwrap();
                let f = solve_static(&m, &l, &fixed(20)).unwrap();
                let a = solve_static(&m, &l, &StaticOptions::adaptive()).unwrap();
                let d = max_difference(&a, &f);
                assert!(d <= 1e-10, "{kin:?}, {n} elements, PL²/EI = {phi}: {d:e}");
                assert_eq!(a.load_level, 1.0);
                // the round-off floor of both (EA/EI = 1e7): measured ≤ 1.6e-7 N
                let floor = 3e-7 * phi.abs().max(1.0);
                assert!(a.residual <= floor, "residual {:e}", a.residual);
                assert!(f.residual <= floor, "fixed residual {:e}", f.residual);
                // the user's first increment (a tenth) ends at the same equilibrium
                let a10 = solve_static(&m, &l, &fixed(10).with_adaptive_steps()).unwrap();
                let d = max_difference(&a10, &f);
                assert!(d <= 1e-10, "{kin:?}, {n}, {phi}, from a tenth: {d:e}");
            }
        }
    }
}

#[test]
fn adaptive_elastica_matches_the_table_with_a_fraction_of_the_iterations() {
    // 32 elements against the inextensible elastica (EA L²/EI = 1e7: the stretch moves the tip
    // by ≈ PL²/EI · 1e-7): ANCF within 1e-5 (O(h⁴), ≈ 1e-7 at 32 elements, plus the stretch),
    // corotational (O(h²)) within 5e-4 relative, as in
    // the fixed-step validation. Newton iterations: the full load at once converges, 7–12 in
    // all, against 50–66 for 10 fixed steps (a count, not a time).
    for kin in MODELS {
        for &(phi, v_ref, u_ref, th_ref) in &ELASTICA {
            let (m, l) = elastica_problem_with(kin, phi, 32).unwrap();
            let a = solve_static(&m, &l, &StaticOptions::adaptive()).unwrap();
            let f = solve_static(&m, &l, &fixed(10)).unwrap();
            let (u, v, th) = a.node(32);
            let rel = if kin == Kinematics::Ancf { 1e-5 } else { 5e-4 };
            let what = format!("{kin:?}, PL²/EI = {phi}");
            assert_rel(&format!("v/L, {what}"), v, v_ref, rel);
            assert_rel(&format!("u/L, {what}"), -u, u_ref, 2.0 * rel);
            assert_rel(&format!("tip angle, {what}"), th, th_ref, rel);
            assert!(
                a.iterations <= 12 && 4 * a.iterations <= f.iterations,
                "{what}: {} adaptive against {} fixed iterations",
                a.iterations,
                f.iterations
            );
        }
    }
}

#[test]
fn a_long_increment_past_buckling_is_cut_back_to_the_load_path() {
    // Axial compression 3 EI/L² (past the first buckling load π²EI/4L² ≈ 2.47 EI/L²) with a
    // small transverse load 0.01 EI/L²: along the load path the column buckles towards the
    // transverse load (tip angle ≈ 1.23 rad). The full load at once converges to the nearly
    // straight equilibrium bent against it, which is unstable (an indefinite tangent): the
    // adaptive solve must not stop there.
    for kin in MODELS {
        for n in [4, 16, 64] {
            let m = unit_cantilever(n, kin).unwrap();
            let mut l = NodalLoads::zeros(&m);
            l.set_force(n, -3.0, 0.01).unwrap();
            let f = solve_static(&m, &l, &fixed(50)).unwrap();
            let a = solve_static(&m, &l, &StaticOptions::adaptive()).unwrap();
            let (_, v, th) = a.node(n);
            assert!(v > 0.6 && th > 1.1, "{kin:?}, {n}: tip v {v}, angle {th}");
            let d = max_difference(&a, &f);
            assert!(d <= 1e-10, "{kin:?}, {n}: {d:e}");
        }
    }
}

#[test]
fn a_corotational_node_is_not_left_a_full_turn_off() {
    // A tip moment M rolls the beam into an arc whose tip turns by ML/EI exactly (constant
    // curvature M/EI). Long increments can converge with a node turned by one more turn (the
    // element is 2π-periodic in its nodal rotations): the adaptive solve must not.
    for n in [4, 16, 64] {
        for ml in [PI, 2.0 * PI, 12.0] {
            let m = unit_cantilever(n, Kinematics::Corotational).unwrap();
            let mut l = NodalLoads::zeros(&m);
            l.set_moment(n, ml).unwrap();
            let a = solve_static(&m, &l, &StaticOptions::adaptive()).unwrap();
            assert_rel(&format!("tip rotation, {n}, {ml}"), a.node(n).2, ml, 1e-9);
            for i in 0..n {
                let turn = a.node(i + 1).2 - a.node(i).2;
                assert_rel(&format!("element {i} turn"), turn, ml / n as f64, 1e-6);
            }
        }
    }
}

#[test]
fn stubby_sections_converge_where_coarse_fixed_steps_fail() {
    // L/t = 5 and 2 (steel): a fixed increment of PL²/EI = 0.5 already diverges (the fixed-step
    // stress test); the adaptive solve cuts back and ends at the 50-step equilibrium.
    for kin in MODELS {
        for slenderness in [5.0, 2.0] {
            let n = 32;
            let mat = Material::new(210e9, 7850.0).unwrap();
            let sec = Section::rectangular(&mat, 0.02, 1.0 / slenderness).unwrap();
            let m = BeamModel::new(BeamSpec::cantilever(1.0, sec, n, kin)).unwrap();
            let mut l = NodalLoads::zeros(&m);
            l.set_force(n, 0.0, 5.0 * m.section().ei()).unwrap();
            let f = solve_static(&m, &l, &fixed(50)).unwrap();
            let a = solve_static(&m, &l, &StaticOptions::adaptive()).unwrap();
            let d = max_difference(&a, &f);
            assert!(d <= 1e-10, "{kin:?}, L/t = {slenderness}: {d:e}");
        }
    }
}

#[test]
fn an_adaptive_solve_that_cannot_converge_reports_the_load_level_reached() {
    // one iteration per level can never pass the Newton test (it needs a second residual):
    // every increment fails down to the smallest, nothing is carried
    let (m, l) = elastica_problem_with(Kinematics::Ancf, 5.0, 8).unwrap();
    let opts = StaticOptions::new(1, 1, 1e-10)
        .unwrap()
        .with_adaptive_steps();
    let e = solve_static(&m, &l, &opts).unwrap_err();
    assert!(!e.is_input_error(), "{e}");
    assert!(e.to_string().contains("load level reached 0.0000"), "{e}");
    // a singular structure is named as such (not cut back)
    let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 4, Kinematics::Ancf);
    spec.root = RootSupport::Pinned {
        k_theta: 0.0,
        c_theta: 0.0,
    };
    for kin in MODELS {
        let pinned = BeamModel::new(spec.clone()).unwrap().with_kinematics(kin);
        let mut l = NodalLoads::zeros(&pinned);
        l.set_force(4, 0.0, 1.0).unwrap();
        match solve_static(&pinned, &l, &StaticOptions::adaptive()) {
            Err(BeamError::Singular { .. }) => {}
            other => panic!("{kin:?}: {other:?}"),
        }
    }
    // invalid loads are input errors before any work
    let (m, l) = elastica_problem_with(Kinematics::Corotational, 1.0, 4).unwrap();
    let e = solve_static(&m, &l.scaled(f64::NAN), &StaticOptions::adaptive()).unwrap_err();
    assert!(e.is_input_error(), "{e}");
}
