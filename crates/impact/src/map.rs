//! Maps beyond the paper (issue 14): η_FE, the lumped η(2/3), the effective γ and the placed
//! model over m_e/m_r × k_δ/k_c for a head mass and an exponent, every point a Fig. 6-style case
//! (m_r = 10 kg, k_c = 1e8, v0 = 2 m/s) run in parallel by [`crate::eta::eta_case`].

use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_lumped::fig6::{Fig6Case, Fig6Design};
use rayon::prelude::*;
use serde::Serialize;

use crate::ImpactError;
use crate::eta::{
    EtaRow, EtaSettings, case_setup, eta_case_until, validate_most_restrictive_first,
};

/// A log-spaced range of a ratio.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LogRange {
    /// First value (> 0).
    pub from: f64,
    /// Last value (> `from`).
    pub to: f64,
    /// Points, ≥ 2.
    pub points: usize,
}

impl LogRange {
    /// The values, log-spaced from `from` to `to`.
    pub fn values(&self) -> Vec<f64> {
        let (a, b) = (self.from.ln(), self.to.ln());
        (0..self.points)
            .map(|i| (a + (b - a) * i as f64 / (self.points - 1) as f64).exp())
            .collect()
    }

    pub(crate) fn validate(&self, field: &str, lo: f64, hi: f64) -> Result<(), ImpactError> {
        let ok = |x: f64| x.is_finite() && (lo..=hi).contains(&x);
        if !(ok(self.from) && ok(self.to) && self.from < self.to) {
            return Err(ImpactError::invalid(
                field,
                format!("{}:{}", self.from, self.to),
                format!("FROM:TO with {lo:e} ≤ FROM < TO ≤ {hi:e}"),
            ));
        }
        if !(2..=200).contains(&self.points) {
            return Err(ImpactError::invalid(
                format!("{field} points"),
                self.points,
                "must lie in [2, 200]",
            ));
        }
        Ok(())
    }
}

/// One map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MapSpec {
    /// Head mass m_h \[kg\].
    pub m_h: f64,
    /// Hertz exponent n.
    pub n: f64,
    /// m_e/m_r along x.
    pub mass_ratio: LogRange,
    /// k_δ/k_c along y.
    pub stiffness_ratio: LogRange,
}

impl MapSpec {
    /// Checks the ranges; the error names the field.
    pub fn validate(&self) -> Result<(), ImpactError> {
        if !(self.m_h.is_finite() && self.m_h > 0.0 && self.m_h <= 1e9) {
            return Err(ImpactError::invalid(
                "m_h",
                self.m_h,
                "must lie in (0, 1e9] kg",
            ));
        }
        if !(self.n.is_finite() && (1.0..=3.0).contains(&self.n)) {
            return Err(ImpactError::invalid("n", self.n, "must lie in [1, 3]"));
        }
        // m_e ≤ 1e6 kg, k_δ in [1e-3, 1e12] N/m (the link's limits)
        self.mass_ratio.validate("mass_ratio", 1e-6, 1e5)?;
        self.stiffness_ratio
            .validate("stiffness_ratio", 1e-11, 1e4)?;
        Ok(())
    }
}

/// One point of a map: its ratios and its row, or why it failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapPoint {
    /// m_e/m_r.
    pub mass_ratio: f64,
    /// k_δ/k_c.
    pub stiffness_ratio: f64,
    /// The η row, or the error's text.
    pub row: Result<EtaRow, String>,
}

/// The map, row-major over (stiffness ratio, mass ratio): point `iy * nx + ix`.
pub fn eta_map(spec: &MapSpec, settings: &EtaSettings) -> Result<Vec<MapPoint>, ImpactError> {
    eta_map_until(spec, settings, &AtomicBool::new(false))
}

/// The Fig. 6 case at mass ratio m_e/m_r = `x` and stiffness ratio k_δ/k_c = `y` of `design`.
fn map_case(spec: &MapSpec, design: &Fig6Design, x: f64, y: f64) -> Fig6Case {
    Fig6Case {
        m_h: spec.m_h,
        k_delta: y * design.k_c,
        m_e: x * design.m_r,
    }
}

/// [`eta_map`], stopping with [`ImpactError::Interrupted`] once `stop` is set (checked before
/// each point).
pub fn eta_map_until(
    spec: &MapSpec,
    settings: &EtaSettings,
    stop: &AtomicBool,
) -> Result<Vec<MapPoint>, ImpactError> {
    spec.validate()?;
    settings.validate()?;
    let xs = spec.mass_ratio.values();
    let ys = spec.stiffness_ratio.values();
    let grid: Vec<(f64, f64)> = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
        .collect();
    // a set-up a point would refuse (e.g. a contact damped far past critical at the lightest
    // payload) is refused before any point runs
    validate_most_restrictive_first(
        grid.iter()
            .map(|&(x, y)| case_setup(&map_case(spec, &settings.design, x, y), spec.n, settings)),
    )?;
    let points: Vec<Option<MapPoint>> = grid
        .par_iter()
        .map(|&(x, y)| {
            if stop.load(Ordering::Relaxed) {
                return None;
            }
            let case = map_case(spec, &settings.design, x, y);
            Some(MapPoint {
                mass_ratio: x,
                stiffness_ratio: y,
                row: eta_case_until(&case, spec.n, settings, stop).map_err(|e| e.to_string()),
            })
        })
        .collect();
    points
        .into_iter()
        .collect::<Option<Vec<_>>>()
        .ok_or(ImpactError::Interrupted)
}
