//! The simulation method on a test-bed scene: the operator's permissible speed on the
//! drop-pendulum rig (a scene file without a `[drive]` section, docs/scenes.md).
//!
//! The scene fixes the robot (CJ or CL at rest on its axis, its payload and dome) and the person:
//! the operator's block on its free pendulum, whose skin is the contact's Hertz law
//! f = k_c δ_c^n (paper Eq. 4). The search variable is the block's speed at the bottom of the
//! swing, where it meets the dome, v = ω_b l (l the arm's length to the block centre); the
//! operator is released at rest from the angle θ₀ that gives it,
//! ½ J ω_b² = M g l_c (1 − cos θ₀), so 1 − cos θ₀ = J v²/(2 M g l_c l²). Each speed is one whole
//! rig run: the swing and **every contact of the swing** — the rig stops when the operator's
//! block, out of contact and moving away, turns back at the apex of its rebound (scene stop
//! `rebound`; a later contact would be the pendulum's return swing under gravity, a new strike
//! of the test bed) — and the permissible speed is the smallest speed at which the largest
//! contact's peak force reaches the region's force limit, by the scan from below and the
//! Illinois refinement on ln v of a driven scene ([`crate::safety::simulation::scan_up`]),
//! started at the test bed's energy floor ([`TestBedScene::energy_floor`]). A CL's beam rings
//! after a contact: its swing is stepped at [`CL_FLIGHT_STEP_S`] at most, and the answer is run
//! again at half that step to say how far the later contacts move.
//!
//! The release angle is bounded by 170° (the scene's own bound): the largest speed the test bed
//! can reach. When the peak force there is still below the limit, the search reports that speed
//! as the highest tried and says that the limit is not reached, instead of extrapolating.
//!
//! The pendulum is free, so the contact is transient; a transient contact where the body model
//! does not permit one (skull and forehead, face) is refused with its clause before any run.

use flexrig_contact::Materials;
use flexrig_rig::geometry::RigGeometry;
use flexrig_rig::{Design, NoRecorder, Override, RunOptions, RunSummary, Scene, Simulation};
use flexrig_safety::{EnergyContact, Limits, PressureCrossing};

use crate::Error;
use crate::driven::strike::StrikeDesign;
use crate::safety::simulation::{
    ContactsAtRoot, RootStep, SCENE_REFINE_RUNS, Scan, SceneSimulation, SimulationSettings, refine,
    scan_up,
};
use crate::safety::simulation::{Peaks, SCAN_START_OF_GUESS, grid_index_at_or_below, grid_speed};

/// The largest release angle of the test bed \[deg\] (`operator.start.release_angle_deg`).
pub const MAX_RELEASE_ANGLE_DEG: f64 = 170.0;

/// The CL's swing step after a contact \[s\] at most (a scene's finer `solver.swing_step_s` is
/// kept): the step that resolves the beam's ringing
/// ([`flexrig_rig::plausibility::CL_FLIGHT_STEP_S`]). The verdict reruns its answer at half
/// this step and says how far the later contacts moved ([`simulate`]).
pub use flexrig_rig::plausibility::CL_FLIGHT_STEP_S;

/// The generalized-α spectral radius ρ∞ of the CL's beam in the verdict's runs: a little
/// numerical dissipation, of modes far above what the step resolves. The corotational beam
/// stepped by the trapezoidal rule (ρ∞ = 1, the rig's default) can gain energy in a long rattle
/// of later contacts: `cl_light_load` released from 90° grows by 5 % at 5.7 s and the run stops
/// as unstable; at ρ∞ = 0.9 it runs to its rebound (876 contacts, 7.0 s). The resolved contacts
/// do not move: `cl_iron`'s second contact (30°) is 137.168 N at ρ∞ = 0.9 and 137.169 N at 1
/// (2e-5 s), and converges alike, 137.168 / 137.216 / 137.244 N at 2e-5 / 1e-5 / 5e-6 s.
pub const CL_VERDICT_RHO_INF: f64 = 0.9;

/// A test-bed scene loaded for the safety verdict.
#[derive(Debug, Clone)]
pub struct TestBedScene {
    /// Where it came from (`bundled cj_aluminium` or the file's path).
    pub origin: String,
    /// The scene's text (overrides are applied to it for each run).
    text: String,
    /// The checked scene as written.
    pub scene: Scene,
    /// Its geometry, masses and inertias.
    pub geometry: RigGeometry,
}

impl TestBedScene {
    /// Parses and validates the test-bed scene `text` from `origin`.
    pub fn parse(origin: &str, text: &str) -> Result<Self, Error> {
        let scene = Scene::from_toml_str(text, &Materials::bundled()?)?;
        let geometry = RigGeometry::of(&scene);
        Ok(TestBedScene {
            origin: origin.into(),
            text: text.into(),
            scene,
            geometry,
        })
    }

    /// CJ or CL.
    pub fn design(&self) -> StrikeDesign {
        match self.scene.file.robot.design {
            Design::Cj => StrikeDesign::Cj,
            Design::Cl => StrikeDesign::Cl,
        }
    }

    /// The mass \[kg\] the operator pendulum presents at the contact, J/l².
    pub fn operator_mass(&self) -> f64 {
        self.geometry.operator.effective_mass()
    }

    /// The block's speed at the bottom of a swing released at rest from `angle_deg` \[deg\]:
    /// v = ω_b l [m/s].
    pub fn speed_of_release(&self, angle_deg: f64) -> f64 {
        let op = &self.geometry.operator;
        op.bottom_angular_speed(angle_deg.to_radians(), self.scene.file.gravity_mps2)
            * op.arm_length
    }

    /// The release angle \[deg\] whose swing reaches the contact at `v` [m/s]:
    /// 1 − cos θ₀ = J v²/(2 M g l_c l²); `None` beyond [`MAX_RELEASE_ANGLE_DEG`].
    pub fn release_angle_for(&self, v: f64) -> Option<f64> {
        let op = &self.geometry.operator;
        let omega = v / op.arm_length;
        let g = self.scene.file.gravity_mps2;
        let c = 1.0 - op.inertia_pivot * omega * omega / (2.0 * op.mass * g * op.com_distance);
        let angle = c.clamp(-1.0, 1.0).acos().to_degrees();
        // the largest speed itself maps back to 170° up to rounding
        (c >= -1.0 && angle <= MAX_RELEASE_ANGLE_DEG * (1.0 + 1e-12) && angle > 0.0)
            .then_some(angle.min(MAX_RELEASE_ANGLE_DEG))
    }

    /// The largest speed at contact the test bed reaches (release from 170°) [m/s].
    pub fn max_speed(&self) -> f64 {
        self.speed_of_release(MAX_RELEASE_ANGLE_DEG)
    }

    /// The speed at contact of the scene as written [m/s] (its release angle; the speed of its
    /// start otherwise).
    pub fn scene_speed(&self) -> f64 {
        let op = &self.geometry.operator;
        let swing = self.scene.file.operator.start.initial_swing(
            op.mass,
            op.com_distance,
            op.inertia_pivot,
            self.scene.file.gravity_mps2,
        );
        swing.rate_at_contact * op.arm_length
    }

    /// The step \[s\] of the swing after a contact, for a CL: the scene's swing step, at most
    /// [`CL_FLIGHT_STEP_S`]; `None` for a CJ, whose swing between contacts is the adaptive
    /// integrator's (exact to its tolerance).
    pub fn flight_step(&self) -> Option<f64> {
        (self.design() == StrikeDesign::Cl)
            .then(|| self.scene.file.solver.swing_step_s.min(CL_FLIGHT_STEP_S))
    }

    /// The speed at contact [m/s] below which no contact of the swing can reach the force `f`
    /// \[N\], from energy: the rig's mechanical energy above the operator's lowest point is
    /// ½ m_op v² when the block reaches the dome at v (the robot at rest and undeformed, m_op =
    /// J/l², [`Self::operator_mass`]); the robot turns about a vertical axis (no work of
    /// gravity), the pendulum's height above its lowest point, every kinetic energy and the
    /// link's strain energy are never negative, and the contact stores U_c(f) = k δ_c^{n+1}/(n+1),
    /// δ_c = (f/k)^{1/n}, at force f: so U_c ≤ ½ m_op v² for every contact of the swing, and f
    /// is not reached below v_0 = √(2 U_c(f)/m_op). `None` with a damped contact (its force
    /// exceeds the elastic part while the indentation grows).
    pub fn energy_floor(&self, f: f64) -> Option<f64> {
        if !matches!(
            self.scene.file.contact.damping,
            flexrig_contact::DampingSpec::None {}
        ) {
            return None;
        }
        let hertz = &self.scene.hertz;
        let u = hertz.energy(hertz.indentation(f));
        let v = (2.0 * u / self.operator_mass()).sqrt();
        (v.is_finite() && v > 0.0).then_some(v)
    }

    /// The scene run with the operator released from rest at `angle_deg` \[deg\] to the apex
    /// of the operator's rebound, every contact of the swing (scene stop `rebound`); a CL's
    /// swing after a contact in steps of [`Self::flight_step`], its beam at ρ∞ =
    /// [`CL_VERDICT_RHO_INF`].
    pub fn run_released(&self, angle_deg: f64) -> Result<RunSummary, Error> {
        self.run_released_with(angle_deg, self.flight_step())
    }

    /// [`Self::run_released`] with the swing step `flight_step` \[s\] when given.
    fn run_released_with(
        &self,
        angle_deg: f64,
        flight_step: Option<f64>,
    ) -> Result<RunSummary, Error> {
        let start = toml::Value::Table(toml::Table::from_iter([
            ("from".to_string(), toml::Value::String("release".into())),
            (
                "release_angle_deg".to_string(),
                toml::Value::Float(angle_deg),
            ),
        ]));
        let stop = toml::Value::Table(toml::Table::from_iter([(
            "at".to_string(),
            toml::Value::String("rebound".into()),
        )]));
        let mut overrides = vec![
            Override::new("operator.start", start),
            Override::new("stop", stop),
        ];
        if let Some(h) = flight_step {
            overrides.push(Override::new("solver.swing_step_s", toml::Value::Float(h)));
        }
        let scene =
            flexrig_rig::scene_with_overrides(&self.text, &overrides, &Materials::bundled()?)?;
        let options = RunOptions {
            beam_rho_inf: CL_VERDICT_RHO_INF,
            ..RunOptions::DEFAULT
        };
        Ok(Simulation::new(&scene, options)?
            .with_lean_samples()
            .run(&mut NoRecorder)?)
    }

    /// The largest contact's peak force \[N\] over the swing at speed `v` [m/s] at contact (a
    /// release angle up to 170°; beyond it an error naming the speed and the largest).
    pub fn peak_force(&self, v: f64) -> Result<f64, Error> {
        let angle = self.release_angle_for(v).ok_or_else(|| Error::InvalidArgument {
            arg: "--speed".into(),
            value: flexrig_contact::validate::display(v),
            allowed: format!(
                "a speed the test bed reaches: up to {} m/s (release from {MAX_RELEASE_ANGLE_DEG}°)",
                flexrig_contact::validate::display(self.max_speed())
            ),
        })?;
        Ok(largest_contact(&self.run_released(angle)?).1.peak_force_n)
    }
}

/// The contact with the largest peak force of a run and its number (1 = the first).
pub fn largest_contact(run: &RunSummary) -> (usize, flexrig_rig::ContactEvent) {
    largest_contact_from(run, 0).expect("a run summary holds its first contact")
}

/// The contact with the largest peak force among those of `run` after the first `skip`, and
/// its number (1 = the first); `None` when there is none.
fn largest_contact_from(
    run: &RunSummary,
    skip: usize,
) -> Option<(usize, flexrig_rig::ContactEvent)> {
    run.contacts.iter().enumerate().skip(skip).fold(
        None::<(usize, flexrig_rig::ContactEvent)>,
        |best, (i, c)| match best {
            Some((_, b)) if b.peak_force_n >= c.peak_force_n => best,
            _ => Some((i + 1, *c)),
        },
    )
}

/// The smallest speed below the test bed's largest, `v_cap`, at which the largest peak force
/// `run(v)` reaches `limit` (the scan from below from `start`, halved up to ten times when the
/// limit is reached there already; the scan's next speeds run side by side, [`Peaks::prefetch`],
/// each run kept in `peaks`), or `None` when the scan reaches `v_cap` with the peak still below
/// the limit or starts above it (`start` a proven floor: nothing to run); with the peak at
/// `v_cap` when it was run.
fn smallest_test_bed_speed(
    v_cap: f64,
    start: f64,
    rtol: f64,
    limit: f64,
    peaks: &Peaks,
    run: &(dyn Fn(f64) -> Result<f64, Error> + Sync),
    trace: Option<&mut Vec<RootStep>>,
) -> Result<(Option<f64>, Option<f64>), Error> {
    if start > v_cap {
        return Ok((None, None));
    }
    let peak = |v: f64| peaks.at(v, run);
    let mut ahead = |speeds: &[f64]| {
        let below_cap: Vec<f64> = speeds.iter().copied().filter(|&v| v < v_cap).collect();
        peaks.prefetch(&below_cap, run);
    };
    let mut at_cap = None;
    let mut below_at_cap = false;
    let mut ratio = |v: f64| -> Result<f64, Error> {
        if v < v_cap {
            return Ok(peak(v)? / limit);
        }
        let p = peak(v_cap)?;
        at_cap = Some(p);
        if p < limit {
            below_at_cap = true;
            // ends the scan (the error is replaced below): not reached up to the test bed's
            // largest speed
            return Err(Error::InvalidArgument {
                arg: "--speed".into(),
                value: flexrig_contact::validate::display(v),
                allowed: "a speed the test bed reaches".into(),
            });
        }
        Ok(p / limit)
    };
    let found = match scan_up(start, rtol, &mut ratio, &mut ahead, trace) {
        Ok(Scan::Crossing(v)) => Ok(Some(v.min(v_cap))),
        Ok(Scan::Never) => Ok(None),
        Ok(Scan::AtStart) => (|| {
            let (mut above, mut r_above) = (start, ratio(start)?);
            for _ in 0..10 {
                let below = 0.5 * above;
                let r = ratio(below)?;
                if r < 1.0 {
                    return refine(
                        (below, r),
                        (above, r_above),
                        rtol,
                        SCENE_REFINE_RUNS,
                        &mut ratio,
                    )
                    .map(Some);
                }
                (above, r_above) = (below, r);
            }
            Ok(Some(0.0))
        })(),
        Err(e) => Err(e),
    };
    match found {
        Err(_) if below_at_cap => Ok((None, at_cap)),
        other => Ok((other?, at_cap)),
    }
}

/// The permissible speed at contact of the test bed `tb` under `limits` (force; pressure
/// through `energy`'s contact-area model), the searches started at `guess_force` and
/// `guess_pressure` [m/s], to the root tolerance of `settings`.
pub fn simulate(
    tb: &TestBedScene,
    limits: &Limits,
    energy: &EnergyContact,
    guess_force: f64,
    guess_pressure: Option<f64>,
    settings: &SimulationSettings,
    stop: &std::sync::atomic::AtomicBool,
) -> Result<SceneSimulation, Error> {
    settings.validate()?;
    let peaks = Peaks::default();
    let run = |v: f64| -> Result<f64, Error> {
        crate::safety::simulation::check_stop(stop)?;
        tb.peak_force(v)
    };
    let v_cap = tb.max_speed();
    let mut force_search = Vec::new();
    let (by_force, force_at_cap) = smallest_test_bed_speed(
        v_cap,
        scan_start(tb, limits.force, guess_force),
        settings.root_rtol,
        limits.force,
        &peaks,
        &run,
        Some(&mut force_search),
    )?;
    // the pressure's speed; the test bed's largest when its limit is not reached there (a note
    // says so)
    let mut pressure_unreached = None;
    let by_pressure = match (limits.pressure, guess_pressure) {
        (Some(p), Some(g)) => match energy.force_at_pressure(p) {
            Some(PressureCrossing::AtForce(f)) => {
                // on the force's grid: the runs the two scans share are run once
                let (root, _) = smallest_test_bed_speed(
                    v_cap,
                    scan_start(tb, f, g.min(guess_force)),
                    settings.root_rtol,
                    f,
                    &peaks,
                    &run,
                    None,
                )?;
                if root.is_none() {
                    pressure_unreached = Some(p);
                }
                // not reached up to the test bed's largest speed: that speed, a lower bound (as
                // for the force; a note says so)
                Some(root.unwrap_or(v_cap))
            }
            Some(PressureCrossing::Always) => Some(0.0),
            Some(PressureCrossing::Never) | None => Some(f64::INFINITY),
        },
        _ => None,
    };
    // the peak at the test bed's largest speed, for the note when the limit is not reached
    let peak_at_cap = match (by_force, force_at_cap) {
        (Some(_), _) => None,
        (None, Some(p)) => Some(p),
        (None, None) => Some(peaks.at(v_cap, run)?),
    };
    let mut runs = peaks.runs();
    let speed = by_force.unwrap_or(v_cap);
    let angle = match by_force {
        Some(v) => tb.release_angle_for(v).unwrap_or(MAX_RELEASE_ANGLE_DEG),
        None => MAX_RELEASE_ANGLE_DEG,
    };
    // the answer's run and, for a CL, the same at half the swing step after a contact (how far
    // the step moves the later contacts), side by side
    let (at_root, at_half_step) = rayon::join(
        || tb.run_released(angle),
        || {
            tb.flight_step()
                .map(|h| tb.run_released_with(angle, Some(0.5 * h)).map(|r| (h, r)))
                .transpose()
        },
    );
    let (at_root, at_half_step) = (at_root?, at_half_step?);
    runs += 1 + usize::from(at_half_step.is_some());
    let (governing, largest) = largest_contact(&at_root);
    let g = |v: f64| flexrig_contact::validate::display(v);
    let mut notes = vec![match peak_at_cap {
        None => format!(
            "the operator released at rest from {}° reaches the dome at {} m/s",
            g(angle),
            g(speed)
        ),
        Some(peak_at_cap) => format!(
            "the force limit is not reached on this test bed: released from the largest angle, \
             {MAX_RELEASE_ANGLE_DEG}°, the operator reaches the dome at {} m/s and the peak force \
             is {} N, below the limit of {} N; the permissible speed is at least {} m/s",
            g(v_cap),
            g(peak_at_cap),
            g(limits.force),
            g(v_cap)
        ),
    }];
    if let Some((h, half)) = &at_half_step {
        notes.push(flight_step_note(*h, &at_root, half, limits.force));
    }
    if let Some(p) = pressure_unreached {
        notes.push(format!(
            "the pressure limit of {} N/cm² is not reached on this test bed (released from \
             {MAX_RELEASE_ANGLE_DEG}°, up to {} m/s)",
            g(p / 1e4),
            g(v_cap)
        ));
    }
    Ok(SceneSimulation {
        scene: tb.origin.clone(),
        name: tb.scene.file.name.clone(),
        design: tb.design(),
        support: "pendulum",
        scene_tip_speed_mps: tb.scene_speed(),
        by_force_mps: speed,
        by_pressure_mps: by_pressure,
        approach_speed_at_root_mps: at_root.impact_velocity_mps,
        peak_force_at_root_n: largest.peak_force_n,
        contacts_at_root: Some(ContactsAtRoot {
            contacts: at_root.contacts.len(),
            governing,
            time_of_peak_s: largest.time_of_peak_s,
            ended: flexrig_impact::RunEnd::Rebound(at_root.duration_s),
        }),
        notes,
        force_search,
        runs,
        run_tol: contact_accuracy(tb, &at_root),
        root_rtol: settings.root_rtol,
        link_model: format!(
            "the test bed's rig ({} link) with {}",
            match tb.design() {
                StrikeDesign::Cj => "CJ",
                StrikeDesign::Cl => "CL",
            },
            contact_integration_words(tb, &at_root)
        ),
        release_angle_at_root_deg: Some(angle),
        limit_reached: by_force.is_some(),
    })
}

/// What the CL's answer run at the swing step `h` \[s\] after a contact and the same run at
/// `h`/2 (`half`) say of the later contacts, the force limit `limit` \[N\]: their largest peak
/// at both steps, and a warning when at half the step any contact exceeds the limit by more
/// than the root search's resolution (1e-4) — the later contacts are then not resolved at `h`.
fn flight_step_note(h: f64, run: &RunSummary, half: &RunSummary, limit: f64) -> String {
    let g = |v: f64| flexrig_contact::validate::display(v);
    let steps = format!(
        "the beam's swing after a contact is stepped at {} s (the scene's swing step, at most \
         {} s)",
        g(h),
        g(CL_FLIGHT_STEP_S)
    );
    let later_of = |r: &RunSummary| largest_contact_from(r, 1).map(|(i, c)| (i, c.peak_force_n));
    let later = match (later_of(run), later_of(half)) {
        (None, None) => "no later contact at this speed, nor at half that step".to_string(),
        (a, b) => {
            let say = |c: Option<(usize, f64)>| {
                c.map_or("none".to_string(), |(i, p)| {
                    format!("{} N (contact {i})", g(p))
                })
            };
            format!(
                "the largest later contact is {}; at half that step {}",
                say(a),
                say(b)
            )
        }
    };
    let top = largest_contact(half).1.peak_force_n;
    if top > limit * (1.0 + 1e-4) {
        format!(
            "{steps}; {later}: at half the step a contact exceeds the force limit ({} N > {} N), \
             so the later contacts are not resolved at this step — do not rely on this speed; \
             set a smaller solver.swing_step_s in the scene",
            g(top),
            g(limit)
        )
    } else {
        format!("{steps}; {later}")
    }
}

/// Where the scan for the force `f` \[N\] starts [m/s]: on the grid of every simulated search
/// ([`grid_speed`]), the last speed at or below the energy floor ([`TestBedScene::energy_floor`])
/// lowered by the energy the rig may gain before it stops as unstable (√(1 + 5 %), the run's
/// energy check: a contact of a run that gains energy stores at most that much more); with a
/// damped contact, which has no such floor, `guess` × [`SCAN_START_OF_GUESS`] (at most the test
/// bed's largest speed).
fn scan_start(tb: &TestBedScene, f: f64, guess: f64) -> f64 {
    match tb.energy_floor(f) {
        Some(floor) => {
            let slack = (1.0 + RunOptions::default().energy_growth_limit).sqrt();
            grid_speed(grid_index_at_or_below(floor / slack))
        }
        // not a floor: at most the test bed's largest speed, where the scan then looks
        None => (clamp_guess(guess) * SCAN_START_OF_GUESS)
            .max(1e-4)
            .min(tb.max_speed()),
    }
}

/// The accuracy setting of the rig's contact in `run`: the adaptive contact's relative
/// tolerance, or Rapier's contact step \[s\].
fn contact_accuracy(tb: &TestBedScene, run: &RunSummary) -> f64 {
    if run.contact_integration.is_adaptive() {
        tb.scene
            .file
            .solver
            .contact_rtol
            .unwrap_or(flexrig_rig::free_flight::CONTACT_RTOL)
    } else {
        run.contact_step_s
    }
}

/// How the rig integrated the contact of `run`, in words.
fn contact_integration_words(tb: &TestBedScene, run: &RunSummary) -> String {
    let accuracy = flexrig_contact::validate::display(contact_accuracy(tb, run));
    if run.contact_integration.is_adaptive() {
        format!("the adaptive contact (DOP853 at relative tolerance {accuracy})")
    } else {
        format!("its contact step {accuracy} s")
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
