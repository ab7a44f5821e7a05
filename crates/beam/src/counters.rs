//! Work counters of the time steps taken with one [`crate::Workspace`]: how many Newton
//! iterations, residual-only assemblies, assemblies with the iteration matrix, factorisations
//! and solves. Counts, not times: they are load-independent, so tests can pin them (e.g. that a
//! Newton variant needs fewer iterations) while speed itself lives in the benchmarks. The time of
//! a run is, to a good approximation, Σ count × unit cost (the unit costs are the criterion
//! benches `stage/…`, see docs/performance-beam.md).

/// Cumulative work of the steps taken with a workspace (reset by
/// [`crate::Workspace::reset_counters`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct StepCounters {
    /// Steps accepted (a step taken in pieces counts once per piece).
    pub steps: usize,
    /// Newton iterations (one linear solve each), rejected attempts included.
    pub iterations: usize,
    /// Assemblies of the residual alone.
    pub residuals: usize,
    /// Assemblies of the residual with the iteration matrix.
    pub tangents: usize,
    /// Factorisations of the iteration matrix.
    pub factorizations: usize,
}

impl StepCounters {
    /// Newton iterations per accepted step (0 before the first step).
    pub fn iterations_per_step(&self) -> f64 {
        self.iterations as f64 / self.steps.max(1) as f64
    }
    /// Factorisations per accepted step.
    pub fn factorizations_per_step(&self) -> f64 {
        self.factorizations as f64 / self.steps.max(1) as f64
    }
}
