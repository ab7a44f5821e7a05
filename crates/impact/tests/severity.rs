//! Severity of the FE impacts against closed forms: with a linear contact (n = 1) and a link
//! far stiffer than the contact, the head bounces off a wall of the series stiffness
//! k_s = k_c k_δ/(k_c + k_δ): its force is a half-sine of amplitude v0 √(k_s m_h) and duration
//! π √(m_h/k_s), so the head's HIC has the closed form of `hic_half_sine`.

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::cj::run_cj_traced;
use flexrig_impact::cl_modal::run_on_modes_traced;
use flexrig_impact::graded::{GradedMesh, cl_tip_modes};
use flexrig_impact::modal_run::ModalOptions;
use flexrig_impact::{FreeMassImpact, Joint, LinkParams};
use flexrig_safety::{HicWindow, hic_half_sine};

const M_H: f64 = 4.4;
const V0: f64 = 1.0;
const K_C: f64 = 5e4;
const K_DELTA: f64 = 1e12;
const DOME: f64 = 0.0715;

fn setup() -> FreeMassImpact {
    FreeMassImpact {
        m_h: M_H,
        v0: V0,
        link: LinkParams {
            m_r: 1.0,
            length: 1.0,
            k_delta: K_DELTA,
            m_e: 0.5,
        },
        joint: Joint::Held,
        contact: Hertz::new(K_C, 1.0).unwrap(),
        damping: DampingSpec::NONE,
    }
}

/// (amplitude of the head's acceleration \[m/s²\], pulse duration \[s\], peak force \[N\]).
fn half_sine() -> (f64, f64, f64) {
    let k_s = K_C * K_DELTA / (K_C + K_DELTA);
    let force = V0 * (k_s * M_H).sqrt();
    (
        force / M_H,
        std::f64::consts::PI * (M_H / k_s).sqrt(),
        force,
    )
}

fn rel(a: f64, b: f64) -> f64 {
    (a / b - 1.0).abs()
}

/// The FE CJ's HIC15 (the window binds: 15 ms < 0.670 T, T = 29.5 ms) and HIC36 (it does not)
/// within 1e-6 of the closed form; peak force and head acceleration within 1e-7; the energy the
/// skin stores, ½ m_h v0² k_δ/(k_c + k_δ), within 1e-6. The tip's own vibration perturbs the
/// pulse by O(k_c/k_δ) = 5e-8, the DOP853 run (rtol 1e-12) by less, and the linear interpolant
/// of T/4000 samples by (π/4000)²/12 ≈ 5e-8.
#[test]
fn fe_cj_hic_of_a_linear_contact_on_a_rigid_link_is_the_half_sine_closed_form() {
    let (a, t, f) = half_sine();
    assert!(15e-3 < 0.670 * t && 36e-3 > 0.671 * t);
    let (outcome, trace) = run_cj_traced(&setup(), 1e-12).unwrap();
    let s = trace.severity(M_H, DOME, 1.0).unwrap();
    assert!(
        rel(outcome.first.duration_s, t) < 1e-7,
        "{}",
        outcome.first.duration_s
    );
    assert!(rel(s.peak_force_n, f) < 1e-7, "{} vs {f}", s.peak_force_n);
    assert!(rel(s.peak_acceleration_mps2.unwrap(), a) < 1e-7);
    let h15 = hic_half_sine(a, t, HicWindow::Hic15).unwrap();
    let h36 = hic_half_sine(a, t, HicWindow::Hic36).unwrap();
    let (s15, s36) = (s.hic15.unwrap().hic, s.hic36.unwrap().hic);
    assert!(
        rel(s15, h15) < 1e-6,
        "HIC15 {s15} vs {h15}: {:e}",
        rel(s15, h15)
    );
    assert!(
        rel(s36, h36) < 1e-6,
        "HIC36 {s36} vs {h36}: {:e}",
        rel(s36, h36)
    );
    assert!(rel(s15, s36) > 1e-3, "the window binds for HIC15 only");
    let stored = 0.5 * M_H * V0 * V0 * K_DELTA / (K_C + K_DELTA);
    assert!(rel(s.energy_transferred_j, stored) < 1e-6);
    // n = 1 is a spring without a contact geometry: no dome pressure (its Hertz-sphere mean
    // k_c/(πR) would not depend on the force)
    assert!(s.pressure.is_empty(), "{:?}", s.pressure);
}

/// The modal CL (the FE beam by its modes) on the same stiff link: the trace is the force the
/// scheme holds linear between its steps, so its HIC is the closed form's to the hold's
/// tolerance: within 1e-5 at tol 1e-8.
#[test]
fn modal_cl_hic_of_a_linear_contact_on_a_rigid_link_is_the_half_sine_closed_form() {
    let (a, t, f) = half_sine();
    let setup = setup();
    let options = ModalOptions {
        tol: 1e-8,
        ..ModalOptions::DEFAULT
    };
    let modes = cl_tip_modes(&setup, &GradedMesh::DEFAULT).unwrap();
    let (_, trace) = run_on_modes_traced(&setup, &modes, &options).unwrap();
    let s = trace.severity(M_H, DOME, 1.0).unwrap();
    assert!(rel(s.peak_force_n, f) < 1e-6, "{} vs {f}", s.peak_force_n);
    for window in [HicWindow::Hic15, HicWindow::Hic36] {
        let h = hic_half_sine(a, t, window).unwrap();
        let got = match window {
            HicWindow::Hic15 => s.hic15.unwrap().hic,
            _ => s.hic36.unwrap().hic,
        };
        assert!(
            rel(got, h) < 1e-5,
            "{window:?} {got} vs {h}: {:e}",
            rel(got, h)
        );
    }
}
