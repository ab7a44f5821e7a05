//! Virtual sensors as on the test bed (paper Fig. 8): encoders on both axes, an accelerometer on
//! the operator block and one on the load, and the force sensor between the load and the dome
//! (the dome is massless here, so it reads the contact force). Sampled at a fixed rate,
//! independent of the step, by linear interpolation between step ends; the accelerations are
//! those of the step containing the sample (velocity change over the step).

use serde::Serialize;

/// One sample of every sensor.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SensorSample {
    /// Time \[s\].
    pub t: f64,
    /// Operator encoder: pendulum angle from the vertical, positive towards the robot \[rad\].
    pub operator_angle_rad: f64,
    /// Robot encoder: angle of the robot axis \[rad\] (CL: the shaft the link is clamped to, 0
    /// without a drive).
    pub robot_angle_rad: f64,
    /// Lateral tip deflection of the link (CJ: L sin θ; CL: beam tip v) \[m\].
    pub link_tip_deflection_m: f64,
    /// Operator block accelerometer, along the strike direction (world y) [m/s²].
    pub operator_accel_mps2: f64,
    /// Load accelerometer, along the strike direction (world y) [m/s²].
    pub load_accel_mps2: f64,
    /// Force sensor between load and dome \[N\].
    pub force_n: f64,
    /// Contact indentation δ \[m\] (linear between step ends like the force; 0 outside contact).
    pub indentation_m: f64,
}

/// The state of the measured quantities at a step end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// Time \[s\].
    pub t: f64,
    /// Operator angle \[rad\].
    pub operator_angle: f64,
    /// Robot axis angle \[rad\].
    pub robot_angle: f64,
    /// Link tip deflection \[m\].
    pub tip_deflection: f64,
    /// Operator block velocity along y [m/s].
    pub operator_velocity: f64,
    /// Load velocity along y [m/s].
    pub load_velocity: f64,
    /// Contact force \[N\].
    pub force: f64,
    /// Contact indentation \[m\] (0 outside contact).
    pub indentation: f64,
}

/// Samples the readings at `rate` Hz.
#[derive(Debug, Clone)]
pub struct Sampler {
    period: f64,
    next_index: u64,
    samples: Vec<SensorSample>,
}

impl Sampler {
    /// A sampler at `rate_hz` > 0 starting at t = 0.
    pub fn new(rate_hz: f64) -> Self {
        Sampler {
            period: 1.0 / rate_hz,
            next_index: 0,
            samples: Vec::new(),
        }
    }

    /// Records every sample time in (a.t, b.t] (and t = 0 at the first call).
    pub fn record_step(&mut self, a: &Reading, b: &Reading) {
        let dt = b.t - a.t;
        if !(dt > 0.0) {
            return;
        }
        let operator_accel = (b.operator_velocity - a.operator_velocity) / dt;
        let load_accel = (b.load_velocity - a.load_velocity) / dt;
        loop {
            let t = self.next_index as f64 * self.period;
            if t > b.t {
                break;
            }
            self.next_index += 1;
            if t < a.t {
                continue;
            }
            let w = (t - a.t) / dt;
            let lerp = |x: f64, y: f64| x + (y - x) * w;
            self.samples.push(SensorSample {
                t,
                operator_angle_rad: lerp(a.operator_angle, b.operator_angle),
                robot_angle_rad: lerp(a.robot_angle, b.robot_angle),
                link_tip_deflection_m: lerp(a.tip_deflection, b.tip_deflection),
                operator_accel_mps2: operator_accel,
                load_accel_mps2: load_accel,
                force_n: lerp(a.force, b.force),
                indentation_m: lerp(a.indentation, b.indentation),
            });
        }
    }

    /// Records every sample time in (`t_a`, `t_b`] (and t = 0 at the first call) from `at`, the
    /// exact state at a time (e.g. an integrator's dense output): no interpolation between the
    /// step's ends.
    pub fn record_exact(&mut self, t_a: f64, t_b: f64, mut at: impl FnMut(f64) -> SensorSample) {
        if !(t_b > t_a) {
            return;
        }
        loop {
            let t = self.next_index as f64 * self.period;
            if t > t_b {
                break;
            }
            self.next_index += 1;
            if t < t_a {
                continue;
            }
            self.samples.push(at(t));
        }
    }

    /// The samples so far.
    pub fn samples(&self) -> &[SensorSample] {
        &self.samples
    }

    /// Takes the samples.
    pub fn into_samples(self) -> Vec<SensorSample> {
        self.samples
    }
}
