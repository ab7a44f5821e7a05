//! flexrig-contact: normal contact laws for impact simulation.
//!
//! - [`Hertz`]: f = k_c δ_c^n (paper Eq. 4), with the paper's fitted materials in
//!   [`Materials::bundled`] (skinned aluminium k = 7.359e7, n = 1.961; skinned iron k = 9.642e7,
//!   n = 2.002; ABS k = 1.311e7, n = 1.817; dome radius 71.5 mm).
//! - [`DampedHertz`]: f = k δ^n (1 + χ δ̇) with χ from Hunt–Crossley or Lankarani–Nikravesh.
//! - [`AdamsImpact`]: the ADAMS IMPACT function with its cubic STEP damping ramp.
//! - [`DampingSpec`]: the choice among these as plain data (scene files, CLI flags).
//! - [`SeriesCompliance`]: a link spring in series with the contact (paper Eq. 6–9): the force at
//!   a given total displacement, the stored energy, and the force at a given energy.
//! - [`DomeBlockContact`]: the [`ContactCallback`] the test rig calls each step — the
//!   parry3d-f64 penetration of the dome into the block, then the contact law.
//! - [`fit_hertz`]: least-squares (k, n) with R² and standard errors from compression data.
//!
//! Every law implements [`ContactLaw`]; all are plain `Send + Sync` data, so many simulations can
//! share them in one process. Units are SI: m, N, s, J; k in N/m^n.
//!
//! ```
//! use flexrig_contact::{ContactLaw, Hertz, SeriesCompliance};
//! let contact = Hertz::new(1e8, 2.0)?;
//! assert_eq!(contact.force(1e-3, 0.0), 100.0);
//! // A stiff link (k_δ = 1e8 N/m) in series: 100 N now needs 1 mm + 1 µm.
//! let series = SeriesCompliance::new(1e8, contact)?;
//! assert!((series.force(1.001e-3) - 100.0).abs() < 1e-9);
//! # Ok::<(), flexrig_contact::ContactError>(())
//! ```

mod damped;
mod damping_spec;
mod dome_block;
mod error;
mod fit;
mod hertz;
mod impact;
mod law;
mod materials;
mod series;
pub mod tolerance;
pub mod validate;

/// The parry3d-f64 math types used by [`ContactCallback`] (glam `DVec3`, `DPose3`).
pub use parry3d_f64::math;

pub use damped::{DampedHertz, DampingModel};
pub use damping_spec::{DampingSpec, MAX_OVERDAMPING, critical_damping};
pub use dome_block::{BodyKinematics, ContactCallback, ContactSample, DomeBlockContact};
pub use error::ContactError;
pub use fit::{CSV_HEADER, CompressionPoint, HertzFit, fit_hertz, parse_compression_csv};
pub use hertz::{Hertz, HertzSpec, MAX_EXPONENT};
pub use impact::{AdamsImpact, cubic_step, cubic_step_slope};
pub use law::ContactLaw;
pub use materials::{BUNDLED_MATERIALS_TOML, Material, Materials};
pub use series::{ForceSolve, SeriesCompliance};
