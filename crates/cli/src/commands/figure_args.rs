//! The figure flags every command that draws figures shares: printed width, formats, PNG
//! resolution, into [`flexrig::plots::FigureOptions`].

use clap::Args;
use flexrig::Error;
use flexrig::plots::FigureOptions;

/// `--size`, `--format`, `--dpi`.
#[derive(Debug, Clone, Args)]
pub struct FigureArgs {
    /// Printed width of the figures: `1` (one column, 3.5 in), `2` (two columns, 7 in) or a
    /// width in inches such as `5in`; text is at least 8 pt at this width.
    #[arg(long, value_name = "WIDTH", default_value = "2")]
    pub size: String,
    /// Figure formats, comma-separated or repeated: svg, pdf, png (PDF and PNG with the font
    /// embedded).
    #[arg(
        long,
        value_name = "FORMATS",
        value_delimiter = ',',
        default_value = "svg"
    )]
    pub format: Vec<String>,
    /// Resolution of PNG figures (dots per inch).
    #[arg(long, value_name = "DPI", default_value_t = 300.0)]
    pub dpi: f64,
}

impl FigureArgs {
    /// The library's figure options ([`flexrig::fronts::figure_options`]); errors name the flag.
    pub fn options(&self) -> Result<FigureOptions, Error> {
        flexrig::fronts::figure_options(&self.size, &self.format, self.dpi)
    }
}
