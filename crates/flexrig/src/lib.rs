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

pub mod beam;
pub mod bench;
pub mod cancel;
pub mod driven;
pub mod error;
pub mod eta;
pub mod eta_map;
pub mod eta_rotor;
pub mod experiment;
pub mod fig6;
pub mod fit;
pub mod foxglove_layout;
pub mod fronts;
pub mod impact;
pub mod link;
pub mod mcap_log;
pub mod output;
pub mod payload;
pub mod plots;
pub mod prb;
pub mod progress;
pub mod run;
pub mod safety;
pub mod safety_map;
pub mod safety_report;
pub mod safety_scene;
pub mod safety_simulation;
pub mod safety_test_bed;
pub mod scenes;
pub mod severity;
pub mod study;
pub mod traces;
pub mod validation;

pub use cancel::CancelToken;
pub use error::{Error, ErrorKind};
pub use progress::{NoProgress, Progress};
