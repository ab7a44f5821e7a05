//! `flexrig eta-rotor`'s figure: η_FE along the free hub's rotor inertia, one panel per head mass
//! and link stiffness, one curve per payload (colour) and exponent (n = 2 solid, n = 1 dashed on
//! top, so coinciding curves both show), the held joint as a diamond in a column of its own at
//! the right (filled for n = 2, hollow for n = 1, each curve's diamond in a slot of its own so
//! equal values do not hide each other), each panel on its own η range (the variation is what
//! matters), one legend.

use std::collections::BTreeMap;

use flexrig_impact::rotor::RotorPoint;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, LABEL_PT, Linear, PALETTE, TICK_PT, TITLE_PT, decade_label, err, font, nice_step,
    px, render, sci_label, stroke, text, text_width_pt, ticks,
};

/// Narrowest panel \[pt\].
const MIN_PANEL_W: f64 = 240.0;
/// Height of a panel \[pt\].
const PANEL_H: u32 = 165;
/// Flattest panel \[pt\] (with its axes) when the stack is flattened to fit a page's column.
const MIN_PANEL_H: u32 = 120;
/// Height of a title or legend line \[pt\].
const LINE: i32 = 12;
/// Spacing of the held joint's diamonds in their column \[pt\].
const HELD_SLOT: f64 = 7.0;

/// A curve key: payload m_e \[kg\] and exponent n, as bit patterns for ordering.
type Key = (u64, u64);

/// One curve: (log10 ratio, η) points and the held η.
type CurvePoints = (Vec<(f64, f64)>, Option<f64>);

/// One panel: (m_h, k_δ) and its curves by (m_e, n).
struct Panel {
    m_h: f64,
    k_delta: f64,
    curves: BTreeMap<Key, CurvePoints>,
}

fn panels(points: &[RotorPoint]) -> Vec<Panel> {
    let mut out: Vec<Panel> = Vec::new();
    for p in points {
        let i = match out
            .iter()
            .position(|q| q.m_h == p.case.m_h && q.k_delta == p.case.k_delta)
        {
            Some(i) => i,
            None => {
                out.push(Panel {
                    m_h: p.case.m_h,
                    k_delta: p.case.k_delta,
                    curves: BTreeMap::new(),
                });
                out.len() - 1
            }
        };
        let curve = out[i]
            .curves
            .entry((p.case.m_e.to_bits(), p.n.to_bits()))
            .or_default();
        if !p.eta_fe.is_finite() {
            continue;
        }
        match p.inertia_ratio {
            Some(r) if r > 0.0 && r.is_finite() => curve.0.push((r.log10(), p.eta_fe)),
            Some(_) => {}
            None => curve.1 = Some(p.eta_fe),
        }
    }
    out
}

/// The payloads in ascending order (each its colour).
fn payloads(points: &[RotorPoint]) -> Vec<f64> {
    let mut v: Vec<f64> = points.iter().map(|p| p.case.m_e).collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The colour of payload `m_e`.
fn colour(payloads: &[f64], m_e: f64) -> RGBColor {
    let i = payloads.iter().position(|p| *p == m_e).unwrap_or(0);
    PALETTE[i % PALETTE.len()]
}

/// The η_FE-over-rotor-inertia figure at the printed width `width_pt` \[pt\]; `subtitle` says
/// the contact and the constants.
pub fn eta_rotor_svg(
    points: &[RotorPoint],
    subtitle: &str,
    width_pt: f64,
) -> Result<String, String> {
    let panels = panels(points);
    if panels.is_empty() {
        return Err("no points to draw".into());
    }
    let payloads = payloads(points);
    let (x_lo, x_hi) = decades(&panels);
    let cols = ((width_pt / MIN_PANEL_W).floor() as usize).clamp(1, panels.len());
    let rows = panels.len().div_ceil(cols);
    let legend = Legend::new(&payloads, points, width_pt);
    let subtitle = super::wrap(subtitle, width_pt - 8.0, LABEL_PT);
    let title_lines = 1 + subtitle.len() as i32;
    let header = title_lines * LINE + LINE * legend.rows + 6;
    // panels stacked in one column are flattened to stay within a page's column
    let panel_h = super::page::fitted_chart_height(PANEL_H, rows, header as u32, 0, MIN_PANEL_H);
    let size = (
        width_pt.round() as u32,
        header as u32 + panel_h * rows as u32,
    );
    render(size, |root| {
        let (head, body) = root.split_vertically(px(header));
        let w = px(width_pt.round() as i32);
        let title = [
            "η_FE = f_max(CL)/f_max(CJ) from a freely pivoting link (J_R → 0) to the held joint",
            "η_FE from a free link (J_R → 0) to the held joint",
        ]
        .into_iter()
        .find(|t| text_width_pt(t, TITLE_PT) < width_pt - 8.0)
        .unwrap_or("η_FE over the rotor inertia");
        let lines = std::iter::once((title, TITLE_PT, BLACK))
            .chain(subtitle.iter().map(|l| (l.as_str(), LABEL_PT, GREY)));
        for (i, (line, size, colour)) in lines.enumerate() {
            head.draw(&Text::new(
                line.to_string(),
                (w / 2, px(2 + LINE * i as i32)),
                text(size, colour, HPos::Center, VPos::Top),
            ))
            .map_err(err)?;
        }
        legend.draw(&head, title_lines * LINE + 4)?;
        let areas = body.split_evenly((rows, cols));
        for (i, (area, panel)) in areas.iter().zip(&panels).enumerate() {
            let letter = (b'a' + i as u8) as char;
            let bottom = i + cols >= panels.len();
            draw_panel(area, panel, letter, (x_lo, x_hi), &payloads, bottom)?;
        }
        Ok(())
    })
}

/// Whole decades enclosing every ratio (log10).
fn decades(panels: &[Panel]) -> (i32, i32) {
    let (lo, hi) = panels
        .iter()
        .flat_map(|p| p.curves.values())
        .flat_map(|c| c.0.iter())
        .fold((f64::MAX, f64::MIN), |(lo, hi), (x, _)| {
            (lo.min(*x), hi.max(*x))
        });
    if lo > hi {
        return (0, 1);
    }
    let a = (lo + 1e-9).floor() as i32;
    let b = (hi - 1e-9).ceil() as i32;
    (a, b.max(a + 1))
}

/// The legend entries flowed into rows.
struct Legend {
    items: Vec<(Item, String, f64, i32)>,
    rows: i32,
}

#[derive(Clone, Copy)]
enum Item {
    Colour(RGBColor),
    Line(bool),
    /// The held joint's diamond, hollow for n = 1.
    Held {
        hollow: bool,
    },
}

impl Legend {
    fn new(payloads: &[f64], points: &[RotorPoint], width_pt: f64) -> Self {
        let mut entries: Vec<(Item, String)> = payloads
            .iter()
            .map(|m| (Item::Colour(colour(payloads, *m)), format!("m_e = {m} kg")))
            .collect();
        let mut ns: Vec<f64> = points.iter().map(|p| p.n).collect();
        ns.sort_by(|a, b| b.total_cmp(a));
        ns.dedup();
        for n in &ns {
            entries.push((Item::Line(*n < 1.5), format!("n = {n}")));
        }
        for n in &ns {
            entries.push((
                Item::Held { hollow: *n < 1.5 },
                format!("held joint, n = {n}"),
            ));
        }
        let (mut x, mut row) = (4.0, 0);
        let mut items = Vec::new();
        for (item, label) in entries {
            let w = 20.0 + text_width_pt(&label, LABEL_PT) + 12.0;
            if x + w > width_pt && x > 4.0 {
                row += 1;
                x = 4.0;
            }
            items.push((item, label, x, row));
            x += w;
        }
        Legend {
            items,
            rows: row + 1,
        }
    }

    fn draw(&self, area: &DrawingArea<SVGBackend, Shift>, top: i32) -> Result<(), String> {
        for (item, label, x, row) in &self.items {
            let x0 = px(x.round() as i32);
            let y = px(top + LINE * row + LINE / 2);
            match *item {
                Item::Colour(c) => {
                    area.draw(&Rectangle::new(
                        [(x0, y - px(3)), (x0 + px(14), y + px(3))],
                        c.filled(),
                    ))
                    .map_err(err)?;
                }
                Item::Line(dashed) => {
                    let segments: &[(i32, i32)] = if dashed {
                        &[(0, 4), (6, 10), (12, 16)]
                    } else {
                        &[(0, 16)]
                    };
                    for (a, b) in segments {
                        area.draw(&PathElement::new(
                            [(x0 + px(*a), y), (x0 + px(*b), y)],
                            stroke(BLACK, 1.25),
                        ))
                        .map_err(err)?;
                    }
                }
                Item::Held { hollow } => held_marker(area, (x0 + px(7), y), BLACK, hollow)?,
            }
            area.draw(&Text::new(
                label.clone(),
                (x0 + px(20), y),
                text(LABEL_PT, BLACK, HPos::Left, VPos::Center),
            ))
            .map_err(err)?;
        }
        Ok(())
    }
}

/// A diamond at `at` (drawing units) in colour `c`: filled, or white with a `c` edge when
/// `hollow`.
fn held_marker(
    area: &DrawingArea<SVGBackend, Shift>,
    (x, y): (i32, i32),
    c: RGBColor,
    hollow: bool,
) -> Result<(), String> {
    let r = px(3);
    let corners = vec![(x, y - r), (x + r, y), (x, y + r), (x - r, y)];
    area.draw(&Polygon::new(
        corners.clone(),
        if hollow { WHITE } else { c }.filled(),
    ))
    .map_err(err)?;
    if hollow {
        let mut closed = corners.clone();
        closed.extend_from_slice(&corners[..2]);
        area.draw(&PathElement::new(closed, stroke(c, 1.0)))
            .map_err(err)?;
    }
    Ok(())
}

/// The y range of a panel: its values with a margin, at least 0.02 wide.
fn y_range(panel: &Panel) -> (f64, f64, f64) {
    let values = panel
        .curves
        .values()
        .flat_map(|c| c.0.iter().map(|p| p.1).chain(c.1));
    let (lo, hi) = values.fold((f64::MAX, f64::MIN), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let (lo, hi) = if lo > hi { (0.0, 1.0) } else { (lo, hi) };
    let mid = 0.5 * (lo + hi);
    let half = (0.5 * (hi - lo)).max(0.01) * 1.15;
    let step = nice_step(2.0 * half, 4);
    let a = ((mid - half) / step).floor() * step;
    let b = ((mid + half) / step).ceil() * step;
    (a, b, step)
}

fn draw_panel(
    area: &DrawingArea<SVGBackend, Shift>,
    panel: &Panel,
    letter: char,
    (x_lo, x_hi): (i32, i32),
    payloads: &[f64],
    bottom: bool,
) -> Result<(), String> {
    // the held column: a decade and a half wide, room for four diamonds side by side
    let held_x = f64::from(x_hi) + 1.5;
    let (y_lo, y_hi, step) = y_range(panel);
    let x_ticks: Vec<f64> = (x_lo..=x_hi)
        .step_by(((x_hi - x_lo) / 6 + 1) as usize)
        .map(f64::from)
        .chain(std::iter::once(held_x))
        .collect();
    let decimals = (0..6)
        .find(|d| {
            let s = step * 10f64.powi(*d);
            (s - s.round()).abs() < 1e-6
        })
        .unwrap_or(6) as usize;
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "({letter}) m_h = {} kg, k_δ = {} N/m",
                panel.m_h,
                sci_label(panel.k_delta)
            ),
            font(LABEL_PT),
        )
        .margin(px(3))
        .margin_right(px(8))
        .x_label_area_size(px(if bottom { 28 } else { 16 }))
        .y_label_area_size(px(40))
        .build_cartesian_2d(
            Linear::new(f64::from(x_lo), held_x + 1.0, x_ticks),
            Linear::new(y_lo, y_hi, ticks(y_lo, y_hi, step)),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .bold_line_style(stroke(GRID, 0.75))
        .axis_style(stroke(BLACK, 0.75))
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .x_desc(if bottom {
            "rotor over link inertia J_R/(m_r L²/3)"
        } else {
            ""
        })
        .y_desc("η_FE")
        .x_label_formatter(&|x| {
            if (*x - held_x).abs() < 1e-9 {
                "held".into()
            } else {
                decade_label(10f64.powf(*x))
            }
        })
        .y_label_formatter(&|y| format!("{y:.decimals$}"))
        .draw()
        .map_err(err)?;
    // the held column, apart from the sweep
    chart
        .draw_series(DashedLineSeries::new(
            [(held_x - 1.0, y_lo), (held_x - 1.0, y_hi)],
            px(2),
            px(2),
            stroke(GREY, 0.5),
        ))
        .map_err(err)?;
    // n = 2 (solid) first, n = 1 (dashed) over it, and each payload thinner than the one
    // before: coinciding curves all show
    let mut keys: Vec<&Key> = panel.curves.keys().collect();
    keys.sort_by(|a, b| {
        f64::from_bits(b.1)
            .total_cmp(&f64::from_bits(a.1))
            .then(f64::from_bits(a.0).total_cmp(&f64::from_bits(b.0)))
    });
    let slots = keys.len();
    for (slot, key) in keys.into_iter().enumerate() {
        let (points, held) = &panel.curves[key];
        let (m_e, n) = (f64::from_bits(key.0), f64::from_bits(key.1));
        let c = colour(payloads, m_e);
        let order = payloads.iter().position(|p| *p == m_e).unwrap_or(0) as f64;
        let width = (2.5 - 1.25 * order).max(0.75);
        if n < 1.5 {
            chart
                .draw_series(DashedLineSeries::new(
                    points.clone(),
                    px(3),
                    px(2),
                    stroke(c, width),
                ))
                .map_err(err)?;
        } else {
            chart
                .draw_series(LineSeries::new(points.clone(), stroke(c, width)))
                .map_err(err)?;
        }
        if let Some(h) = held {
            let plotting = chart.plotting_area().strip_coord_spec();
            let origin = plotting.get_base_pixel();
            let (x, y) = chart.backend_coord(&(held_x, *h));
            // slots in the order of the curves: n = 2 before n = 1, lighter payload first
            let dx = (slot as f64 - 0.5 * (slots as f64 - 1.0)) * HELD_SLOT;
            let dx = px(1) * dx.round() as i32;
            held_marker(&plotting, (x - origin.0 + dx, y - origin.1), c, n < 1.5)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrig_lumped::fig6::Fig6Case;

    #[test]
    fn one_legend_own_ranges_and_the_held_column() {
        let mut points = Vec::new();
        for (m_e, base) in [(0.1, 0.9), (10.0, 0.3)] {
            for n in [1.0, 2.0] {
                for e in -3..=3 {
                    points.push(RotorPoint {
                        case: Fig6Case {
                            m_h: 4.0,
                            k_delta: 1e8,
                            m_e,
                        },
                        n,
                        inertia_ratio: Some(10f64.powi(e)),
                        f_cj_n: 1.0,
                        f_cl_n: base,
                        eta_fe: base + 0.01 * f64::from(e),
                        severity: None,
                    });
                }
                points.push(RotorPoint {
                    case: Fig6Case {
                        m_h: 4.0,
                        k_delta: 1e8,
                        m_e,
                    },
                    n,
                    inertia_ratio: None,
                    f_cj_n: 1.0,
                    f_cl_n: base,
                    eta_fe: base + 0.05,
                    severity: None,
                });
            }
        }
        let svg = eta_rotor_svg(&points, "elastic contact", 504.0).unwrap();
        let lines = super::super::inspect::texts(&svg);
        for n in ["2", "1"] {
            assert_eq!(
                lines
                    .iter()
                    .filter(|l| **l == format!("held joint, n = {n}"))
                    .count(),
                1,
                "one legend"
            );
        }
        assert!(lines.iter().any(|l| l == "held"));
        assert!(svg.contains("m<tspan") && !svg.contains("1e8"));
    }
}
