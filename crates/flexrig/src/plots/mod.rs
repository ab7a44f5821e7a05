//! SVG figures (plotters), rendered to a string so the caller can write them atomically.
//!
//! Every figure is drawn at [`SCALE`]× its nominal size and the SVG root is then given the
//! nominal width and height (the viewBox keeps the drawn size). The SVG backend rounds every
//! coordinate to a whole pixel; drawn this way a pixel of the drawing is a quarter pixel of the
//! figure, and curves come out smooth.

mod curves;
mod eta;
mod fig6;
mod fig9;
mod heatmap;
mod prb;
mod work_precision;

pub use curves::{Curve, CurvePanel, log_x_curves_svg};
pub use eta::eta_svg;
pub use fig6::{Fig6Point, fig6_svg, fig6_with_points_svg};
pub use fig9::fig9_svg;
pub use heatmap::{ColorScale, HeatMap, heatmaps_svg};
pub use prb::prb_svg;
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

/// `v` nominal pixels in drawing pixels.
pub(crate) fn px(v: i32) -> i32 {
    v * SCALE
}

/// A `size`-pixel (nominal) sans-serif text style in `colour`, anchored at `(h, v)`.
pub(crate) fn text(size: f64, colour: RGBColor, h: HPos, v: VPos) -> TextStyle<'static> {
    ("sans-serif", size * f64::from(SCALE))
        .into_font()
        .color(&colour)
        .pos(Pos::new(h, v))
}

/// A `size`-pixel (nominal) sans-serif font for axis labels and captions.
pub(crate) fn font(size: f64) -> FontDesc<'static> {
    ("sans-serif", size * f64::from(SCALE)).into_font()
}

/// A solid line of `width` nominal pixels.
pub(crate) fn stroke(colour: RGBColor, width: f64) -> ShapeStyle {
    colour.stroke_width((width * f64::from(SCALE)).round() as u32)
}

/// Text `s` at pixel `at` of `area`, anchored as `style` says, on a white box so that no grid
/// line runs through it. The box is sized by an estimate of DejaVu Sans' mean glyph width.
pub(crate) fn boxed_text(
    area: &DrawingArea<SVGBackend, Shift>,
    s: &str,
    at: (i32, i32),
    style: TextStyle<'static>,
) -> Result<(), String> {
    // plotters writes font-size = size/1.24; a glyph is about 0.6 font-size wide on average.
    let font_px = style.font.get_size() / 1.24;
    let w = (0.6 * font_px * s.chars().count() as f64).round() as i32;
    let h = font_px.round() as i32;
    let x0 = match style.pos.h_pos {
        HPos::Left => at.0,
        HPos::Center => at.0 - w / 2,
        HPos::Right => at.0 - w,
    };
    let y0 = match style.pos.v_pos {
        VPos::Top => at.1,
        VPos::Center => at.1 - h / 2,
        VPos::Bottom => at.1 - h,
    };
    let pad = px(2);
    area.draw(&Rectangle::new(
        [(x0 - pad, y0 - pad), (x0 + w + pad, y0 + h + pad)],
        WHITE.filled(),
    ))
    .map_err(err)?;
    area.draw(&Text::new(s.to_string(), at, style)).map_err(err)
}

/// Any plotting error as text.
pub(crate) fn err(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// Renders `draw` on a white canvas of nominal size `(w, h)` and returns the SVG text.
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
    let nominal = format!("<svg width=\"{w}\" height=\"{h}\"");
    if !svg.starts_with(&drawn) {
        return Err("unexpected SVG header from the plotting backend".into());
    }
    Ok(subscripts(&svg.replacen(&drawn, &nominal, 1)))
}

/// Symbols written `m_h` in the figures' text and set with a real subscript in the SVG.
const SUBSCRIPTED: [(&str, &str); 8] = [
    ("m_h", "h"),
    ("m_e", "e"),
    ("m_r", "r"),
    ("k_δ", "δ"),
    ("k_c", "c"),
    ("v_0", "0"),
    ("f_max", "max"),
    ("η_FE", "FE"),
];

/// `svg` with the [`SUBSCRIPTED`] symbols' subscripts as lowered, smaller `tspan`s.
fn subscripts(svg: &str) -> String {
    let mut out = svg.to_string();
    for (symbol, sub) in SUBSCRIPTED {
        let base = &symbol[..symbol.len() - sub.len() - 1];
        let set = format!("{base}<tspan baseline-shift=\"sub\" font-size=\"75%\">{sub}</tspan>");
        out = out.replace(symbol, &set);
    }
    out
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

/// `10` with the exponent of `v` (a power of ten) in superscript digits, e.g. `10⁻⁵`.
pub(crate) fn decade_label(v: f64) -> String {
    let exponent = v.log10().round() as i64;
    let digits: String = exponent
        .to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect();
    format!("10{digits}")
}

/// `v` as `10ᵏ` or `m·10ᵏ` (mantissa to 6 significant digits).
pub(crate) fn sci_label(v: f64) -> String {
    let decade = 10f64.powf(v.log10().floor());
    let mantissa = v / decade;
    if (mantissa - 1.0).abs() < 1e-9 {
        decade_label(decade)
    } else {
        format!(
            "{}·{}",
            (mantissa * 1e5).round() / 1e5,
            decade_label(decade)
        )
    }
}

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
    fn nice_steps_and_ticks() {
        assert_eq!(nice_step(300.0, 6), 50.0);
        assert_eq!(nice_step(0.4, 5), 0.1);
        assert_eq!(nice_step(0.09, 6), 0.02);
        assert_eq!(ticks(0.0, 300.0, 50.0).len(), 7);
    }

    #[test]
    fn the_svg_is_scaled_to_its_nominal_size() {
        let svg = render((100, 50), |_| Ok(())).unwrap();
        assert!(svg.starts_with("<svg width=\"100\" height=\"50\" viewBox=\"0 0 400 200\""));
    }
}
