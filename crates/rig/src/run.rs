//! The run loop: a named pipeline per step (check → contact → loads → integrate → events →
//! sensors), a step policy that takes large steps in the free swing, lands on the contact onset
//! and resolves the contact on its own time scale, and the stop condition of the scene.

use flexrig_contact::math::{Pose, Vector};
use flexrig_contact::{ContactCallback, ContactSample, DomeBlockContact, Materials};
use serde::Serialize;

use crate::RigError;
use crate::beam_link::{BeamLink, LinkVariant};
use crate::geometry::RigGeometry;
use crate::scene::{Design, Scene, StopSpec};
use crate::sensors::{Reading, Sampler, SensorSample};
use crate::world::{HingeState, RapierRig};

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
    /// Operator hinge.
    pub operator: HingeState,
    /// Robot hinge (CJ).
    pub robot: Option<HingeState>,
    /// Operator body pose (origin at the pivot).
    pub operator_pose: Pose,
    /// Robot body pose (CJ) or tip section pose (CL).
    pub dome_body_pose: Pose,
    /// The beam (CL).
    pub beam: Option<&'a BeamLink>,
    /// The contact at the end of the step, if touching.
    pub contact: Option<ContactSample>,
    /// Total mechanical energy \[J\] (kinetic, gravity, spring, beam strain, contact).
    pub energy: f64,
    /// Sensor samples taken during this step.
    pub samples: &'a [SensorSample],
}

/// Receives every step (e.g. an MCAP logger). Implementations must not panic; an error stops
/// the run.
pub trait Recorder {
    /// Called after every step.
    fn frame(&mut self, _frame: &Frame<'_>) -> Result<(), RigError> {
        Ok(())
    }
}

/// A recorder that keeps nothing.
#[derive(Debug, Default, Clone, Copy)]
pub struct NoRecorder;

impl Recorder for NoRecorder {}

/// Result of a run.
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
    pub separation_velocity_mps: Option<f64>,
    /// Time of contact onset \[s\] (interpolated within the onset step).
    pub onset_time_s: f64,
    /// Contact duration \[s\] (interpolated at both ends); `None` if the run stopped before
    /// separation.
    pub contact_duration_s: Option<f64>,
    /// Largest indentation \[m\].
    pub max_indentation_m: f64,
    /// Impulse of the contact force ∫ f dt [N·s].
    pub impulse_n_s: f64,
    /// Steps taken (all), and within contact.
    pub steps: usize,
    /// Steps taken in contact.
    pub contact_steps: usize,
    /// Step size used in contact \[s\].
    pub contact_step_s: f64,
    /// Mechanical energy at the start and at the end \[J\].
    pub energy_initial_j: f64,
    /// Mechanical energy at the end \[J\].
    pub energy_final_j: f64,
    /// Mechanical energy just before the contact and just after separation \[J\]; equal for an
    /// undamped contact up to the integration error.
    pub energy_through_contact_j: Option<(f64, f64)>,
    /// Simulated time \[s\].
    pub duration_s: f64,
    /// Sensor samples.
    #[serde(skip)]
    pub samples: Vec<SensorSample>,
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
    phase: Phase,
    contact_step: f64,
    previous_gap: Option<(f64, f64)>,
    onset_tolerance: f64,
    indentation_scale: f64,
    last: Reading,
    sampler: Sampler,
    force_history: [(f64, f64); 3],
    stats: Stats,
}

#[derive(Debug, Clone, Default)]
struct Stats {
    steps: usize,
    contact_steps: usize,
    onset_time: Option<f64>,
    separation_time: Option<f64>,
    impact_velocity: f64,
    peak: Option<(f64, f64)>,
    max_indentation: f64,
    impulse: f64,
    energy_initial: f64,
    energy: f64,
    energy_onset: Option<f64>,
    energy_separation: Option<f64>,
    last_indentation: f64,
    last_contact: Option<ContactSample>,
    separation_velocity: Option<f64>,
}

/// Factor of the Hertz contact duration t_c ≈ C δ_max/v0 used to size the contact step
/// (C = 2.94 for n = 3/2, π for n = 1; 3 is close for the fitted exponents 1.8–2.0).
const CONTACT_TIME_FACTOR: f64 = 3.0;

impl<'s> Simulation<'s> {
    /// Builds the rig of `scene` in its initial state.
    pub fn new(scene: &'s Scene, options: RunOptions) -> Result<Self, RigError> {
        let geometry = RigGeometry::of(scene);
        let op = &geometry.operator;
        let g = scene.file.gravity_mps2;
        let design = scene.file.robot.design;
        let rapier = RapierRig::new(g, op, (design == Design::Cj).then_some(&geometry.robot));
        let swing =
            scene
                .file
                .operator
                .start
                .initial_swing(op.mass, op.com_distance, op.inertia_pivot, g);
        let v_impact = swing.rate_at_contact * op.arm_length;
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

        let mut sim = Simulation {
            scene,
            options,
            geometry,
            rapier,
            robot,
            contact,
            t: 0.0,
            phase: Phase::Swing,
            contact_step,
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
            },
            sampler: Sampler::new(scene.file.record.sample_rate_hz),
            force_history: [(0.0, 0.0); 3],
            stats: Stats::default(),
        };
        // Rapier's symplectic Euler (kick, then drift) is leapfrog with the velocity half a step
        // behind the position: start it from ω(−dt/2) = ω₀ − (dt/2) α(φ₀), so that a swing that
        // starts moving keeps second-order accuracy (from ω₀ itself the impact speed of a start
        // at −10°, −1 rad/s was off by 7e-4; now 1e-6). No contact acts at a swing start.
        let alpha0 = -op.mass * g * op.com_distance * swing.angle.sin() / op.inertia_pivot;
        let half_kick = if swing.starts_in_contact {
            0.0
        } else {
            0.5 * scene.file.solver.swing_step_s * alpha0
        };
        let initial = HingeState {
            angle: swing.angle,
            rate: swing.rate - half_kick,
        };
        if swing.starts_in_contact {
            sim.phase = Phase::Contact;
            // Touching at t = 0: the onset is the start of the first step.
            sim.previous_gap = Some((0.0, 0.0));
        }
        let robot_initial = (design == Design::Cj).then_some(HingeState {
            angle: 0.0,
            rate: 0.0,
        });
        sim.rapier.set_state(initial, robot_initial);
        sim.stats.energy_initial = sim.energy(None);
        sim.stats.energy = sim.stats.energy_initial;
        sim.last = sim.reading(None);
        Ok(sim)
    }

    /// Simulated time \[s\].
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The geometry.
    pub fn geometry(&self) -> &RigGeometry {
        &self.geometry
    }

    /// Step size used in contact \[s\].
    pub fn contact_step(&self) -> f64 {
        self.contact_step
    }

    fn dome_kinematics(&self) -> flexrig_contact::BodyKinematics {
        match &self.robot {
            RobotSide::Rigid { .. } => self
                .rapier
                .robot_kinematics()
                .expect("a rigid robot lives in Rapier"),
            RobotSide::Beam(b) => b.tip_kinematics(),
        }
    }

    fn evaluate_contact(&self) -> Option<ContactSample> {
        self.contact
            .evaluate(&self.dome_kinematics(), &self.rapier.operator_kinematics())
    }

    fn gap(&self) -> f64 {
        self.contact.gap(
            &self.dome_kinematics().pose,
            &self.rapier.operator_kinematics().pose,
        )
    }

    /// Total mechanical energy \[J\].
    fn energy(&self, contact: Option<&ContactSample>) -> f64 {
        let op = &self.geometry.operator;
        let s = self.rapier.operator_state();
        let g = self.scene.file.gravity_mps2;
        let mut e = 0.5 * op.inertia_pivot * s.rate * s.rate
            + op.mass * g * op.com_distance * (1.0 - s.angle.cos());
        e += match &self.robot {
            RobotSide::Rigid { spring } => {
                let r = self
                    .rapier
                    .robot_state()
                    .expect("a rigid robot lives in Rapier");
                0.5 * self.geometry.robot.inertia_axis * r.rate * r.rate
                    + 0.5 * spring * r.angle * r.angle
            }
            RobotSide::Beam(b) => b.energy(),
        };
        if let Some(c) = contact {
            e += self.contact.law().elastic_energy(c.indentation);
        }
        e
    }

    fn reading(&self, contact: Option<&ContactSample>) -> Reading {
        let op = self.rapier.operator_state();
        let l = self.geometry.operator.arm_length;
        let (robot_angle, tip_deflection, load_velocity) = match &self.robot {
            RobotSide::Rigid { .. } => {
                let r = self
                    .rapier
                    .robot_state()
                    .expect("a rigid robot lives in Rapier");
                let len = self.geometry.robot.length;
                (r.angle, len * r.angle.sin(), len * r.angle.cos() * r.rate)
            }
            RobotSide::Beam(b) => {
                let (v, vdot, _) = b.tip_transverse();
                (0.0, v, vdot)
            }
        };
        Reading {
            t: self.t,
            operator_angle: op.angle,
            robot_angle,
            tip_deflection,
            operator_velocity: l * op.angle.cos() * op.rate,
            load_velocity,
            force: contact.map_or(0.0, |c| c.force),
        }
    }

    /// The next step size: the contact step in contact; in the swing the swing step, shortened to
    /// land on the predicted onset (secant on the gap).
    fn next_step(&mut self) -> f64 {
        let swing = self.scene.file.solver.swing_step_s;
        match self.phase {
            Phase::Contact => self.contact_step,
            Phase::After => {
                // Back to swing steps (and onset prediction) once the bodies are well apart:
                // five peak indentations (the swing phase predicts the next onset).
                if self.gap() > 5.0 * self.indentation_scale {
                    self.phase = Phase::Swing;
                    self.previous_gap = None;
                    return self.next_step();
                }
                swing.min(self.contact_step * 10.0).max(self.contact_step)
            }
            Phase::Swing => {
                let gap = self.gap();
                if gap <= self.onset_tolerance {
                    self.phase = Phase::Contact;
                    return self.contact_step;
                }
                let step = match self.previous_gap {
                    Some((t_prev, g_prev)) if self.t > t_prev => {
                        let rate = (gap - g_prev) / (self.t - t_prev);
                        if rate < 0.0 && gap + rate * swing < 0.0 {
                            (gap / -rate).max(self.contact_step * 1e-3)
                        } else {
                            swing
                        }
                    }
                    _ => swing,
                };
                self.previous_gap = Some((self.t, gap));
                step
            }
        }
    }

    /// One step of the pipeline: check → contact → loads → integrate → events → sensors.
    pub fn step(&mut self, recorder: &mut dyn Recorder) -> Result<StepOutcome, RigError> {
        let dt = self.next_step();
        // Contact force at the start of the step, held over it (explicit coupling).
        let contact = self.evaluate_contact();
        let spring_torque = match &self.robot {
            RobotSide::Rigid { spring } => {
                -spring * self.rapier.robot_state().expect("rigid robot").angle
            }
            RobotSide::Beam(_) => 0.0,
        };
        // For the beam, the contact at the end of the step: the operator's end state is exactly
        // what Rapier's symplectic Euler will produce, the tip's is predicted to second order.
        let contact_at_end = match &self.robot {
            RobotSide::Beam(b) => {
                let op_end = self.operator_state_after(dt, contact.as_ref());
                self.contact.evaluate(
                    &b.predicted_tip_kinematics(dt),
                    &self.rapier.operator_kinematics_at(op_end),
                )
            }
            RobotSide::Rigid { .. } => None,
        };
        self.rapier.apply_loads(contact.as_ref(), spring_torque);
        self.rapier.step(dt);
        if let RobotSide::Beam(b) = &mut self.robot {
            b.step(dt, contact_at_end.as_ref())?;
        }
        self.t += dt;
        self.stats.steps += 1;
        if let Some(c) = &contact {
            self.stats.impulse += c.force * dt;
        }

        let after = self.evaluate_contact();
        let outcome = self.classify(after.as_ref(), dt);
        let energy = self.energy(after.as_ref());
        self.check_health(energy)?;
        match outcome {
            // The energy at the start of the onset step, when nothing touched yet.
            StepOutcome::ContactOnset => self.stats.energy_onset = Some(self.stats.energy),
            StepOutcome::Separation if self.stats.energy_separation.is_none() => {
                self.stats.energy_separation = Some(energy)
            }
            _ => {}
        }
        self.stats.energy = energy;

        let reading = self.reading(after.as_ref());
        let sampled_before = self.sampler.samples().len();
        self.sampler.record_step(&self.last, &reading);
        self.last = reading;

        let operator_pose = self.rapier.operator_kinematics().pose;
        let dome_body_pose = self.dome_kinematics().pose;
        let (robot_state, beam) = match &self.robot {
            RobotSide::Rigid { .. } => (self.rapier.robot_state(), None),
            RobotSide::Beam(b) => (None, Some(b.as_ref())),
        };
        recorder.frame(&Frame {
            t: self.t,
            dt,
            outcome,
            operator: self.rapier.operator_state(),
            robot: robot_state,
            operator_pose,
            dome_body_pose,
            beam,
            contact: after,
            energy,
            samples: &self.sampler.samples()[sampled_before..],
        })?;
        Ok(outcome)
    }

    /// The operator's hinge state after a symplectic Euler step of `dt` with the contact force
    /// `contact` and gravity: ω' = ω + dt (τ_contact + τ_gravity)/J, φ' = φ + dt ω'.
    fn operator_state_after(&self, dt: f64, contact: Option<&ContactSample>) -> HingeState {
        let op = &self.geometry.operator;
        let s = self.rapier.operator_state();
        let mut torque = -op.mass * self.scene.file.gravity_mps2 * op.com_distance * s.angle.sin();
        if let Some(c) = contact {
            torque += (c.point - op.pivot).cross(c.force_on_block()).x;
        }
        let rate = s.rate + dt * torque / op.inertia_pivot;
        HingeState {
            angle: s.angle + dt * rate,
            rate,
        }
    }

    /// Updates the contact statistics and names the event of the step.
    fn classify(&mut self, after: Option<&ContactSample>, dt: f64) -> StepOutcome {
        match (self.stats.onset_time, after) {
            (None, Some(c)) => {
                // Onset inside this step: interpolate on the gap (was ≥ 0, now −δ).
                let frac = self
                    .previous_gap_at_step_start()
                    .map_or(1.0, |g0| g0 / (g0 + c.indentation));
                self.stats.onset_time = Some(self.t - dt + frac * dt);
                self.stats.impact_velocity = c.rate;
                self.phase = Phase::Contact;
                self.note_contact(c);
                StepOutcome::ContactOnset
            }
            (Some(_), Some(c)) => {
                self.note_contact(c);
                let [(_, f0), (_, f1), (_, f2)] = self.force_history;
                if self.stats.peak.is_none() && f2 < f1 && f1 >= f0 && f1 > 0.0 {
                    self.stats.peak = Some(parabola_vertex(self.force_history));
                    return StepOutcome::Peak;
                }
                StepOutcome::Advanced
            }
            (Some(_), None) if self.phase == Phase::Contact => {
                let gap = self.gap().max(0.0);
                let d0 = self.stats.last_indentation;
                let frac = if d0 + gap > 0.0 { d0 / (d0 + gap) } else { 1.0 };
                // The summary describes the first contact; later ones (a duration run) only
                // add to the impulse and the step counts.
                if self.stats.separation_time.is_some() {
                    self.phase = Phase::After;
                    self.previous_gap = None;
                    return StepOutcome::Separation;
                }
                self.stats.separation_time = Some(self.t - dt + frac * dt);
                // Relative normal velocity at the last contact point, positive when parting.
                if let Some(c) = self.stats.last_contact {
                    let dome = self.dome_kinematics();
                    let block = self.rapier.operator_kinematics();
                    self.stats.separation_velocity = Some(
                        -(dome.velocity_at(c.point) - block.velocity_at(c.point)).dot(c.normal),
                    );
                }
                self.phase = Phase::After;
                self.previous_gap = None;
                StepOutcome::Separation
            }
            _ => StepOutcome::Advanced,
        }
    }

    fn previous_gap_at_step_start(&self) -> Option<f64> {
        self.previous_gap.map(|(_, g)| g.max(0.0))
    }

    fn note_contact(&mut self, c: &ContactSample) {
        self.stats.contact_steps += 1;
        self.stats.max_indentation = self.stats.max_indentation.max(c.indentation);
        self.stats.last_indentation = c.indentation;
        self.stats.last_contact = Some(*c);
        self.force_history = [
            self.force_history[1],
            self.force_history[2],
            (self.t, c.force),
        ];
    }

    /// Stops on a non-finite state or on energy growth beyond the limit.
    fn check_health(&self, energy: f64) -> Result<(), RigError> {
        let op = self.rapier.operator_state();
        let suggestion = if self.phase == Phase::Contact {
            format!(
                "solver.contact_steps (more than {})",
                self.scene.file.solver.contact_steps
            )
        } else {
            format!(
                "solver.swing_step_s (below {:e} s)",
                self.scene.file.solver.swing_step_s
            )
        };
        if !(op.angle.is_finite() && op.rate.is_finite() && energy.is_finite()) {
            return Err(RigError::Unstable {
                t: self.t,
                quantity: "the state".into(),
                reason: "became non-finite".into(),
                suggestion,
            });
        }
        let e0 = self.stats.energy_initial;
        if energy > e0 * (1.0 + self.options.energy_growth_limit) + 1e-12 {
            return Err(RigError::Unstable {
                t: self.t,
                quantity: "the mechanical energy".into(),
                reason: format!(
                    "grew from {e0:.6e} J to {energy:.6e} J (more than {:.0} %)",
                    100.0 * self.options.energy_growth_limit
                ),
                suggestion,
            });
        }
        Ok(())
    }

    /// Runs to the scene's stop condition.
    pub fn run(mut self, recorder: &mut dyn Recorder) -> Result<RunSummary, RigError> {
        let stop = self.scene.file.stop;
        let max_steps = self.scene.file.solver.max_steps;
        loop {
            if self.stats.steps >= max_steps {
                return Err(RigError::NotReached {
                    what: format!("{stop:?}"),
                    limit: format!("solver.max_steps = {max_steps}"),
                });
            }
            let outcome = self.step(recorder)?;
            let done = match stop {
                StopSpec::Peak => outcome == StepOutcome::Peak,
                StopSpec::Separation => outcome == StepOutcome::Separation,
                StopSpec::Duration { duration_s } => self.t >= duration_s,
            };
            if done {
                break;
            }
            if let StopSpec::Peak | StopSpec::Separation = stop
                && self.stats.onset_time.is_none()
                && self.t > 60.0
            {
                return Err(RigError::NotReached {
                    what: "contact".into(),
                    limit: "60 s of simulated time (does the pendulum reach the dome?)".into(),
                });
            }
        }
        let (time_of_peak, peak_force) = self.stats.peak.unwrap_or_else(|| {
            let (t, f) = self.force_history[2];
            (t, f)
        });
        Ok(RunSummary {
            scene: self.scene.file.name.clone(),
            design: self.scene.file.robot.design,
            peak_force_n: peak_force,
            time_of_peak_s: time_of_peak,
            impact_velocity_mps: self.stats.impact_velocity,
            separation_velocity_mps: self.stats.separation_velocity,
            onset_time_s: self.stats.onset_time.unwrap_or(f64::NAN),
            contact_duration_s: self
                .stats
                .separation_time
                .zip(self.stats.onset_time)
                .map(|(s, o)| s - o),
            max_indentation_m: self.stats.max_indentation,
            impulse_n_s: self.stats.impulse,
            steps: self.stats.steps,
            contact_steps: self.stats.contact_steps,
            contact_step_s: self.contact_step,
            energy_initial_j: self.stats.energy_initial,
            energy_final_j: self.stats.energy,
            energy_through_contact_j: self.stats.energy_onset.zip(self.stats.energy_separation),
            duration_s: self.t,
            samples: self.sampler.into_samples(),
        })
    }
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
