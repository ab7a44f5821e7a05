//! The role-switch verdict: does it matter that the test bed (§VI) let the operator strike the
//! robot at rest instead of the robot striking a person at rest?
//!
//! For each case and design (CJ, CL) and each drive stiffness, three peaks at the same relative
//! speed v0:
//!
//! * **test bed**: the head at v0 strikes the robot at rest, its joint held (the rig's fixed
//!   frame; [`crate::setup::Joint::Held`]);
//! * **driven**: the robot, turning at v0/L under its drive, strikes the head at rest;
//! * **switched, same drive**: the head at v0 strikes the robot at rest held by the *same* drive
//!   (its controller holding the angle).
//!
//! Drive stiffness runs from an ideal position source (a prescribed trajectory, ≈ held) through
//! PD position loops K_p = κ k_θr (k_θr = k_δ L², the CJ's spring; K_d for a damping ratio ζ on
//! the rotor and link, K_d = 2ζ√(K_p (J_R + J_link))) to a torque-free rotor (≈ free hub), with
//! the rotor inertia J_R = ρ m_r L²/3. Every run starts in steady motion at the contact.
//!
//! A linear drive is Galilean-invariant along the tip's path: a loop tracking a constant speed
//! sees the impact exactly as a loop holding still, so "switched, same drive" equals "driven"
//! (a check, to the integration's tolerance). What the role switch of the paper changes is the
//! joint's condition: the rig's held joint against the real drive.

use rayon::prelude::*;
use serde::Serialize;

use flexrig_contact::{DampingSpec, Hertz};

use crate::ImpactError;
use crate::drive::{Drive, Gains, HeadSupport, Motor, Person, Placement, Profile};
use crate::driven_cj::{CjSettings, run_driven_cj, run_exact_cj};
use crate::driven_cl::{ClDriveSettings, run_driven_cl};
use crate::exact_link::{ExactSettings, run_exact_cl};
use crate::setup::LinkParams;
use crate::strike::DrivenStrike;

/// The drive's stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case", tag = "drive")]
pub enum DriveLevel {
    /// An ideal position source (the held joint's limit).
    Prescribed,
    /// A PD position loop K_p = κ k_θr.
    Pd {
        /// κ = K_p/k_θr.
        kappa: f64,
    },
    /// No torque (the free hub's limit).
    TorqueFree,
}

/// The link design.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Design {
    /// Rigid link on a torsion spring (series elastic actuator).
    Cj,
    /// Beam clamped to the hub.
    Cl,
}

/// One impact set-up.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoleCase {
    /// A short label.
    pub label: String,
    /// The link.
    pub link: LinkParams,
    /// Head mass \[kg\].
    pub m_h: f64,
    /// The contact law.
    pub contact: Hertz,
    /// Relative speed [m/s].
    pub v0: f64,
}

/// How the table is made.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoleSettings {
    /// Rotor inertia as ρ = J_R/(m_r L²/3).
    pub rotor_ratio: f64,
    /// Damping ratio ζ of the PD loops.
    pub damping_ratio: f64,
    /// The drive levels, stiffest first.
    pub levels: Vec<DriveLevel>,
    /// `Some`: the geometrically exact link (the default; the CL by these settings, the CJ
    /// with their dome); `None`: the linear option (the modal CL by `cl`, the arc-coordinate
    /// CJ).
    pub exact: Option<ExactSettings>,
    /// The linear CL's settings.
    pub cl: ClDriveSettings,
    /// The CJ's settings.
    pub cj: CjSettings,
}

impl RoleSettings {
    /// ρ = 1, ζ = 0.7, prescribed, κ = 1e4, 1e2, 1, 1e-2, torque-free; the exact link at its
    /// default settings with the test bed's dome.
    pub fn standard() -> RoleSettings {
        RoleSettings {
            rotor_ratio: 1.0,
            damping_ratio: 0.7,
            levels: vec![
                DriveLevel::Prescribed,
                DriveLevel::Pd { kappa: 1e4 },
                DriveLevel::Pd { kappa: 1e2 },
                DriveLevel::Pd { kappa: 1.0 },
                DriveLevel::Pd { kappa: 1e-2 },
                DriveLevel::TorqueFree,
            ],
            exact: Some(ExactSettings::DEFAULT),
            cl: ClDriveSettings::DEFAULT,
            cj: CjSettings::DEFAULT,
        }
    }
}

/// One row.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RoleRow {
    /// The case's label.
    pub case: String,
    /// The design.
    pub design: Design,
    /// The drive.
    pub level: DriveLevel,
    /// Head at v0 on the robot at rest, joint held \[N\].
    pub f_test_bed_n: f64,
    /// Robot at v0 under the drive into the head at rest \[N\].
    pub f_driven_n: f64,
    /// f_driven / f_test_bed.
    pub ratio: f64,
    /// Head at v0 on the robot at rest held by the same drive \[N\].
    pub f_switched_same_drive_n: f64,
}

/// The paper's test bed (§VI; the bundled light-load scene's link: L = 0.33802 m, m_r = 51 g,
/// k_θr = 1.2334 N·m/rad, payload 0.1 kg), struck at 0.89 m/s (the operator released from
/// 30°) by the aluminium and the iron operator (block plus a third of the 30 g arm; the
/// skinned-block Hertz fits of §III-B).
pub fn test_bed_cases() -> Result<Vec<RoleCase>, ImpactError> {
    let l = 0.33802;
    let link = LinkParams {
        m_r: 0.051,
        length: l,
        k_delta: 1.2334 / (l * l),
        m_e: 0.1,
    };
    Ok(vec![
        RoleCase {
            label: "test bed, Al operator".into(),
            link,
            m_h: 0.398 + 0.01,
            contact: Hertz::new(7.359e7, 1.961)?,
            v0: 0.89,
        },
        RoleCase {
            label: "test bed, iron operator".into(),
            link,
            m_h: 4.008 + 0.01,
            contact: Hertz::new(9.642e7, 2.002)?,
            v0: 0.89,
        },
    ])
}

/// The Fig. 6 design cases (m_r = 10 kg, L = 1 m, k_c = 1e8 N/m, v0 = 2 m/s) with exponent `n`,
/// labelled as a reader writes them ("k_δ = 10⁸ N/m").
pub fn fig6_cases(n: f64) -> Result<Vec<RoleCase>, ImpactError> {
    flexrig_lumped::fig6::cases()
        .iter()
        .map(|c| {
            Ok(RoleCase {
                label: format!(
                    "Fig. 6: m_h = {} kg, k_δ = {} N/m, m_e = {} kg, n = {n}",
                    c.m_h,
                    flexrig_contact::validate::sci_label(c.k_delta),
                    c.m_e
                ),
                link: LinkParams {
                    m_r: flexrig_lumped::fig6::M_R,
                    length: 1.0,
                    k_delta: c.k_delta,
                    m_e: c.m_e,
                },
                m_h: c.m_h,
                contact: Hertz::new(flexrig_lumped::fig6::K_C, n)?,
                v0: flexrig_lumped::fig6::V0,
            })
        })
        .collect()
}

fn drive_for(
    case: &RoleCase,
    level: DriveLevel,
    speed: f64,
    settings: &RoleSettings,
) -> Result<Drive, ImpactError> {
    let link = case.link;
    let l = link.length;
    let j_link = link.cj_tip_mass() * l * l;
    let j_r = settings.rotor_ratio * link.m_r * l * l / 3.0;
    // N = 10: J_m = J_R/100
    let motor = Motor::new(j_r / 100.0, 10.0, 0.0)?;
    match level {
        DriveLevel::Prescribed => Drive::trajectory(motor, Profile::Steady { speed }),
        DriveLevel::TorqueFree => Drive::torque_free(motor, speed),
        DriveLevel::Pd { kappa } => {
            let kp = kappa * link.k_theta();
            let kd = 2.0 * settings.damping_ratio * (kp * (j_r + j_link)).sqrt();
            Drive::controller(
                motor,
                Profile::Steady { speed },
                Gains::position_pd(kp, kd),
                None,
            )
        }
    }
}

fn peak(
    case: &RoleCase,
    design: Design,
    drive: Drive,
    head_speed: f64,
    settings: &RoleSettings,
) -> Result<f64, ImpactError> {
    let strike = DrivenStrike {
        link: case.link,
        drive,
        person: Person {
            m_h: case.m_h,
            support: HeadSupport::Free,
            contact: case.contact,
            damping: DampingSpec::NONE,
            speed: head_speed,
        },
        placement: Placement::Angle { angle: 0.0 },
        horizon_s: 1.0,
    };
    let out = match (design, &settings.exact) {
        (Design::Cj, Some(exact)) => run_exact_cj(&strike, &settings.cj, &exact.dome)?,
        (Design::Cl, Some(exact)) => run_exact_cl(&strike, exact)?,
        (Design::Cj, None) => run_driven_cj(&strike, &settings.cj)?,
        (Design::Cl, None) => run_driven_cl(&strike, &settings.cl)?,
    };
    Ok(out.contact.peak_force_n)
}

/// The table: every case × design × level, in parallel (case-major, then design, then level).
pub fn role_switch_table(
    cases: &[RoleCase],
    settings: &RoleSettings,
) -> Result<Vec<RoleRow>, ImpactError> {
    if !(settings.rotor_ratio.is_finite() && settings.rotor_ratio > 0.0) {
        return Err(ImpactError::invalid(
            "rotor_ratio",
            settings.rotor_ratio,
            "a ratio > 0",
        ));
    }
    if !(settings.damping_ratio.is_finite() && settings.damping_ratio >= 0.0) {
        return Err(ImpactError::invalid(
            "damping_ratio",
            settings.damping_ratio,
            "a ratio ≥ 0",
        ));
    }
    let mut jobs = Vec::new();
    for case in cases {
        for design in [Design::Cj, Design::Cl] {
            for &level in &settings.levels {
                jobs.push((case, design, level));
            }
        }
    }
    // the test bed's held joint, once per case and design
    let held: Vec<(usize, Design, f64)> = cases
        .par_iter()
        .enumerate()
        .flat_map(|(i, case)| {
            [Design::Cj, Design::Cl].into_par_iter().map(move |d| {
                let drive = drive_for(case, DriveLevel::Prescribed, 0.0, settings)?;
                Ok((i, d, peak(case, d, drive, case.v0, settings)?))
            })
        })
        .collect::<Result<_, ImpactError>>()?;
    jobs.par_iter()
        .map(|(case, design, level)| {
            let i = cases
                .iter()
                .position(|c| std::ptr::eq(c, *case))
                .unwrap_or(0);
            let f_test_bed = held
                .iter()
                .find(|(j, d, _)| *j == i && d == design)
                .map(|h| h.2)
                .unwrap_or(f64::NAN);
            let speed = case.v0 / case.link.length;
            let f_driven = peak(
                case,
                *design,
                drive_for(case, *level, speed, settings)?,
                0.0,
                settings,
            )?;
            let f_switched = peak(
                case,
                *design,
                drive_for(case, *level, 0.0, settings)?,
                case.v0,
                settings,
            )?;
            Ok(RoleRow {
                case: case.label.clone(),
                design: *design,
                level: *level,
                f_test_bed_n: f_test_bed,
                f_driven_n: f_driven,
                ratio: f_driven / f_test_bed,
                f_switched_same_drive_n: f_switched,
            })
        })
        .collect()
}
