//! Plausibility warnings: a scene that is valid but looks like a mistake (a unit that looks
//! wrong, a contact law taken outside its fit, an indentation deeper than the bodies, a joint
//! spring left behind when the link was changed, a swing step too large for the swing), and the
//! shared rule for the masses, lengths and speeds typed for a robot ([`mass`], [`length`],
//! [`speed`], [`joint_speed`]) that every front applies to what it takes. A warning never stops
//! a run; the fronts print it and list it in their JSON.

use flexrig_contact::Materials;
use flexrig_contact::validate::display;

pub use crate::scene::Warning;
use crate::scene::{Design, Scene, Start};

fn warning(field: &str, message: String) -> Warning {
    Warning {
        field: field.to_string(),
        message,
    }
}

/// A release angle at most this \[deg\] looks like radians (π rad = 180°).
const RADIAN_LIKE_DEG: f64 = std::f64::consts::PI;

/// Relative mismatch of an explicit CJ spring and 3EI/L beyond which a warning is given.
const SPRING_MISMATCH: f64 = 0.01;

/// The heaviest plausible mass \[kg\] of a robot's link, payload or moving parts near a person:
/// collaborative arms move at most a few tens of kilograms (ISO/TS 15066:2016 Annex A's
/// examples stay below 50 kg); 200 kg leaves room for a mobile base.
pub const PLAUSIBLE_MASS_KG: f64 = 200.0;

/// The longest plausible robot link \[m\].
pub const PLAUSIBLE_LENGTH_M: f64 = 5.0;

/// The fastest plausible relative speed of a robot and a person \[m/s\] (industrial arms reach a
/// few m/s; the standard's transient contacts are studied below 2.5 m/s).
pub const PLAUSIBLE_SPEED_MPS: f64 = 10.0;

/// The shared rule for the masses, lengths and speeds a user types for a robot: a valid value
/// that looks like a unit slip (grams typed for kilograms, millimetres for metres, degrees per
/// second for radians per second) gets the same warning in every front that takes it — scenes
/// (`flexrig run`, sweeps), `strike`, `safety` and `safety-map` — named by the field or flag
/// the user typed (`field`).
///
/// A warning for the mass `kg` given as `field`, when it is heavier than
/// [`PLAUSIBLE_MASS_KG`] (with its value in grams read as kilograms).
pub fn mass(field: &str, kg: f64) -> Option<Warning> {
    (kg.is_finite() && kg > PLAUSIBLE_MASS_KG).then(|| {
        warning(
            field,
            format!(
                "{} kg is heavier than a robot near a person moves (up to about {} kg); if \
                 grams were meant, {} g is {} kg",
                display(kg),
                display(PLAUSIBLE_MASS_KG),
                display(kg),
                display(kg / 1000.0)
            ),
        )
    })
}

/// A warning for the length `m` given as `field`, when it is longer than
/// [`PLAUSIBLE_LENGTH_M`] (the shared rule, see [`mass`]).
pub fn length(field: &str, m: f64) -> Option<Warning> {
    (m.is_finite() && m > PLAUSIBLE_LENGTH_M).then(|| {
        warning(
            field,
            format!(
                "{} m is longer than a robot's link (up to about {} m); if millimetres were \
                 meant, {} mm is {} m",
                display(m),
                display(PLAUSIBLE_LENGTH_M),
                display(m),
                display(m / 1000.0)
            ),
        )
    })
}

/// A warning for the relative speed `mps` given as `field`, when it is faster than
/// [`PLAUSIBLE_SPEED_MPS`] (the shared rule, see [`mass`]).
pub fn speed(field: &str, mps: f64) -> Option<Warning> {
    (mps.is_finite() && mps.abs() > PLAUSIBLE_SPEED_MPS).then(|| {
        warning(
            field,
            format!(
                "{} m/s is faster than robot arms move near people (up to about {} m/s)",
                display(mps),
                display(PLAUSIBLE_SPEED_MPS)
            ),
        )
    })
}

/// A warning for the joint speed `rad_s` given as `field` on a link of length `length_m` \[m\],
/// when it moves the tip, v = |ω| L, faster than [`PLAUSIBLE_SPEED_MPS`] (degrees per second
/// typed for radians per second; the shared rule, see [`mass`]).
pub fn joint_speed(field: &str, rad_s: f64, length_m: f64) -> Option<Warning> {
    let tip = rad_s.abs() * length_m;
    (tip.is_finite() && tip > PLAUSIBLE_SPEED_MPS).then(|| {
        warning(
            field,
            format!(
                "{} rad/s moves the tip at {} m/s, faster than robot arms go (up to about {} \
                 m/s); if {} was meant in degrees per second, it is {} rad/s",
                display(rad_s),
                display(tip),
                display(PLAUSIBLE_SPEED_MPS),
                display(rad_s),
                display(rad_s.to_radians())
            ),
        )
    })
}

/// The plausibility warnings of `scene` (validated with `materials`), in field order.
pub fn warnings(scene: &Scene, materials: &Materials) -> Vec<Warning> {
    let mut out = Vec::new();
    typed_robot_quantities(scene, &mut out);
    release_angle_in_radians(scene, &mut out);
    exponent_without_its_stiffness(scene, materials, &mut out);
    indentation_deeper_than_the_bodies(scene, &mut out);
    dome_radius_outside_the_fit(scene, materials, &mut out);
    spring_left_behind_by_the_link(scene, &mut out);
    swing_step_too_large(scene, &mut out);
    beam_flight_unresolved(scene, &mut out);
    out
}

/// The robot's payload, its link's length and its drive's commanded speed by the shared rule
/// ([`mass`], [`length`], [`joint_speed`]).
fn typed_robot_quantities(scene: &Scene, out: &mut Vec<Warning>) {
    let r = &scene.file.robot;
    out.extend(mass("robot.payload_kg", r.payload_kg));
    out.extend(length("robot.length_m", r.length_m));
    let profile = r.drive.as_ref().and_then(|d| match &d.command {
        flexrig_impact::drive::DriveCommand::Trajectory { profile }
        | flexrig_impact::drive::DriveCommand::Controller { profile, .. } => Some(profile),
        flexrig_impact::drive::DriveCommand::OpenLoop { .. } => None,
    });
    if let Some(p) = profile {
        out.extend(joint_speed(
            "robot.drive.command.profile.speed",
            p.final_speed(),
            r.length_m,
        ));
    }
}

/// Fewest steps of `solver.swing_step_s` over a quarter of the pendulum's small-swing period
/// (the swing from a release to the bottom) below which the step looks too large.
const SWING_STEPS_PER_QUARTER_PERIOD: f64 = 20.0;

fn swing_step_too_large(scene: &Scene, out: &mut Vec<Warning>) {
    let g = crate::geometry::RigGeometry::of(scene);
    // the small-swing period: the shortest the pendulum has at any amplitude
    let period =
        crate::canonical::compound_pendulum_period(&g.operator, scene.file.gravity_mps2, 1e-6);
    let step = scene.file.solver.swing_step_s;
    let largest = 0.25 * period / SWING_STEPS_PER_QUARTER_PERIOD;
    if period.is_finite() && step > largest {
        out.push(warning(
            "solver.swing_step_s",
            format!(
                "{} s is more than 1/{} of a quarter of the pendulum's period ({} s): the \
                 swing takes fewer than {} steps from a release to the bottom, so the impact \
                 speed and the onset may be off; take at most {} s",
                display(step),
                SWING_STEPS_PER_QUARTER_PERIOD,
                display((0.25 * period * 1e4).round() / 1e4),
                SWING_STEPS_PER_QUARTER_PERIOD,
                display(float_2(largest))
            ),
        ));
    }
}

/// The CL's swing step after a contact \[s\] that resolves the beam's ringing: after a contact
/// the payload flies off on the soft beam and the beam rings in its higher modes, whose phase at
/// the next onset sets that contact's peak. On `cl_iron` released from 30° the second contact's
/// peak is 126.6 / 133.6 / 137.11 / 137.17 / 137.22 / 137.24 N at swing steps of 5e-4 / 1e-4 /
/// 5e-5 / 2e-5 / 1e-5 / 5e-6 s (the bundled 5e-4 s is 8 % off), the third of `cl_light_load`
/// 38.2 / 41.1 / 42.2 / 42.4 N at 5e-5 / 2e-5 / 1e-5 / 5e-6 s. The safety verdict on a CL test
/// bed steps the swing after a contact at most this.
pub const CL_FLIGHT_STEP_S: f64 = 2e-5;

/// A CL on the test bed run past its first contact (stop `rebound` or a duration) with a swing
/// step coarser than [`CL_FLIGHT_STEP_S`]: its later contacts are not resolved.
fn beam_flight_unresolved(scene: &Scene, out: &mut Vec<Warning>) {
    let step = scene.file.solver.swing_step_s;
    let past_first = matches!(
        scene.file.stop,
        crate::scene::StopSpec::Rebound | crate::scene::StopSpec::Duration { .. }
    );
    if scene.file.robot.design == Design::Cl
        && scene.drive.is_none()
        && past_first
        && step > CL_FLIGHT_STEP_S
    {
        out.push(warning(
            "solver.swing_step_s",
            format!(
                "{} s does not resolve the beam's ringing after a contact: a later contact's \
                 peak can be off by several per cent (the safety verdict steps it at {} s); \
                 take at most {} s to judge the later contacts",
                display(step),
                display(CL_FLIGHT_STEP_S),
                display(CL_FLIGHT_STEP_S)
            ),
        ));
    }
}

/// `x` to two significant digits, rounded down (a bound to quote).
fn float_2(x: f64) -> f64 {
    let decade = 10f64.powf(x.log10().floor() - 1.0);
    (x / decade).floor() * decade
}

fn release_angle_in_radians(scene: &Scene, out: &mut Vec<Warning>) {
    let (Start::Release {
        release_angle_deg: a,
    }
    | Start::Contact {
        release_angle_deg: a,
    }) = scene.file.operator.start
    else {
        return;
    };
    if a <= RADIAN_LIKE_DEG {
        out.push(warning(
            "operator.start.release_angle_deg",
            format!(
                "{} looks like radians ({} rad = {}°); the field is in degrees",
                display(a),
                display(a),
                display((a.to_degrees() * 10.0).round() / 10.0)
            ),
        ));
    }
}

fn exponent_without_its_stiffness(scene: &Scene, materials: &Materials, out: &mut Vec<Warning>) {
    let c = &scene.file.contact;
    let (Some(n), None) = (c.n, c.k) else {
        return;
    };
    let Ok(material) = materials.get(&scene.file.operator.block_material) else {
        return;
    };
    let fitted = material.hertz;
    if (n - fitted.n()).abs() > 1e-9 * fitted.n() {
        // the same k with another n: the force at 1 mm changes by 1e-3^(n - n_fit)
        let factor = 1e-3f64.powf(n - fitted.n());
        out.push(warning(
            "contact.n",
            format!(
                "{} with the stiffness k = {} N/mⁿ fitted for n = {} ({}): the force at 1 mm \
                 indentation changes ×{}; give contact.k fitted for this exponent",
                display(n),
                display(fitted.k()),
                display(fitted.n()),
                material.name,
                display((factor * 1000.0).round() / 1000.0)
            ),
        ));
    }
}

fn indentation_deeper_than_the_bodies(scene: &Scene, out: &mut Vec<Warning>) {
    let delta = crate::limits::first_impact_estimate(scene).peak_indentation_m;
    if !delta.is_finite() {
        return;
    }
    let block = scene.file.operator.block_size_m[1];
    let dome = scene.file.robot.dome_radius_m;
    let mm = |x: f64| display((x * 1e4).round() / 10.0);
    if delta > 0.5 * block.min(dome) {
        let (field, what, size) = if block <= dome {
            ("operator.block_size_m", "the block's depth", block)
        } else {
            ("robot.dome_radius_m", "the dome's radius", dome)
        };
        out.push(warning(
            field,
            format!(
                "the contact law gives an indentation of about {} mm at this impact, more \
                 than half {what} ({} mm): the Hertz law is far outside its fit; check \
                 contact.k and contact.n (k is in N/mⁿ)",
                mm(delta),
                mm(size)
            ),
        ));
    }
}

fn dome_radius_outside_the_fit(scene: &Scene, materials: &Materials, out: &mut Vec<Warning>) {
    let fitted = materials.dome_radius_m();
    let r = scene.file.robot.dome_radius_m;
    if scene.file.contact.k.is_none() && (r - fitted).abs() > 1e-6 * fitted {
        out.push(warning(
            "robot.dome_radius_m",
            format!(
                "{} m: the contact law is the block material's fit, measured with the {} m \
                 dome; the radius changes the drawing and the contact geometry, not the law \
                 (give contact.k and contact.n for another dome)",
                display(r),
                display(fitted)
            ),
        ));
    }
}

fn spring_left_behind_by_the_link(scene: &Scene, out: &mut Vec<Warning>) {
    let r = &scene.file.robot;
    let Some(k) = r.torsion_spring_nm_per_rad.and_then(|k| k.value()) else {
        return;
    };
    if r.design != Design::Cj {
        return;
    }
    let matched = 3.0 * scene.link_ei / r.length_m;
    if ((k - matched) / matched).abs() > SPRING_MISMATCH {
        out.push(warning(
            "robot.torsion_spring_nm_per_rad",
            format!(
                "{} N·m/rad differs by {} % from 3EI/L = {} N·m/rad of this link (Eq. 3): if \
                 the link was changed, the CJ no longer matches the CL's stiffness; set it to \"matched\" \
                 (or leave it out) to follow the link",
                display(k),
                display(((k / matched - 1.0) * 1000.0).round() / 10.0),
                display((matched * 1e4).round() / 1e4)
            ),
        ));
    }
}
