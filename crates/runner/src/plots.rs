//! SVG figures (plotters), rendered to a string so the caller can write them atomically.

use flexrig_lumped::fig6::{EtaCurve, GAMMA_RANGE};
use plotters::prelude::*;
use plotters::series::DashedLineSeries;

/// Colour of the n = 2 curves (solid), as in the paper.
const BLUE: RGBColor = RGBColor(31, 119, 180);
/// Colour of the n = 1 curves (dashed), as in the paper.
const ORANGE: RGBColor = RGBColor(255, 127, 14);

/// The paper's Fig. 6: one panel per design case, η over γ, n = 2 solid and n = 1 dashed, η(2/3)
/// marked and labelled. `curves` holds both exponents of each case.
pub fn fig6_svg(curves: &[EtaCurve]) -> Result<String, String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (1600, 820)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let (title, body) = root.split_vertically(50);
        title
            .titled(
                "Fig. 6: peak-force ratio η = f_max(γ)/f_max(1) — n = 2 solid, n = 1 dashed (m_r = 10 kg, k_c = 1e8, v0 = 2 m/s)",
                ("sans-serif", 20),
            )
            .map_err(|e| e.to_string())?;
        let panels = body.split_evenly((2, 4));
        let mut cases: Vec<_> = curves.iter().map(|c| c.case).collect();
        cases.dedup();
        for (panel, case) in panels.iter().zip(&cases) {
            let of_case: Vec<&EtaCurve> = curves.iter().filter(|c| c.case == *case).collect();
            let y_min = of_case
                .iter()
                .flat_map(|c| c.eta.iter().copied())
                .fold(1.0, f64::min);
            let y_lo = ((y_min - 0.02) * 20.0).floor() / 20.0;
            let mut chart = ChartBuilder::on(panel)
                .caption(
                    format!(
                        "m_h={} kg, k_δ={:e} N/m, m_e={} kg",
                        case.m_h, case.k_delta, case.m_e
                    ),
                    ("sans-serif", 15),
                )
                .margin(12)
                .x_label_area_size(36)
                .y_label_area_size(48)
                .build_cartesian_2d(GAMMA_RANGE.0..GAMMA_RANGE.1, y_lo..1.01)
                .map_err(|e| e.to_string())?;
            chart
                .configure_mesh()
                .x_desc("γ")
                .y_desc("η")
                .x_labels(6)
                .y_labels(6)
                .draw()
                .map_err(|e| e.to_string())?;
            for c in &of_case {
                let points: Vec<(f64, f64)> =
                    c.gamma.iter().copied().zip(c.eta.iter().copied()).collect();
                let colour = if c.n == 1.0 { ORANGE } else { BLUE };
                let style = colour.stroke_width(2);
                if c.n == 1.0 {
                    chart
                        .draw_series(DashedLineSeries::new(points, 8, 5, style))
                        .map_err(|e| e.to_string())?;
                } else {
                    chart
                        .draw_series(LineSeries::new(points, style))
                        .map_err(|e| e.to_string())?;
                }
                let mark = (2.0 / 3.0, c.eta_at_2_3);
                let label_at = if c.n == 1.0 { (-150, -22) } else { (8, 6) };
                chart
                    .draw_series(std::iter::once(
                        EmptyElement::at(mark)
                            + Circle::new((0, 0), 4, colour.filled())
                            + Text::new(
                                format!("η(2/3)={:.3} (n={})", c.eta_at_2_3, c.n),
                                label_at,
                                ("sans-serif", 13).into_font().color(&colour),
                            ),
                    ))
                    .map_err(|e| e.to_string())?;
            }
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
