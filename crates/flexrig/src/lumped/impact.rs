//! The peak force of the lumped two-mass impact (paper Eq. 10–14): by the exact energy balance
//! (any Hertz exponent), the n = 1 closed form (Eq. 13), or time integration. Inputs are
//! validated against physical ranges; errors name the flag of `flexrig impact` (`--m-h`).

use flexrig_contact::validate::in_left_open;
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::AnalyticImpact;
use flexrig_lumped::ode::{OdeOptions, OdeSolution, integrate};
use flexrig_lumped::prb::PrbLink;
use flexrig_lumped::{peak_analytic, peak_exact};

use crate::Error;
use crate::shared::output::{finite_result, range_arg};

/// The ode method's settings and the model and peak (flexrig-lumped's), for callers of this
/// module.
pub use flexrig_lumped::ode::{DEFAULT_RTOL, Formulation};
pub use flexrig_lumped::{ImpactModel, Peak};

/// The effective robot mass at the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum EffectiveMass {
    /// m_eff \[kg\] as given (`--m-eff`).
    Given(f64),
    /// m_eff = m_e + γ m_r/3 of a Pseudo-Rigid-Body link (paper Eq. 5): γ ∈ (0, 1]
    /// (`--gamma`), link mass m_r \[kg\] (`--m-r`), payload m_e \[kg\] (`--m-e`).
    Prb {
        /// PRB characteristic radius γ.
        gamma: f64,
        /// Link mass m_r \[kg\].
        m_r: f64,
        /// Payload m_e \[kg\].
        m_e: f64,
    },
}

/// One lumped impact, as given (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactInput {
    /// Human (operator) mass m_h \[kg\] (`--m-h`).
    pub m_h: f64,
    /// Effective robot mass.
    pub m_eff: EffectiveMass,
    /// Link lateral stiffness k_δ \[N/m\] (`--k-delta`).
    pub k_delta: f64,
    /// Contact stiffness k_c \[N/m^n\] (`--k-c`).
    pub k_c: f64,
    /// Hertz exponent n (`--n`).
    pub n: f64,
    /// Approach speed v0 \[m/s\] (`--v0`).
    pub v0: f64,
}

impl ImpactInput {
    /// The validated impact model (errors name the flag, the value and the allowed range).
    pub fn model(&self) -> Result<ImpactModel, Error> {
        let mass = |flag: &str, v: f64| range_arg(flag, v, MASS.0, MASS.1, "kg");
        let m_h = mass("--m-h", self.m_h)?;
        let m_eff = match self.m_eff {
            EffectiveMass::Given(m_eff) => mass("--m-eff", m_eff)?,
            EffectiveMass::Prb { gamma, m_r, m_e } => PrbLink::new(
                in_left_open("--gamma", gamma, 0.0, 1.0)?,
                mass("--m-r", m_r)?,
                range_arg("--m-e", m_e, 0.0, MASS.1, "kg")?,
            )?
            .effective_mass(),
        };
        let k_delta = range_arg("--k-delta", self.k_delta, STIFFNESS.0, STIFFNESS.1, "N/m")?;
        let k_c = range_arg("--k-c", self.k_c, STIFFNESS.0, STIFFNESS.1, "N/mⁿ")?;
        let n = in_left_open("--n", self.n, 0.0, flexrig_contact::MAX_EXPONENT)?;
        let v0 = range_arg("--v0", self.v0, SPEED.0, SPEED.1, "m/s")?;
        let spring = SeriesCompliance::new(k_delta, Hertz::new(k_c, n)?)?;
        Ok(ImpactModel::new(m_h, m_eff, spring, v0)?)
    }
}

/// Physical ranges of the impact flags: masses (kg), stiffnesses [N/m or N/m^n], speed [m/s].
const MASS: (f64, f64) = (1e-9, 1e9);
const STIFFNESS: (f64, f64) = (1e-9, 1e20);
const SPEED: (f64, f64) = (1e-9, 1e3);

/// Refuses a peak that left double precision (the error says which quantity and what to change).
fn check_finite(peak: &Peak) -> Result<(), Error> {
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
) -> Result<(ImpactModel, Peak), Error> {
    let model = ImpactInput {
        m_h,
        m_eff: EffectiveMass::Given(m_eff),
        k_delta,
        k_c,
        n,
        v0,
    }
    .model()?;
    let peak = peak_exact(&model);
    check_finite(&peak)?;
    Ok((model, peak))
}

/// How the peak is computed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Energy balance ½ μ v0² = U(f_max): exact for any Hertz exponent.
    Exact,
    /// Closed form f_max = v0 √(k_o μ) (Eq. 13): only for n = 1.
    Analytic,
    /// Time integration (8th-order adaptive Runge–Kutta) from contact to separation, with
    /// these state variables and relative tolerance `rtol` (in [1e-14, 0.1], `--rtol`).
    Ode {
        /// State variables.
        formulation: Formulation,
        /// Relative tolerance.
        rtol: f64,
    },
}

impl Method {
    /// The method's name (`exact`, `analytic`, `ode`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Exact => "exact",
            Method::Analytic => "analytic",
            Method::Ode { .. } => "ode",
        }
    }
}

/// What a method found beyond the peak.
#[derive(Debug, Clone, PartialEq)]
pub enum Details {
    /// The energy balance: the peak only.
    Exact,
    /// The closed form: overall stiffness, time to peak, contact duration.
    Analytic(AnalyticImpact),
    /// The time integration, with the state variables it used (`Auto` resolved).
    Ode {
        /// The integration's result.
        solution: OdeSolution,
        /// The state variables used.
        formulation: Formulation,
    },
}

/// The peak of one impact and how it was found.
#[derive(Debug, Clone, PartialEq)]
pub struct ImpactResult {
    /// The validated model (masses, reduced mass, impact energy).
    pub model: ImpactModel,
    /// The peak (finite).
    pub peak: Peak,
    /// The method's further results.
    pub details: Details,
}

/// The peak of `input` by `method`; a non-finite peak is refused.
pub fn solve(input: &ImpactInput, method: Method) -> Result<ImpactResult, Error> {
    let model = input.model()?;
    let (peak, details) = match method {
        Method::Exact => (peak_exact(&model), Details::Exact),
        Method::Analytic => {
            let a = peak_analytic(&model)?;
            (a.peak, Details::Analytic(a))
        }
        Method::Ode { formulation, rtol } => {
            let options = OdeOptions::new(rtol).map_err(|_| Error::InvalidArgument {
                arg: "--rtol".into(),
                value: flexrig_contact::validate::display(rtol),
                allowed: "must lie in [1e-14, 0.1]".into(),
            })?;
            let solution = integrate(&model, &options.formulation(formulation))?;
            let formulation = formulation.resolve(&model);
            (
                solution.peak,
                Details::Ode {
                    solution,
                    formulation,
                },
            )
        }
    };
    check_finite(&peak)?;
    Ok(ImpactResult {
        model,
        peak,
        details,
    })
}

/// The severity of the lumped impact `model` by the ode method ([`crate::shared::severity::of_lumped`]:
/// relative tolerance `rtol`, `formulation`), with the contact area of a dome of radius
/// `dome_radius_m` \[m\] (`--dome-radius`, > 0; none: the paper's dome).
pub fn severity(
    model: &ImpactModel,
    rtol: f64,
    formulation: Formulation,
    dome_radius_m: Option<f64>,
) -> Result<crate::shared::severity::Severity, Error> {
    let radius = match dome_radius_m {
        Some(r) => range_arg("--dome-radius", r, 1e-6, 10.0, "m")?,
        None => crate::shared::severity::paper_dome_radius_m()?,
    };
    let options = OdeOptions::new(rtol).map_err(|_| Error::InvalidArgument {
        arg: "--rtol".into(),
        value: flexrig_contact::validate::display(rtol),
        allowed: "must lie in [1e-14, 0.1]".into(),
    })?;
    crate::shared::severity::of_lumped(model, options.rtol, formulation, radius)
}
