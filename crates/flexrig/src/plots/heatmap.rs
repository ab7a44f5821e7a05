//! Heat maps over log–log grids: panels in as many columns as the printed width holds, each a grid of cells coloured by a value on a
//! sequential, diverging or logarithmic colour scale with its own colour bar, cells without a
//! value hatched grey, and an optional thick outline around a region of cells.
//!
//! The cells fill the log-spaced grid: a cell's edges lie at the geometric midpoints between its
//! centre and its neighbours' (extrapolated by half a step at the ends of each axis). Values
//! outside the scale are drawn in the colour of the nearer end; the colour bar then carries a
//! triangle and a "≥"/"≤" label at that end.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::FontTransform;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, LABEL_PT, Linear, TICK_PT, TITLE_PT, decade_label, err, font, nice_step, px, render,
    sci_label, stroke, text,
};

/// One heat map over a log–log grid.
pub struct HeatMap<'a> {
    /// Panel title.
    pub title: &'a str,
    /// Label of the x axis, e.g. `m_e/m_r`.
    pub x_label: &'a str,
    /// Label of the y axis, e.g. `k_δ/k_c`.
    pub y_label: &'a str,
    /// Cell centres along x: ascending, > 0, log-spaced (nx values).
    pub xs: &'a [f64],
    /// Cell centres along y: ascending, > 0, log-spaced (ny values).
    pub ys: &'a [f64],
    /// Row-major values, `values[iy * nx + ix]`; `None` (or NaN) = no value, drawn hatched grey.
    pub values: &'a [Option<f64>],
    /// The colour scale.
    pub scale: ColorScale,
    /// Colour-bar label, e.g. `η_FE`.
    pub value_label: &'a str,
    /// Optional outline: the cells where `mask[iy * nx + ix]` is true get a thick black outline
    /// along the region's boundary (edges between true and false cells, and the grid's edge),
    /// with this legend text.
    pub outline: Option<(&'a [bool], &'a str)>,
}

/// How a value maps to a colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ColorScale {
    /// Sequential (viridis, colour-blind safe) from `lo` to `hi`.
    Sequential {
        /// Value of the dark end.
        lo: f64,
        /// Value of the bright end.
        hi: f64,
    },
    /// Diverging around `centre` (blue below, red above, white at centre), symmetric half-width
    /// `span`.
    Diverging {
        /// Value drawn white.
        centre: f64,
        /// Half-width: `centre ± span` are the ends of the scale.
        span: f64,
    },
    /// Sequential (viridis) over log10 of the value, from `lo` to `hi` (both > 0). Values ≤ 0
    /// are drawn as below `lo`.
    Log {
        /// Value of the dark end (> 0).
        lo: f64,
        /// Value of the bright end (> `lo`).
        hi: f64,
    },
}

/// Narrowest panel \[pt\]: the width holds as many columns of panels as fit.
const MIN_PANEL_W: f64 = 240.0;
/// Height of a panel over its width (without its legend rows).
const PANEL_ASPECT: f64 = 0.85;
/// Tallest figure \[pt\]: what a journal page's column takes ([`super::page::MAX_HEIGHT_IN`]);
/// panels stacked in one column are flattened to fit (down to [`MIN_CHART_H`]).
const MAX_HEIGHT_PT: f64 = super::page::MAX_HEIGHT_IN * 72.0;
/// Flattest chart \[pt\] a panel is drawn with.
const MIN_CHART_H: f64 = 120.0;
/// Height of one row of a named category axis along y \[pt\].
const CATEGORY_ROW: f64 = 14.0;
/// Room under a panel's legend, before the next row of panels \[pt\].
const ROW_GAP: i32 = 6;
/// Height of a line of the figure title \[pt\].
const HEADER_LINE: u32 = 12;
/// Height of a panel's title row \[pt\].
const TITLE: i32 = 14;
/// Height of a legend row \[pt\] (a panel has one per legend item).
const LEGEND: i32 = 12;
/// Width of a panel's colour-bar strip \[pt\].
const BAR_STRIP: i32 = 56;
/// Width of the colour bar \[pt\].
const BAR_WIDTH: i32 = 8;
/// Gap between the plot's top (bottom) and the bar's, room for the clamp triangle \[pt\].
const BAR_INSET: i32 = 7;
/// Fill of the cells without a value.
const NO_VALUE: RGBColor = RGBColor(215, 215, 215);
/// Hatching over the cells without a value.
const HATCH: RGBColor = RGBColor(120, 120, 120);
/// Edge of the legend's "no value" swatch.
const GREY_EDGE: RGBColor = RGBColor(150, 150, 150);
/// Distance between hatching lines \[pt\].
const HATCH_STEP: i32 = 4;
/// Width of the region outline \[pt\].
const OUTLINE: f64 = 1.5;

/// Viridis at nine evenly spaced stops (matplotlib).
const VIRIDIS: [(u8, u8, u8); 9] = [
    (68, 1, 84),
    (72, 40, 120),
    (62, 73, 137),
    (49, 104, 142),
    (38, 130, 142),
    (31, 158, 137),
    (53, 183, 121),
    (110, 206, 88),
    (253, 231, 37),
];

/// Blue–white–red (ColorBrewer RdBu, reversed, with a white centre) at eleven evenly spaced stops.
const BLUE_RED: [(u8, u8, u8); 11] = [
    (5, 48, 97),
    (33, 102, 172),
    (67, 147, 195),
    (146, 197, 222),
    (209, 229, 240),
    (255, 255, 255),
    (253, 219, 199),
    (244, 165, 130),
    (214, 96, 77),
    (178, 24, 43),
    (103, 0, 31),
];

/// Legend rows of `map`: "no value" if a cell has none, and the outline's text.
fn legend_rows(map: &HeatMap<'_>) -> i32 {
    i32::from(map.values.iter().any(|v| v.is_none_or(f64::is_nan)))
        + i32::from(map.outline.is_some())
}

/// Several heat maps in a grid (as many columns as `width_pt` holds at [`MIN_PANEL_W`], each
/// with its own colour bar), under the lines of `figure_title`, at the printed width `width_pt`
/// \[pt\]. Returns SVG text, or what is wrong with the first bad map.
pub fn heatmaps_svg(
    figure_title: &[String],
    maps: &[HeatMap<'_>],
    width_pt: f64,
) -> Result<String, String> {
    heatmaps_svg_named(figure_title, maps, AxisNames::default(), width_pt)
}

/// Category names of the axes of every map (a body-region axis): the axis's centres are the
/// positions 1, 2, …, n, drawn evenly spaced and labelled with the names; `None`: a log axis.
#[derive(Debug, Clone, Copy, Default)]
pub struct AxisNames<'a> {
    /// Names along x (drawn turned by a quarter turn).
    pub x: Option<&'a [String]>,
    /// Names along y.
    pub y: Option<&'a [String]>,
}

/// [`heatmaps_svg`] with category axes `names`.
pub fn heatmaps_svg_named(
    figure_title: &[String],
    maps: &[HeatMap<'_>],
    names: AxisNames<'_>,
    width_pt: f64,
) -> Result<String, String> {
    if maps.is_empty() {
        return Err("no heat maps to draw".into());
    }
    let grids = maps
        .iter()
        .enumerate()
        .map(|(i, m)| {
            Grid::new(m, names).map_err(|e| format!("heat map {} ({}): {e}", i + 1, m.title))
        })
        .collect::<Result<Vec<_>, _>>()?;
    // named y categories: the panel is wider by the names and as tall as the rows need
    let names_w = names.y.map_or(0.0, |n| {
        n.iter()
            .map(|s| super::text_width_pt(s, TICK_PT))
            .fold(0.0, f64::max)
    });
    let cols = ((width_pt / (MIN_PANEL_W + names_w)).floor() as usize).clamp(1, maps.len());
    let rows = maps.len().div_ceil(cols);
    let legend = maps.iter().map(legend_rows).max().unwrap_or(0);
    let panel_w = width_pt / cols as f64;
    let chart_h = match names.y {
        Some(n) => CATEGORY_ROW * n.len() as f64 + 60.0,
        None => panel_w * PANEL_ASPECT,
    };
    // the title's lines are counted first: a stack of panels is flattened so that the figure
    // stays within a journal page's column (MAX_HEIGHT_PT)
    let title_lines: usize = figure_title
        .iter()
        .enumerate()
        .map(|(i, line)| {
            super::wrap(
                line,
                width_pt - 8.0,
                if i == 0 { TITLE_PT } else { LABEL_PT },
            )
            .len()
        })
        .sum();
    let header_pt = (HEADER_LINE as usize * title_lines + 4) as f64;
    let legend_pt = (LEGEND * legend + ROW_GAP) as f64;
    let chart_h = match names.y {
        Some(_) => chart_h,
        None => chart_h
            .min(((MAX_HEIGHT_PT - header_pt) / rows as f64 - legend_pt).floor())
            .max(MIN_CHART_H),
    };
    let panel_h = chart_h.round() as u32 + (LEGEND * legend + ROW_GAP) as u32;
    // the title's first line in black, the others in grey, each broken to the width
    let lines: Vec<(String, f64, RGBColor)> = figure_title
        .iter()
        .enumerate()
        .flat_map(|(i, line)| {
            let (size, colour) = if i == 0 {
                (TITLE_PT, BLACK)
            } else {
                (LABEL_PT, GREY)
            };
            super::wrap(line, width_pt - 8.0, size)
                .into_iter()
                .map(move |l| (l, size, colour))
        })
        .collect();
    let header = HEADER_LINE * lines.len() as u32 + 4;
    let size = (width_pt.round() as u32, header + panel_h * rows as u32);
    render(size, |root| {
        let (header_area, body) = root.split_vertically(px(header as i32));
        let (w, _) = header_area.dim_in_pixel();
        for (i, (line, size, colour)) in lines.iter().enumerate() {
            let (size, colour) = (*size, *colour);
            header_area
                .draw(&Text::new(
                    line.clone(),
                    (w as i32 / 2, px(2 + (HEADER_LINE * i as u32) as i32)),
                    text(size, colour, HPos::Center, VPos::Top),
                ))
                .map_err(err)?;
        }
        let panels = body.split_evenly((rows, cols));
        for ((area, map), grid) in panels.iter().zip(maps).zip(&grids) {
            draw_panel(area, map, grid, legend, names)?;
        }
        Ok(())
    })
}

/// A checked map: the cell edges in log10 along each axis.
struct Grid {
    nx: usize,
    x_edges: Vec<f64>,
    y_edges: Vec<f64>,
}

impl Grid {
    /// Checks `map` (grid, values, mask, scale) and computes its cell edges.
    fn new(map: &HeatMap<'_>, names: AxisNames<'_>) -> Result<Self, String> {
        let x_edges = match names.x {
            Some(n) => category_edges(map.xs, n, "xs")?,
            None => log_edges(map.xs, "xs")?,
        };
        let y_edges = match names.y {
            Some(n) => category_edges(map.ys, n, "ys")?,
            None => log_edges(map.ys, "ys")?,
        };
        let cells = map.xs.len() * map.ys.len();
        if map.values.len() != cells {
            return Err(format!(
                "values has {} entries, expected nx·ny = {}·{} = {cells}",
                map.values.len(),
                map.xs.len(),
                map.ys.len()
            ));
        }
        if let Some((mask, _)) = map.outline
            && mask.len() != cells
        {
            return Err(format!(
                "outline mask has {} entries, expected nx·ny = {cells}",
                mask.len()
            ));
        }
        map.scale.check()?;
        Ok(Self {
            nx: map.xs.len(),
            x_edges,
            y_edges,
        })
    }

    /// Cell `(ix, iy)` as `((x0, y0), (x1, y1))` in log10 coordinates.
    fn cell(&self, ix: usize, iy: usize) -> ((f64, f64), (f64, f64)) {
        (
            (self.x_edges[ix], self.y_edges[iy]),
            (self.x_edges[ix + 1], self.y_edges[iy + 1]),
        )
    }

    fn ny(&self) -> usize {
        self.y_edges.len() - 1
    }
}

/// The cell edges of a category axis: centres 1, 2, …, n (one per name), edges half-way.
fn category_edges(cs: &[f64], names: &[String], name: &str) -> Result<Vec<f64>, String> {
    let expected = (1..=names.len()).map(|k| k as f64);
    if cs.len() != names.len() || !cs.iter().copied().eq(expected) {
        return Err(format!(
            "{name} of a category axis must be 1, 2, …, {} (one per name)",
            names.len()
        ));
    }
    Ok((0..=cs.len()).map(|k| k as f64 + 0.5).collect())
}

/// The label of category position `v` (1-based) among `names`, underscores as spaces.
fn category_label(names: &[String], v: f64) -> String {
    let k = v.round() as usize;
    names
        .get(k.wrapping_sub(1))
        .map(|n| n.replace('_', " "))
        .unwrap_or_default()
}

/// log10 of the cell edges of the centres `cs` (named `name` in errors): geometric midpoints,
/// half a step beyond the first and the last centre (half a decade for a single centre).
fn log_edges(cs: &[f64], name: &str) -> Result<Vec<f64>, String> {
    if cs.is_empty() {
        return Err(format!("empty grid: {name} has no values"));
    }
    if let Some(bad) = cs.iter().find(|c| !(c.is_finite() && **c > 0.0)) {
        return Err(format!(
            "{name} must be finite and > 0 (log axis), found {bad}"
        ));
    }
    if cs.windows(2).any(|w| w[1] <= w[0]) {
        return Err(format!("{name} must be strictly ascending"));
    }
    let l: Vec<f64> = cs.iter().map(|c| c.log10()).collect();
    let n = l.len();
    if n == 1 {
        return Ok(vec![l[0] - 0.5, l[0] + 0.5]);
    }
    let mut edges = Vec::with_capacity(n + 1);
    edges.push(l[0] - 0.5 * (l[1] - l[0]));
    edges.extend(l.windows(2).map(|w| 0.5 * (w[0] + w[1])));
    edges.push(l[n - 1] + 0.5 * (l[n - 1] - l[n - 2]));
    Ok(edges)
}

impl ColorScale {
    /// Whether the scale's parameters are usable.
    fn check(&self) -> Result<(), String> {
        let ok = match *self {
            Self::Sequential { lo, hi } => lo.is_finite() && hi.is_finite() && lo < hi,
            Self::Diverging { centre, span } => {
                centre.is_finite() && span.is_finite() && span > 0.0
            }
            Self::Log { lo, hi } => lo.is_finite() && hi.is_finite() && lo > 0.0 && lo < hi,
        };
        if ok {
            Ok(())
        } else {
            Err(format!(
                "bad colour scale {self:?}: needs finite lo < hi (lo > 0 for Log), or span > 0"
            ))
        }
    }

    /// The ends of the scale in its own coordinate (log10 of the value for `Log`).
    fn domain(&self) -> (f64, f64) {
        match *self {
            Self::Sequential { lo, hi } => (lo, hi),
            Self::Diverging { centre, span } => (centre - span, centre + span),
            Self::Log { lo, hi } => (lo.log10(), hi.log10()),
        }
    }

    /// `v` in the scale's coordinate (−∞ for values ≤ 0 on a `Log` scale).
    fn coord(&self, v: f64) -> f64 {
        match self {
            Self::Log { .. } if v <= 0.0 => f64::NEG_INFINITY,
            Self::Log { .. } => v.log10(),
            _ => v,
        }
    }

    /// Position of `v` along the scale, 0 at the low end and 1 at the high end, clamped.
    fn fraction(&self, v: f64) -> f64 {
        let (a, b) = self.domain();
        ((self.coord(v) - a) / (b - a)).clamp(0.0, 1.0)
    }

    /// Colour at position `t` ∈ [0, 1] along the scale.
    fn colour_at(&self, t: f64) -> RGBColor {
        match self {
            Self::Diverging { .. } => interpolate(&BLUE_RED, t),
            _ => interpolate(&VIRIDIS, t),
        }
    }

    /// Colour of value `v` (`None` for NaN: no value).
    fn colour(&self, v: f64) -> Option<RGBColor> {
        (!v.is_nan()).then(|| self.colour_at(self.fraction(v)))
    }

    /// Whether `v` lies below (`-1`), inside (`0`) or above (`1`) the scale.
    fn side(&self, v: f64) -> i8 {
        let (a, b) = self.domain();
        let c = self.coord(v);
        if c < a {
            -1
        } else if c > b {
            1
        } else {
            0
        }
    }

    /// The label of a point `c` of the scale's coordinate.
    fn label(&self, c: f64) -> String {
        match self {
            Self::Log { .. } => sci_label(10f64.powf(c)),
            _ => plain(c),
        }
    }

    /// Colour-bar ticks in the scale's coordinate.
    fn ticks(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        match *self {
            Self::Sequential { .. } => {
                let step = nice_step(b - a, 5);
                let first = (a / step - 1e-9).ceil() as i64;
                let last = (b / step + 1e-9).floor() as i64;
                (first..=last).map(|k| k as f64 * step).collect()
            }
            Self::Diverging { centre, span } => {
                let step = nice_step(span, 3);
                let k = (span / step + 1e-9).floor() as i64;
                (-k..=k).map(|i| centre + i as f64 * step).collect()
            }
            Self::Log { .. } => log_ticks(a, b),
        }
    }
}

/// Linear interpolation between evenly spaced colour `stops` at `t` ∈ [0, 1].
fn interpolate(stops: &[(u8, u8, u8)], t: f64) -> RGBColor {
    let x = t.clamp(0.0, 1.0) * (stops.len() - 1) as f64;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let f = x - i as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + f * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (stops[i], stops[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Ticks of a log axis from log10 `l0` to `l1`, in log10: whole decades (every other one beyond
/// eight), or 1, 2 and 5 × 10ᵏ when fewer than two decades fall inside.
fn log_ticks(l0: f64, l1: f64) -> Vec<f64> {
    let a = (l0 - 1e-9).ceil() as i32;
    let b = (l1 + 1e-9).floor() as i32;
    if b > a {
        let every = if b - a > 8 { 2 } else { 1 };
        return (a..=b)
            .filter(|e| (e - a) % every == 0)
            .map(f64::from)
            .collect();
    }
    let mut out = Vec::new();
    for k in (l0.floor() as i32)..=(l1.ceil() as i32) {
        for m in [1.0_f64, 2.0, 5.0] {
            let v = f64::from(k) + m.log10();
            if v >= l0 - 1e-9 && v <= l1 + 1e-9 {
                out.push(v);
            }
        }
    }
    out
}

/// The label of a log-axis tick at log10 `v`: `10ᵏ` at a decade; between decades the number as
/// written (`2`, `0.05`, `300`; [`plain`]), `m·10ᵏ` only where that would be long — never a
/// factor of `10⁰`.
fn log_label(v: f64) -> String {
    if (v - v.round()).abs() < 1e-9 {
        decade_label(10f64.powf(v.round()))
    } else {
        plain(10f64.powf(v))
    }
}

/// `v` to four significant digits without trailing zeros (`m·10ᵏ` beyond 10⁴ or below 10⁻³),
/// with a true minus sign.
fn plain(v: f64) -> String {
    let a = v.abs();
    if a < 1e-12 {
        return "0".into();
    }
    let s = if (1e-3..1e4).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
        let s = format!("{a:.decimals$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        sci_label(a)
    };
    if v < 0.0 { format!("−{s}") } else { s }
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Linear, Linear>>;

/// A pixel rectangle `((x0, y0), (x1, y1))`, `x0 < x1`, `y0 < y1`.
type PixelRect = ((i32, i32), (i32, i32));

fn draw_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    map: &HeatMap<'_>,
    grid: &Grid,
    legend_rows: i32,
    names: AxisNames<'_>,
) -> Result<(), String> {
    let (w, h) = area.dim_in_pixel();
    let (w, h) = (w as i32, h as i32);
    area.draw(&Text::new(
        map.title.to_string(),
        (w / 2, px(3)),
        text(LABEL_PT, BLACK, HPos::Center, VPos::Top),
    ))
    .map_err(err)?;
    let body = area.margin(px(TITLE), 0, 0, 0);
    let (main, legend) = body.split_vertically(h - px(TITLE) - px(LEGEND * legend_rows + ROW_GAP));
    let (chart_area, bar_area) = main.split_horizontally(w - px(BAR_STRIP));
    let chart = build_chart(&chart_area, map, grid, names)?;
    let plotting = chart.plotting_area().strip_coord_spec();
    let origin = plotting.get_base_pixel();
    let to_pixel = |p: (f64, f64)| {
        let (x, y) = chart.backend_coord(&p);
        (x - origin.0, y - origin.1)
    };
    let cells = cell_rects(grid, to_pixel);
    draw_cells(&plotting, map, &cells)?;
    let (x_range, y_range) = plotting.get_pixel_range();
    let frame = (
        (0, 0),
        (
            x_range.end - x_range.start - 1,
            y_range.end - y_range.start - 1,
        ),
    );
    rect_outline(&plotting, frame, stroke(BLACK, 0.75))?;
    if let Some((mask, _)) = map.outline {
        draw_outline(&plotting, grid, mask, &cells)?;
    }
    let bar_origin = bar_area.get_base_pixel();
    let span = (y_range.start - bar_origin.1, y_range.end - bar_origin.1);
    draw_colour_bar(&bar_area, map, span)?;
    let legend_x = x_range.start - legend.get_base_pixel().0;
    draw_legend(&legend, map, legend_x)
}

/// The chart of a map: log10 axes over the cell edges, decade labels, no grid lines.
fn build_chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    map: &HeatMap<'_>,
    grid: &Grid,
    names: AxisNames<'_>,
) -> Result<Chart<'a, 'b>, String> {
    let (x0, x1) = (grid.x_edges[0], grid.x_edges[grid.x_edges.len() - 1]);
    let (y0, y1) = (grid.y_edges[0], grid.y_edges[grid.y_edges.len() - 1]);
    let ticks = |a: f64, b: f64, n: Option<&[String]>| match n {
        Some(n) => (1..=n.len()).map(|k| k as f64).collect(),
        None => log_ticks(a, b),
    };
    // room for the longest category name (a quarter turn along x)
    let longest = |n: Option<&[String]>| {
        n.map_or(0.0, |n| {
            n.iter()
                .map(|s| super::text_width_pt(s, TICK_PT))
                .fold(0.0, f64::max)
        })
    };
    let x_area = 26 + longest(names.x).ceil() as i32;
    let y_area = if names.y.is_some() {
        14 + longest(names.y).ceil() as i32
    } else {
        36
    };
    let mut chart = ChartBuilder::on(area)
        .margin(px(3))
        .margin_left(px(10))
        .margin_right(px(2))
        .x_label_area_size(px(x_area))
        .y_label_area_size(px(y_area))
        .build_cartesian_2d(
            Linear::new(x0, x1, ticks(x0, x1, names.x)),
            Linear::new(y0, y1, ticks(y0, y1, names.y)),
        )
        .map_err(err)?;
    let x_format = |v: &f64| match names.x {
        Some(n) => category_label(n, *v),
        None => log_label(*v),
    };
    let y_format = |v: &f64| match names.y {
        Some(n) => category_label(n, *v),
        None => log_label(*v),
    };
    let x_style = match names.x {
        Some(_) => font(TICK_PT)
            .transform(FontTransform::Rotate90)
            .into_text_style(area),
        None => font(TICK_PT).into_text_style(area),
    };
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .axis_style(stroke(BLACK, 0.75))
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .x_label_style(x_style)
        .axis_desc_style(font(LABEL_PT))
        .x_desc(map.x_label)
        .y_desc(map.y_label)
        .x_label_formatter(&x_format)
        .y_label_formatter(&y_format)
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// Pixel rectangles of the cells, row-major like the values.
fn cell_rects(grid: &Grid, to_pixel: impl Fn((f64, f64)) -> (i32, i32)) -> Vec<PixelRect> {
    let mut out = Vec::with_capacity(grid.nx * grid.ny());
    for iy in 0..grid.ny() {
        for ix in 0..grid.nx {
            let (a, b) = grid.cell(ix, iy);
            let (pa, pb) = (to_pixel(a), to_pixel(b));
            out.push((
                (pa.0.min(pb.0), pa.1.min(pb.1)),
                (pa.0.max(pb.0), pa.1.max(pb.1)),
            ));
        }
    }
    out
}

/// The cells in their colours, hatched grey where there is no value. Each cell reaches one
/// pixel into its right and upper neighbours, which are drawn after it, so that no seam of the
/// background shows between cells.
fn draw_cells(
    area: &DrawingArea<SVGBackend, Shift>,
    map: &HeatMap<'_>,
    cells: &[PixelRect],
) -> Result<(), String> {
    let (w, _) = area.dim_in_pixel();
    let right = w as i32 - 1;
    for (value, &((x0, y0), (x1, y1))) in map.values.iter().zip(cells) {
        let colour = value.and_then(|v| map.scale.colour(v));
        let grown = [(x0, (y0 - px(1)).max(0)), ((x1 + px(1)).min(right), y1)];
        match colour {
            Some(c) => area.draw(&Rectangle::new(grown, c.filled())).map_err(err)?,
            None => area
                .draw(&Rectangle::new(grown, NO_VALUE.filled()))
                .map_err(err)?,
        }
    }
    for (value, rect) in map.values.iter().zip(cells) {
        if value.is_none_or(f64::is_nan) {
            hatch(area, *rect)?;
        }
    }
    Ok(())
}

/// Diagonal hatching ("/") over `rect`, on lines x + y = k·step of `area` so that neighbouring
/// hatched cells join up.
fn hatch(
    area: &DrawingArea<SVGBackend, Shift>,
    ((x0, y0), (x1, y1)): PixelRect,
) -> Result<(), String> {
    let step = px(HATCH_STEP);
    let first = (x0 + y0 + step - 1).div_euclid(step);
    let last = (x1 + y1).div_euclid(step);
    for k in first..=last {
        let c = k * step;
        let (xa, xb) = ((c - y1).max(x0), (c - y0).min(x1));
        if xa < xb {
            area.draw(&PathElement::new(
                vec![(xa, c - xa), (xb, c - xb)],
                stroke(HATCH, 0.5),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

/// The boundary of the cells where `mask` is true: a black line with a thin white halo (visible
/// on dark cells), each segment stretched by half its width so that corners close.
fn draw_outline(
    area: &DrawingArea<SVGBackend, Shift>,
    grid: &Grid,
    mask: &[bool],
    cells: &[PixelRect],
) -> Result<(), String> {
    let (nx, ny) = (grid.nx, grid.ny());
    let inside = |ix: isize, iy: isize| {
        ix >= 0
            && iy >= 0
            && (ix as usize) < nx
            && (iy as usize) < ny
            && mask[iy as usize * nx + ix as usize]
    };
    let mut segments = Vec::new();
    for iy in 0..ny {
        for ix in 0..nx {
            if !mask[iy * nx + ix] {
                continue;
            }
            let ((x0, y0), (x1, y1)) = cells[iy * nx + ix];
            let (i, j) = (ix as isize, iy as isize);
            // Pixel y grows downwards: the cell above (iy + 1) shares the edge at y0.
            if !inside(i - 1, j) {
                segments.push(((x0, y0), (x0, y1)));
            }
            if !inside(i + 1, j) {
                segments.push(((x1, y0), (x1, y1)));
            }
            if !inside(i, j + 1) {
                segments.push(((x0, y0), (x1, y0)));
            }
            if !inside(i, j - 1) {
                segments.push(((x0, y1), (x1, y1)));
            }
        }
    }
    for (colour, width) in [(WHITE, OUTLINE + 1.0), (BLACK, OUTLINE)] {
        let half = (width * f64::from(px(1)) / 2.0).round() as i32;
        for &((xa, ya), (xb, yb)) in &segments {
            let (dx, dy) = (half * (xb - xa).signum(), half * (yb - ya).signum());
            area.draw(&PathElement::new(
                vec![(xa - dx, ya - dy), (xb + dx, yb + dy)],
                stroke(colour, width),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

/// The colour bar of `map` in `area`, spanning the pixel rows `span` of the plot (less the
/// room for the clamp triangles), with its ticks, the clamped ends and the value label.
fn draw_colour_bar(
    area: &DrawingArea<SVGBackend, Shift>,
    map: &HeatMap<'_>,
    span: (i32, i32),
) -> Result<(), String> {
    let scale = &map.scale;
    let (x0, x1) = (px(6), px(6 + BAR_WIDTH));
    let (top, bottom) = (span.0 + px(BAR_INSET), span.1 - px(BAR_INSET));
    let height = bottom - top;
    let slices = 128;
    for i in 0..slices {
        let ya = bottom - height * i / slices;
        let yb = (bottom - height * (i + 1) / slices - px(1)).max(top);
        let colour = scale.colour_at((f64::from(i) + 0.5) / f64::from(slices));
        area.draw(&Rectangle::new([(x0, yb), (x1, ya)], colour.filled()))
            .map_err(err)?;
    }
    rect_outline(area, ((x0, top), (x1, bottom)), stroke(BLACK, 0.75))?;
    let sides: Vec<i8> = map
        .values
        .iter()
        .flatten()
        .filter(|v| !v.is_nan())
        .map(|v| scale.side(*v))
        .collect();
    let (below, above) = (sides.contains(&-1), sides.contains(&1));
    let (a, b) = scale.domain();
    let at = |c: f64| bottom - ((c - a) / (b - a) * f64::from(height)).round() as i32;
    let mut labelled: Vec<(f64, String)> = scale
        .ticks()
        .into_iter()
        .map(|c| (c, scale.label(c)))
        .collect();
    // A clamped end replaces the ticks within a third of a tick step of it.
    let room = labelled
        .windows(2)
        .map(|w| w[1].0 - w[0].0)
        .fold(b - a, f64::min)
        / 3.0;
    if above {
        labelled.retain(|(c, _)| b - c > room);
        labelled.push((b, format!("≥ {}", scale.label(b))));
        triangle(area, (x0, x1), top, -1, scale.colour_at(1.0))?;
    }
    if below {
        labelled.retain(|(c, _)| c - a > room);
        labelled.push((a, format!("≤ {}", scale.label(a))));
        triangle(area, (x0, x1), bottom, 1, scale.colour_at(0.0))?;
    }
    for (c, label) in labelled {
        let y = at(c);
        area.draw(&PathElement::new(
            vec![(x1, y), (x1 + px(2), y)],
            stroke(BLACK, 0.75),
        ))
        .map_err(err)?;
        area.draw(&Text::new(
            label,
            (x1 + px(3), y),
            text(TICK_PT, BLACK, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
    }
    let style =
        text(LABEL_PT, BLACK, HPos::Center, VPos::Center).transform(FontTransform::Rotate270);
    area.draw(&Text::new(
        map.value_label.to_string(),
        (x1 + px(32), (top + bottom) / 2),
        style,
    ))
    .map_err(err)
}

/// The outline of `rect` in `style` (a closed path: the SVG backend draws rectangles' outlines
/// one drawing pixel wide whatever the style's width).
fn rect_outline(
    area: &DrawingArea<SVGBackend, Shift>,
    ((x0, y0), (x1, y1)): PixelRect,
    style: ShapeStyle,
) -> Result<(), String> {
    let half = i32::try_from(style.stroke_width / 2).unwrap_or(0);
    area.draw(&PathElement::new(
        vec![
            (x0 - half, y0),
            (x1, y0),
            (x1, y1),
            (x0, y1),
            (x0, y0 - half),
        ],
        style,
    ))
    .map_err(err)
}

/// The clamp triangle on the bar's end at pixel row `y`, pointing up (`dir = −1`) or down (`1`).
fn triangle(
    area: &DrawingArea<SVGBackend, Shift>,
    (x0, x1): (i32, i32),
    y: i32,
    dir: i32,
    colour: RGBColor,
) -> Result<(), String> {
    let tip = (x0 + (x1 - x0) / 2, y + dir * px(BAR_INSET - 2));
    let points = vec![(x0, y), (x1, y), tip];
    area.draw(&Polygon::new(points.clone(), colour.filled()))
        .map_err(err)?;
    let mut closed = points;
    closed.push((x0, y));
    area.draw(&PathElement::new(closed, stroke(BLACK, 0.75)))
        .map_err(err)
}

/// The legend rows under the plot, from `x`: the hatched "no value" swatch if a cell has no
/// value, and the outline's swatch and text, one row each.
fn draw_legend(
    area: &DrawingArea<SVGBackend, Shift>,
    map: &HeatMap<'_>,
    x: i32,
) -> Result<(), String> {
    let mut y = px(LEGEND / 2);
    let swatch = |y: i32| ((x, y - px(4)), (x + px(12), y + px(4)));
    let label = |s: &str, y: i32| {
        Text::new(
            s.to_string(),
            (x + px(16), y),
            text(TICK_PT, BLACK, HPos::Left, VPos::Center),
        )
    };
    if map.values.iter().any(|v| v.is_none_or(f64::is_nan)) {
        let r = swatch(y);
        area.draw(&Rectangle::new([r.0, r.1], NO_VALUE.filled()))
            .map_err(err)?;
        hatch(area, r)?;
        rect_outline(area, r, stroke(GREY_EDGE, 0.75))?;
        area.draw(&label("no value", y)).map_err(err)?;
        y += px(LEGEND);
    }
    if let Some((_, text)) = map.outline {
        let r = swatch(y);
        rect_outline(area, r, stroke(WHITE, OUTLINE + 1.0))?;
        rect_outline(area, r, stroke(BLACK, OUTLINE))?;
        area.draw(&label(text, y)).map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests;
