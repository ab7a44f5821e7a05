//! flexrig-lumped: the Pseudo-Rigid-Body relations and the two-mass impact model of the paper.
//!
//! - [`prb`]: equal lateral stiffness (Eq. 1–3), the PRB torsion spring k_θp = π EI γ²/L and the
//!   effective mass m_eff = m_e + γ m_r/3 (Eq. 5).
//! - [`ImpactModel`]: μ δ̈ = −f(δ) with a link spring in series with a Hertz contact (Eq. 6–12).
//! - Three solutions: [`peak_analytic`] (n = 1, Eq. 13), [`peak_exact`] (any n, by energy — the
//!   paper says no explicit formulation exists for n ≠ 1; the energy balance is one exact scalar
//!   equation), and [`ode::integrate`] (8th-order adaptive Runge–Kutta with dense output and event
//!   location of the peak and of separation).
//! - [`fig6`]: η(γ) (Eq. 15) for the eight design cases of the paper's Fig. 6.
//!
//! ```
//! use flexrig_contact::{Hertz, SeriesCompliance};
//! use flexrig_lumped::{ImpactModel, peak_exact, prb::PrbLink};
//! // Fig. 6 case: m_h = 4 kg, rigid link k_δ = 1e8 N/m, m_e = 0.1 kg, CJ (γ = 1), n = 2.
//! let spring = SeriesCompliance::new(1e8, Hertz::new(1e8, 2.0)?)?;
//! let link = PrbLink::new(1.0, 10.0, 0.1)?;
//! let model = ImpactModel::with_prb_link(4.0, link, spring, 2.0)?;
//! let peak = peak_exact(&model);
//! assert!((peak.f_max - 2296.617006).abs() < 1e-5);
//! # Ok::<(), flexrig_lumped::LumpedError>(())
//! ```

mod analytic;
mod error;
mod exact;
pub mod fig6;
mod model;
pub mod ode;
pub mod prb;
pub mod samples;

pub use analytic::{AnalyticImpact, peak_analytic};
pub use error::LumpedError;
pub use exact::peak_exact;
pub use model::{ImpactModel, Peak};
