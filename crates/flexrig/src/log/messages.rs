//! The log's own messages beside Foxglove's (the force sensor, accelerometers, the contact's and
//! the energy's state, the drive's joint motion, motor torque and link load) and the schema of
//! the severity record, as the recorder ([`crate::log::mcap`]) writes them.

use foxglove::Encode;
use foxglove::messages::Timestamp;

/// Contact force sensor between load and dome.
#[derive(Debug, Clone, Encode)]
pub struct ForceSensor {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Force \[N\].
    pub force_n: f64,
}

/// One accelerometer, along the strike direction (world y).
#[derive(Debug, Clone, Encode)]
pub struct Accelerometer {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Acceleration [m/s²].
    pub accel_mps2: f64,
}

/// The contact state at a step end.
#[derive(Debug, Clone, Encode)]
pub struct ContactState {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Indentation δ \[m\].
    pub indentation_m: f64,
    /// Indentation rate δ̇ [m/s].
    pub rate_mps: f64,
    /// Contact force \[N\].
    pub force_n: f64,
    /// Indentation δ in millimetres (the same as `indentation_m`, for the plots) \[mm\].
    pub indentation_mm: f64,
}

/// Mechanical energy.
#[derive(Debug, Clone, Encode)]
pub struct EnergyState {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Total mechanical energy \[J\].
    pub total_j: f64,
}

/// The motion of a driven joint (the motor side's, the command's or the link's; the
/// `/drive/*` channels of a run with a motor, on the test bed or driven).
#[derive(Debug, Clone, Encode)]
pub struct JointMotion {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// Joint angle (the motor's, after the gear) \[rad\].
    pub angle_rad: f64,
    /// Joint speed [rad/s].
    pub speed_rad_s: f64,
}

/// The motor's torque.
#[derive(Debug, Clone, Encode)]
pub struct MotorTorque {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// At the joint, τ_j = N τ_m [N·m].
    pub joint_nm: f64,
    /// At the motor shaft, τ_m [N·m].
    pub motor_nm: f64,
}

/// What the link puts on the drive's joint and how far it is bent.
#[derive(Debug, Clone, Encode)]
pub struct LinkLoad {
    /// Simulation time.
    pub timestamp: Timestamp,
    /// The link's elastic moment on the motor's hub [N·m] (CJ: the torsion spring's
    /// k_θr (φ_m − φ_l); CL: the beam's root moment).
    pub moment_nm: f64,
    /// Deflection of the link's tip from the hub's line \[m\], positive towards the operator.
    pub deflection_m: f64,
    /// The same deflection in millimetres \[mm\], for the plot.
    pub deflection_mm: f64,
}

/// Schema name of the `/severity` channel.
pub const SEVERITY_SCHEMA_NAME: &str = "flexrig.Severity";

/// JSON Schema of the `/severity` message: the run's severity (see `docs/safety.md`).
pub const SEVERITY_JSON_SCHEMA: &str = r#"{
  "title": "flexrig.Severity",
  "description": "Severity of a run: peak force, peak pressure under each contact-area model, energy transferred, peak struck-body acceleration, HIC15 and HIC36 (SI units; HIC without unit)",
  "type": "object",
  "properties": {
    "peak_force_n": {"type": "number"},
    "time_of_peak_force_s": {"type": "number"},
    "pressure": {"type": "array", "items": {"type": "object", "properties": {
      "area_model": {"type": "object"},
      "mean_pa": {"type": "number"},
      "peak_pa": {"type": "number"},
      "time_s": {"type": "number"}}}},
    "energy_transferred_j": {"type": "number"},
    "contact_work_j": {"type": "number"},
    "peak_acceleration_mps2": {"type": "number"},
    "peak_acceleration_g": {"type": "number"},
    "hic15": {"type": "object", "properties": {"hic": {"type": "number"}, "t1_s": {"type": "number"}, "t2_s": {"type": "number"}, "mean_acceleration_g": {"type": "number"}}},
    "hic36": {"type": "object", "properties": {"hic": {"type": "number"}, "t1_s": {"type": "number"}, "t2_s": {"type": "number"}, "mean_acceleration_g": {"type": "number"}}},
    "hic_method": {"type": "string"},
    "struck_body": {"type": "string"}
  }
}"#;
