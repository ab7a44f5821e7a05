//! Print size and file formats of the figures: [`FigureWidth`] (one column, two columns or any
//! width in inches), [`FigureFormat`] (SVG, PDF, PNG) and [`FigureOptions`], and
//! [`write_figure`], which writes one drawn figure in every asked format.
//!
//! Every figure is laid out in points (1/72 in) at the chosen width, its text at least
//! [`MIN_TEXT_PT`] there. The SVG states its size in inches. PNG (resvg/tiny-skia) and PDF
//! (svg2pdf) are rendered from the same SVG with the DejaVu Sans font embedded in the library
//! (`assets/fonts/DejaVuSans.ttf`, Bitstream Vera/DejaVu licence beside it), so they look the
//! same on every machine whatever fonts it has; the SVG names `sans-serif` and is shown with
//! the viewer's sans-serif font.

use std::path::{Path, PathBuf};
use std::sync::{Arc, OnceLock};

use resvg::usvg;
use serde::Serialize;

use crate::Error;
use crate::shared::output::write_atomic;

/// Smallest text of any figure at its printed width \[pt\] (journals ask for ≥ 8 pt).
pub const MIN_TEXT_PT: f64 = 8.0;

/// Width of one column of a two-column journal page \[in\].
pub const ONE_COLUMN_IN: f64 = 3.5;
/// Width of both columns of a two-column journal page \[in\].
pub const TWO_COLUMN_IN: f64 = 7.0;
/// Tallest figure \[in\]: what a journal page's column holds. A figure whose panels stack in
/// one column is flattened to fit ([`fitted_chart_height`]).
pub const MAX_HEIGHT_IN: f64 = 9.0;

/// The chart height \[pt\] of `rows` stacked panels whose charts would be `natural` points tall,
/// each with `extra` points beside its chart (its legend), under `header` points: `natural`, or
/// lower so that the figure stays within [`MAX_HEIGHT_IN`], but never below `min`.
pub fn fitted_chart_height(natural: u32, rows: usize, header: u32, extra: u32, min: u32) -> u32 {
    let room = (MAX_HEIGHT_IN * 72.0 - f64::from(header)) / rows.max(1) as f64 - f64::from(extra);
    natural.min((room.floor().max(f64::from(min))) as u32)
}

/// Narrowest and widest figure \[in\].
pub const WIDTH_RANGE_IN: (f64, f64) = (2.5, 20.0);
/// Lowest and highest PNG resolution \[dots per inch\].
pub const DPI_RANGE: (f64, f64) = (50.0, 1200.0);

/// The printed width of a figure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FigureWidth {
    /// One column, [`ONE_COLUMN_IN`] (3.5 in).
    OneColumn,
    /// Two columns, [`TWO_COLUMN_IN`] (7 in).
    TwoColumn,
    /// Any width \[in\], within [`WIDTH_RANGE_IN`].
    Inches(f64),
}

impl FigureWidth {
    /// The width \[in\].
    pub fn inches(self) -> f64 {
        match self {
            FigureWidth::OneColumn => ONE_COLUMN_IN,
            FigureWidth::TwoColumn => TWO_COLUMN_IN,
            FigureWidth::Inches(w) => w,
        }
    }

    /// The width \[pt\].
    pub fn points(self) -> f64 {
        self.inches() * 72.0
    }

    /// `1`/`one`/`column`, `2`/`two`/`page`, or inches as `5in` or `5` (the flag `--size`).
    pub fn parse(text: &str) -> Result<Self, Error> {
        let t = text.trim().to_ascii_lowercase();
        let width = match t.as_str() {
            "1" | "one" | "column" | "one-column" => FigureWidth::OneColumn,
            "2" | "two" | "page" | "two-column" => FigureWidth::TwoColumn,
            other => {
                let number = other.strip_suffix("in").unwrap_or(other).trim();
                FigureWidth::Inches(number.parse().map_err(|_| size_error(text))?)
            }
        };
        width.check()?;
        Ok(width)
    }

    /// Refuses a width outside [`WIDTH_RANGE_IN`] (naming `--size`).
    pub fn check(self) -> Result<(), Error> {
        let w = self.inches();
        if w.is_finite() && (WIDTH_RANGE_IN.0..=WIDTH_RANGE_IN.1).contains(&w) {
            Ok(())
        } else {
            Err(size_error(&w.to_string()))
        }
    }
}

fn size_error(value: &str) -> Error {
    Error::InvalidArgument {
        arg: "--size".into(),
        value: value.into(),
        allowed: format!(
            "one column (1, one: {ONE_COLUMN_IN} in), two columns (2, two: {TWO_COLUMN_IN} in) \
             or a width in inches from {} to {} (e.g. 5in)",
            WIDTH_RANGE_IN.0, WIDTH_RANGE_IN.1
        ),
    }
}

/// A figure file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FigureFormat {
    /// Scalable vector graphics (the drawing itself).
    Svg,
    /// PDF, vector, with the font embedded.
    Pdf,
    /// PNG at [`FigureOptions::dpi`].
    Png,
}

impl FigureFormat {
    /// The file extension.
    pub fn extension(self) -> &'static str {
        match self {
            FigureFormat::Svg => "svg",
            FigureFormat::Pdf => "pdf",
            FigureFormat::Png => "png",
        }
    }

    /// `svg`, `pdf` or `png` (the flag `--format`).
    pub fn parse(text: &str) -> Result<Self, Error> {
        match text.trim().to_ascii_lowercase().as_str() {
            "svg" => Ok(FigureFormat::Svg),
            "pdf" => Ok(FigureFormat::Pdf),
            "png" => Ok(FigureFormat::Png),
            _ => Err(Error::InvalidArgument {
                arg: "--format".into(),
                value: text.into(),
                allowed: "svg, pdf or png (comma-separated or repeated)".into(),
            }),
        }
    }
}

/// How figures are written: printed width, formats, PNG resolution.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FigureOptions {
    /// Printed width (`--size`).
    pub width: FigureWidth,
    /// Formats, each written beside the others with its extension (`--format`).
    pub formats: Vec<FigureFormat>,
    /// PNG resolution \[dots per inch\] (`--dpi`), within [`DPI_RANGE`].
    pub dpi: f64,
}

impl FigureOptions {
    /// Two columns (7 in), SVG only, PNG at 300 dpi if asked for.
    pub fn two_column_svg() -> Self {
        FigureOptions {
            width: FigureWidth::TwoColumn,
            formats: vec![FigureFormat::Svg],
            dpi: 300.0,
        }
    }

    /// Checks the width, the formats and the resolution; errors name the flag.
    pub fn validate(&self) -> Result<(), Error> {
        self.width.check()?;
        if self.formats.is_empty() {
            return Err(Error::InvalidArgument {
                arg: "--format".into(),
                value: String::new(),
                allowed: "at least one of svg, pdf, png".into(),
            });
        }
        if !(self.dpi.is_finite() && (DPI_RANGE.0..=DPI_RANGE.1).contains(&self.dpi)) {
            return Err(Error::InvalidArgument {
                arg: "--dpi".into(),
                value: self.dpi.to_string(),
                allowed: format!("must lie in [{}, {}]", DPI_RANGE.0, DPI_RANGE.1),
            });
        }
        Ok(())
    }

    /// The drawing width \[pt\].
    pub fn width_pt(&self) -> f64 {
        self.width.points()
    }
}

/// The font embedded in the library for PNG and PDF (DejaVu Sans).
const FONT: &[u8] = include_bytes!("../../../../assets/fonts/DejaVuSans.ttf");
/// Its family name.
const FONT_FAMILY: &str = "DejaVu Sans";

/// The font database of the renderers: only the embedded font, for every generic family.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        db.set_sans_serif_family(FONT_FAMILY);
        db.set_serif_family(FONT_FAMILY);
        db.set_monospace_family(FONT_FAMILY);
        Arc::new(db)
    })
    .clone()
}

/// `svg` parsed with the embedded font.
fn tree(svg: &str) -> Result<usvg::Tree, String> {
    let options = usvg::Options {
        font_family: FONT_FAMILY.into(),
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    usvg::Tree::from_str(svg, &options).map_err(|e| format!("the SVG does not parse: {e}"))
}

/// `svg` as a PNG at `dpi` (the SVG's size is in inches).
pub fn svg_to_png(svg: &str, dpi: f64) -> Result<Vec<u8>, String> {
    let tree = tree(svg)?;
    // usvg sizes the tree in CSS pixels, 96 per inch
    let zoom = (dpi / 96.0) as f32;
    let size = tree.size();
    let (w, h) = (
        (size.width() * zoom).ceil() as u32,
        (size.height() * zoom).ceil() as u32,
    );
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| format!("a {w}×{h} pixel image cannot be allocated"))?;
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(zoom, zoom),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().map_err(|e| e.to_string())
}

/// `svg` as a one-page PDF of the SVG's size, text as text with the font embedded.
pub fn svg_to_pdf(svg: &str) -> Result<Vec<u8>, String> {
    let tree = tree(svg)?;
    // usvg sizes the tree in CSS pixels (96 per inch): a page of that many pixels per inch
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions { dpi: 96.0 },
    )
    .map_err(|e| e.to_string())
}

/// Writes the figure `svg` as `dir/stem.EXT` for each of `options.formats`, atomically, and
/// returns the paths written.
pub fn write_figure(
    dir: &Path,
    stem: &str,
    svg: &str,
    options: &FigureOptions,
) -> Result<Vec<PathBuf>, Error> {
    let mut written = Vec::new();
    for format in &options.formats {
        let path = dir.join(format!("{stem}.{}", format.extension()));
        let plot_error = |message: String| Error::Plot {
            path: path.clone(),
            message,
        };
        let bytes = match format {
            FigureFormat::Svg => svg.as_bytes().to_vec(),
            FigureFormat::Pdf => svg_to_pdf(svg).map_err(plot_error)?,
            FigureFormat::Png => svg_to_png(svg, options.dpi).map_err(plot_error)?,
        };
        write_atomic(&path, &bytes)?;
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stack_is_flattened_to_nine_inches_and_no_further_than_its_floor() {
        // 4 panels of 175 pt under a 66 pt header: 766 pt; (648 − 66)/4 = 145.5 pt a panel
        assert_eq!(fitted_chart_height(175, 4, 66, 0, 120), 145);
        // two rows fit as they are; a legend beside each chart counts
        assert_eq!(fitted_chart_height(175, 2, 66, 0, 120), 175);
        assert_eq!(fitted_chart_height(175, 3, 40, 60, 120), 142);
        // never below the floor
        assert_eq!(fitted_chart_height(175, 8, 66, 0, 120), 120);
    }

    #[test]
    fn widths_parse_and_bad_ones_name_the_flag() {
        assert_eq!(FigureWidth::parse("1").unwrap().inches(), 3.5);
        assert_eq!(FigureWidth::parse("two").unwrap().points(), 504.0);
        assert_eq!(FigureWidth::parse("5in").unwrap().inches(), 5.0);
        assert_eq!(FigureWidth::parse("4.25").unwrap().inches(), 4.25);
        for bad in ["0", "-3", "NaN", "wide", "100in"] {
            let e = FigureWidth::parse(bad).unwrap_err().to_string();
            assert!(e.contains("--size"), "{bad}: {e}");
        }
        assert!(
            FigureFormat::parse("jpeg")
                .unwrap_err()
                .to_string()
                .contains("--format")
        );
        let mut o = FigureOptions::two_column_svg();
        o.dpi = 0.0;
        assert!(o.validate().unwrap_err().to_string().contains("--dpi"));
    }

    /// A 1 in × 0.5 in SVG at 200 dpi is a 200 × 100 PNG; its PDF page is 72 × 36 pt.
    #[test]
    fn png_and_pdf_have_the_printed_size() {
        let svg = "<svg width=\"1in\" height=\"0.5in\" viewBox=\"0 0 400 200\" \
                   xmlns=\"http://www.w3.org/2000/svg\"><rect x=\"0\" y=\"0\" width=\"200\" \
                   height=\"200\" fill=\"#000000\"/><text x=\"220\" y=\"120\" font-size=\"40\" \
                   font-family=\"sans-serif\">Ag</text></svg>";
        let png = svg_to_png(svg, 200.0).unwrap();
        // PNG header: width and height big-endian at bytes 16..24
        let w = u32::from_be_bytes(png[16..20].try_into().unwrap());
        let h = u32::from_be_bytes(png[20..24].try_into().unwrap());
        assert_eq!((w, h), (200, 100));
        let pdf = svg_to_pdf(svg).unwrap();
        let text = String::from_utf8_lossy(&pdf);
        assert!(text.starts_with("%PDF-"));
        assert!(text.contains("/MediaBox [0 0 72 36]"), "no 72×36 pt page");
        assert!(text.contains("DejaVu"), "the font is not embedded");
    }
}
