//! `flexrig spin-up`: the spin-up beam benchmark (Kane, Ryan & Banerjee 1987), see
//! [`flexrig::driven::spin_up`]; a summary or JSON.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::driven::spin_up::{SpinUpOptions, run_with_figures as run_spin_up};
use flexrig::{CancelToken, Error};

use crate::print::{line, print_json};

/// The flags' defaults: the library's literature case.
const D: SpinUpOptions = SpinUpOptions::LITERATURE;

/// Arguments of `flexrig spin-up` (defaults: the literature case).
#[derive(Debug, Args)]
pub struct SpinUpArgs {
    /// Directory for spin_up.csv, spin_up.json and the figure spin_up.svg (or .pdf, .png; created
    /// if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// Beam length L [m].
    #[arg(long, value_name = "M", default_value_t = D.length)]
    pub length: f64,
    /// Cross-section area A [m²].
    #[arg(long, value_name = "M2", default_value_t = D.area)]
    pub area: f64,
    /// Second moment of area I [m⁴].
    #[arg(long, value_name = "M4", default_value_t = D.second_moment)]
    pub second_moment: f64,
    /// Young's modulus E [Pa].
    #[arg(long, value_name = "PA", default_value_t = D.youngs_modulus)]
    pub youngs_modulus: f64,
    /// Density ρ [kg/m³].
    #[arg(long, value_name = "KG_M3", default_value_t = D.density)]
    pub density: f64,
    /// Spin-up time T_s [s].
    #[arg(long, value_name = "S", default_value_t = D.t_s)]
    pub t_s: f64,
    /// Final hub speed ω_s [rad/s].
    #[arg(long, value_name = "RAD_S", default_value_t = D.omega_s)]
    pub omega_s: f64,
    /// FE elements (1 to 10000).
    #[arg(long, value_name = "N", default_value_t = D.elements)]
    pub elements: usize,
    /// Run length [s] (default: T_s + 5 s).
    #[arg(long, value_name = "S")]
    pub duration: Option<f64>,
    /// Reporting interval [s].
    #[arg(long, value_name = "S", default_value_t = D.sample_every)]
    pub sample_every: f64,
    /// Largest FE time step [s].
    #[arg(long, value_name = "S", default_value_t = D.max_step)]
    pub max_step: f64,
    /// Modes of the reference and the linear model (2 to 12).
    #[arg(long, value_name = "N", default_value_t = D.modes)]
    pub modes: usize,
    /// Print JSON instead of the summary.
    #[arg(long)]
    pub json: bool,
    /// The figure's printed width and formats.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
}

impl SpinUpArgs {
    fn options(&self) -> SpinUpOptions {
        SpinUpOptions {
            length: self.length,
            area: self.area,
            second_moment: self.second_moment,
            youngs_modulus: self.youngs_modulus,
            density: self.density,
            t_s: self.t_s,
            omega_s: self.omega_s,
            elements: self.elements,
            duration: self.duration,
            sample_every: self.sample_every,
            max_step: self.max_step,
            modes: self.modes,
        }
    }
}

/// Runs `flexrig spin-up`.
pub fn run(args: &SpinUpArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let r = run_spin_up(&args.options(), &args.out, &args.figure.options()?, cancel)?;
    if args.json {
        let v = serde_json::to_value(&r).map_err(|e| Error::NonFinite {
            what: "spin-up result".into(),
            value: e.to_string(),
            advice: "a non-finite value cannot be printed as JSON".into(),
        })?;
        return print_json(out, &v);
    }
    let (i_max, _) = r
        .reference
        .iter()
        .enumerate()
        .fold(
            (0, 0.0_f64),
            |m, (i, d)| if d.abs() > m.1 { (i, d.abs()) } else { m },
        );
    let last = r.t.len() - 1;
    line(
        out,
        format!(
            "Spin-up beam (Kane, Ryan & Banerjee 1987): ω_s = {} rad/s, T_s = {} s, to {} s",
            r.options.omega_s, r.options.t_s, r.t[last]
        ),
    )?;
    line(
        out,
        format!(
            "  reference ({} modes): largest tip deflection {:.6} m at t = {:.2} s; at the end {:.6} m",
            r.options.modes, r.reference[i_max], r.t[i_max], r.reference[last]
        ),
    )?;
    line(
        out,
        format!(
            "  FE ({} corotational elements): largest difference {:.2e} of the max; at the end {:.6} m",
            r.options.elements, r.fe_error_of_max, r.fe[last]
        ),
    )?;
    line(
        out,
        format!(
            "  linear rotating-frame beam (no stiffening): at the end {:.3e} m",
            r.linear[last]
        ),
    )?;
    line(
        out,
        format!(
            "Wrote {}, {} and {}",
            r.csv.display(),
            r.json.display(),
            r.figures
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )
}
