//! Plausibility of the quantities a user types for a robot: valid values that look like a unit
//! slip (grams typed for kilograms, millimetres for metres, degrees per second for radians per
//! second). One rule per quantity, shared by every front that takes masses, lengths and speeds
//! (`safety`, `safety-map`, `strike`), so that the same slip gets the same warning everywhere.
//! A warning never stops the work: the fronts print it (text: standard error) and list it in
//! their JSON.

use flexrig_contact::validate::display;
pub use flexrig_rig::plausibility::Warning;

fn warning(flag: &str, message: String) -> Warning {
    Warning {
        field: flag.to_string(),
        message,
    }
}

/// The heaviest plausible mass \[kg\] of a robot's link, payload or moving parts near a person:
/// collaborative arms move at most a few tens of kilograms (ISO/TS 15066:2016 Annex A's
/// examples stay below 50 kg); 200 kg leaves room for a mobile base.
pub const PLAUSIBLE_MASS_KG: f64 = 200.0;

/// The longest plausible robot link \[m\].
pub const PLAUSIBLE_LENGTH_M: f64 = 5.0;

/// The fastest plausible relative speed of a robot and a person \[m/s\] (industrial arms reach a
/// few m/s; the standard's transient contacts are studied below 2.5 m/s).
pub const PLAUSIBLE_SPEED_MPS: f64 = 10.0;

/// A warning for the mass `kg` given as `flag`, when it is heavier than
/// [`PLAUSIBLE_MASS_KG`] (with its value in grams read as kilograms).
pub fn mass(flag: &str, kg: f64) -> Option<Warning> {
    (kg.is_finite() && kg > PLAUSIBLE_MASS_KG).then(|| {
        warning(
            flag,
            format!(
                "{} kg is heavier than a robot near a person moves (up to about {} kg); if \
             grams were meant, {} g is {} kg",
                display(kg),
                display(PLAUSIBLE_MASS_KG),
                display(kg),
                display(kg / 1000.0)
            ),
        )
    })
}

/// A warning for the length `m` given as `flag`, when it is longer than [`PLAUSIBLE_LENGTH_M`].
pub fn length(flag: &str, m: f64) -> Option<Warning> {
    (m.is_finite() && m > PLAUSIBLE_LENGTH_M).then(|| {
        warning(
            flag,
            format!(
                "{} m is longer than a robot's link (up to about {} m); if millimetres were \
             meant, {} mm is {} m",
                display(m),
                display(PLAUSIBLE_LENGTH_M),
                display(m),
                display(m / 1000.0)
            ),
        )
    })
}

/// A warning for the relative speed `mps` given as `flag`, when it is faster than
/// [`PLAUSIBLE_SPEED_MPS`].
pub fn speed(flag: &str, mps: f64) -> Option<Warning> {
    (mps.is_finite() && mps > PLAUSIBLE_SPEED_MPS).then(|| {
        warning(
            flag,
            format!(
                "{} m/s is faster than robot arms move near people (up to about {} m/s)",
                display(mps),
                display(PLAUSIBLE_SPEED_MPS)
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slips_are_named_with_their_conversion_and_plausible_values_pass() {
        let w = mass("--m-r", 1200.0).unwrap().to_string();
        assert!(
            w.contains("--m-r: 1200 kg") && w.contains("1200 g is 1.2 kg"),
            "{w}"
        );
        assert!(mass("--m-r", 200.0).is_none() && mass("--m-e", 0.412).is_none());
        let w = length("--length", 600.0).unwrap().message;
        assert!(w.contains("600 mm is 0.6 m"), "{w}");
        assert!(length("--length", 0.338).is_none());
        assert!(speed("--speed", 57.3).is_some() && speed("--speed", 2.5).is_none());
    }
}
