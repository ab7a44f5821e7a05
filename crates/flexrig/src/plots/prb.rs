//! The PRB check's figure: the FE tip path against the PRB circles.

use flexrig_beam::prb::{PrbFit, TipPoint};
use plotters::prelude::*;

/// FE tip path against the PRB circle of the fitted γ (up to Θ_max, dashed beyond) and γ = 2/3.
pub fn prb_svg(path: &[TipPoint], fit: &PrbFit) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 700)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!(
                    "Cantilever tip path: FE (corotational) vs PRB γ = {:.4} (Θ_max = {:.1}°)",
                    fit.gamma, fit.theta_max_deg
                ),
                ("sans-serif", 18),
            )
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..1.05, 0.0..1.0)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("a/L (horizontal tip position)")
            .y_desc("b/L (tip deflection)")
            .draw()
            .map_err(|e| e.to_string())?;
        let arc = |g: f64, t0: f64, t1: f64| -> Vec<(f64, f64)> {
            (0..=200)
                .map(|i| {
                    let t = t0 + (t1 - t0) * i as f64 / 200.0;
                    (1.0 - g + g * t.cos(), g * t.sin())
                })
                .collect()
        };
        let tm = fit.theta_max_deg.to_radians();
        let blue = RGBColor(31, 119, 180);
        let orange = RGBColor(255, 127, 14);
        chart
            .draw_series(LineSeries::new(
                arc(fit.gamma, 0.0, tm),
                blue.stroke_width(3),
            ))
            .map_err(|e| e.to_string())?
            .label(format!("PRB γ = {:.4}, Θ ≤ Θ_max", fit.gamma))
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], blue.stroke_width(3))
            });
        chart
            .draw_series(LineSeries::new(
                arc(fit.gamma, tm, 1.6),
                blue.stroke_width(1),
            ))
            .map_err(|e| e.to_string())?;
        chart
            .draw_series(LineSeries::new(
                arc(2.0 / 3.0, 0.0, 1.6),
                orange.stroke_width(2),
            ))
            .map_err(|e| e.to_string())?
            .label("PRB γ = 2/3 (small deflection)")
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], orange.stroke_width(2))
            });
        chart
            .draw_series(
                path.iter()
                    .step_by(6)
                    .map(|p| Circle::new((p.a, p.b), 3, BLACK.filled())),
            )
            .map_err(|e| e.to_string())?
            .label("FE tip path (PL²/EI up to 30)")
            .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.filled()));
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerLeft)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
