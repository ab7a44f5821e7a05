//! The paper's Fig. 9: peak force of CJ and CL, (a) on the test bed (412 g payload) against the
//! aluminium and the iron operator, (b) with the light load, both on one force scale, mean ± 95 %
//! CI with capped whiskers; and (c) the CL/CJ ratio paired by repeat with its 95 % CI.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::{
    GREY, GRID, Linear, PALETTE, boxed_text, err, font, nice_step, px, render, stroke, text, ticks,
};
use crate::experiment::{GroupStats, RatioStats, mean_pm_ci};

/// Colour of the compliant-joint bars.
const CJ: RGBColor = PALETTE[1];
/// Colour of the compliant-link bars.
const CL: RGBColor = PALETTE[0];
/// Nominal size of the figure [px].
const SIZE: (u32, u32) = (1200, 500);
/// Half-width of a whisker cap [px].
const CAP: i32 = 8;

/// A category on the x axis: its two label lines and the scene-name suffix (`aluminium`, ...).
struct Category {
    name: &'static str,
    detail: &'static str,
    key: &'static str,
}

const TEST_BED: [Category; 2] = [
    Category {
        name: "aluminium operator",
        detail: "m_h = 398 g",
        key: "aluminium",
    },
    Category {
        name: "iron operator",
        detail: "m_h = 4008 g",
        key: "iron",
    },
];

const LIGHT_LOAD: [Category; 1] = [Category {
    name: "aluminium operator",
    detail: "m_h = 398 g",
    key: "light_load",
}];

const RATIO_CASES: [Category; 3] = [
    Category {
        name: "aluminium operator",
        detail: "m_e = 412 g",
        key: "aluminium",
    },
    Category {
        name: "iron operator",
        detail: "m_e = 412 g",
        key: "iron",
    },
    Category {
        name: "light load",
        detail: "m_e = 0.1 kg",
        key: "light_load",
    },
];

/// The paper's Fig. 9 from the experiment's per-scene statistics and paired ratios.
pub fn fig9_svg(groups: &[GroupStats], ratios: &[RatioStats]) -> Result<String, String> {
    let top = groups
        .iter()
        .map(|g| g.mean_peak_force_n + g.ci95_n.unwrap_or(0.0))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
        .max(1.0);
    let step = nice_step(top, 6);
    let y_top = (top * 1.05 / step).ceil() * step;
    render(SIZE, |root| {
        let (bars, ratio_area) = root.split_horizontally(px(760));
        let (bed, light) = bars.split_horizontally(px(470));
        let bed_title = format!(
            "(a) test bed, m_e = 412 g: {}",
            runs_note(groups, "aluminium")
        );
        let light_title = format!(
            "(b) light load, m_e = 0.1 kg: {}",
            runs_note(groups, "light_load")
        );
        let axis = ForceAxis { top: y_top, step };
        draw_bars(&bed, &bed_title, &TEST_BED, groups, axis, true)?;
        draw_bars(&light, &light_title, &LIGHT_LOAD, groups, axis, false)?;
        draw_ratios(&ratio_area, ratios)
    })
}

/// "mean ± 95 % CI, 5 runs" or "single run, no CI" for the CL scene of `key`.
fn runs_note(groups: &[GroupStats], key: &str) -> String {
    let n = groups
        .iter()
        .find(|g| g.scene == format!("cl_{key}"))
        .map_or(0, |g| g.n);
    if n > 1 {
        format!("mean ± 95 % CI, {n} runs")
    } else {
        "1 run, no CI".into()
    }
}

/// The force axis shared by panels (a) and (b): top and tick step \[N\].
#[derive(Clone, Copy)]
struct ForceAxis {
    top: f64,
    step: f64,
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<Linear, Linear>>;

/// Categories at x = 0.5, 1.5, …: pairs of bars (CJ at x − 0.5, CL at x + 0.5) in panels with
/// bars, single points in the ratio panel. `width` is the x extent of one category.
fn category_centre(i: usize, width: f64) -> f64 {
    width * (i as f64 + 0.5)
}

fn draw_bars(
    area: &DrawingArea<SVGBackend, Shift>,
    title: &str,
    cats: &[Category],
    groups: &[GroupStats],
    axis: ForceAxis,
    y_desc: bool,
) -> Result<(), String> {
    let width = 3.0;
    let bar_centres: Vec<f64> = (0..cats.len())
        .flat_map(|i| {
            let c = category_centre(i, width);
            [c - 0.5, c + 0.5]
        })
        .collect();
    let mut chart = ChartBuilder::on(area)
        .caption(title, font(14.0))
        .margin(px(10))
        .x_label_area_size(px(58))
        .y_label_area_size(px(if y_desc { 62 } else { 40 }))
        .build_cartesian_2d(
            Linear::new(0.0, width * cats.len() as f64, bar_centres),
            Linear::new(
                0.0,
                axis.top + 0.3 * axis.step,
                ticks(0.0, axis.top, axis.step),
            ),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .bold_line_style(stroke(GRID, 1.0))
        .axis_style(stroke(BLACK, 1.0))
        .set_all_tick_mark_size(px(4))
        .label_style(font(13.0))
        .axis_desc_style(font(14.0))
        .y_desc(if y_desc { "peak impact force [N]" } else { "" })
        .x_label_formatter(&|x| if x.rem_euclid(3.0) < 1.5 { "CJ" } else { "CL" }.into())
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()
        .map_err(err)?;
    for (i, cat) in cats.iter().enumerate() {
        let c = category_centre(i, width);
        for (design, colour, x) in [("cj", CJ, c - 0.5), ("cl", CL, c + 0.5)] {
            if let Some(g) = groups
                .iter()
                .find(|g| g.scene == format!("{design}_{}", cat.key))
            {
                draw_bar(&mut chart, g, colour, x, axis.top)?;
            }
        }
    }
    let cats: Vec<&Category> = cats.iter().collect();
    draw_category_labels(area, &chart, &cats, width, 24)
}

/// One bar at `x` with its capped whisker (none without an interval) and its value written
/// inside the bar's top (above a bar too short to hold it).
fn draw_bar(
    chart: &mut Chart,
    g: &GroupStats,
    colour: RGBColor,
    x: f64,
    y_top: f64,
) -> Result<(), String> {
    let m = g.mean_peak_force_n;
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(x - 0.4, 0.0), (x + 0.4, m)],
            colour.filled(),
        )))
        .map_err(err)?;
    if let Some(ci) = g.ci95_n {
        draw_whisker(chart, x, m, ci)?;
    }
    let low = m - g.ci95_n.unwrap_or(0.0);
    let (y, v, c) = if low > 0.15 * y_top {
        (low - 0.015 * y_top, VPos::Top, WHITE)
    } else {
        (
            m + g.ci95_n.unwrap_or(0.0) + 0.015 * y_top,
            VPos::Bottom,
            BLACK,
        )
    };
    chart
        .draw_series(std::iter::once(Text::new(
            format!("{m:.1}"),
            (x, y),
            text(12.0, c, HPos::Center, v),
        )))
        .map_err(err)?;
    Ok(())
}

/// A vertical whisker from `m − ci` to `m + ci` at `x` with caps.
fn draw_whisker(chart: &mut Chart, x: f64, m: f64, ci: f64) -> Result<(), String> {
    let style = stroke(BLACK, 1.5);
    let cap =
        |y: f64| EmptyElement::at((x, y)) + PathElement::new([(-px(CAP), 0), (px(CAP), 0)], style);
    chart
        .draw_series(std::iter::once(PathElement::new(
            [(x, m - ci), (x, m + ci)],
            style,
        )))
        .map_err(err)?;
    chart.draw_series([cap(m - ci), cap(m + ci)]).map_err(err)?;
    Ok(())
}

/// Each category's two label lines, centred under it, the first `below` pixels under the axis.
fn draw_category_labels(
    area: &DrawingArea<SVGBackend, Shift>,
    chart: &Chart,
    cats: &[&Category],
    width: f64,
    below: i32,
) -> Result<(), String> {
    let origin = area.get_base_pixel();
    let (_, axis) = chart.backend_coord(&(0.0, chart.y_range().start));
    for (i, cat) in cats.iter().enumerate() {
        let (x, _) = chart.backend_coord(&(category_centre(i, width), 0.0));
        let (x, y) = (x - origin.0, axis - origin.1 + px(below));
        area.draw(&Text::new(
            cat.name,
            (x, y),
            text(13.0, BLACK, HPos::Center, VPos::Top),
        ))
        .map_err(err)?;
        area.draw(&Text::new(
            cat.detail,
            (x, y + px(16)),
            text(12.0, GREY, HPos::Center, VPos::Top),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// The y range and tick step of the ratio panel: the intervals and 1 (CL = CJ) with a margin.
fn ratio_axis(ratios: &[RatioStats]) -> (f64, f64, f64) {
    let (mut lo, mut hi) = (1.0_f64, 1.0_f64);
    for r in ratios {
        let ci = r.ci95.unwrap_or(0.0);
        lo = lo.min(r.mean_cl_over_cj - ci);
        hi = hi.max(r.mean_cl_over_cj + ci);
    }
    let pad = 0.2 * (hi - lo).max(1e-3);
    let step = nice_step(hi - lo + 2.0 * pad, 6);
    let lo = ((lo - pad) / step).floor() * step;
    let hi = ((hi + pad) / step).ceil() * step;
    (lo, hi, step)
}

/// Decimals to write ticks of `step` exactly (0.02 → 2, 0.025 → 3).
fn decimals(step: f64) -> usize {
    (0..8)
        .find(|d| {
            let scaled = step * 10f64.powi(*d);
            (scaled - scaled.round()).abs() < 1e-9
        })
        .unwrap_or(8) as usize
}

fn draw_ratios(area: &DrawingArea<SVGBackend, Shift>, ratios: &[RatioStats]) -> Result<(), String> {
    let (lo, hi, step) = ratio_axis(ratios);
    let d = decimals(step);
    let cats: Vec<&Category> = RATIO_CASES
        .iter()
        .filter(|c| ratios.iter().any(|r| r.case == c.key))
        .collect();
    let centres: Vec<f64> = (0..cats.len()).map(|i| category_centre(i, 1.0)).collect();
    let mut chart = ChartBuilder::on(area)
        .caption("(c) CL/CJ, paired by repeat: mean ± 95 % CI", font(14.0))
        .margin(px(10))
        .margin_right(px(16))
        .x_label_area_size(px(58))
        .y_label_area_size(px(70))
        .build_cartesian_2d(
            Linear::new(0.0, cats.len().max(1) as f64, centres),
            Linear::new(lo, hi + 0.3 * step, ticks(lo, hi, step)),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .bold_line_style(stroke(GRID, 1.0))
        .axis_style(stroke(BLACK, 1.0))
        .set_all_tick_mark_size(px(4))
        .label_style(font(13.0))
        .axis_desc_style(font(14.0))
        .y_desc("peak-force ratio CL/CJ")
        .x_label_formatter(&|_| String::new())
        .y_label_formatter(&|y| format!("{y:.d$}"))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(DashedLineSeries::new(
            [(0.0, 1.0), (cats.len().max(1) as f64, 1.0)],
            px(6),
            px(4),
            stroke(GREY, 1.0),
        ))
        .map_err(err)?;
    chart
        .draw_series(std::iter::once(Text::new(
            "CL = CJ",
            (cats.len() as f64 - 0.03, 1.0 + 0.01 * (hi - lo)),
            text(12.0, GREY, HPos::Right, VPos::Bottom),
        )))
        .map_err(err)?;
    let mut hidden = false;
    for (i, cat) in cats.iter().enumerate() {
        if let Some(r) = ratios.iter().find(|r| r.case == cat.key) {
            hidden |= draw_ratio(&mut chart, r, category_centre(i, 1.0))?;
        }
    }
    if hidden {
        let plotting = chart.plotting_area().strip_coord_spec();
        let (_, h) = plotting.dim_in_pixel();
        boxed_text(
            &plotting,
            "whiskers shorter than the marker are not drawn",
            (px(8), h as i32 - px(6)),
            text(11.0, GREY, HPos::Left, VPos::Bottom),
        )?;
    }
    draw_category_labels(area, &chart, &cats, 1.0, 10)
}

/// Radius of the ratio markers [px].
const MARKER: i32 = 4;

/// One case's mean ratio (a point), its capped whisker and its value. Returns whether the
/// case has an interval too short to show beside the marker (then its whisker is not drawn).
fn draw_ratio(chart: &mut Chart, r: &RatioStats, x: f64) -> Result<bool, String> {
    let m = r.mean_cl_over_cj;
    let mut hidden = false;
    if let Some(ci) = r.ci95 {
        let (_, y0) = chart.backend_coord(&(x, m));
        let (_, y1) = chart.backend_coord(&(x, m + ci));
        hidden = (y0 - y1).abs() <= px(MARKER + 1);
        if !hidden {
            draw_whisker(chart, x, m, ci)?;
        }
    }
    chart
        .draw_series(std::iter::once(Circle::new(
            (x, m),
            px(MARKER),
            BLACK.filled(),
        )))
        .map_err(err)?;
    let top = m + r.ci95.unwrap_or(0.0);
    let lines = match r.ci95 {
        Some(_) => vec![(mean_pm_ci(m, r.ci95), BLACK)],
        None => vec![(mean_pm_ci(m, None), BLACK), ("1 pair, no CI".into(), GREY)],
    };
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let (px_x, px_y) = chart.backend_coord(&(x, top));
    for (k, (line, colour)) in lines.into_iter().rev().enumerate() {
        boxed_text(
            &area,
            &line,
            (px_x - origin.0, px_y - origin.1 - px(10 + 16 * k as i32)),
            text(12.0, colour, HPos::Center, VPos::Bottom),
        )?;
    }
    Ok(hidden)
}
