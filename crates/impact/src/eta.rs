//! The paper's Fig. 6 at finite-element fidelity (issue 14): for each design case and Hertz
//! exponent, the CJ and CL peaks of the free-mass impact, η_FE = f_max(CL)/f_max(CJ) beside the
//! lumped η(2/3) of Eq. 15, and the **effective γ**: the γ for which the lumped model (Eq. 5,
//! m_eff = m_e + γ m_r/3, two free masses with the series compliance between them) reproduces
//! the FE CL peak, found by bisection on the exact energy solution (the lumped peak grows
//! monotonically with m_eff). Where no γ ∈ (0, 1] fits, [`EffectiveGamma`] says on which side.
//!
//! With a damped contact law ([`EtaSettings::damping`]) the lumped peaks have no closed form;
//! they come from the same lumped model run through the exact modal integrator
//! ([`chain::paper_lumped`]: a free mass behind the series spring), which reproduces the closed
//! form for the elastic law (a test).

use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_lumped::fig6::{Fig6Case, Fig6Design};
use flexrig_lumped::peak_exact;
use rayon::prelude::*;
use serde::Serialize;

use crate::cl_modal::{run_on_modes, run_on_modes_traced, run_placed};
use crate::graded::{GradedMesh, cl_tip_modes};
use crate::horizon::{WindowReport, run_window};
use crate::modal_run::{Head, ModalOptions, run_modes};
use crate::setup::{ClSolver, FreeMassImpact, ImpactOutcome, Joint, LinkParams};
use crate::severity::{ContactTrace, PairSeverity};
use crate::{ImpactError, chain, cj, cl};

/// How the CL link is solved.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "method")]
pub enum ClMethod {
    /// The FE link's modes on a mesh graded towards the tip, integrated exactly between
    /// force samples ([`crate::modal_run`]): the fast path.
    Modal {
        /// The mesh and the modes kept.
        mesh: GradedMesh,
        /// Tolerance of the force hold.
        tol: f64,
    },
    /// The FE link on a uniform mesh by generalized-α ([`crate::cl`]): the reference.
    Alpha(ClSolver),
}

impl ClMethod {
    /// The modal path with the default mesh at tol 1e-6.
    pub const DEFAULT: ClMethod = ClMethod::Modal {
        mesh: GradedMesh::DEFAULT,
        tol: 1e-6,
    };

    /// The tolerance of the modal runs beside the CL (the CJ and reduced models through the modal
    /// integrator): the modal method's, 1e-6 with the alpha method.
    pub fn modal_tol(&self) -> f64 {
        match self {
            ClMethod::Modal { tol, .. } => *tol,
            ClMethod::Alpha(_) => 1e-6,
        }
    }

    /// Checks the method's parameters.
    pub fn validate(&self) -> Result<(), ImpactError> {
        match self {
            ClMethod::Modal { mesh, tol } => {
                mesh.validate()?;
                ModalOptions {
                    tol: *tol,
                    ..ModalOptions::DEFAULT
                }
                .validate()
            }
            ClMethod::Alpha(solver) => solver.validate(),
        }
    }
}

/// How the FE study is run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EtaSettings {
    /// Link length L \[m\] (free: for an Euler–Bernoulli beam the transverse impact depends on
    /// m_r and k_δ only).
    pub length: f64,
    /// The joint during the impact.
    pub joint: Joint,
    /// How the CL is solved.
    pub method: ClMethod,
    /// Relative tolerance of the CJ integration.
    pub cj_rtol: f64,
    /// `Some(p)`: also follow every contact for p first-mode periods of the CJ link,
    /// 2π √((m_e + m_r/3)/k_δ) (modal method only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window_periods: Option<f64>,
    /// Damping added to the Hertz contact (the paper: none).
    pub damping: DampingSpec,
    /// The design held fixed across the cases: link mass m_r, contact stiffness k_c, approach
    /// speed v0 (the paper's §V by default).
    pub design: Fig6Design,
    /// `Some(R)`: every row also carries the severity of its CJ and CL impacts
    /// ([`crate::severity`]), pressure under the contact-area models of a dome of radius R \[m\];
    /// `None`: peaks only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub severity_dome_radius_m: Option<f64>,
}

impl EtaSettings {
    /// L = 1 m, held joint, the modal CL on the default graded mesh, CJ to 1e-10, first contact.
    pub const DEFAULT: EtaSettings = EtaSettings {
        length: 1.0,
        joint: Joint::Held,
        method: ClMethod::DEFAULT,
        cj_rtol: 1e-10,
        window_periods: None,
        damping: DampingSpec::NONE,
        design: Fig6Design::PAPER,
        severity_dome_radius_m: None,
    };
}

impl EtaSettings {
    /// Checks the method and the window; the error names the field.
    pub fn validate(&self) -> Result<(), ImpactError> {
        self.method.validate()?;
        // a bad joint would fail every case of a table or a map: refused before any runs
        self.joint.validate()?;
        if let Some(r) = self.severity_dome_radius_m
            && !(r.is_finite() && r > 0.0 && r <= 1e3)
        {
            return Err(ImpactError::invalid(
                "dome_radius",
                r,
                "must lie in (0, 1e3] m",
            ));
        }
        if let Some(periods) = self.window_periods {
            if !matches!(self.method, ClMethod::Modal { .. }) {
                return Err(ImpactError::invalid(
                    "window_periods",
                    periods,
                    "only with the modal method",
                ));
            }
            if !(periods.is_finite() && (0.01..=1000.0).contains(&periods)) {
                return Err(ImpactError::invalid(
                    "window_periods",
                    periods,
                    "must lie in [0.01, 1000]",
                ));
            }
        }
        Ok(())
    }
}

/// The γ of the lumped model that reproduces a peak.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "kind", content = "gamma")]
pub enum EffectiveGamma {
    /// γ ∈ (0, 1].
    Fits(f64),
    /// The peak is above the lumped model's at γ = 1 (the CJ): no γ ≤ 1 reaches it.
    AboveGammaOne,
    /// The peak is below the lumped model's with the payload alone (γ → 0).
    BelowPayloadOnly,
}

/// One row of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EtaRow {
    /// The design case.
    pub case: Fig6Case,
    /// Hertz exponent n.
    pub n: f64,
    /// FE (rigid-link) CJ peak \[N\].
    pub f_cj_n: f64,
    /// FE CL peak \[N\].
    pub f_cl_n: f64,
    /// η_FE = f_CL/f_CJ.
    pub eta_fe: f64,
    /// The lumped model's η(2/3) (Eq. 15).
    pub eta_lumped_2_3: f64,
    /// The lumped model's CJ peak (γ = 1) \[N\], beside the FE CJ peak.
    pub f_cj_lumped_n: f64,
    /// The γ for which the lumped peak equals the FE CL peak.
    pub gamma_eff: EffectiveGamma,
    /// The placed reduced model's CL peak \[N\] ([`chain::Chain::placed`]).
    pub f_placed_n: f64,
    /// Every contact in the window (with `window_periods`): CJ and CL; absent from JSON
    /// without a window.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub window: Option<EtaWindow>,
    /// The severity of the CJ and CL first contacts (with
    /// [`EtaSettings::severity_dome_radius_m`]); absent from JSON without it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub severity: Option<PairSeverity>,
}

/// The window of a row: every contact, the horizon to which they are converged, the overall
/// peaks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EtaWindow {
    /// The window \[s\].
    pub window_s: f64,
    /// The CJ's contacts.
    pub cj: WindowReport,
    /// The CL's contacts.
    pub cl: WindowReport,
}

/// The free-mass set-up of a Fig. 6 case in the design of `settings` (the paper's: m_r = 10 kg,
/// k_c = 1e8, v0 = 2 m/s).
pub fn case_setup(
    case: &Fig6Case,
    n: f64,
    settings: &EtaSettings,
) -> Result<FreeMassImpact, ImpactError> {
    Ok(FreeMassImpact {
        m_h: case.m_h,
        v0: settings.design.v0,
        link: LinkParams {
            m_r: settings.design.m_r,
            length: settings.length,
            k_delta: case.k_delta,
            m_e: case.m_e,
        },
        joint: settings.joint,
        contact: Hertz::new(settings.design.k_c, n)?,
        damping: settings.damping,
    })
}

/// The FE CL's first-contact peak \[N\] of `setup` by the method of `settings`.
pub fn cl_first_peak(setup: &FreeMassImpact, settings: &EtaSettings) -> Result<f64, ImpactError> {
    cl_first_peak_until(setup, settings, &AtomicBool::new(false))
}

/// [`cl_first_peak`], stopping with [`ImpactError::Interrupted`] once `stop` is set (the
/// generalized-α run looks at it every few steps).
pub fn cl_first_peak_until(
    setup: &FreeMassImpact,
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<f64, ImpactError> {
    Ok(match settings.method {
        ClMethod::Alpha(solver) => cl::run_cl_until(setup, &solver, stop)?.first.peak_force_n,
        ClMethod::Modal { mesh, tol } => {
            let options = ModalOptions {
                tol,
                ..ModalOptions::DEFAULT
            };
            run_on_modes(setup, &cl_tip_modes(setup, &mesh)?, &options)?
                .first
                .peak_force_n
        }
    })
}

/// The FE CL's first contact of `setup` by the method of `settings`, with its traces.
pub fn cl_first_traced_until(
    setup: &FreeMassImpact,
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<(ImpactOutcome, ContactTrace), ImpactError> {
    match settings.method {
        ClMethod::Alpha(solver) => cl::run_cl_traced_until(setup, &solver, stop),
        ClMethod::Modal { mesh, tol } => {
            let options = ModalOptions {
                tol,
                ..ModalOptions::DEFAULT
            };
            run_on_modes_traced(setup, &cl_tip_modes(setup, &mesh)?, &options)
        }
    }
}

/// The CJ (DOP853 at `settings.cj_rtol`) and CL (the settings' method) first-contact peaks
/// \[N\] of `setup`, and their severity when `settings` asks for it.
pub fn peaks_and_severity(
    setup: &FreeMassImpact,
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<(f64, f64, Option<PairSeverity>), ImpactError> {
    match settings.severity_dome_radius_m {
        None => Ok((
            cj::run_cj(setup, settings.cj_rtol)?.first.peak_force_n,
            cl_first_peak_until(setup, settings, stop)?,
            None,
        )),
        Some(radius) => {
            let (cj, cj_trace) = cj::run_cj_traced(setup, settings.cj_rtol)?;
            let (cl, cl_trace) = cl_first_traced_until(setup, settings, stop)?;
            Ok((
                cj.first.peak_force_n,
                cl.first.peak_force_n,
                Some(PairSeverity {
                    cj: cj_trace.severity(setup.m_h, radius, setup.contact.n())?,
                    cl: cl_trace.severity(setup.m_h, radius, setup.contact.n())?,
                }),
            ))
        }
    }
}

/// One case and exponent.
pub fn eta_case(case: &Fig6Case, n: f64, settings: &EtaSettings) -> Result<EtaRow, ImpactError> {
    eta_case_until(case, n, settings, &AtomicBool::new(false))
}

/// [`eta_case`], stopping with [`ImpactError::Interrupted`] once `stop` is set (checked inside
/// the long generalized-α run of the CL, see [`cl::run_cl_until`]).
pub fn eta_case_until(
    case: &Fig6Case,
    n: f64,
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<EtaRow, ImpactError> {
    settings.validate()?;
    let setup = case_setup(case, n, settings)?;
    let (f_cj, f_cl, severity) = peaks_and_severity(&setup, settings, stop)?;
    let mut window = None;
    if let (ClMethod::Modal { mesh, tol }, Some(periods)) =
        (settings.method, settings.window_periods)
    {
        let link = setup.link;
        let window_s =
            periods * 2.0 * std::f64::consts::PI * (link.cj_tip_mass() / link.k_delta).sqrt();
        let options = ModalOptions {
            tol,
            window_s: Some(window_s),
            max_steps: 2_000_000,
        };
        let cj_modes = chain::Chain::cj(&setup).tip_modes(&setup, 0.0)?;
        window = Some(EtaWindow {
            window_s,
            cj: run_window(&setup, &cj_modes, &options)?,
            cl: run_window(&setup, &cl_tip_modes(&setup, &mesh)?, &options)?,
        });
    }
    let f_cj_lumped = lumped_peak(case, n, 1.0, settings)?;
    let f_placed = run_placed(
        &setup,
        &ModalOptions {
            tol: settings.method.modal_tol(),
            ..ModalOptions::DEFAULT
        },
    )?
    .first
    .peak_force_n;
    Ok(EtaRow {
        case: *case,
        n,
        f_cj_n: f_cj,
        f_cl_n: f_cl,
        eta_fe: f_cl / f_cj,
        eta_lumped_2_3: lumped_peak(case, n, 2.0 / 3.0, settings)? / f_cj_lumped,
        f_cj_lumped_n: f_cj_lumped,
        gamma_eff: effective_gamma(case, n, f_cl, settings)?,
        f_placed_n: f_placed,
        window,
        severity,
    })
}

/// Validates every set-up before any runs, the one with the lowest critical contact damping
/// first, so that a refused damping names the bound every case can take.
pub(crate) fn validate_most_restrictive_first(
    setups: impl Iterator<Item = Result<FreeMassImpact, ImpactError>>,
) -> Result<(), ImpactError> {
    let mut setups = setups.collect::<Result<Vec<_>, _>>()?;
    let critical = |s: &FreeMassImpact| {
        flexrig_contact::critical_damping(s.contact, s.payload_reduced_mass(), s.v0)
    };
    setups.sort_by(|a, b| critical(a).total_cmp(&critical(b)));
    setups.iter().try_for_each(FreeMassImpact::validate)
}

/// The paper's eight cases × n ∈ {1, 2}, in parallel (case-major, as `flexrig fig6`).
pub fn eta_table(settings: &EtaSettings) -> Result<Vec<EtaRow>, ImpactError> {
    eta_table_until(settings, &AtomicBool::new(false))
}

/// [`eta_table`], stopping with [`ImpactError::Interrupted`] once `stop` is set (checked
/// before each case).
pub fn eta_table_until(
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<Vec<EtaRow>, ImpactError> {
    eta_cases_until(&flexrig_lumped::fig6::cases(), settings, stop)
}

/// [`eta_table_until`] of any `cases` × n ∈ {1, 2} (case-major).
pub fn eta_cases_until(
    cases: &[Fig6Case],
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<Vec<EtaRow>, ImpactError> {
    let jobs: Vec<(Fig6Case, f64)> = cases
        .iter()
        .flat_map(|c| {
            flexrig_lumped::fig6::EXPONENTS
                .iter()
                .map(move |&n| (*c, n))
        })
        .collect();
    // a set-up every case would refuse (e.g. a contact damped far past critical) is refused
    // before any case runs
    settings.validate()?;
    validate_most_restrictive_first(jobs.iter().map(|(case, n)| case_setup(case, *n, settings)))?;
    jobs.par_iter()
        .map(|(case, n)| {
            if stop.load(Ordering::Relaxed) {
                return Err(ImpactError::Interrupted);
            }
            eta_case_until(case, *n, settings, stop)
        })
        .collect()
}

/// Tolerance of the lumped model's modal runs with a damped law.
const LUMPED_TOL: f64 = 1e-8;

/// The lumped model's peak \[N\] at γ (m_eff = m_e + γ m_r/3, Eq. 5) with the contact of
/// `settings`: the exact energy solution for the elastic law, the modal integrator for a damped
/// one.
pub fn lumped_peak(
    case: &Fig6Case,
    n: f64,
    gamma: f64,
    settings: &EtaSettings,
) -> Result<f64, ImpactError> {
    let model = case.model_in(&settings.design, n, gamma)?;
    if settings.damping.is_none() {
        return Ok(peak_exact(&model).f_max);
    }
    let setup = case_setup(case, n, settings)?;
    let head = Head {
        mass: model.m_h(),
        x: 0.0,
        v: model.v0(),
    };
    let options = ModalOptions {
        tol: LUMPED_TOL,
        ..ModalOptions::DEFAULT
    };
    let modes = chain::paper_lumped(model.m_eff(), model.spring().k_delta());
    Ok(run_modes(
        &modes,
        head,
        &*setup.law()?,
        setup.payload_contact_time(),
        &options,
    )?
    .first
    .peak_force_n)
}

/// The γ ∈ (0, 1] with f_lumped(γ) = `peak` \[N\] under the contact of `settings` (bisection,
/// to 1e-12 in γ for the elastic law, 1e-9 for a damped one: its lumped peaks carry the modal
/// integrator's error, ≈ [`LUMPED_TOL`]).
pub fn effective_gamma(
    case: &Fig6Case,
    n: f64,
    peak: f64,
    settings: &EtaSettings,
) -> Result<EffectiveGamma, ImpactError> {
    let f = |gamma: f64| lumped_peak(case, n, gamma, settings);
    let resolution = if settings.damping.is_none() {
        1e-12
    } else {
        1e-9
    };
    const GAMMA_MIN: f64 = 1e-9;
    if peak > f(1.0)? {
        return Ok(EffectiveGamma::AboveGammaOne);
    }
    if peak < f(GAMMA_MIN)? {
        return Ok(EffectiveGamma::BelowPayloadOnly);
    }
    let (mut lo, mut hi) = (GAMMA_MIN, 1.0);
    while hi - lo > resolution {
        let mid = 0.5 * (lo + hi);
        if f(mid)? < peak {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(EffectiveGamma::Fits(0.5 * (lo + hi)))
}

/// The γ ∈ [`GAMMA_RANGE`](flexrig_lumped::fig6::GAMMA_RANGE) at which the lumped curve η(γ) of
/// Fig. 6 takes the value `eta` (bisection to 1e-10; η(γ) rises with γ), or `None` when `eta`
/// lies outside the curve's range: where an FE result sits on the figure of `design`.
pub fn gamma_on_curve(
    design: &Fig6Design,
    case: &Fig6Case,
    n: f64,
    eta: f64,
) -> Result<Option<f64>, ImpactError> {
    let (lo, hi) = flexrig_lumped::fig6::GAMMA_RANGE;
    let (e_lo, e_hi) = (case.eta_in(design, n, lo)?, case.eta_in(design, n, hi)?);
    if !(eta >= e_lo.min(e_hi) && eta <= e_lo.max(e_hi)) {
        return Ok(None);
    }
    let rising = e_hi >= e_lo;
    let (mut a, mut b) = (lo, hi);
    while b - a > 1e-10 {
        let mid = 0.5 * (a + b);
        if (case.eta_in(design, n, mid)? < eta) == rising {
            a = mid;
        } else {
            b = mid;
        }
    }
    Ok(Some(0.5 * (a + b)))
}
