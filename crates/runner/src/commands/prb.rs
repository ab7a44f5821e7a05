//! `flexrig prb`: the Pseudo-Rigid-Body model (γ, K_Θ) of a cantilever with a perpendicular
//! dead end load, fitted to the corotational FE tip path as Howell does, compared with the
//! published values, the paper's k_θp = πEIγ²/L and its effective mass m_eff = m_e + γ m_r/3.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig_beam::canonical::{
    CANTILEVER_BETA_L, HOWELL_GAMMA, HOWELL_K_THETA, HOWELL_THETA_MAX_DEG, PAPER_GAMMA_SMALL,
    unit_cantilever_with_tip_mass,
};
use flexrig_beam::prb::{
    ErrorMeasure, PrbFit, TipPoint, default_load_indices, fit_prb, trace_tip_path_with,
};
use flexrig_beam::{Kinematics, ModalDirection, modal_analysis};
use plotters::prelude::*;
use serde_json::json;

use crate::CliError;
use crate::output::{ensure_dir, line, print_json, write_atomic};

/// Arguments of `flexrig prb`.
#[derive(Debug, Args)]
pub struct PrbArgs {
    /// Number of elements of the traced cantilever (4 to 1024).
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
}

/// Payload-to-beam mass ratios μ = m_e/m_r for the effective-mass comparison: none, the paper's
/// light load (0.1 kg on 51 g) and its test payload (412 g on 51 g).
const PAYLOAD_RATIOS: [f64; 3] = [0.0, 0.1 / 0.051, 0.412 / 0.051];

/// FE effective mass of the beam at its tip, as a fraction of m_r, with a tip payload μ m_r:
/// m_eff = k_tip/ω₁² − m_e, k_tip = 3EI/L³ (unit beam, 64 linear elements).
fn fe_beam_share(mu: f64) -> Result<f64, CliError> {
    let m = unit_cantilever_with_tip_mass(64, mu)?;
    let w = modal_analysis(&m, 1, ModalDirection::Transverse)?.omegas[0];
    Ok(3.0 / (w * w) - mu)
}

/// Runs the PRB check.
pub fn run(args: &PrbArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if !(4..=1024).contains(&args.elements) {
        return Err(CliError::InvalidArgument {
            arg: "--elements".into(),
            value: args.elements.to_string(),
            allowed: "must be an integer from 4 to 1024".into(),
        });
    }
    let measure = match args.criterion.as_str() {
        "deflection" => ErrorMeasure::Deflection,
        "length" => ErrorMeasure::Length,
        other => {
            return Err(CliError::InvalidArgument {
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
            return Err(CliError::InvalidArgument {
                arg: "--model".into(),
                value: other.into(),
                allowed: "must be ancf or corotational".into(),
            });
        }
    };
    let path = trace_tip_path_with(kinematics, args.elements, &default_load_indices())?;
    let fit = fit_prb(&path, measure)?;
    let other = fit_prb(
        &path,
        match measure {
            ErrorMeasure::Deflection => ErrorMeasure::Length,
            ErrorMeasure::Length => ErrorMeasure::Deflection,
        },
    )?;
    let pi = std::f64::consts::PI;
    let stiffness = |g: f64, k: f64| json!({"gamma": g, "howell_k_l_over_ei": g * k, "paper_k_l_over_ei": pi * g * g});
    let m_eff_modal = 3.0 / CANTILEVER_BETA_L[0].powi(4);
    let mut shares = Vec::new();
    for mu in PAYLOAD_RATIOS {
        shares.push(json!({"payload_over_m_r": mu, "fe_beam_share": fe_beam_share(mu)?}));
    }
    ensure_dir(&args.out)?;
    let svg_path = args.out.join("prb.svg");
    let svg = prb_svg(&path, &fit).map_err(|message| CliError::Plot {
        path: svg_path.clone(),
        message,
    })?;
    write_atomic(&svg_path, svg.as_bytes())?;
    let report = json!({
        "elements": args.elements,
        "model": args.model,
        "criterion": args.criterion,
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
            "PRB fit to the corotational FE tip path ({} elements, error relative to {}):",
            args.elements, args.criterion
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
                "  effective mass, payload {:.2} m_r: FE beam share {:.4} m_r vs γ/3 = {:.4} (γ = 2/3), {:.4} (fitted γ)",
                s["payload_over_m_r"].as_f64().unwrap_or(0.0),
                s["fe_beam_share"].as_f64().unwrap_or(0.0),
                PAPER_GAMMA_SMALL / 3.0,
                fit.gamma / 3.0
            ),
        )?;
    }
    line(out, format!("  wrote {}", svg_path.display()))
}

/// FE tip path against the PRB circle of the fitted γ (up to Θ_max, dashed beyond) and γ = 2/3.
fn prb_svg(path: &[TipPoint], fit: &PrbFit) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "Cantilever tip path: FE (corotational) vs PRB γ = {:.4} (Θ_max = {:.1}°)",
                    fit.gamma, fit.theta_max_deg
                ),
                ("sans-serif", 18),
            )
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..1.05, 0.0..1.0)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("a/L (horizontal tip position)")
            .y_desc("b/L (tip deflection)")
            .draw()
            .map_err(|e| e.to_string())?;
        let arc = |g: f64, t0: f64, t1: f64| -> Vec<(f64, f64)> {
            (0..=200)
                .map(|i| {
                    let t = t0 + (t1 - t0) * i as f64 / 200.0;
                    (1.0 - g + g * t.cos(), g * t.sin())
                })
                .collect()
        };
        let tm = fit.theta_max_deg.to_radians();
        let blue = RGBColor(31, 119, 180);
        let orange = RGBColor(255, 127, 14);
        chart
            .draw_series(LineSeries::new(
                arc(fit.gamma, 0.0, tm),
                blue.stroke_width(3),
            ))
            .map_err(|e| e.to_string())?
            .label(format!("PRB γ = {:.4}, Θ ≤ Θ_max", fit.gamma))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(3))
            });
        chart
            .draw_series(LineSeries::new(
                arc(fit.gamma, tm, 1.6),
                blue.stroke_width(1),
            ))
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(LineSeries::new(
                arc(2.0 / 3.0, 0.0, 1.6),
                orange.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label("PRB γ = 2/3 (small deflection)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], orange.stroke_width(2))
            });
        chart
            .draw_series(
                path.iter()
                    .step_by(6)
                    .map(|p| Circle::new((p.a, p.b), 3, BLACK.filled())),
            )
            .map_err(|e| e.to_string())?
            .label("FE tip path (PL²/EI up to 30)")
            .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerLeft)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
