//! The lumped two-mass impact (the paper's Eq. 10–14) and what feeds it: one impact's peak by the
//! analytic, exact (energy) or time-integrated solution ([`impact`]), the paper's Fig. 6 η(γ)
//! curves for any design ([`fig6`]), and the Hertz law fitted to compression data ([`fit`]).
//!
//! May use: `shared`, `plots`.

pub mod fig6;
pub mod fit;
pub mod impact;
