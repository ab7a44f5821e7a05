//! Energy accounting: kinetic energy ½ q̇ᵀ M(q) q̇, strain energy of the elements and the root
//! spring, external work by the trapezoidal rule W += ½ (F_n + F_{n+1})·(q_{n+1} − q_n), and
//! the dissipated energy E₀ + W − T − U (damping plus algorithmic dissipation of
//! generalized-α; 0 up to round-off for ρ∞ = 1, undamped, linear model).

pub use crate::assembly::{kinetic_and_strain_energy, kinetic_energy, strain_energy};
pub use crate::dynamics::Energy;
