use flexrig_impact::eta::*;
use flexrig_impact::map::*;
use flexrig_impact::cl_modal::*;
use flexrig_impact::graded::*;
use flexrig_impact::modal_run::ModalOptions;
use flexrig_lumped::fig6::Fig6Case;
use std::time::Instant;
fn main() {
    let spec = MapSpec { m_h: 4.0, n: 2.0, mass_ratio: LogRange { from: 1e-3, to: 1e2, points: 8 }, stiffness_ratio: LogRange { from: 1e-7, to: 1.0, points: 8 } };
    let mut rows = vec![];
    for &y in &spec.stiffness_ratio.values() { for &x in &spec.mass_ratio.values() {
        let case = Fig6Case { m_h: 4.0, k_delta: y * 1e8, m_e: x * 10.0 };
        let s = case_setup(&case, 2.0, &EtaSettings::DEFAULT).unwrap();
        let t0 = Instant::now();
        let _ = flexrig_impact::cj::run_cj(&s, 1e-10).unwrap();
        let t1 = Instant::now();
        let modes = cl_tip_modes(&s, &GradedMesh::DEFAULT).unwrap();
        let t2 = Instant::now();
        let cl = run_on_modes(&s, &modes, &ModalOptions { tol: 1e-6, ..ModalOptions::DEFAULT }).unwrap();
        let t3 = Instant::now();
        let _ = run_placed(&s, &ModalOptions { tol: 1e-7, ..ModalOptions::DEFAULT }).unwrap();
        let t4 = Instant::now();
        let _ = effective_gamma(&case, 2.0, cl.first.peak_force_n).unwrap();
        let t5 = Instant::now();
        let ms = |a: Instant, b: Instant| (b - a).as_secs_f64() * 1e3;
        rows.push((ms(t0,t5), format!("x {x:.1e} y {y:.1e}: cj {:.2} eig {:.2} ({} modes) cl {:.2} ({} steps) placed {:.2} gamma {:.2}", ms(t0,t1), ms(t1,t2), modes.len(), ms(t2,t3), cl.work, ms(t3,t4), ms(t4,t5))));
    }}
    rows.sort_by(|a,b| b.0.total_cmp(&a.0));
    let total: f64 = rows.iter().map(|r| r.0).sum();
    println!("mean {:.1} ms", total / rows.len() as f64);
    for r in rows.iter().take(12) { println!("{:.1} {}", r.0, r.1); }
}
