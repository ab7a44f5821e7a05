//! Maps of η_FE, the lumped model's error, the effective γ and the placed model's error over
//! m_e/m_r × k_δ/k_c ([`flexrig_impact::map`]), one heat-map figure per head mass with the region
//! where the CL beats the CJ by more than 5 %, and a CSV of every point.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use flexrig_impact::eta::{EffectiveGamma, EtaRow, EtaSettings};
use flexrig_impact::map::eta_map_until;

use crate::CancelToken;
use serde::Serialize;

use crate::Error;
use crate::fe::eta::{contact_text, joint_text};
use crate::plots::{ColorScale, HeatMap, heatmaps_svg};
use crate::shared::output::{ensure_dir, write_atomic};

/// A map's spec and points (flexrig-impact's), for callers of this module.
pub use flexrig_impact::map::{LogRange, MapPoint, MapSpec};

/// Parses a log-spaced axis written as every range of the command line is (docs/cli.md,
/// "Ranges"): `FROM:TO:N:log`, or `FROM:TO` with `points` values. A linear `FROM:TO:N` is
/// refused (these axes are log-spaced); errors name `flag`.
pub fn parse_log_range(flag: &str, text: &str, points: usize) -> Result<LogRange, Error> {
    let bad = |why: &str| Error::InvalidArgument {
        arg: flag.into(),
        value: text.into(),
        allowed: format!(
            "{why}: write FROM:TO:N:log, or FROM:TO with N from --points (FROM and TO > 0, \
             FROM < TO; e.g. 1e-3:1e2:30:log)"
        ),
    };
    let parts: Vec<&str> = text.split(':').map(str::trim).collect();
    let number = |t: &str| {
        t.parse::<f64>()
            .map_err(|_| bad(&format!("{t} is not a number")))
    };
    let (from, to, points) = match parts.as_slice() {
        [from, to] => (number(from)?, number(to)?, points),
        [from, to, n, "log"] => (
            number(from)?,
            number(to)?,
            n.parse::<usize>()
                .map_err(|_| bad(&format!("{n} is not a whole number of points")))?,
        ),
        [_, _, _] => return Err(bad("this axis is log-spaced")),
        _ => return Err(bad("not a range")),
    };
    Ok(LogRange { from, to, points })
}

/// η_FE below this: the CL beats the CJ by more than 5 %.
pub const BEATS: f64 = 0.95;

/// The maps to compute (one per head mass) and where to write them.
#[derive(Debug, Clone, PartialEq)]
pub struct EtaMapOptions {
    /// Directory for eta_map.csv and one eta_map_mh<M>.svg per map (created if missing).
    pub out: PathBuf,
    /// One map per spec (head mass, exponent, the two log ranges).
    pub specs: Vec<MapSpec>,
    /// The impact's settings (joint, CL method, damping) shared by every point.
    pub settings: EtaSettings,
    /// Printed size and formats of the figures (`--size`, `--format`, `--dpi`).
    pub figures: crate::plots::FigureOptions,
}

/// One computed map.
#[derive(Debug, Clone)]
pub struct ComputedMap {
    /// Its spec.
    pub spec: MapSpec,
    /// Every point, row-major over the stiffness ratio then the mass ratio.
    pub points: Vec<MapPoint>,
    /// Wall-clock time it took \[s\].
    pub seconds: f64,
}

/// Summary numbers of one map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MapSummary {
    /// Head mass \[kg\].
    pub m_h_kg: f64,
    /// Points of the map.
    pub points: usize,
    /// Points whose impact failed.
    pub failed: usize,
    /// Points where the CL beats the CJ by more than 5 % (η_FE < [`BEATS`]).
    pub cl_beats_cj_by_5_percent: usize,
    /// Points where an effective γ in (0, 1] fits.
    pub gamma_eff_fits: usize,
    /// Largest |η(2/3)/η_FE − 1|.
    pub lumped_error_max: f64,
    /// Points with |η(2/3)/η_FE − 1| ≤ 5 %.
    pub lumped_within_5_percent: usize,
    /// Largest |f_placed/f_CL − 1|.
    pub placed_error_max: f64,
    /// Points with |f_placed/f_CL − 1| ≤ 5 %.
    pub placed_within_5_percent: usize,
    /// Wall-clock time \[s\].
    pub seconds: f64,
}

/// The maps, their summaries and the files written.
#[derive(Debug, Clone)]
pub struct EtaMapResult {
    /// Every map.
    pub maps: Vec<ComputedMap>,
    /// One summary per map.
    pub summaries: Vec<MapSummary>,
    /// eta_map.csv, then one figure per map.
    pub files: Vec<PathBuf>,
}

/// The joint and contact as the figures' titles say them.
pub fn settings_text(settings: &EtaSettings) -> String {
    format!(
        "{} joint, {}",
        joint_text(&settings.joint),
        contact_text(&settings.damping)
    )
}

/// Most maps of one call (one per head mass).
pub const MAX_MAPS: usize = 8;

/// Computes every map, renders everything, then writes the files (no partial output).
pub fn run(options: &EtaMapOptions, cancel: &CancelToken) -> Result<EtaMapResult, Error> {
    if options.specs.is_empty() || options.specs.len() > MAX_MAPS {
        return Err(Error::InvalidArgument {
            arg: "--m-h".into(),
            value: format!("{} head masses", options.specs.len()),
            allowed: format!("one to {MAX_MAPS} head masses (one map each)"),
        });
    }
    crate::fe::eta::check_length(options.settings.length)?;
    crate::lumped::fig6::check_design(&options.settings.design)?;
    options.settings.validate()?;
    options.figures.validate()?;
    let joint_text = settings_text(&options.settings);
    let mut maps = Vec::new();
    for spec in &options.specs {
        spec.validate()?;
        let start = Instant::now();
        let points = eta_map_until(spec, &options.settings, &cancel.flag())?;
        maps.push(ComputedMap {
            spec: *spec,
            points,
            seconds: start.elapsed().as_secs_f64(),
        });
    }
    let out = &options.out;
    let mut figures = Vec::new();
    for m in &maps {
        let stem = format!(
            "eta_map_mh{}",
            flexrig_contact::validate::display(m.spec.m_h)
        );
        let text = svg(
            m,
            &joint_text,
            &options.settings.design,
            options.figures.width_pt(),
        )
        .map_err(|message| Error::Plot {
            path: out.join(format!("{stem}.svg")),
            message,
        })?;
        figures.push((stem, text));
    }
    ensure_dir(out)?;
    let csv_path = out.join("eta_map.csv");
    write_atomic(&csv_path, csv(&maps).as_bytes())?;
    let mut files = vec![csv_path];
    for (stem, text) in &figures {
        files.extend(crate::plots::write_figure(
            out,
            stem,
            text,
            &options.figures,
        )?);
    }
    let summaries = maps.iter().map(summary).collect();
    Ok(EtaMapResult {
        maps,
        summaries,
        files,
    })
}

/// eta_map.csv: every point of every map (a failed point carries its error).
pub fn csv(maps: &[ComputedMap]) -> String {
    let mut s = String::from(
        "m_h_kg,n,mass_ratio,stiffness_ratio,m_e_kg,k_delta_n_per_m,f_cj_n,f_cl_n,eta_fe,eta_lumped_2_3,lumped_error,gamma_eff,gamma_eff_note,f_placed_n,placed_error,error",
    );
    s += &crate::shared::severity::pair_header();
    s.push('\n');
    for m in maps {
        for p in &m.points {
            let head = format!(
                "{},{},{},{}",
                m.spec.m_h, m.spec.n, p.mass_ratio, p.stiffness_ratio
            );
            match &p.row {
                Ok(r) => {
                    let (gamma, note) = match r.gamma_eff {
                        EffectiveGamma::Fits(g) => (format!("{g}"), ""),
                        EffectiveGamma::AboveGammaOne => (String::new(), "above gamma = 1"),
                        EffectiveGamma::BelowPayloadOnly => {
                            (String::new(), "below the payload alone")
                        }
                    };
                    let _ = writeln!(
                        s,
                        "{head},{},{},{},{},{},{},{},{gamma},{note},{},{},{}",
                        r.case.m_e,
                        r.case.k_delta,
                        r.f_cj_n,
                        r.f_cl_n,
                        r.eta_fe,
                        r.eta_lumped_2_3,
                        r.eta_lumped_2_3 / r.eta_fe - 1.0,
                        r.f_placed_n,
                        r.f_placed_n / r.f_cl_n - 1.0,
                        crate::shared::severity::pair_cells(r.severity.as_ref())
                    );
                }
                Err(e) => {
                    let _ = writeln!(
                        s,
                        "{head},,,,,,,,,,,,\"{}\"{}",
                        e.replace('"', "'"),
                        crate::shared::severity::pair_cells(None)
                    );
                }
            }
        }
    }
    s
}

/// The panels of one head mass at the printed width `width_pt` \[pt\]: η_FE, the lumped
/// model's error, the effective γ (only when some point has one; otherwise a line under the
/// title says why none fits) and the placed model's error.
pub fn svg(
    m: &ComputedMap,
    joint: &str,
    design: &flexrig_lumped::fig6::Fig6Design,
    width_pt: f64,
) -> Result<String, String> {
    let xs = m.spec.mass_ratio.values();
    let ys = m.spec.stiffness_ratio.values();
    let value = |f: &dyn Fn(&EtaRow) -> Option<f64>| -> Vec<Option<f64>> {
        m.points
            .iter()
            .map(|p| p.row.as_ref().ok().and_then(f))
            .collect()
    };
    let eta = value(&|r| Some(r.eta_fe));
    let lumped = value(&|r| Some(r.eta_lumped_2_3 / r.eta_fe - 1.0));
    let gamma = value(&|r| match r.gamma_eff {
        EffectiveGamma::Fits(g) => Some(g),
        _ => None,
    });
    let placed = value(&|r| Some(r.f_placed_n / r.f_cl_n - 1.0));
    let beats: Vec<bool> = eta.iter().map(|e| e.is_some_and(|e| e < BEATS)).collect();
    // both error maps on one scale, clamped at ±100 % so the region near 0 keeps its detail
    let (lumped_span, placed_span) = (1.0, 1.0);
    let mut maps = vec![
        HeatMap {
            title: "η_FE = f_max(CL)/f_max(CJ)",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &eta,
            scale: ColorScale::Sequential { lo: 0.0, hi: 1.0 },
            value_label: "η_FE",
            outline: Some((&beats, "CL beats CJ by > 5 % (η_FE < 0.95)")),
        },
        HeatMap {
            title: "lumped model's error η(2/3)/η_FE − 1",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &lumped,
            scale: ColorScale::Diverging {
                centre: 0.0,
                span: lumped_span,
            },
            value_label: "η(2/3)/η_FE − 1",
            outline: None,
        },
        HeatMap {
            title: "effective γ (blank: none in (0, 1] fits)",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &gamma,
            scale: ColorScale::Sequential { lo: 0.0, hi: 1.0 },
            value_label: "γ_eff",
            outline: None,
        },
        HeatMap {
            title: "placed model's error f_placed/f_CL − 1",
            x_label: "m_e/m_r",
            y_label: "k_δ/k_c",
            xs: &xs,
            ys: &ys,
            values: &placed,
            scale: ColorScale::Diverging {
                centre: 0.0,
                span: placed_span,
            },
            value_label: "f_placed/f_CL − 1",
            outline: None,
        },
    ];
    let mut title = vec![
        format!(
            "Free head m_h = {} kg on the CL (FE) and CJ links, n = {}",
            m.spec.m_h, m.spec.n
        ),
        format!(
            "{joint}; m_r = {} kg, k_c = {} N/mⁿ, v_0 = {} m/s",
            design.m_r,
            crate::plots::sci_label(design.k_c),
            design.v0
        ),
    ];
    if gamma.iter().all(Option::is_none) {
        maps.remove(2);
        title.push(gamma_note(m));
    }
    heatmaps_svg(&title, &maps, width_pt)
}

/// Why no point has an effective γ: how many lie above γ = 1 and below the payload alone.
fn gamma_note(m: &ComputedMap) -> String {
    let (mut above, mut below) = (0, 0);
    for p in &m.points {
        match p.row.as_ref().map(|r| r.gamma_eff) {
            Ok(EffectiveGamma::AboveGammaOne) => above += 1,
            Ok(EffectiveGamma::BelowPayloadOnly) => below += 1,
            _ => {}
        }
    }
    format!(
        "Effective γ: no γ in (0, 1] fits at any point ({above} need γ > 1, {below} fall below the payload alone)"
    )
}

/// Summary numbers of one map: points, failures, CL-beats-CJ count and the largest errors.
pub fn summary(m: &ComputedMap) -> MapSummary {
    let rows: Vec<_> = m
        .points
        .iter()
        .filter_map(|p| p.row.as_ref().ok())
        .collect();
    let beats = rows.iter().filter(|r| r.eta_fe < BEATS).count();
    let fits = rows
        .iter()
        .filter(|r| matches!(r.gamma_eff, EffectiveGamma::Fits(_)))
        .count();
    let worst =
        |f: &dyn Fn(&&EtaRow) -> f64| rows.iter().map(f).fold(0.0_f64, |a, b| a.max(b.abs()));
    let within = |f: &dyn Fn(&&EtaRow) -> f64, limit: f64| {
        rows.iter().filter(|r| f(r).abs() <= limit).count()
    };
    let lumped = |r: &&EtaRow| r.eta_lumped_2_3 / r.eta_fe - 1.0;
    let placed = |r: &&EtaRow| r.f_placed_n / r.f_cl_n - 1.0;
    MapSummary {
        m_h_kg: m.spec.m_h,
        points: m.points.len(),
        failed: m.points.len() - rows.len(),
        cl_beats_cj_by_5_percent: beats,
        gamma_eff_fits: fits,
        lumped_error_max: worst(&lumped),
        lumped_within_5_percent: within(&lumped, 0.05),
        placed_error_max: worst(&placed),
        placed_within_5_percent: within(&placed, 0.05),
        seconds: m.seconds,
    }
}
