//! Linear model, modal and static validation against the published references
//! (docs/references.md).

#![allow(clippy::needless_range_loop)]

mod common;
use common::{assert_rel, order};

use flexrig_beam::assembly::{JacobianWeights, Kinematic, assemble, band_for};
use flexrig_beam::canonical::*;
use flexrig_beam::*;

fn omega_ref(i: usize) -> f64 {
    beam_omega(CANTILEVER_BETA_L[i], 1.0, 1.0, 1.0)
}

fn lumped(model: &BeamModel) -> BeamModel {
    let mut spec = model.spec().clone();
    spec.mass = MassMatrix::Lumped;
    BeamModel::new(spec).unwrap()
}

#[test]
fn cantilever_frequencies_consistent_mass_16_and_32_elements() {
    for (n, tol) in [(16, 2e-4), (32, 1e-5)] {
        let m = unit_cantilever(n, Kinematics::Linear).unwrap();
        let r = modal_analysis(&m, 4, ModalDirection::Transverse).unwrap();
        for i in 0..4 {
            assert_rel(
                &format!("ω{} with {n} elements", i + 1),
                r.omegas[i],
                omega_ref(i),
                tol,
            );
        }
    }
}

#[test]
fn omega1_converges_from_above_h4_consistent_and_from_below_h2_lumped() {
    let errs = |lump: bool| -> Vec<f64> {
        [4usize, 8, 16]
            .iter()
            .map(|&n| {
                let mut m = unit_cantilever(n, Kinematics::Linear).unwrap();
                if lump {
                    m = lumped(&m);
                }
                let w = modal_analysis(&m, 1, ModalDirection::Transverse)
                    .unwrap()
                    .omegas[0];
                w / omega_ref(0) - 1.0
            })
            .collect()
    };
    let c = errs(false);
    assert!(
        c.iter().all(|e| *e > 0.0),
        "consistent mass converges from above: {c:?}"
    );
    // reference: 2.1e-6 with 8 elements, 1.3e-7 with 16
    assert_rel("consistent ω₁ error, 8 elements", c[1], 2.1e-6, 0.05);
    assert_rel("consistent ω₁ error, 16 elements", c[2], 1.3e-7, 0.05);
    for k in 0..2 {
        let p = order(c[k], c[k + 1]);
        assert!((p - 4.0).abs() < 0.1, "consistent order {p}");
    }
    let l = errs(true);
    assert!(
        l.iter().all(|e| *e < 0.0),
        "lumped mass converges from below: {l:?}"
    );
    for k in 0..2 {
        let p = order(l[k], l[k + 1]);
        assert!((p - 2.0).abs() < 0.1, "lumped order {p}");
    }
}

#[test]
fn cantilever_with_tip_mass_matches_beta1() {
    for &(mu, beta) in &TIP_MASS_BETA1 {
        let m = unit_cantilever_with_tip_mass(32, mu).unwrap();
        let w = modal_analysis(&m, 1, ModalDirection::Transverse)
            .unwrap()
            .omegas[0];
        // the reference roots carry 6 significant digits
        assert_rel(
            &format!("ω₁ with tip mass μ = {mu}"),
            w,
            beam_omega(beta, 1.0, 1.0, 1.0),
            2e-5,
        );
    }
}

#[test]
fn pinned_free_beam_has_a_rigid_mode_then_the_pinned_free_roots() {
    let mut spec = BeamSpec::cantilever(1.0, unit_section(), 32, Kinematics::Linear);
    spec.root = RootSupport::Pinned {
        k_theta: 0.0,
        c_theta: 0.0,
    };
    let m = BeamModel::new(spec).unwrap();
    let r = modal_analysis(&m, 4, ModalDirection::Transverse).unwrap();
    assert_eq!(r.omegas[0], 0.0, "rigid mode reported as 0");
    for i in 0..3 {
        assert_rel(
            "pinned-free ω",
            r.omegas[i + 1],
            beam_omega(PINNED_FREE_BETA_L[i], 1.0, 1.0, 1.0),
            2e-5,
        );
    }
}

#[test]
fn linear_static_tip_load_and_moment_are_exact() {
    let (len, ei) = (0.34, 1.5e9 * 0.064 * 0.0026f64.powi(3) / 12.0);
    let sec = Section::from_stiffness(1.5e9 * 0.064 * 0.0026, ei, 0.15).unwrap();
    let model = BeamModel::new(BeamSpec::cantilever(len, sec, 7, Kinematics::Linear)).unwrap();
    let (p, mo) = (3.7, 0.21);
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(7, 0.0, p).unwrap();
    let s = solve_static(&model, &loads, &StaticOptions::with_load_steps(1).unwrap()).unwrap();
    let (_, v, th) = s.node(7);
    assert_rel("PL³/3EI", v, p * len.powi(3) / (3.0 * ei), 1e-12);
    assert_rel("PL²/2EI", th, p * len.powi(2) / (2.0 * ei), 1e-12);
    let mut loads = NodalLoads::zeros(&model);
    loads.set_moment(7, mo).unwrap();
    let s = solve_static(&model, &loads, &StaticOptions::with_load_steps(1).unwrap()).unwrap();
    let (_, v, th) = s.node(7);
    assert_rel("ML²/2EI", v, mo * len.powi(2) / (2.0 * ei), 1e-12);
    assert_rel("ML/EI", th, mo * len / ei, 1e-12);
    // reactions balance the moment
    assert_rel("root reaction moment", -s.reactions[2], mo, 1e-12);
}

#[test]
fn corotational_elastica_within_5e4_with_32_elements_second_order() {
    let opts = StaticOptions::with_load_steps(10).unwrap();
    for &(phi, v_ref, u_ref, th_ref) in &ELASTICA {
        let mut errs = Vec::new();
        for n in [16, 32] {
            let (m, l) = elastica_problem(phi, n).unwrap();
            let s = solve_static(&m, &l, &opts).unwrap();
            let (u, v, th) = s.node(n);
            errs.push(v / v_ref - 1.0);
            if n == 32 {
                assert_rel(&format!("v/L at PL²/EI = {phi}"), v, v_ref, 5e-4);
                assert_rel(&format!("u/L at PL²/EI = {phi}"), -u, u_ref, 1e-3);
                assert_rel(&format!("tip angle at PL²/EI = {phi}"), th, th_ref, 5e-4);
                assert!(s.residual < 1e-8 * phi, "residual {}", s.residual);
            }
        }
        let p = order(errs[0], errs[1]);
        assert!((p - 2.0).abs() < 0.1, "elastica order {p} at {phi}");
    }
}

#[test]
fn tip_moment_two_pi_rolls_the_beam_into_a_full_circle() {
    let m = unit_cantilever(32, Kinematics::Corotational).unwrap();
    let mut loads = NodalLoads::zeros(&m);
    loads.set_moment(32, 2.0 * std::f64::consts::PI).unwrap();
    let s = solve_static(&m, &loads, &StaticOptions::with_load_steps(8).unwrap()).unwrap();
    let (u, v, th) = s.node(32);
    // tip back at the root, tangent turned by 2π
    assert!(
        (1.0 + u).abs() < 2e-3 && v.abs() < 2e-3,
        "tip at ({}, {v})",
        1.0 + u
    );
    assert_rel("tip rotation", th, 2.0 * std::f64::consts::PI, 1e-9);
    // every node on the circle of radius L/2π centred at (0, L/2π)
    let rad = 1.0 / (2.0 * std::f64::consts::PI);
    for i in 0..=32 {
        let (u, v, _) = s.node(i);
        let (x, y) = (m.node_x(i) + u, v);
        // O(h²): each element chord keeps the length l while the arc it stands for is
        // longer by (κl)²/24 ≈ 1.6e-3 relative, accumulated along the beam
        let off = (x.hypot(y - rad) - rad).abs();
        assert!(off < 2e-3, "node {i} off the circle by {off:e} (L = 1)");
    }
    // half load: tip at (L sin φ/φ, L(1 − cos φ)/φ), φ = π
    let half = loads.scaled(0.5);
    let s = solve_static(&m, &half, &StaticOptions::with_load_steps(4).unwrap()).unwrap();
    let (u, v, _) = s.node(32);
    assert!((1.0 + u).abs() < 1e-3, "x tip {}", 1.0 + u);
    assert_rel(
        "semicircle tip height 2L/π",
        v,
        2.0 / std::f64::consts::PI,
        1e-3,
    );
}

fn rotated_mesh(m: &BeamModel, phi: f64) -> Vec<f64> {
    let mut q = vec![0.0; m.n_dofs()];
    for i in 0..m.n_nodes() {
        let x = m.node_x(i);
        q[3 * i] = x * (phi.cos() - 1.0);
        q[3 * i + 1] = x * phi.sin();
        q[3 * i + 2] = phi;
    }
    q
}

#[test]
fn rigid_rotation_by_several_turns_gives_zero_internal_force() {
    let mut spec = BeamSpec::cantilever(0.34, unit_section(), 12, Kinematics::Corotational);
    spec.root = RootSupport::Pinned {
        k_theta: 0.0,
        c_theta: 0.0,
    };
    let m = BeamModel::new(spec).unwrap();
    let zeros = vec![0.0; m.n_dofs()];
    let mut r = vec![0.0; m.n_dofs()];
    for phi in [
        0.5,
        2.0 * std::f64::consts::PI,
        3.0 * 2.0 * std::f64::consts::PI + 2.7,
        -13.0,
    ] {
        let q = rotated_mesh(&m, phi);
        let kin = Kinematic {
            q: &q,
            v: None,
            a: None,
        };
        let u = assemble(&m, kin, &zeros, &mut r, None);
        let fmax = r.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        // compare with the force scale of a unit deformation: EA·1e-12
        assert!(
            fmax < 1e7 * 1e-12,
            "rotation {phi}: internal force {fmax:e}"
        );
        assert!(u.abs() < 1e-16, "strain energy {u:e}");
    }
}

#[test]
fn global_jacobian_matches_finite_differences() {
    // a pinned hub with a spring, a damper, a point mass and mass-proportional damping
    let mut spec = BeamSpec::cantilever(
        0.5,
        Section::from_stiffness(2e4, 3.0, 0.4).unwrap(),
        5,
        Kinematics::Corotational,
    );
    spec.root = RootSupport::Hub {
        inertia: 0.02,
        k_theta: 5.0,
        c_theta: 0.3,
    };
    spec.point_masses.push(PointMass {
        node: 5,
        mass: 0.1,
        inertia: 1e-4,
    });
    spec.damping = Rayleigh {
        alpha_mass: 0.7,
        beta_stiffness: 0.0,
    };
    let m = BeamModel::new(spec).unwrap();
    let n = m.n_dofs();
    let nfix = m.n_fixed();
    let pseudo = |i: usize, s: f64| ((i as f64 * 1.7 + s).sin()) * 0.3;
    let mut q: Vec<f64> = (0..n).map(|i| pseudo(i, 0.0) * 0.2).collect();
    let v: Vec<f64> = (0..n).map(|i| pseudo(i, 1.0) * 5.0).collect();
    let a: Vec<f64> = (0..n).map(|i| pseudo(i, 2.0) * 40.0).collect();
    for x in q.iter_mut().take(nfix) {
        *x = 0.0;
    }
    let f = vec![0.0; n];
    let mut r0 = vec![0.0; n];
    let mut rp = vec![0.0; n];
    let mut rm = vec![0.0; n];
    let h = 1e-6;
    for (which, w) in [
        (0, (1.0, 0.0, 0.0)),
        (1, (0.0, 1.0, 0.0)),
        (2, (0.0, 0.0, 1.0)),
    ] {
        let mut band = band_for(&m);
        let weights = JacobianWeights {
            stiffness: w.0,
            velocity: w.1,
            acceleration: w.2,
        };
        assemble(
            &m,
            Kinematic {
                q: &q,
                v: Some(&v),
                a: Some(&a),
            },
            &f,
            &mut r0,
            Some((&mut band, weights)),
        );
        let scale = (0..n - nfix)
            .map(|i| band.get(i, i).abs())
            .fold(1.0, f64::max);
        let mut worst = 0.0f64;
        for k in nfix..n {
            let (mut qp, mut vp, mut ap) = (q.clone(), v.clone(), a.clone());
            let (mut qm, mut vm, mut am) = (q.clone(), v.clone(), a.clone());
            match which {
                0 => {
                    qp[k] += h;
                    qm[k] -= h
                }
                1 => {
                    vp[k] += h;
                    vm[k] -= h
                }
                _ => {
                    ap[k] += h;
                    am[k] -= h
                }
            }
            assemble(
                &m,
                Kinematic {
                    q: &qp,
                    v: Some(&vp),
                    a: Some(&ap),
                },
                &f,
                &mut rp,
                None,
            );
            assemble(
                &m,
                Kinematic {
                    q: &qm,
                    v: Some(&vm),
                    a: Some(&am),
                },
                &f,
                &mut rm,
                None,
            );
            for d in nfix..n {
                let fd = (rp[d] - rm[d]) / (2.0 * h);
                worst = worst.max((fd - band.get(d - nfix, k - nfix)).abs() / scale);
            }
        }
        assert!(
            worst < 2e-5,
            "Jacobian block {which}: relative FD mismatch {worst:e}"
        );
    }
}
