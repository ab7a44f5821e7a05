//! The virtual test bed (the paper's §VI): the bundled scenes and a scene file with overrides
//! ([`scenes`]), one run of any scene — a test-bed scene, or a driven scene routed to the driven
//! strike — logged or not, with its summary as JSON ([`run`]), the link quantities of a scene
//! ([`link`]), a run kept in memory for Python ([`traces`]), and the Fig. 9 experiment with its
//! figure ([`experiment`]).
//!
//! May use: `shared`, `plots`, `log`, `driven`.

pub mod experiment;
pub mod link;
pub mod run;
pub mod scenes;
pub mod traces;
