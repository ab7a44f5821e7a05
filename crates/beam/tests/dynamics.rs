//! Generalized-α transient: energy conservation (ρ∞ = 1), monotone decay (ρ∞ < 1), second-order
//! convergence in the time step, rigid spinning of a pinned beam.

mod common;
use common::order;

use flexrig_beam::canonical::*;
use flexrig_beam::energy::{kinetic_and_strain_energy, kinetic_energy, strain_energy};
use flexrig_beam::*;

/// Initial velocity: the first (linear) mode shape scaled to a tip speed `tip_speed`.
fn mode1_velocity(model: &BeamModel, tip_speed: f64) -> Vec<f64> {
    let r = modal_analysis(model, 1, ModalDirection::Transverse).unwrap();
    let phi = &r.shapes[0];
    let s = tip_speed / phi[3 * model.tip_node() + 1];
    phi.iter().map(|x| x * s).collect()
}

/// Free vibration from the undeformed state with initial velocity `v0` (a smooth start: no
/// unresolved high-frequency content).
fn run(
    model: &BeamModel,
    v0: Vec<f64>,
    rho: f64,
    h: f64,
    steps: usize,
    mut each: impl FnMut(&State),
) -> State {
    let loads = NodalLoads::zeros(model);
    let n = model.n_dofs();
    let mut s = State::new(model, vec![0.0; n], v0, 0.0, &loads).unwrap();
    let mut ws = Workspace::new(model);
    let ga = GeneralizedAlpha::new(rho)
        .unwrap()
        .with_newton(30, 1e-11)
        .unwrap();
    for _ in 0..steps {
        ga.step(model, &mut s, &mut ws, h, &loads).unwrap();
        each(&s);
    }
    s
}

/// A unit beam (L = 1, EI = 1, ρA = 1) with EA = `ea_ratio`·EI/L².
fn beam(elements: usize, kin: Kinematics, ea_ratio: f64) -> BeamModel {
    let sec = Section::from_stiffness(ea_ratio, 1.0, 1.0).unwrap();
    BeamModel::new(BeamSpec::cantilever(1.0, sec, elements, kin)).unwrap()
}

fn period1() -> f64 {
    2.0 * std::f64::consts::PI / beam_omega(CANTILEVER_BETA_L[0], 1.0, 1.0, 1.0)
}

#[test]
fn rho_one_conserves_energy_over_1000_periods_linear_and_corotational() {
    // linear: the trapezoidal rule conserves ½vᵀMv + ½qᵀKq exactly; bound 1e-9 (round-off)
    let m = unit_cantilever(8, Kinematics::Linear).unwrap();
    let v0 = mode1_velocity(&m, 0.1);
    let e0 = kinetic_energy(&m, &vec![0.0; m.n_dofs()], &v0);
    let mut worst = 0.0f64;
    run(&m, v0, 1.0, period1() / 40.0, 40_000, |s| {
        let e = s.energy(&m);
        worst = worst.max(((e.kinetic + e.strain) / e0 - 1.0).abs());
    });
    assert!(worst < 1e-9, "linear energy drift {worst:e}");
    // corotational (tip amplitude ≈ 0.2 L), 4 elements, EA L²/EI = 1e3, h = T₁/100: bounded,
    // no drift. (The trapezoidal rule is only conditionally stable for nonlinear problems; with
    // stiff unresolved modes use ρ∞ < 1.)
    let m = beam(4, Kinematics::Corotational, 1e3);
    let v0 = mode1_velocity(&m, 0.2 * 3.516);
    let e0 = kinetic_energy(&m, &vec![0.0; m.n_dofs()], &v0);
    let mut worst = 0.0f64;
    let mut last = 0.0;
    run(&m, v0, 1.0, period1() / 100.0, 100_000, |s| {
        let e = s.energy(&m);
        last = (e.kinetic + e.strain) / e0 - 1.0;
        worst = worst.max(last.abs());
    });
    println!("corotational energy: worst {worst:e}, final {last:e}");
    assert!(worst < 5e-4, "corotational energy error {worst:e}");
}

#[test]
fn rho_below_one_decays_monotonically() {
    for kin in [Kinematics::Linear, Kinematics::Corotational] {
        // generalized-α decays a quadratic form of (q, q̇, â), not the physical energy step by
        // step; the physical energy averaged over each period must decrease monotonically
        let m = beam(8, kin, 1e4);
        let v0 = mode1_velocity(&m, 0.3 * 3.516);
        let e0 = kinetic_energy(&m, &vec![0.0; m.n_dofs()], &v0);
        let per = 10;
        let mut block = Vec::new();
        let mut means = Vec::new();
        let end = run(&m, v0, 0.6, period1() / per as f64, 100 * per, |s| {
            let e = s.energy(&m);
            block.push(e.kinetic + e.strain);
            if block.len() == per {
                means.push(block.iter().sum::<f64>() / per as f64);
                block.clear();
            }
        });
        for w in means.windows(2) {
            assert!(
                w[1] < w[0],
                "{kin:?}: period-mean energy rose {} → {}",
                w[0],
                w[1]
            );
        }
        let e = end.energy(&m);
        assert!(e.kinetic + e.strain < 0.9 * e0, "{kin:?}: no decay");
        assert!((e.dissipated - (e0 - e.kinetic - e.strain)).abs() < 1e-12 * e0);
    }
}

#[test]
fn second_order_in_the_time_step() {
    for kin in [Kinematics::Linear, Kinematics::Corotational] {
        for rho in [1.0, 0.5, 0.0] {
            let m = beam(4, kin, 1e3);
            let v0 = mode1_velocity(&m, 0.4 * 3.516);
            let t_end = 0.3 * period1();
            let tip = |k: usize| {
                let s = run(&m, v0.clone(), rho, t_end / k as f64, k, |_| {});
                s.q[3 * 4 + 1]
            };
            let reference = tip(81_920);
            let ks: &[usize] = if kin == Kinematics::Linear {
                &[80, 160, 320, 640]
            } else {
                &[640, 1280, 2560, 5120]
            };
            let e: Vec<f64> = ks.iter().map(|&k| tip(k) - reference).collect();
            println!(
                "{kin:?} {rho}: {e:?} orders {} {} {}",
                order(e[0], e[1]),
                order(e[1], e[2]),
                order(e[2], e[3])
            );
            for i in 0..3 {
                let p = order(e[i], e[i + 1]);
                assert!(p > 1.7 && p < 2.3, "{kin:?} ρ∞ = {rho}: order {p} ({e:?})");
            }
        }
    }
}

#[test]
fn variable_step_stays_second_order() {
    // the rig halves and restores h around contact: alternate h and h/2
    let m = beam(4, Kinematics::Corotational, 1e3);
    let v0 = mode1_velocity(&m, 0.4 * 3.516);
    let t_end = 0.3 * period1();
    let loads = NodalLoads::zeros(&m);
    let tip = |k: usize| {
        let n = m.n_dofs();
        let mut s = State::new(&m, vec![0.0; n], v0.clone(), 0.0, &loads).unwrap();
        let mut ws = Workspace::new(&m);
        let ga = GeneralizedAlpha::new(0.8)
            .unwrap()
            .with_newton(30, 1e-12)
            .unwrap();
        let h = t_end / k as f64;
        for i in 0..k {
            if i % 2 == 0 {
                ga.step(&m, &mut s, &mut ws, h, &loads).unwrap();
            } else {
                ga.step(&m, &mut s, &mut ws, 0.5 * h, &loads).unwrap();
                ga.step(&m, &mut s, &mut ws, 0.5 * h, &loads).unwrap();
            }
        }
        s.q[13]
    };
    let reference = tip(65_536);
    let e: Vec<f64> = [512, 1024, 2048, 4096]
        .iter()
        .map(|&k| tip(k) - reference)
        .collect();
    println!(
        "var: {e:?} orders {} {} {}",
        order(e[0], e[1]),
        order(e[1], e[2]),
        order(e[2], e[3])
    );
    for i in 0..3 {
        let p = order(e[i], e[i + 1]);
        assert!(p > 1.9 && p < 2.2, "variable-step order {p} ({e:?})");
    }
}

#[test]
fn a_free_pinned_beam_spins_rigidly_for_several_turns() {
    let sec = Section::from_stiffness(1e4, 1.0, 1.0).unwrap();
    let mut spec = BeamSpec::cantilever(1.0, sec, 8, Kinematics::Corotational);
    spec.root = RootSupport::Hub {
        inertia: 0.1,
        k_theta: 0.0,
        c_theta: 0.0,
    };
    let m = BeamModel::new(spec).unwrap();
    let omega = 2.0;
    let n = m.n_dofs();
    let mut v = vec![0.0; n];
    for i in 0..m.n_nodes() {
        v[3 * i + 1] = omega * m.node_x(i);
        v[3 * i + 2] = omega;
    }
    let loads = NodalLoads::zeros(&m);
    let mut s = State::new(&m, vec![0.0; n], v, 0.0, &loads).unwrap();
    let mut ws = Workspace::new(&m);
    let ga = GeneralizedAlpha::new(1.0).unwrap();
    let e0 = s.energy(&m).kinetic;
    // exact: ½ (J_hub + ρAL³/3) ω²
    assert!((e0 - 0.5 * (0.1 + 1.0 / 3.0) * omega * omega).abs() < 1e-12);
    let h = 0.01;
    let steps = (3.0 * 2.0 * std::f64::consts::PI / omega / h) as usize;
    for _ in 0..steps {
        ga.step(&m, &mut s, &mut ws, h, &loads).unwrap();
    }
    let e = s.energy(&m);
    // only the centrifugal stretch (strain ~ ρAω²L²/EA = 4e-4) deforms the beam
    assert!(e.strain < 1e-4 * e0, "strain energy {}", e.strain);
    // the trapezoidal rule is not exactly conservative for the nonlinear, unresolved axial
    // vibration the sudden spin-up starts (h ω_axial ≈ 1.6)
    assert!(
        ((e.kinetic + e.strain) / e0 - 1.0).abs() < 2e-4,
        "energy {:?}",
        e
    );
    let (_, _, th) = s.node(8);
    assert!(th > 6.0 * std::f64::consts::PI - 0.2, "turned {th} rad");
    assert!(
        (th / (omega * s.t) - 1.0).abs() < 2e-3,
        "tip angle {th} vs {}",
        omega * s.t
    );
    // still straight: every node on the line from the root at the tip angle, same θ
    for i in 0..=8 {
        let (u, v, t) = s.node(i);
        let (x, y) = (m.node_x(i) + u, v);
        // (Coriolis forces of the axial stretch vibration bend it very slightly)
        assert!(
            (x * th.sin() - y * th.cos()).abs() < 1e-4,
            "node {i} off the line"
        );
        assert!((t - th).abs() < 1e-3, "node {i} θ {t} vs {th}");
    }
}

#[test]
fn hub_torque_does_work_that_is_accounted() {
    let mut spec = BeamSpec::cantilever(
        0.34,
        Section::from_stiffness(1e5, 0.14, 0.15).unwrap(),
        8,
        Kinematics::Corotational,
    );
    spec.root = RootSupport::Hub {
        inertia: 1e-3,
        k_theta: 1.2334,
        c_theta: 0.0,
    };
    let m = BeamModel::new(spec).unwrap();
    let mut loads = NodalLoads::zeros(&m);
    let mut s = State::at_rest(&m, &loads).unwrap();
    let mut ws = Workspace::new(&m);
    let ga = GeneralizedAlpha::new(1.0).unwrap();
    let h = 2e-4;
    for k in 0..2000 {
        let t = (k + 1) as f64 * h;
        loads.set_moment(0, 0.05 * (30.0 * t).sin()).unwrap();
        ga.step(&m, &mut s, &mut ws, h, &loads).unwrap();
    }
    let e = s.energy(&m);
    assert!(e.external_work.abs() > 1e-4);
    // trapezoidal work vs energy: O(h²) mismatch
    assert!(e.dissipated.abs() < 1e-3 * e.external_work.abs(), "{e:?}");
}

#[test]
fn rayleigh_damping_gives_the_modal_damping_ratio() {
    // proportional damping keeps the first mode decoupled: exact response of the modal
    // coordinate with ζ = a₀/(2ω) + a₁ω/2, v_tip(t) = V e^{−ζωt} sin(ω_d t)/ω_d
    let mut spec = BeamSpec::cantilever(1.0, unit_section(), 8, Kinematics::Linear);
    spec.damping = Rayleigh {
        alpha_mass: 0.2,
        beta_stiffness: 1e-3,
    };
    let m = BeamModel::new(spec).unwrap();
    let omega = modal_analysis(&m, 1, ModalDirection::Transverse)
        .unwrap()
        .omegas[0];
    let zeta = 0.2 / (2.0 * omega) + 1e-3 * omega / 2.0;
    let wd = omega * (1.0 - zeta * zeta).sqrt();
    let v0 = mode1_velocity(&m, 1.0);
    let period = 2.0 * std::f64::consts::PI / omega;
    let steps = 900;
    let t_end = 2.25 * period;
    let s = run(&m, v0, 1.0, t_end / steps as f64, steps, |_| {});
    let exact = (-zeta * omega * t_end).exp() * (wd * t_end).sin() / wd;
    let got = s.q[3 * 8 + 1];
    assert!(
        (got - exact).abs() < 1e-3 * exact.abs(),
        "tip {got} vs {exact} (ζ = {zeta})"
    );
}

/// The kinetic and strain energy in one pass over the elements are the separate passes' bit
/// for bit (linear and corotational, lumped and consistent mass, a tip mass with rotary
/// inertia, a deformed and moving state), and for a rigid turn of the corotational beam about
/// its root (angle φ, rate ω) they are the rod's ½ (ρAL³/3 + m L² + J) ω² and zero.
#[test]
fn the_energies_in_one_pass_are_the_separate_ones() {
    let (tip_mass, tip_inertia) = (0.3, 0.01);
    for kin in [Kinematics::Linear, Kinematics::Corotational] {
        for mass in [MassMatrix::Lumped, MassMatrix::Consistent] {
            let mut spec = BeamSpec::cantilever(1.0, canonical::unit_section(), 8, kin);
            spec.mass = mass;
            spec.point_masses.push(PointMass {
                node: 8,
                mass: tip_mass,
                inertia: tip_inertia,
            });
            let m = BeamModel::new(spec).unwrap();
            let n = m.n_dofs();
            let q: Vec<f64> = (0..n).map(|i| 0.1 * (1.7 * i as f64).sin()).collect();
            let v: Vec<f64> = (0..n).map(|i| (0.9 * i as f64).cos()).collect();
            let (t, u) = kinetic_and_strain_energy(&m, &q, &v);
            assert_eq!(
                t.to_bits(),
                kinetic_energy(&m, &q, &v).to_bits(),
                "{kin:?} {mass:?}"
            );
            assert_eq!(
                u.to_bits(),
                strain_energy(&m, &q).to_bits(),
                "{kin:?} {mass:?}"
            );
            assert!(t > 0.0 && u > 0.0);
            if kin == Kinematics::Corotational && mass == MassMatrix::Consistent {
                let (phi, omega) = (2.0f64, 3.0);
                let mut q = vec![0.0; n];
                let mut v = vec![0.0; n];
                for node in 0..=8 {
                    let x = node as f64 / 8.0;
                    q[3 * node..3 * node + 3].copy_from_slice(&[
                        x * phi.cos() - x,
                        x * phi.sin(),
                        phi,
                    ]);
                    v[3 * node..3 * node + 3].copy_from_slice(&[
                        -x * phi.sin() * omega,
                        x * phi.cos() * omega,
                        omega,
                    ]);
                }
                let (t, u) = kinetic_and_strain_energy(&m, &q, &v);
                let want = 0.5 * (1.0 / 3.0 + tip_mass + tip_inertia) * omega * omega;
                common::assert_rel("rigid turn's kinetic energy", t, want, 1e-13);
                assert!(u.abs() < 1e-18 * 1e7, "rigid turn's strain energy {u:e}");
            }
        }
    }
}
