//! Where one simulated impact's time goes (scratch profiling aid).
use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::chain::Chain;
use flexrig_impact::cl_modal::{run_on_modes, run_on_modes_against};
use flexrig_impact::graded::{GradedMesh, cl_tip_modes};
use flexrig_impact::modal_run::ModalOptions;
use flexrig_impact::{FreeMassImpact, Joint, LinkParams};
use std::time::Instant;

fn main() {
    let args: Vec<f64> = std::env::args().skip(1).map(|a| a.parse().unwrap()).collect();
    let (m_e, k_delta, cl, m_h, free) = (args[0], args[1], args[2] > 0.5, args[3], args[4] > 0.5);
    let tol = args.get(5).copied().unwrap_or(1e-6);
    let scale = args.get(6).copied().unwrap_or(0.0);
    let hertz = Hertz::new(7.359e7, 1.961).unwrap();
    for &v in &[0.5, 1.0, 2.0, 4.0, 8.0] {
        let setup = FreeMassImpact {
            m_h,
            v0: v,
            link: LinkParams { m_r: 0.051, length: 1.0, k_delta, m_e },
            joint: if free { Joint::FreeHub { rotor_inertia: 1e-12 } } else { Joint::Held },
            contact: hertz,
            damping: DampingSpec::NONE,
        };
        let modes = if cl {
            cl_tip_modes(&setup, &GradedMesh::DEFAULT).unwrap()
        } else {
            Chain::cj(&setup).tip_modes(&setup, 0.0).unwrap()
        };
        let options = ModalOptions { tol, window_s: Some(1e6), max_steps: 20_000_000 };
        let t = Instant::now();
        let out = run_on_modes_against(&setup, &modes, &options, scale).unwrap();
        let dt = t.elapsed().as_secs_f64();
        let fine = run_on_modes(&setup, &modes, &ModalOptions { tol: 1e-9, ..options }).unwrap();
        println!(
            "v {v:5} modes {:3} contacts {:4} steps {:8} time {:8.3} ms peak {:.6} err {:.2e} ref-contacts {} ref-steps {}",
            modes.len(), out.contacts.len(), out.work, dt * 1e3, out.overall.peak_force_n,
            out.overall.peak_force_n / fine.overall.peak_force_n - 1.0, fine.contacts.len(), fine.work
        );
    }
}
