//! `flexrig prb`: the Pseudo-Rigid-Body model (γ, K_Θ) against the large-deflection FE beam, see
//! [`flexrig::prb`].

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::Error;
use flexrig::prb::{
    CANTILEVER_BETA_L, ErrorMeasure, HOWELL_GAMMA, HOWELL_K_THETA, HOWELL_THETA_MAX_DEG,
    Kinematics, LOAD_ANGLE_DEG, PAPER_GAMMA_SMALL, PrbOptions, check_elements, kinematics_name,
};
use serde_json::json;

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
    check_elements(args.elements)?;
    let measure = match args.criterion.as_str() {
        "deflection" => ErrorMeasure::Deflection,
        "length" => ErrorMeasure::Length,
        other => {
            return Err(Error::InvalidArgument {
                arg: "--criterion".into(),
                value: other.into(),
                allowed: "must be deflection or length".into(),
            });
        }
    };
    let kinematics = match args.model.as_str() {
        "ancf" => Kinematics::Ancf,
        "corotational" => Kinematics::Corotational,
        other => {
            return Err(Error::InvalidArgument {
                arg: "--model".into(),
                value: other.into(),
                allowed: "must be ancf or corotational".into(),
            });
        }
    };
    let r = flexrig::prb::run(&PrbOptions {
        elements: args.elements,
        kinematics,
        criterion: measure,
        out: args.out.clone(),
        figures: args.figure.options()?,
    })?;
    let (fit, other, svg_path) = (r.fit, r.other, &r.svg);
    let pi = std::f64::consts::PI;
    let stiffness = |g: f64, k: f64| json!({"gamma": g, "howell_k_l_over_ei": g * k, "paper_k_l_over_ei": pi * g * g});
    let m_eff_modal = 3.0 / CANTILEVER_BETA_L[0].powi(4);
    let shares: Vec<serde_json::Value> = r
        .shares
        .iter()
        .map(|s| json!({"payload_over_m_r": s.payload_over_m_r, "fe_beam_share": s.fe_beam_share}))
        .collect();
    let report = json!({
        "elements": args.elements,
        "model": args.model,
        "criterion": args.criterion,
        "load_angle_deg": LOAD_ANGLE_DEG,
        "gamma": fit.gamma,
        "k_theta": fit.k_theta,
        "theta_max_deg": fit.theta_max_deg,
        "small_deflection": {"gamma": fit.gamma_small, "k_theta": fit.k_theta_small},
        "published": {"gamma": HOWELL_GAMMA, "k_theta": HOWELL_K_THETA, "theta_max_deg": HOWELL_THETA_MAX_DEG,
                      "theta_max_deg_on_fe_path": fit.theta_max_deg_howell_gamma},
        "other_criterion": {"criterion": if measure == ErrorMeasure::Deflection {"length"} else {"deflection"},
                            "gamma": other.gamma, "k_theta": other.k_theta, "theta_max_deg": other.theta_max_deg},
        "spring_stiffness": {
            "note": "k L/EI: Howell k = γ K_Θ EI/L vs the paper's k_θp = π EI γ²/L",
            "fitted": stiffness(fit.gamma, fit.k_theta),
            "published": stiffness(HOWELL_GAMMA, HOWELL_K_THETA),
            "paper_small_deflection": stiffness(PAPER_GAMMA_SMALL, fit.k_theta_small),
        },
        "effective_mass": {
            "note": "beam share of the tip effective mass / m_r: FE k_tip/ω₁² − m_e vs lumped γ/3 (Eq. 5)",
            "fe_modal_no_payload": m_eff_modal,
            "fe": shares,
            "lumped_gamma_2_3": PAPER_GAMMA_SMALL / 3.0,
            "lumped_gamma_fitted": fit.gamma / 3.0,
            "lumped_gamma_1": 1.0 / 3.0,
        },
        "svg": svg_path.display().to_string(),
    });
    if args.json {
        return print_json(out, &report);
    }
    line(
        out,
        format!(
            "PRB fit to the {} FE tip path ({} elements, dead tip load at {}° to the undeformed beam, error relative to {}):",
            kinematics_name(kinematics),
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
