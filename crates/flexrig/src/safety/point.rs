//! The permissible speed of a design near a body region (ISO/TS 15066:2016, power and force
//! limiting), side by side by three methods:
//!
//! - **standard**: the standard's formula, v_max = F_max/√(μK), p_max A/√(μK) (Annex A,
//!   Eq. A.1–A.6) with m_R = M/2 + m_L (Eq. A.4) and Table A.3's K and m_H
//!   ([`flexrig_safety::StandardContact`]);
//! - **energy**: the paper's lumped energy balance ½μv² = U(f_max) (Eq. 13 generalised to the
//!   fitted Hertz law f = k_c δ_c^n, Eq. 4, in series with the link stiffness k_δ, Eq. 6–9;
//!   [`flexrig_safety::EnergyContact`]);
//! - **simulation**: the speed at which the finite-element impact the safe-speed maps use
//!   reaches the limit ([`crate::safety::simulation::FeImpact`]: the CJ as a rigid link on its torsion
//!   spring by DOP853, the CL as the Euler–Bernoulli beam by its modes and the exact modal
//!   integrator; held joint or free hub), by a bracket around the energy method's speed and the
//!   Illinois root search on ln v to the settings' `root_rtol` (default 1e-6, below the 1e-4
//!   the result is quoted to). The design is the link of mass m_r with payload m_e (`--m-r`,
//!   `--m-e`) and stiffness k_δ (absent: rigid, [`FE_RIGID_LINK_STIFFNESS`]).
//!
//! Transient contact with the skull, forehead or face is refused with
//! [`flexrig_safety::SafetyError::ContactNotPermitted`] quoting the clause of the body model
//! (exit code 2).
//!
//! **JSON.** [`SafetyReport`] serialises without null, NaN or ∞: optional values are absent keys,
//! and a speed that no limit bounds (e.g. the pressure of a linear contact whose Hertz-area
//! pressure never reaches the limit) is the word `"unlimited"` ([`Speed::Unlimited`]).

use flexrig_contact::{Hertz, Materials};
use flexrig_safety::{
    BodyArea, BodyRegion, EnergyContact, Limits, LinkStiffness, PermissibleSpeed, RobotMass,
    StandardContact, Verdict,
};
pub use flexrig_safety::{BodyModel, ContactAreaModel, ContactKind, GoverningLimit};
use serde::{Deserialize, Serialize};

use crate::Error;
use crate::safety::scene::SafetyDesignScene;

pub use crate::safety::simulation::{
    CLAMPED_HUMAN_MASS, FE_RIGID_LINK_STIFFNESS, FeImpact, FeLink, MapJoint, RootStep,
    SimulationSettings,
};

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
    fn from_f64(v: f64) -> Self {
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
    /// Robot mass the method uses \[kg\] (m_R for the standard, m_eff otherwise).
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
    /// The verdict at the requested speed (absent without `--speed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdict: Option<SpeedVerdict>,
    /// The simulation method of a link design: the contact that reaches the limit at the
    /// permissible speed (its number, 1 = the first, and time) and the contacts of that impact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub governing_contact: Option<crate::safety::simulation::SimulatedPeak>,
}

/// The answer: the limits applied and each method's permissible speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SafetyReport {
    /// Body region key.
    pub region: String,
    /// Body region name.
    pub region_name: String,
    /// The specific area whose pressure limit applies.
    pub area: String,
    /// Contact kind.
    pub contact: ContactKind,
    /// Human mass m_H \[kg\] (absent for quasi-static contact: a clamped body, m_H = ∞).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub human_mass_kg: Option<f64>,
    /// Body spring K of Table A.3 \[N/m\].
    pub body_stiffness_n_per_m: f64,
    /// Force limit \[N\].
    pub force_limit_n: f64,
    /// Pressure limit of the area \[Pa\].
    pub pressure_limit_pa: f64,
    /// The contact-area model for pressure (absent: pressure not assessed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub area_model: Option<ContactAreaModel>,
    /// The skin's Hertz law used by the energy and simulation methods: k_c \[N/m^n\].
    pub k_c: f64,
    /// Its exponent n.
    pub n: f64,
    /// Link stiffness k_δ \[N/m\] (absent: rigid).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_delta_n_per_m: Option<f64>,
    /// One result per requested method, in the order asked.
    pub methods: Vec<MethodResult>,
    /// The driven scene's simulation (absent without `--scene` or the simulation method).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene: Option<crate::safety::simulation::SceneSimulation>,
}

fn bad(arg: &str, value: impl ToString, allowed: &str) -> Error {
    Error::InvalidArgument {
        arg: arg.into(),
        value: crate::shared::output::value_text(value),
        allowed: allowed.into(),
    }
}

fn positive(arg: &str, v: f64) -> Result<f64, Error> {
    if v.is_finite() && v > 0.0 && v <= 1e20 {
        Ok(v)
    } else {
        Err(bad(arg, v, "must be a finite number in (0, 1e20]"))
    }
}

/// Everything the methods share, validated.
struct Setup<'a> {
    region: &'a BodyRegion,
    area: &'a BodyArea,
    kind: ContactKind,
    limits: Limits,
    standard_robot_mass: f64,
    m_eff: f64,
    hertz: Hertz,
    link: LinkStiffness,
    area_model: Option<ContactAreaModel>,
}

fn setup<'a>(input: &SafetyInput, model: &'a BodyModel) -> Result<Setup<'a>, Error> {
    // an unknown name is the flag's fault: the error names it
    let named = |flag: &str, e: flexrig_safety::SafetyError| match e {
        flexrig_safety::SafetyError::Unknown { what, name, known } => Error::InvalidArgument {
            arg: flag.into(),
            value: flexrig_safety::quoted_name(&name),
            allowed: format!("a {what} of the body model: {known}"),
        },
        other => other.into(),
    };
    let region = model
        .region(&input.region)
        .map_err(|e| named("--region", e))?;
    let area = match &input.area {
        Some(name) => region.area(name).map_err(|e| named("--area", e))?,
        None => region.most_sensitive_area(),
    };
    let kind = input.contact;
    let mut limits = region.limits(Some(area), kind)?;
    let m_eff = match input.m_eff {
        Some(RobotEffectiveMass::Given(m)) => Some(positive("--m-eff", m)?),
        Some(RobotEffectiveMass::Prb { gamma, m_r, m_e }) => {
            if !(gamma > 0.0 && gamma <= 1.0) {
                return Err(bad("--gamma", gamma, "must lie in (0, 1]"));
            }
            let m_r = positive("--m-r", m_r)?;
            if !(m_e.is_finite() && m_e >= 0.0) {
                return Err(bad("--m-e", m_e, "must be a finite number ≥ 0"));
            }
            Some(m_e + gamma * m_r / 3.0)
        }
        None => None,
    };
    if !(input.payload.is_finite() && input.payload >= 0.0) {
        return Err(bad(
            "--payload",
            input.payload,
            "must be a finite number ≥ 0",
        ));
    }
    let standard_robot_mass = match (input.moving_mass, m_eff) {
        (Some(m), _) => RobotMass {
            total_moving_mass: positive("--moving-mass", m)?,
            payload: input.payload,
        }
        .effective()?,
        (None, Some(m)) => m,
        (None, None) => {
            return Err(bad(
                "--moving-mass",
                "(missing)",
                "give --moving-mass (and --payload), --m-eff, or --m-r --m-e --gamma",
            ));
        }
    };
    let m_eff = m_eff.unwrap_or(standard_robot_mass);
    let materials;
    let (hertz, material_radius) = match &input.law {
        ContactLaw::BodySpring => (Hertz::new(region.spring_constant(), 1.0)?, None),
        ContactLaw::Hertz { k_c, n } => {
            let k_c = positive("--k-c", *k_c)?;
            if !(*n > 0.0 && *n <= flexrig_contact::MAX_EXPONENT) {
                return Err(bad(
                    "--n",
                    n,
                    &format!("must lie in (0, {}]", flexrig_contact::MAX_EXPONENT),
                ));
            }
            (Hertz::new(k_c, *n)?, None)
        }
        ContactLaw::Material(name) => {
            materials = Materials::bundled()?;
            let m = materials
                .get(name)
                .map_err(|e| bad("--material", name, &e.to_string()))?;
            (m.hertz, Some(materials.dome_radius_m()))
        }
    };
    let link = match input.k_delta {
        Some(k) => LinkStiffness::Finite(positive("--k-delta", k)?),
        None => LinkStiffness::Rigid,
    };
    let area_model = input
        .area_model
        .or(material_radius.map(|r| ContactAreaModel::HertzSphere { radius_m: r }));
    if let Some(a) = &area_model {
        a.validate()
            .map_err(|e| bad("--area-model", format!("{a:?}"), &e.to_string()))?;
    }
    if area_model.is_none() {
        limits.pressure = None;
    }
    if let Some(v) = input.speed
        && !(v.is_finite() && (0.0..=1e3).contains(&v))
    {
        return Err(bad("--speed", v, "must lie in [0, 1000] m/s"));
    }
    if input.methods.is_empty() {
        return Err(bad(
            "--method",
            "(none)",
            "give at least one of standard, energy, simulation",
        ));
    }
    Ok(Setup {
        region,
        area,
        kind,
        limits,
        standard_robot_mass,
        m_eff,
        hertz,
        link,
        area_model,
    })
}

/// The body model of `--body-model FILE` (the bundled format, see
/// assets/safety/iso_ts_15066_2016.toml), or `None` for the bundled ISO/TS 15066:2016 table; an
/// unreadable file is a read error naming it, a bad table names the region and field.
pub fn load_body_model(path: Option<&std::path::Path>) -> Result<Option<BodyModel>, Error> {
    path.map(|p| {
        let text = crate::shared::output::read_text_bounded(
            p,
            MAX_BODY_MODEL_BYTES,
            "a body-model table is expected; the bundled one is about 10 kB",
        )
        .map_err(|e| match e {
            // a file that cannot be read is the flag's fault: the error names it
            Error::Read { path, source } => Error::InvalidArgument {
                arg: "--body-model".into(),
                value: path.display().to_string(),
                allowed: format!("a readable body-model file ({source})"),
            },
            other => other,
        })?;
        body_model_from_text(&text, &p.display().to_string())
    })
    .transpose()
}

/// Largest body-model file read, bytes (the bundled table is about 10 kB).
pub const MAX_BODY_MODEL_BYTES: u64 = 1 << 20;

/// The body model of the TOML `text` read from `file` (its name as the user gave it); an error
/// names `--body-model` and the file, then the region, field and line.
pub fn body_model_from_text(text: &str, file: &str) -> Result<BodyModel, Error> {
    BodyModel::from_toml_str(text).map_err(|e| {
        let why = e.to_string();
        Error::InvalidArgument {
            arg: "--body-model".into(),
            value: file.to_string(),
            allowed: flexrig_rig::format_message::plain(
                why.strip_prefix("body-model file: ").unwrap_or(&why),
            ),
        }
    })
}

/// The permissible speed of `input` by each requested method, with the ISO/TS 15066:2016 body
/// model, or `model` when given (a user's table).
pub fn safety(input: &SafetyInput, model: Option<&BodyModel>) -> Result<SafetyReport, Error> {
    safety_cancellable(input, model, &crate::CancelToken::new())
}

/// [`safety`], stopped between the simulation method's runs once `cancel` is set (an error of
/// kind [`crate::ErrorKind::Interrupted`], exit code 130).
pub fn safety_cancellable(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    cancel: &crate::CancelToken,
) -> Result<SafetyReport, Error> {
    let stop = cancel.flag();
    let stop: &std::sync::atomic::AtomicBool = &stop;
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    let scene = input
        .scene
        .as_deref()
        .map(crate::safety::scene::load_any)
        .transpose()?;
    let derived;
    let input = match &scene {
        Some(sc) => {
            derived = any_scene_input(input, sc)?;
            &derived
        }
        None => input,
    };
    let s = setup(input, model)?;
    let mut methods = Vec::with_capacity(input.methods.len());
    let mut scene_simulation = None;
    for &m in &input.methods {
        methods.push(match (m, &scene) {
            (SafetyMethod::Standard, _) => standard(&s, input.speed)?,
            (SafetyMethod::Energy, _) => energy(&s, input.speed)?,
            (SafetyMethod::Simulation, None) => simulation_traced(&s, input, None, stop)?,
            (SafetyMethod::Simulation, Some(SafetyDesignScene::Driven(sc))) => {
                let (m, sim) = scene_method(&s, input, sc, stop)?;
                scene_simulation = Some(sim);
                m
            }
            (SafetyMethod::Simulation, Some(SafetyDesignScene::TestBed(tb))) => {
                let (mut m, sim) = test_bed_method(&s, input, tb, stop)?;
                scene_simulation = Some(sim);
                // the test bed strikes its operator's pendulum, not the region's person
                m.human_mass_kg = Some(tb.operator_mass());
                m
            }
        });
        if let Some(last) = methods.last_mut()
            && last.human_mass_kg.is_none()
        {
            last.human_mass_kg = Some(s.region.human_mass(s.kind)).filter(|m| m.is_finite());
        }
    }
    Ok(SafetyReport {
        region: s.region.key().to_string(),
        region_name: s.region.name().to_string(),
        area: s.area.name().to_string(),
        contact: s.kind,
        human_mass_kg: Some(s.region.human_mass(s.kind)).filter(|m| m.is_finite()),
        body_stiffness_n_per_m: s.region.spring_constant(),
        force_limit_n: s.limits.force,
        pressure_limit_pa: s.region.pressure_limit(s.area, s.kind)?,
        area_model: s.area_model,
        k_c: s.hertz.k(),
        n: s.hertz.n(),
        k_delta_n_per_m: match s.link {
            LinkStiffness::Finite(k) => Some(k),
            LinkStiffness::Rigid => None,
        },
        methods,
        scene: scene_simulation,
    })
}

/// The input with the design of the driven scene `sc`: its link (m_eff = m_e + γ m_r/3 with
/// γ = 1 for the CJ and 2/3 for the CL, paper Eq. 5; k_δ; length), its skin's Hertz law, the
/// contact kind of its support, and the Hertz-sphere area of the paper's dome unless an area
/// model is given. The design flags are refused beside a scene (the scene is the design).
fn scene_input(
    input: &SafetyInput,
    sc: &crate::safety::scene::SafetyScene,
) -> Result<SafetyInput, Error> {
    let strike = &sc.scene.strike;
    let (gamma, link) = match strike.design {
        crate::driven::strike::StrikeDesign::Cj => {
            (crate::safety::simulation::GAMMA_CJ, FeLink::CompliantJoint)
        }
        crate::driven::strike::StrikeDesign::Cl => {
            (crate::safety::simulation::GAMMA_CL, FeLink::CompliantLink)
        }
    };
    let hertz = strike.person.contact;
    let area_model = match input.area_model {
        Some(a) => a,
        None => ContactAreaModel::HertzSphere {
            radius_m: crate::shared::severity::paper_dome_radius_m()?,
        },
    };
    let derived = SafetyInput {
        contact: sc.contact_kind(),
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma,
            m_r: strike.link.m_r,
            m_e: strike.link.m_e,
        }),
        k_delta: Some(strike.link.k_delta),
        law: ContactLaw::Hertz {
            k_c: hertz.k(),
            n: hertz.n(),
        },
        area_model: Some(area_model),
        link: Some(link),
        simulation: Some(SimulationSettings {
            length: strike.link.length,
            ..input.simulation.unwrap_or(SimulationSettings::DEFAULT)
        }),
        ..input.clone()
    };
    refuse_design_flags(input, &derived)?;
    Ok(derived)
}

/// The input with the design of the scene `sc`, driven ([`scene_input`]) or test bed
/// ([`test_bed_input`]).
fn any_scene_input(input: &SafetyInput, sc: &SafetyDesignScene) -> Result<SafetyInput, Error> {
    match sc {
        SafetyDesignScene::Driven(d) => scene_input(input, d),
        SafetyDesignScene::TestBed(tb) => test_bed_input(input, tb),
    }
}

/// The input with the design of the test-bed scene `tb`: its robot link (m_eff = m_e + γ m_r/3,
/// γ = 1 for the CJ and 2/3 for the CL, paper Eq. 5; k_δ of Eq. 1–2; length), the block's Hertz
/// law, transient contact (the operator's pendulum is free), and the Hertz-sphere area of the
/// scene's dome unless an area model is given.
fn test_bed_input(
    input: &SafetyInput,
    tb: &crate::safety::test_bed::TestBedScene,
) -> Result<SafetyInput, Error> {
    let (gamma, link) = match tb.design() {
        crate::driven::strike::StrikeDesign::Cj => {
            (crate::safety::simulation::GAMMA_CJ, FeLink::CompliantJoint)
        }
        crate::driven::strike::StrikeDesign::Cl => {
            (crate::safety::simulation::GAMMA_CL, FeLink::CompliantLink)
        }
    };
    let quantities = crate::testbed::link::of_scene(&tb.scene);
    let robot = &tb.scene.file.robot;
    let area_model = match input.area_model {
        Some(a) => a,
        None => ContactAreaModel::HertzSphere {
            radius_m: robot.dome_radius_m,
        },
    };
    let derived = SafetyInput {
        contact: ContactKind::Transient,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma,
            m_r: quantities.m_r_kg,
            m_e: robot.payload_kg,
        }),
        k_delta: Some(quantities.k_delta_n_per_m),
        law: ContactLaw::Hertz {
            k_c: tb.scene.hertz.k(),
            n: tb.scene.hertz.n(),
        },
        area_model: Some(area_model),
        link: Some(link),
        simulation: Some(SimulationSettings {
            length: robot.length_m,
            ..input.simulation.unwrap_or(SimulationSettings::DEFAULT)
        }),
        ..input.clone()
    };
    refuse_design_flags(input, &derived)?;
    Ok(derived)
}

/// Refuses a design value given beside a scene unless it is the scene's own (`derived`).
fn refuse_design_flags(input: &SafetyInput, derived: &SafetyInput) -> Result<(), Error> {
    // a design value given beside the scene must be the scene's own (a derived input passes)
    let given = [
        (
            "--m-eff",
            input.m_eff.is_some() && input.m_eff != derived.m_eff,
        ),
        (
            "--k-delta",
            input.k_delta.is_some() && input.k_delta != derived.k_delta,
        ),
        (
            "--k-c",
            input.law != ContactLaw::BodySpring && input.law != derived.law,
        ),
        ("--link", input.link.is_some() && input.link != derived.link),
    ];
    if let Some((flag, _)) = given.iter().find(|(_, g)| *g) {
        return Err(bad(
            flag,
            "(given with --scene)",
            "leave it out: the scene gives the link, its masses and stiffness and the skin's \
             contact law (edit the scene file to change them)",
        ));
    }
    Ok(())
}

/// `input` with its design filled in from its driven scene (see [`SafetyInput::scene`]), or
/// `input` itself without a scene: what the methods compute with, as a report lists it.
pub fn design_input(input: &SafetyInput) -> Result<SafetyInput, Error> {
    match &input.scene {
        Some(given) => any_scene_input(input, &crate::safety::scene::load_any(given)?),
        None => Ok(input.clone()),
    }
}

/// The simulation method on the driven scene `sc` ([`crate::safety::scene::simulate`]): the
/// searches start at the energy method's speeds; the verdict runs the scene at the judged speed.
fn scene_method(
    s: &Setup,
    input: &SafetyInput,
    sc: &crate::safety::scene::SafetyScene,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<(MethodResult, crate::safety::simulation::SceneSimulation), Error> {
    let settings = input.simulation.unwrap_or(SimulationSettings::DEFAULT);
    let contact = energy_contact(s)?;
    let guess = contact.permissible_speed(s.limits)?;
    let judged = judged_scene(sc, s);
    let sc = &judged;
    let sim = crate::safety::scene::simulate(
        sc,
        &s.limits,
        &contact,
        guess.by_force,
        guess.by_pressure,
        &settings,
        stop,
    )?;
    scene_method_result(s, input.speed, contact.reduced_mass(), sim, |v| {
        crate::safety::simulation::check_stop(stop)?;
        crate::safety::scene::peak_force(sc, v, &settings)
    })
}

/// The driven scene `sc` with the region's person: a free head or a head on a neck (transient
/// contact) takes the body region's mass m_H of the body model, so that the simulation judges
/// the same person as the standard and the energy method (a head against a wall is clamped:
/// the region's m_H is infinite and the scene's own mass is kept, ignored against the wall).
fn judged_scene(
    sc: &crate::safety::scene::SafetyScene,
    s: &Setup,
) -> crate::safety::scene::SafetyScene {
    let mut judged = sc.clone();
    let m_h = s.region.human_mass(s.kind);
    if s.kind == ContactKind::Transient && m_h.is_finite() {
        judged.scene.strike.person.m_h = m_h;
    }
    judged
}

/// The simulation method on the test-bed scene `tb` ([`crate::safety::test_bed::simulate`]):
/// the searches start at the energy method's speeds for the operator's pendulum (the struck
/// mass J/l² in place of the region's m_H, and the link as a free mass: the contact is short
/// against the link's own period, so its spring hardly acts); the verdict runs the scene at the
/// judged speed.
fn test_bed_method(
    s: &Setup,
    input: &SafetyInput,
    tb: &crate::safety::test_bed::TestBedScene,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<(MethodResult, crate::safety::simulation::SceneSimulation), Error> {
    let settings = input.simulation.unwrap_or(SimulationSettings::DEFAULT);
    let contact = EnergyContact::new(
        tb.operator_mass(),
        s.m_eff,
        s.hertz,
        LinkStiffness::Rigid,
        s.area_model,
    )?;
    let guess = contact.permissible_speed(s.limits)?;
    let sim = crate::safety::test_bed::simulate(
        tb,
        &s.limits,
        &contact,
        guess.by_force,
        guess.by_pressure,
        &settings,
        stop,
    )?;
    scene_method_result(s, input.speed, contact.reduced_mass(), sim, |v| {
        crate::safety::simulation::check_stop(stop)?;
        tb.peak_force(v)
    })
}

/// The simulation method's result on a scene (driven or test bed) from its searches `sim`
/// (reduced mass `reduced_mass` \[kg\] of the energy contact): the permissible speed, and the
/// verdict at `speed` \[m/s\] with the scene's peak force there from `peak_at`.
fn scene_method_result(
    s: &Setup,
    speed: Option<f64>,
    reduced_mass: f64,
    sim: crate::safety::simulation::SceneSimulation,
    peak_at: impl FnOnce(f64) -> Result<f64, Error>,
) -> Result<(MethodResult, crate::safety::simulation::SceneSimulation), Error> {
    let p = PermissibleSpeed::from_parts(
        sim.by_force_mps,
        sim.by_pressure_mps,
        reduced_mass,
        s.limits,
    );
    let verdict = match speed {
        Some(v) if v > 0.0 => {
            let force = peak_at(v)?;
            Some(Verdict::new(
                v,
                p,
                force,
                s.limits.pressure.and(pressure_at_force(s, force)),
            ))
        }
        Some(v) => Some(Verdict::new(v, p, 0.0, s.limits.pressure.map(|_| 0.0))),
        None => None,
    };
    Ok((
        from_permissible(SafetyMethod::Simulation, s.m_eff, &p, verdict),
        sim,
    ))
}

fn from_permissible(
    method: SafetyMethod,
    robot_mass: f64,
    p: &PermissibleSpeed,
    verdict: Option<Verdict>,
) -> MethodResult {
    MethodResult {
        method,
        robot_mass_kg: robot_mass,
        human_mass_kg: None,
        reduced_mass_kg: p.reduced_mass,
        v_max_mps: Speed::from_f64(p.v_max),
        by_force_mps: Speed::from_f64(p.by_force),
        by_pressure_mps: p.by_pressure.map(Speed::from_f64),
        governing: p.governing,
        verdict: verdict.map(|v| SpeedVerdict {
            speed_mps: v.speed,
            pass: v.pass,
            peak_force_n: v.peak_force,
            peak_pressure_pa: v.peak_pressure,
            force_margin: v.force_margin,
            pressure_margin: v.pressure_margin,
            governing_contact: None,
        }),
        governing_contact: None,
    }
}

/// The standard's formula; its pressure check needs a fixed area (Eq. A.6 has no area law), so a
/// Hertz-sphere or thin-layer model leaves the standard's pressure unassessed.
fn standard(s: &Setup, speed: Option<f64>) -> Result<MethodResult, Error> {
    let area = match s.area_model {
        Some(ContactAreaModel::Fixed { area_m2 }) if s.limits.pressure.is_some() => {
            Some((s.area, area_m2))
        }
        _ => None,
    };
    let contact = StandardContact {
        region: s.region,
        area,
        robot_mass: s.standard_robot_mass,
        kind: s.kind,
    };
    let p = contact.permissible_speed()?;
    let verdict = speed.map(|v| contact.verdict(v)).transpose()?;
    Ok(from_permissible(
        SafetyMethod::Standard,
        s.standard_robot_mass,
        &p,
        verdict,
    ))
}

fn energy_contact(s: &Setup) -> Result<EnergyContact, Error> {
    Ok(EnergyContact::for_region(
        s.region,
        s.kind,
        s.m_eff,
        s.hertz,
        s.link,
        s.area_model,
    )?)
}

fn energy(s: &Setup, speed: Option<f64>) -> Result<MethodResult, Error> {
    let contact = energy_contact(s)?;
    let p = contact.permissible_speed(s.limits)?;
    let verdict = speed.map(|v| contact.verdict(v, s.limits)).transpose()?;
    Ok(from_permissible(SafetyMethod::Energy, s.m_eff, &p, verdict))
}

/// The finite-element impact of the simulation method for `s` and `input`.
fn fe_impact(s: &Setup, input: &SafetyInput) -> Result<crate::safety::simulation::FeImpact, Error> {
    let settings = input.simulation.unwrap_or(SimulationSettings::DEFAULT);
    settings.validate()?;
    let (gamma, m_r, m_e) = match input.m_eff {
        Some(RobotEffectiveMass::Prb { gamma, m_r, m_e }) => (gamma, m_r, m_e),
        _ => {
            return Err(bad(
                "--m-r",
                "(missing)",
                "the simulation method simulates a link: give its mass and payload with --m-r \
                 --m-e (and --gamma or --link)",
            ));
        }
    };
    let link = match input.link {
        Some(link) => link,
        None if gamma == crate::safety::simulation::GAMMA_CJ => FeLink::CompliantJoint,
        None if (gamma - crate::safety::simulation::GAMMA_CL).abs() < 1e-12 => {
            FeLink::CompliantLink
        }
        None => {
            return Err(bad(
                "--link",
                "(missing)",
                "the simulation method needs the link: cj or cl (implied by --gamma 1 or 2/3)",
            ));
        }
    };
    if s.hertz.n() < 1.0 {
        return Err(bad("--n", s.hertz.n(), "the simulation method needs n ≥ 1"));
    }
    if s.kind == ContactKind::QuasiStatic && settings.joint == MapJoint::Held {
        return Err(bad(
            "--contact",
            "quasi-static",
            "with --method simulation needs --joint free-hub: a held joint pressing a clamped \
             body has no bounded peak force",
        ));
    }
    let k_delta = match s.link {
        LinkStiffness::Finite(k) => k,
        LinkStiffness::Rigid => FE_RIGID_LINK_STIFFNESS,
    };
    if k_delta > FE_RIGID_LINK_STIFFNESS {
        return Err(bad(
            "--k-delta",
            k_delta,
            "the simulation method's link takes k_δ ≤ 1e12 N/m (leave --k-delta out for a \
             rigid link)",
        ));
    }
    Ok(crate::safety::simulation::FeImpact {
        m_h: match s.region.human_mass(s.kind) {
            m if m.is_finite() => m,
            _ => CLAMPED_HUMAN_MASS,
        },
        hertz: s.hertz,
        m_r,
        m_e,
        k_delta,
        link,
        settings,
    })
}

/// The mean pressure \[Pa\] of the area model at a peak force `f` \[N\] (the indentation of the
/// contact law at that force, δ_c = (f/k_c)^{1/n}).
fn pressure_at_force(s: &Setup, f: f64) -> Option<f64> {
    s.area_model
        .map(|a| a.mean_pressure(f, (f / s.hertz.k()).powf(1.0 / s.hertz.n())))
}

fn simulation_traced(
    s: &Setup,
    input: &SafetyInput,
    trace: Option<&mut Vec<RootStep>>,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<MethodResult, Error> {
    let impact = fe_impact(s, input)?;
    let contact = energy_contact(s)?;
    let guess = contact.permissible_speed(s.limits)?;
    let (by_force, by_pressure, _) = crate::safety::simulation::fe_speeds(
        &impact,
        &s.limits,
        &contact,
        guess.by_force,
        guess.by_pressure,
        stop,
        trace,
    )?;
    let p = PermissibleSpeed::from_parts(by_force, by_pressure, contact.reduced_mass(), s.limits);
    let mut runs = impact.prepare(crate::safety::simulation::MODES_SPEED)?;
    let mut at_speed = None;
    let verdict = match input.speed {
        Some(v) if v > 0.0 => {
            let peak = runs.impact_at(v, stop)?;
            at_speed = Some(peak);
            let force = peak.peak_force_n;
            Some(Verdict::new(
                v,
                p,
                force,
                s.limits.pressure.and(pressure_at_force(s, force)),
            ))
        }
        Some(v) => Some(Verdict::new(v, p, 0.0, s.limits.pressure.map(|_| 0.0))),
        None => None,
    };
    let mut m = from_permissible(SafetyMethod::Simulation, s.m_eff, &p, verdict);
    m.human_mass_kg = Some(s.region.human_mass(s.kind)).filter(|m| m.is_finite());
    if let Some(v) = m.verdict.as_mut() {
        v.governing_contact = at_speed;
    }
    if p.v_max.is_finite() && p.v_max > 0.0 {
        m.governing_contact = Some(runs.impact_at(p.v_max, stop)?);
    }
    Ok(m)
}

/// The simulation method of `input` with its force search traced: the method's result (the
/// same as [`safety`]'s, bit for bit), every evaluation of the search on the force limit, and
/// the finite-element impact it ran.
pub fn simulation_trace(
    input: &SafetyInput,
    model: Option<&BodyModel>,
) -> Result<
    (
        MethodResult,
        Vec<RootStep>,
        crate::safety::simulation::FeImpact,
    ),
    Error,
> {
    simulation_trace_until(input, model, &std::sync::atomic::AtomicBool::new(false))
}

/// [`simulation_trace`], stopped between its runs once `stop` is set.
pub fn simulation_trace_until(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<
    (
        MethodResult,
        Vec<RootStep>,
        crate::safety::simulation::FeImpact,
    ),
    Error,
> {
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    let s = setup(input, model)?;
    let mut trace = Vec::new();
    let m = simulation_traced(&s, input, Some(&mut trace), stop)?;
    Ok((m, trace, fe_impact(&s, input)?))
}

/// The simulation method's first-contact peak force \[N\] of `input` at each speed of `speeds`
/// [m/s], as (speed, force) pairs (the CL's modes solved at the first speed; with a driven
/// scene, its strike at each commanded tip speed; with a test-bed scene, its run at each speed
/// the operator reaches, those beyond its largest release angle left out).
pub fn simulated_peak_forces(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    speeds: &[f64],
) -> Result<Vec<(f64, f64)>, Error> {
    simulated_peak_forces_until(
        input,
        model,
        speeds,
        &std::sync::atomic::AtomicBool::new(false),
    )
}

/// [`simulated_peak_forces`], stopped between its runs once `stop` is set.
pub fn simulated_peak_forces_until(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    speeds: &[f64],
    stop: &std::sync::atomic::AtomicBool,
) -> Result<Vec<(f64, f64)>, Error> {
    use crate::safety::simulation::check_stop;
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    if let Some(given) = &input.scene {
        let settings = input.simulation.unwrap_or(SimulationSettings::DEFAULT);
        return match crate::safety::scene::load_any(given)? {
            SafetyDesignScene::Driven(sc) => {
                let s = setup(&scene_input(input, &sc)?, model)?;
                let sc = judged_scene(&sc, &s);
                speeds
                    .iter()
                    .map(|&v| {
                        check_stop(stop)?;
                        Ok((v, crate::safety::scene::peak_force(&sc, v, &settings)?))
                    })
                    .collect()
            }
            SafetyDesignScene::TestBed(tb) => {
                let reach = tb.max_speed();
                speeds
                    .iter()
                    .filter(|&&v| v <= reach)
                    .map(|&v| {
                        check_stop(stop)?;
                        Ok((v, tb.peak_force(v)?))
                    })
                    .collect()
            }
        };
    }
    let s = setup(input, model)?;
    let impact = fe_impact(&s, input)?;
    let Some(&first) = speeds.first() else {
        return Ok(Vec::new());
    };
    let _ = first;
    let mut runs = impact.prepare(crate::safety::simulation::MODES_SPEED)?;
    speeds
        .iter()
        .map(|&v| Ok((v, runs.peak(v, stop)?)))
        .collect()
}
