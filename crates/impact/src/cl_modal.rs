//! The CL (and any lumped link) by its modes and the exact modal integrator: the fast path of
//! the FE impact study (issue 14). The CL's modes come from the finite-element link on a mesh
//! graded towards the tip ([`crate::graded`]); the modal integrator ([`crate::modal_run`]) carries
//! no time-discretisation error in the link, so the step follows the contact alone.

use crate::ImpactError;
use crate::chain::Chain;
use crate::graded::{GradedMesh, cl_tip_modes};
use crate::modal_run::{Head, ModalOptions, run_modes, run_modes_against, run_modes_traced};
use crate::setup::{FreeMassImpact, ImpactOutcome, Joint};
use crate::severity::ContactTrace;
use crate::tip_modes::TipModes;

/// The head at the onset: at v0 towards a robot at rest (held joint), or at rest with the robot
/// moving into it (free hub).
pub fn head_at_onset(setup: &FreeMassImpact) -> Head {
    Head {
        mass: setup.m_h,
        x: 0.0,
        v: match setup.joint {
            Joint::Held => setup.v0,
            Joint::FreeHub { .. } => 0.0,
        },
    }
}

/// Runs `setup` on a link given by its modes.
pub fn run_on_modes(
    setup: &FreeMassImpact,
    modes: &TipModes,
    options: &ModalOptions,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    run_modes(
        modes,
        head_at_onset(setup),
        &*setup.law()?,
        setup.payload_contact_time(),
        options,
    )
}

/// [`run_on_modes`] with the hold's tolerance against at least `force_scale` \[N\]
/// ([`run_modes_against`]).
pub fn run_on_modes_against(
    setup: &FreeMassImpact,
    modes: &TipModes,
    options: &ModalOptions,
    force_scale: f64,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    run_modes_against(
        modes,
        head_at_onset(setup),
        &*setup.law()?,
        setup.payload_contact_time(),
        options,
        force_scale,
    )
}

/// [`run_on_modes`] with the contact's traces ([`run_modes_traced`]).
pub fn run_on_modes_traced(
    setup: &FreeMassImpact,
    modes: &TipModes,
    options: &ModalOptions,
) -> Result<(ImpactOutcome, ContactTrace), ImpactError> {
    setup.validate()?;
    run_modes_traced(
        modes,
        head_at_onset(setup),
        &*setup.law()?,
        setup.payload_contact_time(),
        options,
    )
}

/// The CL impact: the FE link on the graded `mesh`.
pub fn run_cl_modal(
    setup: &FreeMassImpact,
    mesh: &GradedMesh,
    options: &ModalOptions,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    run_on_modes(setup, &cl_tip_modes(setup, mesh)?, options)
}

/// The CJ impact through the same integrator (the rigid link: one mode).
pub fn run_cj_modal(
    setup: &FreeMassImpact,
    options: &ModalOptions,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    run_on_modes(setup, &Chain::cj(setup).tip_modes(setup, 0.0)?, options)
}

/// The placed reduced model of the CL ([`Chain::placed`]).
pub fn run_placed(
    setup: &FreeMassImpact,
    options: &ModalOptions,
) -> Result<ImpactOutcome, ImpactError> {
    setup.validate()?;
    let link = setup.link;
    let modes = Chain::placed(setup).tip_modes(setup, link.m_r / 3.0 - link.m_r / 4.0)?;
    run_on_modes(setup, &modes, options)
}
