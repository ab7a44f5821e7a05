//! The Pseudo-Rigid-Body model (γ, K_Θ) of a cantilever with a perpendicular dead end load,
//! fitted to the large-deflection FE tip path as Howell does, to compare with the published
//! values, the paper's k_θp = πEIγ²/L and its effective mass m_eff = m_e + γ m_r/3 (Eq. 5).

use std::path::PathBuf;

use flexrig_beam::canonical::unit_cantilever_with_tip_mass;
use flexrig_beam::prb::{default_load_indices, fit_prb, trace_tip_path_with};
use flexrig_beam::{ModalDirection, modal_analysis};

use crate::Error;
use crate::plots::{prb_svg, write_figure};
use crate::shared::output::ensure_dir;

/// The fit's inputs and results and the published references (flexrig-beam's), for callers of
/// this module.
pub use flexrig_beam::Kinematics;
pub use flexrig_beam::canonical::{
    CANTILEVER_BETA_L, HOWELL_GAMMA, HOWELL_K_THETA, HOWELL_THETA_MAX_DEG, PAPER_GAMMA_SMALL,
};
pub use flexrig_beam::prb::{ErrorMeasure, PrbFit, TipPoint};

/// What the check traces and where it writes (the flags of `flexrig prb`).
#[derive(Debug, Clone, PartialEq)]
pub struct PrbOptions {
    /// Elements of the traced cantilever, 4 to 256 (`--elements`).
    pub elements: usize,
    /// Large-deflection element: ANCF (fourth order in the mesh) or corotational (second
    /// order) (`--model`).
    pub kinematics: Kinematics,
    /// Tip-error measure of the 0.5 % criterion (`--criterion`).
    pub criterion: ErrorMeasure,
    /// Directory for prb.svg (created if missing; `--out`).
    pub out: PathBuf,
    /// Printed size and formats of the figure (`--size`, `--format`, `--dpi`).
    pub figures: crate::plots::FigureOptions,
}

/// Angle of the traced dead tip load to the undeformed beam \[deg\]: perpendicular (Howell's
/// n = 0 case, the one his γ = 0.8517 and K_Θ = 2.65 are for).
pub const LOAD_ANGLE_DEG: f64 = 90.0;

/// The element's name as reports say it: `ANCF` or `corotational`.
pub fn kinematics_name(kinematics: Kinematics) -> &'static str {
    match kinematics {
        Kinematics::Ancf => "ANCF",
        Kinematics::Corotational => "corotational",
        Kinematics::Linear => "linear",
    }
}

/// Payload-to-beam mass ratios μ = m_e/m_r for the effective-mass comparison: none, the paper's
/// light load (0.1 kg on 51 g) and its test payload (412 g on 51 g).
pub const PAYLOAD_RATIOS: [f64; 3] = [0.0, 0.1 / 0.051, 0.412 / 0.051];

/// FE effective mass of the beam at its tip, as a fraction of m_r, with a tip payload μ m_r:
/// m_eff = k_tip/ω₁² − m_e, k_tip = 3EI/L³ (unit beam, 64 linear elements).
pub fn fe_beam_share(mu: f64) -> Result<f64, Error> {
    let m = unit_cantilever_with_tip_mass(64, mu)?;
    let w = modal_analysis(&m, 1, ModalDirection::Transverse)?.omegas[0];
    Ok(3.0 / (w * w) - mu)
}

/// The mesh size in its range (the error names `--elements`).
pub fn check_elements(elements: usize) -> Result<usize, Error> {
    if (4..=256).contains(&elements) {
        Ok(elements)
    } else {
        Err(Error::InvalidArgument {
            arg: "--elements".into(),
            value: elements.to_string(),
            allowed: "must be an integer from 4 to 256".into(),
        })
    }
}

/// The other tip-error measure.
pub fn other_measure(measure: ErrorMeasure) -> ErrorMeasure {
    match measure {
        ErrorMeasure::Deflection => ErrorMeasure::Length,
        ErrorMeasure::Length => ErrorMeasure::Deflection,
    }
}

/// The effective-mass comparison at one payload.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassShare {
    /// Payload over the link mass, m_e/m_r.
    pub payload_over_m_r: f64,
    /// The FE beam's share of the tip effective mass over m_r ([`fe_beam_share`]).
    pub fe_beam_share: f64,
}

/// What the check found.
#[derive(Debug, Clone, PartialEq)]
pub struct PrbResult {
    /// The traced FE tip path.
    pub path: Vec<TipPoint>,
    /// The fit by the chosen criterion.
    pub fit: PrbFit,
    /// The fit by the other criterion ([`other_measure`]).
    pub other: PrbFit,
    /// The FE beam share of the effective mass at each of [`PAYLOAD_RATIOS`].
    pub shares: Vec<MassShare>,
    /// The figure in the first format asked for (prb.svg by default).
    pub svg: PathBuf,
    /// The figure in every format asked for.
    pub figures: Vec<PathBuf>,
}

/// Traces the tip path, fits the PRB model by both criteria, compares the effective mass and
/// draws prb.svg.
pub fn run(options: &PrbOptions) -> Result<PrbResult, Error> {
    check_elements(options.elements)?;
    options.figures.validate()?;
    let path = trace_tip_path_with(
        options.kinematics,
        options.elements,
        &default_load_indices(),
    )?;
    let fit = fit_prb(&path, options.criterion)?;
    let other = fit_prb(&path, other_measure(options.criterion))?;
    let shares = PAYLOAD_RATIOS
        .iter()
        .map(|&mu| {
            Ok(MassShare {
                payload_over_m_r: mu,
                fe_beam_share: fe_beam_share(mu)?,
            })
        })
        .collect::<Result<Vec<_>, Error>>()?;
    ensure_dir(&options.out)?;
    let svg = prb_svg(
        &path,
        &fit,
        kinematics_name(options.kinematics),
        options.figures.width_pt(),
    )
    .map_err(|message| Error::Plot {
        path: options.out.join("prb.svg"),
        message,
    })?;
    let figures = write_figure(&options.out, "prb", &svg, &options.figures)?;
    Ok(PrbResult {
        path,
        fit,
        other,
        shares,
        svg: figures[0].clone(),
        figures,
    })
}
