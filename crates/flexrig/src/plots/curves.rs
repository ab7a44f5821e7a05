//! Curves at the printed width: panels (in as many columns as the width holds) on one x range
//! and one linear y scale, x linear or logarithmic (whole decades), each curve a line with
//! markers in its own colour and marker (as in the work–precision figures), its large-x limit,
//! if given, a dashed line in the same colour, the legend (wrapped to the panel) below each
//! panel, or once below all panels when every panel has the same curves. Optionally the first
//! curve of each panel is a reference drawn as a wide pale band under the others, so that a curve
//! lying on it stays visible. Laid out in points with the figures' text sizes (at least 8 pt).

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, Ranged};
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::page::FigureWidth;
use super::work_precision::{draw_marker, log_axis, style};
use super::{
    GREY, GRID, LABEL_PT, Linear, TICK_PT, TITLE_PT, err, font, nice_step, px, render, sci_label,
    stroke, text, ticks, wrap,
};

/// One curve: legend label, (x, y) points in order, and optionally the limit the curve tends to
/// at large x, drawn as a dashed horizontal line in the curve's colour.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// Legend label.
    pub label: String,
    /// `(x, y)` points in order of x.
    pub points: Vec<(f64, f64)>,
    /// The value the curve tends to at large x, if known.
    pub limit: Option<f64>,
}

/// One panel: a title and its curves.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePanel {
    /// Title above the panel.
    pub title: String,
    /// Curves, each drawn in the next colour and marker.
    pub curves: Vec<Curve>,
}

/// The axes of a curve figure: their labels and whether x is logarithmic.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveAxes<'a> {
    /// Label of the x axis (with its unit).
    pub x_desc: &'a str,
    /// Label of the y axis (with its unit).
    pub y_desc: &'a str,
    /// A logarithmic x axis over whole decades (points at x ≤ 0 are left out), else linear.
    pub x_log: bool,
    /// Markers at every point (for a few computed points; off for a dense time series).
    pub markers: bool,
    /// The first curve of each panel is a reference: drawn as a wide pale band under the other
    /// curves, which are drawn thin on top (a computed curve on its reference stays visible).
    pub reference_band: bool,
}

/// Height of the plotting part of a panel \[pt\].
const PLOT_HEIGHT: u32 = 170;
/// Height of a line of the figure title \[pt\].
const TITLE_LINE: u32 = 12;
/// Height of one legend line \[pt\], and of one whose labels set subscripts (`m_h`: the
/// lowered subscript of one line would touch the next).
const LEGEND_LINE: u32 = 10;
const LEGEND_LINE_SUBSCRIPTED: u32 = 12;

/// The legend's line height \[pt\] for `panels`: taller when a label sets a subscript.
fn legend_line(panels: &[CurvePanel]) -> u32 {
    if panels
        .iter()
        .flat_map(|p| &p.curves)
        .any(|c| super::has_subscript(&c.label))
    {
        LEGEND_LINE_SUBSCRIPTED
    } else {
        LEGEND_LINE
    }
}
/// Narrowest panel \[pt\].
const MIN_PANEL_W: f64 = 240.0;
/// Left edge of the legend and the room of its samples \[pt\].
const LEGEND_X: i32 = 8;
const LEGEND_SAMPLE: i32 = 20;
/// The note under a legend with dashed limits.
const LIMIT_NOTE: &str = "dashed: the limit at large x, in the curve's colour";
/// Width of a reference band \[pt\] and of the curves drawn on it.
const BAND_PT: f64 = 4.0;
const ON_BAND_PT: f64 = 0.8;

/// `colour` blended with white (`fraction` of white), the band of a reference curve.
fn pale(colour: RGBColor, fraction: f64) -> RGBColor {
    let mix = |c: u8| (f64::from(c) + (255.0 - f64::from(c)) * fraction).round() as u8;
    RGBColor(mix(colour.0), mix(colour.1), mix(colour.2))
}

/// How curve `i` is drawn: its colour and line width \[pt\].
fn line_style(i: usize, axes: &CurveAxes) -> (RGBColor, f64) {
    let (colour, _, _) = style(i);
    match (axes.reference_band, i) {
        (true, 0) => (pale(colour, 0.55), BAND_PT),
        (true, _) => (colour, ON_BAND_PT),
        (false, _) => (colour, 1.0),
    }
}

/// Whether every panel has the same curve labels (and the same dashed limits note), so that one
/// legend below all panels serves them all.
fn shared_legend(panels: &[CurvePanel]) -> bool {
    let labels =
        |p: &CurvePanel| -> Vec<String> { p.curves.iter().map(|c| c.label.clone()).collect() };
    panels.len() > 1
        && panels
            .windows(2)
            .all(|w| labels(&w[0]) == labels(&w[1]) && has_limit(&w[0]) == has_limit(&w[1]))
}

/// A curve figure titled `title` with `axes`, one panel per entry, at the printed width
/// `width_pt` \[pt\].
///
/// Points with a non-finite coordinate (or, on a log axis, x ≤ 0) are skipped, as are
/// non-finite limits. The y axis runs from 0 (or a rounded-down negative minimum) to a
/// rounded-up maximum of all points and limits of all panels.
pub fn curves_svg(
    title: &str,
    axes: &CurveAxes,
    panels: &[CurvePanel],
    width_pt: f64,
) -> Result<String, String> {
    let y_axis = YAxis::of(panels, axes.x_log);
    let count = panels.len().max(1);
    let cols = ((width_pt / MIN_PANEL_W).floor() as usize).clamp(1, count);
    let rows = count.div_ceil(cols);
    let panel_w = width_pt / cols as f64;
    let shared = shared_legend(panels);
    let legend_rows = |p: &CurvePanel, w: f64| -> u32 {
        legend_lines(p, w, axes.x_log)
            .iter()
            .map(Vec::len)
            .sum::<usize>() as u32
    };
    let line = legend_line(panels);
    let (panel_legend, shared_height) = if shared {
        let rows = legend_rows(&panels[0], width_pt);
        (0, 6 + line * rows)
    } else {
        let rows = panels
            .iter()
            .map(|p| legend_rows(p, panel_w))
            .max()
            .unwrap_or(0);
        (6 + line * rows, 0)
    };
    let title_lines = wrap(title, width_pt - 8.0, TITLE_PT);
    let header = TITLE_LINE * title_lines.len() as u32 + 4;
    // panels stacked in one column are flattened to stay within a page's column
    let plot_h = super::page::fitted_chart_height(
        PLOT_HEIGHT,
        rows,
        header + shared_height,
        panel_legend,
        120,
    );
    let panel_h = plot_h + panel_legend;
    let size = (
        width_pt.round() as u32,
        header + panel_h * rows as u32 + shared_height,
    );
    render(size, |root| {
        let (head, rest) = root.split_vertically(px(header as i32));
        let (body, foot) = rest.split_vertically(px((panel_h * rows as u32) as i32));
        if shared {
            draw_legend(&foot, &panels[0], width_pt, axes, line)?;
        }
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
            if axes.x_log {
                let decades = x_decades(panels);
                let bounds = (10f64.powi(decades.0), 10f64.powi(decades.1));
                draw_panel(
                    &plot,
                    panel,
                    axes,
                    log_axis(decades),
                    bounds,
                    &y_axis,
                    &|v| sci_label(*v),
                )?;
            } else {
                let x = XLinear::of(panels);
                let axis = Linear::new(x.lo, x.hi, ticks(x.lo, x.hi, x.step));
                draw_panel(&plot, panel, axes, axis, (x.lo, x.hi), &y_axis, &|v| {
                    x.label(*v)
                })?;
            }
            if !shared {
                draw_legend(&legend, panel, panel_w, axes, line)?;
            }
        }
        Ok(())
    })
}

/// [`curves_svg`] with a log x axis at the two-column width (7 in).
pub fn log_x_curves_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    panels: &[CurvePanel],
) -> Result<String, String> {
    curves_svg(
        title,
        &CurveAxes {
            x_desc,
            y_desc,
            x_log: true,
            markers: true,
            reference_band: false,
        },
        panels,
        FigureWidth::TwoColumn.points(),
    )
}

/// The points of `curve` that can be drawn (finite; x > 0 on a log axis).
fn plottable(curve: &Curve, x_log: bool) -> impl Iterator<Item = (f64, f64)> + '_ {
    curve
        .points
        .iter()
        .copied()
        .filter(move |(x, y)| x.is_finite() && y.is_finite() && (!x_log || *x > 0.0))
}

/// The limit of `curve`, if it is given and finite.
fn limit(curve: &Curve) -> Option<f64> {
    curve.limit.filter(|l| l.is_finite())
}

/// Whether a curve of `panel` has a (finite) limit.
fn has_limit(panel: &CurvePanel) -> bool {
    panel.curves.iter().any(|c| limit(c).is_some())
}

/// Exponents of the whole decades enclosing every plottable x of every panel (10⁰ to 10¹ when
/// there is none).
fn x_decades(panels: &[CurvePanel]) -> (i32, i32) {
    let (lo, hi) = x_extent(panels, true);
    if lo > hi {
        return (0, 1);
    }
    // The tolerance keeps an exact power of ten (up to rounding of its logarithm) on the edge.
    let a = (lo.log10() + 1e-9).floor() as i32;
    let b = (hi.log10() - 1e-9).ceil() as i32;
    (a, b.max(a + 1))
}

/// Smallest and largest plottable x (`(MAX, MIN)` when there is none).
fn x_extent(panels: &[CurvePanel], x_log: bool) -> (f64, f64) {
    panels
        .iter()
        .flat_map(|p| &p.curves)
        .flat_map(|c| plottable(c, x_log))
        .fold((f64::MAX, f64::MIN), |(lo, hi), (x, _)| {
            (lo.min(x), hi.max(x))
        })
}

/// The linear x axis: the data's range, its ends rounded out to a tick.
#[derive(Debug, Clone, Copy, PartialEq)]
struct XLinear {
    lo: f64,
    hi: f64,
    step: f64,
}

impl XLinear {
    fn of(panels: &[CurvePanel]) -> Self {
        let (lo, hi) = x_extent(panels, false);
        let (lo, hi) = if lo < hi { (lo, hi) } else { (0.0, 1.0) };
        let step = nice_step(hi - lo, 6);
        Self {
            lo: (lo / step + 1e-9).floor() * step + 0.0,
            hi: (hi / step - 1e-9).ceil() * step,
            step,
        }
    }

    fn label(&self, x: f64) -> String {
        decimal_label(x, self.step)
    }
}

/// `v` with as many decimals as `step` needs (`0` for zero, `m·10ᵏ` for steps of 10⁴ or more).
fn decimal_label(v: f64, step: f64) -> String {
    if v.abs() < 1e-9 * step {
        return "0".into();
    }
    let sign = if v < 0.0 { "−" } else { "" };
    if step >= 1e4 {
        return format!("{sign}{}", sci_label(v.abs()));
    }
    let decimals = (0..=6)
        .find(|d| {
            let scaled = step * 10f64.powi(*d);
            (scaled - scaled.round()).abs() < 1e-6 * scaled
        })
        .unwrap_or(6) as usize;
    format!("{sign}{:.decimals$}", v.abs())
}

/// The shared linear y axis: `lo` to `hi` with ticks every `step`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct YAxis {
    lo: f64,
    hi: f64,
    step: f64,
}

impl YAxis {
    /// From 0 (or a rounded-down negative minimum) to the maximum of every plottable y and limit,
    /// plus 2 % so that nothing lies on the frame, rounded up to a tick; at least [0, 1] when
    /// every value is 0.
    fn of(panels: &[CurvePanel], x_log: bool) -> Self {
        let values = panels.iter().flat_map(|p| &p.curves).flat_map(|c| {
            plottable(c, x_log)
                .map(|(_, y)| y)
                .chain(limit(c))
                .collect::<Vec<_>>()
        });
        let (min, max) = values.fold((0.0f64, 0.0f64), |(lo, hi), y| (lo.min(y), hi.max(y)));
        let (mut top, bottom) = (1.02 * max, 1.02 * min);
        if top - bottom <= 0.0 {
            top = 1.0;
        }
        let step = nice_step(top - bottom, 6);
        let axis = Self {
            // `+ 0.0` turns −0 into 0 (no "-0" tick label).
            lo: (bottom / step).floor() * step + 0.0,
            hi: (top / step).ceil() * step,
            step,
        };
        if [axis.lo, axis.hi, axis.step].iter().all(|v| v.is_finite()) && axis.step > 0.0 {
            axis
        } else {
            Self {
                lo: 0.0,
                hi: 1.0,
                step: 0.2,
            }
        }
    }

    fn ticks(&self) -> Vec<f64> {
        ticks(self.lo, self.hi, self.step)
    }

    fn label(&self, y: f64) -> String {
        decimal_label(y, self.step)
    }
}

#[allow(clippy::too_many_arguments)]
fn draw_panel<X>(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &CurvePanel,
    axes: &CurveAxes,
    x_axis: X,
    (x0, x1): (f64, f64),
    y_axis: &YAxis,
    x_label: &dyn Fn(&f64) -> String,
) -> Result<(), String>
where
    X: Ranged<ValueType = f64, FormatOption = DefaultFormatting>,
{
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, font(LABEL_PT))
        .margin(px(3))
        .margin_right(px(14))
        .x_label_area_size(px(28))
        .y_label_area_size(px(40))
        .build_cartesian_2d(x_axis, Linear::new(y_axis.lo, y_axis.hi, y_axis.ticks()))
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(WHITE)
        .bold_line_style(stroke(GRID, 0.75))
        .axis_style(stroke(BLACK, 0.75))
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .x_desc(axes.x_desc)
        .y_desc(axes.y_desc)
        .x_label_formatter(x_label)
        .y_label_formatter(&|v| y_axis.label(*v))
        .draw()
        .map_err(err)?;
    for (i, curve) in panel.curves.iter().enumerate() {
        let (colour, width) = line_style(i, axes);
        if let Some(l) = limit(curve) {
            chart
                .draw_series(DashedLineSeries::new(
                    [(x0, l), (x1, l)],
                    px(3),
                    px(2),
                    stroke(colour, width),
                ))
                .map_err(err)?;
        }
        let points: Vec<(f64, f64)> = plottable(curve, axes.x_log).collect();
        if points.len() > 1 {
            chart
                .draw_series(LineSeries::new(points, stroke(colour, width)))
                .map_err(err)?;
        }
    }
    if axes.markers {
        // Markers over every line, so that no curve hides another's points.
        let plotting = chart.plotting_area().strip_coord_spec();
        let origin = plotting.get_base_pixel();
        for (i, curve) in panel.curves.iter().enumerate() {
            let (colour, marker, filled) = style(i);
            for p in plottable(curve, axes.x_log) {
                let (x, y) = chart.backend_coord(&p);
                draw_marker(
                    &plotting,
                    (x - origin.0, y - origin.1),
                    marker,
                    (colour, filled),
                )?;
            }
        }
    }
    Ok(())
}

/// The legend of `panel` in a panel `width_pt` wide: per curve its label's lines, then the
/// note on dashed limits (if any), as the last entry.
fn legend_lines(panel: &CurvePanel, width_pt: f64, _x_log: bool) -> Vec<Vec<String>> {
    let room = width_pt - f64::from(LEGEND_X + LEGEND_SAMPLE) - 4.0;
    let mut lines: Vec<Vec<String>> = panel
        .curves
        .iter()
        .map(|c| wrap(&c.label, room, TICK_PT))
        .collect();
    if has_limit(panel) {
        lines.push(wrap(LIMIT_NOTE, room, TICK_PT));
    }
    lines
}

/// The legend under a panel `width_pt` wide, `line` points a line: per curve its line (and
/// marker) and its label (wrapped), then the note on the dashed limits if there are any.
fn draw_legend(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &CurvePanel,
    width_pt: f64,
    axes: &CurveAxes,
    line: u32,
) -> Result<(), String> {
    let entries = legend_lines(panel, width_pt, axes.x_log);
    let x = px(LEGEND_X);
    let line_y = |i: usize| px(4 + (line * i as u32) as i32 + line as i32 / 2);
    let mut row = 0;
    for (i, lines) in entries.iter().enumerate() {
        let y = line_y(row);
        let colour = if i < panel.curves.len() {
            let (_, marker, filled) = style(i);
            let (colour, width) = line_style(i, axes);
            if plottable(&panel.curves[i], axes.x_log).count() > 1 {
                area.draw(&PathElement::new(
                    vec![(x, y), (x + px(14), y)],
                    stroke(colour, width),
                ))
                .map_err(err)?;
            }
            if axes.markers {
                draw_marker(area, (x + px(7), y), marker, (colour, filled))?;
            }
            BLACK
        } else {
            for (a, b) in [(0, 3), (5, 8), (10, 13)] {
                area.draw(&PathElement::new(
                    vec![(x + px(a), y), (x + px(b), y)],
                    stroke(GREY, 1.0),
                ))
                .map_err(err)?;
            }
            GREY
        };
        for label in lines {
            area.draw(&Text::new(
                label.clone(),
                (x + px(LEGEND_SAMPLE), line_y(row)),
                text(TICK_PT, colour, HPos::Left, VPos::Center),
            ))
            .map_err(err)?;
            row += 1;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plots::inspect::{min_text_pt, printed_width, texts};

    /// Two panels of eight curves, x from 10⁻⁶ to 10⁶, y in [0.1, 1.05], with limits.
    fn sample() -> Vec<CurvePanel> {
        let xs: Vec<f64> = (-6..=6).map(|e| 10f64.powi(e)).collect();
        (0..2)
            .map(|p| CurvePanel {
                title: format!("({}) panel {}", ['a', 'b'][p], p + 1),
                curves: (0..8)
                    .map(|i| {
                        let lim = 0.3 + 0.75 * (i as f64 + p as f64) / 8.0;
                        let rate = 10f64.powf(i as f64 - 4.0);
                        Curve {
                            label: format!("curve {} of panel {}, rate 10^{}", i + 1, p + 1, i - 4),
                            points: xs
                                .iter()
                                .map(|x| (*x, 0.1 + (lim - 0.1) * (x * rate) / (1.0 + x * rate)))
                                .collect(),
                            limit: Some(lim),
                        }
                    })
                    .collect(),
            })
            .collect()
    }

    #[test]
    fn two_panels_of_eight_curves_render_at_every_width_with_every_label() {
        let panels = sample();
        for inches in [3.5, 7.0] {
            let axes = CurveAxes {
                x_desc: "x",
                y_desc: "fraction",
                x_log: true,
                markers: true,
                reference_band: false,
            };
            let svg = curves_svg("Saturation curves", &axes, &panels, inches * 72.0).unwrap();
            assert!(svg.contains("Saturation curves"));
            let all = texts(&svg).join("\n");
            for c in panels.iter().flat_map(|p| &p.curves) {
                assert!(all.contains(&c.label), "{} missing", c.label);
            }
            assert!(!svg.contains("NaN"));
            assert!((printed_width(&svg).unwrap().0 - inches).abs() < 1e-9);
            assert!(min_text_pt(&svg).unwrap() >= 8.0 - 1e-3);
        }
        // the default width: two columns
        let svg = log_x_curves_svg("t", "x", "y", &panels).unwrap();
        assert!((printed_width(&svg).unwrap().0 - 7.0).abs() < 1e-9);
    }

    #[test]
    fn a_curve_on_its_reference_band_stays_visible() {
        // the same points twice: the reference a wide pale band drawn first, the curve thin on it
        let points: Vec<(f64, f64)> = (0..50)
            .map(|i| (0.1 * i as f64, (0.3 * i as f64).sin()))
            .collect();
        let panel = CurvePanel {
            title: "on the band".into(),
            curves: vec![
                Curve {
                    label: "reference".into(),
                    points: points.clone(),
                    limit: None,
                },
                Curve {
                    label: "computed".into(),
                    points,
                    limit: None,
                },
            ],
        };
        let axes = CurveAxes {
            x_desc: "t [s]",
            y_desc: "y [m]",
            x_log: false,
            markers: false,
            reference_band: true,
        };
        let svg = curves_svg("band", &axes, &[panel], 504.0).unwrap();
        let hex = |c: RGBColor| format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
        let (colour0, _, _) = style(0);
        let (colour1, _, _) = style(1);
        let width = |pt: f64| (pt * f64::from(crate::plots::SCALE)).round();
        let band = format!(
            "stroke=\"{}\" stroke-width=\"{}\"",
            hex(pale(colour0, 0.55)),
            width(BAND_PT)
        );
        let line = format!(
            "stroke=\"{}\" stroke-width=\"{}\"",
            hex(colour1),
            width(ON_BAND_PT)
        );
        let (b, l) = (svg.find(&band), svg.rfind(&line));
        assert!(b.is_some() && l.is_some(), "{band} / {line} not in\n{svg}");
        // the band's plot line comes before the curve's (the legend's samples follow both)
        assert!(
            svg.find(&band) < svg.find(&line),
            "the band is drawn over the curve"
        );
        assert!(min_text_pt(&svg).unwrap() >= 8.0 - 1e-3);
    }

    #[test]
    fn non_finite_points_and_no_panels_render() {
        let panels = [CurvePanel {
            title: "non-finite".into(),
            curves: vec![Curve {
                label: "with a non-finite point".into(),
                points: vec![
                    (1.0, 0.5),
                    (f64::NAN, 0.7),
                    (10.0, f64::INFINITY),
                    (0.0, 1.0),
                ],
                limit: Some(f64::NAN),
            }],
        }];
        let svg = log_x_curves_svg("t", "x", "y", &panels).unwrap();
        assert!(!svg.contains("NaN"));
        let svg = log_x_curves_svg("empty", "x", "y", &[]).unwrap();
        assert!(svg.contains("empty") && !svg.contains("NaN"));
        let svg = log_x_curves_svg(
            "no curves",
            "x",
            "y",
            &[CurvePanel {
                title: "none".into(),
                curves: Vec::new(),
            }],
        )
        .unwrap();
        assert!(!svg.contains("NaN"));
    }

    #[test]
    fn axes_enclose_the_data() {
        let panels = sample();
        assert_eq!(x_decades(&panels), (-6, 6));
        let y = YAxis::of(&panels, true);
        assert_eq!((y.lo, y.step), (0.0, 0.2));
        assert!((y.hi - 1.2).abs() < 1e-12);
        assert_eq!(y.ticks().len(), 7);
        assert_eq!(y.label(0.4), "0.4");
        assert_eq!(y.label(0.0), "0");
        assert_eq!(y.label(-0.4), "−0.4");
        let small = [CurvePanel {
            title: String::new(),
            curves: vec![Curve {
                label: String::new(),
                points: vec![(3e-3, 0.2), (0.4, 0.5)],
                limit: None,
            }],
        }];
        assert_eq!(x_decades(&small), (-3, 0));
        assert!((YAxis::of(&small, true).hi - 0.6).abs() < 1e-12);
        assert_eq!(x_decades(&[]), (0, 1));
        // a linear x axis from the data's ends, rounded out to a tick
        let x = XLinear::of(&small);
        assert_eq!((x.lo, x.hi), (0.0, 0.4));
        assert_eq!(x.label(0.1), "0.1");
    }

    /// Legend lines whose labels set subscripts (`m_h`) lie 12 pt apart, so that a lowered
    /// subscript (80 % of 8 pt, set below the baseline) does not reach the next line's text;
    /// labels without subscripts keep 10 pt.
    #[test]
    fn a_legend_with_subscripts_leaves_room_below_each_line() {
        let panel = |labels: [&str; 2]| CurvePanel {
            title: "p".into(),
            curves: labels
                .iter()
                .map(|l| Curve {
                    label: l.to_string(),
                    points: vec![(1.0, 0.5), (10.0, 0.7)],
                    limit: None,
                })
                .collect(),
        };
        let axes = CurveAxes {
            x_desc: "x",
            y_desc: "y",
            x_log: true,
            markers: true,
            reference_band: false,
        };
        // the y of the text element holding `label`, in points
        let y_of = |svg: &str, label: &str| -> f64 {
            let at = svg.find(label).expect("the label is drawn");
            let start = svg[..at].rfind("<text").expect("in a text element");
            let y = svg[start..].find(" y=\"").expect("with a y") + start + 4;
            let end = y + svg[y..].find('"').unwrap();
            svg[y..end].parse::<f64>().unwrap() / f64::from(super::super::SCALE)
        };
        for (labels, gap) in [
            (["m_h = 4 kg", "m_h = 1000 kg"], 12.0),
            (["first", "second"], 10.0),
        ] {
            let svg = curves_svg("t", &axes, &[panel(labels)], 252.0).unwrap();
            // the subscripts written back as `_h`
            let mut svg = svg.replace("</tspan>", "");
            while let Some(at) = svg.find("<tspan baseline-shift=\"sub\"") {
                let end = at + svg[at..].find('>').unwrap();
                svg.replace_range(at..=end, "_");
            }
            let d = y_of(&svg, labels[1]) - y_of(&svg, labels[0]);
            assert!((d - gap).abs() < 0.5, "{labels:?}: {d} pt apart");
        }
    }
}
