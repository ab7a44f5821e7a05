//! `flexrig prb`: the Pseudo-Rigid-Body model (γ, K_Θ) against the large-deflection FE beam, see
//! [`flexrig::fe::prb`].

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::Error;
use flexrig::fe::prb::{
    HOWELL_GAMMA, HOWELL_K_THETA, HOWELL_THETA_MAX_DEG, LOAD_ANGLE_DEG, PAPER_GAMMA_SMALL,
    kinematics_name,
};

use crate::print::{line, print_json};

/// Arguments of `flexrig prb`.
#[derive(Debug, Args)]
pub struct PrbArgs {
    /// Number of elements of the traced cantilever (4 to 256).
    #[arg(long, value_name = "N", default_value_t = 32)]
    pub elements: usize,
    /// Large-deflection element: ancf (default: fourth order in the mesh, 1e-7 on the elastica
    /// at 32 elements) or corotational (second order, 1.5e-4).
    #[arg(long, value_name = "ancf|corotational", default_value = "ancf")]
    pub model: String,
    /// Tip-error measure of the 0.5 % criterion: deflection (relative to the tip deflection,
    /// Howell's; reproduces γ = 0.8517) or length (relative to L).
    #[arg(long, value_name = "deflection|length", default_value = "deflection")]
    pub criterion: String,
    /// Directory for prb.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
    /// Size and formats of prb.svg.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
}

/// Runs the PRB check.
pub fn run(args: &PrbArgs, out: &mut dyn Write) -> Result<(), Error> {
    let options = flexrig::fronts::prb_options(
        args.elements,
        &args.model,
        &args.criterion,
        args.out.clone(),
        args.figure.options()?,
    )?;
    let r = flexrig::fe::prb::run(&options)?;
    let report = flexrig::fronts::prb_report(&options, &r);
    let (fit, other, svg_path) = (r.fit, r.other, &r.svg);
    let pi = std::f64::consts::PI;
    let shares = report["effective_mass"]["fe"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    if args.json {
        return print_json(out, &report);
    }
    line(
        out,
        format!(
            "PRB fit to the {} FE tip path ({} elements, dead tip load at {}° to the undeformed beam, error relative to {}):",
            kinematics_name(options.kinematics),
            args.elements,
            LOAD_ANGLE_DEG,
            args.criterion
        ),
    )?;
    line(
        out,
        format!(
            "  γ = {:.4}  K_Θ = {:.4}  Θ_max = {:.1}°   (Howell: γ = {HOWELL_GAMMA}, K_Θ = {HOWELL_K_THETA}, Θ_max ≈ {HOWELL_THETA_MAX_DEG}°)",
            fit.gamma, fit.k_theta, fit.theta_max_deg
        ),
    )?;
    line(
        out,
        format!(
            "  other criterion ({}): γ = {:.4}, K_Θ = {:.4}, Θ_max = {:.1}°",
            report["other_criterion"]["criterion"]
                .as_str()
                .unwrap_or(""),
            other.gamma,
            other.k_theta,
            other.theta_max_deg
        ),
    )?;
    line(
        out,
        format!(
            "  small-deflection limit: γ = {:.4}, K_Θ = {:.4} (exact 2/3, 2)",
            fit.gamma_small, fit.k_theta_small
        ),
    )?;
    line(
        out,
        format!(
            "  spring k L/EI: fitted γK_Θ = {:.4} vs paper πγ² = {:.4}; γ = 2/3: exact 4/3 vs paper {:.4}",
            fit.gamma * fit.k_theta,
            pi * fit.gamma * fit.gamma,
            pi * 4.0 / 9.0
        ),
    )?;
    for s in &shares {
        line(
            out,
            format!(
                "  effective mass, payload ratio m_e/m_r = {:.3}: FE beam share {:.4} m_r vs γ/3 = {:.4} (γ = 2/3), {:.4} (fitted γ)",
                s["payload_over_m_r"].as_f64().unwrap_or(0.0),
                s["fe_beam_share"].as_f64().unwrap_or(0.0),
                PAPER_GAMMA_SMALL / 3.0,
                fit.gamma / 3.0
            ),
        )?;
    }
    line(out, format!("  wrote {}", svg_path.display()))
}
