//! The paper's Fig. 6 η(γ) study (§V, Eq. 15): η(γ) = f_max(γ)/f_max(1) for the eight design
//! cases, n = 1 and n = 2, written as a CSV and an SVG.

use std::fmt::Write as _;
use std::path::PathBuf;

use flexrig_lumped::fig6::{self, EtaCurve};

use crate::Error;
use crate::output::{ensure_dir, write_atomic};
use crate::plots::{FigureOptions, fig6_svg, write_figure};

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
}

/// Most γ samples of a curve (16 curves of them are kept in memory and written).
pub const MAX_POINTS: usize = 1_000_000;

/// Computes the curves and writes fig6.csv (`points` samples) and fig6.svg (drawn from at
/// least [`PLOT_POINTS`] samples, so that its curves are smooth).
pub fn run(options: &Fig6Options) -> Result<Fig6Result, Error> {
    if !(2..=MAX_POINTS).contains(&options.points) {
        return Err(Error::InvalidArgument {
            arg: "--points".into(),
            value: options.points.to_string(),
            allowed: format!("must be from 2 to {MAX_POINTS}"),
        });
    }
    options.figures.validate()?;
    let curves = fig6::fig6(options.points)?;
    ensure_dir(&options.out)?;
    let csv_path = options.out.join("fig6.csv");
    write_atomic(&csv_path, csv(&curves).as_bytes())?;
    let dense;
    let plotted = if options.points >= PLOT_POINTS {
        &curves
    } else {
        dense = fig6::fig6(PLOT_POINTS)?;
        &dense
    };
    let svg = fig6_svg(plotted, options.figures.width_pt()).map_err(|message| Error::Plot {
        path: options.out.join("fig6.svg"),
        message,
    })?;
    let figures = write_figure(&options.out, "fig6", &svg, &options.figures)?;
    Ok(Fig6Result {
        curves,
        csv: csv_path,
        svg: figures[0].clone(),
        figures,
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
