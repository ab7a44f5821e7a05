//! The paper's Fig. 6: η(γ) of the eight design cases.
//!
//! Four panels (human mass × link stiffness) on one shared y scale; each holds both payloads
//! (the light payload's pair of curves well below the heavy payload's, labelled on the curves),
//! n = 2 solid blue and n = 1 dashed orange as in the paper, η(2/3) marked and tabulated in the
//! panel's empty lower-right corner, and a note where the n = 1 and n = 2 curves coincide.
//!
//! [`fig6_with_points_svg`] adds finite-element results as diamonds in the colour of their curve:
//! filled where η_FE lies on the curve, hollow at the edge of the γ range where it does not; the
//! table then moves to a corner the markers leave free. Markers whose points lie within a
//! marker's width of each other (several η_FE ≈ 1 at γ ≈ 1) are set in a column below their
//! points with their values, the points marked by dots and joined to the column by a leader.

use flexrig_lumped::fig6::{EtaCurve, Fig6Case, Fig6Design, GAMMA_RANGE};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, LABEL_PT, Linear, TICK_PT, TITLE_PT, err, font, px, render, sci_label, stroke,
    text, text_width_pt, ticks,
};

/// Colour of the n = 2 curves (solid), as in the paper.
const BLUE: RGBColor = RGBColor(31, 119, 180);
/// Colour of the n = 1 curves (dashed), as in the paper.
const ORANGE: RGBColor = RGBColor(230, 120, 0);
/// Height of a panel \[pt\].
const PANEL_H: u32 = 175;
/// Flattest panel \[pt\] (with its axes) when the stack is flattened to fit a page's column.
const MIN_PANEL_H: u32 = 130;
/// Figures narrower than this put the panels in one column \[pt\].
const ONE_COLUMN_BELOW: f64 = 400.0;
/// Height of a title or legend row \[pt\].
const ROW_H: i32 = 12;
/// Half-diagonal of a finite-element marker (a diamond; half-side of a square) [drawing units].
const DIAMOND: i32 = 14;
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

/// The paper's Fig. 6 from the curves of `flexrig_lumped::fig6::fig6_in` in `design` (its
/// m_r, k_c and v0 in the title), at the printed width `width_pt` \[pt\].
pub fn fig6_svg(curves: &[EtaCurve], design: &Fig6Design, width_pt: f64) -> Result<String, String> {
    draw_figure(curves, &[], design, width_pt)
}

/// Fig. 6 with finite-element results: each of `points` as a marker in the colour of its curve
/// (filled on the curve, hollow off it), on a y scale that includes every point.
pub fn fig6_with_points_svg(
    curves: &[EtaCurve],
    points: &[Fig6Point],
    design: &Fig6Design,
    width_pt: f64,
) -> Result<String, String> {
    for p in points {
        check_point(curves, p)?;
    }
    draw_figure(curves, points, design, width_pt)
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
fn draw_figure(
    curves: &[EtaCurve],
    points: &[Fig6Point],
    design: &Fig6Design,
    width_pt: f64,
) -> Result<String, String> {
    let axis = EtaAxis::new(curves, points);
    let panels = panel_keys(curves);
    let cols = if width_pt < ONE_COLUMN_BELOW { 1 } else { 2 };
    let rows = panels.len().div_ceil(cols).max(1);
    let header = Header::new(width_pt, design, points);
    // four panels stacked in one column are flattened to stay within a page's column
    let panel_h = super::page::fitted_chart_height(PANEL_H, rows, header.height(), 0, MIN_PANEL_H);
    let size = (
        width_pt.round() as u32,
        header.height() + panel_h * rows as u32,
    );
    render(size, |root| {
        let (head, body) = root.split_vertically(px(header.height() as i32));
        header.draw(&head)?;
        let areas = body.split_evenly((rows, cols));
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
                left: i % cols == 0,
                bottom: i + cols >= panels.len(),
                narrow: cols == 1,
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
    narrow: bool,
}

/// A legend sample.
#[derive(Clone, Copy)]
enum Sample {
    /// A solid or dashed line.
    Line(RGBColor, bool),
    /// The η(2/3) dot.
    Dot,
    /// Two finite-element markers (n = 2 and n = 1 colours): filled or hollow, diamond or square.
    Markers { filled: bool, square: bool },
}

impl Sample {
    /// Width of the sample \[pt\].
    fn width(self) -> f64 {
        match self {
            Sample::Line(..) => 16.0,
            Sample::Dot => 6.0,
            Sample::Markers { .. } => 16.0,
        }
    }
}

/// Title lines and legend items laid out in rows that fit the width.
struct Header {
    title: Vec<String>,
    items: Vec<(Sample, String, (f64, i32))>,
    rows: i32,
}

impl Header {
    fn new(width_pt: f64, design: &Fig6Design, points: &[Fig6Point]) -> Self {
        let with_points = !points.is_empty();
        // the payloads of the diamonds (light) and the squares (heavy), as they ran
        let payloads = |heavy: bool| {
            let mut m: Vec<f64> = points
                .iter()
                .map(|p| p.case.m_e)
                .filter(|&m| (m > HEAVY_PAYLOAD) == heavy)
                .collect();
            m.sort_by(f64::total_cmp);
            m.dedup();
            m.iter().map(|m| m.to_string()).collect::<Vec<_>>()
        };
        let long = "Peak-force ratio η = f_max(γ)/f_max(1), compliant link (γ) over compliant joint (γ = 1)";
        let short = "η = f_max(γ)/f_max(1): compliant link (γ) over joint (γ = 1)";
        let shortest = "η = f_max(γ)/f_max(1), CL (γ) over CJ (γ = 1)";
        let first = [long, short, shortest]
            .into_iter()
            .find(|t| text_width_pt(t, TITLE_PT) < width_pt - 8.0)
            .unwrap_or(shortest);
        let title = vec![
            first.to_string(),
            format!(
                "m_r = {} kg, k_c = {} N/mⁿ, v_0 = {} m/s",
                design.m_r,
                super::sci_label(design.k_c),
                design.v0
            ),
        ];
        let mut items = vec![
            (
                Sample::Line(BLUE, false),
                "n = 2 (Hertz contact)".to_string(),
            ),
            (
                Sample::Line(ORANGE, true),
                "n = 1 (linear contact)".to_string(),
            ),
            (Sample::Dot, "η(2/3), uniform compliant link".to_string()),
        ];
        if with_points {
            for (square, m) in [(false, payloads(false)), (true, payloads(true))] {
                if !m.is_empty() {
                    items.push((
                        Sample::Markers {
                            filled: true,
                            square,
                        },
                        format!("η_FE, m_e = {} kg", m.join(", ")),
                    ));
                }
            }
            items.extend([(
                Sample::Markers {
                    filled: false,
                    square: false,
                },
                "hollow: η_FE off its curve, drawn at γ = 1".to_string(),
            )]);
        }
        // flow the items into rows
        let (mut x, mut row) = (4.0, 0);
        let mut placed = Vec::new();
        for (sample, label) in items {
            let w = sample.width() + 4.0 + text_width_pt(&label, LABEL_PT) + 12.0;
            if x + w > width_pt && x > 4.0 {
                row += 1;
                x = 4.0;
            }
            placed.push((sample, label, (x, row)));
            x += w;
        }
        Header {
            title,
            items: placed,
            rows: row + 1,
        }
    }

    /// Height \[pt\].
    fn height(&self) -> u32 {
        (ROW_H * (self.title.len() as i32 + self.rows) + 6) as u32
    }

    fn draw(&self, area: &DrawingArea<SVGBackend, Shift>) -> Result<(), String> {
        let (w, _) = area.dim_in_pixel();
        for (i, line) in self.title.iter().enumerate() {
            let (size, colour) = if i == 0 {
                (TITLE_PT, BLACK)
            } else {
                (LABEL_PT, GREY)
            };
            area.draw(&Text::new(
                line.clone(),
                (w as i32 / 2, px(2 + ROW_H * i as i32)),
                text(size, colour, HPos::Center, VPos::Top),
            ))
            .map_err(err)?;
        }
        let top = ROW_H * self.title.len() as i32 + 2;
        for (sample, label, (x, row)) in &self.items {
            let y = px(top + ROW_H * row + ROW_H / 2);
            let x0 = px(x.round() as i32);
            match *sample {
                Sample::Line(colour, dashed) => legend_line(area, (x0, y), colour, dashed)?,
                Sample::Dot => {
                    area.draw(&Circle::new((x0 + px(3), y), px(2), BLACK.filled()))
                        .map_err(err)?;
                }
                Sample::Markers { filled, square } => {
                    for (dx, colour) in [(4, BLUE), (12, ORANGE)] {
                        marker(
                            area,
                            (x0 + px(dx), y),
                            filled.then_some(colour),
                            colour,
                            square,
                        )?;
                    }
                }
            }
            area.draw(&Text::new(
                label.clone(),
                (x0 + px((sample.width() + 4.0) as i32), y),
                text(LABEL_PT, BLACK, HPos::Left, VPos::Center),
            ))
            .map_err(err)?;
        }
        Ok(())
    }
}

/// A finite-element marker at `at` (drawing units): a diamond (a square when `square`) filled
/// with `fill` (white when hollow) and edged in `edge` (wide when hollow, thin black when filled).
fn marker(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    fill: Option<RGBColor>,
    edge: RGBColor,
    square: bool,
) -> Result<(), String> {
    let r = DIAMOND;
    let corners = if square {
        let h = r * 3 / 4;
        vec![
            (x - h, y - h),
            (x + h, y - h),
            (x + h, y + h),
            (x - h, y + h),
        ]
    } else {
        vec![(x, y - r), (x + r, y), (x, y + r), (x - r, y)]
    };
    area.draw(&Polygon::new(
        corners.clone(),
        fill.unwrap_or(WHITE).filled(),
    ))
    .map_err(err)?;
    let mut closed = corners.clone();
    closed.push(corners[0]);
    closed.push(corners[1]);
    let style = match fill {
        Some(_) => stroke(BLACK, 0.5),
        None => stroke(edge, 1.25),
    };
    area.draw(&PathElement::new(closed, style)).map_err(err)
}

/// A 16-point legend sample of a solid or dashed line starting at `(x, y)`.
fn legend_line(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    colour: RGBColor,
    dashed: bool,
) -> Result<(), String> {
    let style = stroke(colour, 1.25);
    let segments: Vec<(i32, i32)> = if dashed {
        vec![(0, 4), (6, 10), (12, 16)]
    } else {
        vec![(0, 16)]
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

/// Short description of a case's human mass and link stiffness, as long as fits `width_pt`.
fn panel_caption(letter: char, case: &Fig6Case, width_pt: f64) -> String {
    let long = panel_caption_long(letter, case);
    if text_width_pt(&long, LABEL_PT) < width_pt - 8.0 {
        return long;
    }
    format!(
        "({letter}) m_h = {} kg, k_δ = {} N/m",
        case.m_h,
        sci_label(case.k_delta)
    )
}

/// The long caption: masses, stiffness and what they mean.
fn panel_caption_long(letter: char, case: &Fig6Case) -> String {
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
    let (w, _) = area.dim_in_pixel();
    let caption = panel_caption(place.letter, &first.case, f64::from(w) / px(1) as f64);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, font(LABEL_PT))
        .margin_top(px(3))
        .margin_left(px(4))
        .margin_right(px(8))
        .margin_bottom(px(2))
        .x_label_area_size(px(if place.bottom { 28 } else { 14 }))
        .y_label_area_size(px(if place.left { 30 } else { 8 }))
        .build_cartesian_2d(
            Linear::new(axis.left, axis.right, ticks(g0, g1, 0.1)),
            Linear::new(axis.lo, axis.top, axis.ticks()),
        )
        .map_err(err)?;
    let left = place.left;
    chart
        .configure_mesh()
        .bold_line_style(stroke(GRID, 0.75))
        .axis_style(stroke(BLACK, 0.75))
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .x_desc(match (place.bottom, place.narrow) {
            (false, _) => "",
            (true, false) => "γ (1 = compliant joint, 2/3 = uniform compliant link)",
            (true, true) => "γ (1: compliant joint, 2/3: uniform link)",
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
            px(2),
            px(2),
            stroke(GREY, 0.75),
        ))
        .map_err(err)?;
    let mut payloads: Vec<f64> = curves.iter().map(|c| c.case.m_e).collect();
    payloads.dedup();
    let mut rows = Vec::new();
    let mut labels = Vec::new();
    for m_e in &payloads {
        let pair: Vec<&EtaCurve> = curves
            .iter()
            .copied()
            .filter(|c| c.case.m_e == *m_e)
            .collect();
        labels.extend(draw_pair(&mut chart, &pair, span)?);
        rows.push(table_row(&pair, span));
    }
    let origin = chart.plotting_area().get_base_pixel();
    let to_pixel = |p: (f64, f64)| {
        let (x, y) = chart.backend_coord(&p);
        (x - origin.0, y - origin.1)
    };
    let mut obstacles = Vec::new();
    for c in curves {
        obstacles.extend(c.gamma.iter().zip(&c.eta).map(|(g, e)| {
            let (x, y) = to_pixel((*g, *e));
            ((x, y), (x, y))
        }));
    }
    let (plot_w, _) = chart.plotting_area().dim_in_pixel();
    let markers = place_markers(points, to_pixel, plot_w as i32);
    obstacles.extend(markers.iter().flat_map(placed_boxes));
    // Each payload is labelled under its pair's start; if that leaves the table no free
    // corner, the lowest pair's label goes above its start instead.
    let mut placed: Vec<PixelRect> = labels.iter().map(|l| l.below).collect();
    let with = |placed: &[PixelRect]| [obstacles.as_slice(), placed].concat();
    if table_corner(&chart, axis, &rows, &with(&placed)).is_none()
        && let Some(lowest) = (0..labels.len()).max_by_key(|i| labels[*i].below.0.1)
    {
        placed[lowest] = labels[lowest].above;
    }
    let area = chart.plotting_area().strip_coord_spec();
    for (label, rect) in labels.iter().zip(&placed) {
        area.draw(&Text::new(
            label.text.clone(),
            rect.0,
            text(TICK_PT, BLACK, HPos::Left, VPos::Top),
        ))
        .map_err(err)?;
    }
    draw_table(&chart, axis, &rows, &with(&placed))?;
    draw_points(&chart, &markers)
}

/// A payload's label and its two places: under its pair's start, and above it.
struct PairLabel {
    text: String,
    below: PixelRect,
    above: PixelRect,
}

/// A finite-element marker where it is drawn.
struct Placed {
    marker: Marker,
    /// Centre of the marker [drawing units, from the plotting area's corner].
    at: (i32, i32),
    /// Set when the marker was moved out of a cluster of on-curve markers that would cover
    /// each other: its own point on the curve (drawn as a dot) and the top of the leader line
    /// that joins the cluster's column to it.
    callout: Option<Callout>,
}

/// Where a moved marker belongs, and the leader line of its cluster.
#[derive(Clone, Copy)]
struct Callout {
    /// The marker's own point on its curve.
    point: (i32, i32),
    /// The leader line from the cluster's points down to its column (drawn once, by the
    /// column's first marker).
    leader: Option<((i32, i32), (i32, i32))>,
}

/// The markers of `points` with their pixel centres. On-curve markers sit where they belong,
/// except where two or more would cover each other (their points lie within a marker's width,
/// e.g. several η_FE ≈ 1 at γ ≈ 1): those are set in a column below their points, highest η
/// first, each with its value beside it, their points marked by dots and joined to the column
/// by a leader line. Off-curve markers sit at the edge, each moved inwards by a marker's width
/// while it would cover a marker placed before it (their γ means only "off the curve").
/// `width` is the plotting area's width in drawing units.
fn place_markers(
    points: &[&Fig6Point],
    to_pixel: impl Fn((f64, f64)) -> (i32, i32),
    width: i32,
) -> Vec<Placed> {
    let step = 2 * DIAMOND + px(1);
    let near = |a: (i32, i32), b: (i32, i32)| (a.0 - b.0).abs() < step && (a.1 - b.1).abs() < step;
    let on: Vec<(Marker, (i32, i32))> = points
        .iter()
        .map(|p| Marker::of(p))
        .filter(|m| m.on_curve)
        .map(|m| {
            let at = to_pixel((m.gamma, m.eta));
            (m, at)
        })
        .collect();
    let mut placed: Vec<Placed> = Vec::new();
    for cluster in clusters(&on.iter().map(|(_, at)| *at).collect::<Vec<_>>(), near) {
        if let [single] = cluster.as_slice() {
            let (m, at) = &on[*single];
            placed.push(Placed {
                marker: *m,
                at: *at,
                callout: None,
            });
            continue;
        }
        let mut members = cluster.clone();
        members.sort_by(|a, b| on[*b].0.eta.total_cmp(&on[*a].0.eta));
        let n = members.len() as i32;
        let cx = members.iter().map(|i| on[*i].1.0).sum::<i32>() / n;
        let cy = members.iter().map(|i| on[*i].1.1).sum::<i32>() / n;
        let bottom = members.iter().map(|i| on[*i].1.1).max().unwrap_or(cy);
        let x = cx.clamp(DIAMOND + px(1), width - DIAMOND - px(1));
        let first = bottom + step + px(4);
        for (k, i) in members.iter().enumerate() {
            let (m, point) = &on[*i];
            let y = first + k as i32 * step;
            placed.push(Placed {
                marker: *m,
                at: (x, y),
                callout: Some(Callout {
                    point: *point,
                    leader: (k == 0).then_some(((cx, cy), (x, y - DIAMOND))),
                }),
            });
        }
    }
    for p in points {
        let m = Marker::of(p);
        if m.on_curve {
            continue;
        }
        let (mut x, y) = to_pixel((m.gamma, m.eta));
        let inwards = if m.gamma < GAMMA_RANGE.0 + 0.5 * GAMMA_PAD {
            1
        } else {
            -1
        };
        while placed.iter().any(|q| near((x, y), q.at)) {
            x += inwards * step;
        }
        placed.push(Placed {
            marker: m,
            at: (x, y),
            callout: None,
        });
    }
    placed
}

/// The groups of `points` joined (directly or through others) by `near`, each in the order of
/// `points`, the groups in the order of their first member.
fn clusters(
    points: &[(i32, i32)],
    near: impl Fn((i32, i32), (i32, i32)) -> bool,
) -> Vec<Vec<usize>> {
    let mut group: Vec<usize> = (0..points.len()).collect();
    fn root(group: &mut [usize], mut i: usize) -> usize {
        while group[i] != i {
            group[i] = group[group[i]];
            i = group[i];
        }
        i
    }
    for i in 0..points.len() {
        for j in 0..i {
            if near(points[i], points[j]) {
                let (a, b) = (root(&mut group, i), root(&mut group, j));
                group[a.max(b)] = a.min(b);
            }
        }
    }
    let mut out: Vec<Vec<usize>> = Vec::new();
    let mut roots: Vec<usize> = Vec::new();
    for i in 0..points.len() {
        let r = root(&mut group, i);
        match roots.iter().position(|&q| q == r) {
            Some(k) => out[k].push(i),
            None => {
                roots.push(r);
                out.push(vec![i]);
            }
        }
    }
    out
}

/// The pixel boxes a placed marker covers: the marker, and for a moved one its value.
fn placed_boxes(p: &Placed) -> Vec<PixelRect> {
    let (x, y) = p.at;
    let r = DIAMOND;
    let mut boxes = vec![((x - r, y - r), (x + r, y + r))];
    if p.callout.is_some() {
        let w = px(text_width_pt(&value_label(p.marker.eta), TICK_PT).ceil() as i32);
        let h = px(TICK_PT as i32) / 2;
        boxes.push(((x - r - px(2) - w, y - h), (x - r - px(2), y + h)));
    }
    boxes
}

/// η_FE as written beside a moved marker: to four decimals, one more than the η(2/3) table,
/// since the markers of a cluster lie within a few 10⁻³ of each other.
fn value_label(eta: f64) -> String {
    format!("{eta:.4}")
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
) -> Result<Option<PairLabel>, String> {
    let mut sorted = pair.to_vec();
    sorted.sort_by(|a, b| b.n.total_cmp(&a.n));
    for c in &sorted {
        let points: Vec<(f64, f64)> = c.gamma.iter().copied().zip(c.eta.iter().copied()).collect();
        if c.n == 1.0 {
            chart
                .draw_series(DashedLineSeries::new(
                    points,
                    px(4),
                    px(2),
                    stroke(ORANGE, 1.25),
                ))
                .map_err(err)?;
        } else {
            chart
                .draw_series(LineSeries::new(points, stroke(BLUE, 1.25)))
                .map_err(err)?;
        }
    }
    for c in &sorted {
        chart
            .draw_series(std::iter::once(Circle::new(
                (2.0 / 3.0, c.eta_at_2_3),
                px(2),
                curve_colour(c.n).filled(),
            )))
            .map_err(err)?;
    }
    // Below the pair's lower start: the curves rise to the right, so that corner is free (or
    // above its upper start, `above`).
    let start = sorted
        .iter()
        .filter_map(|c| c.eta.first().copied())
        .fold(f64::MAX, f64::min);
    // the pair's highest η under the label (which reaches about 0.16 into the γ range)
    let top = sorted
        .iter()
        .flat_map(|c| c.gamma.iter().zip(&c.eta))
        .filter(|(g, _)| **g <= GAMMA_RANGE.0 + 0.16)
        .map(|(_, e)| *e)
        .fold(f64::MIN, f64::max);
    let Some(case) = sorted.first().map(|c| c.case) else {
        return Ok(None);
    };
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let label = format!("m_e = {} kg", case.m_e);
    let width = px(text_width_pt(&label, TICK_PT).round() as i32);
    let height = px(TICK_PT as i32);
    let (x, y_below) = chart.backend_coord(&(GAMMA_RANGE.0, start - 0.015 * span));
    let (_, y_above) = chart.backend_coord(&(GAMMA_RANGE.0, top + 0.02 * span));
    let x = x - origin.0 + px(4);
    let rect = |y: i32| ((x, y), (x + width, y + height));
    Ok(Some(PairLabel {
        text: label,
        below: rect(y_below - origin.1),
        above: rect(y_above - origin.1 - height),
    }))
}

/// Colour of the curves of exponent `n`: blue for n = 2, orange for n = 1.
fn curve_colour(n: f64) -> RGBColor {
    if n == 1.0 { ORANGE } else { BLUE }
}

/// Payloads above this are drawn as squares, those at or below it as diamonds \[kg\] (the
/// paper's cases: 0.1 and 10 kg).
const HEAVY_PAYLOAD: f64 = 1.0;

/// Where and how a finite-element point is drawn.
#[derive(Clone, Copy)]
struct Marker {
    gamma: f64,
    eta: f64,
    colour: RGBColor,
    on_curve: bool,
    /// The heavier payload (drawn as a square; the lighter as a diamond).
    square: bool,
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
            square: p.case.m_e > HEAVY_PAYLOAD,
        }
    }
}

/// The finite-element markers at their places: filled on the curve, hollow off it; a moved
/// marker with its value on its left, a dot on its own point and its cluster's leader line.
fn draw_points(chart: &Chart, placed: &[Placed]) -> Result<(), String> {
    let area = chart.plotting_area().strip_coord_spec();
    for c in placed.iter().filter_map(|p| p.callout) {
        if let Some((from, to)) = c.leader {
            area.draw(&PathElement::new(vec![from, to], stroke(GREY, 0.5)))
                .map_err(err)?;
        }
    }
    for p in placed {
        let m = &p.marker;
        marker(
            &area,
            p.at,
            m.on_curve.then_some(m.colour),
            m.colour,
            m.square,
        )?;
        if let Some(c) = p.callout {
            area.draw(&Circle::new(c.point, px(1) + 2, m.colour.filled()))
                .map_err(err)?;
            area.draw(&Text::new(
                value_label(m.eta),
                (p.at.0 - DIAMOND - px(2), p.at.1),
                text(TICK_PT, BLACK, HPos::Right, VPos::Center),
            ))
            .map_err(err)?;
        }
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

/// The notes of a panel's table and its three candidate boxes (lower right, lower left, upper
/// left), 3 points in from the frame.
fn table_geometry(
    chart: &Chart,
    axis: EtaAxis,
    rows: &[TableRow],
) -> (Vec<String>, [PixelRect; 3]) {
    let origin = chart.plotting_area().get_base_pixel();
    // one note for every payload whose n = 1 and n = 2 curves coincide on the plot
    let gaps: Vec<f64> = rows.iter().filter_map(|r| r.coincide).collect();
    let notes: Vec<String> = match gaps.len() {
        0 => Vec::new(),
        k => {
            let gap = gaps.iter().copied().fold(0.0, f64::max);
            let which = if k == rows.len() {
                "n = 1 and 2 coincide".to_string()
            } else {
                let m: Vec<String> = rows
                    .iter()
                    .filter(|r| r.coincide.is_some())
                    .map(|r| format!("{} kg", r.m_e))
                    .collect();
                format!("{}: n = 1 and 2 coincide", m.join(", "))
            };
            vec![format!("{which}, |Δη| ≤ {}", sci_label(round_up_1(gap)))]
        }
    };
    let line = px(10);
    let c2 = px(60);
    let label_w = rows
        .iter()
        .map(|r| text_width_pt(&format!("m_e = {} kg", r.m_e), TICK_PT))
        .fold(text_width_pt("η(2/3)", TICK_PT), f64::max);
    let table_w = px(label_w.ceil() as i32) + c2 + px(8);
    // the note broken to the table's width: a narrow table fits the corner under the curves
    let notes: Vec<String> = notes
        .iter()
        .flat_map(|n| super::wrap(n, label_w.ceil() + 60.0, TICK_PT))
        .collect();
    let lines = 1 + rows.len() + notes.len();
    let height = line * lines as i32 + px(4);
    let note_w = notes
        .iter()
        .map(|n| px(text_width_pt(n, TICK_PT).ceil() as i32 + 8))
        .max()
        .unwrap_or(0);
    let width = table_w.max(note_w);
    let corner = |g: f64, eta: f64| {
        let (x, y) = chart.backend_coord(&(g, eta));
        (x - origin.0, y - origin.1)
    };
    let (x_left, y_bottom) = corner(axis.left, axis.lo);
    let (x_right, y_top) = corner(axis.right, axis.top);
    // Boxes ((x0, y0), (x1, y1)), 4 pixels in from the frame.
    let inset = px(3);
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
    (notes, boxes)
}

/// The first candidate box of the table that covers none of `obstacles`.
fn table_corner(
    chart: &Chart,
    axis: EtaAxis,
    rows: &[TableRow],
    obstacles: &[PixelRect],
) -> Option<PixelRect> {
    let (_, boxes) = table_geometry(chart, axis, rows);
    boxes
        .into_iter()
        .find(|b| !obstacles.iter().any(|o| overlap(b, o, px(2))))
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
    let (notes, boxes) = table_geometry(chart, axis, rows);
    let line = px(10);
    let (c1, c2) = (px(30), px(60));
    let chosen = table_corner(chart, axis, rows, obstacles).unwrap_or(boxes[0]);
    let ((x0, y0), (x1, y1)) = chosen;
    // a framed box, as a legend: it reads as a label over the grid, not a hole in it
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], WHITE.filled()))
        .map_err(err)?;
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], stroke(GRID, 0.75)))
        .map_err(err)?;
    let right = x1 - px(4);
    let cell = |s: String, x: i32, y: i32, colour: RGBColor| {
        Text::new(s, (x, y), text(TICK_PT, colour, HPos::Right, VPos::Bottom))
    };
    let mut y = y0 + line + px(1);
    let header = [
        ("η(2/3)", right - c2),
        ("n = 2", right - c1),
        ("n = 1", right),
    ];
    for (s, x) in header {
        area.draw(&cell(s.into(), x, y, BLACK)).map_err(err)?;
    }
    for r in rows {
        y += line;
        area.draw(&cell(format!("m_e = {} kg", r.m_e), right - c2, y, BLACK))
            .map_err(err)?;
        area.draw(&cell(format!("{:.3}", r.eta_n2), right - c1, y, BLUE))
            .map_err(err)?;
        area.draw(&cell(format!("{:.3}", r.eta_n1), right, y, ORANGE))
            .map_err(err)?;
    }
    for note in notes {
        y += line;
        area.draw(&Text::new(
            note,
            (right, y),
            text(TICK_PT, GREY, HPos::Right, VPos::Bottom),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// `v` rounded up to one significant digit (9.3e-5 → 1e-4, 8.2e-5 → 9e-5).
fn round_up_1(v: f64) -> f64 {
    if !(v > 0.0) {
        return v;
    }
    let decade = 10f64.powf(v.log10().floor());
    (v / decade - 1e-9).ceil() * decade
}

/// Whether boxes `a` and `b`, `a` grown by `pad` pixels, overlap.
fn overlap(a: &PixelRect, b: &PixelRect, pad: i32) -> bool {
    let ((ax0, ay0), (ax1, ay1)) = *a;
    let ((bx0, by0), (bx1, by1)) = *b;
    ax0 - pad <= bx1 && bx0 <= ax1 + pad && ay0 - pad <= by1 && by0 <= ay1 + pad
}

#[cfg(test)]
mod tests;
