//! Flags shared by the FE impact commands (`eta`, `eta-map`, `eta-rotor`): the joint, the
//! contact's damping, log ranges, and impact errors named by flag.

use clap::{Args, ValueEnum};
use flexrig::Error;
use flexrig::fe::eta::{DampingSpec, Joint};
use flexrig::fronts::{DampingModel, JointKind, damping_spec};
pub use flexrig::fronts::{as_flag, impact_as_flag, parse_range};
use flexrig::lumped::fig6::{Fig6Design, Fig6Grid};

/// The design held fixed across the cases (`fig6`, `eta`, `eta-map`, `eta-rotor`); the
/// defaults are the paper's (§V).
#[derive(Debug, Args)]
pub struct DesignArgs {
    /// Robot link mass m_r [kg], in [1e-3, 1e4].
    #[arg(long = "m-r", value_name = "KG", default_value_t = Fig6Design::PAPER.m_r)]
    pub m_r: f64,
    /// Contact stiffness k_c [N/mⁿ] of the Hertz law f = k_c δⁿ, in [1, 1e13].
    #[arg(long = "k-c", value_name = "N_PER_MN", default_value_t = Fig6Design::PAPER.k_c)]
    pub k_c: f64,
    /// Approach speed v0 [m/s], in [1e-3, 100].
    #[arg(long, value_name = "M_PER_S", default_value_t = Fig6Design::PAPER.v0)]
    pub v0: f64,
}

impl DesignArgs {
    /// The library's design; its ranges are checked by the library (errors name the flag).
    pub fn design(&self) -> Fig6Design {
        Fig6Design {
            m_r: self.m_r,
            k_c: self.k_c,
            v0: self.v0,
        }
    }
}

/// The cases of a Fig. 6 study: every combination of the values given (`fig6`, `eta`,
/// `eta-rotor`); the defaults are the paper's eight cases.
#[derive(Debug, Args)]
pub struct CaseArgs {
    /// Human masses m_h [kg], comma-separated (1 to 4 values, each in [1e-3, 1e6]).
    #[arg(
        long = "m-h",
        value_name = "KG,...",
        value_delimiter = ',',
        default_value = "4,1000"
    )]
    pub m_h: Vec<f64>,
    /// Link lateral stiffnesses k_δ [N/m], comma-separated (1 to 4 values, each in
    /// [1e-3, 1e13]).
    #[arg(
        long = "k-delta",
        value_name = "N_PER_M,...",
        value_delimiter = ',',
        default_value = "1e8,200"
    )]
    pub k_delta: Vec<f64>,
    /// Payloads m_e [kg], comma-separated (1 to 4 values, each in [1e-6, 1e4]).
    #[arg(
        long = "m-e",
        value_name = "KG,...",
        value_delimiter = ',',
        default_value = "0.1,10"
    )]
    pub m_e: Vec<f64>,
}

impl CaseArgs {
    /// The library's grid; its ranges are checked by the library (errors name the flag).
    pub fn grid(&self) -> Fig6Grid {
        Fig6Grid {
            m_h: self.m_h.clone(),
            k_delta: self.k_delta.clone(),
            m_e: self.m_e.clone(),
        }
    }
}

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
    /// Indentation [m] at which the damping reaches --c-max, in [1e-9, 1] (with --damping
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
