//! Curves against a log x axis: panels side by side on one x range (whole decades) and one
//! linear y scale from 0, each curve a line with markers in its own colour and marker (as in the
//! work–precision figures), its large-x limit, if given, a dashed line in the same colour, the
//! legend below each panel.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::work_precision::{Axis, draw_marker, log_axis, style};
use super::{GREY, GRID, Linear, err, font, nice_step, px, render, sci_label, stroke, text, ticks};

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

/// Height of the plotting part of a panel [px].
const PLOT_HEIGHT: u32 = 400;
/// Height of the figure title [px].
const HEADER: u32 = 34;
/// Height of one legend entry [px].
const LEGEND_LINE: u32 = 17;
/// Left edge of a legend column, from the column's left edge [px].
const LEGEND_INSET: i32 = 24;
/// Room of a legend entry's line-and-marker sample, up to its label [px].
const LEGEND_SAMPLE: i32 = 36;
/// Estimated mean glyph width of the 12-pixel legend text [px] (DejaVu Sans: about 0.6 of the
/// font size, which plotters writes as size / 1.24).
const LEGEND_GLYPH: f64 = 0.6 * 12.0 / 1.24;

/// Panels side by side: x on a log axis (whole decades enclosing every positive finite x), y on
/// a linear axis from 0 to a rounded-up maximum of all y and limits of all panels (shared y
/// range; at least [0, 1]); each curve a line with markers in its colour/marker style, its limit
/// dashed; legend under each panel; `title` on top.
///
/// Points with a non-finite coordinate or x ≤ 0 are skipped, as are non-finite limits. Should
/// any y or limit be negative, the y axis reaches down to a rounded-down minimum instead of 0.
pub fn log_x_curves_svg(
    title: &str,
    x_desc: &str,
    y_desc: &str,
    panels: &[CurvePanel],
) -> Result<String, String> {
    let x_range = x_decades(panels);
    let y_axis = YAxis::of(panels);
    let count = panels.len().max(1) as u32;
    let panel_width = if count >= 3 { 440 } else { 560 };
    let legend_rows = panels
        .iter()
        .map(|p| legend_layout(p, panel_width).1 + usize::from(has_limit(p)))
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
            draw_panel(&plot, panel, (x_desc, y_desc), x_range, &y_axis)?;
            draw_legend(&legend, panel, panel_width)?;
        }
        Ok(())
    })
}

/// The points of `curve` that can be drawn (finite, x > 0).
fn plottable(curve: &Curve) -> impl Iterator<Item = (f64, f64)> + '_ {
    curve
        .points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0)
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
    let (lo, hi) = panels
        .iter()
        .flat_map(|p| &p.curves)
        .flat_map(plottable)
        .fold((f64::MAX, f64::MIN), |(lo, hi), (x, _)| {
            (lo.min(x), hi.max(x))
        });
    if lo > hi {
        return (0, 1);
    }
    // The tolerance keeps an exact power of ten (up to rounding of its logarithm) on the edge.
    let a = (lo.log10() + 1e-9).floor() as i32;
    let b = (hi.log10() - 1e-9).ceil() as i32;
    (a, b.max(a + 1))
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
    /// plus 2 % so that nothing lies on the frame, rounded up to a tick; at least [0, 1].
    fn of(panels: &[CurvePanel]) -> Self {
        let values = panels.iter().flat_map(|p| &p.curves).flat_map(|c| {
            plottable(c)
                .map(|(_, y)| y)
                .chain(limit(c))
                .collect::<Vec<_>>()
        });
        let (min, max) = values.fold((0.0f64, 0.0f64), |(lo, hi), y| (lo.min(y), hi.max(y)));
        let (top, bottom) = ((1.02 * max).max(1.0), 1.02 * min);
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

    /// Tick label of `y`: as many decimals as the step needs, or `m·10ᵏ` for large steps.
    fn label(&self, y: f64) -> String {
        if y.abs() < 1e-9 * self.step {
            return "0".into();
        }
        if self.step >= 1e4 {
            let sign = if y < 0.0 { "−" } else { "" };
            return format!("{sign}{}", sci_label(y.abs()));
        }
        let decimals = (0..=6)
            .find(|d| {
                let scaled = self.step * 10f64.powi(*d);
                (scaled - scaled.round()).abs() < 1e-6 * scaled
            })
            .unwrap_or(6) as usize;
        format!("{y:.decimals$}")
    }
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Axis, Linear>>;

fn draw_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &CurvePanel,
    (x_desc, y_desc): (&str, &str),
    x_range: (i32, i32),
    y_axis: &YAxis,
) -> Result<(), String> {
    let mut chart: Chart = ChartBuilder::on(area)
        .caption(&panel.title, font(14.0))
        .margin(px(8))
        .margin_right(px(18))
        .x_label_area_size(px(44))
        .y_label_area_size(px(62))
        .build_cartesian_2d(
            log_axis(x_range),
            Linear::new(y_axis.lo, y_axis.hi, y_axis.ticks()),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .bold_line_style(stroke(GRID, 1.0))
        .axis_style(stroke(BLACK, 1.0))
        .set_all_tick_mark_size(px(4))
        .label_style(font(13.0))
        .axis_desc_style(font(14.0))
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&|v| sci_label(*v))
        .y_label_formatter(&|v| y_axis.label(*v))
        .draw()
        .map_err(err)?;
    let (x0, x1) = (10f64.powi(x_range.0), 10f64.powi(x_range.1));
    for (i, curve) in panel.curves.iter().enumerate() {
        let (colour, _, _) = style(i);
        if let Some(l) = limit(curve) {
            chart
                .draw_series(DashedLineSeries::new(
                    [(x0, l), (x1, l)],
                    px(6),
                    px(4),
                    stroke(colour, 1.5),
                ))
                .map_err(err)?;
        }
        let points: Vec<(f64, f64)> = plottable(curve).collect();
        if points.len() > 1 {
            chart
                .draw_series(LineSeries::new(points, stroke(colour, 1.5)))
                .map_err(err)?;
        }
    }
    // Markers over every line, so that no curve hides another's points.
    let plotting = chart.plotting_area().strip_coord_spec();
    let origin = plotting.get_base_pixel();
    for (i, curve) in panel.curves.iter().enumerate() {
        let (colour, marker, filled) = style(i);
        for p in plottable(curve) {
            let (x, y) = chart.backend_coord(&p);
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

/// Columns and rows of the legend of `panel` in a panel `panel_width` wide: two columns for
/// more than four curves if every label fits in half the width.
fn legend_layout(panel: &CurvePanel, panel_width: u32) -> (usize, usize) {
    let n = panel.curves.len();
    let longest = panel
        .curves
        .iter()
        .map(|c| c.label.chars().count())
        .max()
        .unwrap_or(0);
    let room = f64::from(panel_width as i32 / 2 - LEGEND_INSET - LEGEND_SAMPLE - 12);
    let columns = if n > 4 && longest as f64 * LEGEND_GLYPH <= room {
        2
    } else {
        1
    };
    (columns, n.div_ceil(columns))
}

/// The legend under a panel: one entry per curve with its line and marker (down the first
/// column, then the second), then a note on the dashed limits if there are any.
fn draw_legend(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &CurvePanel,
    panel_width: u32,
) -> Result<(), String> {
    let (_, rows) = legend_layout(panel, panel_width);
    let column_x = |c: usize| px(LEGEND_INSET + (panel_width as i32 / 2) * c as i32);
    let line_y = |r: usize| px(10 + (LEGEND_LINE * r as u32) as i32 + LEGEND_LINE as i32 / 2);
    for (i, curve) in panel.curves.iter().enumerate() {
        let (colour, marker, filled) = style(i);
        let (x, y) = (column_x(i / rows.max(1)), line_y(i % rows.max(1)));
        if plottable(curve).count() > 1 {
            area.draw(&PathElement::new(
                vec![(x, y), (x + px(26), y)],
                stroke(colour, 1.5),
            ))
            .map_err(err)?;
        }
        draw_marker(area, (x + px(13), y), marker, (colour, filled))?;
        area.draw(&Text::new(
            curve.label.clone(),
            (x + px(LEGEND_SAMPLE), y),
            text(12.0, BLACK, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
    }
    if has_limit(panel) {
        let (x, y) = (column_x(0), line_y(rows));
        for (a, b) in [(0, 6), (10, 16), (20, 26)] {
            area.draw(&PathElement::new(
                vec![(x + px(a), y), (x + px(b), y)],
                stroke(GREY, 1.5),
            ))
            .map_err(err)?;
        }
        area.draw(&Text::new(
            "dashed: the limit at large x, in the curve's colour",
            (x + px(LEGEND_SAMPLE), y),
            text(12.0, GREY, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn two_panels_of_eight_curves_render_with_every_label() {
        let panels = sample();
        let svg = log_x_curves_svg("Saturation curves", "x", "fraction", &panels).unwrap();
        assert!(!svg.is_empty());
        assert!(svg.contains("Saturation curves"));
        for c in panels.iter().flat_map(|p| &p.curves) {
            assert!(svg.contains(&c.label), "{} missing", c.label);
        }
        assert!(!svg.contains("NaN"));
        if std::env::var_os("CURVES_SAMPLE").is_some() {
            std::fs::write("/tmp/curves_sample.svg", &svg).unwrap();
        }
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
        let y = YAxis::of(&panels);
        assert_eq!((y.lo, y.step), (0.0, 0.2));
        assert!((y.hi - 1.2).abs() < 1e-12);
        assert_eq!(y.ticks().len(), 7);
        assert_eq!(y.label(0.4), "0.4");
        assert_eq!(y.label(0.0), "0");
        let small = [CurvePanel {
            title: String::new(),
            curves: vec![Curve {
                label: String::new(),
                points: vec![(3e-3, 0.2), (0.4, 0.5)],
                limit: None,
            }],
        }];
        assert_eq!(x_decades(&small), (-3, 0));
        assert_eq!(YAxis::of(&small).hi, 1.0);
        assert_eq!(x_decades(&[]), (0, 1));
    }
}
