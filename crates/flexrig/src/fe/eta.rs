//! The paper's Fig. 6 design cases at finite-element fidelity: the free-mass impact on the FE
//! compliant link and the rigid compliant joint ([`flexrig_impact::eta`]), η_FE beside the
//! lumped η(2/3) and the effective γ of the lumped model, as a CSV and two figures (the table,
//! and the FE points on the Fig. 6 curves).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexrig_impact::eta::eta_cases_until;
use flexrig_lumped::fig6::Fig6Grid;

use crate::CancelToken;
use serde::Serialize;

use crate::Error;
use crate::shared::output::{ensure_dir, write_atomic};

/// The table's inputs and rows (flexrig-impact's and flexrig-contact's), for callers of this
/// module.
pub use flexrig_contact::DampingSpec;
pub use flexrig_impact::eta::{ClMethod, EffectiveGamma, EtaRow, EtaSettings};
pub use flexrig_impact::graded::GradedMesh;
pub use flexrig_impact::horizon::WindowReport;
pub use flexrig_impact::{ClSolver, ImpactError, Joint};

/// Shortest and longest link length L \[m\] (the transverse impact does not depend on it).
pub const LENGTH: (f64, f64) = (1e-3, 1e3);

/// The link length in its range (the error names `--length`).
pub fn check_length(length: f64) -> Result<f64, Error> {
    if length.is_finite() && (LENGTH.0..=LENGTH.1).contains(&length) {
        Ok(length)
    } else {
        Err(Error::InvalidArgument {
            arg: "--length".into(),
            value: flexrig_contact::validate::display(length),
            allowed: "must lie in [1e-3, 1e3] m".into(),
        })
    }
}

/// The table and the files written.
#[derive(Debug, Clone, Serialize)]
pub struct EtaResult {
    /// One row per case and exponent.
    pub rows: Vec<EtaRow>,
    /// eta.csv.
    pub csv: PathBuf,
    /// eta.svg (the table as a figure).
    pub svg: PathBuf,
    /// eta_fig6.svg (the FE points on the Fig. 6 curves).
    pub fig6_svg: PathBuf,
    /// Both figures in every format asked for.
    pub figures: Vec<PathBuf>,
}

/// Computes the table of the cases of `grid` (the paper's: [`Fig6Grid::paper`]) for `settings`
/// and writes eta.csv, eta.svg and eta_fig6.svg (in the sizes
/// and formats of `figures`) into `out` (created if missing; nothing is written if a figure
/// cannot be drawn, or if `cancel` stops the computation: then the error is an interruption).
pub fn run(
    settings: &EtaSettings,
    grid: &Fig6Grid,
    out: &Path,
    figures: &crate::plots::FigureOptions,
    cancel: &CancelToken,
) -> Result<EtaResult, Error> {
    check_length(settings.length)?;
    crate::lumped::fig6::check_design(&settings.design)?;
    crate::lumped::fig6::check_grid(grid)?;
    settings.validate()?;
    figures.validate()?;
    let rows = eta_cases_until(&grid.cases(), settings, &cancel.flag())?;
    ensure_dir(out)?;
    let csv_path = out.join("eta.csv");
    let svg_path = out.join("eta.svg");
    let fig6_path = out.join("eta_fig6.svg");
    let width = figures.width_pt();
    let fig6_svg =
        fig6_with_fe_points(&rows, &settings.design, width).map_err(|message| Error::Plot {
            path: fig6_path.clone(),
            message,
        })?;
    let svg =
        crate::plots::eta_svg(&rows, &joint_text(&settings.joint), width).map_err(|message| {
            Error::Plot {
                path: svg_path.clone(),
                message,
            }
        })?;
    write_atomic(&csv_path, csv(&rows).as_bytes())?;
    let mut written = crate::plots::write_figure(out, "eta", &svg, figures)?;
    let fig6_written = crate::plots::write_figure(out, "eta_fig6", &fig6_svg, figures)?;
    let (svg_path, fig6_path) = (written[0].clone(), fig6_written[0].clone());
    written.extend(fig6_written);
    Ok(EtaResult {
        rows,
        csv: csv_path,
        svg: svg_path,
        fig6_svg: fig6_path,
        figures: written,
    })
}

/// The joint as titles say it: `held`, or `free-hub (J_R = … kg·m²)`.
pub fn joint_text(joint: &Joint) -> String {
    match *joint {
        Joint::Held => "held".to_string(),
        Joint::FreeHub { rotor_inertia } => format!("free-hub (J_R = {rotor_inertia} kg·m²)"),
    }
}

/// The contact as the table's title says it.
pub fn contact_text(damping: &DampingSpec) -> String {
    match *damping {
        DampingSpec::None {} => "elastic Hertz contact".into(),
        DampingSpec::HuntCrossley { restitution } => {
            format!("Hunt–Crossley contact, e = {restitution}")
        }
        DampingSpec::LankaraniNikravesh { restitution } => {
            format!("Lankarani–Nikravesh contact, e = {restitution}")
        }
        DampingSpec::AdamsImpact {
            c_max_n_s_per_m,
            depth_m,
        } => format!("ADAMS IMPACT contact, c_max = {c_max_n_s_per_m} N·s/m at {depth_m} m"),
    }
}

/// eta.csv: one row per case and exponent, with the window's columns when it was followed.
pub fn csv(rows: &[EtaRow]) -> String {
    let mut s = String::from(
        "m_h_kg,k_delta_n_per_m,m_e_kg,n,f_cj_n,f_cl_n,eta_fe,eta_lumped_2_3,f_cj_lumped_n,gamma_eff,gamma_eff_note,f_placed_n,placed_error,window_s,cj_contacts,cl_contacts,cj_horizon_s,cl_horizon_s,cj_overall_n,cl_overall_n,eta_overall",
    );
    s += &crate::shared::severity::pair_header();
    s.push('\n');
    for r in rows {
        let (gamma, note) = match r.gamma_eff {
            EffectiveGamma::Fits(g) => (format!("{g}"), ""),
            EffectiveGamma::AboveGammaOne => {
                (String::new(), "FE CL peak above the lumped CJ (gamma = 1)")
            }
            EffectiveGamma::BelowPayloadOnly => (
                String::new(),
                "FE CL peak below the lumped payload-only peak",
            ),
        };
        let window = match &r.window {
            Some(w) => {
                let (cj, cl) = (&w.cj, &w.cl);
                format!(
                    "{},{},{},{},{},{},{},{}",
                    w.window_s,
                    cj.converged_contacts,
                    cl.converged_contacts,
                    cj.horizon_s,
                    cl.horizon_s,
                    cj.overall_converged.peak_force_n,
                    cl.overall_converged.peak_force_n,
                    cl.overall_converged.peak_force_n / cj.overall_converged.peak_force_n
                )
            }
            None => ",,,,,,,".to_string(),
        };
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{}{}",
            r.case.m_h,
            r.case.k_delta,
            r.case.m_e,
            r.n,
            r.f_cj_n,
            r.f_cl_n,
            r.eta_fe,
            r.eta_lumped_2_3,
            r.f_cj_lumped_n,
            gamma,
            note,
            r.f_placed_n,
            r.f_placed_n / r.f_cl_n - 1.0,
            window,
            crate::shared::severity::pair_cells(r.severity.as_ref())
        );
    }
    s
}

/// The Fig. 6 curves of the rows' cases in `design` with each row's η_FE placed where its lumped
/// curve takes that value.
fn fig6_with_fe_points(
    rows: &[EtaRow],
    design: &flexrig_lumped::fig6::Fig6Design,
    width_pt: f64,
) -> Result<String, String> {
    let mut cases: Vec<flexrig_lumped::fig6::Fig6Case> = Vec::new();
    for r in rows {
        if !cases.contains(&r.case) {
            cases.push(r.case);
        }
    }
    let curves = flexrig_lumped::fig6::fig6_in(design, &cases, 41).map_err(|e| e.to_string())?;
    let points = rows
        .iter()
        .map(|r| {
            Ok(crate::plots::Fig6Point {
                case: r.case,
                n: r.n,
                eta_fe: r.eta_fe,
                gamma: flexrig_impact::eta::gamma_on_curve(design, &r.case, r.n, r.eta_fe)
                    .map_err(|e| e.to_string())?,
            })
        })
        .collect::<Result<Vec<_>, String>>()?;
    crate::plots::fig6_with_points_svg(&curves, &points, design, width_pt)
}
