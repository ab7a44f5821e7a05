//! flexrig: the flexible-multibody impact simulator's library — the product's API, shared by the
//! command line (`flexrig-cli`) and the Python package. Every computation takes typed inputs
//! (SI units), returns typed results and fails with [`Error`], which names the field and says
//! whether the input was bad ([`Error::exit_code`]). Nothing here parses a command line, prints a
//! report or holds global state: many computations run in parallel in one process, and a
//! [`CancelToken`] stops the runs of one of them. See `docs/architecture.md` for which module
//! owns which concept.
//!
//! ```
//! use flexrig::impact::{EffectiveMass, ImpactInput, Method, solve};
//! // The lumped impact of the paper's Fig. 6 (n = 1): f_max = v0 √(k_o μ), Eq. 13.
//! let input = ImpactInput {
//!     m_h: 4.0,
//!     m_eff: EffectiveMass::Given(3.4333),
//!     k_delta: 1e8,
//!     k_c: 1e8,
//!     n: 1.0,
//!     v0: 2.0,
//! };
//! let r = solve(&input, Method::Analytic)?;
//! assert!(r.peak.f_max > 19_000.0);
//! # Ok::<(), flexrig::Error>(())
//! ```

// The library by concept, from the fronts down (docs/architecture.md; the allowed directions
// between the folders are written once, in `tests/architecture/rules.toml`, and checked by the
// test beside them):
pub mod arm;
pub mod driven;
pub mod fe;
pub mod fronts;
pub mod log;
pub mod lumped;
pub mod plots;
pub mod quality;
pub mod safety;
pub mod shared;
pub mod study;
pub mod testbed;

// The paths of earlier versions, kept so that users' code and scripts keep compiling.
pub use fe::{beam, eta, eta_map, eta_rotor, payload, prb};
pub use log::layout as foxglove_layout;
pub use log::mcap as mcap_log;
pub use lumped::{fig6, fit, impact};
pub use quality::{bench, validation};
pub use safety::map as safety_map;
pub use safety::report as safety_report;
pub use safety::scene as safety_scene;
pub use safety::simulation as safety_simulation;
pub use safety::test_bed as safety_test_bed;
pub use shared::{cancel, error, output, progress, severity};
pub use testbed::{experiment, link, run, scenes, traces};

pub use cancel::CancelToken;
pub use error::{Error, ErrorKind};
pub use progress::{NoProgress, Progress};
