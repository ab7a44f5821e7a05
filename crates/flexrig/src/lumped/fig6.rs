//! The paper's Fig. 6 η(γ) study (§V, Eq. 15): η(γ) = f_max(γ)/f_max(1) for the eight design
//! cases, n = 1 and n = 2, written as a CSV and an SVG.

use std::fmt::Write as _;
use std::path::PathBuf;

use flexrig_lumped::fig6::{self, EtaCurve};

/// The design held fixed and the varied values of a Fig. 6 study (flexrig-lumped's), for
/// callers of this module.
pub use flexrig_lumped::fig6::{Fig6Case, Fig6Design, Fig6Grid};

use crate::Error;
use crate::plots::{FigureOptions, fig6_svg, write_figure};
use crate::shared::output::{ensure_dir, write_atomic};

/// Default number of γ samples over [0.5, 1].
pub const DEFAULT_POINTS: usize = 101;
/// Fewest γ samples the figure is drawn from (the CSV keeps `--points`).
pub const PLOT_POINTS: usize = 201;

/// What the study computes and where it writes.
#[derive(Debug, Clone, PartialEq)]
pub struct Fig6Options {
    /// Directory for fig6.csv and fig6.svg (created if missing; `--out`).
    pub out: PathBuf,
    /// Number of γ samples over [0.5, 1], at least 2 (`--points`).
    pub points: usize,
    /// Printed size and formats of the figure (`--size`, `--format`, `--dpi`).
    pub figures: FigureOptions,
    /// The design held fixed: m_r, k_c, v0 (`--m-r`, `--k-c`, `--v0`; the paper's by default).
    pub design: Fig6Design,
    /// The cases: every combination of m_h, k_δ, m_e (`--m-h`, `--k-delta`, `--m-e`; the
    /// paper's eight by default).
    pub grid: Fig6Grid,
}

/// Allowed link mass m_r \[kg\] (`--m-r`).
pub const M_R_RANGE: (f64, f64) = (1e-3, 1e4);
/// Allowed contact stiffness k_c [N/mⁿ] (`--k-c`).
pub const K_C_RANGE: (f64, f64) = (1.0, 1e13);
/// Allowed approach speed v0 [m/s] (`--v0`).
pub const V0_RANGE: (f64, f64) = (1e-3, 100.0);
/// Allowed human mass m_h \[kg\] (`--m-h`).
pub const M_H_RANGE: (f64, f64) = (1e-3, 1e6);
/// Allowed link lateral stiffness k_δ [N/m] (`--k-delta`).
pub const K_DELTA_RANGE: (f64, f64) = (1e-3, 1e13);
/// Allowed payload m_e \[kg\] (`--m-e`).
pub const M_E_RANGE: (f64, f64) = (1e-6, 1e4);
/// Most values of each varied parameter (`--m-h`, `--k-delta`, `--m-e`).
pub const MAX_VALUES: usize = 4;

/// Checks the design's ranges; the error names the flag (`--m-r`, `--k-c`, `--v0`), the value
/// and the range.
pub fn check_design(design: &Fig6Design) -> Result<(), Error> {
    use crate::shared::output::range_arg;
    range_arg("--m-r", design.m_r, M_R_RANGE.0, M_R_RANGE.1, "kg")?;
    range_arg("--k-c", design.k_c, K_C_RANGE.0, K_C_RANGE.1, "N/mⁿ")?;
    range_arg("--v0", design.v0, V0_RANGE.0, V0_RANGE.1, "m/s")?;
    Ok(())
}

/// Checks the varied values (one to [`MAX_VALUES`] of each, in range, none twice); the error
/// names the flag (`--m-h`, `--k-delta`, `--m-e`).
pub fn check_grid(grid: &Fig6Grid) -> Result<(), Error> {
    for (flag, values, (lo, hi), unit) in [
        ("--m-h", &grid.m_h, M_H_RANGE, "kg"),
        ("--k-delta", &grid.k_delta, K_DELTA_RANGE, "N/m"),
        ("--m-e", &grid.m_e, M_E_RANGE, "kg"),
    ] {
        if values.is_empty() || values.len() > MAX_VALUES {
            return Err(Error::InvalidArgument {
                arg: flag.into(),
                value: format!("{} values", values.len()),
                allowed: format!("give one to {MAX_VALUES} values, comma-separated"),
            });
        }
        for (i, &v) in values.iter().enumerate() {
            crate::shared::output::range_arg(flag, v, lo, hi, unit)?;
            if values[..i].contains(&v) {
                return Err(Error::InvalidArgument {
                    arg: flag.into(),
                    value: crate::shared::output::display_number(v),
                    allowed: "is given twice; give each value once".into(),
                });
            }
        }
    }
    Ok(())
}

/// The curves and the files written.
#[derive(Debug, Clone)]
pub struct Fig6Result {
    /// One curve per case and exponent (n = 1, then n = 2, per case).
    pub curves: Vec<EtaCurve>,
    /// fig6.csv.
    pub csv: PathBuf,
    /// The figure in the first format asked for (fig6.svg by default).
    pub svg: PathBuf,
    /// The figure in every format asked for.
    pub figures: Vec<PathBuf>,
    /// The design the curves were computed in.
    pub design: Fig6Design,
}

/// Most γ samples of a curve (16 curves of them are kept in memory and written).
pub const MAX_POINTS: usize = 1_000_000;

/// The curves of the cases of `grid` (n = 1, then n = 2, per case) in `design`, with `points`
/// samples of γ over [0.5, 1]: the inputs checked first (errors name the flag: `--points`,
/// `--m-r`, `--k-c`, `--v0`, `--m-h`, `--k-delta`, `--m-e`).
pub fn curves(points: usize, design: &Fig6Design, grid: &Fig6Grid) -> Result<Vec<EtaCurve>, Error> {
    if !(2..=MAX_POINTS).contains(&points) {
        return Err(Error::InvalidArgument {
            arg: "--points".into(),
            value: points.to_string(),
            allowed: format!("must be from 2 to {MAX_POINTS}"),
        });
    }
    check_design(design)?;
    check_grid(grid)?;
    Ok(fig6::fig6_in(design, &grid.cases(), points)?)
}

/// Computes the curves ([`curves`]) and writes fig6.csv (`points` samples) and fig6.svg (drawn
/// from at least [`PLOT_POINTS`] samples, so that its curves are smooth).
pub fn run(options: &Fig6Options) -> Result<Fig6Result, Error> {
    options.figures.validate()?;
    let curves = curves(options.points, &options.design, &options.grid)?;
    let cases = options.grid.cases();
    ensure_dir(&options.out)?;
    let csv_path = options.out.join("fig6.csv");
    write_atomic(&csv_path, csv(&curves).as_bytes())?;
    let dense;
    let plotted = if options.points >= PLOT_POINTS {
        &curves
    } else {
        dense = fig6::fig6_in(&options.design, &cases, PLOT_POINTS)?;
        &dense
    };
    let svg =
        fig6_svg(plotted, &options.design, options.figures.width_pt()).map_err(|message| {
            Error::Plot {
                path: options.out.join("fig6.svg"),
                message,
            }
        })?;
    let figures = write_figure(&options.out, "fig6", &svg, &options.figures)?;
    Ok(Fig6Result {
        curves,
        csv: csv_path,
        svg: figures[0].clone(),
        figures,
        design: options.design,
    })
}

/// One row per (case, n, γ): `m_h_kg,k_delta_n_per_m,m_e_kg,n,gamma,eta`.
pub fn csv(curves: &[EtaCurve]) -> String {
    let mut text = String::from("m_h_kg,k_delta_n_per_m,m_e_kg,n,gamma,eta\n");
    for c in curves {
        for (g, e) in c.gamma.iter().zip(&c.eta) {
            let _ = writeln!(
                text,
                "{},{:e},{},{},{:.17},{:.17}",
                c.case.m_h, c.case.k_delta, c.case.m_e, c.n, g, e
            );
        }
    }
    text
}
