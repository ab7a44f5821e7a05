//! Property-based stress tests: random but valid inputs never panic and give finite results or a
//! clean error; invalid inputs are always input errors.

use flexrig_beam::*;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn linear_static_tip_deflection_is_pl3_over_3ei_for_any_valid_beam(
        len in 0.01f64..10.0, e in 1e6f64..1e12, w in 1e-3f64..0.5, t in 1e-4f64..0.05,
        n in 1usize..40, p in -1e3f64..1e3,
    ) {
        let mat = Material::new(e, 1000.0).unwrap();
        let sec = Section::rectangular(&mat, w, t).unwrap();
        let m = BeamModel::new(BeamSpec::cantilever(len, sec, n, Kinematics::Linear)).unwrap();
        let mut loads = NodalLoads::zeros(&m);
        loads.set_force(n, 0.0, p).unwrap();
        let s = solve_static(&m, &loads, &StaticOptions::with_load_steps(1).unwrap()).unwrap();
        let want = p * len.powi(3) / (3.0 * sec.ei());
        prop_assert!((s.node(n).1 - want).abs() <= 1e-8 * want.abs().max(1e-300));
    }

    #[test]
    fn corotational_steps_with_random_step_sizes_and_loads_stay_finite(
        hs in proptest::collection::vec(1e-5f64..2e-3, 1..40),
        f in -5.0f64..5.0, rho in 0.0f64..1.0,
    ) {
        let mat = Material::new(1.5e9, 905.0).unwrap();
        let sec = Section::rectangular(&mat, 0.064, 0.0026).unwrap();
        let mut spec = BeamSpec::cantilever(0.34, sec, 8, Kinematics::Corotational);
        spec.point_masses.push(PointMass { node: 8, mass: 0.1, inertia: 0.0 });
        let m = BeamModel::new(spec).unwrap();
        let mut loads = NodalLoads::zeros(&m);
        let mut s = State::at_rest(&m, &loads).unwrap();
        let mut ws = Workspace::new(&m);
        let ga = GeneralizedAlpha::new(rho).unwrap();
        for (k, h) in hs.iter().enumerate() {
            loads.set_force(8, 0.0, f * ((k as f64) * 0.3).sin()).unwrap();
            match ga.step(&m, &mut s, &mut ws, *h, &loads) {
                Ok(_) => prop_assert!(s.q.iter().all(|x| x.is_finite())),
                Err(e) => prop_assert!(!e.is_input_error(), "{e}"),
            }
        }
    }

    #[test]
    fn non_positive_or_nan_dimensions_are_input_errors(
        bad in prop_oneof![Just(f64::NAN), Just(0.0), -1e3f64..0.0, Just(f64::INFINITY)],
        which in 0usize..4,
    ) {
        let mut v = [1e9, 900.0, 0.05, 0.002];
        v[which] = bad;
        let r = Material::new(v[0], v[1]).and_then(|m| Section::rectangular(&m, v[2], v[3]));
        let e = r.unwrap_err();
        prop_assert!(e.is_input_error());
        let field = ["youngs", "density", "width", "thickness"][which];
        prop_assert!(e.to_string().contains(field), "{e}");
    }
}
