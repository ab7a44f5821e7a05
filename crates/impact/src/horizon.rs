//! Every contact within a window, and how far in time the result holds.
//!
//! A light payload chatters between the head and a soft link; each later contact starts from the
//! phases of many link modes, so the sequence of contacts is sensitive to any perturbation (the
//! tolerance of the integration, the mesh) and a long window holds no converged later peaks. The
//! run is therefore made twice, at `tol` and at `tol`/10, and the contacts are compared in order:
//! the **horizon** is the onset of the first contact that differs (peak by more than
//! [`PEAK_AGREEMENT`] relative, or onset by more than 1e-3 of the payload's contact time), or
//! the end of the run if none does. The overall peak is reported within the horizon, where it
//! is converged, and over the whole window beside it.

use serde::Serialize;

use crate::ImpactError;
use crate::cl_modal::run_on_modes;
use crate::modal_run::ModalOptions;
use crate::setup::{ContactEvent, FreeMassImpact, ImpactOutcome};
use crate::tip_modes::TipModes;

/// Largest relative difference of two peaks that still counts as the same contact.
pub const PEAK_AGREEMENT: f64 = 1e-4;

/// The contacts of a window and their converged horizon.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WindowReport {
    /// The run at the finer tolerance (tol/10).
    pub outcome: ImpactOutcome,
    /// Contacts that agree between the two runs (a prefix of `outcome.contacts`).
    pub converged_contacts: usize,
    /// Time up to which the two runs agree \[s\].
    pub horizon_s: f64,
    /// The largest peak among the converged contacts.
    pub overall_converged: ContactEvent,
}

/// Runs `setup` on `modes` over `options.window_s` at `options.tol` and at a tenth of it.
pub fn run_window(
    setup: &FreeMassImpact,
    modes: &TipModes,
    options: &ModalOptions,
) -> Result<WindowReport, ImpactError> {
    let coarse = run_on_modes(setup, modes, options)?;
    let fine = run_on_modes(
        setup,
        modes,
        &ModalOptions {
            tol: options.tol / 10.0,
            ..*options
        },
    )?;
    let onset_tol = 1e-3 * setup.payload_contact_time();
    let agree = |a: &ContactEvent, b: &ContactEvent| {
        (a.peak_force_n - b.peak_force_n).abs() <= PEAK_AGREEMENT * b.peak_force_n.abs().max(1e-300)
            && (a.onset_s - b.onset_s).abs() <= onset_tol
    };
    let converged = coarse
        .contacts
        .iter()
        .zip(&fine.contacts)
        .take_while(|(a, b)| agree(a, b))
        .count();
    let end = match fine.ended {
        crate::RunEnd::PartedForGood(t)
        | crate::RunEnd::Window(t)
        | crate::RunEnd::StepBudget(t)
        | crate::RunEnd::Rebound(t) => t,
        crate::RunEnd::FirstSeparation => fine.first.duration_s,
    };
    let all_agree = converged == fine.contacts.len() && converged == coarse.contacts.len();
    let horizon_s = if all_agree {
        end
    } else {
        fine.contacts[converged.min(fine.contacts.len() - 1)].onset_s
    };
    let overall_converged = fine.contacts[..converged.max(1)]
        .iter()
        .copied()
        .max_by(|a, b| a.peak_force_n.total_cmp(&b.peak_force_n))
        .unwrap_or(fine.first);
    Ok(WindowReport {
        outcome: fine,
        converged_contacts: converged,
        horizon_s,
        overall_converged,
    })
}
