//! The free-mass set-up shared by the impact tests: m_r = 10 kg, L = 1 m, v0 = 2 m/s, k_c = 1e8.

use flexrig_contact::Hertz;
use flexrig_impact::{FreeMassImpact, Joint, LinkParams};

/// A head of `m_h` kg on a link of stiffness `k_delta` N/m with payload `m_e` kg, Hertz exponent n.
pub fn setup(m_h: f64, k_delta: f64, m_e: f64, n: f64, joint: Joint) -> FreeMassImpact {
    FreeMassImpact {
        m_h,
        v0: 2.0,
        link: LinkParams {
            m_r: 10.0,
            length: 1.0,
            k_delta,
            m_e,
        },
        joint,
        contact: Hertz::new(1e8, n).unwrap(),
        damping: flexrig_contact::DampingSpec::NONE,
    }
}
