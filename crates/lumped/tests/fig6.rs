//! The paper's Fig. 6 (§V): η(2/3) values and the qualitative conclusions.

use flexrig_contact::tolerance::assert_abs;
use flexrig_lumped::fig6;
use flexrig_lumped::samples;

#[test]
fn eta_at_two_thirds_reproduces_the_paper() {
    for r in samples::eta_references() {
        let eta = r.case.eta(r.n, 2.0 / 3.0).unwrap();
        assert_abs(r.source, eta, r.eta, r.reference_accuracy);
    }
}

#[test]
fn curves_have_the_papers_shape() {
    let curves = fig6::fig6(101).unwrap();
    assert_eq!(curves.len(), 16);
    for c in &curves {
        let label = format!("{} n = {}", c.case.label(), c.n);
        assert_eq!(c.gamma.len(), 101);
        assert_eq!((c.gamma[0], c.gamma[100]), (0.5, 1.0));
        // η(1) = 1 by definition; η grows with γ (a lighter effective mass hits softer).
        assert_abs(&label, *c.eta.last().unwrap(), 1.0, 1e-15);
        assert!(
            c.eta.windows(2).all(|w| w[1] > w[0]),
            "{label}: not increasing"
        );
        // A heavy payload (m_e = m_r) leaves little for γ to change (conclusion 1 of §V). Bound:
        // f_max ∝ μ^p with p ∈ [1/2, n/(n+1)] ⊂ (0, 1], and μ(2/3)/μ(1) ≥ r = m_eff(2/3)/m_eff(1),
        // so η(2/3) ≥ r (0.917 for m_e = 10 kg, 0.676 for 0.1 kg).
        let m_eff = |g: f64| c.case.m_e + g * fig6::M_R / 3.0;
        let r = m_eff(2.0 / 3.0) / m_eff(1.0);
        assert!(
            c.eta_at_2_3 >= r && c.eta_at_2_3 < 1.0,
            "{label}: {}",
            c.eta_at_2_3
        );
        if c.case.m_e == 0.1 {
            // A light payload: the compliant link lowers the peak by more than 8 %.
            assert!(c.eta_at_2_3 < 0.92, "{label}: {}", c.eta_at_2_3);
        }
    }
    // For n = 1, η depends on the masses only (k_o cancels): rigid and compliant links agree.
    let n1: Vec<_> = curves.iter().filter(|c| c.n == 1.0).collect();
    for a in &n1 {
        for b in &n1 {
            if a.case.m_h == b.case.m_h && a.case.m_e == b.case.m_e {
                assert_abs(
                    "η independent of k_δ for n = 1",
                    a.eta_at_2_3,
                    b.eta_at_2_3,
                    1e-14,
                );
            }
        }
    }
}

#[test]
fn too_few_points_is_an_error() {
    let case = fig6::cases()[0];
    let e = fig6::eta_curve(&case, 2.0, 1).unwrap_err().to_string();
    assert!(e.contains("points"), "{e}");
}
