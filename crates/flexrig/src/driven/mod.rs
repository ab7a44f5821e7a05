//! The driven robot (docs/driven.md): typed entry points over flexrig-impact's drive models —
//! the spin-up beam benchmark ([`spin_up`]), one driven CJ or CL strike from a drive description
//! ([`strike`]), the role-switch table ([`role_switch`]), and driven scenes ([`scene`]: a scene
//! file with a `[drive]` section, run by `flexrig run`, `sweep` and Python) with their MCAP logs
//! ([`log`]). Each takes a plain options struct of
//! SI fields, checks it (errors name the flag or the file's field), returns its numbers and the
//! files it wrote (CSV, JSON, SVG; each written whole or not at all).

pub mod log;
pub mod role_switch;
pub mod scene;
pub mod spin_up;
pub mod strike;

use crate::{CancelToken, Error};

// The physics types a drive description is made of (the fronts name them through the library).
pub use flexrig_contact::{ContactError, DampingSpec, Hertz};
pub use flexrig_impact::LinkParams;
pub use flexrig_impact::drive;

/// Stops with [`flexrig_impact::ImpactError::Interrupted`] (exit code 130) once `cancel` is set.
pub(crate) fn check(cancel: &CancelToken) -> Result<(), Error> {
    if cancel.is_cancelled() {
        Err(Error::Impact(flexrig_impact::ImpactError::Interrupted))
    } else {
        Ok(())
    }
}

/// A float as Rust prints it: the shortest text that reads back to the same bits.
pub(crate) fn num(v: f64) -> String {
    format!("{v}")
}
