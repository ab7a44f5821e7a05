//! Safe-speed maps: the permissible speed of the compliant-joint (CJ) and the compliant-link
//! (CL) design of one robot link near one body region (ISO/TS 15066:2016, power and force
//! limiting) over two design parameters, with the ratio CL/CJ, as data, CSV and a heat-map
//! figure.
//!
//! Every cell is one design: link mass m_r, payload m_e, lateral tip stiffness k_δ = 3EI/L³
//! (Eq. 1–3) and the skin's contact law f = k_c δ^n (Eq. 4). Two of them vary along the axes
//! ([`MapParameter`]); the others are fixed. The methods:
//!
//! - **standard** (method a): the standard's formula v = F_max/√(μK) (Annex A, Eq. A.1–A.6) with
//!   m_R = m_eff; the CJ and CL differ only by m_eff.
//! - **energy** (method b, lumped): the paper's energy balance ½μv² = U(f_max) (Eq. 13 with the
//!   Hertz law and k_δ in series, Eq. 4–9), m_eff = m_e + γ m_r/3 (Eq. 5) with γ = 1 for the CJ
//!   and γ = 2/3 for the CL. Every cell is [`crate::safety::point::safety`] at the cell's parameters,
//!   so it equals the single-point answer bit for bit.
//! - **simulation** (method c): the smallest speed at which the largest peak force over every
//!   contact of the finite-element impact reaches the limit (and the force at which the mean
//!   pressure reaches its limit), by the scan from below on the grid q^k m/s from the energy floor
//!   and the Illinois refinement on ln v
//!   ([`crate::safety::simulation::smallest_speed_on_grid`], the single-point answer's own path,
//!   so every cell equals it bit for bit): the CJ as a rigid link on
//!   its torsion spring k_θr = k_δL² (DOP853, [`flexrig_impact::cj`]), the CL as the
//!   Euler–Bernoulli beam on a mesh graded towards the tip, by its modes and the exact modal
//!   integrator ([`flexrig_impact::cl_modal`]). So CJ and CL differ by the link's real
//!   compliance, not by a lumped γ. The joint is held (driven at constant speed, the body region
//!   arriving at v: the test bed's operator striking the robot) or a free hub with the motor's
//!   rotor inertia behind it. The CL's modes are solved once per cell at the lumped CL speed and
//!   reused along the scan (the free hub's initial modal rates scale with v exactly).
//!   The modal CL holds for the linear beam (small deflections, no end stop), elastic contact.
//!
//! Speeds are in m/s, masses in kg, stiffnesses in N/m (k_c in N/m^n), EI in N·m².

use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use flexrig_contact::{Hertz, Materials};
use flexrig_impact::ImpactError;
use flexrig_safety::LinkStiffness;
use flexrig_safety::{BodyModel, ContactAreaModel, ContactKind, EnergyContact, GoverningLimit};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::safety::point::{
    ContactLaw, MethodResult, RobotEffectiveMass, SafetyInput, SafetyMethod, Speed, Unbounded,
    safety,
};
pub use crate::safety::simulation::{
    CLAMPED_HUMAN_MASS, FE_RIGID_LINK_STIFFNESS, FeImpact, FeLink, FeRuns, GAMMA_CJ, GAMMA_CL,
    MapJoint, RootStep, SimulationSettings, speed_at_ratio,
};
use crate::safety::simulation::{LimitSearch, bad, display, fe_search};
use crate::{CancelToken, Error};

/// Most points along one axis.
pub const MAX_AXIS_POINTS: usize = 200;
/// A design parameter along an axis of the map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MapParameter {
    /// Payload (end mass) m_e \[kg\] ≥ 0.
    Payload,
    /// Link mass m_r \[kg\] > 0.
    LinkMass,
    /// Lateral tip stiffness k_δ \[N/m\] > 0 (Eq. 1–3).
    LinkStiffness,
    /// Bending stiffness EI \[N·m²\] > 0: k_δ = 3EI/L³ with the link length L.
    BendingStiffness,
    /// Contact stiffness k_c \[N/m^n\] > 0 (Eq. 4), the exponent n kept.
    ContactStiffness,
    /// The body region (a category: the axis names the regions of the body model, each with
    /// its own limits, Table A.3's K and m_H, and its most sensitive area).
    BodyRegion,
}

impl MapParameter {
    /// Every parameter.
    pub const ALL: [MapParameter; 6] = [
        MapParameter::Payload,
        MapParameter::LinkMass,
        MapParameter::LinkStiffness,
        MapParameter::BendingStiffness,
        MapParameter::ContactStiffness,
        MapParameter::BodyRegion,
    ];

    /// The name on the command line (`m-e`, `m-r`, `k-delta`, `ei`, `k-c`).
    pub fn flag_name(self) -> &'static str {
        match self {
            MapParameter::Payload => "m-e",
            MapParameter::LinkMass => "m-r",
            MapParameter::LinkStiffness => "k-delta",
            MapParameter::BendingStiffness => "ei",
            MapParameter::ContactStiffness => "k-c",
            MapParameter::BodyRegion => "region",
        }
    }

    /// Parses a command-line name (`m-e`/`m_e`/`payload`, `m-r`/`m_r`, `k-delta`/`k_delta`, `ei`,
    /// `k-c`/`k_c`).
    pub fn parse(text: &str) -> Option<MapParameter> {
        Some(match text.trim().replace('_', "-").as_str() {
            "m-e" | "payload" => MapParameter::Payload,
            "m-r" | "link-mass" => MapParameter::LinkMass,
            "k-delta" | "link-stiffness" => MapParameter::LinkStiffness,
            "ei" | "EI" => MapParameter::BendingStiffness,
            "k-c" | "contact-stiffness" => MapParameter::ContactStiffness,
            "region" | "body-region" => MapParameter::BodyRegion,
            _ => return None,
        })
    }

    /// The axis label with the unit, as the figure prints it.
    pub fn label(self) -> &'static str {
        match self {
            MapParameter::Payload => "payload m_e [kg]",
            MapParameter::LinkMass => "link mass m_r [kg]",
            MapParameter::LinkStiffness => "link stiffness k_δ [N/m]",
            MapParameter::BendingStiffness => "bending stiffness EI [N·m²]",
            MapParameter::ContactStiffness => "contact stiffness k_c [N/mⁿ]",
            MapParameter::BodyRegion => "body region",
        }
    }

    /// The CSV column of the axis (name and unit).
    pub fn column(self) -> &'static str {
        match self {
            MapParameter::Payload => "m_e_kg",
            MapParameter::LinkMass => "m_r_kg",
            MapParameter::LinkStiffness => "k_delta_n_per_m",
            MapParameter::BendingStiffness => "ei_n_m2",
            MapParameter::ContactStiffness => "k_c_n_per_m_n",
            MapParameter::BodyRegion => "body_region",
        }
    }

    /// Checks one value of the parameter; the error names `flag`.
    fn check(self, flag: &str, v: f64) -> Result<(), Error> {
        let ok = match self {
            MapParameter::Payload => v.is_finite() && (0.0..=1e6).contains(&v),
            MapParameter::LinkMass => v.is_finite() && (1e-6..=1e6).contains(&v),
            MapParameter::LinkStiffness => v.is_finite() && (1e-3..=1e12).contains(&v),
            MapParameter::BendingStiffness | MapParameter::ContactStiffness => {
                v.is_finite() && v > 0.0 && v <= 1e20
            }
            // the position along a region axis, 1, 2, …
            MapParameter::BodyRegion => v >= 1.0 && v.fract() == 0.0,
        };
        if ok {
            Ok(())
        } else {
            let allowed = match self {
                MapParameter::Payload => "a payload in [0, 1e6] kg",
                MapParameter::LinkMass => "a link mass in [1e-6, 1e6] kg",
                MapParameter::LinkStiffness => "a link stiffness in [1e-3, 1e12] N/m",
                MapParameter::BendingStiffness => "a bending stiffness in (0, 1e20] N·m²",
                MapParameter::ContactStiffness => "a contact stiffness in (0, 1e20] N/mⁿ",
                MapParameter::BodyRegion => "a position 1, 2, … along the region axis",
            };
            Err(bad(flag, display(v), allowed))
        }
    }
}

/// One axis: a parameter and its values (ascending, > 0 except a payload of 0 on a linear
/// axis, which the figure cannot draw on its log axis). A body-region axis has the region keys
/// in `names` and their positions 1, 2, … as its values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapAxis {
    /// The parameter.
    pub parameter: MapParameter,
    /// Its values, strictly ascending.
    pub values: Vec<f64>,
    /// The body regions of a region axis (keys of the body model, or `all`), in order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub names: Vec<String>,
}

impl MapAxis {
    /// A body-region axis over `names` (region keys of the body model; `all` for every region).
    pub fn regions(names: &[&str]) -> MapAxis {
        MapAxis {
            parameter: MapParameter::BodyRegion,
            values: (1..=names.len()).map(|k| k as f64).collect(),
            names: names.iter().map(|n| n.to_string()).collect(),
        }
    }

    /// The region key at position `v` of a region axis.
    fn region_at(&self, v: f64) -> Option<&str> {
        (self.parameter == MapParameter::BodyRegion)
            .then(|| {
                self.names
                    .get((v as usize).wrapping_sub(1))
                    .map(String::as_str)
            })
            .flatten()
    }

    /// The axis with `all` expanded to every region of `model` and each name checked (the
    /// error names `flag` and lists the keys); other axes unchanged.
    fn resolved(&self, flag: &str, model: &BodyModel) -> Result<MapAxis, Error> {
        if self.parameter != MapParameter::BodyRegion {
            return Ok(self.clone());
        }
        let keys: Vec<&str> = if self.names.len() == 1 && self.names[0] == "all" {
            model.regions().iter().map(|r| r.key()).collect()
        } else {
            self.names
                .iter()
                .map(|n| {
                    model
                        .region(n)
                        .map(|r| r.key())
                        .map_err(|e| bad(flag, n, &e.to_string()))
                })
                .collect::<Result<_, _>>()?
        };
        // a region named twice (by its key and its name, or in another case) would be two
        // columns of one region
        if let Some((i, key)) = keys
            .iter()
            .enumerate()
            .find(|(i, k)| keys[..*i].contains(k))
        {
            return Err(bad(
                flag,
                self.names.join(","),
                &format!(
                    "each body region once: item {} names {key} again (a region is found by its \
                     key or its name, ignoring case)",
                    i + 1
                ),
            ));
        }
        let axis = MapAxis::regions(&keys);
        axis.validate(flag)?;
        Ok(axis)
    }
}

/// Parses `PARAM=FROM:TO:N[:log]` (both ends included, the sweep's range syntax) or
/// `PARAM=V1,V2,…` for the flag `flag`.
pub fn parse_axis(flag: &str, text: &str) -> Result<MapAxis, Error> {
    let names = MapParameter::ALL
        .iter()
        .map(|p| p.flag_name())
        .collect::<Vec<_>>()
        .join(", ");
    let syntax = format!(
        "PARAM=FROM:TO:N[:log] (both ends included, e.g. k-delta=10:1e7:30:log) or \
         PARAM=V1,V2,… with PARAM one of {names}"
    );
    let (name, spec) = text
        .split_once('=')
        .ok_or_else(|| bad(flag, text, &syntax))?;
    let parameter = MapParameter::parse(name).ok_or_else(|| {
        bad(
            flag,
            text,
            &format!("the parameter must be one of {names} (then =RANGE)"),
        )
    })?;
    if parameter == MapParameter::BodyRegion {
        let names: Vec<&str> = spec.split(',').map(str::trim).collect();
        if names.iter().any(|n| n.is_empty()) {
            return Err(bad(
                flag,
                text,
                "region=all or region=KEY1,KEY2,… with keys of the body model (chest, …)",
            ));
        }
        return Ok(MapAxis::regions(&names));
    }
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    let values: Vec<f64> = if spec.contains(':') {
        let parts: Vec<&str> = spec.split(':').collect();
        if !(parts.len() == 3 || (parts.len() == 4 && parts[3].trim() == "log")) {
            return Err(bad(flag, text, &syntax));
        }
        let (Some(start), Some(stop)) = (number(parts[0]), number(parts[1])) else {
            return Err(bad(flag, text, &syntax));
        };
        let count: usize = parts[2].trim().parse().map_err(|_| {
            bad(
                flag,
                text,
                "FROM:TO:N needs a whole number of points, e.g. 10:1e7:30:log",
            )
        })?;
        if !(2..=MAX_AXIS_POINTS).contains(&count) {
            return Err(bad(
                flag,
                text,
                &format!("the count must lie in [2, {MAX_AXIS_POINTS}]"),
            ));
        }
        let log = parts.len() == 4;
        if log && !(start > 0.0 && stop > 0.0) {
            return Err(bad(flag, text, "a log range needs START > 0 and STOP > 0"));
        }
        (0..count)
            .map(|i| {
                // land exactly on both ends
                if i + 1 == count {
                    return stop;
                }
                if i == 0 {
                    return start;
                }
                let s = i as f64 / (count - 1) as f64;
                if log {
                    (start.ln() + s * (stop.ln() - start.ln())).exp()
                } else {
                    start + s * (stop - start)
                }
            })
            .collect()
    } else {
        spec.split(',')
            .map(|s| number(s).ok_or_else(|| bad(flag, text, &syntax)))
            .collect::<Result<_, _>>()?
    };
    let axis = MapAxis {
        parameter,
        values,
        names: Vec::new(),
    };
    axis.validate(flag)?;
    Ok(axis)
}

impl MapAxis {
    /// Checks the values (count, order, each value's range); the error names `flag`.
    pub fn validate(&self, flag: &str) -> Result<(), Error> {
        if self.parameter == MapParameter::BodyRegion {
            if self.names.len() != self.values.len() {
                return Err(bad(
                    flag,
                    format!("{} names, {} values", self.names.len(), self.values.len()),
                    "a region axis has one name per value",
                ));
            }
            if self.names.len() == 1 && self.names[0] == "all" {
                return Ok(());
            }
        } else if !self.names.is_empty() {
            return Err(bad(
                flag,
                self.names.join(","),
                "names belong to a region axis only",
            ));
        }
        if !(2..=MAX_AXIS_POINTS).contains(&self.values.len()) {
            return Err(bad(
                flag,
                format!("{} values", self.values.len()),
                &format!("an axis has 2 to {MAX_AXIS_POINTS} values"),
            ));
        }
        for v in &self.values {
            self.parameter.check(flag, *v)?;
        }
        if self.values.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(bad(
                flag,
                self.values
                    .iter()
                    .map(|v| display(*v))
                    .collect::<Vec<_>>()
                    .join(","),
                "the values must increase strictly (START < STOP)",
            ));
        }
        if self.values[0] <= 0.0 {
            return Err(bad(
                flag,
                display(self.values[0]),
                "values > 0: the map's axes are logarithmic (use e.g. m-e=0.01:5:30:log)",
            ));
        }
        Ok(())
    }
}

/// The method of a map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MapMethod {
    /// The standard's formula (Annex A, Eq. A.1–A.6), m_R = m_eff.
    Standard,
    /// The lumped energy method (Eq. 13 generalised).
    Energy,
    /// The finite-element impact (CJ by DOP853, CL by its modes) and a root search on v.
    Simulation,
}

/// One safe-speed map question, SI units.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SafetyMapInput {
    /// Body region key (`--region`).
    pub region: String,
    /// Specific area for the pressure limit (absent: the region's most sensitive area).
    #[serde(default)]
    pub area: Option<String>,
    /// Transient or quasi-static contact.
    pub contact: ContactKind,
    /// Link mass m_r \[kg\] (unless an axis).
    #[serde(default)]
    pub m_r: Option<f64>,
    /// Payload m_e \[kg\] (unless an axis).
    #[serde(default)]
    pub m_e: Option<f64>,
    /// Link stiffness k_δ \[N/m\] (unless an axis; absent: a rigid link, lumped methods only).
    #[serde(default)]
    pub k_delta: Option<f64>,
    /// The skin's contact law.
    pub law: ContactLaw,
    /// The contact-area model for pressure (absent: the material's dome with a material, else
    /// force only).
    #[serde(default)]
    pub area_model: Option<ContactAreaModel>,
    /// The x axis.
    pub x: MapAxis,
    /// The y axis.
    pub y: MapAxis,
    /// The method.
    pub method: MapMethod,
    /// The simulation method's joint, length and tolerances (L also converts an EI axis).
    pub simulation: SimulationSettings,
    /// A speed to outline on the figure: the cells that permit it \[m/s\].
    #[serde(default)]
    pub speed: Option<f64>,
}

/// The speed at which one limit is reached, as a cell knows it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum LimitSpeed {
    /// Found: the speed, or unlimited (serialises as a number or `"unlimited"`).
    Known(Speed),
    /// Not searched, the other limit governing: the limit is reached at this speed or above
    /// (serialises as `{"at_least": v}`). The simulation method searches only the limit that
    /// governs ([`crate::safety::simulation::LimitSearch::Governing`]).
    AtLeast {
        /// The governing limit's speed [m/s].
        at_least: f64,
    },
}

impl LimitSpeed {
    /// The speed [m/s] (+∞: unlimited; the bound when known only from below).
    pub fn value(&self) -> f64 {
        match self {
            LimitSpeed::Known(s) => s.value(),
            LimitSpeed::AtLeast { at_least } => *at_least,
        }
    }
}

/// The permissible speed of one design (CJ or CL) of a cell.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DesignSpeed {
    /// m_eff = m_e + γ m_r/3 \[kg\] (Eq. 5).
    pub m_eff_kg: f64,
    /// v_max = min(by force, by pressure) [m/s].
    pub v_max_mps: Speed,
    /// The speed at which the peak force reaches the force limit [m/s] (the simulation method:
    /// a lower bound when the pressure governs).
    pub by_force_mps: LimitSpeed,
    /// The speed at which the mean pressure reaches its limit [m/s] (absent: not assessed; the
    /// simulation method: a lower bound when the force governs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub by_pressure_mps: Option<LimitSpeed>,
    /// The limit that sets v_max.
    pub governing: GoverningLimit,
    /// Impact runs of the root searches (simulation method only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub runs: Option<usize>,
}

/// One cell: its design and both speeds, or why it failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapCell {
    /// The x value.
    pub x: f64,
    /// The y value.
    pub y: f64,
    /// Link mass m_r \[kg\].
    pub m_r_kg: f64,
    /// Payload m_e \[kg\].
    pub m_e_kg: f64,
    /// Link stiffness k_δ \[N/m\] (absent: rigid).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_delta_n_per_m: Option<f64>,
    /// Contact stiffness k_c \[N/m^n\].
    pub k_c: f64,
    /// Contact exponent n.
    pub n: f64,
    /// The cell's body region (a region axis only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub region: Option<String>,
    /// The cell's force limit \[N\] (a region axis only; absent where the contact is refused).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_limit_n: Option<f64>,
    /// The cell's pressure limit \[Pa\] (a region axis with an area model only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_limit_pa: Option<f64>,
    /// The compliant joint (absent when the cell failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cj: Option<DesignSpeed>,
    /// The compliant link (absent when the cell failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cl: Option<DesignSpeed>,
    /// v_max(CL)/v_max(CJ) (absent when the cell failed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_cl_cj: Option<f64>,
    /// Why the cell failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

/// A computed map.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SafetyMap {
    /// The question.
    pub input: SafetyMapInput,
    /// Body region name.
    pub region_name: String,
    /// The area whose pressure limit applies.
    pub area: String,
    /// Force limit \[N\].
    pub force_limit_n: f64,
    /// Pressure limit \[Pa\] (absent: pressure not assessed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_limit_pa: Option<f64>,
    /// The contact-area model used (absent: pressure not assessed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area_model: Option<ContactAreaModel>,
    /// Human mass \[kg\] of the method (absent: a clamped body in the closed-form methods).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub human_mass_kg: Option<f64>,
    /// Every cell, row-major: cell `iy * nx + ix`.
    pub cells: Vec<MapCell>,
    /// Wall-clock time of the computation \[s\].
    pub seconds: f64,
    /// The plausibility warnings of the masses, length and speed typed ([`typed_warnings`];
    /// empty: none), each naming its flag.
    pub warnings: Vec<crate::shared::plausibility::Warning>,
}

/// The plausibility warnings of the masses, length and speed of `input`, by the rule every
/// front shares ([`crate::shared::plausibility`]): `--m-r`, `--m-e`, `--length` and `--speed`,
/// and a mass axis whose largest value is implausible (named `--x (m-e)`: its flag and
/// parameter).
pub fn typed_warnings(input: &SafetyMapInput) -> Vec<crate::shared::plausibility::Warning> {
    use crate::shared::plausibility::{length, mass, speed};
    let mut out: Vec<_> = [
        input.m_r.and_then(|m| mass("--m-r", m)),
        input.m_e.and_then(|m| mass("--m-e", m)),
    ]
    .into_iter()
    .flatten()
    .collect();
    for (flag, axis) in [("--x", &input.x), ("--y", &input.y)] {
        if matches!(
            axis.parameter,
            MapParameter::Payload | MapParameter::LinkMass
        ) {
            let largest = axis.values.iter().copied().fold(f64::NAN, f64::max);
            out.extend(mass(
                &format!("{flag} ({})", axis.parameter.flag_name()),
                largest,
            ));
        }
    }
    out.extend(input.simulation.length.and_then(|l| length("--length", l)));
    out.extend(input.speed.and_then(|v| speed("--speed", v)));
    out
}

fn speed(v: f64) -> Speed {
    if v.is_finite() {
        Speed::Finite(v)
    } else {
        Speed::Unlimited(Unbounded::Unlimited)
    }
}

/// One cell's design.
#[derive(Debug, Clone, PartialEq)]
struct Design {
    m_r: f64,
    m_e: f64,
    k_delta: Option<f64>,
    law: ContactLaw,
    /// The body region of a region axis (absent: the map's region).
    region: Option<String>,
}

/// What every cell shares, validated once.
struct Shared<'a> {
    input: &'a SafetyMapInput,
    model: &'a BodyModel,
    area_model: Option<ContactAreaModel>,
    /// The base law's exponent n (for a k_c axis) and stiffness.
    base: Hertz,
}

impl Shared<'_> {
    fn design(&self, x: f64, y: f64) -> Design {
        let i = self.input;
        let mut d = Design {
            m_r: i.m_r.unwrap_or(f64::NAN),
            m_e: i.m_e.unwrap_or(f64::NAN),
            k_delta: i.k_delta,
            law: i.law.clone(),
            region: None,
        };
        for (axis, v) in [(&i.x, x), (&i.y, y)] {
            match axis.parameter {
                MapParameter::BodyRegion => d.region = axis.region_at(v).map(str::to_string),
                MapParameter::Payload => d.m_e = v,
                MapParameter::LinkMass => d.m_r = v,
                MapParameter::LinkStiffness => d.k_delta = Some(v),
                MapParameter::BendingStiffness => {
                    d.k_delta = Some(3.0 * v / i.simulation.length().powi(3));
                }
                MapParameter::ContactStiffness => {
                    d.law = ContactLaw::Hertz {
                        k_c: v,
                        n: self.base.n(),
                    };
                }
            }
        }
        d
    }

    /// The single-point question of design `d` with γ and one method.
    fn point(&self, d: &Design, gamma: f64, method: SafetyMethod) -> SafetyInput {
        let i = self.input;
        SafetyInput {
            region: d.region.clone().unwrap_or_else(|| i.region.clone()),
            area: i.area.clone(),
            contact: i.contact,
            m_eff: Some(RobotEffectiveMass::Prb {
                gamma,
                m_r: d.m_r,
                m_e: d.m_e,
            }),
            k_delta: d.k_delta,
            law: d.law.clone(),
            area_model: self.area_model,
            moving_mass: None,
            payload: 0.0,
            speed: None,
            methods: vec![method],
            link: None,
            simulation: None,
            scene: None,
        }
    }
}

fn from_method(m: &MethodResult, runs: Option<usize>) -> DesignSpeed {
    DesignSpeed {
        m_eff_kg: m.robot_mass_kg,
        v_max_mps: m.v_max_mps,
        by_force_mps: LimitSpeed::Known(m.by_force_mps),
        by_pressure_mps: m.by_pressure_mps.map(LimitSpeed::Known),
        governing: m.governing,
        runs,
    }
}

/// The map of `input` with the ISO/TS 15066:2016 body model, or `model` when given; stops with
/// [`ImpactError::Interrupted`] (exit code 130) once `cancel` is set.
pub fn safety_map(
    input: &SafetyMapInput,
    model: Option<&BodyModel>,
    cancel: &CancelToken,
) -> Result<SafetyMap, Error> {
    let start = Instant::now();
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    input.x.validate("--x")?;
    input.y.validate("--y")?;
    // a region axis: `all` expanded, every name checked; the map-level region is its first
    let resolved = SafetyMapInput {
        x: input.x.resolved("--x", model)?,
        y: input.y.resolved("--y", model)?,
        ..input.clone()
    };
    let input = &resolved;
    let region_axis = [&input.x, &input.y]
        .into_iter()
        .find(|a| a.parameter == MapParameter::BodyRegion);
    if region_axis.is_some() && !input.region.is_empty() {
        return Err(bad(
            "--region",
            &input.region,
            "not with a body-region axis: the axis names the regions",
        ));
    }
    if region_axis.is_some() && input.area.is_some() {
        return Err(bad(
            "--area",
            input.area.as_deref().unwrap_or_default(),
            "not with a body-region axis: each region's most sensitive area applies",
        ));
    }
    // the map-level region: the first of a region axis whose contact is permitted (the
    // figure's and the JSON's limits are its; every cell carries its own)
    let map_region = match region_axis {
        Some(axis) => axis
            .names
            .iter()
            .find(|k| {
                model.region(k).is_ok_and(|r| {
                    r.limits(Some(r.most_sensitive_area()), input.contact)
                        .is_ok()
                })
            })
            .cloned()
            .ok_or_else(|| {
                bad(
                    "--contact",
                    "transient",
                    "no region of the axis permits this contact (transient contact with the \
                     head and face is not permitted)",
                )
            })?,
        None if input.region.is_empty() => {
            return Err(bad(
                "--region",
                "(missing)",
                "give the body region (e.g. chest), or a region axis (e.g. --y region=all)",
            ));
        }
        None => input.region.clone(),
    };
    if input.x.parameter == input.y.parameter
        || [input.x.parameter, input.y.parameter].iter().all(|p| {
            matches!(
                p,
                MapParameter::LinkStiffness | MapParameter::BendingStiffness
            )
        })
    {
        return Err(bad(
            "--y",
            input.y.parameter.flag_name(),
            &format!(
                "a parameter other than the x axis's {} (k-delta and ei are the same stiffness)",
                input.x.parameter.flag_name()
            ),
        ));
    }
    input.simulation.validate()?;
    let axes = [input.x.parameter, input.y.parameter];
    let on_axis = |p: MapParameter| axes.contains(&p);
    if on_axis(MapParameter::BendingStiffness) && input.simulation.length.is_none() {
        return Err(bad(
            "--length",
            "(missing)",
            "give the link's length with an ei axis: the stiffness at the tip is k_δ = 3EI/L³",
        ));
    }
    if !on_axis(MapParameter::LinkMass) {
        match input.m_r {
            Some(v) => MapParameter::LinkMass.check("--m-r", v)?,
            None => return Err(bad("--m-r", "(missing)", "give the link mass m_r in kg")),
        }
    }
    if !on_axis(MapParameter::Payload) {
        match input.m_e {
            Some(v) => MapParameter::Payload.check("--m-e", v)?,
            None => return Err(bad("--m-e", "(missing)", "give the payload m_e in kg")),
        }
    }
    let stiffness_axis =
        on_axis(MapParameter::LinkStiffness) || on_axis(MapParameter::BendingStiffness);
    if !stiffness_axis && let Some(k) = input.k_delta {
        MapParameter::LinkStiffness.check("--k-delta", k)?;
    }
    if let Some(v) = input.speed
        && !(v.is_finite() && v > 0.0 && v <= 1e3)
    {
        return Err(bad("--speed", display(v), "must lie in (0, 1000] m/s"));
    }
    // the base law and the default area model, as `safety` resolves them
    let region = model.region(&map_region)?;
    let (base, material_radius) = match &input.law {
        ContactLaw::BodySpring => (Hertz::new(region.spring_constant(), 1.0)?, None),
        ContactLaw::Hertz { k_c, n } => {
            let base =
                Hertz::new(*k_c, *n).map_err(|e| bad("--k-c", display(*k_c), &e.to_string()));
            (base?, None)
        }
        ContactLaw::Material(name) => {
            let materials = Materials::bundled()?;
            let m = materials
                .get(name)
                .map_err(|e| bad("--material", name, &e.to_string()))?;
            (m.hertz, Some(materials.dome_radius_m()))
        }
    };
    let area_model = input
        .area_model
        .or(material_radius.map(|r| ContactAreaModel::HertzSphere { radius_m: r }));
    if let Some(a) = &area_model
        && !matches!(a, ContactAreaModel::Fixed { .. })
        && base.n() <= 1.0
    {
        return Err(bad(
            "--area-model",
            format!("{a:?}"),
            "a dome's area model needs a contact law with n > 1: a linear contact is a spring \
             without a contact geometry; give --k-c and --n of the skin (or --material), or a \
             fixed area (--contact-area, e.g. 1cm2)",
        ));
    }
    let shared = Shared {
        input,
        model,
        area_model,
        base,
    };
    let simulation = input.method == MapMethod::Simulation;
    if simulation {
        if input.contact == ContactKind::QuasiStatic && input.simulation.joint == MapJoint::Held {
            return Err(bad(
                "--contact",
                "quasi-static",
                "with --method simulation needs --joint free-hub: a held joint pressing a \
                 clamped body has no bounded peak force",
            ));
        }
        if !stiffness_axis && input.k_delta.is_none() {
            return Err(bad(
                "--k-delta",
                "(missing)",
                "the simulation method needs a link stiffness (--k-delta, or an axis k-delta or ei)",
            ));
        }
        if matches!(input.law, ContactLaw::Hertz { n, .. } if n < 1.0) || base.n() < 1.0 {
            return Err(bad(
                "--n",
                display(base.n()),
                "the simulation method needs n ≥ 1",
            ));
        }
    }
    let xs = &input.x.values;
    let ys = &input.y.values;
    // the first cell answers every question the input can be refused for (region, contact,
    // law, area model) before the map runs; along a region axis a refused region (transient
    // contact with the head) is a failed cell, not a refused map
    let first = match cell(&shared, xs[0], ys[0], &AtomicBool::new(false)) {
        Ok(c) => c,
        Err(e @ Error::Safety(flexrig_safety::SafetyError::ContactNotPermitted { .. }))
            if region_axis.is_some() =>
        {
            failed_cell(&shared, xs[0], ys[0], e.to_string())
        }
        Err(e) => return Err(e),
    };
    let grid: Vec<(f64, f64)> = ys
        .iter()
        .flat_map(|&y| xs.iter().map(move |&x| (x, y)))
        .collect();
    let flag = cancel.flag();
    let cells: Vec<Option<MapCell>> = grid
        .par_iter()
        .enumerate()
        .map(|(i, &(x, y))| {
            if flag.load(Ordering::Relaxed) {
                return None;
            }
            if i == 0 {
                return Some(first.clone());
            }
            match cell(&shared, x, y, &flag) {
                Ok(c) => Some(c),
                Err(Error::Impact(ImpactError::Interrupted)) => None,
                Err(e) => Some(failed_cell(&shared, x, y, e.to_string())),
            }
        })
        .collect();
    let cells = cells
        .into_iter()
        .collect::<Option<Vec<_>>>()
        .ok_or(Error::Impact(ImpactError::Interrupted))?;
    let area = match &input.area {
        Some(name) => region.area(name)?,
        None => region.most_sensitive_area(),
    };
    // the map-level limits: the region's (the first region of a region axis, whose cells each
    // carry their own)
    let mut limits = region.limits(Some(area), input.contact)?;
    if area_model.is_none() {
        limits.pressure = None;
    }
    let human_mass = region.human_mass(input.contact);
    Ok(SafetyMap {
        input: input.clone(),
        region_name: region.name().to_string(),
        area: area.name().to_string(),
        force_limit_n: limits.force,
        pressure_limit_pa: limits.pressure,
        area_model,
        human_mass_kg: if human_mass.is_finite() {
            Some(human_mass)
        } else if simulation {
            Some(CLAMPED_HUMAN_MASS)
        } else {
            None
        },
        cells,
        seconds: start.elapsed().as_secs_f64(),
        warnings: typed_warnings(input),
    })
}

/// The limits of the cell's own region (a region axis): force \[N\] and pressure \[Pa\] of its
/// most sensitive area (absent without an area model), or `None` when the contact is refused.
fn cell_limits(shared: &Shared, d: &Design) -> (Option<f64>, Option<f64>) {
    let Some(key) = &d.region else {
        return (None, None);
    };
    let Ok(region) = shared.model.region(key) else {
        return (None, None);
    };
    match region.limits(Some(region.most_sensitive_area()), shared.input.contact) {
        Ok(l) => (
            Some(l.force),
            l.pressure.filter(|_| shared.area_model.is_some()),
        ),
        Err(_) => (None, None),
    }
}

fn failed_cell(shared: &Shared, x: f64, y: f64, error: String) -> MapCell {
    let d = shared.design(x, y);
    let limits = cell_limits(shared, &d);
    let (k_c, n) = law_numbers(shared, &d);
    MapCell {
        x,
        y,
        m_r_kg: d.m_r,
        m_e_kg: d.m_e,
        k_delta_n_per_m: d.k_delta,
        k_c,
        n,
        region: d.region.clone(),
        force_limit_n: limits.0,
        pressure_limit_pa: limits.1,
        cj: None,
        cl: None,
        ratio_cl_cj: None,
        error: Some(error),
    }
}

fn law_numbers(shared: &Shared, d: &Design) -> (f64, f64) {
    match (&d.law, &d.region) {
        (ContactLaw::Hertz { k_c, n }, _) => (*k_c, *n),
        // the body spring of the cell's own region (n = 1)
        (ContactLaw::BodySpring, Some(key)) => shared
            .model
            .region(key)
            .map_or((f64::NAN, 1.0), |r| (r.spring_constant(), 1.0)),
        _ => (shared.base.k(), shared.base.n()),
    }
}

/// One cell by the method of the map.
fn cell(shared: &Shared, x: f64, y: f64, stop: &AtomicBool) -> Result<MapCell, Error> {
    let d = shared.design(x, y);
    let method = match shared.input.method {
        MapMethod::Standard => SafetyMethod::Standard,
        MapMethod::Energy | MapMethod::Simulation => SafetyMethod::Energy,
    };
    let lumped = |gamma: f64| -> Result<MethodResult, Error> {
        let r = safety(&shared.point(&d, gamma, method), Some(shared.model))?;
        Ok(r.methods[0])
    };
    let (cj_lumped, cl_lumped) = (lumped(GAMMA_CJ)?, lumped(GAMMA_CL)?);
    let (cj, cl) = if shared.input.method == MapMethod::Simulation {
        (
            simulated(shared, &d, FeLink::CompliantJoint, &cj_lumped, stop)?,
            simulated(shared, &d, FeLink::CompliantLink, &cl_lumped, stop)?,
        )
    } else {
        (from_method(&cj_lumped, None), from_method(&cl_lumped, None))
    };
    let (k_c, n) = law_numbers(shared, &d);
    let limits = cell_limits(shared, &d);
    Ok(MapCell {
        x,
        y,
        m_r_kg: d.m_r,
        m_e_kg: d.m_e,
        k_delta_n_per_m: d.k_delta,
        k_c,
        n,
        region: d.region.clone(),
        force_limit_n: limits.0,
        pressure_limit_pa: limits.1,
        ratio_cl_cj: Some(cl.v_max_mps.value() / cj.v_max_mps.value()),
        cj: Some(cj),
        cl: Some(cl),
        error: None,
    })
}

/// The simulated permissible speed of one design: root searches on the finite-element impact's
/// first-contact peak force, started at the lumped method's speeds.
fn simulated(
    shared: &Shared,
    d: &Design,
    link: FeLink,
    lumped: &MethodResult,
    stop: &AtomicBool,
) -> Result<DesignSpeed, Error> {
    let input = shared.input;
    let region = shared
        .model
        .region(d.region.as_deref().unwrap_or(&input.region))?;
    let area = match &input.area {
        Some(name) => region.area(name)?,
        None => region.most_sensitive_area(),
    };
    let mut limits = region.limits(Some(area), input.contact)?;
    if shared.area_model.is_none() {
        limits.pressure = None;
    }
    let (k_c, n) = law_numbers(shared, d);
    let hertz = Hertz::new(k_c, n)?;
    let k_delta = d.k_delta.ok_or_else(|| {
        bad(
            "--k-delta",
            "(missing)",
            "the simulation method needs a link stiffness",
        )
    })?;
    let m_h = match region.human_mass(input.contact) {
        m if m.is_finite() => m,
        _ => CLAMPED_HUMAN_MASS,
    };
    let gamma = match link {
        FeLink::CompliantJoint => GAMMA_CJ,
        FeLink::CompliantLink => GAMMA_CL,
    };
    let energy = EnergyContact::for_region(
        region,
        input.contact,
        d.m_e + gamma * d.m_r / 3.0,
        hertz,
        LinkStiffness::Finite(k_delta),
        shared.area_model,
    )?;
    let impact = FeImpact {
        m_h,
        hertz,
        m_r: d.m_r,
        m_e: d.m_e,
        k_delta,
        link,
        settings: input.simulation,
    };
    let found = fe_search(
        &impact,
        &limits,
        &energy,
        lumped.by_pressure_mps.is_some(),
        LimitSearch::Governing,
        stop,
        None,
    )?;
    let v_max = match (found.governing, found.by_pressure) {
        (GoverningLimit::Pressure, Some(vp)) => vp,
        _ => found.by_force,
    };
    let as_searched = |v: f64, limit: GoverningLimit| match found.bound {
        Some(b) if b == limit && v.is_finite() => LimitSpeed::AtLeast { at_least: v },
        _ => LimitSpeed::Known(speed(v)),
    };
    Ok(DesignSpeed {
        m_eff_kg: d.m_e + gamma * d.m_r / 3.0,
        v_max_mps: speed(v_max),
        by_force_mps: as_searched(found.by_force, GoverningLimit::Force),
        by_pressure_mps: found
            .by_pressure
            .map(|v| as_searched(v, GoverningLimit::Pressure)),
        governing: found.governing,
        runs: Some(found.runs.runs),
    })
}

mod files;
pub use files::{MapSummary, SafetyMapFiles, csv, method_text, run, summary, svg};

#[cfg(test)]
mod tests;
