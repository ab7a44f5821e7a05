//! Bad input gives errors naming the field (never a panic); the PRB fit against Howell.

mod common;
use common::assert_rel;

use flexrig_beam::canonical::*;
use flexrig_beam::prb::{ErrorMeasure, default_load_indices, fit_prb, trace_tip_path};
use flexrig_beam::*;

fn field_of(e: BeamError) -> String {
    assert!(e.is_input_error(), "{e}");
    match e {
        BeamError::InvalidParameter { field, .. } => field,
        _ => unreachable!(),
    }
}

#[test]
fn bad_input_names_the_field() {
    assert_eq!(field_of(Material::new(-1.0, 900.0).unwrap_err()), "youngs");
    assert_eq!(
        field_of(Material::new(1e9, f64::NAN).unwrap_err()),
        "density"
    );
    let mat = Material::new(1e9, 900.0).unwrap();
    assert_eq!(
        field_of(Section::rectangular(&mat, 0.0, 0.01).unwrap_err()),
        "width"
    );
    assert_eq!(
        field_of(Section::rectangular(&mat, 0.05, -0.01).unwrap_err()),
        "thickness"
    );
    assert_eq!(
        field_of(Section::from_stiffness(1.0, f64::INFINITY, 1.0).unwrap_err()),
        "ei"
    );
    let sec = unit_section();
    let e = BeamModel::new(BeamSpec::cantilever(1.0, sec, 0, Kinematics::Linear)).unwrap_err();
    assert_eq!(field_of(e), "elements");
    let e = BeamModel::new(BeamSpec::cantilever(f64::NAN, sec, 4, Kinematics::Linear)).unwrap_err();
    assert_eq!(field_of(e), "length");
    assert_eq!(
        field_of(RootSupport::parse("welded", 0.0).unwrap_err()),
        "root"
    );
    assert_eq!(
        field_of(RootSupport::parse("pinned", -2.0).unwrap_err()),
        "k_theta"
    );
    let mut spec = BeamSpec::cantilever(1.0, sec, 4, Kinematics::Linear);
    spec.point_masses.push(PointMass {
        node: 5,
        mass: 1.0,
        inertia: 0.0,
    });
    assert_eq!(
        field_of(BeamModel::new(spec).unwrap_err()),
        "point mass node"
    );
    let m = unit_cantilever(4, Kinematics::Corotational).unwrap();
    let mut loads = NodalLoads::zeros(&m);
    assert_eq!(
        field_of(loads.set_force(4, 0.0, f64::NAN).unwrap_err()),
        "force y"
    );
    assert_eq!(field_of(loads.set_moment(9, 1.0).unwrap_err()), "load node");
    assert_eq!(field_of(GeneralizedAlpha::new(1.5).unwrap_err()), "rho_inf");
    assert_eq!(
        field_of(StaticOptions::with_load_steps(0).unwrap_err()),
        "load-steps"
    );
    assert_eq!(
        field_of(modal_analysis(&m, 0, ModalDirection::Transverse).unwrap_err()),
        "modes"
    );
    let mut s = State::at_rest(&m, &loads).unwrap();
    let mut ws = Workspace::new(&m);
    let ga = GeneralizedAlpha::new(0.9).unwrap();
    assert_eq!(
        field_of(ga.step(&m, &mut s, &mut ws, -1e-3, &loads).unwrap_err()),
        "time step"
    );
}

#[test]
fn a_pinned_root_without_spring_cannot_carry_a_static_load() {
    let mut spec = BeamSpec::cantilever(1.0, unit_section(), 4, Kinematics::Linear);
    spec.root = RootSupport::Pinned {
        k_theta: 0.0,
        c_theta: 0.0,
    };
    let m = BeamModel::new(spec).unwrap();
    let mut loads = NodalLoads::zeros(&m);
    loads.set_force(4, 0.0, 1.0).unwrap();
    let e = solve_static(&m, &loads, &StaticOptions::with_load_steps(1).unwrap()).unwrap_err();
    assert!(matches!(e, BeamError::Singular { .. }), "{e}");
    assert!(!e.is_input_error());
}

#[test]
fn too_few_load_steps_is_a_clear_not_converged_error() {
    let (m, l) = elastica_problem(10.0, 16).unwrap();
    let opts = StaticOptions::new(1, 3, 1e-10).unwrap();
    match solve_static(&m, &l, &opts).unwrap_err() {
        BeamError::NotConverged {
            load_level,
            iterations,
            ..
        } => {
            // the single load step failed: no load level reached
            assert_eq!(load_level, 0.0);
            assert_eq!(iterations, 3);
        }
        e => panic!("{e}"),
    }
}

#[test]
fn prb_fit_reproduces_howell() {
    let path = trace_tip_path(32, &default_load_indices()).unwrap();
    let fit = fit_prb(&path, ErrorMeasure::Deflection).unwrap();
    // Howell: γ = 0.8517, Θ_max ≈ 64.3°; K_Θ = 2.67617 quoted, ≈ 2.70 by least squares
    assert!((fit.gamma - HOWELL_GAMMA).abs() < 1e-3, "γ = {}", fit.gamma);
    assert!(
        (fit.theta_max_deg - HOWELL_THETA_MAX_DEG).abs() < 0.5,
        "Θ_max = {}",
        fit.theta_max_deg
    );
    assert!((fit.k_theta - 2.70).abs() < 0.03, "K_Θ = {}", fit.k_theta);
    // small-deflection limit (2/3, 2)
    assert_rel("γ₀", fit.gamma_small, 2.0 / 3.0, 1e-4);
    assert_rel("K_Θ0", fit.k_theta_small, 2.0, 1e-4);
}
