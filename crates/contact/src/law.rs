//! The [`ContactLaw`] trait: a normal contact force as a function of indentation and its rate.

use crate::Hertz;

/// A normal contact law f(δ, δ̇) between two bodies.
///
/// Conventions (all laws): δ \[m\] is the indentation (penetration), positive in contact; δ̇ [m/s]
/// its rate, positive while approaching. The force is compressive and never adhesive:
/// f ≥ 0, and f = 0 for δ ≤ 0. Implementors are plain data (`Send + Sync`), so one law may be
/// shared by many simulations running in parallel.
pub trait ContactLaw: Send + Sync + std::fmt::Debug {
    /// Contact force f(δ, δ̇) ≥ 0 \[N\].
    fn force(&self, delta: f64, delta_dot: f64) -> f64;

    /// Tangent stiffness ∂f/∂δ [N/m] at (δ, δ̇); 0 where the force is clamped to 0.
    fn stiffness(&self, delta: f64, delta_dot: f64) -> f64;

    /// Force f(δ, δ̇) \[N\] and tangent stiffness ∂f/∂δ [N/m] together ([`Self::force`],
    /// [`Self::stiffness`]); a law may share their work (Hertz: one power of δ).
    fn force_and_stiffness(&self, delta: f64, delta_dot: f64) -> (f64, f64) {
        (
            self.force(delta, delta_dot),
            self.stiffness(delta, delta_dot),
        )
    }

    /// True unless the force at (δ, δ̇) is ≤ 0 (a NaN force counts as pushing): the same
    /// answer as testing [`Self::force`], which a law may give without computing the force
    /// (Hertz: any indentation at which k δ^n cannot underflow).
    fn pushes(&self, delta: f64, delta_dot: f64) -> bool {
        !(-self.force(delta, delta_dot) >= 0.0)
    }

    /// Tangent damping ∂f/∂δ̇ [N·s/m] at (δ, δ̇); 0 for an elastic law.
    fn damping(&self, _delta: f64, _delta_dot: f64) -> f64 {
        0.0
    }

    /// Elastic energy stored at indentation δ \[J\]: ∫₀^δ f(s, 0) ds. Dissipation is not included.
    fn elastic_energy(&self, delta: f64) -> f64 {
        self.elastic().energy(delta)
    }

    /// The elastic (rate-independent) part of the law.
    fn elastic(&self) -> Hertz;
}
