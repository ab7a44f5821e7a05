//! The run loop's side of the adaptive contact (`solver.contact = "adaptive"`): the contact
//! begun at the located onset, stepped by the free flight's DOP853 with the contact force
//! ([`crate::contact_flight`]), its statistics (peak, largest indentation, impulse) from the
//! dense output, and the free flight resumed at the located separation.

use flexrig_contact::ContactSample;
use flexrig_contact::math::Vector;

use super::{OpenContact, Phase, RobotSide, Simulation, StepOutcome, Synced};
use crate::RigError;
use crate::contact_flight::{HingesInContact, sample_times, search_max, simpson};
use crate::free_flight::EVENT_SUBINTERVALS;
use crate::free_flight::{CONTACT_RTOL, ContactPolicy, DIM, FreeFlight, FreeHinges};
use crate::hinge::HingeState;
use crate::limits::CONTACT_TIME_FACTOR;
use crate::run::Recorder;
use crate::scene::StopSpec;
use flexrig_lumped::ode::dop853::DenseOutput;

/// The maxima of the contact in progress.
#[derive(Debug, Clone, Copy)]
pub(super) struct PeakSearch {
    /// Time \[s\] and value \[N\] of the largest force so far.
    force: (f64, f64),
    /// Largest indentation so far \[m\].
    indentation: f64,
    /// True once the force has fallen below its largest value.
    found: bool,
    /// Steps taken in this contact.
    steps: usize,
    /// The last step's interpolant and sample times (a maximum at its end is searched on both
    /// sides of it).
    previous: Option<(DenseOutput<DIM>, [f64; EVENT_SUBINTERVALS + 1])>,
}

/// Samples of one quantity at the sample times of a step.
type Samples = [f64; EVENT_SUBINTERVALS + 1];

/// The largest value of a quantity of the contact (`value` of a state) given its largest so far
/// `best` and its `samples` on the present step (interpolant `dense`, times `times`): when the
/// step's largest sample is not at its end (the quantity has turned), the maximum searched on
/// the sub-intervals next to it — at the step's start also on the last sub-interval of the
/// `previous` step.
fn refine_max(
    best: (f64, f64),
    samples: &Samples,
    times: &Samples,
    at: impl Fn(f64) -> [f64; DIM],
    previous: Option<&(DenseOutput<DIM>, Samples)>,
    value: impl Fn(&[f64; DIM]) -> f64,
) -> (f64, f64) {
    let last = EVENT_SUBINTERVALS;
    let k = samples
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(k, _)| k);
    if samples[k] < best.1 {
        return best;
    }
    if k == last {
        // still rising: the step's end, refined once the quantity turns
        return (times[k], samples[k]);
    }
    let mut found = search_max(times[k.saturating_sub(1)], times[k + 1], |t| value(&at(t)));
    if k == 0
        && let Some((dense, t)) = previous
    {
        let before = search_max(t[last - 1], t[last], |t| value(&dense.eval(t)));
        if before.1 > found.1 {
            found = before;
        }
    }
    if found.1 >= best.1 { found } else { best }
}

impl Simulation<'_> {
    /// True when the scene's contact is integrated adaptively.
    pub(super) fn adaptive_contact(&self) -> bool {
        self.scene.contact_integration() == ContactPolicy::Adaptive
            && matches!(self.robot, RobotSide::Rigid { .. })
            && self.scene.drive.is_none()
    }

    /// The CJ's hinges without the contact.
    fn rigid_hinges(&self) -> FreeHinges {
        let op = &self.geometry.operator;
        let spring = match self.robot {
            RobotSide::Rigid { spring } => spring,
            RobotSide::Beam(_) => unreachable!("the adaptive contact is the CJ's"),
        };
        FreeHinges {
            operator_inertia: op.inertia_pivot,
            gravity_moment: op.mass * self.scene.file.gravity_mps2 * op.com_distance,
            robot: Some((self.geometry.robot.inertia_axis, spring)),
        }
    }

    /// The synchronised state as the flight's y = (φ, φ̇, ψ, ψ̇, sin φ, cos φ).
    pub(super) fn flight_state(&self) -> [f64; DIM] {
        let s = self.now.operator;
        let r = self
            .now
            .robot
            .map_or((0.0, 0.0), |(r, _)| (r.angle, r.rate));
        let (sin, cos) = s.angle.sin_cos();
        [s.angle, s.rate, r.0, r.1, sin, cos]
    }

    /// Starts the adaptive contact at the present time in state `y` (the onset): the contact
    /// opened with its approach speed and energy, DOP853 with the tolerances of
    /// `solver.contact_rtol` relative to the peak indentation (angles: over the arm and the link
    /// length) and to the impact speed (rates), steps of at most a third of the estimated contact
    /// time.
    pub(super) fn begin_contact_flight(&mut self, y: [f64; DIM]) {
        let free = self.rigid_hinges();
        let system = HingesInContact {
            free,
            contact: &self.contact,
            rapier: &self.rapier,
            pivot: self.geometry.operator.pivot,
        };
        let (_, rate) = system.approach(&y);
        if !self.stats.contacts.is_empty() && rate > 0.0 {
            self.size_contact(rate);
        }
        let rtol = self.scene.file.solver.contact_rtol.unwrap_or(CONTACT_RTOL);
        let (arm, link) = (
            self.geometry.operator.arm_length,
            self.geometry.robot.length,
        );
        let depth = rtol * self.indentation_scale;
        let speed = rtol * rate.max(1e-3);
        let atol = [
            depth / arm,
            speed / arm,
            depth / link,
            speed / link,
            depth / arm,
            depth / arm,
        ];
        let contact_time = self.contact_step * self.scene.file.solver.contact_steps as f64;
        let system = HingesInContact {
            free,
            contact: &self.contact,
            rapier: &self.rapier,
            pivot: self.geometry.operator.pivot,
        };
        let flight = FreeFlight::in_contact(
            free,
            &system,
            self.t,
            y,
            (rtol, atol),
            contact_time / CONTACT_TIME_FACTOR,
        );
        self.flight = Some(flight);
        self.peak_search = Some(PeakSearch {
            force: (self.t, 0.0),
            indentation: 0.0,
            found: false,
            steps: 0,
            previous: None,
        });
        self.stats.open = Some(OpenContact {
            onset_time: self.t,
            impact_velocity: rate,
            energy_before: self.stats.energy,
            force_history: [(self.t, 0.0); 3],
            peak: None,
            max_indentation: 0.0,
            impulse: 0.0,
            last_indentation: 0.0,
            last: ContactSample {
                indentation: 0.0,
                rate,
                force: 0.0,
                normal: Vector::Y,
                point: Vector::ZERO,
            },
        });
        self.phase = Phase::Contact;
    }

    /// The synchronised state of the contact flight's `y` with the contact `c`.
    fn contact_synced(&self, y: &[f64; DIM], c: Option<ContactSample>) -> Synced {
        let operator = HingeState {
            angle: y[0],
            rate: y[1],
        };
        let robot = HingeState {
            angle: y[2],
            rate: y[3],
        };
        let (operator_accel, robot_accel) =
            self.accelerations(operator, Some(robot), 0.0, c.as_ref());
        Synced {
            operator,
            operator_accel,
            robot: robot_accel.map(|a| (robot, a)),
            contact: c,
            rotor: None,
        }
    }

    /// One accepted DOP853 step of the contact, ending at the separation if it reaches it (then
    /// the contact is closed and the free flight resumes); the force, the indentation and the
    /// sensors sampled on its dense output.
    pub(super) fn contact_flight_step(
        &mut self,
        recorder: &mut dyn Recorder,
    ) -> Result<StepOutcome, RigError> {
        let t_limit = match self.scene.file.stop {
            StopSpec::Duration { duration_s } => Some(duration_s),
            StopSpec::Peak | StopSpec::Separation | StopSpec::Rebound => None,
        };
        let mut flight = self.flight.take().expect("in the adaptive contact");
        let mut search = self.peak_search.take().expect("in the adaptive contact");
        let system = HingesInContact {
            free: *flight.system(),
            contact: &self.contact,
            rapier: &self.rapier,
            pivot: self.geometry.operator.pivot,
        };
        let step = match flight.step_with(&system, t_limit, |y| -system.gap(y)) {
            Ok(step) => step,
            Err(failure) => {
                return Err(RigError::Unstable {
                    t: self.t,
                    quantity: "the contact (adaptive integration)".into(),
                    reason: format!("failed: {failure:?}"),
                    suggestion: format!(
                        "solver.contact = \"fixed\" or a larger solver.contact_rtol (now {:e})",
                        self.scene.file.solver.contact_rtol.unwrap_or(CONTACT_RTOL)
                    ),
                });
            }
        };
        let dense = flight.dense_with(&system);
        let times = sample_times(&dense, step.t_end);
        let at = |t: f64| {
            if t == step.t_end {
                step.y
            } else {
                dense.eval(t)
            }
        };
        let contacts = times.map(|t| system.sample(&at(t)));
        let forces = contacts.map(|c| c.map_or(0.0, |c| c.force));
        let depths = contacts.map(|c| c.map_or(0.0, |c| c.indentation));
        let last = forces.len() - 1;
        let force_of = |y: &[f64; DIM]| system.sample(y).map_or(0.0, |c| c.force);
        let depth_of = |y: &[f64; DIM]| system.sample(y).map_or(0.0, |c| c.indentation);
        let previous = search.previous.as_ref();
        search.force = refine_max(search.force, &forces, &times, at, previous, force_of);
        search.indentation = refine_max(
            (0.0, search.indentation),
            &depths,
            &times,
            at,
            previous,
            depth_of,
        )
        .1;
        search.previous = Some((dense, times));
        let peak_now = !search.found && search.force.1 > 0.0 && forces[last] < search.force.1;
        search.found |= peak_now;
        search.steps += 1;
        // Sensors from the dense output.
        let sampled_before = self.sampler.samples().len();
        let (arm, link) = (
            self.geometry.operator.arm_length,
            self.geometry.robot.length,
        );
        self.sampler.record_exact(step.t_start, step.t_end, |t| {
            system.sensors(t, &at(t), arm, link)
        });
        // At the located separation the contact has closed (as after Rapier's separation step,
        // which is not counted in contact and logs no contact).
        let end_contact = if step.onset {
            None
        } else {
            system.sample(&step.y)
        };
        let parting = -system.approach(&step.y).1;
        let impulse = simpson(step.t_start, step.t_end, &forces);
        // The new state.
        self.t = step.t_end;
        self.h_prev = 0.0;
        self.now = self.contact_synced(&step.y, end_contact);
        self.stats.steps += 1;
        if !step.onset {
            self.stats.contact_steps += 1;
        }
        let energy = self.energy();
        self.check_health(energy)?;
        self.stats.energy = energy;
        let open = self.stats.open.as_mut().expect("an open contact");
        open.impulse += impulse;
        open.peak = Some(search.force);
        open.max_indentation = search.indentation;
        open.last_indentation = depths[last];
        if let Some(c) = end_contact {
            open.last = c;
        }
        let first_contact = self.stats.contacts.is_empty();
        let mut outcome = if search.steps == 1 {
            StepOutcome::ContactOnset
        } else {
            StepOutcome::Advanced
        };
        if peak_now && first_contact {
            outcome = StepOutcome::Peak;
        }
        if step.onset {
            // Separated: the contact closed, the free flight resumed (Rapier, stepped by neither,
            // is given the state when a fixed step needs it).
            let open = self.stats.open.take().expect("an open contact");
            let event = open.event(Some((self.t, parting, energy)));
            self.stats.contacts.push(event);
            self.phase = Phase::After;
            self.previous_gap = None;
            if !(outcome == StepOutcome::Peak && self.scene.file.stop == StopSpec::Peak) {
                outcome = StepOutcome::Separation;
            }
            self.start_free_flight();
        } else {
            self.flight = Some(flight);
            self.peak_search = Some(search);
        }
        self.last = self.reading();
        let dt = step.t_end - step.t_start;
        self.emit(recorder, dt, outcome, energy, sampled_before)?;
        Ok(outcome)
    }
}
