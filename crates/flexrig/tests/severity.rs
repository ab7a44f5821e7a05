//! The severity of every run against independent references: the n = 1 lumped impact (a
//! half-sine pulse: HIC in closed form, peak force Eq. 13, stored energy of series springs, no
//! dome pressure without a contact geometry), the test bed's summary against the one function applied to
//! its recorded traces, and the dissipated energy of a damped contact against the run's energy
//! balance.

use flexrig::CancelToken;
use flexrig::lumped::impact::{EffectiveMass, Formulation, ImpactInput};
use flexrig::shared::severity::{ContactAreaModel, of_lumped, of_samples};
use flexrig::testbed::traces::run_traced;
use flexrig_contact::tolerance::assert_close;
use flexrig_safety::{ContactTraces, HicWindow, hic_half_sine, severity};
use std::f64::consts::PI;

const CJ_ALUMINIUM: &str = include_str!("../../../assets/scenes/cj_aluminium.toml");

#[test]
fn lumped_linear_impact_severity_matches_the_closed_forms() {
    // n = 1: series springs k_o = k_δ k_c/(k_δ + k_c); f = F sin(πt/T), F = v0 √(k_o μ) (Eq. 13),
    // T = π √(μ/k_o); the head's acceleration f/m_h is a half-sine of amplitude F/m_h.
    // T ≈ 42.7 ms: the HIC15 window binds (15 ms < 0.670 T), the HIC36 window does not.
    let (m_h, m_eff, k_delta, k_c, v0) = (4.0, 3.4333, 2e4, 2e4, 2.0);
    let input = ImpactInput {
        m_h,
        m_eff: EffectiveMass::Given(m_eff),
        k_delta,
        k_c,
        n: 1.0,
        v0,
    };
    let model = input.model().unwrap();
    let radius = 0.0715;
    let s = of_lumped(&model, 1e-10, Formulation::Indentation, radius).unwrap();
    let mu = m_h * m_eff / (m_h + m_eff);
    let k_o = k_delta * k_c / (k_delta + k_c);
    let (f_max, t_c) = (v0 * (k_o * mu).sqrt(), PI * (mu / k_o).sqrt());
    assert_close("peak force", s.peak_force_n, f_max, 1e-7);
    assert_close(
        "time of the peak force",
        s.time_of_peak_force_s,
        0.5 * t_c,
        1e-3,
    );
    assert_close(
        "peak head acceleration",
        s.peak_acceleration_mps2.unwrap(),
        f_max / m_h,
        1e-7,
    );
    for (window, hic) in [(HicWindow::Hic15, s.hic15), (HicWindow::Hic36, s.hic36)] {
        let reference = hic_half_sine(f_max / m_h, t_c, window).unwrap();
        assert_close("HIC of the half-sine", hic.unwrap().hic, reference, 1e-6);
    }
    let h15 = s.hic15.unwrap();
    assert!((h15.t2_s - h15.t1_s - 0.015).abs() < 1e-9, "{h15:?}");
    // the contact stores its share of ½ μ v0² at the peak: k_δ/(k_δ + k_c) for series springs
    let stored = 0.5 * mu * v0 * v0 * k_delta / (k_delta + k_c);
    assert_close("energy transferred", s.energy_transferred_j, stored, 1e-6);
    // elastic: no net work over the closed loop (the head leaves with the energy it brought)
    assert!(
        s.contact_work_j.abs() < 1e-6 * stored,
        "{}",
        s.contact_work_j
    );
    // n = 1: a spring without a contact geometry; its Hertz-area mean pressure k_c/(πR) would not
    // depend on the force, so no pressure is reported; with n = 2 the dome's two models are
    assert!(s.pressure.is_empty(), "{:?}", s.pressure);
    let dome = ImpactInput {
        n: 2.0,
        k_c: 1e8,
        ..input
    }
    .model()
    .unwrap();
    let s = of_lumped(&dome, 1e-10, Formulation::Indentation, radius).unwrap();
    assert_eq!(
        s.pressure.iter().map(|p| p.area_model).collect::<Vec<_>>(),
        ContactAreaModel::dome_models(radius)
    );
}

#[test]
fn run_summary_severity_is_the_function_applied_to_the_recorded_traces() {
    let (summary, traces) = run_traced(CJ_ALUMINIUM, &[], &CancelToken::new()).unwrap();
    let s = summary.severity.clone().expect("a run has a severity");
    // the same function on the samples the summary carries, and on the in-memory traces
    assert_eq!(of_samples(&summary.samples, 0.0715).unwrap(), s);
    let t = &traces.samples;
    let accel: Vec<f64> = t.operator_accel_mps2.iter().map(|a| a.abs()).collect();
    let again = severity(
        &ContactTraces {
            times: &t.time_s,
            force: &t.force_n,
            indentation: &t.indentation_m,
            head_acceleration: Some(&accel),
        },
        &ContactAreaModel::dome_models(0.0715),
    )
    .unwrap();
    // over every sample: the same peaks, times and energies; HIC (computed over the contact
    // stretch, whose running integral starts at its own first sample) to round-off
    let hic = |x: &flexrig_safety::Severity| [x.hic15.unwrap(), x.hic36.unwrap()];
    for (a, b) in hic(&again).iter().zip(hic(&s)) {
        assert!((a.hic / b.hic - 1.0).abs() <= 1e-12, "{a:?} {b:?}");
        assert!((a.t1_s - b.t1_s).abs() <= 1e-12 && (a.t2_s - b.t2_s).abs() <= 1e-12);
    }
    let without_hic = |x: &flexrig_safety::Severity| {
        let mut x = x.clone();
        (x.hic15, x.hic36) = (None, None);
        x
    };
    assert_eq!(without_hic(&again), without_hic(&s));
    // the sampled peak lies within 1 % below the summary's (parabola through the step values)
    assert!(s.peak_force_n <= summary.peak_force_n * (1.0 + 1e-9));
    assert!(s.peak_force_n > 0.99 * summary.peak_force_n);
    assert!(s.hic15.unwrap().hic > 0.0 && s.hic36.unwrap().hic >= s.hic15.unwrap().hic);
    let w = s.hic15.unwrap();
    assert!(w.t1_s >= summary.onset_time_s - 0.015 && w.t2_s - w.t1_s <= 0.015 + 1e-12);
}

#[test]
fn damped_contact_work_equals_the_energy_the_run_lost_through_the_contact() {
    let text = CJ_ALUMINIUM.replace(
        "damping = { model = \"none\" }",
        "damping = { model = \"hunt_crossley\", restitution = 0.6 }",
    );
    assert_ne!(text, CJ_ALUMINIUM);
    let (summary, _) = run_traced(&text, &[], &CancelToken::new()).unwrap();
    let s = summary.severity.clone().unwrap();
    let (before, after) = summary.energy_through_contact_j.unwrap();
    let lost = before - after;
    assert!(lost > 0.0);
    assert_close(
        "net contact work = energy lost",
        s.contact_work_j,
        lost,
        0.02,
    );
    // and the undamped run loses (almost) nothing through the contact
    let (undamped, _) = run_traced(CJ_ALUMINIUM, &[], &CancelToken::new()).unwrap();
    let u = undamped.severity.unwrap();
    assert!(
        u.contact_work_j.abs() < 0.02 * u.energy_transferred_j,
        "{u:?}"
    );
}
