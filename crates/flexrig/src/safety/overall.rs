//! The overall verdict of a safety question: the most restrictive of the methods run, named, and
//! the warnings of a method whose answer rests on something the design violates.
//!
//! A safety engineer signs one answer, not three. The permissible speed flexrig reports is the
//! **smallest** v_max of the methods run (speeds within round-off, [`TIE_RTOL`], tie, and the
//! more complete model governs: the simulation, then the energy method, then the standard's
//! formula), and a speed is judged FAIL when **any**
//! method fails it. The answer says which method governs and by how much the others differ, so
//! that a disagreement between methods is visible rather than averaged away.
//!
//! The methods run by default ([`default_methods`]) are all three whenever the design is known
//! (a scene, or the link's masses with its kind), so that the default answer is the most
//! restrictive flexrig can give; without a link (only m_eff or the standard's M and m_L) the
//! simulation has nothing to simulate and the default is the standard's formula and the energy
//! method.

use flexrig_contact::validate::display;
use serde::Serialize;

use crate::safety::question::{
    ContactLaw, MethodResult, RobotEffectiveMass, SafetyInput, SafetyMethod, Speed,
};
use crate::safety::simulation::{GAMMA_CJ, GAMMA_CL};
use flexrig_safety::GoverningLimit;

/// The overall answer: the governing method and the verdict at the judged speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OverallVerdict {
    /// The method with the smallest permissible speed (it governs).
    pub method: SafetyMethod,
    /// Its permissible speed, the overall one [m/s].
    pub v_max_mps: Speed,
    /// The limit that sets it (force or pressure).
    pub governing: GoverningLimit,
    /// The judged speed [m/s] (absent without `--speed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub speed_mps: Option<f64>,
    /// At the requested speed: pass only when every method passes (absent without a speed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pass: Option<bool>,
    /// The methods that fail the requested speed (empty without a speed or when all pass).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub failed_by: Vec<SafetyMethod>,
    /// Why this method governs, in words: its speed against the others'.
    pub reason: String,
}

/// The methods a question is answered by when none is asked for: the standard's formula and the
/// energy method always, and the simulation whenever the design is known — a scene, or the link's
/// masses (m_r, m_e) with its kind (`--link`, or γ = 1 for the CJ, 2/3 for the CL).
pub fn default_methods(input: &SafetyInput) -> Vec<SafetyMethod> {
    let link_known = match input.m_eff {
        Some(RobotEffectiveMass::Prb { gamma, .. }) => {
            input.link.is_some() || gamma == GAMMA_CJ || (gamma - GAMMA_CL).abs() < 1e-12
        }
        _ => false,
    };
    let mut methods = vec![SafetyMethod::Standard, SafetyMethod::Energy];
    if input.scene.is_some() || link_known {
        methods.push(SafetyMethod::Simulation);
    }
    methods
}

/// Two permissible speeds closer than this (relative) tie: they differ by round-off only (the
/// standard's formula and the energy method with the body's own spring and a rigid link are the
/// same closed form evaluated in two ways).
pub const TIE_RTOL: f64 = 1e-9;

/// The rank of a method when two permissible speeds tie: the more complete model governs.
fn completeness(m: SafetyMethod) -> u8 {
    match m {
        SafetyMethod::Simulation => 2,
        SafetyMethod::Energy => 1,
        SafetyMethod::Standard => 0,
    }
}

/// A method's name as the verdict speaks it.
pub fn method_name(m: SafetyMethod) -> &'static str {
    match m {
        SafetyMethod::Standard => "the standard's formula",
        SafetyMethod::Energy => "the energy method",
        SafetyMethod::Simulation => "the simulation",
    }
}

/// The overall verdict over `methods` (none: `None`).
pub fn overall(methods: &[MethodResult]) -> Option<OverallVerdict> {
    // the smallest speed; speeds within round-off of it (1e-9 relative) tie, and the more
    // complete model of the tied methods governs
    let lowest = methods
        .iter()
        .map(|m| m.v_max_mps.value())
        .min_by(f64::total_cmp)?;
    let governing = methods
        .iter()
        .filter(|m| {
            let v = m.v_max_mps.value();
            v == lowest || v <= lowest * (1.0 + TIE_RTOL)
        })
        .max_by_key(|m| completeness(m.method))?;
    let speeds = |m: &MethodResult| match m.v_max_mps {
        Speed::Finite(v) => format!("{} m/s", display(v)),
        Speed::Unlimited(_) => "unlimited".into(),
    };
    let others: Vec<String> = methods
        .iter()
        .filter(|m| m.method != governing.method)
        .map(|m| format!("{} {}", method_name(m.method), speeds(m)))
        .collect();
    let reason = if others.is_empty() {
        format!("{} is the only method run", method_name(governing.method))
    } else {
        format!(
            "{} gives the smallest permissible speed, {} (against {})",
            method_name(governing.method),
            speeds(governing),
            others.join(", ")
        )
    };
    let judged: Vec<(SafetyMethod, bool)> = methods
        .iter()
        .filter_map(|m| m.verdict.map(|v| (m.method, v.pass)))
        .collect();
    Some(OverallVerdict {
        method: governing.method,
        v_max_mps: governing.v_max_mps,
        governing: governing.governing,
        speed_mps: methods.iter().find_map(|m| m.verdict.map(|v| v.speed_mps)),
        pass: (!judged.is_empty()).then(|| judged.iter().all(|(_, pass)| *pass)),
        failed_by: judged
            .iter()
            .filter(|(_, pass)| !pass)
            .map(|(m, _)| *m)
            .collect(),
        reason,
    })
}

/// The travel [m] beyond which a link's deflection is not plausible when its length is not
/// known: half a metre, about the reach of a collaborative arm's forearm.
pub const PLAUSIBLE_TRAVEL_M: f64 = 0.5;

/// The warnings of the energy method's answer: its speed stores the contact force at the limit
/// in the link's spring, so the link deflects F/k_δ; more than the link's length (or, without a
/// length, more than [`PLAUSIBLE_TRAVEL_M`]) is a deflection no linear link makes, and the
/// answer is not one to rely on. `force` \[N\] is the force at the governing limit, `k_delta`
/// \[N/m\] the link's stiffness, `length` \[m\] the link's length when known.
pub fn energy_travel_warning(
    energy: &MethodResult,
    force: f64,
    k_delta: Option<f64>,
    length: Option<f64>,
) -> Option<crate::shared::plausibility::Warning> {
    let k = k_delta?;
    let deflection = force / k;
    let (travel, what) = match length {
        Some(l) => (l, format!("the link's length L = {} m", display(l))),
        None => (
            PLAUSIBLE_TRAVEL_M,
            format!("{} m, a plausible travel", display(PLAUSIBLE_TRAVEL_M)),
        ),
    };
    (deflection > travel && energy.v_max_mps.value().is_finite()).then(|| crate::shared::plausibility::Warning {
        field: "--k-delta".into(),
        message: format!(
            "the energy method's {} m/s needs the link to deflect F/k_δ = {} m at the {} N limit, \
             more than {what}: it assumes a linear link that bends that far — do not rely on it{}",
            display(energy.v_max_mps.value()),
            display(deflection),
            display(force),
            if matches!(energy.governing, GoverningLimit::Pressure) {
                ""
            } else {
                " (run the simulation method for this design)"
            }
        ),
    })
}

/// Whether the contact law is the body's own linear spring (n = 1), for which no contact
/// geometry exists.
pub fn is_body_spring(law: &ContactLaw) -> bool {
    matches!(law, ContactLaw::BodySpring)
}
