//! The least-squares Hertz fit f = k δ^n of compression data (paper §III-B) from a CSV file
//! (header `indentation_m,force_n`, one sample per line, m and N).

use std::path::Path;

use flexrig_contact::{HertzFit, fit_hertz, parse_compression_csv};

use crate::Error;

/// Reads and fits the compression data of `path` (errors name the file, or the CSV line).
pub fn fit_file(path: &Path) -> Result<HertzFit, Error> {
    let text = crate::output::read_text(path)?;
    Ok(fit_hertz(&parse_compression_csv(&text)?)?)
}
