//! The safe-speed map written out: its CSV (one row per cell, units in the header), its JSON
//! summary, its figure, and the files of `flexrig safety-map --out`.

use super::*;

/// The number as CSV and JSON write it (shortest round-trip form), `unlimited` for +∞.
fn num(v: f64) -> String {
    if v.is_finite() {
        format!("{v}")
    } else {
        "unlimited".into()
    }
}

/// A limit's speed as the CSV writes it: the number, `unlimited`, or `>=` and the number when
/// only its lower bound is known (a limit that does not govern, not searched).
fn limit_speed(s: LimitSpeed) -> String {
    match s {
        LimitSpeed::Known(v) => num(v.value()),
        LimitSpeed::AtLeast { at_least } => format!(">={}", num(at_least)),
    }
}

/// The map's CSV: one row per cell, units in the header; a speed no limit bounds is
/// `unlimited`, a limit's speed known only from below (it does not govern and the simulation
/// did not search it) `>=` and the governing speed, a pressure not assessed an empty field, a
/// failed cell carries its error.
pub fn csv(map: &SafetyMap) -> String {
    let x = map.input.x.parameter.column();
    let y = map.input.y.parameter.column();
    let mut s = format!(
        "x_{x},y_{y},m_r_kg,m_e_kg,k_delta_n_per_m,k_c_n_per_m_n,n,m_eff_cj_kg,m_eff_cl_kg,\
         v_max_cj_mps,v_max_cl_mps,ratio_cl_cj,by_force_cj_mps,by_pressure_cj_mps,governing_cj,\
         by_force_cl_mps,by_pressure_cl_mps,governing_cl,runs_cj,runs_cl,error\n"
    );
    let gov = |g: GoverningLimit| match g {
        GoverningLimit::Force => "force",
        GoverningLimit::Pressure => "pressure",
    };
    let on_axis = |axis: &MapAxis, v: f64| match axis.region_at(v) {
        Some(key) => key.to_string(),
        None => num(v),
    };
    for c in &map.cells {
        let k_delta = c.k_delta_n_per_m.map_or("rigid".into(), num);
        let _ = write!(
            s,
            "{},{},{},{},{k_delta},{},{},",
            on_axis(&map.input.x, c.x),
            on_axis(&map.input.y, c.y),
            num(c.m_r_kg),
            num(c.m_e_kg),
            num(c.k_c),
            num(c.n)
        );
        match (&c.cj, &c.cl, c.ratio_cl_cj) {
            (Some(cj), Some(cl), Some(r)) => {
                let p = |d: &DesignSpeed| d.by_pressure_mps.map_or(String::new(), limit_speed);
                let runs = |d: &DesignSpeed| d.runs.map_or(String::new(), |r| r.to_string());
                let _ = writeln!(
                    s,
                    "{},{},{},{},{},{},{},{},{},{},{},{},{},",
                    num(cj.m_eff_kg),
                    num(cl.m_eff_kg),
                    num(cj.v_max_mps.value()),
                    num(cl.v_max_mps.value()),
                    num(r),
                    limit_speed(cj.by_force_mps),
                    p(cj),
                    gov(cj.governing),
                    limit_speed(cl.by_force_mps),
                    p(cl),
                    gov(cl.governing),
                    runs(cj),
                    runs(cl)
                );
            }
            _ => {
                let e = c.error.clone().unwrap_or_default().replace('"', "'");
                let _ = writeln!(s, ",,,,,,,,,,,,,\"{e}\"");
            }
        }
    }
    s
}

/// The smallest and largest of the finite `values` (`None` when there is none).
fn finite_range(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.filter(|v| v.is_finite()).fold(None, |r, v| match r {
        None => Some((v, v)),
        Some((a, b)) => Some((f64::min(a, v), f64::max(b, v))),
    })
}

/// What a map found, in brief (`flexrig safety-map` prints it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapSummary {
    /// Cells computed.
    pub cells: usize,
    /// Cells that failed (their error is in the CSV and the JSON).
    pub failed: usize,
    /// Smallest and largest v_max of the CJ over the cells [m/s] (absent: none finite).
    pub v_max_cj_mps_range: Option<(f64, f64)>,
    /// The same for the CL [m/s].
    pub v_max_cl_mps_range: Option<(f64, f64)>,
    /// The same for the ratio CL/CJ.
    pub ratio_cl_cj_range: Option<(f64, f64)>,
    /// Designs (CJ and CL of every computed cell) whose v_max the force limit sets.
    pub governed_by_force: usize,
    /// Designs whose v_max the pressure limit sets.
    pub governed_by_pressure: usize,
    /// Designs whose other limit's speed is only a lower bound (the simulation searched the
    /// governing limit alone).
    pub other_limit_bounded: usize,
}

/// The summary of `map`: cell counts, the ranges of v_max and of the ratio, and which limit
/// governs how many designs.
pub fn summary(map: &SafetyMap) -> MapSummary {
    let ok: Vec<&MapCell> = map.cells.iter().filter(|c| c.error.is_none()).collect();
    let speed = |d: Option<DesignSpeed>| d.map_or(f64::NAN, |d| d.v_max_mps.value());
    let designs: Vec<&DesignSpeed> = ok
        .iter()
        .flat_map(|c| c.cj.iter().chain(c.cl.iter()))
        .collect();
    let count = |f: &dyn Fn(&DesignSpeed) -> bool| designs.iter().filter(|d| f(d)).count();
    let bounded = |l: &LimitSpeed| matches!(l, LimitSpeed::AtLeast { .. });
    MapSummary {
        cells: map.cells.len(),
        failed: map.cells.len() - ok.len(),
        v_max_cj_mps_range: finite_range(ok.iter().map(|c| speed(c.cj))),
        v_max_cl_mps_range: finite_range(ok.iter().map(|c| speed(c.cl))),
        ratio_cl_cj_range: finite_range(ok.iter().map(|c| c.ratio_cl_cj.unwrap_or(f64::NAN))),
        governed_by_force: count(&|d| d.governing == GoverningLimit::Force),
        governed_by_pressure: count(&|d| d.governing == GoverningLimit::Pressure),
        other_limit_bounded: count(&|d| {
            bounded(&d.by_force_mps) || d.by_pressure_mps.as_ref().is_some_and(bounded)
        }),
    }
}

/// The method in words, as the figure's title says it.
pub fn method_text(map: &SafetyMap) -> String {
    let s = &map.input.simulation;
    match map.input.method {
        MapMethod::Standard => "the standard's formula (ISO/TS 15066 Annex A), m_R = m_eff".into(),
        MapMethod::Energy => {
            "lumped energy method (CJ: m_eff = m_e + m_r/3, CL: m_e + 2m_r/9)".into()
        }
        MapMethod::Simulation => format!(
            "finite-element impact ({}; CJ rigid link on k_θ = k_δL², CL modal beam), root search to {:e}",
            match s.joint {
                MapJoint::Held => "joint held".to_string(),
                MapJoint::FreeHub { rotor_inertia } =>
                    format!("free hub, J_R = {} kg·m²", display(rotor_inertia)),
            },
            s.root_rtol
        ),
    }
}

/// The figure: v_max of the CJ, of the CL (one logarithmic colour scale for both) and their
/// ratio CL/CJ, at the printed width `width_pt` \[pt\].
pub fn svg(map: &SafetyMap, width_pt: f64) -> Result<String, String> {
    use crate::plots::{AxisNames, ColorScale, HeatMap, heatmaps_svg_named};
    let xs = &map.input.x.values;
    let ys = &map.input.y.values;
    let v = |f: &dyn Fn(&MapCell) -> Option<f64>| -> Vec<Option<f64>> {
        map.cells.iter().map(f).collect()
    };
    let cj = v(&|c| c.cj.map(|d| d.v_max_mps.value()).filter(|v| v.is_finite()));
    let cl = v(&|c| c.cl.map(|d| d.v_max_mps.value()).filter(|v| v.is_finite()));
    let ratio = v(&|c| c.ratio_cl_cj.filter(|r| r.is_finite()));
    let (lo, hi) = cj
        .iter()
        .chain(&cl)
        .flatten()
        .filter(|v| **v > 0.0)
        .fold((f64::INFINITY, 0.0_f64), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let (lo, hi) = if lo.is_finite() && hi > lo * 1.0001 {
        (lo, hi)
    } else if lo.is_finite() {
        (lo / 1.1, lo * 1.1)
    } else {
        (0.1, 10.0)
    };
    let span = ratio
        .iter()
        .flatten()
        .fold(0.0_f64, |s, r| s.max((r - 1.0).abs()));
    let span = if span > 1e-3 { span } else { 1e-3 };
    let masks = map.input.speed.map(|s| {
        let mask = |d: &[Option<f64>]| {
            d.iter()
                .map(|v| v.is_some_and(|v| v >= s))
                .collect::<Vec<_>>()
        };
        (
            mask(&cj),
            mask(&cl),
            format!("permits v = {} m/s", display(s)),
        )
    });
    let (x_label, y_label) = (map.input.x.parameter.label(), map.input.y.parameter.label());
    let maps = vec![
        HeatMap {
            title: "compliant joint (CJ): v_max [m/s]",
            x_label,
            y_label,
            xs,
            ys,
            values: &cj,
            scale: ColorScale::Log { lo, hi },
            value_label: "v_max [m/s]",
            outline: masks.as_ref().map(|(m, _, t)| (m.as_slice(), t.as_str())),
        },
        HeatMap {
            title: "compliant link (CL): v_max [m/s]",
            x_label,
            y_label,
            xs,
            ys,
            values: &cl,
            scale: ColorScale::Log { lo, hi },
            value_label: "v_max [m/s]",
            outline: masks.as_ref().map(|(_, m, t)| (m.as_slice(), t.as_str())),
        },
        HeatMap {
            title: "ratio v_max(CL)/v_max(CJ)",
            x_label,
            y_label,
            xs,
            ys,
            values: &ratio,
            scale: ColorScale::Diverging { centre: 1.0, span },
            value_label: "CL/CJ",
            outline: None,
        },
    ];
    let contact = match map.input.contact {
        ContactKind::Transient => "transient contact",
        ContactKind::QuasiStatic => "quasi-static (clamped) contact",
    };
    let limits = match map.pressure_limit_pa {
        Some(p) => format!(
            "F_max = {} N, p_max = {} N/cm²",
            display(map.force_limit_n),
            display(p / 1e4)
        ),
        None => format!(
            "F_max = {} N (pressure not assessed)",
            display(map.force_limit_n)
        ),
    };
    let mut fixed = Vec::new();
    let axes = [map.input.x.parameter, map.input.y.parameter];
    if !axes.contains(&MapParameter::LinkMass)
        && let Some(m) = map.input.m_r
    {
        fixed.push(format!("m_r = {} kg", display(m)));
    }
    if !axes.contains(&MapParameter::Payload)
        && let Some(m) = map.input.m_e
    {
        fixed.push(format!("m_e = {} kg", display(m)));
    }
    if !axes.contains(&MapParameter::LinkStiffness)
        && !axes.contains(&MapParameter::BendingStiffness)
    {
        fixed.push(match map.input.k_delta {
            Some(k) => format!("k_δ = {} N/m", crate::plots::sci_label(k)),
            None => "rigid link".into(),
        });
    }
    if let Some(c) = map.cells.first() {
        if axes.contains(&MapParameter::BodyRegion)
            && matches!(map.input.law, ContactLaw::BodySpring)
        {
            fixed.push("body spring K per region".into());
        } else if !axes.contains(&MapParameter::ContactStiffness) {
            fixed.push(format!(
                "k_c = {} N/mⁿ, n = {}",
                crate::plots::sci_label(c.k_c),
                display(c.n)
            ));
        } else {
            fixed.push(format!("n = {}", display(c.n)));
        }
    }
    fn names(a: &MapAxis) -> Option<&[String]> {
        (a.parameter == MapParameter::BodyRegion).then_some(a.names.as_slice())
    }
    let region_axis = names(&map.input.x).is_some() || names(&map.input.y).is_some();
    let title = if region_axis {
        vec![
            format!("Permissible speed near each body region (its most sensitive area), {contact}"),
            format!(
                "limits per region (Table A.2; hatched: not permitted); {}",
                fixed.join(", ")
            ),
            method_text(map),
        ]
    } else {
        vec![
            format!(
                "Permissible speed near the {} ({}), {contact}",
                map.region_name.to_lowercase(),
                map.area
            ),
            format!("{limits}; {}", fixed.join(", ")),
            method_text(map),
        ]
    };
    let axis_names = AxisNames {
        x: names(&map.input.x),
        y: names(&map.input.y),
    };
    heatmaps_svg_named(&title, &maps, axis_names, width_pt)
}

/// Where to write a map and how to draw it.
#[derive(Debug, Clone, PartialEq)]
pub struct SafetyMapFiles {
    /// Directory for safety_map.csv, safety_map.json and the figure (created if missing).
    pub out: PathBuf,
    /// Printed size and formats of the figure.
    pub figures: crate::plots::FigureOptions,
}

/// Computes the map, renders everything, then writes safety_map.csv, safety_map.json and the
/// figure safety_map.{svg,pdf,png} (no partial output); returns the map and the files.
pub fn run(
    input: &SafetyMapInput,
    model: Option<&BodyModel>,
    files: &SafetyMapFiles,
    cancel: &CancelToken,
) -> Result<(SafetyMap, Vec<PathBuf>), Error> {
    files.figures.validate()?;
    let map = safety_map(input, model, cancel)?;
    let out = &files.out;
    let figure = svg(&map, files.figures.width_pt()).map_err(|message| Error::Plot {
        path: out.join("safety_map.svg"),
        message,
    })?;
    let json = serde_json::to_string_pretty(&map).map_err(|e| Error::NonFinite {
        what: "safety map JSON".into(),
        value: e.to_string(),
        advice: "report this".into(),
    })?;
    crate::shared::output::ensure_dir(out)?;
    let csv_path = out.join("safety_map.csv");
    crate::shared::output::write_atomic(&csv_path, csv(&map).as_bytes())?;
    let json_path = out.join("safety_map.json");
    crate::shared::output::write_atomic(&json_path, json.as_bytes())?;
    let mut written = vec![csv_path, json_path];
    written.extend(crate::plots::write_figure(
        out,
        "safety_map",
        &figure,
        &files.figures,
    )?);
    Ok((map, written))
}
