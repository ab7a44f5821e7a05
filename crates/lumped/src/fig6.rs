//! The paper's Fig. 6 study: η(γ) = f_max(γ)/f_max(1) (Eq. 15) for eight design cases.
//!
//! Fixed (§V): robot link mass m_r = 10 kg, contact stiffness k_c = 1e8 (N/m^n), approach speed
//! v0 = 2 m/s ([`Fig6Design::PAPER`]; any other design through the `_in` functions). Varied: human mass m_h ∈ {4, 1000} kg (unconstrained / constrained impact), link
//! lateral stiffness k_δ ∈ {1e8, 2e2} N/m (rigid / compliant link), payload m_e ∈ {0.1, 10} kg.
//! The effective mass is m_eff = m_e + γ m_r/3 (Eq. 5); γ = 1 is the compliant joint, γ = 2/3 the
//! uniform compliant link. Peaks come from the exact energy solution ([`crate::peak_exact`]), for
//! n = 1 (dashed in the paper) and n = 2 (solid).

use flexrig_contact::{Hertz, SeriesCompliance};
use serde::Serialize;

use crate::model::ImpactModel;
use crate::prb::PrbLink;
use crate::{LumpedError, peak_exact};

/// Robot link mass of the study, m_r \[kg\].
pub const M_R: f64 = 10.0;
/// Contact stiffness of the study, k_c [N/m^n].
pub const K_C: f64 = 1e8;
/// Approach speed of the study, v0 [m/s].
pub const V0: f64 = 2.0;
/// The two Hertz exponents of the figure.
pub const EXPONENTS: [f64; 2] = [1.0, 2.0];
/// Range of γ plotted.
pub const GAMMA_RANGE: (f64, f64) = (0.5, 1.0);

/// The design held fixed across the cases of Fig. 6: the paper's (§V) is [`Fig6Design::PAPER`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fig6Design {
    /// Robot link mass m_r \[kg\].
    pub m_r: f64,
    /// Contact stiffness k_c [N/m^n].
    pub k_c: f64,
    /// Approach speed v0 [m/s].
    pub v0: f64,
}

impl Fig6Design {
    /// The paper's design (§V): m_r = 10 kg, k_c = 1e8 N/m^n, v0 = 2 m/s.
    pub const PAPER: Fig6Design = Fig6Design {
        m_r: M_R,
        k_c: K_C,
        v0: V0,
    };
}

impl Default for Fig6Design {
    fn default() -> Self {
        Fig6Design::PAPER
    }
}

/// The varied values of a Fig. 6 study; its cases are every combination.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fig6Grid {
    /// Human masses m_h \[kg\] (the paper: 4 and 1000).
    pub m_h: Vec<f64>,
    /// Link lateral stiffnesses k_δ [N/m] (the paper: 1e8 and 2e2).
    pub k_delta: Vec<f64>,
    /// Payloads m_e \[kg\] (the paper: 0.1 and 10).
    pub m_e: Vec<f64>,
}

impl Fig6Grid {
    /// The paper's eight cases.
    pub fn paper() -> Self {
        Fig6Grid {
            m_h: vec![4.0, 1000.0],
            k_delta: vec![1e8, 2e2],
            m_e: vec![0.1, 10.0],
        }
    }

    /// Every combination, ordered by m_h, then k_δ, then m_e (the paper's order for
    /// [`Fig6Grid::paper`]).
    pub fn cases(&self) -> Vec<Fig6Case> {
        let mut out = Vec::new();
        for &m_h in &self.m_h {
            for &k_delta in &self.k_delta {
                for &m_e in &self.m_e {
                    out.push(Fig6Case { m_h, k_delta, m_e });
                }
            }
        }
        out
    }
}

impl Default for Fig6Grid {
    fn default() -> Self {
        Fig6Grid::paper()
    }
}

/// One design case of Fig. 6.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Fig6Case {
    /// Human mass m_h \[kg\].
    pub m_h: f64,
    /// Link lateral stiffness k_δ [N/m].
    pub k_delta: f64,
    /// Payload m_e \[kg\].
    pub m_e: f64,
}

impl Fig6Case {
    /// A short label, e.g. `m_h = 4 kg, k_δ = 1e8 N/m, m_e = 0.1 kg`.
    pub fn label(&self) -> String {
        format!(
            "m_h = {} kg, k_δ = {:e} N/m, m_e = {} kg",
            self.m_h, self.k_delta, self.m_e
        )
    }

    /// The impact of this case in the paper's design with Hertz exponent `n` and
    /// characteristic radius `gamma`.
    pub fn model(&self, n: f64, gamma: f64) -> Result<ImpactModel, LumpedError> {
        self.model_in(&Fig6Design::PAPER, n, gamma)
    }

    /// The impact of this case in `design` (m_eff = m_e + γ m_r/3, Eq. 5).
    pub fn model_in(
        &self,
        design: &Fig6Design,
        n: f64,
        gamma: f64,
    ) -> Result<ImpactModel, LumpedError> {
        let spring = SeriesCompliance::new(self.k_delta, Hertz::new(design.k_c, n)?)?;
        ImpactModel::with_prb_link(
            self.m_h,
            PrbLink::new(gamma, design.m_r, self.m_e)?,
            spring,
            design.v0,
        )
    }

    /// η(γ) = f_max(γ)/f_max(1) (Eq. 15) in the paper's design.
    pub fn eta(&self, n: f64, gamma: f64) -> Result<f64, LumpedError> {
        self.eta_in(&Fig6Design::PAPER, n, gamma)
    }

    /// η(γ) = f_max(γ)/f_max(1) (Eq. 15) in `design`.
    pub fn eta_in(&self, design: &Fig6Design, n: f64, gamma: f64) -> Result<f64, LumpedError> {
        let f = peak_exact(&self.model_in(design, n, gamma)?).f_max;
        let f_cj = peak_exact(&self.model_in(design, n, 1.0)?).f_max;
        Ok(f / f_cj)
    }
}

/// The eight cases, ordered by m_h, then k_δ (rigid first), then m_e.
pub fn cases() -> [Fig6Case; 8] {
    let mut out = [Fig6Case {
        m_h: 0.0,
        k_delta: 0.0,
        m_e: 0.0,
    }; 8];
    let mut i = 0;
    for m_h in [4.0, 1000.0] {
        for k_delta in [1e8, 2e2] {
            for m_e in [0.1, 10.0] {
                out[i] = Fig6Case { m_h, k_delta, m_e };
                i += 1;
            }
        }
    }
    out
}

/// η over γ for one case and exponent.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EtaCurve {
    /// The case.
    pub case: Fig6Case,
    /// Hertz exponent n.
    pub n: f64,
    /// γ samples, evenly spaced over [0.5, 1].
    pub gamma: Vec<f64>,
    /// η(γ).
    pub eta: Vec<f64>,
    /// η(2/3), the uniform compliant link.
    pub eta_at_2_3: f64,
}

/// η(γ) at `points` ≥ 2 values of γ evenly spaced over [0.5, 1], in the paper's design.
pub fn eta_curve(case: &Fig6Case, n: f64, points: usize) -> Result<EtaCurve, LumpedError> {
    eta_curve_in(&Fig6Design::PAPER, case, n, points)
}

/// [`eta_curve`] in `design`.
pub fn eta_curve_in(
    design: &Fig6Design,
    case: &Fig6Case,
    n: f64,
    points: usize,
) -> Result<EtaCurve, LumpedError> {
    if points < 2 {
        return Err(flexrig_contact::ContactError::InvalidParameter {
            field: "points".into(),
            value: points.to_string(),
            allowed: "must be at least 2".into(),
        }
        .into());
    }
    let f_cj = peak_exact(&case.model_in(design, n, 1.0)?).f_max;
    let (lo, hi) = GAMMA_RANGE;
    let gamma: Vec<f64> = (0..points)
        .map(|i| lo + (hi - lo) * i as f64 / (points - 1) as f64)
        .collect();
    let eta = gamma
        .iter()
        .map(|&g| Ok(peak_exact(&case.model_in(design, n, g)?).f_max / f_cj))
        .collect::<Result<Vec<f64>, LumpedError>>()?;
    Ok(EtaCurve {
        case: *case,
        n,
        gamma,
        eta,
        eta_at_2_3: peak_exact(&case.model_in(design, n, 2.0 / 3.0)?).f_max / f_cj,
    })
}

/// All sixteen curves of Fig. 6 (eight cases × n ∈ {1, 2}), case-major.
pub fn fig6(points: usize) -> Result<Vec<EtaCurve>, LumpedError> {
    fig6_in(&Fig6Design::PAPER, &cases(), points)
}

/// The curves of `cases` × n ∈ {1, 2} in `design`, case-major.
pub fn fig6_in(
    design: &Fig6Design,
    cases: &[Fig6Case],
    points: usize,
) -> Result<Vec<EtaCurve>, LumpedError> {
    cases
        .iter()
        .flat_map(|case| {
            EXPONENTS
                .iter()
                .map(move |&n| eta_curve_in(design, case, n, points))
        })
        .collect()
}
