//! The finite-element computations a user asks for by name: the Fig. 6 design cases at FE
//! fidelity (η_FE and the effective γ: [`eta`]), their maps ([`eta_map`]) and the rotor sweep
//! ([`eta_rotor`]), the test bed's CL/CJ over the payload ([`payload`], with its figure), the Pseudo-Rigid-Body check ([`prb`]) and the beam's statics and modes
//! ([`beam`]).
//!
//! May use: `shared`, `plots`, `log`, `lumped`, `testbed`, `study`.

pub mod beam;
pub mod eta;
pub mod eta_map;
pub mod eta_rotor;
pub mod payload;
pub mod prb;
