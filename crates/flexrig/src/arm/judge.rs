//! The arm along its trajectory, judged: every sample × every contact point × one body region.
//!
//! # What is computed
//!
//! For every sample of the trajectory (at `speed_scale` times its speed) and every contact point
//! (a point fixed on a link, in that link's frame): the point's position and velocity v = J q̇,
//! its speed |v|, the contact direction u = v/|v| (the point strikes what is in its way), and the
//! arm's **reflected mass** along u, m_u = 1/(uᵀ J M⁻¹ Jᵀ u) (O. Khatib, IEEE J. Robotics and
//! Automation 3(1), 1987; S. Haddadin et al., IJRR 28(11–12), 2009), with the joints rigid,
//! rigid with the rotors' armature J_m N², or elastic (the rotors decoupled on the impact's time
//! scale): [`flexrig_robot::Trajectory::evaluate`].
//!
//! # How the arm meets the single-link model
//!
//! flexrig's safety methods judge one link of mass m_r (stiffness k_δ, CJ or CL) carrying a
//! payload m_e at its tip ([`crate::safety`]). The arm's reflected mass m_u is the rigid mass the
//! person meets at the point; the compliance the user describes (a joint spring, CJ, or a bending
//! link, CL, of stiffness k_δ and mass m_r, `link_mass`) sits between that mass and the person.
//! The rigid tip-equivalent mass of a link on its joint is m_e + m_r/3, so the arm is the single
//! link with
//!
//! m_e = m − m_r/3,
//!
//! m the effective mass below (m_u, or its node on the mass grid): the link's own mass is
//! accounted for as a rigid link's and the rest of the arm rides at the tip. For the CJ every
//! method then sees m_eff = m_e + m_r/3 = m (the held joint's rigid link moves as one mass at its
//! tip); for the CL the beam's distributed mass presents less on the impact's time scale (the
//! lumped methods' γ = 2/3: m_e + 2m_r/9 = m − m_r/9; the simulation the beam itself). Each
//! sample's question is then exactly `flexrig safety --link cj|cl --m-r m_r --m-e (m − m_r/3)
//! --k-delta …` with the user's region, skin and person, answered by the same function
//! ([`crate::safety::safety_cancellable`]): the same three methods and overall verdict.
//!
//! # Sharing the work: the mass grid
//!
//! The permissible speed depends on the sample only through the effective mass (the design, the
//! skin and the region are fixed), so it is computed once per distinct effective mass. A
//! simulated root search costs tens of milliseconds, so with `mass_step` > 0 the reflected mass
//! is **rounded up** to the geometric grid m_k = (1 + mass_step)^k kg and every method is run at
//! the node: the effective mass exceeds m_u by less than `mass_step` (relative), which moves the
//! formula methods' speed (∝ μ^{−1/2}) down by less than mass_step/2 — conservative for them,
//! since their speed falls as the mass rises — and every sample's permissible speed is `flexrig
//! safety`'s answer for its node's mass bit for bit. The simulation's speed is not monotone in
//! the mass in general (a stiffer, re-contacting design can allow a little more speed with a
//! heavier link), so for it the node is "a mass within mass_step above m_u", not a bound.
//! `mass_step = 0` runs every distinct m_u exactly.
//!
//! # The verdict
//!
//! The ratio of a point's speed to its permissible speed says how close it comes; the largest
//! ratio over every sample and point **governs** (its sample, point and method are named), the
//! trajectory passes when it is ≤ 1, and the **speed-scaling factor** 1/ratio is how much faster
//! (> 1) or slower (< 1) the whole trajectory may run: scaling time leaves every posture, contact
//! direction and reflected mass unchanged and multiplies every speed by the factor, so the
//! scaled trajectory's largest ratio is exactly 1. The governing sample's question is asked
//! again with its speed (`flexrig safety --speed`), so each method's verdict and peak force at
//! that speed are reported beside it.

use std::collections::BTreeMap;

use flexrig_robot::{ContactPoint, JointModel, Robot, Trajectory};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::safety::simulation::{FeLink, GAMMA_CJ, GAMMA_CL, SimulationSettings};
use crate::safety::{
    BodyModel, ContactAreaModel, ContactKind, ContactLaw, GoverningLimit, RobotEffectiveMass,
    SafetyInput, SafetyMethod, SafetyReport, Speed,
};
use crate::{CancelToken, Error};

fn bad(arg: &str, value: impl ToString, allowed: impl Into<String>) -> Error {
    Error::InvalidArgument {
        arg: arg.into(),
        value: crate::shared::output::value_text(value),
        allowed: allowed.into(),
    }
}

/// A candidate contact point: a point fixed on a link, in that link's frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArmPoint {
    /// The URDF link (any link, also one merged into its parent by a fixed joint).
    pub link: String,
    /// The point in the link's frame, m.
    pub xyz: [f64; 3],
}

impl ArmPoint {
    /// `LINK:x,y,z` (m) as the command line writes it.
    pub fn label(&self) -> String {
        let n = crate::shared::output::display_number;
        format!(
            "{}:{},{},{}",
            self.link,
            n(self.xyz[0]),
            n(self.xyz[1]),
            n(self.xyz[2])
        )
    }

    /// Parses `LINK:x,y,z` (m) or `LINK` (the link frame's origin); errors name `--point`.
    pub fn parse(text: &str) -> Result<ArmPoint, Error> {
        let allowed = "LINK:x,y,z — a URDF link name, then the point in that link's frame in \
                       metres (e.g. tool0:0,0,0.1), or LINK alone for the link frame's origin";
        let (link, xyz) = match text.split_once(':') {
            Some((l, rest)) => (l.trim(), Some(rest)),
            None => (text.trim(), None),
        };
        if link.is_empty() {
            return Err(bad("--point", text, allowed));
        }
        let xyz = match xyz {
            None => [0.0; 3],
            Some(rest) => {
                let cells: Vec<&str> = rest.split(',').map(str::trim).collect();
                if cells.len() != 3 {
                    return Err(bad("--point", text, allowed));
                }
                let mut p = [0.0; 3];
                for (k, c) in cells.iter().enumerate() {
                    p[k] = match c.parse::<f64>() {
                        Ok(v) if v.is_finite() && v.abs() <= 100.0 => v,
                        _ => {
                            return Err(bad(
                                "--point",
                                text,
                                format!("{allowed}; {c:?} is not a coordinate within ±100 m"),
                            ));
                        }
                    };
                }
                p
            }
        };
        Ok(ArmPoint {
            link: link.to_string(),
            xyz,
        })
    }
}

/// How the arm's joints behave on the impact's time scale.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArmJoints {
    /// Rigid joints, the links' inertias only.
    Rigid,
    /// Rigid joints with the rotor inertia reflected through the gear, J_m N² per moving joint
    /// (kg·m² revolute, kg prismatic; ≥ 0, in the URDF's joint order).
    Armature(Vec<f64>),
    /// Elastic joints (series elastic actuators): the rotors decoupled, the links' inertias only.
    Elastic,
}

impl ArmJoints {
    fn model(&self) -> JointModel<'_> {
        match self {
            ArmJoints::Rigid => JointModel::Rigid,
            ArmJoints::Armature(a) => JointModel::RigidWithArmature(a),
            ArmJoints::Elastic => JointModel::Elastic,
        }
    }
}

/// The question: which points, how the joints behave, how fast, and the compliant impact's
/// design, skin and region (the fields of `flexrig safety`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArmInput {
    /// Candidate contact points (at least one, at most [`MAX_POINTS`]).
    pub points: Vec<ArmPoint>,
    /// The joints on the impact's time scale.
    pub joints: ArmJoints,
    /// The trajectory runs at this multiple of its speed (> 0; 1 as given).
    pub speed_scale: f64,
    /// Relative step of the mass grid, in [0, 0.25] (module documentation; 0: every mass exact).
    pub mass_step: f64,
    /// Body region key (`--region`).
    pub region: String,
    /// The area of the region for the pressure limit (absent: its most sensitive).
    pub area: Option<String>,
    /// Transient (the person free) or quasi-static (clamped).
    pub contact: ContactKind,
    /// The skin's contact law.
    pub law: ContactLaw,
    /// The contact-area model for pressure (absent: as `flexrig safety`).
    pub area_model: Option<ContactAreaModel>,
    /// The compliance: CJ (joint spring) or CL (bending link).
    pub link: FeLink,
    /// Its lateral stiffness at the point, k_δ \[N/m\] (absent: rigid).
    pub k_delta: Option<f64>,
    /// The compliant link's own mass m_r \[kg\] (absent: the URDF mass of the body that carries
    /// the first point).
    pub link_mass: Option<f64>,
    /// The simulation's integrator and root-search tolerances (`--tol`, `--root-rtol`; the
    /// joint held during the impact).
    pub simulation: SimulationSettings,
    /// Methods (empty: all three, as `flexrig safety` for a known design).
    pub methods: Vec<SafetyMethod>,
}

/// The drive during the impact.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ArmDrive {
    /// A stiff drive carries the joint on at its speed (`flexrig safety --joint held`): the
    /// person meets the compliance and the effective mass behind it moves with the drive.
    Held,
    /// The drive exerts no torque during the impact: the effective mass coasts into the person
    /// (`flexrig safety --joint free-hub --rotor-inertia 1e-12 --length 1`, a hub of no
    /// inertia: the rotors are in the reflected mass already when they are).
    Free,
}

/// The free drive's hub inertia, kg·m² (the smallest the simulation accepts; 1e-12 kg at the
/// contact with its 1 m length).
pub const FREE_HUB_INERTIA: f64 = 1e-12;

/// The simulation's settings for `drive` with the integrator's `tol` and the root search's
/// `root_rtol` (their ranges are `flexrig safety`'s: the errors name --tol and --root-rtol).
pub fn simulation_settings(drive: ArmDrive, tol: f64, root_rtol: f64) -> SimulationSettings {
    let (joint, length) = match drive {
        ArmDrive::Held => (crate::safety::MapJoint::Held, None),
        ArmDrive::Free => (
            crate::safety::MapJoint::FreeHub {
                rotor_inertia: FREE_HUB_INERTIA,
            },
            Some(1.0),
        ),
    };
    SimulationSettings {
        joint,
        length,
        tol,
        root_rtol,
        ..SimulationSettings::DEFAULT
    }
}

/// The most contact points judged at once.
pub const MAX_POINTS: usize = 64;

/// The largest relative step of the mass grid.
pub const MAX_MASS_STEP: f64 = 0.25;

/// One point at one sample.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PointResult {
    /// World position, m.
    pub position_m: [f64; 3],
    /// Speed |J q̇|, m/s.
    pub speed_mps: f64,
    /// The contact direction (the velocity's), base frame (absent: the point at rest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub direction: Option<[f64; 3]>,
    /// The reflected mass along it, kg (absent: at rest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reflected_mass_kg: Option<f64>,
    /// The effective mass judged: m_u, or its node on the mass grid, kg (absent: at rest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub effective_mass_kg: Option<f64>,
    /// The permissible speed there (the overall one), m/s (absent: at rest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub v_max_mps: Option<Speed>,
    /// The method that sets it (absent: at rest).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub method: Option<SafetyMethod>,
    /// speed / permissible speed (0 at rest or when unlimited).
    pub ratio: f64,
}

/// One sample.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SampleResult {
    /// Time, s (of the scaled trajectory).
    pub time_s: f64,
    /// Joint positions, rad or m.
    pub q: Vec<f64>,
    /// The contact points, in the order given.
    pub points: Vec<PointResult>,
}

/// The answer of `flexrig safety` for one effective mass.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MassAnswer {
    /// The effective mass m, kg.
    pub effective_mass_kg: f64,
    /// The single link's payload m_e = m − m_r/3, kg.
    pub m_e_kg: f64,
    /// The overall permissible speed, m/s.
    pub v_max_mps: Speed,
    /// The governing method.
    pub method: SafetyMethod,
    /// The governing limit.
    pub governing: GoverningLimit,
    /// Each method's permissible speed, in the order run.
    pub methods: Vec<(SafetyMethod, Speed)>,
}

/// The sample and point that govern.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Governing {
    /// Sample index (0-based).
    pub sample: usize,
    /// Its time, s.
    pub time_s: f64,
    /// Point index (0-based, in the order given).
    pub point: usize,
    /// The point as `LINK:x,y,z`.
    pub label: String,
    /// Its speed, m/s.
    pub speed_mps: f64,
    /// Its reflected mass, kg.
    pub reflected_mass_kg: f64,
    /// The effective mass judged, kg.
    pub effective_mass_kg: f64,
    /// The permissible speed, m/s.
    pub v_max_mps: Speed,
    /// speed / permissible speed.
    pub ratio: f64,
    /// The governing method there.
    pub method: SafetyMethod,
    /// The question asked there: `flexrig safety` with the point's speed.
    pub question: SafetyInput,
    /// `flexrig safety`'s full answer there at the point's speed (each method's verdict, the
    /// peak force at that speed).
    pub safety: SafetyReport,
}

/// The whole answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ArmReport {
    /// The robot's name (URDF).
    pub robot: String,
    /// Its moving joints.
    pub joint_names: Vec<String>,
    /// The joints on the impact's time scale.
    pub joints: ArmJoints,
    /// The speed scale applied.
    pub speed_scale: f64,
    /// The drive during the simulated impact.
    pub drive: ArmDrive,
    /// The mass grid's relative step (0: exact masses).
    pub mass_step: f64,
    /// The compliance.
    pub link: FeLink,
    /// Its stiffness k_δ, N/m (absent: rigid).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_delta_n_per_m: Option<f64>,
    /// The compliant link's mass m_r, kg.
    pub link_mass_kg: f64,
    /// Body region key and name, the area, the contact kind.
    pub region: String,
    /// The region's name.
    pub region_name: String,
    /// The area whose pressure limit applies.
    pub area: String,
    /// Transient or quasi-static.
    pub contact: ContactKind,
    /// The person's mass m_H, kg (absent: clamped).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub human_mass_kg: Option<f64>,
    /// Force limit, N.
    pub force_limit_n: f64,
    /// Pressure limit, Pa.
    pub pressure_limit_pa: f64,
    /// The skin's law k_c, N/mⁿ, and n.
    pub k_c: f64,
    /// Its exponent.
    pub n: f64,
    /// The contact points.
    pub points: Vec<ArmPoint>,
    /// Every sample.
    pub samples: Vec<SampleResult>,
    /// `flexrig safety`'s answer per distinct effective mass, lightest first.
    pub masses: Vec<MassAnswer>,
    /// The governing sample and point (absent when no point ever moves, or no limit is reached).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub governing: Option<Governing>,
    /// The largest ratio of speed to permissible speed.
    pub max_ratio: f64,
    /// How much faster the whole trajectory may run (1/max_ratio; unlimited when nothing moves
    /// towards a limit).
    pub speed_scale_factor: Speed,
    /// PASS when every point at every sample is within its permissible speed.
    pub pass: bool,
    /// The warnings of the answers (each once), with the field each is about.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<crate::safety::measured::Warning>,
}

/// The node of the mass grid of relative step `step` at or above `m` (kg): (1 + step)^k with
/// the smallest integer k for which it is ≥ m; `m` itself when `step` is 0. Returns (k, node).
pub fn effective_mass_node(m: f64, step: f64) -> (i64, f64) {
    if step == 0.0 {
        return (0, m);
    }
    let l = step.ln_1p();
    let mut k = (m.ln() / l).ceil() as i64;
    let node = |k: i64| (k as f64 * l).exp();
    while node(k) < m {
        k += 1;
    }
    while node(k - 1) >= m {
        k -= 1;
    }
    (k, node(k))
}

/// [`judge_cancellable`] without cancelling.
pub fn judge(
    robot: &Robot,
    trajectory: &Trajectory,
    input: &ArmInput,
    model: Option<&BodyModel>,
) -> Result<ArmReport, Error> {
    judge_cancellable(robot, trajectory, input, model, &CancelToken::new())
}

/// The safety question of one effective mass `m` (kg): `flexrig safety --link … --m-r m_r --m-e
/// (m − m_r/3) --k-delta …` with the input's region, skin and tolerances.
pub fn question(input: &ArmInput, link_mass: f64, m: f64, speed: Option<f64>) -> SafetyInput {
    let gamma = match input.link {
        FeLink::CompliantJoint => GAMMA_CJ,
        FeLink::CompliantLink => GAMMA_CL,
    };
    SafetyInput {
        region: input.region.clone(),
        area: input.area.clone(),
        contact: input.contact,
        m_eff: Some(RobotEffectiveMass::Prb {
            gamma,
            m_r: link_mass,
            m_e: m - link_mass / 3.0,
        }),
        k_delta: input.k_delta,
        law: input.law.clone(),
        area_model: input.area_model,
        moving_mass: None,
        payload: 0.0,
        speed,
        methods: input.methods.clone(),
        link: Some(input.link),
        simulation: Some(input.simulation),
        scene: None,
    }
}

/// Every sample × point of `trajectory` judged against the input's region (module
/// documentation), with the bundled ISO/TS 15066:2016 body model or `model`; stopped between
/// simulated impacts once `cancel` is set.
pub fn judge_cancellable(
    robot: &Robot,
    trajectory: &Trajectory,
    input: &ArmInput,
    model: Option<&BodyModel>,
    cancel: &CancelToken,
) -> Result<ArmReport, Error> {
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    crate::safety::check_region(&input.region, Some(model))?;
    if input.points.is_empty() || input.points.len() > MAX_POINTS {
        return Err(bad(
            "--point",
            format!("{} points", input.points.len()),
            format!("give 1 to {MAX_POINTS} contact points (LINK:x,y,z)"),
        ));
    }
    if !(input.mass_step.is_finite() && (0.0..=MAX_MASS_STEP).contains(&input.mass_step)) {
        return Err(bad(
            "--mass-step",
            input.mass_step,
            format!(
                "a relative step in [0, {MAX_MASS_STEP}] (0: every reflected mass exactly; 0.01: \
                 masses rounded up to a 1 % grid)"
            ),
        ));
    }
    if !(input.speed_scale.is_finite() && input.speed_scale > 0.0 && input.speed_scale <= 1e3) {
        return Err(bad(
            "--speed-scale",
            input.speed_scale,
            "a number in (0, 1000] (1: the trajectory as given, 2: twice as fast)",
        ));
    }
    if let ArmJoints::Armature(a) = &input.joints {
        if a.len() != robot.dof() {
            return Err(bad(
                "--armature",
                format!("{} values", a.len()),
                format!(
                    "one rotor inertia J_m N² (kg·m², ≥ 0) per moving joint, {} in this order: {}",
                    robot.dof(),
                    robot.joint_names().join(", ")
                ),
            ));
        }
        for (x, name) in a.iter().zip(robot.joint_names()) {
            if !(x.is_finite() && (0.0..=1e6).contains(x)) {
                return Err(bad(
                    "--armature",
                    x,
                    format!("the rotor inertia of joint {name:?} must lie in [0, 1e6] kg·m²"),
                ));
            }
        }
    }
    let mut points = Vec::with_capacity(input.points.len());
    for p in &input.points {
        let cp = ContactPoint::new(robot, &p.link, p.xyz).map_err(|e| {
            bad(
                "--point",
                p.label(),
                match e {
                    flexrig_robot::RobotError::UnknownLink { robot, name, known } => {
                        format!("robot {robot:?} has no link {name:?}; its links are {known}")
                    }
                    other => other.to_string(),
                },
            )
        })?;
        points.push(cp);
    }
    let link_mass = match input.link_mass {
        Some(m) => {
            if !(m.is_finite() && m > 0.0 && m <= 1e4) {
                return Err(bad(
                    "--link-mass",
                    m,
                    "the compliant link's own mass m_r, a number in (0, 1e4] kg",
                ));
            }
            m
        }
        None => {
            let body = points[0].body();
            let m = robot.bodies()[body].inertia().mass;
            if body == 0 || !(m > 0.0) {
                return Err(bad(
                    "--link-mass",
                    "(missing)",
                    format!(
                        "the first point is on the arm's base ({}), which has no moving link \
                         to take the mass of; give --link-mass (kg)",
                        input.points[0].link
                    ),
                ));
            }
            m
        }
    };
    let scaled = trajectory.with_speed_scale(input.speed_scale)?;
    let samples = scaled.evaluate(robot, &points, input.joints.model())?;

    // the effective mass of every moving point, and the distinct nodes
    let mut nodes: BTreeMap<u64, f64> = BTreeMap::new();
    let mut effective: Vec<Vec<Option<f64>>> = Vec::with_capacity(samples.len());
    for sample in &samples {
        let mut row = Vec::with_capacity(points.len());
        for (p, ps) in sample.points.iter().enumerate() {
            let Some(m_u) = ps.reflected_mass else {
                row.push(None);
                continue;
            };
            if !(m_u.is_finite() && m_u > 0.0 && m_u <= 1e6) {
                return Err(Error::NonFinite {
                    what: format!(
                        "reflected mass at {} at t = {} s",
                        input.points[p].label(),
                        sample.time
                    ),
                    value: crate::shared::output::display_number(m_u),
                    advice: "the arm is at (or next to) a posture where it cannot move the \
                             point along its velocity; leave this point or sample out"
                        .into(),
                });
            }
            let (_, node) = effective_mass_node(m_u, input.mass_step);
            if node - link_mass / 3.0 < 0.0 {
                return Err(bad(
                    "--link-mass",
                    link_mass,
                    format!(
                        "the reflected mass at {} at t = {} s is {} kg, less than a third of the \
                         link's mass ({} kg): the link alone would strike with more; give the \
                         compliant link's own mass, at most {} kg",
                        input.points[p].label(),
                        crate::shared::output::display_number(sample.time),
                        crate::shared::output::display_number(m_u),
                        crate::shared::output::display_number(link_mass / 3.0),
                        crate::shared::output::display_number(3.0 * node)
                    ),
                ));
            }
            nodes.insert(node.to_bits(), node);
            row.push(Some(node));
        }
        effective.push(row);
    }

    // one `flexrig safety` answer per distinct effective mass, on every core
    let masses: Vec<f64> = nodes.values().copied().collect();
    let answers: Vec<SafetyReport> = masses
        .par_iter()
        .map(|&m| {
            crate::safety::safety_cancellable(
                &question(input, link_mass, m, None),
                Some(model),
                cancel,
            )
        })
        .collect::<Result<_, _>>()?;
    let index: BTreeMap<u64, usize> = masses
        .iter()
        .enumerate()
        .map(|(i, m)| (m.to_bits(), i))
        .collect();

    let mut results = Vec::with_capacity(samples.len());
    let mut best: Option<(usize, usize, f64)> = None;
    for (s, sample) in samples.iter().enumerate() {
        let mut row = Vec::with_capacity(points.len());
        for (p, ps) in sample.points.iter().enumerate() {
            let (v_max, method, ratio) = match effective[s][p] {
                Some(node) => {
                    let a = &answers[index[&node.to_bits()]].overall;
                    let v = a.v_max_mps.value();
                    let ratio = if v.is_finite() { ps.speed / v } else { 0.0 };
                    (Some(a.v_max_mps), Some(a.method), ratio)
                }
                None => (None, None, 0.0),
            };
            if ratio > 0.0 && best.is_none_or(|(_, _, r)| ratio > r) {
                best = Some((s, p, ratio));
            }
            row.push(PointResult {
                position_m: ps.position.into(),
                speed_mps: ps.speed,
                direction: ps.direction.map(|u| u.into_inner().into()),
                reflected_mass_kg: ps.reflected_mass,
                effective_mass_kg: effective[s][p],
                v_max_mps: v_max,
                method,
                ratio,
            });
        }
        results.push(SampleResult {
            time_s: sample.time,
            q: sample.q.clone(),
            points: row,
        });
    }

    // the governing sample asked again at its speed: each method's verdict there
    let governing = match best {
        Some((s, p, ratio)) => {
            let r = &results[s].points[p];
            let node = r.effective_mass_kg.expect("a moving point has a mass");
            let speed = r.speed_mps;
            let asked = question(input, link_mass, node, Some(speed));
            let safety = crate::safety::safety_cancellable(&asked, Some(model), cancel)?;
            Some(Governing {
                sample: s,
                time_s: results[s].time_s,
                point: p,
                label: input.points[p].label(),
                speed_mps: speed,
                reflected_mass_kg: r.reflected_mass_kg.expect("a moving point has a mass"),
                effective_mass_kg: node,
                v_max_mps: r.v_max_mps.expect("a moving point has a speed"),
                ratio,
                method: r.method.expect("a moving point has a method"),
                question: asked,
                safety,
            })
        }
        None => None,
    };
    let max_ratio = best.map_or(0.0, |b| b.2);
    let first = match answers.first() {
        Some(a) => a.clone(),
        // nothing moves: the region's limits from the question at 1 kg
        None => crate::safety::safety_cancellable(
            &SafetyInput {
                methods: vec![SafetyMethod::Standard],
                ..question(input, link_mass, 1.0 + link_mass / 3.0, None)
            },
            Some(model),
            cancel,
        )?,
    };
    let mut warnings: Vec<crate::safety::measured::Warning> = Vec::new();
    for w in answers
        .iter()
        .chain(governing.as_ref().map(|g| &g.safety))
        .flat_map(|a| a.warnings.iter())
    {
        if !warnings.iter().any(|x| x.field == w.field) {
            warnings.push(w.clone());
        }
    }
    Ok(ArmReport {
        robot: robot.name().to_string(),
        joint_names: robot.joint_names().iter().map(|s| s.to_string()).collect(),
        joints: input.joints.clone(),
        speed_scale: input.speed_scale,
        drive: match input.simulation.joint {
            crate::safety::MapJoint::Held => ArmDrive::Held,
            crate::safety::MapJoint::FreeHub { .. } => ArmDrive::Free,
        },
        mass_step: input.mass_step,
        link: input.link,
        k_delta_n_per_m: input.k_delta,
        link_mass_kg: link_mass,
        region: first.region.clone(),
        region_name: first.region_name.clone(),
        area: first.area.clone(),
        contact: first.contact,
        human_mass_kg: first.human_mass_kg,
        force_limit_n: first.force_limit_n,
        pressure_limit_pa: first.pressure_limit_pa,
        k_c: first.k_c,
        n: first.n,
        points: input.points.clone(),
        samples: results,
        masses: masses
            .iter()
            .zip(&answers)
            .map(|(&m, a)| MassAnswer {
                effective_mass_kg: m,
                m_e_kg: m - link_mass / 3.0,
                v_max_mps: a.overall.v_max_mps,
                method: a.overall.method,
                governing: a.overall.governing,
                methods: a.methods.iter().map(|r| (r.method, r.v_max_mps)).collect(),
            })
            .collect(),
        governing,
        max_ratio,
        speed_scale_factor: Speed::from_f64(if max_ratio > 0.0 {
            1.0 / max_ratio
        } else {
            f64::INFINITY
        }),
        pass: max_ratio <= 1.0,
        warnings,
    })
}
