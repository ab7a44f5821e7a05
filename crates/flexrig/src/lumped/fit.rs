//! The least-squares Hertz fit f = k δ^n of compression data (paper §III-B) from a CSV file
//! (header `indentation_m,force_n`, one sample per line, m and N), with plausibility warnings
//! about the data (indentations that look like millimetres).

use std::path::Path;

use flexrig_contact::{CompressionPoint, HertzFit, fit_hertz, parse_compression_csv};

use crate::Error;

/// A plausibility warning (the scene's kind): the column it is about and what looks wrong.
pub use flexrig_rig::plausibility::Warning;

/// Largest indentation \[m\] a compression test of a padded contact plausibly reaches: beyond it
/// the column looks like millimetres (the paper's skins compress by a few millimetres under the
/// 71.5 mm dome).
pub const MILLIMETRE_LIKE_M: f64 = 0.05;

/// Reads and fits the compression data of `path` (errors name the file, or the CSV line).
pub fn fit_file(path: &Path) -> Result<HertzFit, Error> {
    Ok(fit_file_with_warnings(path)?.0)
}

/// [`fit_file`] and the plausibility warnings of its data ([`warnings`]).
pub fn fit_file_with_warnings(path: &Path) -> Result<(HertzFit, Vec<Warning>), Error> {
    let text = crate::shared::output::read_text(path)?;
    let points = parse_compression_csv(&text)?;
    Ok((fit_hertz(&points)?, warnings(&points)))
}

/// What is valid but looks like a mistake in compression data: indentations beyond
/// [`MILLIMETRE_LIKE_M`] look like millimetres written in the metre column.
pub fn warnings(points: &[CompressionPoint]) -> Vec<Warning> {
    let largest = points
        .iter()
        .map(|p| p.indentation_m)
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max);
    let mut out = Vec::new();
    if largest > MILLIMETRE_LIKE_M {
        out.push(Warning {
            field: "indentation_m".into(),
            message: format!(
                "the largest indentation is {} m, more than the {} m a compression test of a \
                 padded contact reaches: the column looks like millimetres; it is in metres \
                 (divide by 1000), and the fitted k depends on the unit",
                crate::shared::output::display_number(largest),
                MILLIMETRE_LIKE_M
            ),
        });
    }
    out
}
