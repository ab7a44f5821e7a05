//! The simulation method on a driven scene: the permissible commanded speed of a driven robot
//! (a scene file with a `[drive]` section, docs/driven.md) near a body region.
//!
//! The scene fixes everything but the speed: the link (CJ or CL, m_r, L, k_δ, m_e), the drive
//! (motor, gear, controller or trajectory, the profile's shape), the person (head mass, support,
//! the skin's Hertz law f = k_c δ_c^n, paper Eq. 4) and the placement. The search variable is
//! the commanded joint speed ω_c of the profile (`drive.command.profile.speed`), quoted as the
//! commanded tip speed v = L ω_c; the whole driven strike (the ramp, the settling, the approach
//! and the contact with the drive's torque acting) is simulated at each speed by flexrig-impact's
//! driven solvers by the scene's link model with the scene's dome (exact, the default: the CJ
//! by DOP853 at `cj_rtol`, the CL as the corotational beam at its default settings; the linear
//! option: the CL by the exact modal integrator at `tol` in the contact and 10 × `tol` before
//! it), and the speed at which the first contact's
//! peak force reaches the region's force limit (or the force at which the mean pressure of the
//! contact-area model reaches the pressure limit) is found by the Illinois root search on ln v
//! to `root_rtol` ([`crate::safety::simulation::speed_at_ratio`]).
//!
//! The contact kind follows the scene's support: a head against a wall is clamped
//! (quasi-static limits, ISO/TS 15066:2016 Table A.2's quasi-static values), a free head or a
//! head on a neck is transient (the transient multiplier), and a transient contact where the
//! body model does not permit one (skull and forehead, face) is refused with its clause before
//! any run.

use flexrig_impact::drive::{Drive, DriveCommand, HeadSupport, Profile};
use flexrig_impact::driven_cj::{CjSettings, run_driven_cj_until, run_exact_cj_until};
use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl_until};
use flexrig_impact::exact_link::{ExactSettings, run_exact_cl_until};
use flexrig_impact::{DrivenOutcome, DrivenStrike};
use flexrig_safety::{ContactKind, EnergyContact, Limits, PressureCrossing};

use crate::Error;
use crate::driven::scene::{DrivenScene, note_text};
use crate::driven::strike::{LinkModel, StrikeDesign};
use crate::safety::simulation::{
    ContactsAtRoot, Peaks, RootStep, SCAN_START_OF_GUESS, SCENE_REFINE_RUNS, Scan, SceneSimulation,
    SimulationSettings, refine, scan_up,
};

/// A driven scene loaded for the safety verdict.
#[derive(Debug, Clone)]
pub struct SafetyScene {
    /// Where it came from (`bundled driven_cl_wall` or the file's path).
    pub origin: String,
    /// The checked scene.
    pub scene: DrivenScene,
}

/// A scene given as the design of `flexrig safety`.
#[derive(Debug, Clone)]
pub enum SafetyDesignScene {
    /// A driven scene: its commanded speed is searched.
    Driven(Box<SafetyScene>),
    /// A test-bed scene: the operator's speed at contact is searched
    /// ([`crate::safety::test_bed`]).
    TestBed(Box<crate::safety::test_bed::TestBedScene>),
}

/// Resolves and parses `given` (`--scene`: a bundled scene's name or a scene file's path): a
/// driven scene (with a `[drive]` section) or a test-bed scene.
pub fn load_any(given: &str) -> Result<SafetyDesignScene, Error> {
    let source = crate::testbed::scenes::resolve("--scene", std::path::Path::new(given))?;
    if crate::driven::scene::is_driven_text(&source.text) {
        return Ok(SafetyDesignScene::Driven(Box::new(load(given)?)));
    }
    Ok(SafetyDesignScene::TestBed(Box::new(
        crate::safety::test_bed::TestBedScene::parse(&source.origin, &source.text)?,
    )))
}

/// Resolves and parses the driven scene `given` (`--scene`: a bundled scene's name or a scene
/// file's path); a scene without a `[drive]` section is refused.
pub fn load(given: &str) -> Result<SafetyScene, Error> {
    let source = crate::testbed::scenes::resolve("--scene", std::path::Path::new(given))?;
    if !crate::driven::scene::is_driven_text(&source.text) {
        return Err(Error::InvalidArgument {
            arg: "--scene".into(),
            value: given.into(),
            allowed: "a driven scene (a scene file with a [drive] section, e.g. \
                      driven_cl_wall, driven_cj_free_head): its commanded speed is searched"
                .into(),
        });
    }
    let scene = DrivenScene::parse(&source.text)?;
    if scene.strike.drive.profile().is_none() {
        return Err(Error::InvalidArgument {
            arg: "--scene".into(),
            value: given.into(),
            allowed: "a driven scene whose drive follows a commanded profile (a trajectory or a \
                      controller): an open-loop torque has no commanded speed to search"
                .into(),
        });
    }
    Ok(SafetyScene {
        origin: source.origin,
        scene,
    })
}

impl SafetyScene {
    /// The contact kind of the scene's support: a wall clamps the head (quasi-static), a free
    /// head or one on a neck recoils (transient).
    pub fn contact_kind(&self) -> ContactKind {
        match self.scene.strike.person.support {
            HeadSupport::Wall => ContactKind::QuasiStatic,
            HeadSupport::Free | HeadSupport::Neck { .. } => ContactKind::Transient,
        }
    }

    /// Link length L \[m\].
    pub fn length(&self) -> f64 {
        self.scene.strike.link.length
    }

    /// The commanded tip speed L ω_c of the scene as written [m/s].
    pub fn commanded_tip_speed(&self) -> f64 {
        let omega = self
            .scene
            .strike
            .drive
            .profile()
            .map_or(0.0, |p| p.final_speed());
        self.length() * omega.abs()
    }

    /// The strike with the profile's final speed set to give the commanded tip speed `v` [m/s]
    /// (the sign of the written speed kept).
    fn strike_at(&self, v: f64) -> Result<DrivenStrike, Error> {
        let s = &self.scene.strike;
        let sign = match s.drive.profile().map(|p| p.final_speed()) {
            Some(w) if w < 0.0 => -1.0,
            _ => 1.0,
        };
        let omega = sign * v / s.link.length;
        let command = match s.drive.command().clone() {
            DriveCommand::Trajectory { profile } => DriveCommand::Trajectory {
                profile: with_speed(profile, omega),
            },
            DriveCommand::Controller {
                profile,
                gains,
                torque_limit,
            } => DriveCommand::Controller {
                profile: with_speed(profile, omega),
                gains,
                torque_limit,
            },
            open @ DriveCommand::OpenLoop { .. } => open,
        };
        let drive = Drive::new(*s.drive.motor(), command)?;
        let mut strike = s.strike();
        strike.drive = drive;
        Ok(strike)
    }

    /// The driven strike at commanded tip speed `v` [m/s] by the scene's link model and dome,
    /// with the run tolerances of `settings` (`cj_rtol` for the CJ; the linear CL: `tol` in the
    /// contact, 10 × `tol` before it). Every model follows every contact until the bodies part
    /// for good (the CJ and the exact CL: a free head beyond the dome's reach) or the scene's
    /// window (`horizon_s`) closes, the drive keeping its command throughout (no reaction to the
    /// collision); along the linear models' straight path the tip can always come back, so
    /// those runs go on to the window.
    pub fn run_at(
        &self,
        v: f64,
        settings: &SimulationSettings,
        stop: &std::sync::atomic::AtomicBool,
    ) -> Result<DrivenOutcome, Error> {
        crate::safety::simulation::check_stop(stop)?;
        let strike = self.strike_at(v)?;
        let d = &self.scene.strike;
        Ok(match (d.design, d.link_model) {
            (StrikeDesign::Cj, LinkModel::Exact) => run_exact_cj_until(
                &strike,
                &CjSettings {
                    rtol: settings.cj_rtol,
                    every_contact: true,
                    ..CjSettings::DEFAULT
                },
                &d.dome,
                stop,
            )?,
            (StrikeDesign::Cl, LinkModel::Exact) => run_exact_cl_until(
                &strike,
                &ExactSettings {
                    dome: d.dome,
                    every_contact: true,
                    ..ExactSettings::DEFAULT
                },
                stop,
            )?,
            (StrikeDesign::Cj, LinkModel::Linear) => run_driven_cj_until(
                &strike,
                &CjSettings {
                    rtol: settings.cj_rtol,
                    every_contact: true,
                    ..CjSettings::DEFAULT
                },
                stop,
            )?,
            (StrikeDesign::Cl, LinkModel::Linear) => run_driven_cl_until(
                &strike,
                &ClDriveSettings {
                    tol: settings.tol,
                    approach_tol: (10.0 * settings.tol).min(1e-3),
                    every_contact: true,
                    ..ClDriveSettings::DEFAULT
                },
                stop,
            )?,
        })
    }
}

/// The profile with final joint speed `omega` [rad/s] (its shape kept).
fn with_speed(profile: Profile, omega: f64) -> Profile {
    match profile {
        Profile::Steady { .. } => Profile::Steady { speed: omega },
        Profile::SmoothRamp { ramp_time, .. } => Profile::SmoothRamp {
            speed: omega,
            ramp_time,
        },
        Profile::Trapezoid { acceleration, .. } => Profile::Trapezoid {
            speed: omega,
            acceleration,
        },
        Profile::SpinUp { time, .. } => Profile::SpinUp { speed: omega, time },
    }
}

/// The largest peak force \[N\] over the contacts of `scene` at commanded tip speed `v` [m/s]
/// ([`SafetyScene::run_at`]).
pub fn peak_force(
    scene: &SafetyScene,
    v: f64,
    settings: &SimulationSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<f64, Error> {
    Ok(scene
        .run_at(v, settings, stop)?
        .largest_contact()
        .1
        .peak_force_n)
}

/// The smallest commanded tip speed [m/s] at which the largest contact of `scene` reaches
/// `force` \[N\]: the scan from below ([`scan_up`]) from `guess` × [`SCAN_START_OF_GUESS`]
/// (at least 1e-4 m/s); if the limit is reached there already, the start is halved (at most
/// ten times, down to 1/65 536 of the guess) until it is not, and the crossing refined
/// between; reached even there: 0 (the drive presses harder than the limit at any speed).
/// A speed the scene cannot be run at (the person placed beyond the link's reach, the drive
/// unable to arrive in the window) ends the scan: the answer is then the fastest speed run,
/// a lower bound ([`SceneSpeed::reached`] false, the reason kept).
fn smallest_scene_speed(
    scene: &SafetyScene,
    force: f64,
    guess: f64,
    settings: &SimulationSettings,
    stop: &std::sync::atomic::AtomicBool,
    peaks: &Peaks,
    trace: Option<&mut Vec<RootStep>>,
) -> Result<SceneSpeed, Error> {
    let mut fastest = 0.0_f64;
    let run = |v: f64| peak_force(scene, v, settings, stop);
    let mut ratio = |v: f64| -> Result<f64, Error> {
        let p = peaks.at(v, run)?;
        fastest = fastest.max(v);
        Ok(p / force)
    };
    // the scan's next speeds side by side (the answer does not depend on it)
    let mut ahead = |speeds: &[f64]| peaks.prefetch(speeds, run);
    let start = (clamp_guess(guess) * SCAN_START_OF_GUESS).max(1e-4);
    let found = match scan_up(start, settings.root_rtol, &mut ratio, &mut ahead, trace) {
        Ok(Scan::Crossing(v)) => Ok(v),
        Ok(Scan::Never) => Ok(f64::INFINITY),
        Ok(Scan::AtStart) => (|| {
            let (mut above, mut r_above) = (start, ratio(start)?);
            for _ in 0..10 {
                let below = 0.5 * above;
                let r = ratio(below)?;
                if r < 1.0 {
                    return refine(
                        (below, r),
                        (above, r_above),
                        settings.root_rtol,
                        SCENE_REFINE_RUNS,
                        &mut ratio,
                    );
                }
                (above, r_above) = (below, r);
            }
            Ok(0.0)
        })(),
        Err(e) => Err(e),
    };
    match found {
        Ok(v) => Ok(SceneSpeed {
            speed: v,
            reached: v.is_finite(),
            beyond: None,
        }),
        Err(Error::Impact(e @ flexrig_impact::ImpactError::InvalidParameter { .. }))
            if fastest > 0.0 =>
        {
            Ok(SceneSpeed {
                speed: fastest,
                reached: false,
                beyond: Some(e.to_string()),
            })
        }
        Err(e) => Err(e),
    }
}

/// What the scan of a driven scene found.
#[derive(Debug, Clone, PartialEq)]
struct SceneSpeed {
    /// The smallest speed at which the limit is reached [m/s], or (not reached) the fastest
    /// speed run: a lower bound.
    speed: f64,
    /// The limit was reached (false: not up to `speed`, +∞ or the scene's end).
    reached: bool,
    /// Why the scan stopped before reaching the limit: the scene could not be run faster.
    beyond: Option<String>,
}

/// The permissible commanded tip speed of `scene` under `limits` (force; pressure through
/// `energy`'s contact-area model, [`EnergyContact::force_at_pressure`]): each the smallest speed
/// at which the largest contact reaches the limit ([`smallest_scene_speed`]), the scans started
/// from the energy method's speeds `guess_force` and `guess_pressure` [m/s] scaled down.
pub fn simulate(
    scene: &SafetyScene,
    limits: &Limits,
    energy: &EnergyContact,
    guess_force: f64,
    guess_pressure: Option<f64>,
    settings: &SimulationSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<SceneSimulation, Error> {
    settings.validate()?;
    let peaks = Peaks::default();
    let force = limits.force;
    let mut force_search = Vec::new();
    // both scans start on one grid, from the lower of the energy method's two speeds
    let start_guess = guess_pressure.map_or(guess_force, |g| g.min(guess_force));
    let force_scan = smallest_scene_speed(
        scene,
        force,
        start_guess,
        settings,
        stop,
        &peaks,
        Some(&mut force_search),
    )?;
    let by_force = force_scan.speed;
    let mut pressure_beyond = None;
    let by_pressure = match (limits.pressure, guess_pressure) {
        (Some(p), Some(_)) => Some(match energy.force_at_pressure(p) {
            // the same grid as the force's scan: its runs are reused
            Some(PressureCrossing::AtForce(f)) => {
                let scan =
                    smallest_scene_speed(scene, f, start_guess, settings, stop, &peaks, None)?;
                pressure_beyond = scan.beyond.map(|why| (scan.speed, why));
                scan.speed
            }
            Some(PressureCrossing::Always) => 0.0,
            Some(PressureCrossing::Never) | None => f64::INFINITY,
        }),
        _ => None,
    };
    let judged = if by_force.is_finite() && by_force > 0.0 {
        by_force
    } else {
        clamp_guess(guess_force)
    };
    let at_root = scene.run_at(judged, settings, stop)?;
    let runs = peaks.runs() + 1;
    let (governing, largest) = at_root.largest_contact();
    let s = &scene.scene.strike;
    Ok(SceneSimulation {
        scene: scene.origin.clone(),
        name: scene.scene.name.clone(),
        design: s.design,
        support: match s.person.support {
            HeadSupport::Free => "free",
            HeadSupport::Neck { .. } => "neck",
            HeadSupport::Wall => "wall",
        },
        scene_tip_speed_mps: scene.commanded_tip_speed(),
        by_force_mps: by_force,
        by_pressure_mps: by_pressure,
        approach_speed_at_root_mps: at_root.approach_speed_mps,
        peak_force_at_root_n: largest.peak_force_n,
        contacts_at_root: Some(ContactsAtRoot {
            contacts: at_root.contacts.len(),
            governing,
            time_of_peak_s: largest.time_of_peak_s,
            ended: at_root.ended,
        }),
        notes: at_root
            .notes
            .iter()
            .map(note_text)
            .chain(force_scan.beyond.map(|why| {
                format!(
                    "the force limit was not reached up to {} m/s, the fastest commanded speed \
                     the scene can be run at (faster: {why}); the speed is a lower bound",
                    flexrig_contact::validate::display(by_force)
                )
            }))
            .chain(pressure_beyond.map(|(v, why)| {
                format!(
                    "the pressure limit was not reached up to {} m/s, the fastest commanded \
                     speed the scene can be run at (faster: {why}); that speed is a lower bound",
                    flexrig_contact::validate::display(v)
                )
            }))
            .collect(),
        force_search,
        runs,
        run_tol: match s.design {
            StrikeDesign::Cj => settings.cj_rtol,
            StrikeDesign::Cl => settings.tol,
        },
        root_rtol: settings.root_rtol,
        link_model: link_model_words(s, settings),
        release_angle_at_root_deg: None,
        limit_reached: force_scan.reached,
    })
}

/// The contacts of the run at the judged speed, in words: how many, which one governs and
/// when, how the run ended.
pub fn contacts_words(c: &crate::safety::simulation::ContactsAtRoot) -> String {
    use flexrig_impact::RunEnd;
    let d = flexrig_contact::validate::display;
    let end = match c.ended {
        RunEnd::PartedForGood(t) => format!(
            "the bodies' parting for good at {} s (the head beyond the dome's reach, moving \
             away)",
            d(t)
        ),
        RunEnd::Window(t) => format!(
            "the close of the scene's window at {} s (horizon_s; the drive kept its command, \
             no reaction to the collision)",
            d(t)
        ),
        RunEnd::Rebound(t) => format!(
            "the operator's turn at the apex of its rebound at {} s (every contact of the \
             swing; a later one would be the pendulum's return swing)",
            d(t)
        ),
        RunEnd::FirstSeparation => "the first separation".to_string(),
        RunEnd::StepBudget(t) => format!("the run's step budget at {} s", d(t)),
    };
    format!(
        "the largest peak in contact {} of {}, at {} s; the run ended at {end}",
        c.governing,
        c.contacts,
        d(c.time_of_peak_s)
    )
}

/// How the driven strike of `s` simulates its link, in words (the report's method c).
fn link_model_words(
    s: &crate::driven::strike::StrikeDescription,
    settings: &SimulationSettings,
) -> String {
    let dome = format!(
        "the scene's dome of radius {} m, its apex {} m ahead of the link's axis",
        flexrig_contact::validate::display(s.dome.radius_m),
        flexrig_contact::validate::display(s.dome.standoff_m)
    );
    match (s.design, s.link_model) {
        (StrikeDesign::Cj, LinkModel::Exact) => format!(
            "the compliant joint: the rigid link on its torsion spring turning with the hub, \
             {dome}, by DOP853 at relative tolerance {:e}",
            settings.cj_rtol
        ),
        (StrikeDesign::Cl, LinkModel::Exact) => format!(
            "the compliant link: the geometrically exact (corotational) beam clamped to the \
             driven hub, its mesh doubled until two meshes agree, {dome}"
        ),
        (StrikeDesign::Cj, LinkModel::Linear) => format!(
            "the compliant joint: the rigid link on its torsion spring, the contact along the \
             tip's path (the linear option), by DOP853 at relative tolerance {:e}",
            settings.cj_rtol
        ),
        (StrikeDesign::Cl, LinkModel::Linear) => format!(
            "the compliant link: the linear Euler–Bernoulli beam by its modes and the exact \
             modal integrator at force-hold tolerance {:e}, the contact along the tip's path \
             (the linear option)",
            settings.tol
        ),
    }
}

/// A search's starting speed within [1e-4, 50] m/s.
fn clamp_guess(v: f64) -> f64 {
    if v.is_finite() {
        v.clamp(1e-4, 50.0)
    } else {
        1.0
    }
}
