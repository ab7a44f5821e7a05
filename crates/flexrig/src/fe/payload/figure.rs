//! `flexrig payload`'s figure: (a) the peak force of CJ and CL over the payload m_e, (b) their
//! ratio CL/CJ with the line CL = CJ, both on a log payload axis, with the paper's two payloads
//! (100 g and 412 g) marked where they fall in the range.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::PayloadRow;
use crate::plots::{
    GREY, GRID, LABEL_PT, Linear, PALETTE, TICK_PT, TITLE_PT, err, font, nice_step, px, render,
    stroke, text, ticks, wrap,
};

/// Figures narrower than this stack panel (b) under (a) \[pt\].
const STACK_BELOW: f64 = 420.0;
/// Height of a panel \[pt\].
const PANEL_H: u32 = 190;
/// The paper's payloads \[kg\]: the light load (Fig. 9b) and the test bed's.
const PAPER_PAYLOADS: [(f64, &str); 2] = [(0.1, "light load"), (0.412, "test bed")];
/// Line spacing of the test bed's two-line label \[pt\].
const LINE_PT: i32 = 9;
/// Depth of the test bed's label under the top of the plot, with 7 points clear below it (the
/// glyphs reach about 2 points below their nominal box) \[pt\].
const TOP_LABEL_PT: i32 = 2 + LINE_PT + TICK_PT as i32 + 7;

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

/// The builder of a panel's chart on `area`: caption, margins and label areas.
fn builder<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: &str,
) -> ChartBuilder<'a, 'b, SVGBackend<'b>> {
    let mut builder = ChartBuilder::on(area);
    builder
        .caption(caption, font(TITLE_PT))
        .margin(px(4))
        .margin_right(px(14))
        .x_label_area_size(px(26))
        .y_label_area_size(px(40));
    builder
}

/// Height of the plotting area of a panel of `size` captioned `caption` \[drawing units\],
/// measured on a scratch drawing of the same size.
fn plot_height(size: (u32, u32), caption: &str) -> Result<i32, String> {
    let mut scratch = String::new();
    let height = {
        let area = SVGBackend::with_string(&mut scratch, size).into_drawing_area();
        let chart = builder(&area, caption)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)
            .map_err(err)?;
        chart.plotting_area().dim_in_pixel().1
    };
    Ok(height as i32)
}

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
    let mut chart = builder(area, caption)
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
        // each name in two short lines right of its line (one line would cross the other
        // payload's line): the light load's at the bottom, the test bed's at the top
        let plotting = chart.plotting_area().strip_coord_spec();
        let origin = plotting.get_base_pixel();
        let light = kg < 0.2;
        let (x, y_px) = chart.backend_coord(&(g, if light { y.0 } else { y.1 }));
        let (x, y_px) = (x - origin.0 + px(2), y_px - origin.1);
        let lines = if light {
            vec![
                (name.to_string(), VPos::Bottom, -px(2 + LINE_PT)),
                (format!("{g} g"), VPos::Bottom, -px(2)),
            ]
        } else {
            vec![
                (name.to_string(), VPos::Top, px(2)),
                (format!("{g} g"), VPos::Top, px(2 + LINE_PT)),
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

/// The y range of the ratio panel, whose plotting area is `plot_h` drawing units high: the
/// ratios and 1 (the line CL = CJ) with a tenth of their span below and two tenths above, and,
/// when the test bed's payload is in the range, room above them for its label hanging from the
/// top ([`TOP_LABEL_PT`]).
fn ratio_range(rows: &[PayloadRow], plot_h: i32) -> (f64, f64) {
    let lo = rows.iter().map(|r| r.ratio).fold(1.0, f64::min);
    let hi = rows.iter().map(|r| r.ratio).fold(1.0, f64::max);
    let pad = 0.1 * (hi - lo).max(0.01);
    let bottom = lo - pad;
    let room = f64::from(px(TOP_LABEL_PT)) / f64::from(plot_h.max(1));
    let test_bed_shown = rows
        .first()
        .zip(rows.last())
        .is_some_and(|(a, b)| (a.payload_kg..=b.payload_kg).contains(&PAPER_PAYLOADS[1].0));
    // (top − hi)/(top − bottom) = room
    let clear = if test_bed_shown && room < 0.5 {
        (hi - room * bottom) / (1.0 - room)
    } else {
        hi
    };
    (bottom, (hi + 2.0 * pad).max(clear))
}

fn draw_ratio(area: &DrawingArea<SVGBackend, Shift>, rows: &[PayloadRow]) -> Result<(), String> {
    let caption = "(b) CL/CJ";
    let y = ratio_range(rows, plot_height(area.dim_in_pixel(), caption)?);
    let mut chart = chart(area, rows, caption, y, "peak-force ratio CL/CJ")?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn rows(ratio_at_1kg: f64) -> Vec<PayloadRow> {
        (0..9)
            .map(|i| {
                let m = 0.01 * 10f64.powf(f64::from(i) / 4.0);
                let ratio = 0.6 + (ratio_at_1kg - 0.6) * f64::from(i) / 8.0;
                PayloadRow {
                    payload_kg: m,
                    cj_peak_n: 100.0,
                    cl_peak_n: 100.0 * ratio,
                    ratio,
                }
            })
            .collect()
    }

    /// The test bed's label, hanging TOP_LABEL_PT from the top, stays clear of the line CL = CJ
    /// and of the curve, for ratios below and above 1 and any panel height.
    #[test]
    fn the_test_bed_label_clears_the_line_and_the_curve() {
        for ratio in [0.9, 0.998, 1.05] {
            let rows = rows(ratio);
            for plot_h in [px(100), px(140), px(300)] {
                let (bottom, top) = ratio_range(&rows, plot_h);
                let highest = rows.iter().map(|r| r.ratio).fold(1.0, f64::max);
                let below_top = (top - highest) / (top - bottom) * f64::from(plot_h);
                assert!(
                    below_top >= f64::from(px(TOP_LABEL_PT)) - 1e-6,
                    "ratio {ratio}, height {plot_h}: {below_top} < {}",
                    px(TOP_LABEL_PT)
                );
                assert!(bottom < rows[0].ratio, "{bottom}");
            }
        }
    }
}
