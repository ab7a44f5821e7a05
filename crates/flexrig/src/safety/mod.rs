//! The safety verdict (ISO/TS 15066, docs/safety.md): how fast may a design move near a body
//! region. One design at one region by the standard's formula, the energy method and the
//! simulated impact ([`point`], whose items this module re-exports: `flexrig::safety::safety`);
//! the simulated impact of a link design and its root search for the permissible speed
//! ([`simulation`]); a scene as the design — a driven scene ([`scene`]) or a test-bed scene
//! ([`test_bed`]); the safe-speed maps over two design axes ([`map`]); and the report for a risk
//! assessment ([`report`]); a measured impact's severity and verdict ([`measured`]).
//!
//! May use: `shared`, `plots`, `log`, `lumped`, `driven`, `testbed`.

pub mod map;
pub mod measured;
pub mod overall;
pub mod point;
pub mod question;
pub mod report;
pub mod scene;
pub mod simulation;
pub mod test_bed;

pub use overall::{OverallVerdict, default_methods};
pub use point::*;
