//! `flexrig impact`: the peak force of the lumped two-mass impact (paper Eq. 10–14), see
//! [`flexrig::lumped::impact`].

use std::io::Write;

use clap::{Args, ValueEnum};
use flexrig::Error;
use flexrig::lumped::impact::{Formulation, ImpactInput, Method};

use crate::print::{line, print_json, print_severity};

/// The default of `--rtol` as its help shows it: [`flexrig::lumped::impact::DEFAULT_RTOL`] (checked by a test).
const RTOL_TEXT: &str = "1e-10";

/// How the peak is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum MethodArg {
    /// Energy balance ½ μ v0² = U(f_max): exact for any Hertz exponent.
    Exact,
    /// Closed form f_max = v0 √(k_o μ) (Eq. 13): only for n = 1.
    Analytic,
    /// Time integration (8th-order adaptive Runge–Kutta) from contact to separation.
    Ode,
}

/// State variables of the ode method (see [`Formulation`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum FormulationArg {
    /// Displacement state when the link deflection dominates, indentation state otherwise.
    Auto,
    /// State (δ_c, δ̇): explicit force.
    Indentation,
    /// State (δ, δ̇): a Newton solve of the series compliance per evaluation.
    Displacement,
}

impl From<FormulationArg> for Formulation {
    fn from(f: FormulationArg) -> Self {
        match f {
            FormulationArg::Auto => Formulation::Auto,
            FormulationArg::Indentation => Formulation::Indentation,
            FormulationArg::Displacement => Formulation::Displacement,
        }
    }
}

/// Arguments of `flexrig impact`.
#[derive(Debug, Args)]
#[command(allow_negative_numbers = true)]
pub struct ImpactArgs {
    /// Human (operator) mass m_h [kg].
    #[arg(long = "m-h", value_name = "KG")]
    pub m_h: f64,
    /// Effective robot mass m_eff [kg]; or give --gamma, --m-r and --m-e for m_eff = m_e + γ m_r/3.
    #[arg(long = "m-eff", value_name = "KG", conflicts_with_all = ["gamma", "m_r", "m_e"])]
    pub m_eff: Option<f64>,
    /// PRB characteristic radius γ ∈ (0, 1] (1: compliant joint, 2/3: compliant link).
    #[arg(long, value_name = "G")]
    pub gamma: Option<f64>,
    /// Robot link mass m_r [kg] (with --gamma).
    #[arg(long = "m-r", value_name = "KG")]
    pub m_r: Option<f64>,
    /// Payload (end mass) m_e [kg] (with --gamma).
    #[arg(long = "m-e", value_name = "KG")]
    pub m_e: Option<f64>,
    /// Link lateral stiffness k_δ [N/m].
    #[arg(long = "k-delta", value_name = "N_PER_M")]
    pub k_delta: f64,
    /// Contact stiffness k_c [N/mⁿ].
    #[arg(long = "k-c", value_name = "K")]
    pub k_c: f64,
    /// Hertz exponent n.
    #[arg(long, value_name = "N")]
    pub n: f64,
    /// Approach speed v0 [m/s].
    #[arg(long, value_name = "M_PER_S")]
    pub v0: f64,
    /// Solution method.
    #[arg(long, value_enum, default_value_t = MethodArg::Exact)]
    pub method: MethodArg,
    /// State variables of the ode method: auto, indentation (δ_c, δ̇) or displacement (δ, δ̇).
    #[arg(long, value_enum, default_value_t = FormulationArg::Auto)]
    pub formulation: FormulationArg,
    /// Relative tolerance of the ode method.
    #[arg(long, value_name = "R", default_value = RTOL_TEXT)]
    pub rtol: f64,
    /// Dome radius for the contact pressure of the ode method's severity [m] (default: the
    /// paper's dome, 71.5 mm).
    #[arg(long = "dome-radius", value_name = "M")]
    pub dome_radius: Option<f64>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

impl ImpactArgs {
    /// The library's input: --m-eff, or all of --gamma, --m-r and --m-e
    /// ([`flexrig::fronts::effective_mass`] names the flags missing).
    pub fn input(&self) -> Result<ImpactInput, Error> {
        Ok(ImpactInput {
            m_h: self.m_h,
            m_eff: flexrig::fronts::effective_mass(self.m_eff, self.gamma, self.m_r, self.m_e)?,
            k_delta: self.k_delta,
            k_c: self.k_c,
            n: self.n,
            v0: self.v0,
        })
    }

    /// The library's method.
    pub fn method(&self) -> Method {
        match self.method {
            MethodArg::Exact => Method::Exact,
            MethodArg::Analytic => Method::Analytic,
            MethodArg::Ode => Method::Ode {
                formulation: self.formulation.into(),
                rtol: self.rtol,
            },
        }
    }
}

/// Runs `flexrig impact`.
pub fn run(args: &ImpactArgs, out: &mut dyn Write) -> Result<(), Error> {
    let (report, severity) =
        flexrig::fronts::impact_full_report(&args.input()?, args.method(), args.dome_radius)?;
    if args.json {
        return print_json(out, &report);
    }
    print_text(out, &report)?;
    if let Some(s) = &severity {
        print_severity(out, s, "the head, acceleration f/m_h")?;
    }
    Ok(())
}

fn print_text(out: &mut dyn Write, report: &serde_json::Value) -> Result<(), Error> {
    let rows: [(&str, &str, &str); 14] = [
        ("method", "method", ""),
        ("peak force f_max", "f_max_n", "N"),
        ("peak displacement δ_max", "delta_max_m", "m"),
        ("  contact indentation δ_c", "indentation_max_m", "m"),
        ("  link deflection δ_l", "link_deflection_max_m", "m"),
        ("effective mass m_eff", "m_eff_kg", "kg"),
        ("reduced mass μ", "mu_kg", "kg"),
        ("impact energy ½μv0²", "impact_energy_j", "J"),
        ("overall stiffness k_o", "k_o_n_per_m", "N/m"),
        ("time to peak", "t_peak_s", "s"),
        ("contact duration", "contact_duration_s", "s"),
        ("separation speed", "separation_speed_mps", "m/s"),
        ("right-hand-side evaluations", "rhs_evals", ""),
        ("steps (rejected)", "steps", ""),
    ];
    for (label, key, unit) in rows {
        let Some(value) = report.get(key) else {
            continue;
        };
        let text = match value {
            serde_json::Value::Number(x) if key == "steps" => {
                format!("{x} ({})", report["rejected_steps"])
            }
            serde_json::Value::Number(x) if x.is_f64() => {
                format!("{:.10e}", x.as_f64().unwrap_or(f64::NAN))
            }
            serde_json::Value::String(s) => s.clone(),
            other => other.to_string(),
        };
        line(out, format!("{label:<30} {text} {unit}"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rtol_shown_is_the_default() {
        assert_eq!(
            RTOL_TEXT.parse::<f64>().unwrap(),
            flexrig::lumped::impact::DEFAULT_RTOL
        );
    }
}
