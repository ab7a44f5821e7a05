//! The rotor-inertia sweep (issue 14, deliverable 1): the free hub's rotor inertia J_R from
//! nearly nothing to nearly infinite, joining a robot whose link pivots freely during the impact
//! to the held joint (an infinite rotor). For each Fig. 6 case and exponent the CJ and CL peaks
//! and η_FE along J_R, with the held joint's values as the limit.
//!
//! J_R is given as the ratio ρ = J_R/(m_r L²/3) to the link's own inertia about the joint, so a
//! curve does not depend on the (free) length. At ρ → 0 the CJ link pivots freely behind its
//! spring, so the head meets the free tip mass M = m_e + m_r/3 alone; the CL beam is pinned at
//! the hub; at ρ → ∞ both are held.

use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_lumped::fig6::Fig6Case;
use rayon::prelude::*;
use serde::Serialize;

use crate::ImpactError;
use crate::chain::Chain;
use crate::cl_modal::{run_cj_modal, run_on_modes_traced};
use crate::eta::{
    EtaSettings, case_setup, cl_first_peak_until, cl_first_traced_until,
    validate_most_restrictive_first,
};
use crate::map::LogRange;
use crate::modal_run::ModalOptions;
use crate::setup::Joint;
use crate::severity::PairSeverity;

/// One point of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RotorPoint {
    /// The design case.
    pub case: Fig6Case,
    /// Hertz exponent n.
    pub n: f64,
    /// ρ = J_R/(m_r L²/3); `None` for the held joint (ρ = ∞).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub inertia_ratio: Option<f64>,
    /// CJ peak \[N\] (the rigid link through the modal integrator).
    pub f_cj_n: f64,
    /// CL peak \[N\] (the FE link by the settings' method).
    pub f_cl_n: f64,
    /// η_FE = f_CL/f_CJ.
    pub eta_fe: f64,
    /// The severity of the CJ and CL first contacts (with
    /// [`EtaSettings::severity_dome_radius_m`]); absent from JSON without it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub severity: Option<PairSeverity>,
}

/// The ratios ρ allowed: J_R from 1e-12 to 1e12 kg·m² for m_r = 10 kg, L = 1 m is ρ from 3e-13
/// to 3e11; the sweep keeps within [1e-9, 1e9].
pub const RATIO_LIMITS: (f64, f64) = (1e-9, 1e9);

/// The peaks of `case` with exponent `n` under the joint of `settings` with rotor inertia ratio
/// `ratio` (`None`: held). The CJ runs through the modal integrator at the CL's tolerance (1e-6
/// for the alpha method): an explicit integrator would crawl on the stiff rotor mode of a tiny
/// J_R.
pub fn rotor_point(
    case: &Fig6Case,
    n: f64,
    ratio: Option<f64>,
    settings: &EtaSettings,
) -> Result<RotorPoint, ImpactError> {
    rotor_point_until(case, n, ratio, settings, &AtomicBool::new(false))
}

/// [`rotor_point`], stopping with [`ImpactError::Interrupted`] once `stop` is set (inside the
/// generalized-α CL run).
pub fn rotor_point_until(
    case: &Fig6Case,
    n: f64,
    ratio: Option<f64>,
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<RotorPoint, ImpactError> {
    let joint = match ratio {
        None => Joint::Held,
        Some(rho) => Joint::FreeHub {
            rotor_inertia: rho * settings.design.m_r * settings.length * settings.length / 3.0,
        },
    };
    let settings = EtaSettings { joint, ..*settings };
    let setup = case_setup(case, n, &settings)?;
    let options = ModalOptions {
        tol: settings.method.modal_tol(),
        ..ModalOptions::DEFAULT
    };
    let (f_cj, f_cl, severity) = match settings.severity_dome_radius_m {
        None => (
            run_cj_modal(&setup, &options)?.first.peak_force_n,
            cl_first_peak_until(&setup, &settings, stop)?,
            None,
        ),
        Some(radius) => {
            let cj_modes = Chain::cj(&setup).tip_modes(&setup, 0.0)?;
            let (cj, cj_trace) = run_on_modes_traced(&setup, &cj_modes, &options)?;
            let (cl, cl_trace) = cl_first_traced_until(&setup, &settings, stop)?;
            (
                cj.first.peak_force_n,
                cl.first.peak_force_n,
                Some(PairSeverity {
                    cj: cj_trace.severity(setup.m_h, radius, setup.contact.n())?,
                    cl: cl_trace.severity(setup.m_h, radius, setup.contact.n())?,
                }),
            )
        }
    };
    Ok(RotorPoint {
        case: *case,
        n,
        inertia_ratio: ratio,
        f_cj_n: f_cj,
        f_cl_n: f_cl,
        eta_fe: f_cl / f_cj,
        severity,
    })
}

/// Every case × exponent of `exponents` along `ratios`, then held (the last point of each
/// curve, `inertia_ratio` None), in parallel; case-major, then exponent, then ρ.
pub fn rotor_sweep(
    ratios: &LogRange,
    exponents: &[f64],
    settings: &EtaSettings,
) -> Result<Vec<RotorPoint>, ImpactError> {
    rotor_sweep_until(ratios, exponents, settings, &AtomicBool::new(false))
}

/// [`rotor_sweep`], stopping with [`ImpactError::Interrupted`] once `stop` is set (checked
/// before each point).
pub fn rotor_sweep_until(
    ratios: &LogRange,
    exponents: &[f64],
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<Vec<RotorPoint>, ImpactError> {
    rotor_sweep_cases_until(
        &flexrig_lumped::fig6::cases(),
        ratios,
        exponents,
        settings,
        stop,
    )
}

/// [`rotor_sweep_until`] of any `cases` (case-major, then exponent, then ρ).
pub fn rotor_sweep_cases_until(
    cases: &[Fig6Case],
    ratios: &LogRange,
    exponents: &[f64],
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<Vec<RotorPoint>, ImpactError> {
    settings.validate()?;
    ratios.validate("inertia_ratio", RATIO_LIMITS.0, RATIO_LIMITS.1)?;
    let mut stops: Vec<Option<f64>> = ratios.values().into_iter().map(Some).collect();
    stops.push(None);
    let jobs: Vec<(Fig6Case, f64, Option<f64>)> = cases
        .iter()
        .flat_map(|c| {
            let stops = &stops;
            exponents
                .iter()
                .flat_map(move |&n| stops.iter().map(move |&r| (*c, n, r)))
        })
        .collect();
    // a set-up every point of a case would refuse is refused before any point runs
    validate_most_restrictive_first(
        jobs.iter()
            .map(|(case, n, _)| case_setup(case, *n, settings)),
    )?;
    jobs.par_iter()
        .map(|(case, n, ratio)| {
            if stop.load(Ordering::Relaxed) {
                return Err(ImpactError::Interrupted);
            }
            rotor_point_until(case, *n, *ratio, settings, stop)
        })
        .collect()
}
