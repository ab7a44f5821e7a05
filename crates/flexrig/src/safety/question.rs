//! The question a safety verdict answers and each method's answer to it: the design, the body
//! region and the speed asked about ([`SafetyInput`]), the methods ([`SafetyMethod`]), and one
//! method's permissible speed and verdict ([`MethodResult`]). The methods themselves are in
//! [`crate::safety::point`], the overall verdict over them in [`crate::safety::overall`].

use flexrig_safety::{ContactAreaModel, ContactKind, GoverningLimit};
use serde::{Deserialize, Serialize};

use crate::safety::simulation::{FeLink, SimulationSettings};

/// Which permissible-speed method to evaluate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SafetyMethod {
    /// The standard's formula (Annex A, Eq. A.1–A.6).
    Standard,
    /// The paper's lumped energy balance (Eq. 13 generalised).
    Energy,
    /// The time-integrated lumped impact with a root search on the speed.
    Simulation,
}

/// The effective robot mass at the contact for the energy and simulation methods.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RobotEffectiveMass {
    /// m_eff \[kg\] as given (`--m-eff`).
    Given(f64),
    /// m_eff = m_e + γ m_r/3 (paper Eq. 5): γ ∈ (0, 1] (`--gamma`), link mass m_r \[kg\]
    /// (`--m-r`), end mass m_e \[kg\] (`--m-e`).
    Prb {
        /// PRB characteristic radius γ.
        gamma: f64,
        /// Link mass m_r \[kg\].
        m_r: f64,
        /// End mass (payload) m_e \[kg\].
        m_e: f64,
    },
}

/// The skin's contact law for the energy and simulation methods.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactLaw {
    /// The body region's own linear spring: n = 1, k_c = K of Table A.3 (the standard's model).
    BodySpring,
    /// f = k_c δ_c^n: k_c \[N/m^n\] (`--k-c`), n (`--n`).
    Hertz {
        /// Stiffness k_c \[N/m^n\].
        k_c: f64,
        /// Exponent n.
        n: f64,
    },
    /// A material of the bundled materials file (`--material`, e.g. `skinned_aluminium`).
    Material(String),
}

/// One permissible-speed question, SI units throughout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SafetyInput {
    /// Body region key of the body model (`--region`, e.g. `chest`).
    pub region: String,
    /// A specific area of the region for the pressure limit (`--area`, e.g. `Sternum`); absent:
    /// the region's most sensitive area (lowest pressure limit).
    pub area: Option<String>,
    /// Transient or quasi-static (clamping) contact (`--contact`).
    pub contact: ContactKind,
    /// Effective robot mass for the energy and simulation methods (absent: the standard's m_R).
    pub m_eff: Option<RobotEffectiveMass>,
    /// Link (or joint) lateral stiffness k_δ \[N/m\] (`--k-delta`); absent: a rigid link.
    pub k_delta: Option<f64>,
    /// The skin's contact law (`--k-c --n`, `--material`; default the body spring).
    pub law: ContactLaw,
    /// The contact-area model for pressure (`--area-model`, `--radius`, `--contact-area`);
    /// absent: the Hertz sphere of the bundled dome with `--material`, else pressure not assessed.
    pub area_model: Option<ContactAreaModel>,
    /// The robot's total moving mass M \[kg\] (`--moving-mass`) for m_R = M/2 + m_L (Eq. A.4);
    /// absent: m_R = m_eff.
    pub moving_mass: Option<f64>,
    /// Payload m_L \[kg\] (`--payload`, default 0).
    pub payload: f64,
    /// Relative speed to judge \[m/s\] (`--speed`); absent: no verdict.
    pub speed: Option<f64>,
    /// Methods to evaluate (`--method`).
    pub methods: Vec<SafetyMethod>,
    /// The simulation method's finite-element link (`--link cj|cl`); absent: the CJ for γ = 1,
    /// the CL for γ = 2/3.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub link: Option<FeLink>,
    /// The simulation method's joint, link length and tolerances (`--joint`,
    /// `--rotor-inertia`, `--length`, `--tol`, `--cj-rtol`, `--root-rtol`); absent:
    /// [`SimulationSettings::DEFAULT`] (held joint).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub simulation: Option<SimulationSettings>,
    /// A scene as the design (`--scene`: a bundled scene's name or a scene file's path). A
    /// driven scene ([`crate::safety::scene`]): the link, the skin's law and the contact kind
    /// come from the scene (a wall: quasi-static; a free head or a neck: transient), and the
    /// simulation method searches the scene's commanded speed. A test-bed scene
    /// ([`crate::safety::test_bed`]): the robot link and the operator block's law, transient
    /// contact, and the simulation method searches the operator's speed at contact through its
    /// release angle. Absent: the design of the other fields.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene: Option<String>,
}

/// A speed that may be unbounded (serialises as a number or the word `"unlimited"`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Speed {
    /// A finite speed [m/s].
    Finite(f64),
    /// No limit: the quantity never reaches its limit.
    Unlimited(Unbounded),
}

/// The word of an unbounded speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Unbounded {
    /// `"unlimited"`.
    Unlimited,
}

impl Speed {
    /// A finite speed, or unlimited for +∞ (or NaN).
    pub fn from_f64(v: f64) -> Self {
        if v.is_finite() {
            Speed::Finite(v)
        } else {
            Speed::Unlimited(Unbounded::Unlimited)
        }
    }

    /// The speed [m/s] (+∞ when unlimited).
    pub fn value(&self) -> f64 {
        match self {
            Speed::Finite(v) => *v,
            Speed::Unlimited(_) => f64::INFINITY,
        }
    }
}

/// Pass/fail at the requested speed by one method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SpeedVerdict {
    /// The judged relative speed [m/s].
    pub speed_mps: f64,
    /// True when the speed does not exceed the permissible speed and no predicted peak (force or
    /// pressure) exceeds its limit.
    pub pass: bool,
    /// Predicted peak force \[N\].
    pub peak_force_n: f64,
    /// Predicted peak mean pressure \[Pa\] (absent without an area model).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_pressure_pa: Option<f64>,
    /// 1 − peak force / force limit (negative when exceeded).
    pub force_margin: f64,
    /// 1 − peak pressure / pressure limit (absent without a pressure assessment).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub pressure_margin: Option<f64>,
    /// The energy transferred to the body at the peak force \[J\]: what the method's contact law
    /// stores there, k δ^{n+1}/(n+1) at δ = (F/k)^{1/n} (the standard: its body spring,
    /// F²/(2K) = ½ μ v², Eq. A.1–A.2; the energy and simulation methods: the skin's Hertz law,
    /// the link's own share left out).
    pub energy_transferred_j: f64,
    /// The simulation method: the contact that holds the peak at this speed, its time, and how
    /// many contacts there were until the bodies parted for good (absent for the formulas).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub governing_contact: Option<crate::safety::simulation::SimulatedPeak>,
}

/// The permissible speed by one method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MethodResult {
    /// The method.
    pub method: SafetyMethod,
    /// Robot mass the method uses \[kg\]: m_R for the standard (a driven CL scene: the rigid
    /// robot at the tip, m_e + m_r/3 + J_m N²/L²), m_eff for the energy method, and for the
    /// simulation of a link design the link's rigid-body mass at the tip, m_e + m_r/3 (+ J_R/L²
    /// with a free hub; a held joint moves the link alone).
    pub robot_mass_kg: f64,
    /// Human mass the method uses \[kg\]: the body region's m_H (a driven scene's struck head
    /// takes it too), the test bed's operator pendulum J/l² for its simulation; absent for a
    /// clamped body (m_H = ∞).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub human_mass_kg: Option<f64>,
    /// Reduced mass μ \[kg\].
    pub reduced_mass_kg: f64,
    /// v_max = min(by force, by pressure) [m/s].
    pub v_max_mps: Speed,
    /// The speed at which the peak force reaches the force limit [m/s].
    pub by_force_mps: Speed,
    /// The speed at which the peak pressure reaches the pressure limit [m/s] (absent when the
    /// pressure is not assessed by this method).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub by_pressure_mps: Option<Speed>,
    /// The limit that sets v_max.
    pub governing: GoverningLimit,
    /// Whether this method judged the pressure: false without a contact geometry (no area
    /// model, or the standard's formula without a fixed area); then only the force is judged
    /// and the text says "pressure not assessed" in place of a governing limit.
    pub pressure_assessed: bool,
    /// The energy transferred to the body at v_max \[J\] (the method's contact law at the peak
    /// force there: the force limit, or the force at which the pressure limit is reached;
    /// absent when v_max is unlimited).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_transferred_at_v_max_j: Option<f64>,
    /// The verdict at the requested speed (absent without `--speed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdict: Option<SpeedVerdict>,
    /// The simulation method of a link design: the contact that reaches the limit at the
    /// permissible speed (its number, 1 = the first, and time) and the contacts of that impact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub governing_contact: Option<crate::safety::simulation::SimulatedPeak>,
}
