use flexrig_impact::cl_modal::*;
use flexrig_impact::eta::{EtaSettings, case_setup};
use flexrig_impact::graded::{GradedMesh, cl_tip_modes};
use flexrig_impact::modal_run::ModalOptions;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let tol: f64 = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(1e-6);
    let periods: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(3.0);
    let joint = args.get(3).cloned().unwrap_or("held".into());
    for case in flexrig_lumped::fig6::cases() {
        for n in [1.0, 2.0] {
            let mut st = EtaSettings::DEFAULT;
            if joint != "held" { st.joint = flexrig_impact::Joint::FreeHub { rotor_inertia: joint.parse().unwrap() }; }
            let s = case_setup(&case, n, &st).unwrap();
            let t1 = 2.0 * std::f64::consts::PI * (s.link.cj_tip_mass() / s.link.k_delta).sqrt();
            let opts = ModalOptions { tol, window_s: Some(periods * t1), max_steps: 2_000_000 };
            let t0 = Instant::now();
            let modes = cl_tip_modes(&s, &GradedMesh::DEFAULT).unwrap();
            let cl = run_on_modes(&s, &modes, &opts).unwrap();
            let cj = run_cj_modal(&s, &opts).unwrap();
            let dt = t0.elapsed().as_secs_f64() * 1e3;
            println!("{:6} {:5.0e} {:5} n={} T1 {:.2e} | CL {} contacts first {:.5e} overall {:.5e} at {:.3e} {:?} steps {} E {:.2e} | CJ {} contacts first {:.5e} overall {:.5e} {:?} | {:.1} ms",
              case.m_h, case.k_delta, case.m_e, n, t1, cl.contacts.len(), cl.first.peak_force_n, cl.overall.peak_force_n, cl.overall.time_of_peak_s, cl.ended, cl.work, cl.energy_j.1/cl.energy_j.0-1.0,
              cj.contacts.len(), cj.first.peak_force_n, cj.overall.peak_force_n, cj.ended, dt);
        }
    }
}
