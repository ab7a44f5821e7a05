//! Contact-area models, peak pressure, transferred energy and peak force over sampled traces,
//! against closed forms.

use flexrig_contact::tolerance::assert_close;
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::{ImpactModel, peak_exact};
use flexrig_safety::{
    ContactAreaModel, loading_work, peak_force, peak_pressure, relative_kinetic_energy,
    spring_energy_at_force,
};
use std::f64::consts::PI;

#[test]
fn area_models_follow_their_geometry() {
    let r = 0.0715;
    let hertz = ContactAreaModel::HertzSphere { radius_m: r };
    let thin = ContactAreaModel::ThinLayer { radius_m: r };
    for d in [1e-5, 1e-3, 5e-3] {
        // Hertz: a² = R δ.
        assert_close("Hertz area", hertz.area(d), PI * (r * d), 1e-15);
        // Thin layer: the circle where the sphere crosses the undeformed surface, a² = 2Rδ − δ².
        let a2 = r * r - (r - d) * (r - d);
        assert_close("thin-layer area", thin.area(d), PI * a2, 1e-12);
    }
    assert_close("saturated cap", thin.area(2.0 * r), PI * r * r, 1e-15);
    assert_eq!(hertz.area(-1e-3), 0.0);
    assert_eq!((hertz.peak_factor(), thin.peak_factor()), (1.5, 2.0));
    let fixed = ContactAreaModel::Fixed { area_m2: 1e-4 };
    assert_eq!(fixed.mean_pressure(140.0, 0.0), 1.4e6);
    // The serialised form is a tagged enum.
    let parsed: ContactAreaModel =
        toml::from_str("model = \"thin_layer\"\nradius_m = 0.0715").unwrap();
    assert_eq!(parsed, thin);
}

#[test]
fn peak_pressure_over_a_hertz_loading_trace() {
    // f = k δ^n with the paper's skinned aluminium; Hertz area: p = k δ^{n−1}/(π R) grows with δ,
    // so the peak is at the largest indentation.
    let (k, n, r) = (7.359e7, 1.961, 0.0715);
    let d: Vec<f64> = (0..=100).map(|i| 4e-3 * i as f64 / 100.0).collect();
    let f: Vec<f64> = d.iter().map(|x| k * x.powf(n)).collect();
    let (p, i) = peak_pressure(&f, &d, &ContactAreaModel::HertzSphere { radius_m: r }).unwrap();
    assert_eq!(i, 100);
    assert_close(
        "peak pressure",
        p,
        k * 4e-3_f64.powf(n - 1.0) / (PI * r),
        1e-13,
    );
    assert!(peak_pressure(&f, &d[..50], &ContactAreaModel::HertzSphere { radius_m: r }).is_err());
}

#[test]
fn loading_work_equals_the_impact_energy() {
    // An undamped Hertz impact stores ½ μ v² at the peak: ∫₀^{δ_max} k δ^n dδ = k δ_max^{n+1}/(n+1).
    let (k, n) = (7.359e7, 1.961);
    let (m_h, m_eff, v) = (4.0, 0.5, 1.2);
    let mu = m_h * m_eff / (m_h + m_eff);
    let spring = SeriesCompliance::new(1e16, Hertz::new(k, n).unwrap()).unwrap();
    let peak = peak_exact(&ImpactModel::new(m_h, m_eff, spring, v).unwrap());
    let n_pts = 20001;
    let d: Vec<f64> = (0..n_pts)
        .map(|i| peak.indentation_max * i as f64 / (n_pts - 1) as f64)
        .collect();
    let mut f: Vec<f64> = d.iter().map(|x| k * x.powf(n)).collect();
    // Unloading samples after the peak are ignored.
    let mut d_all = d.clone();
    d_all.extend(d.iter().rev().skip(1).take(100));
    f.extend(f.clone().iter().rev().skip(1).take(100));
    let work = loading_work(&f, &d_all).unwrap();
    let kinetic = relative_kinetic_energy(mu, v).unwrap();
    assert_close("∫ f dδ vs ½ μ v²", work, kinetic, 1e-6);
    let (fmax, _) = peak_force(&f).unwrap();
    assert_close("peak force", fmax, peak.f_max, 1e-9);
    // The standard's energy limit E = F²/(2k) (Eq. A.1).
    assert_eq!(
        spring_energy_at_force(140.0, 75e3).unwrap(),
        140.0 * 140.0 / 150e3
    );
    assert!(relative_kinetic_energy(-1.0, 1.0).is_err());
    assert!(peak_force(&[]).is_err());
}

#[test]
fn severity_of_the_linear_impact_collects_every_measure() {
    // n = 1, rigid-ish link: force F sin(πt/T), indentation (F/k) sin(πt/T), head a = f/m_h.
    use flexrig_safety::{ContactTraces, HicWindow, hic_half_sine, severity};
    let (k, m_h, m_eff, v): (f64, f64, f64, f64) = (150e3, 4.4, 2.0, 1.0);
    let mu = m_h * m_eff / (m_h + m_eff);
    let (f_max, t_c) = (v * (mu * k).sqrt(), PI * (mu / k).sqrt());
    let n = 4001;
    let t: Vec<f64> = (0..n).map(|i| t_c * i as f64 / (n - 1) as f64).collect();
    let f: Vec<f64> = t.iter().map(|x| f_max * (PI * x / t_c).sin()).collect();
    let d: Vec<f64> = f.iter().map(|x| x / k).collect();
    let a: Vec<f64> = f.iter().map(|x| x / m_h).collect();
    let traces = ContactTraces {
        times: &t,
        force: &f,
        indentation: &d,
        head_acceleration: Some(&a),
    };
    let area = ContactAreaModel::Fixed { area_m2: 1e-4 };
    let s = severity(&traces, &[area]).unwrap();
    assert_close("peak force", s.peak_force_n, f_max, 1e-12);
    assert_close("t at peak", s.time_of_peak_force_s, 0.5 * t_c, 1e-12);
    assert_close("peak pressure", s.pressure[0].mean_pa, f_max / 1e-4, 1e-12);
    assert_eq!(s.pressure_of(&area).unwrap().peak_pa, s.pressure[0].mean_pa);
    assert_close(
        "loading work = ½ μ v²",
        s.energy_transferred_j,
        0.5 * mu * v * v,
        1e-6,
    );
    // elastic: the net work over the closed force–indentation loop is 0 up to rounding
    assert!(s.contact_work_j.abs() < 1e-12 * s.energy_transferred_j);
    assert_close(
        "peak acceleration",
        s.peak_acceleration_mps2.unwrap(),
        f_max / m_h,
        1e-12,
    );
    let h15 = hic_half_sine(f_max / m_h, t_c, HicWindow::Hic15).unwrap();
    assert_close("HIC15", s.hic15.unwrap().hic, h15, 1e-6);
    let short = ContactTraces {
        indentation: &d[..10],
        ..traces
    };
    assert!(
        severity(&short, &[])
            .unwrap_err()
            .to_string()
            .contains("indentation")
    );
}
