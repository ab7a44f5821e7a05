//! Log–log work–precision figures: error against run time, one panel per group of methods (on
//! one error scale when the panels are compared; each with its own run-time decades), each
//! series in its own colour and marker, the legend below each panel.

use plotters::coord::Shift;
use plotters::coord::combinators::{IntoLogRange, LogCoord, WithKeyPoints};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, LABEL_PT, PALETTE, TICK_PT, TITLE_PT, err, font, px, render, sci_label, stroke,
    text, wrap,
};

/// One method: its label and its `(run time [s], error)` points.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// `(seconds, error)` points in the order of the setting varied.
    pub points: Vec<(f64, f64)>,
}

/// One panel: a title and its series.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Title above the panel.
    pub title: String,
    /// Series, each drawn in the next colour and marker.
    pub series: Vec<Series>,
    /// A line written under the legend.
    pub note: Option<String>,
}

/// Height of the plotting part of a panel \[pt\].
const PLOT_HEIGHT: u32 = 175;
/// Height of a line of the figure title \[pt\].
const TITLE_LINE: u32 = 12;
/// Height of one legend line \[pt\].
const LEGEND_LINE: u32 = 10;
/// Narrowest panel \[pt\].
const MIN_PANEL_W: f64 = 240.0;
/// Left edge of the legend and the room of its samples \[pt\].
const LEGEND_X: i32 = 8;
const LEGEND_SAMPLE: i32 = 20;

/// The marker shapes, cycled with a period (5) prime to the palette's (7); filled for the first
/// five series of a panel, hollow for the next five.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Marker {
    Circle,
    Square,
    Triangle,
    Diamond,
    Cross,
}

const MARKERS: [Marker; 5] = [
    Marker::Circle,
    Marker::Square,
    Marker::Triangle,
    Marker::Diamond,
    Marker::Cross,
];

/// Colour, marker and whether the marker is filled, of the `i`-th series of a panel.
pub(super) fn style(i: usize) -> (RGBColor, Marker, bool) {
    (
        PALETTE[i % PALETTE.len()],
        MARKERS[i % MARKERS.len()],
        (i / MARKERS.len()).is_multiple_of(2),
    )
}

/// The legend of `panel` in a panel `width_pt` wide: per series its label's lines, then the
/// note's lines.
fn legend_lines(panel: &Panel, width_pt: f64) -> (Vec<Vec<String>>, Vec<String>) {
    let room = width_pt - f64::from(LEGEND_X + LEGEND_SAMPLE) - 4.0;
    let series = panel
        .series
        .iter()
        .map(|s| wrap(&s.label, room, TICK_PT))
        .collect();
    let note = panel.note.as_ref().map_or_else(Vec::new, |n| {
        wrap(n, width_pt - f64::from(LEGEND_X) - 4.0, TICK_PT)
    });
    (series, note)
}

/// A work–precision figure titled `title`, errors labelled `y_desc`, one panel per entry (in as
/// many columns as the printed width `width_pt` \[pt\] holds), all on one error scale if
/// `share_y`.
pub fn work_precision_svg(
    title: &str,
    y_desc: &str,
    panels: &[Panel],
    share_y: bool,
    width_pt: f64,
) -> Result<String, String> {
    let (_, shared_y) = decade_ranges(panels);
    let count = panels.len().max(1);
    let cols = ((width_pt / MIN_PANEL_W).floor() as usize).clamp(1, count);
    let rows = count.div_ceil(cols);
    let panel_w = width_pt / cols as f64;
    let legend_rows = panels
        .iter()
        .map(|p| {
            let (series, note) = legend_lines(p, panel_w);
            series.iter().map(Vec::len).sum::<usize>() + note.len()
        })
        .max()
        .unwrap_or(0) as u32;
    let legend_height = 6 + LEGEND_LINE * legend_rows;
    let title_lines = wrap(title, width_pt - 8.0, TITLE_PT);
    let header = TITLE_LINE * title_lines.len() as u32 + 4;
    // panels stacked in one column are flattened to stay within a page's column
    let plot_h = super::page::fitted_chart_height(PLOT_HEIGHT, rows, header, legend_height, 120);
    let panel_h = plot_h + legend_height;
    let size = (width_pt.round() as u32, header + panel_h * rows as u32);
    render(size, |root| {
        let (head, body) = root.split_vertically(px(header as i32));
        let (w, _) = head.dim_in_pixel();
        for (i, line) in title_lines.iter().enumerate() {
            head.draw(&Text::new(
                line.clone(),
                (w as i32 / 2, px(2 + (TITLE_LINE * i as u32) as i32)),
                text(TITLE_PT, BLACK, HPos::Center, VPos::Top),
            ))
            .map_err(err)?;
        }
        for (area, panel) in body.split_evenly((rows, cols)).iter().zip(panels) {
            let (plot, legend) = area.split_vertically(px(plot_h as i32));
            let (x_range, own_y) = decade_ranges(std::slice::from_ref(panel));
            let y_range = if share_y { shared_y } else { own_y };
            draw_panel(&plot, panel, y_desc, (x_range, y_range))?;
            draw_legend(&legend, panel, panel_w)?;
        }
        Ok(())
    })
}

/// The points that can be drawn on log axes (positive, finite).
fn plottable(points: &[(f64, f64)]) -> impl Iterator<Item = (f64, f64)> + '_ {
    points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
}

/// Whole decades enclosing every point of every panel, as (x, y) exponent ranges.
fn decade_ranges(panels: &[Panel]) -> ((i32, i32), (i32, i32)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for (x, y) in panels
        .iter()
        .flat_map(|p| &p.series)
        .flat_map(|s| plottable(&s.points))
    {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if x0 > x1 {
        return ((-6, 0), (-12, 0));
    }
    let decades = |lo: f64, hi: f64| {
        // A marker's width of room (about 5 % of a decade) between a point and the frame.
        let a = (lo / 1.12).log10().floor() as i32;
        let b = (hi * 1.12).log10().ceil() as i32;
        (a, b.max(a + 1))
    };
    (decades(x0, x1), decades(y0, y1))
}

/// Decade ticks from 10^`a` to 10^`b`, every decade or every other one when there are many;
/// 1, 2 and 5 × 10^`a` and 10^`b` over a single decade.
fn decade_ticks((a, b): (i32, i32)) -> Vec<f64> {
    if b - a == 1 {
        let decade = 10f64.powi(a);
        return vec![decade, 2.0 * decade, 5.0 * decade, 10.0 * decade];
    }
    let every = if b - a > 8 { 2 } else { 1 };
    (a..=b)
        .filter(|e| (e - a) % every == 0)
        .map(|e| 10f64.powi(e))
        .collect()
}

pub(super) type Axis = WithKeyPoints<LogCoord<f64>>;

/// A log axis over whole decades with decade ticks.
pub(super) fn log_axis((a, b): (i32, i32)) -> Axis {
    (10f64.powi(a)..10f64.powi(b))
        .log_scale()
        .with_key_points(decade_ticks((a, b)))
}

fn draw_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &Panel,
    y_desc: &str,
    (x_range, y_range): ((i32, i32), (i32, i32)),
) -> Result<(), String> {
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, font(LABEL_PT))
        .margin(px(3))
        .margin_right(px(14))
        .x_label_area_size(px(28))
        .y_label_area_size(px(40))
        .build_cartesian_2d(log_axis(x_range), log_axis(y_range))
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .bold_line_style(stroke(GRID, 0.75))
        .axis_style(stroke(BLACK, 0.75))
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .x_desc("median run time [s]")
        .y_desc(y_desc)
        .x_label_formatter(&|v| sci_label(*v))
        .y_label_formatter(&|v| sci_label(*v))
        .draw()
        .map_err(err)?;
    let plotting = chart.plotting_area().strip_coord_spec();
    let origin = plotting.get_base_pixel();
    for (i, series) in panel.series.iter().enumerate() {
        let (colour, marker, filled) = style(i);
        let points: Vec<(f64, f64)> = plottable(&series.points).collect();
        if points.len() > 1 {
            chart
                .draw_series(LineSeries::new(points.clone(), stroke(colour, 1.0)))
                .map_err(err)?;
        }
        for p in &points {
            let (x, y) = chart.backend_coord(p);
            draw_marker(
                &plotting,
                (x - origin.0, y - origin.1),
                marker,
                (colour, filled),
            )?;
        }
    }
    Ok(())
}

/// A marker of `kind` centred at pixel `(x, y)` of `area`, filled or hollow (white inside).
pub(super) fn draw_marker(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    kind: Marker,
    (colour, filled): (RGBColor, bool),
) -> Result<(), String> {
    if !filled && kind != Marker::Cross {
        draw_shape(area, (x, y), kind, colour, 11)?;
        return draw_shape(area, (x, y), kind, WHITE, 6);
    }
    draw_shape(area, (x, y), kind, colour, 9)
}

/// A filled marker shape of `kind` and size `r` (drawing pixels) at `(x, y)`.
fn draw_shape(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    kind: Marker,
    colour: RGBColor,
    r: i32,
) -> Result<(), String> {
    let fill = colour.filled();
    let e = r / 4;
    match kind {
        Marker::Circle => area.draw(&Circle::new((x, y), r, fill)),
        Marker::Square => area.draw(&Rectangle::new(
            [(x - r + e, y - r + e), (x + r - e, y + r - e)],
            fill,
        )),
        Marker::Triangle => area.draw(&Polygon::new(
            vec![(x, y - r - e), (x - r, y + r - e), (x + r, y + r - e)],
            fill,
        )),
        Marker::Diamond => area.draw(&Polygon::new(
            vec![(x, y - r - e), (x + r, y), (x, y + r + e), (x - r, y)],
            fill,
        )),
        Marker::Cross => {
            let s = stroke(colour, 1.0);
            area.draw(&PathElement::new(vec![(x - r, y - r), (x + r, y + r)], s))
                .map_err(err)?;
            area.draw(&PathElement::new(vec![(x - r, y + r), (x + r, y - r)], s))
        }
    }
    .map_err(err)
}

/// The legend under a panel `width_pt` wide: per series its line and marker and its label
/// (wrapped), then the note.
fn draw_legend(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &Panel,
    width_pt: f64,
) -> Result<(), String> {
    let (series_lines, note) = legend_lines(panel, width_pt);
    let x = px(LEGEND_X);
    let line_y = |i: usize| px(4 + (LEGEND_LINE * i as u32) as i32 + LEGEND_LINE as i32 / 2);
    let mut row = 0;
    for (i, (s, lines)) in panel.series.iter().zip(&series_lines).enumerate() {
        let (colour, marker, filled) = style(i);
        let y = line_y(row);
        if plottable(&s.points).count() > 1 {
            area.draw(&PathElement::new(
                vec![(x, y), (x + px(14), y)],
                stroke(colour, 1.0),
            ))
            .map_err(err)?;
        }
        draw_marker(area, (x + px(7), y), marker, (colour, filled))?;
        for line in lines {
            area.draw(&Text::new(
                line.clone(),
                (x + px(LEGEND_SAMPLE), line_y(row)),
                text(TICK_PT, BLACK, HPos::Left, VPos::Center),
            ))
            .map_err(err)?;
            row += 1;
        }
    }
    for line in note {
        area.draw(&Text::new(
            line,
            (x, line_y(row)),
            text(TICK_PT, GREY, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
        row += 1;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_span_whole_decades_around_every_point() {
        let panels = [Panel {
            title: "t".into(),
            note: None,
            series: vec![Series {
                label: "s".into(),
                points: vec![(3e-6, 2e-14), (1.2e-4, 1e-6), (1.0, 0.0), (f64::NAN, 1.0)],
            }],
        }];
        assert_eq!(decade_ranges(&panels), ((-6, -3), (-14, -5)));
        assert_eq!(decade_ticks((-12, -4)).len(), 9);
        assert_eq!(decade_ticks((-16, -4)).len(), 7);
        assert_eq!(decade_ticks((-6, -5)).len(), 4);
    }

    #[test]
    fn the_series_of_a_panel_differ_in_colour_or_marker() {
        let styles: Vec<_> = (0..12).map(style).collect();
        for (i, a) in styles.iter().enumerate() {
            for b in &styles[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert_ne!(style(0).0, style(1).0);
    }

    /// The bench's figure at one column: three panels of four series and a note, as
    /// bench_lumped.svg, stacked and flattened to fit a page's column (at most 9 in tall).
    #[test]
    fn three_stacked_panels_fit_a_page_column() {
        let series = |i: usize| Series {
            label: format!("indentation state, n = {}", 1 + i % 2),
            points: (0..6)
                .map(|k| (1e-6 * 10f64.powi(k), 1e-14 * 100f64.powi(k)))
                .collect(),
        };
        let panels: Vec<Panel> = (0..3)
            .map(|p| Panel {
                title: format!("({}) a panel, k_δ = 10⁸ N/m", ['a', 'b', 'c'][p]),
                note: Some("scipy peer not run (no numpy and scipy in FLEXRIG_PYTHON)".into()),
                series: (0..4).map(series).collect(),
            })
            .collect();
        let svg = work_precision_svg(
            "Work–precision, lumped impact (m_h = 4 kg, n = 1, 2): peak force against the exact solution",
            "relative error of f_max",
            &panels,
            false,
            252.0,
        )
        .unwrap();
        let h = crate::plots::inspect::printed_height(&svg).unwrap();
        assert!(h <= 9.0 + 1e-9, "{h} in");
        assert!(crate::plots::inspect::min_text_pt(&svg).unwrap() >= 8.0 - 1e-3);
    }
}
