//! Where the spin-up benchmark's time goes, and what each setting costs against its error:
//! the elastica reference by modes and tolerance, the FE beam by elements and step, each timed
//! and compared with a converged reference (7 modes at rtol 1e-10 is the yardstick: 6 vs 7
//! modes differ by 7e-8 of the max, docs/driven.md).
//!
//! ```sh
//! cargo run --release -p flexrig-impact --example spin_up_cost [omega_s] [case] [fe]
//! ```
//! `case`: `simo` (the 10 m beam, default) or `kane` (the 8 m aluminium beam); a third argument
//! `fe` times the FE beam only.

use std::time::Instant;

use flexrig_impact::spin_up::{SpinUp, spin_up_fe, spin_up_linear, spin_up_reference};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let omega: f64 = args.get(1).map_or(6.0, |a| a.parse().unwrap());
    let spec = match args.get(2).map(String::as_str) {
        Some("kane") => SpinUp::kane_ryan_banerjee(omega),
        _ => SpinUp::simo_vu_quoc(omega),
    };
    let time = |f: &mut dyn FnMut()| {
        let t0 = Instant::now();
        f();
        t0.elapsed().as_secs_f64()
    };
    let mut reference = None;
    let s = time(&mut || reference = Some(spin_up_reference(&spec, 7, 1e-10).unwrap()));
    let reference = reference.unwrap();
    println!(
        "yardstick: 7 modes rtol 1e-10: {s:.2} s, max {:.6} m",
        reference.max_abs()
    );
    let fe_only = args.get(3).map(String::as_str) == Some("fe");
    for modes in if fe_only { vec![] } else { vec![3, 4, 5, 6] } {
        for rtol in [1e-5, 1e-7, 1e-9] {
            let mut r = None;
            let s = time(&mut || r = Some(spin_up_reference(&spec, modes, rtol).unwrap()));
            println!(
                "reference {modes} modes rtol {rtol:e}: {s:.3} s, error {:.2e}",
                r.unwrap().difference(&reference)
            );
        }
    }
    for modes in if fe_only { vec![] } else { vec![2, 4, 5] } {
        let mut r = None;
        let s = time(&mut || r = Some(spin_up_linear(&spec, modes, 1e-8).unwrap()));
        let r = r.unwrap();
        println!(
            "linear {modes} modes rtol 1e-8: {s:.3} s, end {:.3e} m",
            r.tip_deflection_m.last().unwrap()
        );
    }
    for elements in [8, 12, 16, 24] {
        for max_step in [1e-3, 2e-3, 5e-3, 1e-2] {
            let mut r = None;
            let s = time(&mut || r = Some(spin_up_fe(&spec, elements, max_step)));
            match r.unwrap() {
                Ok(r) => println!(
                    "FE {elements} elements step {max_step:e}: {s:.3} s, error {:.2e}",
                    r.difference(&reference)
                ),
                Err(e) => println!("FE {elements} elements step {max_step:e}: {e}"),
            }
        }
    }
}
