//! The paper's Fig. 6: η(γ) of the eight design cases.
//!
//! Four panels (human mass × link stiffness) on one shared y scale; each holds both payloads
//! (the light payload's pair of curves well below the heavy payload's, labelled on the curves),
//! n = 2 solid blue and n = 1 dashed orange as in the paper, η(2/3) marked and tabulated in the
//! panel's empty lower-right corner, and a note where the n = 1 and n = 2 curves coincide.
//!
//! [`fig6_with_points_svg`] adds finite-element results as diamonds in the colour of their curve:
//! filled where η_FE lies on the curve, hollow at the edge of the γ range where it does not; the
//! table then moves to a corner the markers leave free.

use flexrig_lumped::fig6::{EtaCurve, Fig6Case, GAMMA_RANGE, K_C, M_R, V0};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, Linear, boxed_text, decade_label, err, font, px, render, sci_label, stroke, text,
    ticks,
};

/// Colour of the n = 2 curves (solid), as in the paper.
const BLUE: RGBColor = RGBColor(31, 119, 180);
/// Colour of the n = 1 curves (dashed), as in the paper.
const ORANGE: RGBColor = RGBColor(230, 120, 0);
/// Nominal size of the figure [px].
const SIZE: (u32, u32) = (1000, 840);
/// Height of the header (title and legend) [px].
const HEADER: u32 = 64;
/// Height of the legend row of the finite-element points [px].
const LEGEND_ROW: u32 = 24;
/// Half-diagonal of a finite-element marker (a diamond) [px].
const DIAMOND: i32 = 7;
/// Room beyond the γ range for markers at its edge.
const GAMMA_PAD: f64 = 0.025;
/// Top of the shared y axis: a little above η = 1 so the curves' end points stay visible.
const Y_TOP: f64 = 1.02;
/// Two curves closer than this fraction of the y span everywhere are drawn as coinciding.
const COINCIDE: f64 = 0.005;

/// A finite-element result placed on the Fig. 6 curves: η_FE drawn at the γ where the lumped
/// curve of its case and exponent takes that value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fig6Point {
    /// The design case (matched to a panel and a curve by m_h, k_δ and m_e).
    pub case: Fig6Case,
    /// Hertz exponent n (matched to the curve's).
    pub n: f64,
    /// η_FE = f_CL/f_CJ of the finite-element runs.
    pub eta_fe: f64,
    /// γ at which the lumped curve takes the value η_FE; `None` when η_FE lies outside the
    /// curve's range: the point is then drawn hollow ("off the curve") at γ = 1. A γ outside the
    /// plotted range [0.5, 1] is drawn hollow at the nearer edge.
    pub gamma: Option<f64>,
}

/// The paper's Fig. 6 from the sixteen curves of `flexrig_lumped::fig6::fig6`.
pub fn fig6_svg(curves: &[EtaCurve]) -> Result<String, String> {
    draw_figure(curves, &[])
}

/// Fig. 6 with finite-element results: each of `points` as a marker in the colour of its curve
/// (filled on the curve, hollow off it), on a y scale that includes every point.
pub fn fig6_with_points_svg(curves: &[EtaCurve], points: &[Fig6Point]) -> Result<String, String> {
    for p in points {
        check_point(curves, p)?;
    }
    draw_figure(curves, points)
}

/// Whether `p` is finite and has a curve among `curves`.
fn check_point(curves: &[EtaCurve], p: &Fig6Point) -> Result<(), String> {
    let name = || format!("finite-element point ({}, n = {})", p.case.label(), p.n);
    if !p.eta_fe.is_finite() {
        return Err(format!("{}: η_FE = {} is not finite", name(), p.eta_fe));
    }
    if let Some(g) = p.gamma
        && !g.is_finite()
    {
        return Err(format!("{}: γ = {g} is not finite", name()));
    }
    if !curves.iter().any(|c| c.case == p.case && c.n == p.n) {
        return Err(format!("{}: no curve of that case and n", name()));
    }
    Ok(())
}

/// The shared axes: bottom and top of the plotted η range, left and right of the γ range.
#[derive(Clone, Copy)]
struct EtaAxis {
    lo: f64,
    top: f64,
    left: f64,
    right: f64,
}

impl EtaAxis {
    /// Room for every curve (0.01 below the lowest) and every point (a marker's height, 0.025),
    /// the bottom rounded down to 0.05, the top at least [`Y_TOP`]; the γ range [`GAMMA_RANGE`]
    /// widened by [`GAMMA_PAD`] on a side where a marker sits at its edge.
    fn new(curves: &[EtaCurve], points: &[Fig6Point]) -> Self {
        let curve_min = curves
            .iter()
            .flat_map(|c| c.eta.iter().copied())
            .fold(1.0, f64::min);
        let point_min = points
            .iter()
            .map(|p| p.eta_fe)
            .fold(f64::INFINITY, f64::min);
        let point_max = points
            .iter()
            .map(|p| p.eta_fe)
            .fold(f64::NEG_INFINITY, f64::max);
        let lo = ((curve_min - 0.01).min(point_min - 0.025) * 20.0).floor() / 20.0;
        let top = Y_TOP.max(((point_max + 0.02) * 100.0).ceil() / 100.0);
        let (g0, g1) = GAMMA_RANGE;
        let near = |edge: f64| {
            points
                .iter()
                .any(|p| (Marker::of(p).gamma - edge).abs() < GAMMA_PAD)
        };
        Self {
            lo,
            top,
            left: if near(g0) { g0 - GAMMA_PAD } else { g0 },
            right: if near(g1) { g1 + GAMMA_PAD } else { g1 },
        }
    }

    /// Ticks every 0.1 inside the range.
    fn ticks(&self) -> Vec<f64> {
        let first = (self.lo * 10.0 - 1e-9).ceil() / 10.0;
        ticks(first, self.top, 0.1)
    }
}

/// Fig. 6 from `curves`, with `points` if there are any (then with a second legend row).
fn draw_figure(curves: &[EtaCurve], points: &[Fig6Point]) -> Result<String, String> {
    let axis = EtaAxis::new(curves, points);
    let panels = panel_keys(curves);
    let header = HEADER + if points.is_empty() { 0 } else { LEGEND_ROW };
    let size = (SIZE.0, SIZE.1 + header - HEADER);
    render(size, |root| {
        let (head, body) = root.split_vertically(px(header as i32));
        draw_header(&head, !points.is_empty())?;
        let areas = body.split_evenly((2, 2));
        for (i, (area, key)) in areas.iter().zip(&panels).enumerate() {
            let of_panel: Vec<&EtaCurve> = curves
                .iter()
                .filter(|c| (c.case.m_h, c.case.k_delta) == *key)
                .collect();
            let points_of_panel: Vec<&Fig6Point> = points
                .iter()
                .filter(|p| (p.case.m_h, p.case.k_delta) == *key)
                .collect();
            let place = Place {
                letter: (b'a' + i as u8) as char,
                left: i % 2 == 0,
                bottom: i >= 2,
            };
            draw_panel(area, &of_panel, &points_of_panel, axis, place)?;
        }
        Ok(())
    })
}

/// (m_h, k_δ) of each panel in order of appearance (rows by m_h, columns by k_δ).
fn panel_keys(curves: &[EtaCurve]) -> Vec<(f64, f64)> {
    let mut keys: Vec<(f64, f64)> = Vec::new();
    for c in curves {
        let key = (c.case.m_h, c.case.k_delta);
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys
}

/// Where a panel sits: its letter, whether it carries the y and the x axis description.
#[derive(Clone, Copy)]
struct Place {
    letter: char,
    left: bool,
    bottom: bool,
}

/// Title and legend; `with_points` adds the row of the finite-element markers.
fn draw_header(area: &DrawingArea<SVGBackend, Shift>, with_points: bool) -> Result<(), String> {
    let title = format!(
        "Peak-force ratio η = f_max(γ)/f_max(1), compliant link (γ) over compliant joint (γ = 1); m_r = {M_R} kg, k_c = {} N/mⁿ, v_0 = {V0} m/s",
        decade_label(K_C)
    );
    let (w, _) = area.dim_in_pixel();
    area.draw(&Text::new(
        title,
        (w as i32 / 2, px(8)),
        text(15.0, BLACK, HPos::Center, VPos::Top),
    ))
    .map_err(err)?;
    let y = px(44);
    let mut x = px(200);
    for (label, colour, dashed) in [
        ("n = 2 (Hertz contact)", BLUE, false),
        ("n = 1 (linear contact)", ORANGE, true),
    ] {
        legend_line(area, (x, y), colour, dashed)?;
        area.draw(&Text::new(
            label,
            (x + px(36), y),
            text(13.0, BLACK, HPos::Left, VPos::Center),
        ))
        .map_err(err)?;
        x += px(210);
    }
    area.draw(&Circle::new((x + px(8), y), px(4), BLACK.filled()))
        .map_err(err)?;
    area.draw(&Text::new(
        "η at γ = 2/3 (uniform compliant link)",
        (x + px(20), y),
        text(13.0, BLACK, HPos::Left, VPos::Center),
    ))
    .map_err(err)?;
    if with_points {
        draw_points_legend(area, px(44 + LEGEND_ROW as i32))?;
    }
    Ok(())
}

/// The legend row of the finite-element markers at pixel row `y`.
fn draw_points_legend(area: &DrawingArea<SVGBackend, Shift>, y: i32) -> Result<(), String> {
    let label = |s: &str, x: i32| {
        Text::new(
            s.to_string(),
            (x, y),
            text(13.0, BLACK, HPos::Left, VPos::Center),
        )
    };
    let mut x = px(200);
    diamond(area, (x + px(8), y), Some(BLUE), BLUE)?;
    diamond(area, (x + px(26), y), Some(ORANGE), ORANGE)?;
    area.draw(&label(
        "finite elements (η_FE), on the curve of its case and n",
        x + px(42),
    ))
    .map_err(err)?;
    x += px(420);
    diamond(area, (x + px(8), y), None, BLUE)?;
    diamond(area, (x + px(26), y), None, ORANGE)?;
    area.draw(&label(
        "η_FE off the curve, drawn at the edge (γ = 1)",
        x + px(42),
    ))
    .map_err(err)
}

/// A finite-element marker at pixel `at`: a diamond filled with `fill` (white when hollow) and
/// edged in `edge` (two pixels wide when hollow, one pixel of black when filled).
fn diamond(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    fill: Option<RGBColor>,
    edge: RGBColor,
) -> Result<(), String> {
    let r = px(DIAMOND);
    let corners = vec![(x, y - r), (x + r, y), (x, y + r), (x - r, y)];
    area.draw(&Polygon::new(
        corners.clone(),
        fill.unwrap_or(WHITE).filled(),
    ))
    .map_err(err)?;
    let mut closed = corners;
    closed.push((x, y - r));
    closed.push((x + r, y));
    let style = match fill {
        Some(_) => stroke(BLACK, 1.0),
        None => stroke(edge, 2.0),
    };
    area.draw(&PathElement::new(closed, style)).map_err(err)
}

/// A 28-pixel legend sample of a solid or dashed line starting at `(x, y)`.
fn legend_line(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    colour: RGBColor,
    dashed: bool,
) -> Result<(), String> {
    let style = stroke(colour, 2.0);
    let segments: Vec<(i32, i32)> = if dashed {
        vec![(0, 8), (12, 20), (24, 28)]
    } else {
        vec![(0, 28)]
    };
    for (a, b) in segments {
        area.draw(&PathElement::new(
            vec![(x + px(a), y), (x + px(b), y)],
            style,
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// Short description of a case's human mass and link stiffness.
fn panel_caption(letter: char, case: &Fig6Case) -> String {
    let impact = if case.m_h >= 100.0 {
        "constrained impact"
    } else {
        "unconstrained impact"
    };
    let link = if case.k_delta >= 1e6 {
        "rigid link"
    } else {
        "compliant link"
    };
    format!(
        "({letter}) m_h = {} kg ({impact}), k_δ = {} N/m ({link})",
        case.m_h,
        sci_label(case.k_delta)
    )
}

fn draw_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    curves: &[&EtaCurve],
    points: &[&Fig6Point],
    axis: EtaAxis,
    place: Place,
) -> Result<(), String> {
    let Some(first) = curves.first() else {
        return Ok(());
    };
    let (g0, g1) = GAMMA_RANGE;
    let mut chart = ChartBuilder::on(area)
        .caption(panel_caption(place.letter, &first.case), font(13.0))
        .margin_top(px(6))
        .margin_left(px(8))
        .margin_right(px(14))
        .margin_bottom(px(4))
        .x_label_area_size(px(if place.bottom { 44 } else { 26 }))
        .y_label_area_size(px(if place.left { 56 } else { 14 }))
        .build_cartesian_2d(
            Linear::new(axis.left, axis.right, ticks(g0, g1, 0.1)),
            Linear::new(axis.lo, axis.top, axis.ticks()),
        )
        .map_err(err)?;
    let left = place.left;
    chart
        .configure_mesh()
        .bold_line_style(stroke(GRID, 1.0))
        .axis_style(stroke(BLACK, 1.0))
        .set_all_tick_mark_size(px(4))
        .label_style(font(12.0))
        .axis_desc_style(font(14.0))
        .x_desc(if place.bottom {
            "γ (1 = compliant joint, 2/3 = uniform compliant link)"
        } else {
            ""
        })
        .y_desc(if left { "η" } else { "" })
        .x_label_formatter(&|g| format!("{g:.1}"))
        .y_label_formatter(&|y| {
            if left {
                format!("{y:.1}")
            } else {
                String::new()
            }
        })
        .draw()
        .map_err(err)?;
    let span = axis.top - axis.lo;
    chart
        .draw_series(DashedLineSeries::new(
            [(2.0 / 3.0, axis.lo), (2.0 / 3.0, axis.top)],
            px(3),
            px(4),
            stroke(GREY, 1.0),
        ))
        .map_err(err)?;
    let mut payloads: Vec<f64> = curves.iter().map(|c| c.case.m_e).collect();
    payloads.dedup();
    let mut rows = Vec::new();
    let mut obstacles = Vec::new();
    for m_e in payloads {
        let pair: Vec<&EtaCurve> = curves
            .iter()
            .copied()
            .filter(|c| c.case.m_e == m_e)
            .collect();
        obstacles.extend(draw_pair(&mut chart, &pair, span)?);
        rows.push(table_row(&pair, span));
    }
    let origin = chart.plotting_area().get_base_pixel();
    let to_pixel = |p: (f64, f64)| {
        let (x, y) = chart.backend_coord(&p);
        (x - origin.0, y - origin.1)
    };
    for c in curves {
        obstacles.extend(c.gamma.iter().zip(&c.eta).map(|(g, e)| {
            let (x, y) = to_pixel((*g, *e));
            ((x, y), (x, y))
        }));
    }
    let markers = place_markers(points, to_pixel);
    let r = px(DIAMOND);
    obstacles.extend(
        markers
            .iter()
            .map(|(_, (x, y))| ((x - r, y - r), (x + r, y + r))),
    );
    draw_table(&chart, axis, &rows, &obstacles)?;
    draw_points(&chart, &markers)
}

/// The markers of `points` with their pixel centres: on-curve markers where they belong,
/// off-curve ones at the edge, each moved inwards by a marker's width while it would cover a
/// marker placed before it (their γ means only "off the curve").
fn place_markers(
    points: &[&Fig6Point],
    to_pixel: impl Fn((f64, f64)) -> (i32, i32),
) -> Vec<(Marker, (i32, i32))> {
    let mut placed: Vec<(Marker, (i32, i32))> = Vec::new();
    let step = 2 * px(DIAMOND) + px(2);
    for on_curve in [true, false] {
        for p in points {
            let m = Marker::of(p);
            if m.on_curve != on_curve {
                continue;
            }
            let (mut x, y) = to_pixel((m.gamma, m.eta));
            let inwards = if m.gamma < GAMMA_RANGE.0 + 0.5 * GAMMA_PAD {
                1
            } else {
                -1
            };
            let covers = |x: i32, placed: &[(Marker, (i32, i32))]| {
                placed
                    .iter()
                    .any(|(_, (px_, py))| (x - px_).abs() < step && (y - py).abs() < step)
            };
            while !on_curve && covers(x, &placed) {
                x += inwards * step;
            }
            placed.push((m, (x, y)));
        }
    }
    placed
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Linear, Linear>>;

/// A pixel rectangle `((x0, y0), (x1, y1))` of a panel's plotting area, `x0 ≤ x1`, `y0 ≤ y1`.
type PixelRect = ((i32, i32), (i32, i32));

/// One payload's n = 2 (solid) and n = 1 (dashed, drawn on top) curves, η(2/3) marked, and the
/// payload written under the pair's left end. Returns the pixel box of that label.
fn draw_pair(
    chart: &mut Chart,
    pair: &[&EtaCurve],
    span: f64,
) -> Result<Option<PixelRect>, String> {
    let mut sorted = pair.to_vec();
    sorted.sort_by(|a, b| b.n.total_cmp(&a.n));
    for c in &sorted {
        let points: Vec<(f64, f64)> = c.gamma.iter().copied().zip(c.eta.iter().copied()).collect();
        if c.n == 1.0 {
            chart
                .draw_series(DashedLineSeries::new(
                    points,
                    px(7),
                    px(5),
                    stroke(ORANGE, 2.0),
                ))
                .map_err(err)?;
        } else {
            chart
                .draw_series(LineSeries::new(points, stroke(BLUE, 2.0)))
                .map_err(err)?;
        }
    }
    for c in &sorted {
        chart
            .draw_series(std::iter::once(Circle::new(
                (2.0 / 3.0, c.eta_at_2_3),
                px(4),
                curve_colour(c.n).filled(),
            )))
            .map_err(err)?;
    }
    // Below the pair's lower start: the curves rise to the right, so that corner is free.
    let start = sorted
        .iter()
        .filter_map(|c| c.eta.first().copied())
        .fold(f64::MAX, f64::min);
    let Some(case) = sorted.first().map(|c| c.case) else {
        return Ok(None);
    };
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let (x, y) = chart.backend_coord(&(GAMMA_RANGE.0, start - 0.015 * span));
    let label = format!("m_e = {} kg", case.m_e);
    let at = (x - origin.0 + px(8), y - origin.1);
    let style = text(12.0, BLACK, HPos::Left, VPos::Top);
    // As boxed_text sizes its box: a glyph is about 0.6 font-size wide.
    let font_px = style.font.get_size() / 1.24;
    let width = (0.6 * font_px * label.chars().count() as f64).round() as i32;
    let height = font_px.round() as i32;
    boxed_text(&area, &label, at, style)?;
    Ok(Some((at, (at.0 + width, at.1 + height))))
}

/// Colour of the curves of exponent `n`: blue for n = 2, orange for n = 1.
fn curve_colour(n: f64) -> RGBColor {
    if n == 1.0 { ORANGE } else { BLUE }
}

/// Where and how a finite-element point is drawn.
struct Marker {
    gamma: f64,
    eta: f64,
    colour: RGBColor,
    on_curve: bool,
}

impl Marker {
    /// The marker of `p`: on its curve at its γ, or off it at the edge of the γ range (γ = 1
    /// without a γ, else the edge nearer its γ).
    fn of(p: &Fig6Point) -> Self {
        let (g0, g1) = GAMMA_RANGE;
        let (gamma, on_curve) = match p.gamma {
            Some(g) if (g0 - 1e-9..=g1 + 1e-9).contains(&g) => (g.clamp(g0, g1), true),
            Some(g) if g < g0 => (g0, false),
            _ => (g1, false),
        };
        Self {
            gamma,
            eta: p.eta_fe,
            colour: curve_colour(p.n),
            on_curve,
        }
    }
}

/// The finite-element markers at their pixel centres: filled on the curve, hollow off it.
fn draw_points(chart: &Chart, markers: &[(Marker, (i32, i32))]) -> Result<(), String> {
    let area = chart.plotting_area().strip_coord_spec();
    for (m, at) in markers {
        diamond(&area, *at, m.on_curve.then_some(m.colour), m.colour)?;
    }
    Ok(())
}

/// One row of a panel's η(2/3) table: payload, η(2/3) for n = 2 and n = 1, and the largest
/// |η₂ − η₁| when the two curves coincide on the plot.
struct TableRow {
    m_e: f64,
    eta_n2: f64,
    eta_n1: f64,
    coincide: Option<f64>,
}

fn table_row(pair: &[&EtaCurve], span: f64) -> TableRow {
    let of = |n: f64| pair.iter().find(|c| c.n == n);
    let eta = |n: f64| of(n).map_or(f64::NAN, |c| c.eta_at_2_3);
    let gap = match (of(1.0), of(2.0)) {
        (Some(a), Some(b)) => a
            .eta
            .iter()
            .zip(&b.eta)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max),
        _ => f64::INFINITY,
    };
    TableRow {
        m_e: pair.first().map_or(f64::NAN, |c| c.case.m_e),
        eta_n2: eta(2.0),
        eta_n1: eta(1.0),
        coincide: (gap < COINCIDE * span).then_some(gap),
    }
}

/// The η(2/3) table, with a note for coinciding curves, in the first corner of the panel (lower
/// right, lower left, upper left) where it covers none of `obstacles` (curves, labels, markers);
/// lower right, below every curve there, if none is free.
fn draw_table(
    chart: &Chart,
    axis: EtaAxis,
    rows: &[TableRow],
    obstacles: &[PixelRect],
) -> Result<(), String> {
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let notes: Vec<String> = rows
        .iter()
        .filter_map(|r| {
            r.coincide.map(|gap| {
                format!(
                    "m_e = {} kg: n = 1 and n = 2 coincide (|Δη| ≤ {gap:.0e})",
                    r.m_e
                )
            })
        })
        .collect();
    let line = px(16);
    let lines = 1 + rows.len() + notes.len();
    let height = line * lines as i32 + px(6);
    let width = if notes.is_empty() { px(194) } else { px(304) };
    let corner = |g: f64, eta: f64| {
        let (x, y) = chart.backend_coord(&(g, eta));
        (x - origin.0, y - origin.1)
    };
    let (x_left, y_bottom) = corner(axis.left, axis.lo);
    let (x_right, y_top) = corner(axis.right, axis.top);
    // Boxes ((x0, y0), (x1, y1)), 4 pixels in from the frame.
    let inset = px(4);
    let boxes: [PixelRect; 3] = [
        (
            (x_right - inset - width, y_bottom - inset - height),
            (x_right - inset, y_bottom - inset),
        ),
        (
            (x_left + inset, y_bottom - inset - height),
            (x_left + inset + width, y_bottom - inset),
        ),
        (
            (x_left + inset, y_top + inset),
            (x_left + inset + width, y_top + inset + height),
        ),
    ];
    let clear = |b: &PixelRect| !obstacles.iter().any(|o| overlap(b, o, px(3)));
    let chosen = boxes.iter().find(|b| clear(b)).unwrap_or(&boxes[0]);
    let ((x0, y0), (x1, y1)) = *chosen;
    area.draw(&Rectangle::new(
        [(x0, y0), (x1, y1)],
        ShapeStyle::from(&WHITE.mix(0.9)).filled(),
    ))
    .map_err(err)?;
    let right = x1 - px(4);
    let cell = |s: String, x: i32, y: i32, colour: RGBColor| {
        Text::new(s, (x, y), text(12.0, colour, HPos::Right, VPos::Bottom))
    };
    let mut y = y0 + line + px(2);
    let header = [
        ("η(2/3)", right - px(110)),
        ("n = 2", right - px(55)),
        ("n = 1", right),
    ];
    for (s, x) in header {
        area.draw(&cell(s.into(), x, y, BLACK)).map_err(err)?;
    }
    for r in rows {
        y += line;
        area.draw(&cell(
            format!("m_e = {} kg", r.m_e),
            right - px(110),
            y,
            BLACK,
        ))
        .map_err(err)?;
        area.draw(&cell(format!("{:.3}", r.eta_n2), right - px(55), y, BLUE))
            .map_err(err)?;
        area.draw(&cell(format!("{:.3}", r.eta_n1), right, y, ORANGE))
            .map_err(err)?;
    }
    for note in notes {
        y += line;
        area.draw(&Text::new(
            note,
            (right, y),
            text(11.0, GREY, HPos::Right, VPos::Bottom),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// Whether boxes `a` and `b`, `a` grown by `pad` pixels, overlap.
fn overlap(a: &PixelRect, b: &PixelRect, pad: i32) -> bool {
    let ((ax0, ay0), (ax1, ay1)) = *a;
    let ((bx0, by0), (bx1, by1)) = *b;
    ax0 - pad <= bx1 && bx0 <= ax1 + pad && ay0 - pad <= by1 && by0 <= ay1 + pad
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrig_lumped::fig6::fig6;

    /// The γ at which `curve` takes the value `eta` (linear between samples), if it does.
    fn gamma_at(curve: &EtaCurve, eta: f64) -> Option<f64> {
        curve
            .gamma
            .windows(2)
            .zip(curve.eta.windows(2))
            .find(|(_, e)| (e[0] - eta) * (e[1] - eta) <= 0.0 && e[0] != e[1])
            .map(|(g, e)| g[0] + (eta - e[0]) / (e[1] - e[0]) * (g[1] - g[0]))
    }

    /// The held-joint η_FE of docs/impact-fe.md, in the order of the curves.
    const ETA_FE: [f64; 16] = [
        0.9207, 1.0001, 0.9913, 1.0000, 0.2795, 0.3208, 0.9650, 0.9580, 0.9943, 1.0000, 0.9952,
        0.9999, 0.2095, 0.2277, 0.8734, 0.8508,
    ];

    fn points(curves: &[EtaCurve]) -> Vec<Fig6Point> {
        curves
            .iter()
            .map(|c| {
                let i = 2 * cases_index(c) + usize::from(c.n == 2.0);
                let eta_fe = ETA_FE[i];
                Fig6Point {
                    case: c.case,
                    n: c.n,
                    eta_fe,
                    gamma: gamma_at(c, eta_fe),
                }
            })
            .collect()
    }

    fn cases_index(c: &EtaCurve) -> usize {
        flexrig_lumped::fig6::cases()
            .iter()
            .position(|k| *k == c.case)
            .unwrap()
    }

    #[test]
    fn fig6_with_sixteen_points_renders() {
        let curves = fig6(101).unwrap();
        let pts = points(&curves);
        assert_eq!(pts.len(), 16);
        let off = pts.iter().filter(|p| p.gamma.is_none()).count();
        assert!((4..16).contains(&off), "{off} points off the curves");
        let svg = fig6_with_points_svg(&curves, &pts).unwrap();
        assert!(svg.starts_with("<svg width=\"1000\" height=\"864\""));
        assert!(svg.contains("finite elements (η<tspan"));
        assert!(svg.contains("off the curve"));
        // 16 markers plus 4 in the legend, each a polygon
        assert_eq!(svg.matches("<polygon").count(), 20);
        // the curves alone keep the original figure
        let plain = fig6_svg(&curves).unwrap();
        assert!(plain.starts_with("<svg width=\"1000\" height=\"840\""));
        assert!(!plain.contains("off the curve"));
    }

    #[test]
    fn bad_points_are_named() {
        let curves = fig6(11).unwrap();
        let mut p = points(&curves)[0];
        p.n = 1.5;
        let e = fig6_with_points_svg(&curves, &[p]).unwrap_err();
        assert!(e.contains("no curve of that case and n"), "{e}");
        p.n = 1.0;
        p.eta_fe = f64::NAN;
        let e = fig6_with_points_svg(&curves, &[p]).unwrap_err();
        assert!(e.contains("not finite"), "{e}");
    }

    #[test]
    fn the_axis_holds_every_point() {
        let curves = fig6(11).unwrap();
        let axis = EtaAxis::new(&curves, &points(&curves));
        assert!((axis.lo - 0.15).abs() < 1e-12, "{}", axis.lo);
        assert!((axis.top - 1.03).abs() < 1e-12, "{}", axis.top);
        assert!((axis.ticks()[0] - 0.2).abs() < 1e-12);
    }

    /// Writes /tmp/fig6_points_demo.svg (`cargo test … -- --ignored fig6_points_demo`).
    #[test]
    #[ignore = "writes a demo figure to /tmp"]
    fn fig6_points_demo() {
        let curves = fig6(201).unwrap();
        let svg = fig6_with_points_svg(&curves, &points(&curves)).unwrap();
        std::fs::write("/tmp/fig6_points_demo.svg", svg).unwrap();
        std::fs::write("/tmp/fig6_plain_demo.svg", fig6_svg(&curves).unwrap()).unwrap();
    }
}
