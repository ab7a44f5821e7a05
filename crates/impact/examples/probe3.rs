use flexrig_impact::graded::cl_matrices;
use flexrig_impact::tip_modes::TipModes;
use flexrig_impact::{FreeMassImpact, Joint, LinkParams};
use flexrig_contact::Hertz;
fn main() {
    let s = FreeMassImpact { m_h: 4.0, v0: 2.0, link: LinkParams { m_r: 10.0, length: 1.0, k_delta: 2e2, m_e: 0.0 }, joint: Joint::Held, contact: Hertz::new(1e8, 1.0).unwrap() };
    let sc = (s.link.ei()/s.link.rho_a()).sqrt();
    let exact = 1.875104068711961f64.powi(2)*sc;
    for n in [8usize, 16, 32, 64, 128] {
        let lengths = vec![1.0 / n as f64; n];
        let (k, m, tip, v0) = cl_matrices(&s, &lengths).unwrap();
        for shift in [0.667, 80.0] {
            let t = TipModes::from_matrices(&k, &m, tip, &v0, f64::INFINITY, shift).unwrap();
            println!("{n} shift {shift} err {:.3e}", t.omegas[0]/exact-1.0);
        }
    }
}
