//! The paper's Fig. 6: η(γ) of the eight design cases.
//!
//! Four panels (human mass × link stiffness) on one shared y scale; each holds both payloads
//! (the light payload's pair of curves well below the heavy payload's, labelled on the curves),
//! n = 2 solid blue and n = 1 dashed orange as in the paper, η(2/3) marked and tabulated in the
//! panel's empty lower-right corner, and a note where the n = 1 and n = 2 curves coincide.

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
/// Top of the shared y axis: a little above η = 1 so the curves' end points stay visible.
const Y_TOP: f64 = 1.02;
/// Two curves closer than this fraction of the y span everywhere are drawn as coinciding.
const COINCIDE: f64 = 0.005;

/// The paper's Fig. 6 from the sixteen curves of `flexrig_lumped::fig6::fig6`.
pub fn fig6_svg(curves: &[EtaCurve]) -> Result<String, String> {
    let y_min = curves
        .iter()
        .flat_map(|c| c.eta.iter().copied())
        .fold(1.0, f64::min);
    let y_lo = ((y_min - 0.01) * 10.0).floor() / 10.0;
    let panels = panel_keys(curves);
    render(SIZE, |root| {
        let (header, body) = root.split_vertically(px(HEADER as i32));
        draw_header(&header)?;
        let areas = body.split_evenly((2, 2));
        for (i, (area, key)) in areas.iter().zip(&panels).enumerate() {
            let of_panel: Vec<&EtaCurve> = curves
                .iter()
                .filter(|c| (c.case.m_h, c.case.k_delta) == *key)
                .collect();
            let place = Place {
                letter: (b'a' + i as u8) as char,
                left: i % 2 == 0,
                bottom: i >= 2,
            };
            draw_panel(area, &of_panel, y_lo, place)?;
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

fn draw_header(area: &DrawingArea<SVGBackend, Shift>) -> Result<(), String> {
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
    .map_err(err)
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
    y_lo: f64,
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
            Linear::new(g0, g1, ticks(g0, g1, 0.1)),
            Linear::new(y_lo, Y_TOP, ticks(y_lo, 1.0, 0.1)),
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
    let span = Y_TOP - y_lo;
    chart
        .draw_series(DashedLineSeries::new(
            [(2.0 / 3.0, y_lo), (2.0 / 3.0, Y_TOP)],
            px(3),
            px(4),
            stroke(GREY, 1.0),
        ))
        .map_err(err)?;
    let mut payloads: Vec<f64> = curves.iter().map(|c| c.case.m_e).collect();
    payloads.dedup();
    let mut rows = Vec::new();
    for m_e in payloads {
        let pair: Vec<&EtaCurve> = curves
            .iter()
            .copied()
            .filter(|c| c.case.m_e == m_e)
            .collect();
        draw_pair(&mut chart, &pair, span)?;
        rows.push(table_row(&pair, span));
    }
    draw_table(&chart, y_lo, &rows)
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Linear, Linear>>;

/// One payload's n = 2 (solid) and n = 1 (dashed, drawn on top) curves, η(2/3) marked, and the
/// payload written under the pair's left end.
fn draw_pair(chart: &mut Chart, pair: &[&EtaCurve], span: f64) -> Result<(), String> {
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
        let colour = if c.n == 1.0 { ORANGE } else { BLUE };
        chart
            .draw_series(std::iter::once(Circle::new(
                (2.0 / 3.0, c.eta_at_2_3),
                px(4),
                colour.filled(),
            )))
            .map_err(err)?;
    }
    // Below the pair's lower start: the curves rise to the right, so that corner is free.
    let start = sorted
        .iter()
        .filter_map(|c| c.eta.first().copied())
        .fold(f64::MAX, f64::min);
    let Some(case) = sorted.first().map(|c| c.case) else {
        return Ok(());
    };
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let (x, y) = chart.backend_coord(&(GAMMA_RANGE.0, start - 0.015 * span));
    boxed_text(
        &area,
        &format!("m_e = {} kg", case.m_e),
        (x - origin.0 + px(8), y - origin.1),
        text(12.0, BLACK, HPos::Left, VPos::Top),
    )
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

/// The η(2/3) table in the lower-right corner (below every curve there), with a note for
/// coinciding curves.
fn draw_table(chart: &Chart, y_lo: f64, rows: &[TableRow]) -> Result<(), String> {
    let corner = chart.backend_coord(&(GAMMA_RANGE.1, y_lo));
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let (right, bottom) = (corner.0 - origin.0 - px(8), corner.1 - origin.1 - px(6));
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
    let top = bottom - line * lines as i32 - px(4);
    let width = if notes.is_empty() { px(190) } else { px(300) };
    area.draw(&Rectangle::new(
        [(right - width, top), (right + px(4), bottom + px(2))],
        ShapeStyle::from(&WHITE.mix(0.9)).filled(),
    ))
    .map_err(err)?;
    let cell = |s: String, x: i32, y: i32, colour: RGBColor| {
        Text::new(s, (x, y), text(12.0, colour, HPos::Right, VPos::Bottom))
    };
    let mut y = top + line + px(2);
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
