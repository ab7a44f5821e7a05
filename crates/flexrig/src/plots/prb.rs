//! The PRB check's figure: the FE tip path against the PRB circles, on equal axes (a circle
//! looks like one).

use flexrig_beam::prb::{PrbFit, TipPoint};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GRID, LABEL_PT, Linear, PALETTE, TICK_PT, TITLE_PT, err, font, px, render, stroke, text,
    text_width_pt, ticks,
};

/// Axis ranges (a/L, b/L): both in units of the beam length, drawn to the same scale.
const X: (f64, f64) = (0.0, 1.05);
/// The least y range (the FE path may reach higher: the range then grows).
const Y: (f64, f64) = (0.0, 0.9);
/// Room for the axis labels left and below, title and margins \[pt\].
const LEFT: u32 = 48;
const BOTTOM: u32 = 30;
const TOP: u32 = 20;
const RIGHT: u32 = 10;
/// Widest plot \[pt\] (a wider figure keeps the plot at this size, centred).
const MAX_PLOT: f64 = 330.0;

/// FE tip path against the PRB circle of the fitted γ (up to Θ_max, thin beyond) and γ = 2/3, at
/// the printed width `width_pt` \[pt\].
pub fn prb_svg(
    path: &[TipPoint],
    fit: &PrbFit,
    model: &str,
    width_pt: f64,
) -> Result<String, String> {
    let b_max = path
        .iter()
        .map(|p| p.b)
        .filter(|b| b.is_finite())
        .fold(Y.1, f64::max);
    let y_hi = ((b_max * 1.04) / 0.05).ceil() * 0.05;
    let plot_w = (width_pt - f64::from(LEFT + RIGHT)).min(MAX_PLOT);
    // equal scales: the plot's height is its width times the y span over the x span
    let plot_h = plot_w * (y_hi - Y.0) / (X.1 - X.0);
    let chart_w = plot_w + f64::from(LEFT + RIGHT);
    let h = (plot_h + f64::from(TOP + BOTTOM)).round() as u32;
    render((width_pt.round() as u32, h), |root| {
        let offset = ((width_pt - chart_w) / 2.0).max(0.0);
        let area = root.margin(0, 0, px(offset as i32), 0);
        let area = area.shrink((0, 0), (px(chart_w.round() as i32), px(h as i32)));
        let long = format!(
            "Cantilever tip path: FE vs PRB, γ = {:.4}, Θ_max = {:.1}°",
            fit.gamma, fit.theta_max_deg
        );
        let title = if text_width_pt(&long, TITLE_PT) < chart_w - 4.0 {
            long
        } else {
            format!(
                "Tip path: FE vs PRB, γ = {:.4}, Θ_max = {:.1}°",
                fit.gamma, fit.theta_max_deg
            )
        };
        area.draw(&Text::new(
            title,
            (px(chart_w as i32 / 2), px(4)),
            text(TITLE_PT, BLACK, HPos::Center, VPos::Top),
        ))
        .map_err(err)?;
        let mut chart = ChartBuilder::on(&area)
            .margin_top(px(TOP as i32))
            .margin_right(px(RIGHT as i32))
            .x_label_area_size(px(BOTTOM as i32))
            .y_label_area_size(px(LEFT as i32))
            .build_cartesian_2d(
                Linear::new(X.0, X.1, ticks(0.0, 1.0, 0.2)),
                Linear::new(Y.0, y_hi, ticks(0.0, y_hi, 0.2)),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .bold_line_style(stroke(GRID, 0.75))
            .axis_style(stroke(BLACK, 0.75))
            .set_all_tick_mark_size(px(2))
            .label_style(font(TICK_PT))
            .axis_desc_style(font(LABEL_PT))
            .x_desc("a/L (horizontal tip position)")
            .y_desc("b/L (tip deflection)")
            .x_label_formatter(&|v| format!("{v:.1}"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .draw()
            .map_err(err)?;
        let arc = |g: f64, t0: f64, t1: f64| -> Vec<(f64, f64)> {
            (0..=200)
                .map(|i| {
                    let t = t0 + (t1 - t0) * f64::from(i) / 200.0;
                    (1.0 - g + g * t.cos(), g * t.sin())
                })
                .filter(|(x, y)| *y <= y_hi && *x >= X.0)
                .collect()
        };
        let tm = fit.theta_max_deg.to_radians();
        let (blue, orange) = (PALETTE[0], PALETTE[1]);
        chart
            .draw_series(LineSeries::new(arc(fit.gamma, 0.0, tm), stroke(blue, 2.0)))
            .map_err(err)?
            .label(format!("PRB γ = {:.4}, Θ ≤ Θ_max", fit.gamma))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + px(14), y)], stroke(blue, 2.0)));
        chart
            .draw_series(LineSeries::new(arc(fit.gamma, tm, 1.6), stroke(blue, 0.75)))
            .map_err(err)?
            .label("the same beyond Θ_max")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + px(14), y)], stroke(blue, 0.75)));
        chart
            .draw_series(LineSeries::new(
                arc(2.0 / 3.0, 0.0, 1.6),
                stroke(orange, 1.25),
            ))
            .map_err(err)?
            .label("PRB γ = 2/3 (small deflection)")
            .legend(move |(x, y)| {
                PathElement::new([(x, y), (x + px(14), y)], stroke(orange, 1.25))
            });
        chart
            .draw_series(
                path.iter()
                    .step_by(6)
                    .map(|p| Circle::new((p.a, p.b), px(1) + px(1) / 2, BLACK.filled())),
            )
            .map_err(err)?
            .label(format!("{model} FE tip path (PL²/EI up to 30)"))
            .legend(|(x, y)| Circle::new((x + px(7), y), px(1) + px(1) / 2, BLACK.filled()));
        chart
            .configure_series_labels()
            .label_font(font(TICK_PT))
            .legend_area_size(px(20))
            .background_style(WHITE)
            .border_style(stroke(GRID, 0.75))
            .position(SeriesLabelPosition::LowerLeft)
            .margin(px(4))
            .draw()
            .map_err(err)
    })
}
