//! `flexrig impact`: the peak force of the lumped two-mass impact (paper Eq. 10–14).

use std::io::Write;

use clap::{Args, ValueEnum};
use flexrig_contact::validate::in_left_open;
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::ode::{DEFAULT_RTOL, Formulation, OdeOptions, integrate};
use flexrig_lumped::prb::PrbLink;
use flexrig_lumped::{ImpactModel, Peak, peak_analytic, peak_exact};
use serde_json::json;

use crate::CliError;
use crate::output::{finite_result, line, print_json, range_arg};

/// How the peak is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// Energy balance ½ μ v0² = U(f_max): exact for any Hertz exponent.
    Exact,
    /// Closed form f_max = v0 √(k_o μ) (Eq. 13): only for n = 1.
    Analytic,
    /// Time integration (8th-order adaptive Runge–Kutta) from contact to separation.
    Ode,
}

impl Method {
    fn name(self) -> &'static str {
        match self {
            Method::Exact => "exact",
            Method::Analytic => "analytic",
            Method::Ode => "ode",
        }
    }
}

/// State variables of the ode method (see `flexrig_lumped::ode::Formulation`).
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
    /// Human (operator) mass m_h (kg).
    #[arg(long = "m-h", value_name = "KG")]
    pub m_h: f64,
    /// Effective robot mass m_eff (kg); or give --gamma, --m-r and --m-e for m_eff = m_e + γ m_r/3.
    #[arg(long = "m-eff", value_name = "KG", required_unless_present_all = ["gamma", "m_r", "m_e"], conflicts_with_all = ["gamma", "m_r", "m_e"])]
    pub m_eff: Option<f64>,
    /// PRB characteristic radius γ ∈ (0, 1] (1: compliant joint, 2/3: compliant link).
    #[arg(long, value_name = "G", requires_all = ["m_r", "m_e"])]
    pub gamma: Option<f64>,
    /// Robot link mass m_r (kg) (with --gamma).
    #[arg(long = "m-r", value_name = "KG", requires_all = ["gamma", "m_e"])]
    pub m_r: Option<f64>,
    /// Payload (end mass) m_e (kg) (with --gamma).
    #[arg(long = "m-e", value_name = "KG", requires_all = ["gamma", "m_r"])]
    pub m_e: Option<f64>,
    /// Link lateral stiffness k_δ [N/m].
    #[arg(long = "k-delta", value_name = "N_PER_M")]
    pub k_delta: f64,
    /// Contact stiffness k_c [N/m^n].
    #[arg(long = "k-c", value_name = "K")]
    pub k_c: f64,
    /// Hertz exponent n.
    #[arg(long, value_name = "N")]
    pub n: f64,
    /// Approach speed v0 [m/s].
    #[arg(long, value_name = "M_PER_S")]
    pub v0: f64,
    /// Solution method.
    #[arg(long, value_enum, default_value_t = Method::Exact)]
    pub method: Method,
    /// State variables of the ode method: auto, indentation (δ_c, δ̇) or displacement (δ, δ̇).
    #[arg(long, value_enum, default_value_t = FormulationArg::Auto)]
    pub formulation: FormulationArg,
    /// Relative tolerance of the ode method.
    #[arg(long, value_name = "R", default_value_t = DEFAULT_RTOL)]
    pub rtol: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// The validated impact of the arguments.
pub fn model(args: &ImpactArgs) -> Result<ImpactModel, CliError> {
    let mass = |flag: &str, v: f64| range_arg(flag, v, MASS.0, MASS.1);
    let m_h = mass("--m-h", args.m_h)?;
    let m_eff = match (args.m_eff, args.gamma, args.m_r, args.m_e) {
        (Some(m_eff), ..) => mass("--m-eff", m_eff)?,
        (None, Some(gamma), Some(m_r), Some(m_e)) => PrbLink::new(
            in_left_open("--gamma", gamma, 0.0, 1.0)?,
            mass("--m-r", m_r)?,
            range_arg("--m-e", m_e, 0.0, MASS.1)?,
        )?
        .effective_mass(),
        _ => {
            return Err(CliError::InvalidArgument {
                arg: "--m-eff".into(),
                value: "(missing)".into(),
                allowed: "give --m-eff, or all of --gamma, --m-r and --m-e".into(),
            });
        }
    };
    let k_delta = range_arg("--k-delta", args.k_delta, STIFFNESS.0, STIFFNESS.1)?;
    let k_c = range_arg("--k-c", args.k_c, STIFFNESS.0, STIFFNESS.1)?;
    let n = in_left_open("--n", args.n, 0.0, flexrig_contact::MAX_EXPONENT)?;
    let v0 = range_arg("--v0", args.v0, SPEED.0, SPEED.1)?;
    let spring = SeriesCompliance::new(k_delta, Hertz::new(k_c, n)?)?;
    Ok(ImpactModel::new(m_h, m_eff, spring, v0)?)
}

/// Physical ranges of the impact flags: masses (kg), stiffnesses [N/m or N/m^n], speed [m/s].
const MASS: (f64, f64) = (1e-9, 1e9);
const STIFFNESS: (f64, f64) = (1e-9, 1e20);
const SPEED: (f64, f64) = (1e-9, 1e3);

/// Refuses a peak that left double precision (the error says which quantity and what to change).
fn check_finite(peak: &Peak) -> Result<(), CliError> {
    let advice = "the impact leaves double precision; use moderate --v0, masses and stiffnesses";
    finite_result("peak force", peak.f_max, advice)?;
    finite_result("peak displacement", peak.delta_max, advice)?;
    Ok(())
}

/// The exact (energy) peak of one parameter set, validated and computed exactly as
/// `flexrig impact --method exact` does (errors name the flag, e.g. `--m-h`): masses \[kg\],
/// `k_delta` \[N/m\], `k_c` \[N/m^n\], Hertz exponent `n`, approach speed `v0` \[m/s\]. Returns
/// the model (reduced mass, impact energy) and the peak.
pub fn exact(
    m_h: f64,
    m_eff: f64,
    k_delta: f64,
    k_c: f64,
    n: f64,
    v0: f64,
) -> Result<(ImpactModel, Peak), CliError> {
    let args = ImpactArgs {
        m_h,
        m_eff: Some(m_eff),
        gamma: None,
        m_r: None,
        m_e: None,
        k_delta,
        k_c,
        n,
        v0,
        method: Method::Exact,
        formulation: FormulationArg::Auto,
        rtol: DEFAULT_RTOL,
        json: false,
    };
    let model = model(&args)?;
    let peak = peak_exact(&model);
    check_finite(&peak)?;
    Ok((model, peak))
}

/// Runs `flexrig impact`.
pub fn run(args: &ImpactArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let model = model(args)?;
    let mut report = json!({
        "method": args.method.name(),
        "m_h_kg": model.m_h(),
        "m_eff_kg": model.m_eff(),
        "mu_kg": model.reduced_mass(),
        "impact_energy_j": model.impact_energy(),
    });
    let peak: Peak = match args.method {
        Method::Exact => peak_exact(&model),
        Method::Analytic => {
            let a = peak_analytic(&model)?;
            report["k_o_n_per_m"] = json!(a.k_o);
            report["t_peak_s"] = json!(a.t_peak);
            report["contact_duration_s"] = json!(a.contact_duration);
            a.peak
        }
        Method::Ode => {
            let options = OdeOptions::new(args.rtol).map_err(|_| CliError::InvalidArgument {
                arg: "--rtol".into(),
                value: args.rtol.to_string(),
                allowed: "must lie in [1e-14, 0.1]".into(),
            })?;
            let formulation = Formulation::from(args.formulation);
            let options = options.formulation(formulation);
            let sol = integrate(&model, &options)?;
            report["formulation"] =
                json!(format!("{:?}", formulation.resolve(&model)).to_lowercase());
            report["rtol"] = json!(args.rtol);
            report["t_peak_s"] = json!(sol.t_peak);
            report["contact_duration_s"] = json!(sol.contact_duration);
            report["separation_speed_mps"] = json!(sol.separation_speed);
            report["rhs_evals"] = json!(sol.rhs_evals);
            report["steps"] = json!(sol.steps);
            report["rejected_steps"] = json!(sol.rejected_steps);
            sol.peak
        }
    };
    check_finite(&peak)?;
    report["f_max_n"] = json!(peak.f_max);
    report["delta_max_m"] = json!(peak.delta_max);
    report["indentation_max_m"] = json!(peak.indentation_max);
    report["link_deflection_max_m"] = json!(peak.link_deflection_max);
    if args.json {
        return print_json(out, &report);
    }
    print_text(out, &report)
}

fn print_text(out: &mut dyn Write, report: &serde_json::Value) -> Result<(), CliError> {
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
