//! Physical ranges of the scene quantities and the work budget of a run, checked before it
//! starts: a scene that would take longer than `solver.max_steps`, keep more sensor samples
//! than [`MAX_SAMPLES`], or step so finely that time stops advancing is refused with an error
//! naming the scene field and the limit (docs/scenes.md lists both).

use crate::RigError;
use crate::canonical::compound_pendulum_period;
use crate::error::invalid;
use crate::geometry::RigGeometry;
use crate::scene::{BeamSolverSpec, Scene, Start, StopSpec};

/// Factor of the Hertz contact duration t_c ≈ C δ_max/v0 used to size the contact step
/// (C = 2.94 for n = 3/2, π for n = 1; 3 is close for the fitted exponents 1.8–2.0).
pub(crate) const CONTACT_TIME_FACTOR: f64 = 3.0;

/// An allowed closed interval of a scene quantity, in the field's unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Smallest allowed value.
    pub lo: f64,
    /// Largest allowed value.
    pub hi: f64,
}

impl Range {
    /// Checks that `value` lies in the range, naming `field` otherwise.
    pub fn check(&self, field: &str, value: f64) -> Result<f64, RigError> {
        if value.is_finite() && value >= self.lo && value <= self.hi {
            Ok(value)
        } else {
            Err(invalid(
                field,
                flexrig_contact::validate::display(value),
                &flexrig_contact::validate::interval_with_hint(field, value, self.lo, self.hi),
            ))
        }
    }
}

const fn range(lo: f64, hi: f64) -> Range {
    Range { lo, hi }
}

/// Gravitational acceleration [m/s²]: up to ten times the Earth's.
pub const GRAVITY: Range = range(0.01, 100.0);
/// Pendulum arm, link length \[m\].
pub const LENGTH: Range = range(0.01, 10.0);
/// Arm mass \[kg\] (0: a massless arm).
pub const ARM_MASS: Range = range(0.0, 1e3);
/// Block mass \[kg\].
pub const BLOCK_MASS: Range = range(1e-6, 1e4);
/// Block edge, dome radius, dome standoff \[m\].
pub const SIZE: Range = range(1e-4, 10.0);
/// Initial angular velocity of a moving start [rad/s].
pub const ANGULAR_VELOCITY: Range = range(-100.0, 100.0);
/// Link width \[m\].
pub const WIDTH: Range = range(1e-5, 1.0);
/// Link thickness \[m\].
pub const THICKNESS: Range = range(1e-6, 0.5);
/// Young's modulus \[Pa\]: from soft rubber to diamond.
pub const YOUNGS_MODULUS: Range = range(1e5, 1.2e12);
/// Density [kg/m³].
pub const DENSITY: Range = range(1.0, 1e5);
/// Payload \[kg\].
pub const PAYLOAD: Range = range(0.0, 1e4);
/// Torsion spring [N·m/rad].
pub const TORSION_SPRING: Range = range(1e-6, 1e9);
/// Hertz stiffness [N/m^n].
pub const CONTACT_K: Range = range(1e-3, 1e20);
/// ADAMS IMPACT maximum damping [N·s/m].
pub const DAMPING_C_MAX: Range = range(0.0, 1e9);
/// ADAMS IMPACT damping depth \[m\].
pub const DAMPING_DEPTH: Range = range(1e-9, 1.0);
/// Swing step \[s\].
pub const SWING_STEP: Range = range(1e-8, 0.1);
/// Relative tolerance of the adaptive contact (`solver.contact_rtol`).
pub const CONTACT_RTOL: Range = range(1e-13, 1e-2);
/// Simulated duration \[s\].
pub const DURATION: Range = range(1e-6, 1e4);
/// Sensor sampling rate \[Hz\].
pub const SAMPLE_RATE: Range = range(1.0, 1e8);
/// Steps per contact.
pub const CONTACT_STEPS: (usize, usize) = (4, 100_000_000);
/// Cap on the steps of a run.
pub const MAX_STEPS: (usize, usize) = (1, 1_000_000_000);
/// CL beam elements; the modal-reduced beam solves a dense eigenproblem (O(n³)): fewer.
pub const BEAM_ELEMENTS: (usize, usize) = (1, 4096);
/// Largest mesh for `solver.beam = { model = "modal" }`.
pub const MODAL_BEAM_ELEMENTS: usize = 1000;
/// Most sensor samples a run keeps in memory (56 B each: 560 MB).
pub const MAX_SAMPLES: f64 = 1e7;

/// Checks an integer field against `(lo, hi)`.
pub fn check_count(field: &str, value: usize, (lo, hi): (usize, usize)) -> Result<usize, RigError> {
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(invalid(field, value, &format!("must lie in [{lo}, {hi}]")))
    }
}

/// The work a scene will take, estimated before it runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    /// Simulated time \[s\] (to the stop condition; for peak/separation: to the first contact's
    /// end, bounded by a full pendulum period).
    pub simulated_s: f64,
    /// Steps.
    pub steps: f64,
    /// Sensor samples.
    pub samples: f64,
}

/// Estimates the work of `scene` and refuses it if it exceeds `solver.max_steps`,
/// [`MAX_SAMPLES`], or if its contact step is too small for time to advance.
pub fn check_budget(scene: &Scene) -> Result<Budget, RigError> {
    let file = &scene.file;
    let g = RigGeometry::of(scene);
    let op = &g.operator;
    let gravity = file.gravity_mps2;
    // The swing's amplitude from its energy; a start that would go over the top is refused.
    let swing =
        file.operator
            .start
            .initial_swing(op.mass, op.com_distance, op.inertia_pivot, gravity);
    let energy = 0.5 * op.inertia_pivot * swing.rate * swing.rate
        + op.mass * gravity * op.com_distance * (1.0 - swing.angle.cos());
    let cos_amplitude = 1.0 - energy / (op.mass * gravity * op.com_distance);
    if !(cos_amplitude >= 170f64.to_radians().cos() - 1e-12) {
        let (field, value) = match file.operator.start {
            Start::Moving {
                angular_velocity_rad_s,
                ..
            } => (
                "operator.start.angular_velocity_rad_s",
                flexrig_contact::validate::display(angular_velocity_rad_s),
            ),
            Start::Release { release_angle_deg } | Start::Contact { release_angle_deg } => (
                "operator.start.release_angle_deg",
                flexrig_contact::validate::display(release_angle_deg),
            ),
        };
        return Err(invalid(
            field,
            value,
            "must leave the swing below 170° (the pendulum would go over the top)",
        ));
    }
    let period = compound_pendulum_period(op, gravity, cos_amplitude.acos().max(1e-6));
    // Contacts: one per half period at most (the block returns each swing).
    let simulated_s = match file.stop {
        StopSpec::Duration { duration_s } => duration_s,
        StopSpec::Peak | StopSpec::Separation | StopSpec::Rebound => match &scene.drive {
            Some(d) => period.max(d.approach_time_estimate()),
            None => period,
        },
    };
    let contacts = (2.0 * simulated_s / period).ceil().max(1.0);
    let swing_steps = simulated_s / file.solver.swing_step_s;
    let contact_steps = contacts * file.solver.contact_steps as f64;
    let impact = first_impact_estimate(scene);
    let contact_time = CONTACT_TIME_FACTOR * impact.peak_indentation_m / impact.speed_mps;
    let contact_step = contact_time / file.solver.contact_steps as f64;
    // A run to a fixed time may end with the pendulum resting against the block (each contact
    // loses energy to the link's vibration or the damping, the bounces shorten, and the last
    // contact lasts to the end): then every step after the first impact is a contact step, and
    // the run takes up to duration / contact step steps. The estimate counts that case rather
    // than one contact per half period, so a run it admits reaches its stop.
    let resting_steps = match file.stop {
        StopSpec::Duration { .. } => simulated_s / contact_step,
        StopSpec::Peak | StopSpec::Separation | StopSpec::Rebound => 0.0,
    };
    let steps = (swing_steps + contact_steps).max(resting_steps);
    let max_steps = file.solver.max_steps as f64;
    if steps > max_steps {
        let (field, value) = if swing_steps >= contact_steps.max(resting_steps) {
            (
                "solver.swing_step_s",
                format!("{:e}", file.solver.swing_step_s),
            )
        } else {
            (
                "solver.contact_steps",
                file.solver.contact_steps.to_string(),
            )
        };
        return Err(invalid(
            field,
            value,
            &format!(
                "the run would take up to {steps:.3e} steps ({simulated_s:.3e} s simulated, \
                 {}), more than solver.max_steps = {max_steps:e}: raise solver.max_steps, take \
                 larger steps, or a shorter stop",
                if resting_steps > swing_steps + contact_steps {
                    format!(
                        "in contact from the first impact on, as when the pendulum comes to \
                         rest against the block, at a contact step of {contact_step:.3e} s"
                    )
                } else {
                    format!("{contacts} contact(s)")
                }
            ),
        ));
    }
    let samples = simulated_s * file.record.sample_rate_hz;
    if samples > MAX_SAMPLES {
        return Err(invalid(
            "record.sample_rate_hz",
            file.record.sample_rate_hz,
            &format!(
                "{simulated_s:.3e} s at this rate would keep {samples:.3e} sensor samples, more \
                 than {MAX_SAMPLES:e}: lower the rate or shorten the stop"
            ),
        ));
    }
    // The contact step must be representable next to the time reached.
    if !(contact_step > 1e-12 * simulated_s.max(1.0) && contact_time.is_finite()) {
        return Err(invalid(
            "solver.contact_steps",
            file.solver.contact_steps,
            &format!(
                "gives a contact step of {contact_step:.3e} s over a contact of \
                 {contact_time:.3e} s, too small for time to advance over {simulated_s:.3e} s: \
                 take fewer contact steps (or a stiffer contact.k)"
            ),
        ));
    }
    // An ADAMS damping far past the contact's critical damping makes the contact stick and the
    // coupled step unstable: refused with the bound, before the run.
    if let Err(flexrig_contact::ContactError::InvalidParameter { value, allowed, .. }) = file
        .contact
        .damping
        .check_overdamping(scene.hertz, impact.reduced_mass_kg, impact.speed_mps)
    {
        return Err(invalid("contact.damping.c_max_n_s_per_m", value, &allowed));
    }
    Ok(Budget {
        simulated_s,
        steps,
        samples,
    })
}

/// The first impact of a scene as the lumped two-mass model sees it: the pendulum's speed at
/// the contact (energy of the compound pendulum), the reduced mass of the operator's and the
/// robot's effective masses at the contact point, and the undamped Hertz peak indentation
/// from ½ μ v² = k δⁿ⁺¹/(n + 1). An estimate for budgets and plausibility, not the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactEstimate {
    /// Impact speed [m/s].
    pub speed_mps: f64,
    /// Reduced mass μ \[kg\].
    pub reduced_mass_kg: f64,
    /// Peak indentation \[m\].
    pub peak_indentation_m: f64,
}

/// [`ImpactEstimate`] of `scene`.
pub fn first_impact_estimate(scene: &Scene) -> ImpactEstimate {
    let g = RigGeometry::of(scene);
    let op = &g.operator;
    let swing = scene.file.operator.start.initial_swing(
        op.mass,
        op.com_distance,
        op.inertia_pivot,
        scene.file.gravity_mps2,
    );
    // with a drive the link comes too (the speeds add along the strike)
    let speed_mps = swing.rate_at_contact * op.arm_length
        + scene
            .drive
            .as_ref()
            .map_or(0.0, |d| d.tip_speed_estimate(g.robot.length));
    let m_op = op.effective_mass();
    let m_rob = g.robot.effective_mass();
    let reduced_mass_kg = m_op * m_rob / (m_op + m_rob);
    ImpactEstimate {
        speed_mps,
        reduced_mass_kg,
        peak_indentation_m: scene.hertz.peak_indentation(reduced_mass_kg, speed_mps),
    }
}

/// The finest mesh whose mass matrix double precision factorises: the consistent mass of an
/// Euler–Bernoulli element gives the tip's rotation a pivot of about ρA l³/210 (l = L/N, the
/// element's length; measured: the bundled cl_light_load factorises at N = 3000 and not at
/// 3200, where ρA l³/210 crosses the factorisation's 1e-14 of the largest entry, the payload),
/// while the largest entry is the payload (or 312 ρA l/420 without one). Half that threshold's
/// mesh size is kept as a margin: ρA l³/210 ≥ 2e-14 × max(payload, 312 ρA l/420).
pub fn beam_elements_conditioned(rho_a: f64, length: f64, payload: f64) -> usize {
    let fits = |n: usize| {
        let l = length / n as f64;
        rho_a * l.powi(3) / 210.0 >= 2e-14 * payload.max(312.0 * rho_a * l / 420.0)
    };
    let (mut lo, mut hi) = (1usize, BEAM_ELEMENTS.1);
    if fits(hi) {
        return hi;
    }
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if fits(mid) { lo = mid } else { hi = mid }
    }
    lo
}

/// Refuses a mesh finer than [`beam_elements_conditioned`] (its mass matrix is singular in
/// double precision), naming the largest that works.
pub fn check_beam_mass_conditioning(
    elements: usize,
    rho_a: f64,
    length: f64,
    payload: f64,
) -> Result<(), RigError> {
    let most = beam_elements_conditioned(rho_a, length, payload);
    if elements <= most {
        return Ok(());
    }
    Err(invalid(
        "robot.beam_elements",
        elements,
        &format!(
            "at most {most} for this link and payload: finer elements make the tip's rotational \
             inertia (ρA l³/210 for an element of length l) vanish beside the payload's mass in \
             double precision, and the mass matrix becomes singular"
        ),
    ))
}

/// Checks the mesh limit of the chosen beam solver.
pub fn check_beam_mesh(elements: usize, beam: BeamSolverSpec) -> Result<(), RigError> {
    check_count("robot.beam_elements", elements, BEAM_ELEMENTS)?;
    if let BeamSolverSpec::Modal { .. } = beam
        && elements > MODAL_BEAM_ELEMENTS
    {
        return Err(invalid(
            "robot.beam_elements",
            elements,
            &format!(
                "must be at most {MODAL_BEAM_ELEMENTS} with solver.beam = {{ model = \"modal\" }} \
                 (a dense eigenproblem), or use the full beam"
            ),
        ));
    }
    Ok(())
}
