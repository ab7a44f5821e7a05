//! The figure of an arm along its path: three panels over time, one curve per contact point —
//! the reflected mass along the point's velocity, the point's speed, and its permissible speed
//! (the overall one of the methods run), in the house style of [`crate::plots::curves`].

use std::path::{Path, PathBuf};

use crate::Error;
use crate::arm::judge::ArmReport;
use crate::plots::{Curve, CurveAxes, CurvePanel, curves_svg};

/// The figure's SVG at the printed width `width_pt` (pt).
pub fn arm_svg(report: &ArmReport, width_pt: f64) -> Result<String, String> {
    let series = |f: &dyn Fn(&crate::arm::judge::PointResult) -> Option<f64>| -> Vec<Curve> {
        report
            .points
            .iter()
            .enumerate()
            .map(|(k, p)| Curve {
                label: p.label(),
                points: report
                    .samples
                    .iter()
                    .filter_map(|s| f(&s.points[k]).map(|y| (s.time_s, y)))
                    .filter(|(_, y)| y.is_finite())
                    .collect(),
                limit: None,
            })
            .collect()
    };
    let panels = vec![
        CurvePanel {
            title: "Reflected mass along the velocity [kg]".into(),
            curves: series(&|p| p.reflected_mass_kg),
        },
        CurvePanel {
            title: "Point speed [m/s]".into(),
            curves: series(&|p| Some(p.speed_mps)),
        },
        CurvePanel {
            title: "Permissible speed [m/s]".into(),
            curves: series(&|p| p.v_max_mps.map(|v| v.value())),
        },
    ];
    let title = format!(
        "{} along its path, {} ({}): the trajectory may run at {} × its speed",
        report.robot,
        report.region_name.to_lowercase(),
        report.area,
        match report.speed_scale_factor {
            crate::safety::Speed::Finite(v) => format!("{v:.3}"),
            crate::safety::Speed::Unlimited(_) => "any".into(),
        }
    );
    // each panel on its own y axis: three figures stacked in one file
    let mut parts = Vec::new();
    for (i, panel) in panels.into_iter().enumerate() {
        let axes = CurveAxes {
            x_desc: "time [s]",
            y_desc: "",
            x_log: false,
            markers: false,
            reference_band: false,
        };
        parts.push(curves_svg(
            if i == 0 { &title } else { "" },
            &axes,
            &[panel],
            width_pt,
        )?);
    }
    Ok(stack(&parts))
}

/// SVG documents (each laid out in points: its viewBox in pt) stacked vertically into one.
fn stack(parts: &[String]) -> String {
    let mut y = 0.0;
    let mut width: f64 = 0.0;
    let mut body = String::new();
    for p in parts {
        let Some(start) = p.find("<svg") else {
            continue;
        };
        let Some(end) = p[start..].find('>') else {
            continue;
        };
        let root = &p[start..start + end];
        let view_box = root
            .split("viewBox=\"")
            .nth(1)
            .and_then(|r| r.split('"').next())
            .unwrap_or("0 0 504 300");
        let dims: Vec<f64> = view_box
            .split_whitespace()
            .filter_map(|v| v.parse().ok())
            .collect();
        let (w, h) = (
            dims.get(2).copied().unwrap_or(504.0),
            dims.get(3).copied().unwrap_or(300.0),
        );
        body.push_str(&format!(
            "<svg x=\"0\" y=\"{y}\" width=\"{w}\" height=\"{h}\" viewBox=\"{view_box}\">{}",
            &p[start + end + 1..]
        ));
        y += h;
        width = width.max(w);
    }
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{}in\" height=\"{}in\" \
         viewBox=\"0 0 {width} {y}\">{body}</svg>",
        width / 72.0,
        y / 72.0
    )
}

/// Writes the figure to `path` (.svg, .pdf or .png by its extension; atomically).
pub fn write_figure(report: &ArmReport, path: &Path) -> Result<PathBuf, Error> {
    let svg = arm_svg(report, 504.0).map_err(|message| Error::Plot {
        path: path.to_path_buf(),
        message,
    })?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    let bytes = match ext.as_str() {
        "svg" => svg.into_bytes(),
        "pdf" => crate::plots::page::svg_to_pdf(&svg).map_err(|message| Error::Plot {
            path: path.to_path_buf(),
            message,
        })?,
        "png" => crate::plots::page::svg_to_png(&svg, 200.0).map_err(|message| Error::Plot {
            path: path.to_path_buf(),
            message,
        })?,
        _ => {
            return Err(Error::InvalidArgument {
                arg: "--figure".into(),
                value: path.display().to_string(),
                allowed: "a file name ending in .svg, .pdf or .png".into(),
            });
        }
    };
    crate::shared::output::write_atomic(path, &bytes)?;
    Ok(path.to_path_buf())
}
