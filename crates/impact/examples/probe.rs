use flexrig_impact::cl_modal::*;
use flexrig_impact::eta::{EtaSettings, case_setup};
use flexrig_impact::graded::{GradedMesh, cl_tip_modes};
use flexrig_impact::modal_run::ModalOptions;
use flexrig_impact::cj;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let tol: f64 = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(1e-6);
    let zone: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(8.0);
    let cut: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(60.0);
    let reference = [25576.8, 3838.0, 34910.0, 3834.9, 7597.2, 740.2, 33854.5, 3106.0, 456538.5, 147639.9, 468393.7, 147625.3, 7751.6, 792.5, 63359.8, 7267.8];
    let mut i = 0;
    for case in flexrig_lumped::fig6::cases() {
        for n in [1.0, 2.0] {
            let s = case_setup(&case, n, &EtaSettings::DEFAULT).unwrap();
            let opts = ModalOptions { tol, ..ModalOptions::DEFAULT };
            let cj_ref = cj::run_cj(&s, 1e-12).unwrap().first.peak_force_n;
            let cjm = run_cj_modal(&s, &opts).unwrap();
            let mesh = GradedMesh { zone_elements: zone, mode_cut: cut, ..GradedMesh::DEFAULT };
            let t0 = Instant::now();
            let modes = cl_tip_modes(&s, &mesh).unwrap();
            let t1 = Instant::now();
            let clm = run_on_modes(&s, &modes, &opts).unwrap();
            let t2 = Instant::now();
            let pl = run_placed(&s, &opts).unwrap();
            let nel = mesh.element_lengths(&s).unwrap().len();
            println!("{:6} {:5.0e} {:5} n={} CJ dop {:.6e} modal rel {:+.1e} | CL {:.6e} vs ref {:+.1e} el {} modes {} steps {} eig {:.1}ms run {:.2}ms | placed {:.4e} ({:+.2})",
                case.m_h, case.k_delta, case.m_e, n, cj_ref, cjm.first.peak_force_n/cj_ref-1.0,
                clm.first.peak_force_n, clm.first.peak_force_n/reference[i]-1.0, nel, modes.len(), clm.work,
                (t1-t0).as_secs_f64()*1e3, (t2-t1).as_secs_f64()*1e3, pl.first.peak_force_n, pl.first.peak_force_n/clm.first.peak_force_n-1.0);
            i += 1;
        }
    }
}
