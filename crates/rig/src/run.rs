//! The run loop: a named pipeline per step (loads → integrate → synchronise → events → check →
//! sensors), a step policy that crosses the free flight in a few adaptive steps with the contact
//! onset located as an event ([`crate::free_flight`]; or, with `solver.swing = "fixed"`, takes
//! large Rapier steps in the swing and lands on the onset), resolves the contact on its own time
//! scale, and the stop condition of the scene. How the contact force is exchanged within a step
//! (second order; implicit for the compliant link) is in [`crate::coupling`].
//!
//! **One file, one concept** (about 1 750 lines before its tests): the run loop of a `Simulation` —
//! its step pipeline, step policy, events and stop condition share the simulation's private state;
//! the adaptive contact's side of it lives in `run/adaptive_contact`.

use flexrig_contact::math::{Pose, Vector};
use flexrig_contact::{
    BodyKinematics, ContactCallback, ContactSample, DomeBlockContact, Materials,
};
use serde::Serialize;

use crate::RigError;
use crate::beam_link::{BeamLink, LinkCheckpoint, LinkVariant};
use crate::coupling::{HingeMotion, TipContact};
use crate::free_flight::{DIM, FlightSensors, FlightStep, FreeFlight, FreeHinges, SwingPolicy};
use crate::geometry::RigGeometry;
use crate::hinge::HingeState;
use crate::joint_drive::{DriveFrame, DriveSummary, RotorSync};
use crate::limits::CONTACT_TIME_FACTOR;
use crate::scene::{ContactPolicy, Design, Scene, StopSpec};
use crate::sensors::{Reading, Sampler, SensorSample};
use crate::world::RapierRig;

mod adaptive_contact;
use adaptive_contact::PeakSearch;

/// What a step reached (events are part of the step result).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StepOutcome {
    /// An ordinary step.
    Advanced,
    /// The dome and the block touched during this step.
    ContactOnset,
    /// The contact force passed its maximum.
    Peak,
    /// The dome and the block separated.
    Separation,
}

/// The state of the rig after a step, handed to a [`Recorder`].
#[derive(Debug, Clone, Copy)]
pub struct Frame<'a> {
    /// Time \[s\].
    pub t: f64,
    /// Step just taken \[s\].
    pub dt: f64,
    /// What the step reached.
    pub outcome: StepOutcome,
    /// Operator hinge (rate synchronised with the angle).
    pub operator: HingeState,
    /// Robot hinge (CJ; rate synchronised with the angle).
    pub robot: Option<HingeState>,
    /// Operator body pose (origin at the pivot).
    pub operator_pose: Pose,
    /// Robot body pose (CJ) or tip section pose (CL).
    pub dome_body_pose: Pose,
    /// The beam (CL).
    pub beam: Option<&'a BeamLink>,
    /// The contact at the end of the step, if touching.
    pub contact: Option<ContactSample>,
    /// Total mechanical energy \[J\] (kinetic, gravity, spring, beam strain, contact), at
    /// synchronised positions and velocities.
    pub energy: f64,
    /// Sensor samples taken during this step.
    pub samples: &'a [SensorSample],
    /// The drive on the robot joint (`robot.drive`): commanded and actual joint angle and
    /// speed, motor torque, the link's elastic moment.
    pub drive: Option<DriveFrame>,
}

/// Receives every step (e.g. an MCAP logger). Implementations must not panic; an error stops
/// the run.
pub trait Recorder {
    /// Called after every step.
    fn frame(&mut self, _frame: &Frame<'_>) -> Result<(), RigError> {
        Ok(())
    }

    /// The period \[s\] at which the recorder wants the bodies' poses between the steps of the
    /// adaptive free swing (whose steps are long: a dozen over a swing), or `None` (the
    /// default) for the steps alone. The poses come from the integrator's dense output: the
    /// run's numbers are the same with or without them.
    fn pose_period(&self) -> Option<f64> {
        None
    }

    /// Called, when [`Recorder::pose_period`] asks for it, at each multiple of the period inside
    /// a step of the adaptive free swing (before that step's [`Recorder::frame`]), with the
    /// state interpolated on the dense output: `dt` is the time since the step's start, there
    /// is no contact and no sensor sample (the samples come with the step's frame).
    fn between(&mut self, _frame: &Frame<'_>) -> Result<(), RigError> {
        Ok(())
    }

    /// Which sensor samples of the adaptive free swing the recorder reads from
    /// [`Frame::samples`] when the run samples lean ([`Simulation::with_lean_samples`]; a full
    /// run hands every sample whatever this says). The default: every sample.
    fn swing_samples(&self) -> SwingSamples {
        SwingSamples::Every
    }

    /// With [`SwingSamples::Chosen`]: whether the recorder wants the swing's sample at time `t`
    /// \[s\] (asked in time order for each sample time of a free-swing step, before that step's
    /// frame, which then carries the chosen samples).
    fn wants_swing_sample(&mut self, _t: f64) -> bool {
        true
    }
}

/// Which sensor samples of the free swing a [`Recorder`] reads (a lean run computes only
/// those; the contact's samples and those of Rapier's steps always come).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SwingSamples {
    /// Every sample.
    Every,
    /// None.
    None,
    /// Those [`Recorder::wants_swing_sample`] asks for.
    Chosen,
}

/// A recorder that keeps nothing.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoRecorder;

impl Recorder for NoRecorder {
    fn swing_samples(&self) -> SwingSamples {
        SwingSamples::None
    }
}

/// One contact of a run, from onset to separation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactEvent {
    /// Time of contact onset \[s\] (interpolated within the onset step).
    pub onset_time_s: f64,
    /// Approach speed normal to the contact at onset [m/s] (interpolated to the onset time).
    pub impact_velocity_mps: f64,
    /// Peak contact force \[N\] (vertex of the parabola through the three largest step values).
    pub peak_force_n: f64,
    /// Time of the peak \[s\].
    pub time_of_peak_s: f64,
    /// Largest indentation \[m\].
    pub max_indentation_m: f64,
    /// Impulse of the contact force ∫ f dt [N·s] (trapezoidal, as the integrator applies it).
    pub impulse_n_s: f64,
    /// Contact duration \[s\] (interpolated at both ends); `None` if the run stopped in contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub duration_s: Option<f64>,
    /// Relative normal velocity at separation [m/s] (positive when parting); `None` if the run
    /// stopped in contact.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separation_velocity_mps: Option<f64>,
    /// Mechanical energy just before the onset step \[J\].
    pub energy_before_j: f64,
    /// Mechanical energy at the end of the separation step \[J\]; equal to `energy_before_j` for
    /// an undamped contact up to the integration error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_after_j: Option<f64>,
}

/// A recorder that keeps nothing and stops the run (with [`RigError::Interrupted`]) at the
/// first step after its flag is set, e.g. by a Ctrl-C handler.
#[derive(Debug, Clone, Default)]
pub struct Interruptible(pub std::sync::Arc<std::sync::atomic::AtomicBool>);

impl Recorder for Interruptible {
    fn frame(&mut self, frame: &Frame<'_>) -> Result<(), RigError> {
        if self.0.load(std::sync::atomic::Ordering::Relaxed) {
            return Err(RigError::Interrupted { t: frame.t });
        }
        Ok(())
    }

    fn swing_samples(&self) -> SwingSamples {
        SwingSamples::None
    }
}

/// Result of a run. The top-level contact quantities are those of the first contact; `contacts`
/// lists every contact of the run.
#[derive(Debug, Clone, Serialize)]
pub struct RunSummary {
    /// Scene name.
    pub scene: String,
    /// CJ or CL.
    pub design: Design,
    /// Peak contact force \[N\] (vertex of the parabola through the three largest step values).
    pub peak_force_n: f64,
    /// Time of the peak \[s\].
    pub time_of_peak_s: f64,
    /// Approach speed normal to the contact at onset [m/s].
    pub impact_velocity_mps: f64,
    /// Relative normal velocity at separation [m/s] (positive when parting); the coefficient of
    /// restitution is its ratio to `impact_velocity_mps`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub separation_velocity_mps: Option<f64>,
    /// Time of contact onset \[s\] (interpolated within the onset step).
    pub onset_time_s: f64,
    /// Contact duration \[s\] (interpolated at both ends); `None` if the run stopped before
    /// separation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_duration_s: Option<f64>,
    /// Largest indentation \[m\].
    pub max_indentation_m: f64,
    /// Impulse of the contact force ∫ f dt [N·s].
    pub impulse_n_s: f64,
    /// Steps taken (all), and within contact.
    pub steps: usize,
    /// Steps taken in contact: those that end in contact (the step that ends at or past the
    /// separation is counted in `steps` only), of either contact integration.
    pub contact_steps: usize,
    /// How the contact was integrated: `"adaptive"` (DOP853 on the two hinges) or `"fixed"`
    /// (Rapier's steps); the scene's `solver.contact` resolved, `"auto"` taking the adaptive
    /// contact for a CJ without a drive and with the adaptive swing.
    pub contact_integration: ContactPolicy,
    /// Step size used in the first contact \[s\] (each later contact is sized by its own
    /// impact speed); with the adaptive contact the Hertz contact time over
    /// `solver.contact_steps`, which the adaptive steps do not use (`contact_steps` counts
    /// those).
    pub contact_step_s: f64,
    /// Mechanical energy at the start \[J\] (for a release from rest: M g l_c (1 − cos θ₀)).
    pub energy_initial_j: f64,
    /// Mechanical energy at the end \[J\].
    pub energy_final_j: f64,
    /// Mechanical energy just before the first contact and just after its separation \[J\];
    /// equal for an undamped contact up to the integration error.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy_through_contact_j: Option<(f64, f64)>,
    /// Every contact of the run, in order (the first is the one of the top-level keys).
    pub contacts: Vec<ContactEvent>,
    /// Simulated time \[s\].
    pub duration_s: f64,
    /// Plausibility warnings of the scene (empty: none; [`crate::plausibility`]).
    pub warnings: Vec<crate::plausibility::Warning>,
    /// Severity of the run from its sensor samples ([`crate::severity::of_samples`]): peak force,
    /// peak pressure (Hertz sphere and thin layer under the dome), energy transferred, the
    /// operator block's acceleration and its HIC15/HIC36; absent when the run took fewer than
    /// two samples.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub severity: Option<flexrig_safety::Severity>,
    /// Sensor samples; of a lean run ([`Simulation::with_lean_samples`]) those from the first
    /// contact's onset minus its duration to its end plus its duration (the full run's there).
    #[serde(skip)]
    pub samples: Vec<SensorSample>,
    /// How many sensor samples the run took (`samples.len()` of a full run; a lean run
    /// computes most of them only on demand, its count is the same).
    #[serde(skip)]
    pub sample_count: usize,
    /// What the drive on the robot joint did (`robot.drive`): the motor's work, the friction,
    /// the largest joint torque, the link's speed at the onset.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drive: Option<DriveSummary>,
}

/// Settings of the simulation that are not in the scene file (defaults are the documented
/// choices; tests vary them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunOptions {
    /// Generalized-α spectral radius for the beam (1: no numerical dissipation).
    pub beam_rho_inf: f64,
    /// Relative energy growth that counts as instability.
    pub energy_growth_limit: f64,
    /// The beam used for design `cl`.
    pub cl_link: LinkVariant,
}

impl RunOptions {
    /// The defaults, usable in constants: ρ∞ = 1 (no numerical dissipation), instability at 5 %
    /// energy growth, the compliant link for design `cl`.
    pub const DEFAULT: RunOptions = RunOptions {
        beam_rho_inf: 1.0,
        energy_growth_limit: 0.05,
        cl_link: LinkVariant::Compliant,
    };
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions::DEFAULT
    }
}

/// The robot side: the rigid link lives in Rapier; the compliant link is an FE beam.
#[derive(Debug)]
enum RobotSide {
    Rigid { spring: f64 },
    Beam(Box<BeamLink>),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    Swing,
    Contact,
    After,
}

/// The hinges and the contact at one instant, with the rates synchronised to the angles (see
/// [`crate::coupling`]).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Synced {
    operator: HingeState,
    /// Operator angular acceleration [rad/s²] (gravity and contact).
    operator_accel: f64,
    /// Robot hinge and its angular acceleration (CJ).
    robot: Option<(HingeState, f64)>,
    contact: Option<ContactSample>,
    /// The drive's hub (`robot.drive`).
    rotor: Option<RotorSync>,
}

/// A running simulation of one scene.
#[derive(Debug)]
pub struct Simulation<'s> {
    scene: &'s Scene,
    options: RunOptions,
    geometry: RigGeometry,
    rapier: RapierRig,
    robot: RobotSide,
    contact: DomeBlockContact,
    t: f64,
    /// The last step \[s\] (0 before the first): Rapier's rates lag the angles by half of it.
    h_prev: f64,
    now: Synced,
    phase: Phase,
    contact_step: f64,
    /// The first contact's step \[s\] (later contacts are sized by their own impact speed).
    first_contact_step: f64,
    previous_gap: Option<(f64, f64)>,
    onset_tolerance: f64,
    indentation_scale: f64,
    last: Reading,
    sampler: Sampler,
    stats: Stats,
    /// The adaptive free flight in progress (`solver.swing = "adaptive"`, out of contact; and
    /// in contact with `solver.contact = "adaptive"`).
    flight: Option<FreeFlight>,
    /// The adaptive contact in progress: the flight integrates the contact, and its peak.
    peak_search: Option<PeakSearch>,
    /// The compliant link before the step in progress, for the drive's torque limit to take
    /// the step again on its other branch (a buffer reused every step).
    retake: Option<LinkCheckpoint>,
}

/// The state a step can be taken again from.
#[derive(Debug, Clone)]
struct Snapshot {
    t: f64,
    h_prev: f64,
    now: Synced,
    operator: HingeState,
    robot: Option<HingeState>,
    rotor: Option<HingeState>,
    beam: Option<LinkCheckpoint>,
}

/// The contact in progress.
#[derive(Debug, Clone, Copy)]
struct OpenContact {
    onset_time: f64,
    impact_velocity: f64,
    energy_before: f64,
    force_history: [(f64, f64); 3],
    peak: Option<(f64, f64)>,
    max_indentation: f64,
    impulse: f64,
    last_indentation: f64,
    last: ContactSample,
}

impl OpenContact {
    fn note(&mut self, t: f64, c: &ContactSample) {
        self.max_indentation = self.max_indentation.max(c.indentation);
        self.last_indentation = c.indentation;
        self.last = *c;
        self.force_history = [self.force_history[1], self.force_history[2], (t, c.force)];
    }

    /// The contact as reported (`separation`: time, relative normal velocity and energy).
    fn event(&self, separation: Option<(f64, f64, f64)>) -> ContactEvent {
        let (time_of_peak, peak) = self.peak.unwrap_or(self.force_history[2]);
        ContactEvent {
            onset_time_s: self.onset_time,
            impact_velocity_mps: self.impact_velocity,
            peak_force_n: peak,
            time_of_peak_s: time_of_peak,
            max_indentation_m: self.max_indentation,
            impulse_n_s: self.impulse,
            duration_s: separation.map(|(t, _, _)| t - self.onset_time),
            separation_velocity_mps: separation.map(|(_, v, _)| v),
            energy_before_j: self.energy_before,
            energy_after_j: separation.map(|(_, _, e)| e),
        }
    }
}

#[derive(Debug, Clone, Default)]
struct Stats {
    steps: usize,
    contact_steps: usize,
    energy_initial: f64,
    energy: f64,
    open: Option<OpenContact>,
    contacts: Vec<ContactEvent>,
    /// The drive: motor work, friction loss \[J\], largest |τ_j| [N·m], the largest energy or
    /// work seen \[J\] (the scale of the energy check), the link's and the commanded speed at
    /// the first onset [rad/s].
    drive_work: f64,
    drive_friction: f64,
    drive_peak_torque: f64,
    /// Time the drive's torque spent at its limit \[s\].
    drive_limit_time: f64,
    drive_scale: f64,
    drive_onset: Option<(f64, Option<f64>, f64)>,
}

impl<'s> Simulation<'s> {
    /// Builds the rig of `scene` in its initial state.
    pub fn new(scene: &'s Scene, options: RunOptions) -> Result<Self, RigError> {
        let geometry = RigGeometry::of(scene);
        let op = &geometry.operator;
        let g = scene.file.gravity_mps2;
        let design = scene.file.robot.design;
        let mut rapier = RapierRig::new(g, op, (design == Design::Cj).then_some(&geometry.robot));
        let drive = scene.drive.as_ref();
        if let Some(d) = drive
            && design == Design::Cj
            && !d.is_prescribed()
        {
            rapier.add_rotor(d.inertia());
        }
        let swing =
            scene
                .file
                .operator
                .start
                .initial_swing(op.mass, op.com_distance, op.inertia_pivot, g);
        let v_impact = swing.rate_at_contact * op.arm_length
            + drive.map_or(0.0, |d| d.tip_speed_estimate(geometry.robot.length));
        if !(v_impact > 0.0) {
            return Err(crate::error::invalid(
                "operator.start",
                format!("{:?}", scene.file.operator.start),
                "must bring the block to the dome with a positive speed",
            ));
        }
        let law = scene.contact_law(v_impact)?;
        let (robot, dome_offset) = match design {
            Design::Cj => (
                RobotSide::Rigid {
                    spring: scene.torsion_spring,
                },
                Pose::from_translation(geometry.robot.dome_center_local),
            ),
            Design::Cl => (
                RobotSide::Beam(Box::new(BeamLink::new(
                    scene,
                    options.beam_rho_inf,
                    options.cl_link,
                )?)),
                Pose::from_translation(
                    geometry.robot.dome_center_local - Vector::new(geometry.robot.length, 0.0, 0.0),
                ),
            ),
        };
        let contact = DomeBlockContact::new(
            geometry.robot.dome_radius,
            dome_offset,
            op.block_half_extents,
            Pose::from_translation(op.block_center_local),
            law,
        )?;
        // Contact time scale from the undamped Hertz impact of the two effective masses (the
        // link spring is much softer and slower than the contact).
        let m_op = op.effective_mass();
        let m_rob = geometry.robot.effective_mass();
        let mu = m_op * m_rob / (m_op + m_rob);
        let delta_max = scene.hertz.peak_indentation(mu, v_impact);
        let contact_time = CONTACT_TIME_FACTOR * delta_max / v_impact;
        let contact_step = contact_time / scene.file.solver.contact_steps as f64;

        let operator = HingeState {
            angle: swing.angle,
            rate: swing.rate,
        };
        let (hub_initial, link_initial) = match drive {
            Some(d) => {
                let (hub, link, _) = d.initial();
                (Some(hub), link)
            }
            None => (
                None,
                HingeState {
                    angle: 0.0,
                    rate: 0.0,
                },
            ),
        };
        let robot_initial = (design == Design::Cj).then_some(link_initial);
        let mut sim = Simulation {
            scene,
            options,
            geometry,
            rapier,
            robot,
            contact,
            t: 0.0,
            h_prev: 0.0,
            now: Synced {
                operator,
                operator_accel: 0.0,
                robot: None,
                contact: None,
                rotor: None,
            },
            phase: Phase::Swing,
            contact_step,
            first_contact_step: contact_step,
            previous_gap: None,
            onset_tolerance: 1e-9 * delta_max,
            indentation_scale: delta_max,
            last: Reading {
                t: 0.0,
                operator_angle: 0.0,
                robot_angle: 0.0,
                tip_deflection: 0.0,
                operator_velocity: 0.0,
                load_velocity: 0.0,
                force: 0.0,
                indentation: 0.0,
            },
            sampler: Sampler::new(scene.file.record.sample_rate_hz),
            stats: Stats::default(),
            flight: None,
            peak_search: None,
            retake: None,
        };
        if swing.starts_in_contact {
            sim.phase = Phase::Contact;
            // Touching at t = 0: the onset is the start of the first step.
            sim.previous_gap = Some((0.0, 0.0));
        }
        // Rapier holds the synchronised start state; the first kick is a half step (h_prev = 0).
        sim.rapier.set_state(operator, robot_initial);
        if let Some(hub) = hub_initial {
            sim.rapier.set_rotor_state(hub);
        }
        if let (Some(d), RobotSide::Beam(b)) = (drive, &mut sim.robot) {
            let (hub, accel) = b.hub_motion();
            let start = RotorSync {
                state: hub,
                accel,
                torque: 0.0,
                integral: d.initial().2,
            };
            if let Some((free, _)) = d.hub_law(0.0, 0.0, &start) {
                b.start_hub_law(d.limited(free, free.torque(hub.angle, hub.rate)))?;
            }
        }
        sim.now = sim.synchronize(0.0);
        sim.stats.energy_initial = sim.energy();
        sim.stats.energy = sim.stats.energy_initial;
        sim.last = sim.reading();
        if sim.phase == Phase::Swing {
            sim.start_free_flight();
        } else if sim.adaptive_contact() {
            let y = sim.flight_state();
            sim.begin_contact_flight(y);
        }
        Ok(sim)
    }

    /// Samples lean (see [`Sampler`]): the free swing's sensor samples are computed only when
    /// a recorder reads them ([`Recorder::swing_samples`]) or the severity needs them; the
    /// summary's `samples` then holds those around the first contact only (its `sample_count`
    /// is the full run's) and every
    /// other number of the summary — the severity's included — and every frame a recorder gets
    /// are the full run's, bit for bit. For a run whose samples nobody reads (a summary, a
    /// sweep row, a search) or that logs them at a lower rate.
    pub fn with_lean_samples(mut self) -> Self {
        if self.sampler.count() == 0 {
            self.sampler = Sampler::lean(self.scene.file.record.sample_rate_hz);
        }
        self
    }

    /// Simulated time \[s\].
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The geometry.
    pub fn geometry(&self) -> &RigGeometry {
        &self.geometry
    }

    /// Step size used in the first contact \[s\].
    pub fn first_contact_step(&self) -> f64 {
        self.first_contact_step
    }

    /// The dome body's pose and velocity (rates from the synchronised state).
    fn dome_kinematics(&self) -> BodyKinematics {
        match (&self.robot, self.now.robot) {
            (RobotSide::Beam(b), _) => b.tip_kinematics(),
            (RobotSide::Rigid { .. }, Some((r, _))) => self.rapier.robot_kinematics_at(r),
            (RobotSide::Rigid { .. }, None) => unreachable!("a rigid robot has a hinge state"),
        }
    }

    /// The block body's pose and velocity (rate from the synchronised state).
    fn block_kinematics(&self) -> BodyKinematics {
        self.rapier.operator_kinematics_at(self.now.operator)
    }

    fn gap(&self) -> f64 {
        self.contact.gap(
            &self.dome_kinematics().pose,
            &self.rapier.operator_kinematics().pose,
        )
    }

    /// Angular accelerations [rad/s²] of the operator and (CJ) the robot at hinge angles
    /// `operator`, `robot` under gravity, the torsion spring and the contact `contact`.
    fn accelerations(
        &self,
        operator: HingeState,
        robot: Option<HingeState>,
        hub: f64,
        contact: Option<&ContactSample>,
    ) -> (f64, Option<f64>) {
        let op = &self.geometry.operator;
        let g = self.scene.file.gravity_mps2;
        let mut torque = -op.mass * g * op.com_distance * operator.angle.sin();
        if let Some(c) = contact {
            torque += (c.point - op.pivot).cross(c.force_on_block()).x;
        }
        let robot_accel = match (&self.robot, robot) {
            (RobotSide::Rigid { spring }, Some(r)) => {
                // the spring's other end: the drive's hub (0: the fixed axis of the test bed)
                let mut t = -spring * (r.angle - hub);
                if let Some(c) = contact {
                    t += c.point.cross(c.force_on_dome()).z;
                }
                Some(t / self.geometry.robot.inertia_axis)
            }
            _ => None,
        };
        (torque / op.inertia_pivot, robot_accel)
    }

    /// The synchronised state after a step of `h` (0 at the start, when Rapier's rates are
    /// already synchronised): ω = ω_Rapier + (h/2) a(φ, contact), the contact evaluated with
    /// those rates — a predictor–corrector pass for a damped law (δ̇ needs ω, ω needs f).
    fn synchronize(&self, h: f64) -> Synced {
        let lagging = (self.rapier.operator_state(), self.rapier.robot_state());
        let rotor = self.sync_rotor(h, lagging.1);
        let hub = rotor.map_or(0.0, |r| r.state.angle);
        let at = |contact: Option<&ContactSample>| {
            let (a_op, a_rob) = self.accelerations(lagging.0, lagging.1, hub, contact);
            let operator = HingeState {
                angle: lagging.0.angle,
                rate: lagging.0.rate + 0.5 * h * a_op,
            };
            let robot = lagging.1.zip(a_rob).map(|(r, a)| {
                (
                    HingeState {
                        angle: r.angle,
                        rate: r.rate + 0.5 * h * a,
                    },
                    a,
                )
            });
            (operator, a_op, robot)
        };
        let evaluate = |operator: HingeState, robot: Option<(HingeState, f64)>| {
            let dome = match (&self.robot, robot) {
                (RobotSide::Beam(b), _) => b.tip_kinematics(),
                (RobotSide::Rigid { .. }, Some((r, _))) => self.rapier.robot_kinematics_at(r),
                (RobotSide::Rigid { .. }, None) => unreachable!("a rigid robot has a hinge state"),
            };
            self.contact
                .evaluate(&dome, &self.rapier.operator_kinematics_at(operator))
        };
        // Predictor: the rates with the forces of the step's start; then twice with the
        // contact at the synchronised rates. Out of contact at both (no force before, none
        // found), the second pass would repeat the first with the same numbers: skipped.
        let mut guess = at(self.now.contact.as_ref());
        let mut contact = None;
        for pass in 0..2 {
            contact = evaluate(guess.0, guess.2);
            if pass == 0 && contact.is_none() && self.now.contact.is_none() {
                break;
            }
            guess = at(contact.as_ref());
        }
        let (operator, operator_accel, robot) = guess;
        Synced {
            operator,
            operator_accel,
            robot,
            contact,
            rotor,
        }
    }

    /// The drive's hub at the end of a step of `h` (0: at the start) with the link at `link`
    /// (CJ: its elastic moment on the hub −k_θr (φ_m − φ_l)); the controller's integral
    /// advanced by the trapezoidal rule.
    fn sync_rotor(&self, h: f64, link: Option<HingeState>) -> Option<RotorSync> {
        let drive = self.scene.drive.as_ref()?;
        if let RobotSide::Beam(b) = &self.robot {
            return Some(self.sync_hub(drive, b, h));
        }
        let link = link?;
        let (angle, lagging_rate) = match self.rapier.rotor_state() {
            Some(s) => (s.angle, s.rate),
            None => (drive.prescribed(self.t)?.0.angle, 0.0),
        };
        let spring = -self.scene.torsion_spring * (angle - link.angle);
        let integral = match self.now.rotor {
            Some(r) if h > 0.0 => {
                r.integral
                    + 0.5
                        * h
                        * (drive.angle_error(self.t - h, r.state.angle)
                            + drive.angle_error(self.t, angle))
            }
            Some(r) => r.integral,
            None => drive.initial().2,
        };
        Some(drive.synchronise(self.t, angle, lagging_rate, integral, spring, h))
    }

    /// The hub of a driven compliant link after a step of `h` (0: at the start): its motion
    /// is the beam's root node's (synchronised: the link's integrator keeps rates and angles at
    /// the same instant); the torque is the law the step took (free hub) or, for a prescribed
    /// trajectory, τ_j = J_m N² θ̈ + c_m N² θ̇ + the root's reaction.
    fn sync_hub(&self, drive: &crate::joint_drive::JointDrive, b: &BeamLink, h: f64) -> RotorSync {
        let (state, accel) = b.hub_motion();
        let integral = match self.now.rotor {
            Some(r) if h > 0.0 => {
                r.integral
                    + 0.5
                        * h
                        * (drive.angle_error(self.t - h, r.state.angle)
                            + drive.angle_error(self.t, state.angle))
            }
            Some(r) => r.integral,
            None => drive.initial().2,
        };
        let torque = match b.hub_law() {
            Some(law) => law.torque(state.angle, state.rate),
            None => drive.inertia() * accel + drive.friction() * state.rate + b.root_moment(),
        };
        RotorSync {
            state,
            accel,
            torque,
            integral,
        }
    }

    /// Total mechanical energy \[J\] at the synchronised state.
    fn energy(&self) -> f64 {
        let op = &self.geometry.operator;
        let s = self.now.operator;
        let g = self.scene.file.gravity_mps2;
        let mut e = 0.5 * op.inertia_pivot * s.rate * s.rate
            + op.mass * g * op.com_distance * (1.0 - s.angle.cos());
        e += match (&self.robot, self.now.robot) {
            (RobotSide::Rigid { spring }, Some((r, _))) => match self.now.rotor {
                None => {
                    0.5 * self.geometry.robot.inertia_axis * r.rate * r.rate
                        + 0.5 * spring * r.angle * r.angle
                }
                Some(hub) => {
                    let twist = r.angle - hub.state.angle;
                    0.5 * self.geometry.robot.inertia_axis * r.rate * r.rate
                        + 0.5 * spring * twist * twist
                }
            },
            (RobotSide::Beam(b), _) => b.energy(),
            (RobotSide::Rigid { .. }, None) => unreachable!("a rigid robot has a hinge state"),
        };
        if let (Some(hub), Some(d)) = (&self.now.rotor, &self.scene.drive) {
            e += 0.5 * d.inertia() * hub.state.rate * hub.state.rate;
        }
        if let Some(c) = &self.now.contact {
            e += self.contact.law().elastic_energy(c.indentation);
        }
        e
    }

    fn reading(&self) -> Reading {
        let op = self.now.operator;
        let l = self.geometry.operator.arm_length;
        let (robot_angle, tip_deflection, load_velocity) = match (&self.robot, self.now.robot) {
            (RobotSide::Rigid { .. }, Some((r, _))) => {
                let len = self.geometry.robot.length;
                (r.angle, len * r.angle.sin(), len * r.angle.cos() * r.rate)
            }
            (RobotSide::Beam(b), _) => {
                let (v, vdot, _) = b.tip_transverse();
                // the shaft turns with a drive's hub
                let shaft = match self.now.rotor {
                    Some(hub) => hub.state.angle,
                    None => 0.0,
                };
                (shaft, v, vdot)
            }
            (RobotSide::Rigid { .. }, None) => unreachable!("a rigid robot has a hinge state"),
        };
        Reading {
            t: self.t,
            operator_angle: op.angle,
            robot_angle,
            tip_deflection,
            operator_velocity: l * op.angle.cos() * op.rate,
            load_velocity,
            force: self.now.contact.map_or(0.0, |c| c.force),
            indentation: self.now.contact.map_or(0.0, |c| c.indentation),
        }
    }

    /// The next step size: the contact step in contact; out of contact the swing step (after a
    /// separation at most ten contact steps until the bodies are five peak indentations apart),
    /// shortened near an onset: with the time to touch predicted from the gap and the present
    /// approach rate, each step takes half of it until it is within a contact step, so that the
    /// onset falls in a step of the contact's own size whatever the bodies do (a vibrating link
    /// tip defeats a single prediction).
    fn next_step(&mut self) -> f64 {
        let swing = self.scene.file.solver.swing_step_s;
        if self.phase == Phase::Contact {
            return self.contact_step;
        }
        let (gap, closing) = self
            .contact
            .approach(&self.dome_kinematics(), &self.block_kinematics())
            .unwrap_or((f64::INFINITY, 0.0));
        if self.phase == Phase::After && gap > 5.0 * self.indentation_scale {
            self.phase = Phase::Swing;
        }
        self.previous_gap = Some((self.t, gap));
        if gap <= self.onset_tolerance {
            self.phase = Phase::Contact;
            return self.contact_step;
        }
        let cap = match self.phase {
            Phase::After => swing.min(self.contact_step * 10.0).max(self.contact_step),
            _ => swing,
        };
        if closing > 0.0 {
            let time_to_touch = gap / closing;
            if time_to_touch < 2.0 * self.contact_step {
                return self.contact_step.min(cap);
            }
            if time_to_touch < 2.0 * cap {
                return 0.5 * time_to_touch;
            }
        }
        cap
    }

    /// The contact step for an impact at approach speed `v` [m/s]: the Hertz contact time of the
    /// two effective masses over `solver.contact_steps`, at most the first contact's (also the
    /// indentation scale and the onset tolerance).
    fn size_contact(&mut self, v: f64) {
        let m_op = self.geometry.operator.effective_mass();
        let m_rob = self.geometry.robot.effective_mass();
        let mu = m_op * m_rob / (m_op + m_rob);
        let delta_max = self.scene.hertz.peak_indentation(mu, v);
        let contact_time = CONTACT_TIME_FACTOR * delta_max / v;
        let step = contact_time / self.scene.file.solver.contact_steps as f64;
        if step.is_finite() && step > 0.0 {
            // never coarser than the first contact's: a slow, glancing contact against a
            // vibrating link lasts as long as the link makes it, not as Hertz says
            self.contact_step = step.min(self.first_contact_step);
            self.indentation_scale = delta_max;
            self.onset_tolerance = 1e-9 * delta_max;
        }
    }

    /// The torques that turn Rapier's next step of `h` into a velocity-Verlet step from the
    /// synchronised state: J a_n (h_prev + h)/(2h), less the gravity Rapier adds itself.
    fn kick_torques(&self, h: f64) -> (f64, f64, f64) {
        let op = &self.geometry.operator;
        let scale = (self.h_prev + h) / (2.0 * h);
        let gravity = -op.mass
            * self.scene.file.gravity_mps2
            * op.com_distance
            * self.now.operator.angle.sin();
        let operator = op.inertia_pivot * self.now.operator_accel * scale - gravity;
        let robot = self
            .now
            .robot
            .map_or(0.0, |(_, a)| self.geometry.robot.inertia_axis * a * scale);
        let rotor = match (&self.now.rotor, &self.scene.drive) {
            (Some(r), Some(d)) => d.inertia() * r.accel * scale,
            _ => 0.0,
        };
        (operator, robot, rotor)
    }

    /// One step of the pipeline: loads → integrate → synchronise → events → check → sensors.
    pub fn step(&mut self, recorder: &mut dyn Recorder) -> Result<StepOutcome, RigError> {
        if self.peak_search.is_some() {
            return self.contact_flight_step(recorder);
        }
        if self.flight.is_some() {
            return self.free_step(recorder);
        }
        let mut dt = self.next_step();
        let start = (self.now, self.dome_kinematics(), self.block_kinematics());
        let deflection_before = self.link_deflection();
        // Near an onset a step may overshoot it (a vibrating link tip defeats the prediction):
        // keep what is needed to take it again, smaller.
        let retry = (self.phase != Phase::Contact && dt > self.contact_step && self.near_contact())
            .then(|| self.snapshot());
        loop {
            self.advance(dt, &start.0)?;
            // Rejected: a step longer than a contact step that ends deeper in contact than a
            // contact step at the present rate would go. Retaken at an eighth (at least the
            // contact step): the onset lands in a step of the contact's own size.
            if let (Some(snapshot), Some(c)) = (&retry, self.now.contact)
                && dt > self.contact_step
                && c.indentation > c.rate.abs() * self.contact_step
            {
                self.restore(snapshot)?;
                dt = (dt / 8.0).max(self.contact_step);
                continue;
            }
            break;
        }
        self.stats.steps += 1;
        self.account_drive(&start.0, dt);
        // Events.
        let outcome = self.classify(&start, dt);
        if outcome == StepOutcome::ContactOnset
            && let (Some(d), None) = (&self.scene.drive, self.stats.drive_onset)
        {
            let onset = self.stats.open.map_or(self.t, |o| o.onset_time);
            let link = start
                .0
                .robot
                .map_or(-start.0.rotor.map_or(0.0, |r| r.state.rate), |(r, _)| {
                    -r.rate
                });
            // the deflection at the onset, linear between the step's ends
            let frac = ((onset - (self.t - dt)) / dt).clamp(0.0, 1.0);
            let deflection =
                deflection_before + frac * (self.link_deflection() - deflection_before);
            self.stats.drive_onset =
                Some((link, d.commanded(onset).map(|(_, w, _)| -w), deflection));
        }
        if outcome == StepOutcome::Separation {
            self.start_free_flight();
        }
        let energy = self.energy();
        self.check_health(energy)?;
        self.stats.energy = energy;
        // Sensors and the recorder.
        let reading = self.reading();
        let sampled_before = self.sampler.samples().len();
        self.sampler.record_step(&self.last, &reading);
        self.last = reading;
        self.emit(recorder, dt, outcome, energy, sampled_before)?;
        Ok(outcome)
    }

    /// Hands the frame of the step just taken (of `dt`, reaching `outcome`, with the samples
    /// from index `sampled_before` on) to the recorder.
    fn emit(
        &self,
        recorder: &mut dyn Recorder,
        dt: f64,
        outcome: StepOutcome,
        energy: f64,
        sampled_before: usize,
    ) -> Result<(), RigError> {
        let operator_pose = self.block_kinematics().pose;
        let dome_body_pose = self.dome_kinematics().pose;
        let beam = match &self.robot {
            RobotSide::Rigid { .. } => None,
            RobotSide::Beam(b) => Some(b.as_ref()),
        };
        recorder.frame(&Frame {
            t: self.t,
            dt,
            outcome,
            operator: self.now.operator,
            robot: self.now.robot.map(|(r, _)| r),
            operator_pose,
            dome_body_pose,
            beam,
            contact: self.now.contact,
            energy,
            samples: &self.sampler.samples()[sampled_before..],
            drive: self.drive_frame(),
        })
    }

    /// The drive's channels at the synchronised state.
    fn drive_frame(&self) -> Option<DriveFrame> {
        let (d, hub) = (self.scene.drive.as_ref()?, self.now.rotor?);
        let (link, spring) = match (&self.robot, self.now.robot) {
            (_, Some((r, _))) => (r, -self.scene.torsion_spring * (hub.state.angle - r.angle)),
            (RobotSide::Beam(b), None) => (hub.state, -b.root_moment()),
            (RobotSide::Rigid { .. }, None) => (hub.state, 0.0),
        };
        let deflection = self.link_deflection();
        Some(d.frame(
            self.t,
            hub.state,
            link,
            hub.torque,
            (spring, deflection),
            (self.stats.drive_work, self.stats.drive_friction),
        ))
    }

    /// Why a run may never touch, for the error after 60 s without contact: without a drive the
    /// pendulum's swing; with one, how far and how fast the drive has moved the link against
    /// the travel to the block and the commanded speed, and its torque limit.
    fn no_contact_hint(&self) -> String {
        let (Some(d), Some(f)) = (&self.scene.drive, self.drive_frame()) else {
            return "does the pendulum reach the dome?".into();
        };
        let mut hint = format!(
            "the drive has moved the link {:.4} of the {:.4} rad to the block and turns it at \
             {:.4} rad/s, commanded {:.4} rad/s",
            f.link_angle_rad,
            d.start_angle(),
            f.link_speed_rad_s,
            f.commanded_speed_rad_s
        );
        if let flexrig_impact::drive::DriveCommand::Controller {
            torque_limit: Some(limit),
            ..
        } = d.drive().command()
        {
            hint.push_str(&format!(
                "; is robot.drive.command.torque_limit = {} N·m at the motor shaft enough to \
                 move it?",
                flexrig_contact::validate::display(*limit)
            ));
        }
        hint
    }

    /// Deflection of the link's tip from the drive's hub line \[m\], positive towards the
    /// operator (the drive's convention: −y of the hub frame): CJ L sin(φ_m − φ_l), CL the
    /// beam's tip in the hub's frame; 0 without a drive.
    fn link_deflection(&self) -> f64 {
        match (&self.robot, self.now.robot, self.now.rotor) {
            (RobotSide::Beam(b), _, Some(_)) => -b.tip_deflection_in_hub_frame(),
            (RobotSide::Rigid { .. }, Some((r, _)), Some(hub)) => {
                self.geometry.robot.length * (hub.state.angle - r.angle).sin()
            }
            _ => 0.0,
        }
    }

    /// Adds the step of `dt` from `start` to the drive's work, friction loss and peak torque
    /// (trapezoidal rule on the synchronised ends).
    fn account_drive(&mut self, start: &Synced, dt: f64) {
        let (Some(d), Some(a), Some(b)) = (&self.scene.drive, start.rotor, self.now.rotor) else {
            return;
        };
        let c = d.friction();
        let (wa, wb) = (a.state.rate, b.state.rate);
        self.stats.drive_work += 0.5 * dt * (a.torque * wa + b.torque * wb);
        self.stats.drive_friction += 0.5 * dt * c * (wa * wa + wb * wb);
        self.stats.drive_peak_torque = self.stats.drive_peak_torque.max(b.torque.abs());
        if b.torque.abs() >= d.drive().joint_torque_limit() {
            self.stats.drive_limit_time += dt;
        }
        self.stats.drive_scale = self
            .stats
            .drive_scale
            .max(self.stats.drive_work.abs())
            .max(self.stats.energy.abs());
    }

    /// Starts the adaptive free flight from the synchronised state, when the scene asks for it
    /// and the motion out of contact is the hinges' alone: always for the CJ, for the CL only
    /// before its first contact (the beam at rest; afterwards it vibrates and is stepped with
    /// the fixed policy).
    fn start_free_flight(&mut self) {
        // With a drive the motion out of contact is not the hinges' alone: the fixed policy.
        if self.scene.file.solver.swing != SwingPolicy::Adaptive || self.scene.drive.is_some() {
            return;
        }
        let robot = match &self.robot {
            RobotSide::Rigid { spring } => Some((self.geometry.robot.inertia_axis, *spring)),
            RobotSide::Beam(_) if self.stats.contacts.is_empty() && self.stats.open.is_none() => {
                None
            }
            RobotSide::Beam(_) => return,
        };
        let op = &self.geometry.operator;
        let g = self.scene.file.gravity_mps2;
        let system = FreeHinges {
            operator_inertia: op.inertia_pivot,
            gravity_moment: op.mass * g * op.com_distance,
            robot,
        };
        // The largest step: an eighth of the shorter small-amplitude period, so that the
        // gap is sampled finely enough for the onset whatever the tolerance lets through.
        let tau = std::f64::consts::TAU;
        let mut period = tau * (system.operator_inertia / system.gravity_moment).sqrt();
        if let Some((inertia, spring)) = robot {
            period = period.min(tau * (inertia / spring).sqrt());
        }
        let s = self.now.operator;
        let r = self
            .now
            .robot
            .map_or((0.0, 0.0), |(r, _)| (r.angle, r.rate));
        let rate_scale = op.bottom_angular_speed(s.angle, g).hypot(s.rate);
        self.flight = Some(FreeFlight::new(
            system,
            self.t,
            [s.angle, s.rate, r.0, r.1],
            rate_scale,
            period / 8.0,
        ));
    }

    /// The signed dome–block gap \[m\] with the hinges in state `y` of the free flight (the CL
    /// beam at rest); before an adaptive contact by the direct sequence of operations (the
    /// Rapier path keeps parry's, bit for bit).
    fn flight_gap(&self, y: &[f64; DIM]) -> f64 {
        let block = self.rapier.operator_kinematics_at(HingeState {
            angle: y[0],
            rate: y[1],
        });
        let dome = match &self.robot {
            RobotSide::Rigid { .. } => self.rapier.robot_kinematics_at(HingeState {
                angle: y[2],
                rate: y[3],
            }),
            RobotSide::Beam(b) => b.tip_kinematics(),
        };
        if self.adaptive_contact() {
            self.contact.gap_direct(&dome.pose, &block.pose)
        } else {
            self.contact.gap(&dome.pose, &block.pose)
        }
    }

    /// The synchronised state of the free flight's `y` (no contact).
    fn flight_synced(&self, y: &[f64; DIM]) -> Synced {
        let operator = HingeState {
            angle: y[0],
            rate: y[1],
        };
        let robot = matches!(self.robot, RobotSide::Rigid { .. }).then_some(HingeState {
            angle: y[2],
            rate: y[3],
        });
        let (operator_accel, robot_accel) = self.accelerations(operator, robot, 0.0, None);
        Synced {
            operator,
            operator_accel,
            robot: robot.zip(robot_accel),
            contact: None,
            rotor: None,
        }
    }

    /// One step of the adaptive free flight: an accepted DOP853 step (not past a stop time),
    /// ending at the contact onset if it reaches it — then the exact onset state goes to Rapier,
    /// whose next step is the contact's first (h_prev = 0: a half kick, as at the start) — and
    /// the sensors sampled on the dense output.
    fn free_step(&mut self, recorder: &mut dyn Recorder) -> Result<StepOutcome, RigError> {
        let t_limit = match self.scene.file.stop {
            StopSpec::Duration { duration_s } => Some(duration_s),
            StopSpec::Peak | StopSpec::Separation | StopSpec::Rebound => None,
        };
        let mut flight = self.flight.take().expect("in free flight");
        let step: FlightStep = match flight.step(t_limit, |y| self.flight_gap(y)) {
            Ok(step) => step,
            Err(failure) => {
                return Err(RigError::Unstable {
                    t: self.t,
                    quantity: "the free swing (adaptive integration)".into(),
                    reason: format!("failed: {failure:?}"),
                    suggestion: self.step_advice(),
                });
            }
        };
        // Sensors from the dense output (the exact state at each sample time).
        let dense = flight.dense();
        let sampled_before = self.sampler.samples().len();
        let sensors = FlightSensors {
            arm_length: self.geometry.operator.arm_length,
            link_length: matches!(self.robot, RobotSide::Rigid { .. })
                .then_some(self.geometry.robot.length),
            beam_tip: match &self.robot {
                RobotSide::Beam(b) => {
                    let (v, _, a) = b.tip_transverse();
                    (v, a)
                }
                RobotSide::Rigid { .. } => (0.0, 0.0),
            },
        };
        let system = *flight.system();
        if let Some(period) = recorder.pose_period().filter(|p| p.is_finite() && *p > 0.0) {
            self.emit_between(recorder, &dense, (step.t_start, step.t_end), period)?;
        }
        let (t_end, y_end) = (step.t_end, step.y);
        let at = move |t: f64| {
            let y = if t == t_end { y_end } else { dense.eval(t) };
            sensors.sample(&system, t, &y)
        };
        if self.sampler.is_lean() {
            let bound = swing_accel_bound(&system, &sensors, &step.y);
            match recorder.swing_samples() {
                SwingSamples::None => {
                    self.sampler
                        .record_deferred(step.t_start, step.t_end, at, bound, None);
                }
                SwingSamples::Every => {
                    self.sampler.record_deferred(
                        step.t_start,
                        step.t_end,
                        at,
                        bound,
                        Some(&mut |_| true),
                    );
                }
                SwingSamples::Chosen => {
                    self.sampler.record_deferred(
                        step.t_start,
                        step.t_end,
                        at,
                        bound,
                        Some(&mut |t| recorder.wants_swing_sample(t)),
                    );
                }
            }
        } else {
            self.sampler.record_exact(step.t_start, step.t_end, at);
        }
        // The new state, in Rapier too (synchronised: the next fixed step kicks half a step)
        // unless the contact is integrated adaptively too (then Rapier is not stepped).
        self.t = step.t_end;
        self.h_prev = 0.0;
        self.now = self.flight_synced(&step.y);
        let adaptive = self.adaptive_contact();
        if !adaptive {
            self.rapier
                .set_state(self.now.operator, self.now.robot.map(|(r, _)| r));
        }
        if let RobotSide::Beam(b) = &mut self.robot {
            b.set_time(self.t);
        }
        self.stats.steps += 1;
        let adaptive_onset = step.onset && adaptive;
        if step.onset && !adaptive {
            // The fixed policy takes over at the onset: its first step is the contact's.
            self.phase = Phase::Swing;
        } else if !step.onset {
            self.flight = Some(flight);
        }
        let energy = self.energy();
        self.check_health(energy)?;
        self.stats.energy = energy;
        if adaptive_onset {
            self.begin_contact_flight(step.y);
        }
        self.last = self.reading();
        let dt = step.t_end - step.t_start;
        self.emit(recorder, dt, StepOutcome::Advanced, energy, sampled_before)?;
        Ok(StepOutcome::Advanced)
    }

    /// Hands the recorder the poses at the multiples of `period` strictly inside the free-flight
    /// step `(t_start, t_end)`, interpolated on its `dense` output; the run's state is restored
    /// bit for bit afterwards.
    fn emit_between(
        &mut self,
        recorder: &mut dyn Recorder,
        dense: &flexrig_lumped::ode::dop853::DenseOutput<DIM>,
        (t_start, t_end): (f64, f64),
        period: f64,
    ) -> Result<(), RigError> {
        let saved = self.now;
        let mut k = (t_start / period).floor() + 1.0;
        let mut result = Ok(());
        while result.is_ok() {
            let t = k * period;
            if t >= t_end {
                break;
            }
            k += 1.0;
            if t <= t_start {
                continue;
            }
            self.now = self.flight_synced(&dense.eval(t));
            let beam = match &self.robot {
                RobotSide::Rigid { .. } => None,
                RobotSide::Beam(b) => Some(b.as_ref()),
            };
            result = recorder.between(&Frame {
                t,
                dt: t - t_start,
                outcome: StepOutcome::Advanced,
                operator: self.now.operator,
                robot: self.now.robot.map(|(r, _)| r),
                operator_pose: self.block_kinematics().pose,
                dome_body_pose: self.dome_kinematics().pose,
                beam,
                contact: None,
                energy: self.energy(),
                samples: &[],
                // the free flight is the unforced rig's: a driven robot is stepped by Rapier
                drive: None,
            });
        }
        self.now = saved;
        result
    }

    /// Loads → integrate → synchronise for a step of `dt` from the synchronised state `start`.
    fn advance(&mut self, dt: f64, start: &Synced) -> Result<(), RigError> {
        // Loads: the forces at t_n (the contact of the synchronised state) as kicks.
        let (operator_torque, robot_torque, rotor_torque) = self.kick_torques(dt);
        self.rapier.apply_torques(operator_torque, robot_torque);
        self.rapier.apply_rotor_torque(rotor_torque);
        // Integrate: Rapier (explicit), then the beam with the contact implicit at t_n + dt.
        self.rapier.step(dt);
        if let RobotSide::Beam(b) = &mut self.robot {
            let mut tip_contact = TipContact {
                contact: &self.contact,
                rapier: &self.rapier,
                operator: HingeMotion {
                    t0: self.t,
                    start: start.operator,
                    accel: start.operator_accel,
                },
                tip_x: b.model().length(),
                tip: b.tip_node(),
            };
            let hub_law = match (&self.scene.drive, &start.rotor) {
                (Some(d), Some(r)) => d.hub_law(self.t, dt, r),
                _ => None,
            };
            // only a torque limit can make the predicted branch wrong
            let limited = self
                .scene
                .drive
                .as_ref()
                .is_some_and(|d| d.is_torque_limited());
            let retake = hub_law.is_some() && limited;
            if retake {
                b.save(&mut self.retake);
            }
            let mut stepped = match hub_law {
                Some((_, law)) => b
                    .set_hub_law(law)
                    .and_then(|()| b.step(dt, &mut tip_contact)),
                None => b.step(dt, &mut tip_contact),
            };
            // The torque limit's branch as the step's end says: once more on the other if
            // the prediction chose wrong (the law is piecewise affine in the hub's motion).
            if let (Ok(()), Some((free, used)), Some(d), Some(saved), true) =
                (&stepped, hub_law, &self.scene.drive, &self.retake, retake)
            {
                let (hub, _) = b.hub_motion();
                let right = d.limited(free, free.torque(hub.angle, hub.rate));
                if right != used {
                    stepped = b
                        .restore(saved)
                        .and_then(|()| b.set_hub_law(right))
                        .and_then(|()| b.step(dt, &mut tip_contact));
                }
            }
            if let Err(e) = stepped {
                return Err(self.beam_failure(e));
            }
        }
        self.t += dt;
        self.h_prev = dt;
        // Synchronise: rates and contact at t_{n+1}.
        self.now = self.synchronize(dt);
        Ok(())
    }

    /// True when the bodies are within ten peak indentations: where an onset may come within a
    /// step.
    fn near_contact(&self) -> bool {
        self.previous_gap
            .is_some_and(|(_, gap)| gap < 10.0 * self.indentation_scale)
    }

    /// What [`Self::advance`] changes: the time, the hinge states as Rapier holds them and the
    /// beam.
    fn snapshot(&self) -> Snapshot {
        Snapshot {
            t: self.t,
            h_prev: self.h_prev,
            now: self.now,
            operator: self.rapier.operator_state(),
            robot: self.rapier.robot_state(),
            rotor: self.rapier.rotor_state(),
            beam: match &self.robot {
                RobotSide::Beam(b) => {
                    let mut saved = None;
                    b.save(&mut saved);
                    saved
                }
                RobotSide::Rigid { .. } => None,
            },
        }
    }

    fn restore(&mut self, s: &Snapshot) -> Result<(), RigError> {
        self.t = s.t;
        self.h_prev = s.h_prev;
        self.now = s.now;
        self.rapier.set_state(s.operator, s.robot);
        if let Some(r) = s.rotor {
            self.rapier.set_rotor_state(r);
        }
        if let (RobotSide::Beam(b), Some(saved)) = (&mut self.robot, &s.beam) {
            b.restore(saved)?;
        }
        Ok(())
    }

    /// A failed beam step as the user meets it: what failed, when, and which scene field to
    /// change.
    fn beam_failure(&self, e: RigError) -> RigError {
        match e {
            RigError::Beam(cause) if !cause.is_input_error() => RigError::Unstable {
                t: self.t,
                quantity: "the compliant link (beam step)".into(),
                reason: format!("failed: {cause}"),
                suggestion: self.step_advice(),
            },
            e => e,
        }
    }

    /// What to change in the scene when a step fails: the setting of the current phase, named
    /// as in the scene file, with the direction that makes the step smaller.
    fn step_advice(&self) -> String {
        let solver = &self.scene.file.solver;
        if self.phase == Phase::Contact {
            format!(
                "a larger solver.contact_steps (now {}; more steps per contact, a smaller step)",
                solver.contact_steps
            )
        } else {
            format!(
                "a smaller solver.swing_step_s (now {:e} s)",
                solver.swing_step_s
            )
        }
    }

    /// Relative normal velocity [m/s] of the dome against the block at the contact point and
    /// normal of `c`, for the given kinematics (positive when approaching).
    fn normal_rate(dome: &BodyKinematics, block: &BodyKinematics, c: &ContactSample) -> f64 {
        (dome.velocity_at(c.point) - block.velocity_at(c.point)).dot(c.normal)
    }

    /// Updates the contact statistics and names the event of the step; `start` is the
    /// synchronised state and the kinematics at the start of the step.
    fn classify(
        &mut self,
        start: &(Synced, BodyKinematics, BodyKinematics),
        dt: f64,
    ) -> StepOutcome {
        let (before, dome0, block0) = start;
        let after = self.now.contact;
        // The impulse of the step as the integrator applies it: trapezoidal.
        let force0 = before.contact.map_or(0.0, |c| c.force);
        let impulse = 0.5 * dt * (force0 + after.map_or(0.0, |c| c.force));
        match (self.stats.open.as_mut(), after) {
            (None, Some(c)) => {
                // Onset inside this step: interpolate on the gap (was ≥ 0, now −δ), and the
                // normal approach speed between the step's ends to the same instant.
                let frac = self
                    .previous_gap_at_step_start()
                    .map_or(1.0, |g0| g0 / (g0 + c.indentation));
                let rate0 = self
                    .contact
                    .approach(dome0, block0)
                    .map_or(c.rate, |(_, rate)| rate);
                let impact_velocity = rate0 + frac * (c.rate - rate0);
                // every contact on its own time scale (a later one may be faster)
                if !self.stats.contacts.is_empty() && impact_velocity > 0.0 {
                    self.size_contact(impact_velocity);
                }
                let mut open = OpenContact {
                    onset_time: self.t - dt + frac * dt,
                    impact_velocity,
                    energy_before: self.stats.energy,
                    force_history: [(0.0, 0.0); 3],
                    peak: None,
                    max_indentation: 0.0,
                    impulse,
                    last_indentation: 0.0,
                    last: c,
                };
                open.note(self.t, &c);
                self.stats.open = Some(open);
                self.stats.contact_steps += 1;
                self.phase = Phase::Contact;
                StepOutcome::ContactOnset
            }
            (Some(open), Some(c)) => {
                open.impulse += impulse;
                open.note(self.t, &c);
                self.stats.contact_steps += 1;
                let [(_, f0), (_, f1), (_, f2)] = open.force_history;
                if open.peak.is_none() && f2 < f1 && f1 >= f0 && f1 > 0.0 {
                    open.peak = Some(parabola_vertex(open.force_history));
                    if self.stats.contacts.is_empty() {
                        return StepOutcome::Peak;
                    }
                }
                StepOutcome::Advanced
            }
            (Some(_), None) => {
                let mut open = self.stats.open.take().expect("matched Some");
                open.impulse += impulse;
                let gap = self.gap().max(0.0);
                let d0 = open.last_indentation;
                let frac = if d0 + gap > 0.0 { d0 / (d0 + gap) } else { 1.0 };
                let separation = self.t - dt + frac * dt;
                // Relative normal velocity at the last contact point, positive when parting.
                let parting = -Self::normal_rate(
                    &self.dome_kinematics(),
                    &self.block_kinematics(),
                    &open.last,
                );
                let event = open.event(Some((separation, parting, self.energy())));
                self.stats.contacts.push(event);
                self.phase = Phase::After;
                self.previous_gap = None;
                StepOutcome::Separation
            }
            (None, None) => StepOutcome::Advanced,
        }
    }

    fn previous_gap_at_step_start(&self) -> Option<f64> {
        self.previous_gap.map(|(_, g)| g.max(0.0))
    }

    /// Stops on a non-finite state or on growth of the (synchronised) energy beyond the limit.
    fn check_health(&self, energy: f64) -> Result<(), RigError> {
        let op = self.now.operator;
        if !(op.angle.is_finite() && op.rate.is_finite() && energy.is_finite()) {
            return Err(RigError::Unstable {
                t: self.t,
                quantity: "the state".into(),
                reason: "became non-finite".into(),
                suggestion: self.step_advice(),
            });
        }
        let e0 = self.stats.energy_initial;
        let grown = if self.scene.drive.is_some() {
            // with a drive the conserved quantity is the energy less the drive's net work,
            // measured against the largest energy or work of the run
            let net = self.stats.drive_work - self.stats.drive_friction;
            let scale = e0
                .max(self.stats.drive_scale)
                .max(energy.abs())
                .max(net.abs());
            energy - net > e0 + scale * self.options.energy_growth_limit + 1e-12
        } else {
            energy > e0 * (1.0 + self.options.energy_growth_limit) + 1e-12
        };
        if grown {
            return Err(RigError::Unstable {
                t: self.t,
                quantity: "the mechanical energy".into(),
                reason: format!(
                    "grew from {e0:.6e} J to {energy:.6e} J (more than {:.0} %)",
                    100.0 * self.options.energy_growth_limit
                ),
                suggestion: self.step_advice(),
            });
        }
        Ok(())
    }

    /// Runs to the scene's stop condition.
    pub fn run(mut self, recorder: &mut dyn Recorder) -> Result<RunSummary, RigError> {
        let stop = self.scene.file.stop;
        let max_steps = self.scene.file.solver.max_steps;
        let mut rebound = Rebound::default();
        loop {
            if self.stats.steps >= max_steps {
                return Err(RigError::NotReached {
                    what: stop.describe(),
                    limit: format!("solver.max_steps = {max_steps}"),
                });
            }
            let outcome = self.step(recorder)?;
            let done = match stop {
                StopSpec::Peak => outcome == StepOutcome::Peak,
                StopSpec::Separation => outcome == StepOutcome::Separation,
                StopSpec::Duration { duration_s } => self.t >= duration_s,
                StopSpec::Rebound => {
                    rebound.turned(outcome, self.now.operator.rate, self.stats.open.is_some())
                }
            };
            if done {
                break;
            }
            if let StopSpec::Peak | StopSpec::Separation | StopSpec::Rebound = stop
                && self.stats.contacts.is_empty()
                && self.stats.open.is_none()
                && self.t > 60.0
            {
                return Err(RigError::NotReached {
                    what: "contact".into(),
                    limit: format!("60 s of simulated time ({})", self.no_contact_hint()),
                });
            }
        }
        let mut contacts = std::mem::take(&mut self.stats.contacts);
        if let Some(open) = &self.stats.open {
            contacts.push(open.event(None));
        }
        let Some(first) = contacts.first().copied() else {
            return Err(RigError::NotReached {
                what: "the first contact".into(),
                limit: format!(
                    "stop.duration_s = {} s (the run ended at t = {:.6e} s)",
                    match stop {
                        StopSpec::Duration { duration_s } => duration_s,
                        _ => self.t,
                    },
                    self.t
                ),
            });
        };
        let contact_integration = if self.adaptive_contact() {
            ContactPolicy::Adaptive
        } else {
            ContactPolicy::Fixed
        };
        let dome = self.scene.file.robot.dome_radius_m;
        let (samples, sample_count, severity) = if self.sampler.is_lean() {
            let severity = crate::severity::of_sampler(&self.sampler, dome).ok();
            // the first contact with its duration on either side (what a log's layout scales
            // its plots by)
            let end = first.duration_s.map_or(self.t, |d| first.onset_time_s + d);
            let d = (end - first.onset_time_s).max(0.0);
            let around = self
                .sampler
                .samples_between(first.onset_time_s - d, end + d);
            (around, self.sampler.taken(), severity)
        } else {
            let samples = self.sampler.into_samples();
            let severity = crate::severity::of_samples(&samples, dome).ok();
            let n = samples.len();
            (samples, n, severity)
        };
        Ok(RunSummary {
            scene: self.scene.file.name.clone(),
            design: self.scene.file.robot.design,
            peak_force_n: first.peak_force_n,
            time_of_peak_s: first.time_of_peak_s,
            impact_velocity_mps: first.impact_velocity_mps,
            separation_velocity_mps: first.separation_velocity_mps,
            onset_time_s: first.onset_time_s,
            contact_duration_s: first.duration_s,
            max_indentation_m: first.max_indentation_m,
            impulse_n_s: first.impulse_n_s,
            steps: self.stats.steps,
            contact_steps: self.stats.contact_steps,
            contact_integration,
            contact_step_s: self.first_contact_step,
            energy_initial_j: self.stats.energy_initial,
            energy_final_j: self.stats.energy,
            energy_through_contact_j: first.energy_after_j.map(|e| (first.energy_before_j, e)),
            contacts,
            duration_s: self.t,
            warnings: self.scene.warnings.clone(),
            severity,
            samples,
            sample_count,
            drive: self.scene.drive.as_ref().map(|_| DriveSummary {
                motor_work_j: self.stats.drive_work,
                friction_dissipated_j: self.stats.drive_friction,
                peak_joint_torque_nm: self.stats.drive_peak_torque,
                time_at_torque_limit_s: self.stats.drive_limit_time,
                pre_impact_deflection_m: self.stats.drive_onset.map(|o| o.2),
                link_speed_at_onset_rad_s: self.stats.drive_onset.map(|o| o.0),
                commanded_speed_at_onset_rad_s: self.stats.drive_onset.and_then(|o| o.1),
            }),
        })
    }
}

/// The watch of [`StopSpec::Rebound`]: the direction the operator swings in at the first
/// onset, and whether it has moved away from the dome since the last contact.
#[derive(Debug, Default)]
struct Rebound {
    /// The sign of the operator's rate at the first onset (towards the dome).
    towards: Option<f64>,
    away: bool,
}

impl Rebound {
    /// After a step with `outcome`, the operator's rate `rate` [rad/s] and a contact `open`:
    /// whether the operator, out of contact, has turned back towards the dome after moving
    /// away from it (the apex of its rebound).
    fn turned(&mut self, outcome: StepOutcome, rate: f64, open: bool) -> bool {
        if open || matches!(outcome, StepOutcome::ContactOnset | StepOutcome::Peak) {
            self.towards.get_or_insert(rate.signum());
            self.away = false;
            return false;
        }
        let Some(towards) = self.towards else {
            return false;
        };
        if rate * towards < 0.0 {
            self.away = true;
            false
        } else {
            self.away
        }
    }
}

/// An upper bound of |operator accelerometer| \[m/s²\] over a free-swing step that ends in
/// state `y`: out of contact the hinges' energy E (the operator's pendulum and the CJ link's
/// spring) is conserved, so φ̇² ≤ 2E/I_O and 1 − cos φ ≤ E/(M g l_c), which bounds |sin φ| by
/// s; then |l (cos φ φ̈ − sin φ φ̇²)| ≤ l s (ω₀² + φ̇²) with φ̈ = −ω₀² sin φ. 5 % above that for
/// the integrator's error (rtol 1e-12) and the dense output's.
fn swing_accel_bound(system: &FreeHinges, sensors: &FlightSensors, y: &[f64; DIM]) -> f64 {
    let inertia = system.operator_inertia;
    let w0 = system.gravity_moment / inertia;
    let mut energy = 0.5 * inertia * y[1] * y[1] + system.gravity_moment * (1.0 - y[0].cos());
    if let Some((j, k)) = system.robot {
        energy += 0.5 * j * y[3] * y[3] + 0.5 * k * y[2] * y[2];
    }
    let cos_min = 1.0 - energy / system.gravity_moment;
    // (plus 1e-6: the integrator's energy error near the turning points of a tiny swing)
    let sin_max = if cos_min > 0.0 {
        ((1.0 - cos_min * cos_min).sqrt() + 1e-6).min(1.0)
    } else {
        1.0
    };
    1.05 * sensors.arm_length * sin_max * (w0 + 2.0 * energy / inertia)
}

/// Vertex (t, f) of the parabola through three (t, f) points; the middle point if degenerate.
fn parabola_vertex(p: [(f64, f64); 3]) -> (f64, f64) {
    let [(t0, f0), (t1, f1), (t2, f2)] = p;
    let d01 = (f1 - f0) / (t1 - t0);
    let d12 = (f2 - f1) / (t2 - t1);
    let a = (d12 - d01) / (t2 - t0);
    if !(a < 0.0) {
        return (t1, f1);
    }
    let b = d01 - a * (t0 + t1);
    let t = -b / (2.0 * a);
    let f = f1 + d01 * (t - t1) + a * (t - t0) * (t - t1);
    if t >= t0 && t <= t2 && f.is_finite() {
        (t, f)
    } else {
        (t1, f1)
    }
}

/// Loads the bundled materials and runs `scene_text` to its stop condition.
pub fn run_scene_text(
    scene_text: &str,
    recorder: &mut dyn Recorder,
) -> Result<RunSummary, RigError> {
    let materials = Materials::bundled()?;
    let scene = Scene::from_toml_str(scene_text, &materials)?;
    Simulation::new(&scene, RunOptions::default())?.run(recorder)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every frame as text (floats in their shortest round-trip form: equal text, equal bits).
    #[derive(Default)]
    struct Every(Vec<String>);

    impl Recorder for Every {
        fn frame(&mut self, f: &Frame<'_>) -> Result<(), RigError> {
            self.0.push(format!(
                "{:?}",
                (
                    f.t,
                    f.dt,
                    f.outcome,
                    f.operator,
                    f.robot,
                    f.operator_pose,
                    f.dome_body_pose,
                    f.contact,
                    f.energy,
                    f.samples,
                    f.drive,
                )
            ));
            Ok(())
        }
    }

    /// The run and its frames, Rapier stepped even while the operator hangs at rest when
    /// `every_step`.
    fn run_frames(scene: &Scene, every_step: bool) -> (String, Vec<String>) {
        let mut sim = Simulation::new(scene, RunOptions::default()).unwrap();
        if every_step {
            sim.rapier.step_even_at_rest();
        }
        let mut every = Every::default();
        let summary = sim.run(&mut every).unwrap();
        (format!("{summary:?} {:?}", summary.samples), every.0)
    }

    /// Skipping Rapier's step while the operator hangs at rest in equilibrium (the driven
    /// link's approach) changes nothing: the summary, every sample and every frame bit for bit
    /// as with Rapier stepped every time; and the driven scene does skip (the operator hangs at
    /// rest through its approach, Rapier's world holding it alone).
    #[test]
    fn skipping_the_resting_operator_changes_no_bit() {
        let materials = Materials::bundled().unwrap();
        let text = include_str!("../../../assets/scenes/rig_driven_cl.toml");
        let scene = Scene::from_toml_str(text, &materials).unwrap();
        let mut sim = Simulation::new(&scene, RunOptions::default()).unwrap();
        for _ in 0..100 {
            sim.step(&mut NoRecorder).unwrap();
            assert!(sim.rapier.at_rest_in_equilibrium(), "at t = {}", sim.t);
        }
        let (skipped, skipped_frames) = run_frames(&scene, false);
        let (stepped, stepped_frames) = run_frames(&scene, true);
        assert_eq!(skipped_frames.len(), stepped_frames.len());
        for (k, (a, b)) in skipped_frames.iter().zip(&stepped_frames).enumerate() {
            assert_eq!(a, b, "frame {k}");
        }
        assert_eq!(skipped, stepped);
    }
}
