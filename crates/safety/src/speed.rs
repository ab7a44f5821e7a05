//! The result types shared by both permissible-speed methods: the speed each limit allows, which
//! one governs, and the verdict at a given speed.

use serde::Serialize;

use crate::body_model::Limits;

/// Which limit sets the permissible speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum GoverningLimit {
    /// The force limit (Table A.2, maximum permissible force).
    Force,
    /// The pressure limit (Table A.2, maximum permissible pressure of the body area).
    Pressure,
}

/// The largest relative speed at which a contact stays within its limits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PermissibleSpeed {
    /// v_max = min(by_force, by_pressure) [m/s].
    pub v_max: f64,
    /// Speed at which the peak force reaches the force limit [m/s].
    pub by_force: f64,
    /// Speed at which the peak pressure reaches the pressure limit [m/s] (`None` without a
    /// pressure limit; +∞ when the pressure never reaches it; 0 when it is exceeded at any force).
    pub by_pressure: Option<f64>,
    /// The limit that sets v_max (force on a tie).
    pub governing: GoverningLimit,
    /// Reduced mass μ of the contact \[kg\].
    pub reduced_mass: f64,
    /// The limits applied.
    pub limits: Limits,
}

impl PermissibleSpeed {
    /// Combines the speed allowed by each limit.
    pub fn from_parts(
        by_force: f64,
        by_pressure: Option<f64>,
        reduced_mass: f64,
        limits: Limits,
    ) -> Self {
        let (v_max, governing) = match by_pressure {
            Some(vp) if vp < by_force => (vp, GoverningLimit::Pressure),
            _ => (by_force, GoverningLimit::Force),
        };
        PermissibleSpeed {
            v_max,
            by_force,
            by_pressure,
            governing,
            reduced_mass,
            limits,
        }
    }
}

/// Pass or fail of a contact at one speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Verdict {
    /// The relative speed judged [m/s].
    pub speed: f64,
    /// True when the speed does not exceed the permissible speed and no predicted peak (force
    /// or pressure) exceeds its limit.
    pub pass: bool,
    /// v_max − v [m/s] (negative on failure).
    pub speed_margin: f64,
    /// Predicted peak force at this speed \[N\].
    pub peak_force: f64,
    /// Predicted peak mean pressure at this speed \[Pa\] (if a pressure limit applies).
    pub peak_pressure: Option<f64>,
    /// 1 − peak force / force limit (negative when exceeded).
    pub force_margin: f64,
    /// 1 − peak pressure / pressure limit (negative when exceeded).
    pub pressure_margin: Option<f64>,
    /// The limit that sets the permissible speed.
    pub governing: GoverningLimit,
    /// The permissible speed itself.
    pub permissible: PermissibleSpeed,
}

impl Verdict {
    /// Builds the verdict from the permissible speed and the peaks predicted at `speed`.
    pub fn new(
        speed: f64,
        permissible: PermissibleSpeed,
        peak_force: f64,
        peak_pressure: Option<f64>,
    ) -> Self {
        let limits = permissible.limits;
        // a verdict never passes a peak it shows above its limit, whatever the permissible speed
        let force_ok = peak_force <= limits.force;
        let pressure_ok = match (peak_pressure, limits.pressure) {
            (Some(p), Some(lim)) => p <= lim,
            _ => true,
        };
        Verdict {
            speed,
            pass: speed <= permissible.v_max && force_ok && pressure_ok,
            speed_margin: permissible.v_max - speed,
            peak_force,
            peak_pressure,
            force_margin: 1.0 - peak_force / limits.force,
            pressure_margin: match (peak_pressure, limits.pressure) {
                (Some(p), Some(lim)) => Some(1.0 - p / lim),
                _ => None,
            },
            governing: permissible.governing,
            permissible,
        }
    }
}
