//! `flexrig eta-map`: maps of η_FE and the lumped and placed models' errors over
//! m_e/m_r × k_δ/k_c, see [`flexrig::fe::eta_map`].

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::fe::eta_map::{EtaMapOptions, settings_text};
use flexrig::{CancelToken, Error};

use super::impact_args::{DampingArgs, JointArg, impact_as_flag, joint_from_args};
use crate::print::{line, print_json};

/// Arguments of `flexrig eta-map`.
#[derive(Debug, Args)]
pub struct EtaMapArgs {
    /// Directory for eta_map.csv and one eta_map_mh<M>.svg per head mass (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Head masses m_h [kg], comma-separated (one map each).
    #[arg(
        long = "m-h",
        value_name = "KG,...",
        value_delimiter = ',',
        default_value = "4,1000"
    )]
    pub m_h: Vec<f64>,
    /// Hertz exponent n (1 to 3).
    #[arg(long, value_name = "N", default_value_t = 2.0)]
    pub n: f64,
    /// Payload over link mass m_e/m_r along x, log-spaced: FROM:TO:N:log, or FROM:TO with N
    /// from --points (within [1e-6, 1e5]; see "Ranges" in docs/cli.md).
    #[arg(long, value_name = "FROM:TO[:N:log]", default_value = "1e-3:1e2")]
    pub mass_ratio: String,
    /// Link over contact stiffness k_δ/k_c along y, log-spaced: FROM:TO:N:log, or FROM:TO with
    /// N from --points (within [1e-11, 1e4]).
    #[arg(long, value_name = "FROM:TO[:N:log]", default_value = "1e-7:1")]
    pub stiffness_ratio: String,
    /// Points along each axis given as FROM:TO (2 to 200).
    #[arg(long, value_name = "N", default_value_t = 30)]
    pub points: usize,
    /// The joint during the impact.
    #[arg(long, value_enum, default_value = "held")]
    pub joint: JointArg,
    /// Rotor inertia J_R of the free hub [kg·m²] (with --joint free-hub).
    #[arg(long, value_name = "KG_M2")]
    pub rotor_inertia: Option<f64>,
    /// Tolerance of the force's linear hold per step (1e-10 to 0.1); 1e-5 keeps each peak
    /// within 5e-5 of the converged one (tested).
    #[arg(long, value_name = "TOL", default_value = "1e-5")]
    pub tol: f64,
    /// The contact's damping.
    #[command(flatten)]
    pub contact: DampingArgs,
    /// Print JSON instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// Link length L [m], in [1e-3, 1e3] (the transverse impact does not depend on it).
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    pub length: f64,
    /// Size and formats of the figures.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
    /// The design held fixed (the map's axes are ratios to m_r and k_c).
    #[command(flatten)]
    pub design: super::impact_args::DesignArgs,
}

/// Runs `flexrig eta-map`.
pub fn run(args: &EtaMapArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let joint = joint_from_args(args.joint, args.rotor_inertia)?;
    let specs = flexrig::fronts::eta_map_specs(
        &args.m_h,
        args.n,
        &args.mass_ratio,
        &args.stiffness_ratio,
        args.points,
    )?;
    let (nx, ny) = (specs[0].mass_ratio.points, specs[0].stiffness_ratio.points);
    let settings = flexrig::fronts::eta_map_settings(
        joint,
        args.tol,
        args.contact.spec()?,
        args.design.design(),
        args.length,
    )?;
    let joint_text = settings_text(&settings);
    let r = flexrig::fe::eta_map::run(
        &EtaMapOptions {
            out: args.out.clone(),
            specs,
            settings,
            figures: args.figure.options()?,
        },
        cancel,
    )
    .map_err(impact_as_flag)?;
    let report = flexrig::fronts::eta_map_report(&settings, &r);
    if args.json {
        return print_json(out, &report);
    }
    let summaries = report["maps"].as_array().cloned().unwrap_or_default();
    let paths: Vec<_> = r.files.iter().map(|p| p.display().to_string()).collect();
    line(
        out,
        format!(
            "η over m_e/m_r {} × k_δ/k_c {} ({} × {} points, n = {}, m_r = {} kg, k_c = {:e} N/mⁿ, v0 = {} m/s, L = {} m, {joint_text}, tol {:e})",
            args.mass_ratio,
            args.stiffness_ratio,
            nx,
            ny,
            args.n,
            settings.design.m_r,
            settings.design.k_c,
            settings.design.v0,
            settings.length,
            args.tol
        ),
    )?;
    for s in &summaries {
        line(
            out,
            format!(
                "m_h = {} kg: {} points in {:.1} s ({} failed); CL beats CJ by > 5 % at {}; \
                 lumped η(2/3) within 5 % of η_FE at {}, worst {:.3}; placed model within 5 % \
                 at {}, worst {:.3}; γ_eff in (0, 1] at {}",
                s["m_h_kg"],
                s["points"],
                s["seconds"].as_f64().unwrap_or(0.0),
                s["failed"],
                s["cl_beats_cj_by_5_percent"],
                s["lumped_within_5_percent"],
                s["lumped_error_max"].as_f64().unwrap_or(0.0),
                s["placed_within_5_percent"],
                s["placed_error_max"].as_f64().unwrap_or(0.0),
                s["gamma_eff_fits"],
            ),
        )?;
    }
    line(out, format!("Wrote {}", paths.join(", ")))
}
