//! The paper's Fig. 9: peak force of CJ and CL, (a) on the test bed (412 g payload) against the
//! aluminium and the iron operator, (b) with the light load, both on one force scale, mean ± 95 %
//! CI with capped whiskers; and (c) the CL/CJ ratio paired by repeat with its 95 % CI.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::series::DashedLineSeries;
use plotters::style::text_anchor::{HPos, VPos};

use super::{GroupStats, RatioStats, RunInputs};
use crate::plots::{
    GREY, GRID, LABEL_PT, Linear, PALETTE, TICK_PT, TITLE_PT, err, font, nice_step, px, render,
    stroke, text, text_width_pt, ticks, wrap,
};

/// Colour of the compliant-joint bars.
const CJ: RGBColor = PALETTE[1];
/// Colour of the compliant-link bars.
const CL: RGBColor = PALETTE[0];
/// Height of a panel row \[pt\].
const ROW: u32 = 200;
/// Height of a line of the note under the panels \[pt\].
const NOTE: u32 = 11;
/// Figures narrower than this stack the ratio panel under the bars \[pt\].
const STACK_BELOW: f64 = 420.0;
/// Half-width of a whisker cap \[pt\].
const CAP: i32 = 3;

/// A category on the x axis: its two label lines and the scene-name suffix (`aluminium`, ...),
/// the labels written from the values that ran.
struct Category {
    name: String,
    detail: String,
    /// The detail with masses of 1 kg and more in kilograms, for categories too narrow for it.
    compact: String,
    key: &'static str,
}

/// How the experiment's release angles were drawn (for the note on the intervals).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jitter {
    /// Standard deviation of the release-angle jitter \[deg\].
    pub sd_deg: f64,
    /// Seed of its RNG.
    pub seed: u64,
}

/// The group of `scene`.
fn group<'a>(groups: &'a [GroupStats], scene: &str) -> Option<&'a GroupStats> {
    groups.iter().find(|g| g.scene == scene)
}

/// A mass as [`grams`] below 1 kg and in kilograms from 1 kg (`1 kg`, `4.008 kg`, to the gram):
/// the shorter form for narrow labels.
fn compact_mass(kg: f64) -> String {
    if kg >= 1.0 {
        format!("{} kg", (kg * 1e3).round() / 1e3)
    } else {
        crate::plots::grams(kg)
    }
}

/// A block material as the labels say it: `skinned_aluminium` as `aluminium` (all the bundled
/// blocks are skinned), any other name with spaces for underscores.
fn material(name: &str) -> String {
    name.trim_start_matches("skinned_").replace('_', " ")
}

/// The operator of `case` as it ran (its material and mass), from the CJ run or else the CL run.
fn operator_of<'a>(groups: &'a [GroupStats], case: &str) -> Option<&'a RunInputs> {
    group(groups, &format!("cj_{case}"))
        .or_else(|| group(groups, &format!("cl_{case}")))
        .map(|g| &g.inputs)
}

/// The payloads m_e that ran in `cases`, as a label (`m_e = 412 g` or a list when they differ),
/// each mass written by `mass`.
fn payload_label(groups: &[GroupStats], cases: &[&str], mass: fn(f64) -> String) -> String {
    let mut values: Vec<String> = Vec::new();
    for case in cases {
        for design in ["cj", "cl"] {
            if let Some(g) = group(groups, &format!("{design}_{case}")) {
                let v = mass(g.inputs.payload_kg);
                if !values.contains(&v) {
                    values.push(v);
                }
            }
        }
    }
    format!("m_e = {}", values.join(" / "))
}

/// Category labels of the operator of `case` as it ran.
fn operator_category(groups: &[GroupStats], case: &'static str) -> Option<Category> {
    let op = operator_of(groups, case)?;
    Some(Category {
        name: material(&op.block_material),
        detail: format!("m_h = {}", crate::plots::grams(op.block_mass_kg)),
        compact: format!("m_h = {}", compact_mass(op.block_mass_kg)),
        key: case,
    })
}

/// The two designs of a case as run, e.g. `("CJ", "CL")` (upper-case keys).
fn designs(groups: &[GroupStats], case: &str) -> (String, String) {
    let d = |slot: &str| {
        group(groups, &format!("{slot}_{case}"))
            .map_or(slot.to_uppercase(), |g| g.inputs.design.to_uppercase())
    };
    (d("cj"), d("cl"))
}

/// The paper's Fig. 9 from the experiment's per-scene statistics and paired ratios, at the
/// printed width `width_pt` \[pt\]: every label from the values that ran (designs, operator
/// materials and masses, payloads), the intervals noted as coming from the release-angle jitter.
pub fn fig9_svg(
    groups: &[GroupStats],
    ratios: &[RatioStats],
    jitter: Jitter,
    width_pt: f64,
) -> Result<String, String> {
    let top = groups
        .iter()
        .map(|g| g.mean_peak_force_n + g.ci95_n.unwrap_or(0.0))
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
        .max(1.0);
    let step = nice_step(top, 5);
    let y_top = (top * 1.05 / step).ceil() * step;
    let stacked = width_pt < STACK_BELOW;
    let w = width_pt.round() as u32;
    let rows = if stacked { 2 } else { 1 };
    let note = wrap(&note_text(groups, jitter), width_pt - 8.0, TICK_PT);
    let note_h = NOTE * note.len() as u32;
    render((w, ROW * rows + note_h), |root| {
        let (panels, note_area) = root.split_vertically(px((ROW * rows) as i32));
        let (bars, ratio_area) = if stacked {
            panels.split_vertically(px(ROW as i32))
        } else {
            panels.split_horizontally(px((0.56 * width_pt) as i32))
        };
        let bars_w = if stacked { width_pt } else { 0.56 * width_pt };
        let (bed, light) = bars.split_horizontally(px((0.64 * bars_w) as i32));
        let test_bed: Vec<Category> = ["aluminium", "iron"]
            .into_iter()
            .filter_map(|c| operator_category(groups, c))
            .collect();
        let light_load: Vec<Category> = operator_category(groups, "light_load")
            .into_iter()
            .collect();
        let bed_title = format!(
            "(a) {}",
            payload_label(groups, &["aluminium", "iron"], crate::plots::grams)
        );
        let light_title = format!(
            "(b) {}",
            payload_label(groups, &["light_load"], crate::plots::grams)
        );
        let axis = ForceAxis { top: y_top, step };
        draw_bars(&bed, &bed_title, &test_bed, groups, axis, true)?;
        draw_bars(&light, &light_title, &light_load, groups, axis, false)?;
        draw_ratios(&ratio_area, groups, ratios)?;
        for (i, line) in note.iter().enumerate() {
            note_area
                .draw(&Text::new(
                    line.clone(),
                    (px(4), px((NOTE * i as u32 + NOTE / 2) as i32)),
                    text(TICK_PT, GREY, HPos::Left, VPos::Center),
                ))
                .map_err(err)?;
        }
        Ok(())
    })
}

/// The note under the panels: how many runs each panel's bars are, and where the intervals come
/// from (panel (a) holds the aluminium and iron cases, panel (b) the light-load case).
fn note_text(groups: &[GroupStats], jitter: Jitter) -> String {
    let runs = |cases: &[&str]| {
        groups
            .iter()
            .filter(|g| cases.iter().any(|c| g.scene.ends_with(&format!("_{c}"))))
            .map(|g| g.n)
            .max()
    };
    let words = |n: usize| {
        if n > 1 {
            format!("mean of {n} runs ± 95 % CI")
        } else {
            "one run, no confidence interval".to_string()
        }
    };
    let (a, b) = (runs(&["aluminium", "iron"]), runs(&["light_load"]));
    let scatter = format!(
        "The CI reflects only the simulated release-angle scatter (σ = {}°, seed {}).",
        jitter.sd_deg, jitter.seed
    );
    let any_ci = a.into_iter().chain(b).any(|n| n > 1);
    let bars = match (a, b) {
        (Some(a), Some(b)) if a == b => format!("Bars: {}.", words(a)),
        (Some(a), Some(b)) => format!("Bars: (a) {}; (b) {}.", words(a), words(b)),
        (Some(n), None) | (None, Some(n)) => format!("Bars: {}.", words(n)),
        (None, None) => return String::new(),
    };
    if any_ci {
        format!("{bars} {scatter}")
    } else {
        bars
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
        .caption(title, font(TITLE_PT))
        .margin(px(4))
        .x_label_area_size(px(38))
        .y_label_area_size(px(if y_desc { 34 } else { 22 }))
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
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .y_desc(if y_desc { "peak impact force [N]" } else { "" })
        .x_label_formatter(&|x| {
            let i = (x / width).floor().max(0.0) as usize;
            let (cj, cl) = cats
                .get(i)
                .map_or(("CJ".into(), "CL".into()), |c| designs(groups, c.key));
            if x.rem_euclid(width) < 0.5 * width {
                cj
            } else {
                cl
            }
        })
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()
        .map_err(err)?;
    for (i, cat) in cats.iter().enumerate() {
        let c = category_centre(i, width);
        for (slot, x) in [("cj", c - 0.5), ("cl", c + 0.5)] {
            if let Some(g) = group(groups, &format!("{slot}_{}", cat.key)) {
                let colour = if g.inputs.design == "cl" { CL } else { CJ };
                draw_bar(&mut chart, g, colour, x, axis.top)?;
            }
        }
    }
    let cats: Vec<&Category> = cats.iter().collect();
    draw_category_labels(area, &chart, &cats, width, 13)
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
        (low - 0.03 * y_top, VPos::Top, WHITE)
    } else {
        (
            m + g.ci95_n.unwrap_or(0.0) + 0.015 * y_top,
            VPos::Bottom,
            BLACK,
        )
    };
    chart
        .draw_series(std::iter::once(Text::new(
            format!("{m:.0}"),
            (x, y),
            text(TICK_PT, c, HPos::Center, v),
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

/// Each category's two label lines, centred under it, the first `below` pixels under the axis;
/// the details in their compact form when one of them is wider than a category and its compact
/// form is narrower.
fn draw_category_labels(
    area: &DrawingArea<SVGBackend, Shift>,
    chart: &Chart,
    cats: &[&Category],
    width: f64,
    below: i32,
) -> Result<(), String> {
    let origin = area.get_base_pixel();
    let (_, axis) = chart.backend_coord(&(0.0, chart.y_range().start));
    let (x0, _) = chart.backend_coord(&(category_centre(0, width), 0.0));
    let (x1, _) = chart.backend_coord(&(category_centre(1, width), 0.0));
    // the room of a category, less 4 points between neighbours' labels [pt]
    let room = f64::from((x1 - x0).abs()) / f64::from(px(1)) - 4.0;
    let width_of = |s: &str| text_width_pt(s, TICK_PT);
    let compact = cats.len() > 1
        && cats
            .iter()
            .any(|c| width_of(&c.detail) > room && width_of(&c.compact) < width_of(&c.detail));
    for (i, cat) in cats.iter().enumerate() {
        let (x, _) = chart.backend_coord(&(category_centre(i, width), 0.0));
        let (x, y) = (x - origin.0, axis - origin.1 + px(below));
        area.draw(&Text::new(
            cat.name.clone(),
            (x, y),
            text(TICK_PT, BLACK, HPos::Center, VPos::Top),
        ))
        .map_err(err)?;
        area.draw(&Text::new(
            if compact { &cat.compact } else { &cat.detail }.clone(),
            (x, y + px(10)),
            text(TICK_PT, GREY, HPos::Center, VPos::Top),
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

/// The ratio panel's category of `case`: its operator and payload as run.
fn ratio_category(groups: &[GroupStats], case: &'static str) -> Option<Category> {
    let op = operator_of(groups, case)?;
    Some(Category {
        name: material(&op.block_material),
        detail: payload_label(groups, &[case], crate::plots::grams),
        compact: payload_label(groups, &[case], compact_mass),
        key: case,
    })
}

fn draw_ratios(
    area: &DrawingArea<SVGBackend, Shift>,
    groups: &[GroupStats],
    ratios: &[RatioStats],
) -> Result<(), String> {
    let (lo, hi, step) = ratio_axis(ratios);
    let d = decimals(step);
    let owned: Vec<Category> = ["aluminium", "iron", "light_load"]
        .into_iter()
        .filter(|c| ratios.iter().any(|r| r.case == *c))
        .filter_map(|c| ratio_category(groups, c))
        .collect();
    let cats: Vec<&Category> = owned.iter().collect();
    // the designs that ran in the two slots (CL over CJ unless --set changed them)
    let (mut num, mut den) = ("CL".to_string(), "CJ".to_string());
    if let Some(c) = cats.first() {
        let (cj, cl) = designs(groups, c.key);
        (num, den) = (cl, cj);
    }
    let ratio_name = format!("{num}/{den}");
    let centres: Vec<f64> = (0..cats.len()).map(|i| category_centre(i, 1.0)).collect();
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("(c) {ratio_name}, paired by repeat"),
            font(TITLE_PT),
        )
        .margin(px(4))
        .margin_right(px(8))
        .x_label_area_size(px(36))
        .y_label_area_size(px(44))
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
        .set_all_tick_mark_size(px(2))
        .label_style(font(TICK_PT))
        .axis_desc_style(font(LABEL_PT))
        .y_desc(format!("peak-force ratio {ratio_name}"))
        .x_label_formatter(&|_| String::new())
        .y_label_formatter(&|y| format!("{y:.d$}"))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(DashedLineSeries::new(
            [(0.0, 1.0), (cats.len().max(1) as f64, 1.0)],
            px(3),
            px(2),
            stroke(GREY, 0.75),
        ))
        .map_err(err)?;
    chart
        .draw_series(std::iter::once(Text::new(
            format!("{num} = {den}"),
            (cats.len() as f64 - 0.03, 1.0 + 0.01 * (hi - lo)),
            text(TICK_PT, GREY, HPos::Right, VPos::Bottom),
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
        plotting
            .draw(&Text::new(
                "CI shorter than the marker",
                (px(4), h as i32 - px(3)),
                text(TICK_PT, GREY, HPos::Left, VPos::Bottom),
            ))
            .map_err(err)?;
    }
    draw_category_labels(area, &chart, &cats, 1.0, 10)
}

/// Radius of the ratio markers [px].
const MARKER: i32 = 2;

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
    let ci = r.ci95.unwrap_or(0.0);
    let lines = [
        (format!("{m:.3}"), BLACK),
        (ci_label(r.ci95, r.pairs), GREY),
    ];
    let area = chart.plotting_area().strip_coord_spec();
    let origin = area.get_base_pixel();
    let (_, plot_h) = area.dim_in_pixel();
    // below the point in the upper half of the panel, above it in the lower half
    let (_, py) = chart.backend_coord(&(x, m));
    let below = py - origin.1 < plot_h as i32 / 2;
    let (px_x, edge) = if below {
        chart.backend_coord(&(x, m - ci))
    } else {
        chart.backend_coord(&(x, m + ci))
    };
    for (k, (line, colour)) in lines.into_iter().enumerate() {
        let (y, v) = if below {
            (edge - origin.1 + px(4 + 10 * k as i32), VPos::Top)
        } else {
            (edge - origin.1 - px(4 + 10 * (1 - k as i32)), VPos::Bottom)
        };
        area.draw(&Text::new(
            line,
            (px_x - origin.0, y),
            text(TICK_PT, colour, HPos::Center, v),
        ))
        .map_err(err)?;
    }
    Ok(hidden)
}

/// The second line under a ratio: its CI half-width, or why there is none.
fn ci_label(ci: Option<f64>, pairs: usize) -> String {
    match ci.filter(|c| c.is_finite() && *c > 0.0) {
        None => format!("{pairs} pair, no CI"),
        Some(c) if c < 0.0005 => "CI < 0.001".into(),
        Some(c) => {
            let digits = (-c.log10().floor()).max(0.0) as usize;
            format!("± {c:.digits$}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ratios_are_written_to_a_sensible_precision() {
        assert_eq!(ci_label(Some(3.3e-7), 5), "CI < 0.001");
        assert_eq!(ci_label(Some(0.0123), 5), "± 0.01");
        assert_eq!(ci_label(Some(0.0041), 5), "± 0.004");
        assert_eq!(ci_label(None, 1), "1 pair, no CI");
        assert_eq!(crate::plots::grams(0.412), "412 g");
        assert_eq!(crate::plots::grams(1.0), "1000 g");
        assert_eq!(crate::plots::grams(0.0051), "5.1 g");
    }
}
