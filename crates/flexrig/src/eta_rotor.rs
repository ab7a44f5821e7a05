//! η_FE of the Fig. 6 cases as the free hub's rotor inertia J_R grows from a freely pivoting
//! link to the held joint ([`flexrig_impact::rotor`]), as a CSV and a log-x curve figure.

use std::fmt::Write as _;
use std::path::PathBuf;

use flexrig_impact::eta::EtaSettings;
use flexrig_impact::map::LogRange;
use flexrig_impact::rotor::rotor_sweep_until;

use crate::CancelToken;
use serde::Serialize;

use crate::Error;
use crate::eta::contact_text;
use crate::output::{ensure_dir, write_atomic};
use crate::plots::{Curve, CurvePanel, log_x_curves_svg};

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
    /// The impact's settings (CL method, damping; the joint is the swept free hub).
    pub settings: EtaSettings,
}

/// The sweep and the files written.
#[derive(Debug, Clone, Serialize)]
pub struct EtaRotorResult {
    /// Every point, per case and exponent in ratio order, the held limit last.
    pub points: Vec<RotorPoint>,
    /// eta_rotor.csv.
    pub csv: PathBuf,
    /// eta_rotor.svg.
    pub svg: PathBuf,
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
    let points = rotor_sweep_until(&options.ratios, &options.n, settings, &cancel.flag())?;
    let title = format!(
        "η_FE from a freely pivoting link (J_R → 0) to the held joint (dashed), {} (m_r = 10 kg, k_c = 1e8, v0 = 2 m/s)",
        contact_text(&settings.damping)
    );
    let svg_path = options.out.join("eta_rotor.svg");
    let csv_path = options.out.join("eta_rotor.csv");
    let svg = log_x_curves_svg(
        &title,
        "rotor over link inertia J_R/(m_r L²/3)",
        "η_FE = f_CL/f_CJ",
        &panels(&points),
    )
    .map_err(|message| Error::Plot {
        path: svg_path.clone(),
        message,
    })?;
    ensure_dir(&options.out)?;
    write_atomic(&csv_path, csv(&points).as_bytes())?;
    write_atomic(&svg_path, svg.as_bytes())?;
    Ok(EtaRotorResult {
        points,
        csv: csv_path,
        svg: svg_path,
    })
}

/// eta_rotor.csv: one row per point (`held` for the limit).
pub fn csv(points: &[RotorPoint]) -> String {
    let mut s =
        String::from("m_h_kg,k_delta_n_per_m,m_e_kg,n,inertia_ratio,f_cj_n,f_cl_n,eta_fe\n");
    for p in points {
        let ratio = p
            .inertia_ratio
            .map_or("held".to_string(), |r| r.to_string());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{}",
            p.case.m_h, p.case.k_delta, p.case.m_e, p.n, ratio, p.f_cj_n, p.f_cl_n, p.eta_fe
        );
    }
    s
}

/// One panel per head mass, one curve per (k_δ, m_e, n), the held η as its limit.
fn panels(points: &[RotorPoint]) -> Vec<CurvePanel> {
    let mut panels: Vec<CurvePanel> = Vec::new();
    for p in points {
        let title = format!("m_h = {} kg", p.case.m_h);
        if panels.last().is_none_or(|panel| panel.title != title) {
            panels.push(CurvePanel {
                title,
                curves: Vec::new(),
            });
        }
        let panel = panels.last_mut().expect("pushed above");
        let label = format!(
            "k_δ = {:.0e} N/m, m_e = {} kg, n = {}",
            p.case.k_delta, p.case.m_e, p.n
        );
        if panel.curves.last().is_none_or(|c| c.label != label) {
            panel.curves.push(Curve {
                label,
                points: Vec::new(),
                limit: None,
            });
        }
        let curve = panel.curves.last_mut().expect("pushed above");
        match p.inertia_ratio {
            Some(r) => curve.points.push((r, p.eta_fe)),
            None => curve.limit = Some(p.eta_fe),
        }
    }
    panels
}
