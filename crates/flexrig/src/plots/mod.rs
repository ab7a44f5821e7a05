//! Figures (plotters), rendered to an SVG string so the caller can write them atomically, and
//! from it to PDF and PNG ([`page`]).
//!
//! Every figure is laid out in points (1/72 in) at its printed width ([`FigureWidth`]), with
//! text of at least [`MIN_TEXT_PT`]; the helpers [`text`] and [`font`] take sizes in points.
//! It is drawn at [`SCALE`] drawing units per point and the SVG root states the printed width
//! and height in inches (the viewBox keeps the drawn size). The SVG backend rounds every
//! coordinate to a whole unit; drawn this way a unit is a quarter point, and curves come out
//! smooth.

mod curves;
mod eta;
mod fig6;
mod heatmap;
pub mod inspect;
pub mod page;
mod prb;
mod rotor;
mod work_precision;

pub use curves::{Curve, CurveAxes, CurvePanel, curves_svg, log_x_curves_svg};
pub use eta::eta_svg;
pub use fig6::{Fig6Point, fig6_svg, fig6_with_points_svg};
pub use heatmap::{AxisNames, ColorScale, HeatMap, heatmaps_svg, heatmaps_svg_named};
pub use page::{
    FigureFormat, FigureOptions, FigureWidth, MIN_TEXT_PT, svg_to_pdf, svg_to_png, write_figure,
};
pub use prb::prb_svg;
pub use rotor::eta_rotor_svg;
pub use work_precision::{Panel, Series, work_precision_svg};

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint, Ranged};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Drawing scale (see the module documentation).
pub(crate) const SCALE: i32 = 4;

/// Colour-blind-safe palette (Okabe & Ito): blue, vermillion, bluish green, reddish purple,
/// orange, sky blue, black.
pub(crate) const PALETTE: [RGBColor; 7] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
];

/// Light grey of the grid lines.
pub(crate) const GRID: RGBColor = RGBColor(225, 225, 225);
/// Mid grey of reference lines and notes.
pub(crate) const GREY: RGBColor = RGBColor(110, 110, 110);

/// `v` points in drawing units.
pub(crate) fn px(v: i32) -> i32 {
    v * SCALE
}

/// plotters writes a font's `font-size` as its size / 1.24; sizes are given to it times this.
const PLOTTERS_FONT: f64 = 1.24;

/// Text sizes \[pt\]: tick labels and notes, axis labels, panel titles.
pub(crate) const TICK_PT: f64 = 8.0;
/// Axis labels and legends \[pt\].
pub(crate) const LABEL_PT: f64 = 8.5;
/// Panel titles \[pt\].
pub(crate) const TITLE_PT: f64 = 9.0;

/// A `size`-point sans-serif text style in `colour`, anchored at `(h, v)`.
pub(crate) fn text(size: f64, colour: RGBColor, h: HPos, v: VPos) -> TextStyle<'static> {
    font(size).color(&colour).pos(Pos::new(h, v))
}

/// A `size`-point sans-serif font for axis labels and captions.
pub(crate) fn font(size: f64) -> FontDesc<'static> {
    ("sans-serif", size * PLOTTERS_FONT * f64::from(SCALE)).into_font()
}

/// The mean advance of a DejaVu Sans glyph over the font size (for boxes and layout).
pub(crate) const GLYPH: f64 = 0.6;

/// The width of `s` in `size`-point text \[pt\] (estimated from [`GLYPH`]).
pub(crate) fn text_width_pt(s: &str, size: f64) -> f64 {
    GLYPH * size * s.chars().count() as f64
}

/// A solid line of `width` nominal pixels.
pub(crate) fn stroke(colour: RGBColor, width: f64) -> ShapeStyle {
    colour.stroke_width((width * f64::from(SCALE)).round() as u32)
}

/// Units a number keeps on its line (`0.1 kg`, `10⁸ N/m`), after a trailing `,;:).` is cut.
const UNITS: [&str; 22] = [
    "kg", "g", "m", "mm", "cm", "s", "ms", "N", "N/m", "N/mⁿ", "m/s", "rad/s", "rad", "Hz", "%",
    "°", "J", "Pa", "N·m", "N·m/rad", "kg·m²", "in",
];

/// True when `word` starts a number (`0.1`, `10⁸`, `2·10²`, `-4`).
fn is_number(word: &str) -> bool {
    word.trim_start_matches(['-', '−', '(', '+'])
        .starts_with(|c: char| c.is_ascii_digit())
}

/// The words of `s` grouped so that no line breaks inside a quantity: around an `=` (`m_e =
/// 0.1 kg`, one group with its unit) nor between a number and its unit.
fn unbreakable_groups(s: &str) -> Vec<String> {
    let mut groups: Vec<String> = Vec::new();
    let mut last = "";
    for word in s.split(' ') {
        let unit = UNITS.contains(&word.trim_end_matches([',', ';', ':', ')', '.']));
        let glued = !groups.is_empty() && (word == "=" || last == "=" || (unit && is_number(last)));
        match groups.last_mut() {
            Some(group) if glued => {
                group.push(' ');
                group.push_str(word);
            }
            _ => groups.push(word.to_string()),
        }
        last = word;
    }
    groups
}

/// `s` broken at spaces into lines of at most `width_pt` in `size`-point text, never inside a
/// quantity (`m_e = 0.1 kg` stays on one line; [`unbreakable_groups`]); a group longer than the
/// width stands alone on its line.
pub(crate) fn wrap(s: &str, width_pt: f64, size: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in unbreakable_groups(s) {
        let candidate = if current.is_empty() {
            word.to_string()
        } else {
            format!("{current} {word}")
        };
        if text_width_pt(&candidate, size) > width_pt && !current.is_empty() {
            lines.push(std::mem::take(&mut current));
            current = word.to_string();
        } else {
            current = candidate;
        }
    }
    if !current.is_empty() || lines.is_empty() {
        lines.push(current);
    }
    lines
}

/// Any plotting error as text.
pub(crate) fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// Renders `draw` on a white canvas of `(w, h)` points and returns the SVG text, its size in
/// inches.
pub(crate) fn render(
    (w, h): (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend, Shift>) -> Result<(), String>,
) -> Result<String, String> {
    let scale = SCALE as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w * scale, h * scale)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw(&root)?;
        root.present().map_err(err)?;
    }
    let drawn = format!("<svg width=\"{}\" height=\"{}\"", w * scale, h * scale);
    let nominal = format!(
        "<svg width=\"{}in\" height=\"{}in\"",
        f64::from(w) / 72.0,
        f64::from(h) / 72.0
    );
    if !svg.starts_with(&drawn) {
        return Err("unexpected SVG header from the plotting backend".into());
    }
    Ok(subscripts(&svg.replacen(&drawn, &nominal, 1)))
}

/// Symbols written `m_h` in the figures' text and set with a real subscript in the SVG.
const SUBSCRIPTED: [(&str, &str); 23] = [
    ("k_θr", "θr"),
    ("K_p", "p"),
    ("ω_s", "s"),
    ("T_s", "s"),
    ("J_R", "R"),
    ("f_placed", "placed"),
    ("Θ_max", "max"),
    ("γ_eff", "eff"),
    // before m_e, which it contains
    ("m_eff", "eff"),
    ("m_R", "R"),
    ("v_max", "max"),
    ("F_max", "max"),
    ("p_max", "max"),
    ("f_CL", "CL"),
    ("f_CJ", "CJ"),
    ("m_h", "h"),
    ("m_e", "e"),
    ("m_r", "r"),
    ("k_δ", "δ"),
    ("k_c", "c"),
    ("v_0", "0"),
    ("f_max", "max"),
    ("η_FE", "FE"),
];

/// True when `text` holds a symbol the figures set with a subscript ([`SUBSCRIPTED`]): its line
/// needs room below the baseline for the lowered subscript.
pub(crate) fn has_subscript(text: &str) -> bool {
    SUBSCRIPTED.iter().any(|(symbol, _)| text.contains(symbol))
}

/// `svg` with the [`SUBSCRIPTED`] symbols' subscripts as lowered `tspan`s, smaller than their
/// text but never below [`MIN_TEXT_PT`].
fn subscripts(svg: &str) -> String {
    let min = MIN_TEXT_PT * f64::from(SCALE);
    let mut out = String::with_capacity(svg.len() + 1024);
    let mut rest = svg;
    while let Some(start) = rest.find("<text") {
        let Some(end) = rest[start..].find("</text>").map(|e| start + e) else {
            break;
        };
        out.push_str(&rest[..start]);
        let element = &rest[start..end];
        let size = attribute(element, "font-size").unwrap_or(min);
        let sub_size = (0.8 * size).max(min);
        let mut element = element.to_string();
        for (symbol, sub) in SUBSCRIPTED {
            if element.contains(symbol) {
                let base = &symbol[..symbol.len() - sub.len() - 1];
                let set = format!(
                    "{base}<tspan baseline-shift=\"sub\" font-size=\"{sub_size:.2}\">{sub}</tspan>"
                );
                element = element.replace(symbol, &set);
            }
        }
        out.push_str(&element);
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

/// The number in `name="…"` of an SVG element's text.
pub(crate) fn attribute(element: &str, name: &str) -> Option<f64> {
    let key = format!(" {name}=\"");
    let start = element.find(&key)? + key.len();
    let end = start + element[start..].find('"')?;
    element[start..end].parse().ok()
}

/// A linear axis from `lo` to `hi` with ticks (and grid lines) exactly at `ticks`.
#[derive(Debug, Clone)]
pub(crate) struct Linear {
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
}

impl Linear {
    /// The axis `lo..hi` with `ticks`.
    pub(crate) fn new(lo: f64, hi: f64, ticks: Vec<f64>) -> Self {
        Self { lo, hi, ticks }
    }
}

impl Ranged for Linear {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = (value - self.lo) / (self.hi - self.lo);
        limit.0 + (t * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            Vec::new()
        } else {
            self.ticks.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

pub use flexrig_contact::validate::{decade_label, sci_label};

/// A "nice" tick step (1, 2, 2.5 or 5 × 10ᵏ) giving at most `max_ticks` intervals over `span`.
pub(crate) fn nice_step(span: f64, max_ticks: usize) -> f64 {
    let raw = span / max_ticks.max(1) as f64;
    let decade = 10f64.powf(raw.log10().floor());
    [1.0, 2.0, 2.5, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|step| *step >= raw)
        .unwrap_or(10.0 * decade)
}

/// Ticks `start, start + step, …` up to `end` (inclusive, to rounding).
pub(crate) fn ticks(start: f64, end: f64, step: f64) -> Vec<f64> {
    let count = ((end - start) / step + 1e-9).floor().max(0.0) as usize;
    (0..=count).map(|i| start + step * i as f64).collect()
}

/// A mass of `0.412` kg as `412 g`, `4.008` kg as `4008 g` (to the gram; to 0.1 g below 10 g).
pub fn grams(kg: f64) -> String {
    let g = kg * 1e3;
    if g >= 10.0 {
        format!("{} g", g.round())
    } else {
        format!("{:.1} g", g)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decade_labels_use_superscripts() {
        assert_eq!(decade_label(1e-5), "10⁻⁵");
        assert_eq!(decade_label(1e12), "10¹²");
        assert_eq!(decade_label(1.0), "10⁰");
        assert_eq!(sci_label(2e2), "2·10²");
        assert_eq!(sci_label(1e8), "10⁸");
        assert_eq!(sci_label(5e-6), "5·10⁻⁶");
    }

    #[test]
    fn text_wraps_at_spaces_within_the_width() {
        // 8 pt: a glyph is 4.8 pt wide, so 50 pt hold 10 glyphs
        let lines = wrap("aaaa bbbb cccc dddddddddddd e", 50.0, 8.0);
        assert_eq!(lines, ["aaaa bbbb", "cccc", "dddddddddddd", "e"]);
        assert_eq!(wrap("", 50.0, 8.0), [""]);
    }

    #[test]
    fn a_quantity_is_never_broken_across_lines() {
        // the role-switch legend at one column: "m_e =" ended one line and "0.1 kg" began the next
        let label = "Fig. 6: m_h = 1000 kg, k_δ = 10⁸ N/m, m_e = 0.1 kg, n = 1";
        for width in [60.0, 120.0, 200.0, 240.0] {
            let lines = wrap(label, width, 8.0);
            assert_eq!(lines.join(" "), label);
            for quantity in ["m_h = 1000 kg,", "k_δ = 10⁸ N/m,", "m_e = 0.1 kg,", "n = 1"] {
                assert!(
                    lines.iter().any(|l| l.contains(quantity)),
                    "{quantity} broken at {width} pt: {lines:?}"
                );
            }
        }
        // a number keeps its unit; words break as before
        assert_eq!(
            wrap("a peak of 250 N here", 60.0, 8.0),
            ["a peak of", "250 N here"]
        );
    }

    #[test]
    fn nice_steps_and_ticks() {
        assert_eq!(nice_step(300.0, 6), 50.0);
        assert_eq!(nice_step(0.4, 5), 0.1);
        assert_eq!(nice_step(0.09, 6), 0.02);
        assert_eq!(ticks(0.0, 300.0, 50.0).len(), 7);
    }

    #[test]
    fn the_svg_is_scaled_to_its_nominal_size() {
        let svg = render((100, 50), |_| Ok(())).unwrap();
        assert!(
            svg.starts_with("<svg width=\"1.3888888888888888in\" height=\"0.6944444444444444in\" viewBox=\"0 0 400 200\""),
            "{svg}"
        );
    }
}
