//! `flexrig safety-map`: the permissible speed of the CJ and the CL design over two design
//! parameters, with their ratio, as CSV, JSON and a heat-map figure, see
//! [`flexrig::safety::map`].

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use flexrig::safety::ContactKind;
use flexrig::safety::map::{
    MapMethod, SafetyMapFiles, SafetyMapInput, SimulationSettings, parse_axis,
};
use flexrig::{CancelToken, Error};
use serde_json::json;

use flexrig::safety::load_body_model;

use super::impact_args::JointArg;
use super::safety_args::{ContactArg, map_joint};
use crate::print::{line, print_json};

/// The map's method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MapMethodArg {
    /// The standard's formula (ISO/TS 15066 Annex A), m_R = m_eff.
    Standard,
    /// The lumped energy method (CJ: γ = 1, CL: γ = 2/3).
    Energy,
    /// The finite-element impact (CJ rigid link on its spring, CL modal beam) and a root search.
    Simulation,
}

/// Arguments of `flexrig safety-map`.
#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct SafetyMapArgs {
    /// The x axis: PARAM=FROM:TO:N[:log] (both ends included) or PARAM=V1,V2,…, with
    /// PARAM one of m-e (payload [kg]), m-r (link mass [kg]), k-delta (link stiffness [N/m]), ei
    /// (bending stiffness [N·m²], with --length), k-c (contact stiffness [N/mⁿ]); or the body
    /// region: region=all or region=chest,abdomen,… (each cell with its region's limits).
    #[arg(long, value_name = "PARAM=RANGE", default_value = "m-e=0.01:5:30:log")]
    pub x: String,
    /// The y axis, as --x.
    #[arg(
        long,
        value_name = "PARAM=RANGE",
        default_value = "k-delta=10:1e7:30:log"
    )]
    pub y: String,
    /// Body region key of the body model, e.g. chest, hands_and_fingers (not with a region
    /// axis).
    #[arg(long, value_name = "REGION")]
    pub region: Option<String>,
    /// Specific area of the region for the pressure limit (default: its most sensitive area).
    #[arg(long, value_name = "NAME")]
    pub area: Option<String>,
    /// Contact kind.
    #[arg(long, value_enum, default_value = "transient")]
    pub contact: ContactArg,
    /// Link mass m_r [kg], unless an axis.
    #[arg(long = "m-r", value_name = "KG")]
    pub m_r: Option<f64>,
    /// Payload m_e [kg], unless an axis.
    #[arg(long = "m-e", value_name = "KG")]
    pub m_e: Option<f64>,
    /// Link lateral stiffness k_δ [N/m], unless an axis (default: a rigid link, lumped methods
    /// only).
    #[arg(long = "k-delta", value_name = "N_PER_M")]
    pub k_delta: Option<f64>,
    /// Link length L [m]: required with an ei axis (k_δ = 3EI/L³) and with --joint free-hub
    /// (the rotor's inertia acts at the contact as J_R/L²); not needed otherwise.
    #[arg(long, value_name = "M")]
    pub length: Option<f64>,
    /// The contact law and the contact-area model.
    #[command(flatten)]
    pub law: super::safety_args::ContactLawArgs,
    /// The method.
    #[arg(long, value_enum, default_value = "energy")]
    pub method: MapMethodArg,
    /// The joint during the simulated impact: held (driven at constant speed, the body region
    /// arriving at v) or a free hub (with --rotor-inertia).
    #[arg(long, value_enum, default_value = "held")]
    pub joint: JointArg,
    /// Rotor inertia J_R of the free hub [kg·m²] (with --joint free-hub).
    #[arg(long, value_name = "KG_M2")]
    pub rotor_inertia: Option<f64>,
    /// Tolerance of the CL's modal integrator (simulation; 1e-10 to 1e-3).
    #[arg(long, value_name = "TOL", default_value = "1e-6")]
    pub tol: f64,
    /// Relative tolerance of the root search on the speed (simulation; 1e-13 to 1e-4).
    #[arg(long = "root-rtol", value_name = "RTOL", default_value = "1e-6")]
    pub root_rtol: f64,
    /// A speed [m/s] to outline on the figure: the cells that permit it.
    #[arg(long, value_name = "M_PER_S")]
    pub speed: Option<f64>,
    /// A body-model TOML file in the format of assets/safety/iso_ts_15066_2016.toml.
    #[arg(long = "body-model", value_name = "FILE")]
    pub body_model: Option<PathBuf>,
    /// Directory for safety_map.csv, safety_map.json and the figure (created if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Print JSON (the summary and the files) instead of text.
    #[arg(long)]
    pub json: bool,
    /// Size and formats of the figure.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
}

impl SafetyMapArgs {
    /// The library's input.
    pub fn input(&self) -> Result<SafetyMapInput, Error> {
        let (law, area_model) = (self.law.law(), self.law.area_model()?);
        let joint = map_joint(self.joint, self.rotor_inertia)?;
        Ok(SafetyMapInput {
            region: self.region.clone().unwrap_or_default(),
            area: self.area.clone(),
            contact: match self.contact {
                ContactArg::Transient => ContactKind::Transient,
                ContactArg::QuasiStatic => ContactKind::QuasiStatic,
            },
            m_r: self.m_r,
            m_e: self.m_e,
            k_delta: self.k_delta,
            law,
            area_model,
            x: parse_axis("--x", &self.x)?,
            y: parse_axis("--y", &self.y)?,
            method: match self.method {
                MapMethodArg::Standard => MapMethod::Standard,
                MapMethodArg::Energy => MapMethod::Energy,
                MapMethodArg::Simulation => MapMethod::Simulation,
            },
            simulation: SimulationSettings {
                joint,
                length: self.length,
                tol: self.tol,
                root_rtol: self.root_rtol,
                ..SimulationSettings::DEFAULT
            },
            speed: self.speed,
        })
    }
}

/// Runs `flexrig safety-map`.
pub fn run(args: &SafetyMapArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let model = load_body_model(args.body_model.as_deref())?;
    let input = args.input()?;
    // plausibility warnings before the work (on standard error; the JSON lists them too)
    for w in flexrig::safety::map::typed_warnings(&input) {
        eprintln!("warning: {w}");
    }
    let files = SafetyMapFiles {
        out: args.out.clone(),
        figures: args.figure.options()?,
    };
    let (map, written) = flexrig::safety::map::run(&input, model.as_ref(), &files, cancel)?;
    let sum = flexrig::safety::map::summary(&map);
    let paths: Vec<_> = written.iter().map(|p| p.display().to_string()).collect();
    let pair = |r: Option<(f64, f64)>| r.map_or(json!([]), |(a, b)| json!([a, b]));
    if args.json {
        return print_json(
            out,
            &json!({
                "region": map.input.region,
                "area": map.area,
                "method": map.input.method,
                "cells": sum.cells,
                "failed": sum.failed,
                "v_max_cj_mps_range": pair(sum.v_max_cj_mps_range),
                "v_max_cl_mps_range": pair(sum.v_max_cl_mps_range),
                "ratio_cl_cj_range": pair(sum.ratio_cl_cj_range),
                "governed_by_force": sum.governed_by_force,
                "governed_by_pressure": sum.governed_by_pressure,
                "other_limit_bounded": sum.other_limit_bounded,
                "seconds": map.seconds,
                "files": paths,
                "warnings": map.warnings,
            }),
        );
    }
    let nx = map.input.x.values.len();
    let ny = map.input.y.values.len();
    line(
        out,
        format!(
            "safe-speed map near the {} ({}): {} × {} cells over {} × {}, {}",
            map.region_name.to_lowercase(),
            map.area,
            nx,
            ny,
            map.input.x.parameter.label(),
            map.input.y.parameter.label(),
            flexrig::safety::map::method_text(&map)
        ),
    )?;
    let show = |r: Option<(f64, f64)>| r.map_or("—".into(), |(a, b)| format!("{a:.4} to {b:.4}"));
    line(
        out,
        format!("v_max CJ   {} m/s", show(sum.v_max_cj_mps_range)),
    )?;
    line(
        out,
        format!("v_max CL   {} m/s", show(sum.v_max_cl_mps_range)),
    )?;
    line(out, format!("CL/CJ      {}", show(sum.ratio_cl_cj_range)))?;
    if map.area_model.is_some() {
        line(
            out,
            format!(
                "governs    force in {} designs, pressure in {}{}",
                sum.governed_by_force,
                sum.governed_by_pressure,
                if sum.other_limit_bounded > 0 {
                    " (the other limit not searched: its speed is at least v_max)"
                } else {
                    ""
                }
            ),
        )?;
    }
    line(
        out,
        format!(
            "{} cells in {:.2} s ({} failed)",
            sum.cells, map.seconds, sum.failed
        ),
    )?;
    for p in &paths {
        line(out, format!("wrote {p}"))?;
    }
    Ok(())
}
