//! Progress of a long computation (many runs), reported to the caller: a trait with do-nothing
//! defaults, so a front draws a bar ([`Progress`] for the CLI's indicatif bar) and a script
//! passes [`NoProgress`].

/// Told how many steps a computation has, then of each finished step (from any thread).
pub trait Progress: Sync {
    /// The computation has `total` steps.
    fn start(&self, total: usize) {
        let _ = total;
    }
    /// One more step is done.
    fn advance(&self) {}
    /// The computation ended (successfully or not).
    fn finish(&self) {}
}

/// Reports nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {}
