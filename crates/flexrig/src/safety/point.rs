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
use serde::Serialize;

use crate::Error;
pub use crate::safety::question::{
    ContactLaw, MethodResult, RobotEffectiveMass, SafetyInput, SafetyMethod, Speed, SpeedVerdict,
    Unbounded,
};
use crate::safety::scene::SafetyDesignScene;

pub use crate::safety::simulation::{
    CLAMPED_HUMAN_MASS, FE_RIGID_LINK_STIFFNESS, FeImpact, FeLink, MapJoint, RootStep,
    SimulationSettings,
};

/// The answer: the limits applied and each method's permissible speed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SafetyReport {
    /// The overall verdict: the most restrictive of the methods run, named
    /// ([`crate::safety::overall`]).
    pub overall: crate::safety::overall::OverallVerdict,
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
    /// What is valid but looks like a mistake (a unit slip, an implausible contact area) or what
    /// a method's answer rests on that the design violates, each with the field it is about.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<crate::safety::measured::Warning>,
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
        a.validate().map_err(|e| match a {
            ContactAreaModel::HertzSphere { radius_m }
            | ContactAreaModel::ThinLayer { radius_m } => bad(
                "--radius",
                flexrig_contact::validate::display(*radius_m),
                &e.to_string(),
            ),
            ContactAreaModel::Fixed { area_m2 } => bad(
                "--contact-area",
                flexrig_contact::validate::display(*area_m2),
                &e.to_string(),
            ),
        })?;
        if !matches!(a, ContactAreaModel::Fixed { .. }) && hertz.n() <= 1.0 {
            return Err(bad(
                "--area-model",
                format!("{a:?}"),
                &format!(
                    "a dome's area model needs a contact law with n > 1: a linear contact \
                     (n = {}) is a spring without a contact geometry, its dome pressure k/(πR) \
                     would not depend on the force; give --k-c and --n of the skin (or \
                     --material), or a fixed area (--contact-area, e.g. 1cm2)",
                    hertz.n()
                ),
            ));
        }
    }
    if area_model.is_none() {
        limits.pressure = None;
    }
    if let Some(v) = input.speed
        && !(v.is_finite() && (0.0..=1e3).contains(&v))
    {
        return Err(bad("--speed", v, "must lie in [0, 1000] m/s"));
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
    let given = input;
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
    let defaulted;
    let input = if input.methods.is_empty() {
        defaulted = SafetyInput {
            methods: crate::safety::overall::default_methods(input),
            ..input.clone()
        };
        &defaulted
    } else {
        input
    };
    let mut s = setup(input, model)?;
    if input.moving_mass.is_none()
        && let Some(SafetyDesignScene::Driven(sc)) = &scene
        && let Some(m) = rigid_joint_tip_mass(sc)
    {
        s.standard_robot_mass = m;
    }
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
    let overall = crate::safety::overall::overall(&methods).ok_or_else(|| {
        bad(
            "--method",
            "(none)",
            "give at least one of standard, energy, simulation",
        )
    })?;
    for m in &mut methods {
        transferred_energy(&s, m)?;
    }
    let mut warnings = typed_warnings(given);
    warnings.extend(crate::safety::measured::area_warnings(
        s.area_model.as_ref(),
        "--contact-area",
        "--radius",
    ));
    warnings.extend(
        methods
            .iter()
            .filter(|m| m.method == SafetyMethod::Energy)
            .filter_map(|m| {
                crate::safety::overall::energy_travel_warning(
                    m,
                    s.limits.force,
                    match s.link {
                        LinkStiffness::Finite(k) => Some(k),
                        LinkStiffness::Rigid => None,
                    },
                    input.simulation.and_then(|sim| sim.length),
                )
            }),
    );
    Ok(SafetyReport {
        overall,
        warnings,
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

/// Checks that `region` is a region of `model` (the bundled ISO/TS 15066:2016 table when `None`):
/// a front's first check, so that a mistyped region is named (with its nearest key) before any
/// other input is asked for.
pub fn check_region(region: &str, model: Option<&BodyModel>) -> Result<(), Error> {
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    match model.region(region) {
        Ok(_) => Ok(()),
        Err(flexrig_safety::SafetyError::Unknown { what, name, known }) => {
            Err(Error::InvalidArgument {
                arg: "--region".into(),
                value: flexrig_safety::quoted_name(&name),
                allowed: format!("a {what} of the body model: {known}"),
            })
        }
        Err(other) => Err(other.into()),
    }
}

/// The plausibility warnings of the masses, length and speed the user typed
/// ([`crate::shared::plausibility`]; a scene's own values are the scene's warnings).
fn typed_warnings(input: &SafetyInput) -> Vec<crate::safety::measured::Warning> {
    use crate::shared::plausibility::{length, mass, speed};
    let mut masses = vec![
        ("--moving-mass", input.moving_mass),
        ("--payload", Some(input.payload)),
    ];
    match input.m_eff {
        Some(RobotEffectiveMass::Given(m)) => masses.push(("--m-eff", Some(m))),
        Some(RobotEffectiveMass::Prb { m_r, m_e, .. }) => {
            masses.extend([("--m-r", Some(m_r)), ("--m-e", Some(m_e))]);
        }
        None => {}
    }
    masses
        .into_iter()
        .filter_map(|(flag, m)| m.and_then(|m| mass(flag, m)))
        .chain(
            input
                .simulation
                .and_then(|s| s.length)
                .filter(|_| input.scene.is_none())
                .and_then(|l| length("--length", l)),
        )
        .chain(input.speed.and_then(|v| speed("--speed", v)))
        .collect()
}

/// The standard's m_R of a driven scene whose joint is rigid (the CL: the compliance is in the
/// link): the robot as one rigid body turning about its joint, seen at the tip, m_e + m_r/3 +
/// J_m N²/L² — the payload, the link's inertia about the joint and the motor's rotor through the
/// gear (ISO/TS 15066:2016 Eq. A.4 asks for the robot's moving mass; a rigid joint moves the rotor
/// with the link). `None` for the CJ, whose joint spring decouples the rotor (m_R = m_eff).
fn rigid_joint_tip_mass(sc: &crate::safety::scene::SafetyScene) -> Option<f64> {
    let strike = &sc.scene.strike;
    match strike.design {
        crate::driven::strike::StrikeDesign::Cj => None,
        crate::driven::strike::StrikeDesign::Cl => {
            let l = strike.link.length;
            Some(
                strike.link.m_e
                    + strike.link.m_r / 3.0
                    + strike.drive.motor().reflected_inertia() / (l * l),
            )
        }
    }
}

/// Fills in the energy transferred to the body by method `m` at its verdict's peak force and at
/// v_max ([`crate::safety::measured::contact_energy_at_force`]): the standard's body spring
/// (n = 1, k = K) for the standard, the skin's law for the others.
fn transferred_energy(s: &Setup, m: &mut MethodResult) -> Result<(), Error> {
    let (law, area) = match m.method {
        SafetyMethod::Standard => (
            Hertz::new(s.region.spring_constant(), 1.0)?,
            s.area_model
                .filter(|a| matches!(a, ContactAreaModel::Fixed { .. })),
        ),
        _ => (s.hertz, s.area_model),
    };
    let energy = |f: f64| crate::safety::measured::contact_energy_at_force(&law, f);
    if let Some(v) = m.verdict.as_mut() {
        v.energy_transferred_j = energy(v.peak_force_n);
    }
    let force = match (m.v_max_mps, m.governing, s.limits.pressure) {
        (Speed::Unlimited(_), ..) => None,
        (_, GoverningLimit::Pressure, Some(p)) => {
            let contact = EnergyContact::new(1.0, 1.0, law, LinkStiffness::Rigid, area)?;
            match contact.force_at_pressure(p) {
                Some(flexrig_safety::PressureCrossing::AtForce(f)) => Some(f),
                _ => None,
            }
        }
        _ => Some(s.limits.force),
    };
    m.energy_transferred_at_v_max_j = force.map(energy);
    Ok(())
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
    // the paper's dome by default, for a skin with a contact geometry (n > 1)
    let area_model = match input.area_model {
        Some(a) => Some(a),
        None if hertz.n() > 1.0 => Some(ContactAreaModel::HertzSphere {
            radius_m: crate::shared::severity::paper_dome_radius_m()?,
        }),
        None => None,
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
        area_model,
        link: Some(link),
        simulation: Some(SimulationSettings {
            length: Some(strike.link.length),
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
    // the scene's dome by default, for a skin with a contact geometry (n > 1)
    let area_model = match input.area_model {
        Some(a) => Some(a),
        None if tb.scene.hertz.n() > 1.0 => Some(ContactAreaModel::HertzSphere {
            radius_m: robot.dome_radius_m,
        }),
        None => None,
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
        area_model,
        link: Some(link),
        simulation: Some(SimulationSettings {
            length: Some(robot.length_m),
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
        crate::safety::scene::peak_force(sc, v, &settings, stop)
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
        pressure_assessed: p.by_pressure.is_some(),
        energy_transferred_at_v_max_j: None,
        verdict: verdict.map(|v| SpeedVerdict {
            speed_mps: v.speed,
            pass: v.pass,
            peak_force_n: v.peak_force,
            peak_pressure_pa: v.peak_pressure,
            force_margin: v.force_margin,
            pressure_margin: v.pressure_margin,
            energy_transferred_j: 0.0,
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
    // the search's runs also answer the governing contact at v_max
    let found = crate::safety::simulation::fe_search(
        &impact,
        &s.limits,
        &contact,
        guess.by_pressure.is_some(),
        crate::safety::simulation::LimitSearch::Both,
        stop,
        trace,
    )?;
    let mut runs = found.runs;
    let p = PermissibleSpeed::from_parts(
        found.by_force,
        found.by_pressure,
        contact.reduced_mass(),
        s.limits,
    );
    let mut at_speed = None;
    let verdict = match input.speed {
        Some(v) if v > 0.0 => {
            // the peak at the user's speed to the run's own tolerance (the searches' runs are
            // only as accurate as the limits need)
            let peak = impact
                .prepare(crate::safety::simulation::MODES_SPEED)?
                .impact_at(v, stop)?;
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
    // the simulated robot's rigid-body mass at the tip: the payload, the link about its joint
    // and, with a free hub, the rotor through the length (a held joint: the link alone moves)
    let robot = impact.m_e
        + impact.m_r / 3.0
        + match impact.settings.joint {
            MapJoint::Held => 0.0,
            MapJoint::FreeHub { rotor_inertia } => rotor_inertia / impact.settings.length().powi(2),
        };
    let mut m = from_permissible(SafetyMethod::Simulation, robot, &p, verdict);
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
    let mut m = simulation_traced(&s, input, Some(&mut trace), stop)?;
    transferred_energy(&s, &mut m)?;
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
                        Ok((
                            v,
                            crate::safety::scene::peak_force(&sc, v, &settings, stop)?,
                        ))
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
