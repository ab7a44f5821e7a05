//! Plausibility of the quantities a user types for a robot: valid values that look like a unit
//! slip (grams typed for kilograms, millimetres for metres, degrees per second for radians per
//! second). One rule per quantity, shared by every front that takes masses, lengths and speeds
//! (scenes run by `flexrig run` and sweeps, `strike`, `safety`, `safety-map`), so that the same
//! slip gets the same warning everywhere. A warning never stops the work: the fronts print it
//! (text: standard error) and list it in their JSON (`warnings`, each with the `field` or flag
//! it is about). The rule lives in flexrig-rig ([`flexrig_rig::plausibility`]), where the test
//! bed's scenes apply it too.

pub use flexrig_rig::plausibility::{
    PLAUSIBLE_LENGTH_M, PLAUSIBLE_MASS_KG, PLAUSIBLE_SPEED_MPS, Warning, joint_speed, length, mass,
    speed,
};

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
        // 20 rad/s on a 1 m link: 20 m/s at the tip; 20°/s is 0.349066 rad/s
        let w = joint_speed("--speed", 20.0, 1.0).unwrap().message;
        assert!(w.contains("20 m/s") && w.contains("0.349066 rad/s"), "{w}");
        assert!(joint_speed("--speed", 2.0, 1.0).is_none());
    }
}
