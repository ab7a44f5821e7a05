//! Flags shared by the FE impact commands (`eta`, `eta-map`, `eta-rotor`): the joint, the
//! contact's damping, log ranges, and impact errors named by flag.

use clap::{Args, ValueEnum};
use flexrig::Error;
use flexrig::eta::{DampingSpec, Joint};
use flexrig::fronts::{DampingModel, JointKind, damping_spec};
pub use flexrig::fronts::{as_flag, impact_as_flag, parse_range};

/// The joint during the impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum JointArg {
    /// Driven at constant speed: the robot at rest in the joint's frame, struck at v0.
    Held,
    /// A free hub with the rotor inertia --rotor-inertia; the robot moves at v0 into the head.
    FreeHub,
}

/// Damping added to the Hertz contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum DampingArg {
    /// The paper's elastic contact f = k_c δⁿ.
    None,
    /// Hunt–Crossley, f = k_c δⁿ (1 + χ δ̇), χ = 3(1 − e)/(2 v0) (--restitution).
    HuntCrossley,
    /// Lankarani–Nikravesh, χ = 3(1 − e²)/(4 v0) (--restitution).
    LankaraniNikravesh,
    /// ADAMS IMPACT: damping ramped from 0 at first touch to --c-max at --depth.
    AdamsImpact,
}

/// The contact's damping flags (shared by `flexrig eta` and `flexrig eta-map`).
#[derive(Debug, Args)]
pub struct DampingArgs {
    /// Damping added to the Hertz contact (the lumped columns then come from the lumped model
    /// integrated with the same law).
    #[arg(long, value_enum, default_value = "none")]
    pub damping: DampingArg,
    /// Coefficient of restitution e in [0, 1] (with --damping hunt-crossley or
    /// lankarani-nikravesh).
    #[arg(long, value_name = "E")]
    pub restitution: Option<f64>,
    /// Largest damping coefficient c_max [N·s/m] (with --damping adams-impact): from 0 to 1000
    /// times the contact's critical damping 2√(k_lin μ) of every case (3.75e5 for the Fig. 6
    /// table); a contact damped further sticks, and is refused.
    #[arg(long, value_name = "N_S_PER_M")]
    pub c_max: Option<f64>,
    /// Indentation at which the damping reaches --c-max, m in [1e-9, 1] (with --damping
    /// adams-impact).
    #[arg(long, value_name = "M")]
    pub depth: Option<f64>,
}

impl DampingArgs {
    /// The damping the flags ask for ([`flexrig::fronts::damping_spec`]); a missing, stray or
    /// out-of-range flag is named.
    pub fn spec(&self) -> Result<DampingSpec, Error> {
        let model = match self.damping {
            DampingArg::None => DampingModel::None,
            DampingArg::HuntCrossley => DampingModel::HuntCrossley,
            DampingArg::LankaraniNikravesh => DampingModel::LankaraniNikravesh,
            DampingArg::AdamsImpact => DampingModel::AdamsImpact,
        };
        damping_spec(model, self.restitution, self.c_max, self.depth)
    }
}

/// The joint from --joint and --rotor-inertia ([`flexrig::fronts::joint`]).
pub fn joint_from_args(joint: JointArg, rotor_inertia: Option<f64>) -> Result<Joint, Error> {
    let kind = match joint {
        JointArg::Held => JointKind::Held,
        JointArg::FreeHub => JointKind::FreeHub,
    };
    flexrig::fronts::joint(kind, rotor_inertia)
}
