//! Log–log work–precision figures: error against run time, one panel per group of methods (on
//! one error scale when the panels are compared; each with its own run-time decades), each
//! series in its own colour and marker, the legend below each panel.

use plotters::coord::Shift;
use plotters::coord::combinators::{IntoLogRange, LogCoord, WithKeyPoints};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::{GREY, GRID, PALETTE, err, font, px, render, sci_label, stroke, text};

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

/// Height of the plotting part of a panel [px].
const PLOT_HEIGHT: u32 = 400;
/// Height of the figure title [px].
const HEADER: u32 = 34;
/// Height of one legend entry [px].
const LEGEND_LINE: u32 = 17;

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

/// A work–precision figure titled `title`, errors labelled `y_desc`, one panel per entry, all
/// on one error scale if `share_y`.
pub fn work_precision_svg(
    title: &str,
    y_desc: &str,
    panels: &[Panel],
    share_y: bool,
) -> Result<String, String> {
    let (_, shared_y) = decade_ranges(panels);
    let count = panels.len().max(1) as u32;
    let panel_width = if count >= 3 { 440 } else { 560 };
    let legend_rows = panels
        .iter()
        .map(|p| p.series.len() + usize::from(p.note.is_some()))
        .max()
        .unwrap_or(0) as u32;
    let legend_height = 16 + LEGEND_LINE * legend_rows;
    let size = (panel_width * count, HEADER + PLOT_HEIGHT + legend_height);
    render(size, |root| {
        let (header, body) = root.split_vertically(px(HEADER as i32));
        let (w, _) = header.dim_in_pixel();
        header
            .draw(&Text::new(
                title.to_string(),
                (w as i32 / 2, px(8)),
                text(16.0, BLACK, HPos::Center, VPos::Top),
            ))
            .map_err(err)?;
        for (area, panel) in body.split_evenly((1, count as usize)).iter().zip(panels) {
            let (plot, legend) = area.split_vertically(px(PLOT_HEIGHT as i32));
            let (x_range, own_y) = decade_ranges(std::slice::from_ref(panel));
            let y_range = if share_y { shared_y } else { own_y };
            draw_panel(&plot, panel, y_desc, (x_range, y_range))?;
            draw_legend(&legend, panel)?;
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
        .caption(&panel.title, font(14.0))
        .margin(px(8))
        .margin_right(px(18))
        .x_label_area_size(px(44))
        .y_label_area_size(px(62))
        .build_cartesian_2d(log_axis(x_range), log_axis(y_range))
        .map_err(err)?;
    chart
        .configure_mesh()
        .bold_line_style(stroke(GRID, 1.0))
        .axis_style(stroke(BLACK, 1.0))
        .set_all_tick_mark_size(px(4))
        .label_style(font(13.0))
        .axis_desc_style(font(14.0))
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
                .draw_series(LineSeries::new(points.clone(), stroke(colour, 1.5)))
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
        draw_shape(area, (x, y), kind, colour, px(5))?;
        return draw_shape(area, (x, y), kind, WHITE, px(3));
    }
    draw_shape(area, (x, y), kind, colour, px(4))
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
    match kind {
        Marker::Circle => area.draw(&Circle::new((x, y), r, fill)),
        Marker::Square => area.draw(&Rectangle::new(
            [
                (x - r + px(1), y - r + px(1)),
                (x + r - px(1), y + r - px(1)),
            ],
            fill,
        )),
        Marker::Triangle => area.draw(&Polygon::new(
            vec![
                (x, y - r - px(1)),
                (x - r, y + r - px(1)),
                (x + r, y + r - px(1)),
            ],
            fill,
        )),
        Marker::Diamond => area.draw(&Polygon::new(
            vec![
                (x, y - r - px(1)),
                (x + r, y),
                (x, y + r + px(1)),
                (x - r, y),
            ],
            fill,
        )),
        Marker::Cross => {
            let s = stroke(colour, 2.0);
            area.draw(&PathElement::new(vec![(x - r, y - r), (x + r, y + r)], s))
                .map_err(err)?;
            area.draw(&PathElement::new(vec![(x - r, y + r), (x + r, y - r)], s))
        }
    }
    .map_err(err)
}

/// The legend under a panel: one line per series with its line and marker, then the note.
fn draw_legend(area: &DrawingArea<SVGBackend, Shift>, panel: &Panel) -> Result<(), String> {
    let x = px(24);
    let line_y = |i: usize| px(10 + (LEGEND_LINE * i as u32) as i32 + LEGEND_LINE as i32 / 2);
    for (i, s) in panel.series.iter().enumerate() {
        let (colour, marker, filled) = style(i);
        let y = line_y(i);
        if plottable(&s.points).count() > 1 {
            area.draw(&PathElement::new(
                vec![(x, y), (x + px(26), y)],
                stroke(colour, 1.5),
            ))
            .map_err(err)?;
        }
        draw_marker(area, (x + px(13), y), marker, (colour, filled))?;
        area.draw(&Text::new(
            s.label.clone(),
            (x + px(36), y),
            text(12.0, BLACK, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
    }
    if let Some(note) = &panel.note {
        area.draw(&Text::new(
            note.clone(),
            (x, line_y(panel.series.len())),
            text(12.0, GREY, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
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
}
