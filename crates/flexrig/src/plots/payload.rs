//! `flexrig payload`'s figure: (a) the peak force of CJ and CL over the payload m_e, (b) their
//! ratio CL/CJ with the line CL = CJ, both on a log payload axis, with the paper's two payloads
//! (100 g and 412 g) marked where they fall in the range.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, LABEL_PT, Linear, PALETTE, TICK_PT, TITLE_PT, err, font, nice_step, px, render,
    stroke, text, ticks, wrap,
};
use crate::payload::PayloadRow;

/// Figures narrower than this stack panel (b) under (a) \[pt\].
const STACK_BELOW: f64 = 420.0;
/// Height of a panel \[pt\].
const PANEL_H: u32 = 190;
/// The paper's payloads \[kg\]: the light load (Fig. 9b) and the test bed's.
const PAPER_PAYLOADS: [(f64, &str); 2] = [(0.1, "light load"), (0.412, "test bed")];

/// The payload study's figure at the printed width `width_pt` \[pt\]; `operator` names the
/// operator as run (e.g. `skinned aluminium operator, m_h = 398 g`).
pub fn payload_svg(rows: &[PayloadRow], operator: &str, width_pt: f64) -> Result<String, String> {
    if rows.len() < 2 {
        return Err("the payload figure needs at least two payloads".into());
    }
    let stacked = width_pt < STACK_BELOW;
    let title = wrap(&format!("Test bed, {operator}"), width_pt - 8.0, TITLE_PT);
    let head_h = 12 * title.len() as u32 + 4;
    let h = if stacked { 2 * PANEL_H } else { PANEL_H } + head_h;
    render((width_pt.round() as u32, h), |root| {
        let (head, body) = root.split_vertically(px(head_h as i32));
        for (i, line) in title.iter().enumerate() {
            head.draw(&Text::new(
                line.clone(),
                (px(4), px(2 + 12 * i as i32)),
                text(TITLE_PT, BLACK, HPos::Left, VPos::Top),
            ))
            .map_err(err)?;
        }
        let (a, b) = if stacked {
            body.split_vertically(px(PANEL_H as i32))
        } else {
            body.split_horizontally(px((width_pt / 2.0) as i32))
        };
        draw_peaks(&a, rows)?;
        draw_ratio(&b, rows)
    })
}

type LogChart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::combinators::LogCoord<f64>, Linear>,
>;

/// The chart of one panel over the rows' payloads \[g\] with y in `y`.
fn chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    rows: &[PayloadRow],
    caption: &str,
    y: (f64, f64),
    y_desc: &str,
) -> Result<LogChart<'a, 'b>, String> {
    let lo = rows.first().map_or(1.0, |r| r.payload_kg) * 1e3;
    let hi = rows.last().map_or(1e3, |r| r.payload_kg) * 1e3;
    let step = nice_step(y.1 - y.0, 5);
    let first = (y.0 / step - 1e-9).ceil() * step;
    let decimals = (0..6)
        .find(|d| {
            let s = step * 10f64.powi(*d);
            (s - s.round()).abs() < 1e-6
        })
        .unwrap_or(6) as usize;
    let mut chart = ChartBuilder::on(area)
        .caption(caption, font(TITLE_PT))
        .margin(px(4))
        .margin_right(px(14))
        .x_label_area_size(px(26))
        .y_label_area_size(px(40))
        .build_cartesian_2d(
            (lo..hi).log_scale(),
            Linear::new(y.0, y.1, ticks(first, y.1, step)),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .bold_line_style(stroke(GRID, 0.75))
        .axis_style(stroke(BLACK, 0.75))
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .x_desc("payload m_e [g]")
        .y_desc(y_desc)
        .x_labels(6)
        .x_label_formatter(&|v| format!("{v}"))
        .y_label_formatter(&|v| format!("{v:.decimals$}"))
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// The paper's payloads as dashed verticals with their names, where they lie in the range.
fn mark_paper_payloads(
    chart: &mut LogChart,
    rows: &[PayloadRow],
    y: (f64, f64),
) -> Result<(), String> {
    let (lo, hi) = (rows[0].payload_kg, rows[rows.len() - 1].payload_kg);
    for (kg, name) in PAPER_PAYLOADS {
        if kg < lo || kg > hi {
            continue;
        }
        let g = kg * 1e3;
        chart
            .draw_series(DashedLineSeries::new(
                [(g, y.0), (g, y.1)],
                px(3),
                px(2),
                stroke(GREY, 0.75),
            ))
            .map_err(err)?;
        // the light load's name at the bottom right of its line; the test bed's at the top
        // right of its line in two short lines (one line would cross the light load's)
        let plotting = chart.plotting_area().strip_coord_spec();
        let origin = plotting.get_base_pixel();
        let light = kg < 0.2;
        let (x, y_px) = chart.backend_coord(&(g, if light { y.0 } else { y.1 }));
        let (x, y_px) = (x - origin.0 + px(2), y_px - origin.1);
        let lines = if light {
            vec![(format!("{name}, {g} g"), VPos::Bottom, -px(2))]
        } else {
            let step = (TICK_PT * 1.15).round() as i32;
            vec![
                (name.to_string(), VPos::Top, px(2)),
                (format!("{g} g"), VPos::Top, px(2 + step)),
            ]
        };
        for (label, v, dy) in lines {
            plotting
                .draw(&Text::new(
                    label,
                    (x, y_px + dy),
                    text(TICK_PT, GREY, HPos::Left, v),
                ))
                .map_err(err)?;
        }
    }
    Ok(())
}

fn draw_peaks(area: &DrawingArea<SVGBackend, Shift>, rows: &[PayloadRow]) -> Result<(), String> {
    let top = rows
        .iter()
        .flat_map(|r| [r.cj_peak_n, r.cl_peak_n])
        .fold(0.0, f64::max);
    let step = nice_step(top, 5);
    let y = (0.0, (top * 1.15 / step).ceil() * step);
    let mut chart = chart(area, rows, "(a) peak impact force", y, "peak force [N]")?;
    mark_paper_payloads(&mut chart, rows, y)?;
    for (name, colour, get) in [
        (
            "CJ",
            PALETTE[1],
            (|r: &PayloadRow| r.cj_peak_n) as fn(&PayloadRow) -> f64,
        ),
        ("CL", PALETTE[0], |r: &PayloadRow| r.cl_peak_n),
    ] {
        chart
            .draw_series(LineSeries::new(
                rows.iter().map(|r| (r.payload_kg * 1e3, get(r))),
                stroke(colour, 1.5),
            ))
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + px(12), y)], stroke(colour, 1.5)));
    }
    chart
        .configure_series_labels()
        .label_font(font(TICK_PT))
        .legend_area_size(px(16))
        .background_style(WHITE)
        .border_style(stroke(GREY, 0.5))
        .position(SeriesLabelPosition::UpperLeft)
        .margin(px(4))
        .draw()
        .map_err(err)
}

fn draw_ratio(area: &DrawingArea<SVGBackend, Shift>, rows: &[PayloadRow]) -> Result<(), String> {
    let lo = rows.iter().map(|r| r.ratio).fold(1.0, f64::min);
    let hi = rows.iter().map(|r| r.ratio).fold(1.0, f64::max);
    let pad = 0.1 * (hi - lo).max(0.01);
    let y = (lo - pad, hi + 2.0 * pad);
    let mut chart = chart(area, rows, "(b) CL/CJ", y, "peak-force ratio CL/CJ")?;
    mark_paper_payloads(&mut chart, rows, y)?;
    let (x0, x1) = (
        rows[0].payload_kg * 1e3,
        rows[rows.len() - 1].payload_kg * 1e3,
    );
    chart
        .draw_series(DashedLineSeries::new(
            [(x0, 1.0), (x1, 1.0)],
            px(3),
            px(2),
            stroke(GREY, 0.75),
        ))
        .map_err(err)?;
    chart
        .draw_series(std::iter::once(Text::new(
            "CL = CJ",
            // clear of the y axis: a few points into the log payload axis
            (x0 * 1.08, 1.0),
            text(TICK_PT, GREY, HPos::Left, VPos::Bottom),
        )))
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(
            rows.iter().map(|r| (r.payload_kg * 1e3, r.ratio)),
            stroke(BLACK, 1.5),
        ))
        .map_err(err)?;
    chart
        .draw_series(
            rows.iter()
                .map(|r| Circle::new((r.payload_kg * 1e3, r.ratio), px(1), BLACK.filled())),
        )
        .map_err(err)?;
    Ok(())
}
