//! η_FE of the Fig. 6 cases as the free hub's rotor inertia J_R grows from a freely pivoting
//! link to the held joint ([`flexrig_impact::rotor`]), as a CSV and a log-x curve figure.

use std::fmt::Write as _;
use std::path::PathBuf;

use flexrig_impact::eta::EtaSettings;
use flexrig_impact::map::LogRange;
use flexrig_impact::rotor::rotor_sweep_cases_until;
use flexrig_lumped::fig6::Fig6Grid;

use crate::CancelToken;
use serde::Serialize;

use crate::Error;
use crate::fe::eta::contact_text;
use crate::plots::{eta_rotor_svg, write_figure};
use crate::shared::output::{ensure_dir, write_atomic};

/// A point of the sweep (flexrig-impact's), for callers of this module.
pub use flexrig_impact::rotor::RotorPoint;

/// The sweep to run and where to write it.
#[derive(Debug, Clone, PartialEq)]
pub struct EtaRotorOptions {
    /// Directory for eta_rotor.csv and eta_rotor.svg (created if missing).
    pub out: PathBuf,
    /// Rotor over link inertia J_R/(m_r L²/3), log-spaced within [1e-9, 1e9]; the held joint
    /// is added as the limit.
    pub ratios: LogRange,
    /// Hertz exponents n, each in [1, 3].
    pub n: Vec<f64>,
    /// The impact's settings (CL method, damping, the design m_r, k_c, v0; the joint is the
    /// swept free hub).
    pub settings: EtaSettings,
    /// The cases: every combination of m_h, k_δ, m_e (the paper's eight by default).
    pub grid: Fig6Grid,
    /// Printed size and formats of the figure (`--size`, `--format`, `--dpi`).
    pub figures: crate::plots::FigureOptions,
}

/// The sweep and the files written.
#[derive(Debug, Clone, Serialize)]
pub struct EtaRotorResult {
    /// Every point, per case and exponent in ratio order, the held limit last.
    pub points: Vec<RotorPoint>,
    /// eta_rotor.csv.
    pub csv: PathBuf,
    /// The figure in the first format asked for (eta_rotor.svg by default).
    pub svg: PathBuf,
    /// The figure in every format asked for.
    pub figures: Vec<PathBuf>,
}

/// Most Hertz exponents of one rotor sweep (each adds a curve per Fig. 6 case).
pub const MAX_EXPONENTS: usize = 8;

/// Runs the sweep, draws the figure, then writes both files.
pub fn run(options: &EtaRotorOptions, cancel: &CancelToken) -> Result<EtaRotorResult, Error> {
    if options.n.is_empty() || options.n.len() > MAX_EXPONENTS {
        return Err(Error::InvalidArgument {
            arg: "--n".into(),
            value: format!("{} exponents", options.n.len()),
            allowed: format!("one to {MAX_EXPONENTS} exponents (one curve each per case)"),
        });
    }
    let settings = &options.settings;
    options.figures.validate()?;
    crate::fe::eta::check_length(settings.length)?;
    crate::lumped::fig6::check_design(&settings.design)?;
    crate::lumped::fig6::check_grid(&options.grid)?;
    let points = rotor_sweep_cases_until(
        &options.grid.cases(),
        &options.ratios,
        &options.n,
        settings,
        &cancel.flag(),
    )?;
    let subtitle = format!(
        "{}; m_r = {} kg, k_c = {} N/mⁿ, v_0 = {} m/s",
        contact_text(&settings.damping),
        settings.design.m_r,
        crate::plots::sci_label(settings.design.k_c),
        settings.design.v0
    );
    let csv_path = options.out.join("eta_rotor.csv");
    let svg = eta_rotor_svg(&points, &subtitle, options.figures.width_pt()).map_err(|message| {
        Error::Plot {
            path: options.out.join("eta_rotor.svg"),
            message,
        }
    })?;
    ensure_dir(&options.out)?;
    write_atomic(&csv_path, csv(&points).as_bytes())?;
    let figures = write_figure(&options.out, "eta_rotor", &svg, &options.figures)?;
    Ok(EtaRotorResult {
        points,
        csv: csv_path,
        svg: figures[0].clone(),
        figures,
    })
}

/// eta_rotor.csv: one row per point (`held` for the limit).
pub fn csv(points: &[RotorPoint]) -> String {
    let mut s = String::from("m_h_kg,k_delta_n_per_m,m_e_kg,n,inertia_ratio,f_cj_n,f_cl_n,eta_fe");
    s += &crate::shared::severity::pair_header();
    s.push('\n');
    for p in points {
        let ratio = p
            .inertia_ratio
            .map_or("held".to_string(), |r| r.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}{}",
            p.case.m_h,
            p.case.k_delta,
            p.case.m_e,
            p.n,
            ratio,
            p.f_cj_n,
            p.f_cl_n,
            p.eta_fe,
            crate::shared::severity::pair_cells(p.severity.as_ref())
        );
    }
    s
}
