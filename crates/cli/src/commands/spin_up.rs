//! `flexrig spin-up`: the spin-up beam benchmark (Simo & Vu-Quoc's 10 m beam, or Kane, Ryan &
//! Banerjee's 8 m aluminium beam with `--case kane`), see [`flexrig::driven::spin_up`]; a summary
//! or JSON.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::driven::spin_up::{SpinUpCase, SpinUpFlags, run_with_figures as run_spin_up};
use flexrig::{CancelToken, Error};

use crate::print::{line, print_json};

/// The flags' defaults (the discretisation; the beam's come from `--case`).
const D: SpinUpFlags = SpinUpFlags::DEFAULT;

/// The beams by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum CaseArg {
    /// Simo & Vu-Quoc (1986): L = 10 m, EA = 2.8e7 N, EI = 1.4e4 N·m², ρA = 1.2 kg/m, to 6 rad/s.
    SimoVuQuoc,
    /// Kane, Ryan & Banerjee (1987): the 8 m aluminium beam (E = 6.8952e10 Pa, ρ = 2766.67
    /// kg/m³, A = 7.2968e-5 m², I = 8.2189e-9 m⁴), to 4 rad/s.
    Kane,
}

/// Arguments of `flexrig spin-up` (defaults: Simo & Vu-Quoc's beam).
#[derive(Debug, Args)]
pub struct SpinUpArgs {
    /// Directory for spin_up.csv, spin_up.json and the figure spin_up.svg (or .pdf, .png; created
    /// if missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// The beam and spin-up: `simo-vu-quoc` (the 10 m beam often credited to Kane et al.) or
    /// `kane` (Kane, Ryan & Banerjee's 8 m aluminium beam); the flags below override its numbers.
    #[arg(long, value_enum, default_value = "simo-vu-quoc")]
    pub case: CaseArg,
    /// Beam length L [m] (default: the case's).
    #[arg(long, value_name = "M")]
    pub length: Option<f64>,
    /// Cross-section area A [m²] (default: the case's).
    #[arg(long, value_name = "M2")]
    pub area: Option<f64>,
    /// Second moment of area I [m⁴] (default: the case's).
    #[arg(long, value_name = "M4")]
    pub second_moment: Option<f64>,
    /// Young's modulus E [Pa] (default: the case's).
    #[arg(long, value_name = "PA")]
    pub youngs_modulus: Option<f64>,
    /// Density ρ [kg/m³] (default: the case's).
    #[arg(long, value_name = "KG_M3")]
    pub density: Option<f64>,
    /// Spin-up time T_s [s] (default: the case's, 15).
    #[arg(long, value_name = "S")]
    pub t_s: Option<f64>,
    /// Final hub speed ω_s [rad/s] (default: the case's, 6 or 4).
    #[arg(long, value_name = "RAD_S")]
    pub omega_s: Option<f64>,
    /// FE elements (1 to 10000; the FE run's elements × time steps at most 4e6, checked before the
    /// work).
    #[arg(long, value_name = "N", default_value_t = D.elements)]
    pub elements: usize,
    /// Run length [s] (default: T_s + 5 s; bounded by the reference's work, checked before the
    /// work).
    #[arg(long, value_name = "S")]
    pub duration: Option<f64>,
    /// Reporting interval [s] (at most 100 000 reported times).
    #[arg(long, value_name = "S", default_value_t = D.sample_every)]
    pub sample_every: f64,
    /// Largest FE time step [s].
    #[arg(long, value_name = "S", default_value_t = D.max_step)]
    pub max_step: f64,
    /// Modes of the reference and the linear model (2 to 12; 5 are within 2.3e-6 of the max of
    /// 7).
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
    /// The flags as the library reads them.
    fn flags(&self) -> SpinUpFlags {
        SpinUpFlags {
            case: match self.case {
                CaseArg::SimoVuQuoc => SpinUpCase::SimoVuQuoc,
                CaseArg::Kane => SpinUpCase::Kane,
            },
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
    let flags = args.flags();
    let r = run_spin_up(&flags.options(), &args.out, &args.figure.options()?, cancel)?;
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
            "Spin-up beam ({}): L = {} m, ω_s = {} rad/s, T_s = {} s, to {} s",
            flags.source(),
            r.options.length,
            r.options.omega_s,
            r.options.t_s,
            r.t[last]
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
