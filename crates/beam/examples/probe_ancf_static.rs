//! Elastica with the ANCF element: tip errors against the extensible shooting reference for
//! several meshes and integration rules. `cargo run --release --example probe_ancf_static`.
use flexrig_beam::*;

fn shooting(phi: f64, ea_ratio: f64, n: usize) -> (f64, f64, f64) {
    let shoot = |theta_tip: f64| -> [f64; 4] {
        let h = -1.0 / n as f64;
        let f = |y: [f64; 4]| -> [f64; 4] {
            let stretch = 1.0 + phi * y[0].sin() / ea_ratio;
            let (s, c) = y[0].sin_cos();
            [y[1], -phi * stretch * c, stretch * c, stretch * s]
        };
        let mut y = [theta_tip, 0.0, 0.0, 0.0];
        for _ in 0..n {
            let at = |k: [f64; 4], c: f64| std::array::from_fn(|i| y[i] + c * k[i]);
            let k1 = f(y);
            let k2 = f(at(k1, 0.5 * h));
            let k3 = f(at(k2, 0.5 * h));
            let k4 = f(at(k3, h));
            for i in 0..4 {
                y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        y
    };
    let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
    for _ in 0..70 {
        let mid = 0.5 * (lo + hi);
        if shoot(mid)[0] < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let th = 0.5 * (lo + hi);
    let y = shoot(th);
    (-y[3], 1.0 + y[2], th)
}

fn main() {
    let ea_ratio: f64 = std::env::args()
        .nth(1)
        .map_or(1.08e6, |s| s.parse().unwrap());
    for kin in [Kinematics::Ancf, Kinematics::Corotational] {
        for &ne in &[8usize, 16, 32, 64] {
            let mut worst: f64 = 0.0;
            let mut its = 0;
            for &phi in &[1.0, 2.0, 5.0, 10.0] {
                let sec = Section::from_stiffness(ea_ratio, 1.0, 1.0).unwrap();
                let model = BeamModel::new(BeamSpec::cantilever(1.0, sec, ne, kin)).unwrap();
                let mut loads = NodalLoads::zeros(&model);
                loads.set_force(ne, 0.0, phi).unwrap();
                let s = solve_static(&model, &loads, &StaticOptions::new(10, 50, 1e-10).unwrap())
                    .unwrap();
                its += s.iterations;
                let (u, v, th) = s.node(ne);
                let (vr, ur, tr) = shooting(phi, ea_ratio, 20000);
                let e = [(v - vr).abs(), (-u - ur).abs(), (th - tr).abs()];
                worst = worst.max(e.iter().cloned().fold(0.0, f64::max));
                if ne == 32 {
                    println!(
                        "  {kin:?} phi {phi}: dv {:.2e} du {:.2e} dth {:.2e}",
                        e[0], e[1], e[2]
                    );
                }
            }
            println!("{kin:?} ne {ne}: worst abs error {worst:.3e}, iterations {its}");
        }
    }
}
