//! Prints the η table for a given mesh and step: `eta_probe ELEMENTS STEPS`.
use flexrig_impact::ClSolver;
use flexrig_impact::eta::{EtaSettings, eta_table};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let settings = EtaSettings {
        solver: ClSolver {
            elements: a.get(1).map_or(16, |s| s.parse().unwrap()),
            steps_per_contact: a.get(2).map_or(200, |s| s.parse().unwrap()),
        },
        ..EtaSettings::DEFAULT
    };
    let t0 = std::time::Instant::now();
    for r in eta_table(&settings).unwrap() {
        println!(
            "m_h {:>6} k_d {:>6.0e} m_e {:>4} n {}: f_cj {:>10.3} (lumped {:>10.3}) f_cl {:>10.3} eta_fe {:.6} eta_lumped {:.6} gamma_eff {:?}",
            r.case.m_h,
            r.case.k_delta,
            r.case.m_e,
            r.n,
            r.f_cj_n,
            r.f_cj_lumped_n,
            r.f_cl_n,
            r.eta_fe,
            r.eta_lumped_2_3,
            r.gamma_eff
        );
    }
    println!("{:.2} s", t0.elapsed().as_secs_f64());
}
