//! `flexrig eta`: the paper's Fig. 6 design cases at finite-element fidelity, see
//! [`flexrig::fe::eta`]; the flags into [`EtaSettings`], the table printed.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use flexrig::fe::eta::{
    ClMethod, EffectiveGamma, EtaSettings, WindowReport, contact_text, joint_text,
};
use flexrig::fronts::{EtaInputs, JointKind};
use flexrig::{CancelToken, Error};

use super::impact_args::{DampingArgs, JointArg};
use crate::print::{line, print_json};

/// How the CL link is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// The FE link's modes on a mesh graded towards the tip, integrated exactly between force
    /// samples (fast; --tol, --zone-elements).
    Modal,
    /// The FE link on a uniform mesh by generalized-α (the reference; --elements,
    /// --steps-per-contact, --modes).
    Alpha,
}

/// Arguments of `flexrig eta`.
#[derive(Debug, Args)]
pub struct EtaArgs {
    /// Directory for eta.csv and eta.svg (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// The joint during the impact.
    #[arg(long, value_enum, default_value = "held")]
    pub joint: JointArg,
    /// Rotor inertia J_R of the free hub [kg·m²] (with --joint free-hub).
    #[arg(long, value_name = "KG_M2")]
    pub rotor_inertia: Option<f64>,
    /// How the CL link is solved.
    #[arg(long, value_enum, default_value = "modal")]
    pub method: MethodArg,
    /// Modal method: tolerance of the force's linear hold per step (1e-10 to 0.1; default 1e-6).
    #[arg(long, value_name = "TOL")]
    pub tol: Option<f64>,
    /// Modal method: elements across the tip zone (EI/ρA)^¼ √t_c of the graded mesh (0.5 to
    /// 1000; default 8).
    #[arg(long, value_name = "N")]
    pub zone_elements: Option<f64>,
    /// Modal method: also follow every contact for this many first-mode periods of the CJ link
    /// (0.01 to 1000), run at --tol and --tol/10 to find how long the contacts are converged.
    #[arg(long, value_name = "P")]
    pub window_periods: Option<f64>,
    /// Alpha method: Hermite-cubic elements of the CL beam (2 to 4096; default 256).
    #[arg(long, value_name = "N")]
    pub elements: Option<usize>,
    /// Alpha method: time steps over the shortest possible contact (head against the payload;
    /// 20 to 1e6; default 800).
    #[arg(long, value_name = "N")]
    pub steps_per_contact: Option<usize>,
    /// Alpha method: the CL beam reduced to its lowest N modes plus the tip's static correction
    /// shape (at most 1000 elements); without it, the full FE model.
    #[arg(long, value_name = "N")]
    pub modes: Option<usize>,
    /// Link length L [m] (the transverse impact does not depend on it).
    #[arg(long, value_name = "M", default_value_t = 1.0)]
    pub length: f64,
    /// The contact's damping.
    #[command(flatten)]
    pub contact: DampingArgs,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// Size and formats of eta.svg and eta_fig6.svg.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
    /// The design held fixed.
    #[command(flatten)]
    pub design: super::impact_args::DesignArgs,
    /// The cases.
    #[command(flatten)]
    pub cases: super::impact_args::CaseArgs,
}

fn settings(args: &EtaArgs) -> Result<EtaSettings, Error> {
    flexrig::fronts::eta_settings(&EtaInputs {
        joint: match args.joint {
            JointArg::Held => JointKind::Held,
            JointArg::FreeHub => JointKind::FreeHub,
        },
        rotor_inertia: args.rotor_inertia,
        alpha: args.method == MethodArg::Alpha,
        tol: args.tol,
        zone_elements: args.zone_elements,
        window_periods: args.window_periods,
        elements: args.elements,
        steps_per_contact: args.steps_per_contact,
        modes: args.modes,
        length: args.length,
        damping: args.contact.spec()?,
        design: args.design.design(),
    })
}

fn gamma_text(g: &EffectiveGamma) -> String {
    match g {
        EffectiveGamma::Fits(g) => format!("{g:.6}"),
        EffectiveGamma::AboveGammaOne => "> 1".into(),
        EffectiveGamma::BelowPayloadOnly => "< 0".into(),
    }
}

fn method_text(method: &ClMethod) -> String {
    match method {
        ClMethod::Modal { mesh, tol } => format!(
            "CL: FE modes on a graded mesh, {} elements per tip zone, exact modal integration, tol {tol:e}",
            mesh.zone_elements
        ),
        ClMethod::Alpha(s) => format!(
            "CL: {} elements, generalized-α, {} steps per contact",
            s.elements, s.steps_per_contact
        ),
    }
}

/// Runs `flexrig eta`.
pub fn run(args: &EtaArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let settings = settings(args)?;
    let r = flexrig::fe::eta::run(
        &settings,
        &args.cases.grid(),
        &args.out,
        &args.figure.options()?,
        cancel,
    )
    .map_err(super::impact_args::impact_as_flag)?;
    let (rows, csv_path, svg_path, fig6_path) = (&r.rows, &r.csv, &r.svg, &r.fig6_svg);
    let joint = joint_text(&settings.joint);
    if args.json {
        return print_json(out, &flexrig::fronts::eta_report(&settings, &r));
    }
    line(
        out,
        format!(
            "Fig. 6 cases at FE fidelity (free head, {joint} joint; m_r = {} kg, k_c = {:e} N/mⁿ, v0 = {} m/s, L = {} m, {}; {})",
            settings.design.m_r,
            settings.design.k_c,
            settings.design.v0,
            settings.length,
            contact_text(&settings.damping),
            method_text(&settings.method)
        ),
    )?;
    line(
        out,
        format!(
            "{:>7} {:>8} {:>6} {:>3} {:>12} {:>12} {:>9} {:>11} {:>12} {:>9} {:>12}",
            "m_h[kg]",
            "k_δ[N/m]",
            "m_e[kg]",
            "n",
            "f_CJ[N]",
            "f_CL[N]",
            "η_FE",
            "η_lump(2/3)",
            "f_CJ,lump[N]",
            "γ_eff",
            "f_placed[N]"
        ),
    )?;
    for r in rows {
        line(
            out,
            format!(
                "{:>7} {:>8.0e} {:>6} {:>3} {:>12.1} {:>12.1} {:>9.5} {:>11.5} {:>12.1} {:>9} {:>12.1}",
                r.case.m_h,
                r.case.k_delta,
                r.case.m_e,
                r.n,
                r.f_cj_n,
                r.f_cl_n,
                r.eta_fe,
                r.eta_lumped_2_3,
                r.f_cj_lumped_n,
                gamma_text(&r.gamma_eff),
                r.f_placed_n
            ),
        )?;
    }
    if rows.iter().any(|r| r.window.is_some()) {
        line(
            out,
            "Every contact in the window (runs at --tol and --tol/10; the horizon is where they part):",
        )?;
        line(
            out,
            format!(
                "{:>7} {:>8} {:>6} {:>3} {:>10} {:>14} {:>14} {:>12} {:>12} {:>9}",
                "m_h[kg]",
                "k_δ[N/m]",
                "m_e[kg]",
                "n",
                "window[s]",
                "CJ contacts/s",
                "CL contacts/s",
                "f_CJ,all[N]",
                "f_CL,all[N]",
                "η_all"
            ),
        )?;
        for r in rows {
            let Some(w) = &r.window else { continue };
            let contacts = |x: &WindowReport| {
                format!(
                    "{}/{}@{:.3}",
                    x.converged_contacts,
                    x.outcome.contacts.len(),
                    x.horizon_s
                )
            };
            line(
                out,
                format!(
                    "{:>7} {:>8.0e} {:>6} {:>3} {:>10.4} {:>14} {:>14} {:>12.1} {:>12.1} {:>9.5}",
                    r.case.m_h,
                    r.case.k_delta,
                    r.case.m_e,
                    r.n,
                    w.window_s,
                    contacts(&w.cj),
                    contacts(&w.cl),
                    w.cj.overall_converged.peak_force_n,
                    w.cl.overall_converged.peak_force_n,
                    w.cl.overall_converged.peak_force_n / w.cj.overall_converged.peak_force_n
                ),
            )?;
        }
    }
    line(
        out,
        format!(
            "Wrote {}, {} and {} (the FE points on the Fig. 6 curves)",
            csv_path.display(),
            svg_path.display(),
            fig6_path.display()
        ),
    )
}
