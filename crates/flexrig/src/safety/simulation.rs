//! The simulation method's finite-element impact and its search on the speed, shared by
//! `flexrig safety --method simulation` ([`crate::safety::point`]) and the simulated safe-speed maps
//! ([`crate::safety::map`]): every contact, until the bodies part for good, of a body region (mass m_h, the skin's Hertz law
//! f = k_c δ^n, Eq. 4) with the tip of a link of mass m_r, payload m_e and lateral stiffness
//! k_δ (Eq. 1–3), the CJ as a rigid link on its torsion spring k_θr = k_δL² (DOP853,
//! [`flexrig_impact::chain::Chain::cj`]), the CL as the Euler–Bernoulli beam on a mesh graded
//! towards the tip, both by their modes and the exact modal integrator
//! ([`flexrig_impact::cl_modal`]); the largest peak over the contacts ([`FeRuns::impact_at`]);
//! and the scan from below with a refinement that finds the smallest speed at which it reaches
//! a limit ([`smallest_speed_at`]). The scenes' searches still use the bracket around a guess
//! ([`speed_at_ratio`]).

use std::sync::atomic::{AtomicBool, Ordering};

use flexrig_contact::{DampingSpec, Hertz};
use flexrig_impact::chain::Chain;
use flexrig_impact::cl_modal::head_at_onset;
use flexrig_impact::graded::{GradedMesh, cl_tip_modes};
use flexrig_impact::modal_run::{
    ModalOptions, PeakRunEnd, largest_peak_cubic_against, run_modes_cubic_against,
    threshold_cubic_against,
};
use flexrig_impact::setup::hertz_time_integral;
use flexrig_impact::{FreeMassImpact, ImpactError, Joint, LinkParams, RunEnd};
use flexrig_safety::{EnergyContact, GoverningLimit, PressureCrossing};
use serde::{Deserialize, Serialize};

use crate::Error;
use crate::driven::strike::StrikeDesign;

pub(crate) fn bad(arg: &str, value: impl ToString, allowed: &str) -> Error {
    Error::InvalidArgument {
        arg: arg.into(),
        value: crate::shared::output::value_text(value),
        allowed: allowed.into(),
    }
}

/// Stops a search between its runs once `stop` is set ([`ImpactError::Interrupted`], exit code
/// 130).
pub(crate) fn check_stop(stop: &AtomicBool) -> Result<(), Error> {
    if stop.load(std::sync::atomic::Ordering::Relaxed) {
        return Err(Error::Impact(flexrig_impact::ImpactError::Interrupted));
    }
    Ok(())
}

pub(crate) fn display(v: f64) -> String {
    flexrig_contact::validate::display(v)
}

/// γ of the compliant joint (rigid link on a torsion spring): m_eff = m_e + m_r/3 (Eq. 5).
pub const GAMMA_CJ: f64 = 1.0;
/// γ of the compliant link in the lumped model: m_eff = m_e + 2m_r/9 (Eq. 5, γ = 2/3).
pub const GAMMA_CL: f64 = 2.0 / 3.0;
/// The human mass \[kg\] of a clamped body (quasi-static contact) in the simulation method
/// (the finite-element impact's largest m_h; a free hub only).
pub const CLAMPED_HUMAN_MASS: f64 = 1e9;

/// The joint during the simulated impact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MapJoint {
    /// Driven at constant speed (the body region arrives at v; the test bed's operator).
    Held,
    /// A free hub with the motor's rotor inertia J_R \[kg·m²\] behind the link.
    FreeHub {
        /// J_R \[kg·m²\] > 0.
        rotor_inertia: f64,
    },
}

/// Tolerances of the simulation method.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SimulationSettings {
    /// The joint during the impact.
    pub joint: MapJoint,
    /// Link length L \[m\] (`--length`). With a held joint the transverse impact of the link
    /// depends on m_r and k_δ only (L sets EI = k_δL³/3 and cancels), so it may be absent
    /// ([`Self::length`] then takes 1 m); a free hub needs it, since the rotor's inertia J_R acts
    /// at the contact as J_R/L² ([`Self::validate`] refuses a free hub without it), and so does
    /// a map over EI (k_δ = 3EI/L³).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Tolerance of the modal integrator of every simulated impact (relative deviation of the
    /// force's linear hold per step; the searches hold the force cubic over each step, at
    /// [`SEARCH_HOLD_TOL`] × this deviation, so that their speeds are at least as close to
    /// converged as the linear hold's at this tolerance).
    pub tol: f64,
    /// Relative tolerance of the CJ's DOP853 integration.
    pub cj_rtol: f64,
    /// Relative tolerance of the root search on the speed.
    pub root_rtol: f64,
}

impl SimulationSettings {
    /// Held joint, no length (it cancels with a held joint), modal tol 1e-6, CJ rtol 1e-10, root 1e-6: each speed converged well
    /// below 1e-4 relative (tested against tol 1e-8, root 1e-10).
    pub const DEFAULT: SimulationSettings = SimulationSettings {
        joint: MapJoint::Held,
        length: None,
        tol: 1e-6,
        cj_rtol: 1e-10,
        root_rtol: 1e-6,
    };

    /// Checks every setting; the error names its flag.
    pub fn validate(&self) -> Result<(), Error> {
        if let MapJoint::FreeHub { rotor_inertia } = self.joint
            && !(rotor_inertia.is_finite() && (1e-12..=1e12).contains(&rotor_inertia))
        {
            return Err(bad(
                "--rotor-inertia",
                display(rotor_inertia),
                "must lie in [1e-12, 1e12] kg·m²",
            ));
        }
        match self.length {
            Some(l) if !(l.is_finite() && (1e-3..=1e3).contains(&l)) => {
                return Err(bad("--length", display(l), "must lie in [1e-3, 1e3] m"));
            }
            None if matches!(self.joint, MapJoint::FreeHub { .. }) => {
                return Err(bad(
                    "--length",
                    "(missing)",
                    "give the link's length with --joint free-hub: the rotor's inertia J_R acts \
                     at the contact as J_R/L², so the answer depends on it",
                ));
            }
            _ => {}
        }
        if !(self.tol.is_finite() && (1e-10..=1e-3).contains(&self.tol)) {
            return Err(bad("--tol", display(self.tol), "must lie in [1e-10, 1e-3]"));
        }
        if !(self.cj_rtol.is_finite() && (1e-13..=1e-4).contains(&self.cj_rtol)) {
            return Err(bad(
                "--cj-rtol",
                display(self.cj_rtol),
                "must lie in [1e-13, 1e-4]",
            ));
        }
        if !(self.root_rtol.is_finite() && (1e-13..=1e-4).contains(&self.root_rtol)) {
            return Err(bad(
                "--root-rtol",
                display(self.root_rtol),
                "must lie in [1e-13, 1e-4]",
            ));
        }
        Ok(())
    }

    /// The link length L \[m\] the impact is simulated with: the given one, else 1 m (a held
    /// joint, where it cancels).
    pub fn length(&self) -> f64 {
        self.length.unwrap_or(1.0)
    }

    /// The joint of the finite-element impact.
    pub fn joint(&self) -> Joint {
        match self.joint {
            MapJoint::Held => Joint::Held,
            MapJoint::FreeHub { rotor_inertia } => Joint::FreeHub { rotor_inertia },
        }
    }
}

/// The finite-element link of the simulation method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FeLink {
    /// The compliant joint: a rigid link on the torsion spring k_θr = k_δL² (DOP853).
    #[serde(rename = "cj")]
    CompliantJoint,
    /// The compliant link: the Euler–Bernoulli beam by its modes (exact modal integrator).
    #[serde(rename = "cl")]
    CompliantLink,
}

/// The link stiffness \[N/m\] the finite-element simulation uses for a rigid link (k_δ
/// absent in `flexrig safety`): the largest the FE link accepts; its stored energy F²/(2k_δ) is
/// K/k_δ ≤ 1.5e-7 of the contact's for the body springs of Table A.3 (n = 1).
pub const FE_RIGID_LINK_STIFFNESS: f64 = 1e12;

/// One design's finite-element impact, for the root searches of the simulation method (the
/// map's cells and the single-point `flexrig safety --method simulation` share it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeImpact {
    /// Human mass m_h \[kg\] (a clamped body: [`CLAMPED_HUMAN_MASS`]).
    pub m_h: f64,
    /// The skin's contact law.
    pub hertz: Hertz,
    /// Link mass m_r \[kg\].
    pub m_r: f64,
    /// Payload m_e \[kg\].
    pub m_e: f64,
    /// Lateral tip stiffness k_δ \[N/m\].
    pub k_delta: f64,
    /// CJ or CL.
    pub link: FeLink,
    /// Joint, length and tolerances.
    pub settings: SimulationSettings,
}

impl FeImpact {
    fn setup_at(&self, v: f64) -> FreeMassImpact {
        FreeMassImpact {
            m_h: self.m_h,
            v0: v,
            link: LinkParams {
                m_r: self.m_r,
                length: self.settings.length(),
                k_delta: self.k_delta,
                m_e: self.m_e,
            },
            joint: self.settings.joint(),
            contact: self.hertz,
            damping: DampingSpec::NONE,
        }
    }

    /// The impact ready for runs at speeds near `guess` [m/s]: the CL's modes solved once (at
    /// `guess`; the free hub's initial modal rates scale with v exactly).
    pub fn prepare(&self, guess: f64) -> Result<FeRuns, Error> {
        let guess = guess.clamp(1e-5, 1e2);
        let reference = self.setup_at(guess);
        reference.validate()?;
        let modes = match self.link {
            FeLink::CompliantLink => cl_tip_modes(&reference, &GradedMesh::DEFAULT)?,
            // the rigid link on its spring (and the rotor behind it with a free hub)
            FeLink::CompliantJoint => Chain::cj(&reference).tip_modes(&reference, 0.0)?,
        };
        Ok(FeRuns {
            impact: *self,
            modes,
            time_integral: hertz_time_integral(self.hertz.n()),
            guess,
            runs: 0,
            screens: 0,
            force_scale: 0.0,
            done: Vec::new(),
        })
    }
}

/// A prepared [`FeImpact`]: every contact of the impact at any speed, until the bodies part
/// for good.
#[derive(Debug, Clone)]
pub struct FeRuns {
    impact: FeImpact,
    modes: flexrig_impact::tip_modes::TipModes,
    /// The skin law's contact-time integral (each run's time scale from it).
    time_integral: f64,
    guess: f64,
    /// Impacts run so far, screens included (a speed asked again is not run again).
    pub runs: usize,
    /// How many of them were screens ([`FeRuns::screen`]).
    pub screens: usize,
    /// The force \[N\] the integrator's tolerance is measured against at least
    /// ([`FeRuns::against`]; 0: each run's own largest force).
    force_scale: f64,
    /// Every impact run so far, by the bits of its speed: a search that asks a speed again (the
    /// pressure's scan over the force's, the governing contact at the root) gets the same run;
    /// the flag: followed until the bodies parted for good (else stopped at its settled peak).
    done: Vec<(u64, SimulatedPeak, bool)>,
}

/// What a run is asked ([`FeRuns::run_at`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Ask {
    /// Every contact until the bodies part for good.
    Whole,
    /// The largest peak: stopped once no later contact can pass the largest so far.
    Largest,
    /// The screen: at the screen's tolerance, whether any contact reaches this force \[N\].
    Below(f64),
}

/// The stopping rule of every simulated impact: the run follows contact after contact and ends
/// when the bodies have **parted for good** — their rigid motions carry them apart and the gap is
/// larger than the most the link's vibrating tip can ever reach (the sum over the flexible modes
/// of |gain| × amplitude, a bound from the modes' energy, not a guess). The window below only
/// guards against a run that never parts; reaching it is an error, not a verdict.
pub const PARTING_GUARD_S: f64 = 1e6;

/// The searches' force hold's tolerance as a fraction of the run tolerance
/// ([`SimulationSettings::tol`]). The step control bounds the hold's per-step deviation as the
/// linear hold's does, but the higher holds' answers sit farther from converged at the same
/// tolerance: against runs at tol 1e-9 and root tolerance 1e-10, the quadratic hold put the map's
/// rattling corner (CJ, m_e = 0.01 kg, k_δ = 10 N/m) 6.9e-6 away at 1e-6 and 6.9e-7 at 1e-7
/// (the linear hold at 1e-6: 6.7e-7), the hand sample of docs/safety.md 1.2e-6 and 1.0e-7
/// (linear: 2.0e-7). A tenth kept the answers as close to converged as the linear hold's were;
/// the cubic hold the searches run now is closer at the same tenth (the hand map of
/// docs/performance.md outside its rattling corner: 1 599 of 1 728 speeds within 1e-7 of the
/// converged map, the worst 2.5e-6; the quadratic hold 1 059 and 6.3e-6), so a default does not
/// change their accuracy.
pub const SEARCH_HOLD_TOL: f64 = 0.1;

/// Most integration steps of one simulated impact (contacts and free flights together).
pub const MAX_IMPACT_STEPS: usize = 20_000_000;

/// The largest contact of one simulated impact (all contacts until the bodies part for good).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SimulatedPeak {
    /// The largest peak force over every contact \[N\].
    pub peak_force_n: f64,
    /// The number of the contact that holds it (1 = the first contact).
    pub contact: usize,
    /// The time of that peak from the first onset \[s\].
    pub time_of_peak_s: f64,
    /// How many contacts the impact had before the bodies parted for good.
    pub contacts: usize,
    /// When the bodies parted for good, from the first onset \[s\].
    pub parted_at_s: f64,
}

impl FeRuns {
    /// The speed the search starts from [m/s] (the guess, within [1e-5, 100]).
    pub fn guess(&self) -> f64 {
        self.guess
    }

    /// The runs with the integrator's tolerance measured against the force `force` \[N\] at
    /// least (the smallest limit the searches ask about): each run only has to tell how its
    /// largest peak compares with that force, so the force's onset need not be resolved to the
    /// tolerance of its first milli-newtons ([`flexrig_impact::modal_run::run_modes_against`]).
    pub fn against(mut self, force: f64) -> FeRuns {
        self.force_scale = force;
        self.done.clear();
        self
    }

    /// The largest peak force \[N\] over every contact at speed `v` [m/s]: the run stops once no
    /// later contact can pass its largest peak so far (a held joint;
    /// [`flexrig_impact::modal_run::largest_peak_cubic_against`]), which leaves that peak
    /// bit for bit the full run's.
    pub fn peak(&mut self, v: f64, stop: &AtomicBool) -> Result<f64, Error> {
        Ok(self.run_cached(v, false, stop)?.peak_force_n)
    }

    /// Every contact at speed `v` [m/s] until the bodies part for good, and the largest.
    pub fn impact_at(&mut self, v: f64, stop: &AtomicBool) -> Result<SimulatedPeak, Error> {
        self.run_cached(v, true, stop)
    }

    /// The run at `v` [m/s], remembered by the bits of its speed; `whole`: followed until the
    /// bodies part for good (a run that stopped at its settled peak is run again).
    fn run_cached(
        &mut self,
        v: f64,
        whole: bool,
        stop: &AtomicBool,
    ) -> Result<SimulatedPeak, Error> {
        if stop.load(Ordering::Relaxed) {
            return Err(Error::Impact(ImpactError::Interrupted));
        }
        let known = self.done.iter().position(|(bits, ..)| *bits == v.to_bits());
        if let Some(i) = known
            && (self.done[i].2 || !whole)
        {
            return Ok(self.done[i].1);
        }
        let ask = if whole { Ask::Whole } else { Ask::Largest };
        let (peak, complete) = self.run_at(v, ask)?;
        match known {
            Some(i) => self.done[i] = (v.to_bits(), peak, complete),
            None => self.done.push((v.to_bits(), peak, complete)),
        }
        Ok(peak)
    }

    /// The screen at `v` [m/s]: a run at the screen's looser tolerance
    /// ([`SCREEN_TOL_FACTOR`] × the searches') asked only whether a contact reaches `threshold`
    /// \[N\] ([`flexrig_impact::modal_run::threshold_cubic_against`]). The largest peak of its
    /// contacts \[N\] when none does, `None` when one does. Not remembered: the searches' own
    /// runs at `v` are a different run.
    pub fn screen(
        &mut self,
        v: f64,
        threshold: f64,
        stop: &AtomicBool,
    ) -> Result<Option<f64>, Error> {
        if stop.load(Ordering::Relaxed) {
            return Err(Error::Impact(ImpactError::Interrupted));
        }
        self.screens += 1;
        let (peak, _) = self.run_at(v, Ask::Below(threshold))?;
        Ok((peak.peak_force_n < threshold).then_some(peak.peak_force_n))
    }

    /// The run at `v` [m/s] asked `ask`, and whether it was followed until the bodies parted
    /// for good.
    fn run_at(&mut self, v: f64, ask: Ask) -> Result<(SimulatedPeak, bool), Error> {
        self.runs += 1;
        let settings = &self.impact.settings;
        let setup = self.impact.setup_at(v);
        let mut m = self.modes.clone();
        // the free hub's initial modal rates are linear in v (a held joint's are 0)
        let scale = v / self.guess;
        m.rates.iter_mut().for_each(|r| *r *= scale);
        let tol = match ask {
            // (within the integrator's range at any `--tol`)
            Ask::Below(_) => (settings.tol * SEARCH_HOLD_TOL * SCREEN_TOL_FACTOR).min(0.1),
            Ask::Whole | Ask::Largest => settings.tol * SEARCH_HOLD_TOL,
        };
        let options = ModalOptions {
            tol,
            window_s: Some(PARTING_GUARD_S),
            max_steps: MAX_IMPACT_STEPS,
        };
        // the force held cubic over each step: fourth order, far fewer steps than the linear
        // and the quadratic hold at the same accuracy of the answer
        setup.validate()?;
        let t_scale = setup.payload_contact_time_with(self.time_integral);
        let head = head_at_onset(&setup);
        // an undamped law (the searches' damping is none): the energy bounds hold
        let (law, force_scale) = (&setup.contact, self.force_scale);
        let (contacts, end) = match ask {
            Ask::Largest => {
                let run =
                    largest_peak_cubic_against(&m, head, law, t_scale, &options, force_scale)?;
                (run.contacts, run.end)
            }
            Ask::Below(f) => {
                let run =
                    threshold_cubic_against(&m, head, law, t_scale, &options, force_scale, f)?;
                (run.contacts, run.end)
            }
            Ask::Whole => {
                let law = setup.law()?;
                let outcome =
                    run_modes_cubic_against(&m, head, &*law, t_scale, &options, force_scale)?;
                (outcome.contacts, PeakRunEnd::Ended(outcome.ended))
            }
        };
        let parted_at_s = match end {
            PeakRunEnd::Ended(RunEnd::PartedForGood(t))
            | PeakRunEnd::Settled(t)
            | PeakRunEnd::Reached(t)
            | PeakRunEnd::StaysBelow(t) => t,
            PeakRunEnd::Ended(RunEnd::Window(t) | RunEnd::StepBudget(t) | RunEnd::Rebound(t)) => {
                return Err(Error::NonFinite {
                    what: format!("simulated impact at {} m/s", display(v)),
                    value: format!(
                        "the bodies had not parted for good after {} contacts ({} s)",
                        contacts.len(),
                        display(t)
                    ),
                    advice: "a body that keeps meeting the link has no last contact to judge; \
                             check the masses and stiffnesses"
                        .into(),
                });
            }
            PeakRunEnd::Ended(RunEnd::FirstSeparation) => contacts[0].duration_s,
        };
        let complete = matches!(end, PeakRunEnd::Ended(_));
        let (index, top) =
            contacts
                .iter()
                .enumerate()
                .fold((0, contacts[0]), |(i, best), (j, c)| {
                    if c.peak_force_n > best.peak_force_n {
                        (j, *c)
                    } else {
                        (i, best)
                    }
                });
        let peak = SimulatedPeak {
            peak_force_n: top.peak_force_n,
            contact: index + 1,
            time_of_peak_s: top.time_of_peak_s,
            contacts: contacts.len(),
            parted_at_s,
        };
        Ok((peak, complete))
    }

    /// The speed [m/s] below which no contact can reach the force `f` \[N\], from energy: a
    /// contact stores U_c(f) = f δ_c/(n + 1), δ_c = (f/k_c)^{1/n}, which cannot exceed the
    /// mechanical energy of the relative motion, ½ m v² (held joint: m = m_h, the ground frame;
    /// free hub: the reduced mass of m_h and the robot's tip-equivalent mass, the frame of the
    /// centre of mass). A bound for every contact, not only the first.
    pub fn energy_floor(&self, f: f64) -> f64 {
        let i = &self.impact;
        let n = i.hertz.n();
        let u = f * (f / i.hertz.k()).powf(1.0 / n) / (n + 1.0);
        let m = match i.settings.joint {
            MapJoint::Held => i.m_h,
            MapJoint::FreeHub { rotor_inertia } => {
                let l = i.settings.length();
                let robot = i.m_e + i.m_r / 3.0 + rotor_inertia / (l * l);
                i.m_h * robot / (i.m_h + robot)
            }
        };
        (2.0 * u / m).sqrt()
    }
}

/// The ratio of two neighbouring speeds of the scan from below ([`smallest_speed_at`]):
/// 2^{1/16} (4.4 %).
pub const SCAN_RATIO: f64 = 1.044_273_782_427_413_8;

/// The fastest speed the scan looks at [m/s]: a limit not reached below it is reported as
/// never reached (unlimited).
pub const SCAN_TOP_MPS: f64 = 1e3;

/// The k-th speed of the scan's grid, q^k m/s (q = [`SCAN_RATIO`]): one grid for every search
/// of a design, so that the force's and the pressure's scans ask the same speeds.
pub fn grid_speed(k: i32) -> f64 {
    (k as f64 * (std::f64::consts::LN_2 / 16.0)).exp()
}

/// The index of the largest grid speed at or below `v` [m/s] (v > 0).
pub fn grid_index_at_or_below(v: f64) -> i32 {
    let mut k = (v.ln() / (std::f64::consts::LN_2 / 16.0)).floor() as i32;
    while grid_speed(k) > v {
        k -= 1;
    }
    while grid_speed(k + 1) <= v {
        k += 1;
    }
    k
}

/// What [`smallest_speed_on_grid`] found: the smallest speed [m/s] at which the limit is
/// reached (+∞: not up to [`SCAN_TOP_MPS`]) and the index of the grid's last speed below it, at
/// which the largest peak stays below the limit (absent when the limit is reached at the scan's
/// first speed).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridCrossing {
    /// The smallest speed at the limit [m/s].
    pub speed: f64,
    /// The grid index of the last speed below it.
    pub below: Option<i32>,
}

/// The smallest speed [m/s] at which the largest contact force of `runs` reaches `force` \[N\]
/// ([`smallest_speed_on_grid`] from the energy floor). Each evaluation goes to `trace` when
/// given.
pub fn smallest_speed_at(
    runs: &mut FeRuns,
    force: f64,
    rtol: f64,
    stop: &AtomicBool,
    trace: Option<&mut Vec<RootStep>>,
) -> Result<f64, Error> {
    Ok(smallest_speed_on_grid(runs, force, None, rtol, stop, trace)?.speed)
}

/// The smallest speed [m/s] at which the largest contact force of `runs` reaches `force` \[N\]:
/// a scan from below on the grid q^k m/s ([`grid_speed`], q = [`SCAN_RATIO`]) from its last
/// speed at or below the energy floor v_0 ([`FeRuns::energy_floor`], below which no contact can
/// reach `force`) — or from the grid index `from` when that is higher, a speed already known to
/// stay below `force` (the scan of a smaller force ended there) — to the first speed at which it
/// is reached, then the Illinois false position on ln v between that speed and the one before
/// (relative width `rtol`, at most [`REFINE_RUNS`] runs; [`refine`]). +∞ when no speed up to
/// [`SCAN_TOP_MPS`] reaches it. Each evaluation goes to `trace` when given.
///
/// **The screen.** Each grid speed is first run at the screen's looser tolerance
/// ([`FeRuns::screen`]): when every contact stays below [`SCREEN_MARGIN`] × `force` the speed is
/// below the limit, and the search's own run is not needed. Only speeds whose screen reaches
/// that fraction are run at the search's tolerance, and the last speed below the limit is run at
/// it too before the refinement, so the answer is the unscreened scan's. Should that run reach
/// the limit after all (a screen and a search run more than 1/[`SCREEN_MARGIN`] apart), the scan
/// is done again without the screen ([`scan_grid`]).
pub fn smallest_speed_on_grid(
    runs: &mut FeRuns,
    force: f64,
    from: Option<i32>,
    rtol: f64,
    stop: &AtomicBool,
    mut trace: Option<&mut Vec<RootStep>>,
) -> Result<GridCrossing, Error> {
    let floor = runs.energy_floor(force);
    if !(floor.is_finite() && floor > 0.0) {
        return Err(Error::NonFinite {
            what: "simulated speed at the limit".into(),
            value: display(floor),
            advice: "use moderate masses, stiffnesses and limits".into(),
        });
    }
    let start = grid_index_at_or_below(floor).max(from.unwrap_or(i32::MIN));
    // the search's run (its largest peak over the limit), or the screen's (that ratio when it
    // stays below the margin); each evaluation to the trace
    let mut eval = |v: f64, run: GridRun| -> Result<Option<f64>, Error> {
        let (ratio, screened) = match run {
            GridRun::Search => (Some(runs.peak(v, stop)? / force), false),
            GridRun::Screen(margin) => {
                let below = runs.screen(v, margin * force, stop)?;
                (below.map(|peak| peak / force), true)
            }
        };
        if let (Some(t), Some(r)) = (trace.as_deref_mut(), ratio) {
            t.push(RootStep {
                speed_mps: v,
                ratio: r,
                screened,
            });
        }
        Ok(ratio)
    };
    scan_grid(start, rtol, Some(SCREEN_MARGIN), &mut eval)
}

/// One evaluation of [`scan_grid`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GridRun {
    /// The search's own run: its ratio (largest peak over the limit).
    Search,
    /// The screen with this margin (< 1): the ratio when every contact stays below the margin
    /// × the limit, `None` otherwise.
    Screen(f64),
}

/// The scan of [`smallest_speed_on_grid`] from the grid index `start`, `eval` answering each
/// speed [m/s] ([`GridRun`]), each grid speed screened first with `screen`'s margin when given.
/// The last speed below the limit is run by the search before the refinement; should its ratio
/// reach 1 (the screen passed a speed the search does not), the scan is done again without the
/// screen, so a screen that errs on that speed never sets the answer.
pub fn scan_grid(
    start: i32,
    rtol: f64,
    screen: Option<f64>,
    eval: &mut dyn FnMut(f64, GridRun) -> Result<Option<f64>, Error>,
) -> Result<GridCrossing, Error> {
    let search = |v: f64, eval: &mut dyn FnMut(f64, GridRun) -> Result<Option<f64>, Error>| {
        eval(v, GridRun::Search)?.ok_or_else(|| Error::NonFinite {
            what: format!("simulated peak at {} m/s", display(v)),
            value: "none".into(),
            advice: "a search run always has a peak".into(),
        })
    };
    // a grid speed: screened first; (ratio, whether the screen decided it)
    let grid = |v: f64, eval: &mut dyn FnMut(f64, GridRun) -> Result<Option<f64>, Error>| {
        if let Some(margin) = screen
            && let Some(r) = eval(v, GridRun::Screen(margin))?
            && r < 1.0
        {
            return Ok::<(f64, bool), Error>((r, true));
        }
        Ok((search(v, eval)?, false))
    };
    let mut k = start;
    let (mut r_below, mut below_screened) = grid(grid_speed(k), eval)?;
    if r_below >= 1.0 {
        // reached at the first speed (at the floor, within the run's error: a rigid link)
        return Ok(GridCrossing {
            speed: grid_speed(k),
            below: None,
        });
    }
    let r_above = loop {
        let next = grid_speed(k + 1);
        if next > SCAN_TOP_MPS {
            return Ok(GridCrossing {
                speed: f64::INFINITY,
                below: Some(k),
            });
        }
        let (r, screened) = grid(next, eval)?;
        if r >= 1.0 {
            break r;
        }
        k += 1;
        (r_below, below_screened) = (r, screened);
    };
    if below_screened {
        // the refinement starts from the search's own run at the last speed below
        r_below = search(grid_speed(k), eval)?;
        if r_below >= 1.0 {
            return scan_grid(start, rtol, None, eval);
        }
    }
    let speed = refine(
        (grid_speed(k), r_below),
        (grid_speed(k + 1), r_above),
        rtol,
        REFINE_RUNS,
        &mut |v| search(v, eval),
    )?;
    Ok(GridCrossing {
        speed,
        below: Some(k),
    })
}

/// The most runs of a simulated search's refinement ([`refine`]): on the 30 × 30 hand map of
/// docs/performance.md, 1 662 of its 1 800 refinements needed 3 runs or fewer and 75 needed 4 to
/// 6; the 63 that needed 7 to 22 were CL rattles whose largest contact jumps between speeds
/// closer than the root tolerance. With this budget those return the highest speed run below the
/// limit, at most 0.93 % below the unbudgeted answer.
pub const REFINE_RUNS: usize = 6;

/// The most runs of the scenes' and the test bed's refinements ([`scan_up`], [`refine`]): a
/// guard only, their ratios (one smooth scene run per speed) converge in a few.
pub const SCENE_REFINE_RUNS: usize = 200;

/// The screen's tolerance as a multiple of the searches' ([`FeRuns::screen`]): 1e-3 at the
/// default `--tol` (at most 0.1, the integrator's loosest); the cubic hold's steps grow as the
/// tolerance's fourth root, so a smooth contact takes about a tenth of the search's steps.
pub const SCREEN_TOL_FACTOR: f64 = 1e4;

/// A grid speed whose screen keeps every contact below this fraction of the limit is below the
/// limit without the search's run ([`smallest_speed_on_grid`]). Over the 18 433 grid speeds the
/// unscreened scans of the 30 × 30 hand map of docs/performance.md ran, the screen's largest
/// peak was within 1.5e-3 of the search's at half of them and within 1.9 % at nine in ten; at
/// most the search's was 1.51 times the screen's (a rattle whose largest contact depends on
/// round-off: any change of step moves it that much), and no speed whose search reached the
/// limit had a screen below 0.81 of it. 0.65 < 1/1.51, so there no screen passed a speed the
/// search does not, and the map is the unscreened scans' bit for bit.
pub const SCREEN_MARGIN: f64 = 0.65;

/// What a scan from below found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Scan {
    /// The ratio is ≥ 1 at the scan's first speed already.
    AtStart,
    /// The smallest speed [m/s] above the first at which the ratio reaches 1 (refined).
    Crossing(f64),
    /// Not reached up to [`SCAN_TOP_MPS`].
    Never,
}

/// The scan from below: `ratio` (peak over limit) at `start` and on the grid v_k = start q^k
/// (q = [`SCAN_RATIO`]) up to the first speed at which it is ≥ 1, then [`refine`] between that
/// speed and the one before. Each evaluation goes to `trace` when given. Before each speed of
/// the grid, `ahead` is handed that speed and the next ones, one per thread of the pool
/// ([`scan_ahead`]): a caller may run them side by side ([`Peaks::prefetch`]) — the scan still
/// asks them in order and stops at the same speed, so its answer does not depend on it.
pub fn scan_up(
    start: f64,
    rtol: f64,
    ratio: &mut dyn FnMut(f64) -> Result<f64, Error>,
    ahead: &mut dyn FnMut(&[f64]),
    mut trace: Option<&mut Vec<RootStep>>,
) -> Result<Scan, Error> {
    let mut eval = |v: f64, trace: &mut Option<&mut Vec<RootStep>>| -> Result<f64, Error> {
        let r = ratio(v)?;
        if let Some(t) = trace.as_deref_mut() {
            t.push(RootStep {
                speed_mps: v,
                ratio: r,
                screened: false,
            });
        }
        Ok(r)
    };
    let mut below = start;
    ahead(&scan_ahead(start));
    let mut r_below = eval(below, &mut trace)?;
    if r_below >= 1.0 {
        return Ok(Scan::AtStart);
    }
    let (above, r_above) = loop {
        let next = below * SCAN_RATIO;
        if next > SCAN_TOP_MPS {
            return Ok(Scan::Never);
        }
        ahead(&scan_ahead(next));
        let r = eval(next, &mut trace)?;
        if r >= 1.0 {
            break (next, r);
        }
        below = next;
        r_below = r;
    };
    Ok(Scan::Crossing(refine(
        (below, r_below),
        (above, r_above),
        rtol,
        SCENE_REFINE_RUNS,
        &mut |v| eval(v, &mut trace),
    )?))
}

/// The speeds of [`scan_up`]'s grid from `v` on, as it computes them (v, v q, v q², …), one
/// per thread of the rayon pool (just `v` on one thread), none above [`SCAN_TOP_MPS`].
pub fn scan_ahead(v: f64) -> Vec<f64> {
    std::iter::successors(Some(v), |&u| Some(u * SCAN_RATIO))
        .take(rayon::current_num_threads().max(1))
        .take_while(|&u| u <= SCAN_TOP_MPS)
        .collect()
}

/// The Illinois false position on ln v for ln(ratio) = 0 between `below` (ratio < 1) and
/// `above` (ratio ≥ 1), each (speed [m/s], ratio), to the relative width `rtol`: the upper end
/// of the final bracket (a speed at which the limit is reached). A ratio smooth on the bracket
/// gets there in a few runs; one that has not after `max_runs` is not smooth there (a rattle
/// whose largest contact changes from one speed to the next), and the lower end is returned:
/// the highest speed run below the limit, every speed run above it having reached the limit —
/// the conservative end of what the runs showed.
pub fn refine(
    below: (f64, f64),
    above: (f64, f64),
    rtol: f64,
    max_runs: usize,
    ratio: &mut dyn FnMut(f64) -> Result<f64, Error>,
) -> Result<f64, Error> {
    let (mut a, mut b) = (below.0.ln(), above.0.ln());
    let mut ga = below.1.ln();
    let mut gb = above.1.ln();
    let mut side = 0;
    // the lower end as the speed run there
    let mut a_speed = below.0;
    for run in 0.. {
        if (b - a).abs() < rtol || gb == 0.0 {
            break;
        }
        if run == max_runs {
            return Ok(a_speed);
        }
        let x = if gb.is_finite() && ga.is_finite() && gb != ga {
            (a * gb - b * ga) / (gb - ga)
        } else {
            0.5 * (a + b)
        };
        let gx = ratio(x.exp())?.ln();
        if gx >= 0.0 {
            b = x;
            gb = gx;
            if side == 1 {
                ga /= 2.0;
            }
            side = 1;
        } else {
            a = x;
            a_speed = x.exp();
            ga = gx;
            if side == -1 {
                gb /= 2.0;
            }
            side = -1;
        }
    }
    Ok(b.exp())
}

/// Which limits' speeds a design's searches find ([`fe_search`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LimitSearch {
    /// Both: the force limit's speed and the pressure limit's (`flexrig safety`, which prints
    /// both).
    Both,
    /// Only the limit that governs, which the two forces decide without a run: the other
    /// limit's speed is reported as a lower bound, the governing one's (the safe-speed map,
    /// which shows the permissible speed).
    Governing,
}

/// What a design's searches found ([`fe_search`]).
#[derive(Debug, Clone)]
pub struct FeSearch {
    /// The smallest speed at which the largest contact reaches the force limit [m/s] (+∞:
    /// never; a lower bound when [`FeSearch::bound`] names the force).
    pub by_force: f64,
    /// The smallest speed at which it reaches the force f_p of the pressure limit [m/s]
    /// (absent: pressure not assessed; a lower bound when [`FeSearch::bound`] names the
    /// pressure).
    pub by_pressure: Option<f64>,
    /// The limit that sets the permissible speed min(by force, by pressure).
    pub governing: GoverningLimit,
    /// The limit whose speed was not searched ([`LimitSearch::Governing`]): its speed is only
    /// known to be at least the governing one's.
    pub bound: Option<GoverningLimit>,
    /// Every run of the searches: a later question at a speed they ran (the governing contact
    /// at the permissible speed) is answered by the same run.
    pub runs: FeRuns,
}

/// The simulated speeds of one design: by force (the largest contact reaches `limits.force`)
/// and by pressure (it reaches the force f_p at which the mean pressure of `energy`'s area
/// model reaches the pressure limit; searched when `pressure` is true and the limits have
/// one), each the smallest such speed ([`smallest_speed_on_grid`]); the search on the force
/// limit goes to `trace` (with [`LimitSearch::Governing`] and the pressure governing: the
/// search on f_p).
///
/// Which limit governs follows from the two forces alone: a contact that reaches the larger of
/// F_max and f_p has passed the smaller, so the smallest speed that reaches the larger is no
/// lower than the smallest that reaches the smaller. With [`LimitSearch::Governing`] only the
/// smaller force is searched and the other speed is reported as at least the governing one
/// ([`FeSearch::bound`]); with [`LimitSearch::Both`] both are searched on one grid, the larger
/// force's scan starting where the smaller's found its last speed below (and unlimited when the
/// smaller's is). Every run is measured against the smaller force ([`FeRuns::against`]).
pub fn fe_search(
    impact: &FeImpact,
    limits: &flexrig_safety::Limits,
    energy: &EnergyContact,
    pressure: bool,
    search: LimitSearch,
    stop: &AtomicBool,
    trace: Option<&mut Vec<RootStep>>,
) -> Result<FeSearch, Error> {
    let pressure_force = match limits.pressure {
        Some(p) if pressure => Some(energy.force_at_pressure(p)),
        _ => None,
    };
    let f_p = match pressure_force {
        Some(Some(PressureCrossing::AtForce(f))) => Some(f),
        _ => None,
    };
    let smallest = f_p.map_or(limits.force, |f| f.min(limits.force));
    let mut runs = impact.prepare(MODES_SPEED)?.against(smallest);
    let root_rtol = impact.settings.root_rtol;
    let scan = |runs: &mut FeRuns, force, from, trace| {
        smallest_speed_on_grid(runs, force, from, root_rtol, stop, trace)
    };
    let (by_force, by_pressure, bound) = match (pressure_force, f_p) {
        // the pressure's force below the force limit: the pressure governs
        (_, Some(f)) if f < limits.force => match search {
            LimitSearch::Both => {
                let by_force = scan(&mut runs, limits.force, None, trace)?.speed;
                let by_pressure = scan(&mut runs, f, None, None)?.speed;
                (by_force, Some(by_pressure), None)
            }
            LimitSearch::Governing => {
                let by_pressure = scan(&mut runs, f, None, trace)?.speed;
                (by_pressure, Some(by_pressure), Some(GoverningLimit::Force))
            }
        },
        (_, Some(f)) => {
            let by_force = scan(&mut runs, limits.force, None, trace)?;
            match (search, by_force.speed.is_finite()) {
                (LimitSearch::Both, true) => {
                    let by_pressure = scan(&mut runs, f, by_force.below, None)?.speed;
                    (by_force.speed, Some(by_pressure), None)
                }
                (LimitSearch::Governing, true) => (
                    by_force.speed,
                    Some(by_force.speed),
                    Some(GoverningLimit::Pressure),
                ),
                (_, false) => (f64::INFINITY, Some(f64::INFINITY), None),
            }
        }
        (pressure_force, None) => {
            let by_force = scan(&mut runs, limits.force, None, trace)?.speed;
            let by_pressure = match pressure_force {
                Some(Some(PressureCrossing::Always)) => Some(0.0),
                Some(Some(PressureCrossing::Never) | None) => Some(f64::INFINITY),
                _ => None,
            };
            (by_force, by_pressure, None)
        }
    };
    let governing = match (bound, by_pressure) {
        (Some(GoverningLimit::Force), _) => GoverningLimit::Pressure,
        (Some(GoverningLimit::Pressure), _) => GoverningLimit::Force,
        (None, Some(vp)) if vp < by_force => GoverningLimit::Pressure,
        (None, _) => GoverningLimit::Force,
    };
    Ok(FeSearch {
        by_force,
        by_pressure,
        governing,
        bound,
        runs,
    })
}

/// The speed [m/s] at which the link's modes are solved once per design (the free hub's modal
/// rates are scaled from it exactly, so every caller gets the same runs bit for bit).
pub const MODES_SPEED: f64 = 1.0;

/// One evaluation of a root search on the speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RootStep {
    /// The speed tried [m/s].
    pub speed_mps: f64,
    /// Peak over limit at that speed.
    pub ratio: f64,
    /// True for a screen ([`FeRuns::screen`]): a run at the screen's looser tolerance whose
    /// every contact stayed below [`SCREEN_MARGIN`] × the limit.
    pub screened: bool,
}

/// The speed at which `ratio(v)` (peak over limit, increasing in v) equals 1: a bracket grown by
/// factors of 2 around `guess`, then the Illinois false position on ln v until the bracket is
/// narrower than `rtol` (relative in v). Each evaluation is pushed to `trace` when given.
pub fn speed_at_ratio(
    guess: f64,
    rtol: f64,
    ratio: &mut dyn FnMut(f64) -> Result<f64, Error>,
    mut trace: Option<&mut Vec<RootStep>>,
) -> Result<f64, Error> {
    let mut g = |x: f64| -> Result<f64, Error> {
        let r = ratio(x.exp())?;
        if let Some(t) = trace.as_deref_mut() {
            t.push(RootStep {
                speed_mps: x.exp(),
                ratio: r,
                screened: false,
            });
        }
        Ok(r.ln())
    };
    let mut a = (guess / 1.01).ln();
    let mut b = (guess * 1.01).ln();
    let mut ga = g(a)?;
    let mut gb = g(b)?;
    let mut grow = 0;
    while ga * gb > 0.0 {
        grow += 1;
        if grow > 60 || !ga.is_finite() || !gb.is_finite() {
            return Err(Error::NonFinite {
                what: "simulated speed at the limit".into(),
                value: "no bracket".into(),
                advice: "use moderate masses and stiffnesses".into(),
            });
        }
        if ga > 0.0 {
            a -= std::f64::consts::LN_2;
            ga = g(a)?;
        } else {
            b += std::f64::consts::LN_2;
            gb = g(b)?;
        }
    }
    let mut side = 0;
    for _ in 0..200 {
        let x = (a * gb - b * ga) / (gb - ga);
        if (b - a).abs() < rtol {
            return Ok(x.exp());
        }
        let gx = g(x)?;
        if gx == 0.0 {
            return Ok(x.exp());
        }
        if gx * gb < 0.0 {
            a = b;
            ga = gb;
            side = 0;
        } else if side == -1 {
            ga /= 2.0;
        } else {
            side = -1;
        }
        b = x;
        gb = gx;
        if (b - a).abs() < rtol || gx.abs() < rtol * 1e-3 {
            return Ok(b.exp());
        }
    }
    Ok(((a + b) / 2.0).exp())
}

/// The contacts of a driven scene's run at the judged speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactsAtRoot {
    /// How many contacts the run had.
    pub contacts: usize,
    /// The number of the contact with the largest peak force (1 = the first).
    pub governing: usize,
    /// The time of that peak from the drive's start \[s\].
    pub time_of_peak_s: f64,
    /// How the run ended (the bodies parted for good, the window closed, the operator's
    /// rebound).
    pub ended: flexrig_impact::RunEnd,
}

/// The simulated permissible speed of a driven scene, with what the search did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneSimulation {
    /// Where the scene came from.
    pub scene: String,
    /// The scene's name.
    pub name: String,
    /// CJ or CL.
    pub design: StrikeDesign,
    /// The head's support: `free`, `neck` or `wall` (a test bed: `pendulum`).
    pub support: &'static str,
    /// The commanded tip speed of the scene as written [m/s] (a test bed: the operator's speed
    /// at contact as written).
    pub scene_tip_speed_mps: f64,
    /// The commanded tip speed at which the peak force reaches the force limit [m/s] (a test
    /// bed: the operator's speed at contact).
    pub by_force_mps: f64,
    /// The same for the pressure limit [m/s] (absent without a pressure assessment; +∞ when
    /// the pressure never reaches its limit, 0 when it always does).
    #[serde(skip)]
    pub by_pressure_mps: Option<f64>,
    /// The approach speed δ̇ at the onset of the run at the force root [m/s] (the drive lags its
    /// command).
    pub approach_speed_at_root_mps: f64,
    /// The largest peak force over the contacts of the run at the force root \[N\].
    pub peak_force_at_root_n: f64,
    /// The contacts of the run at the force root (a driven scene; absent for a test bed).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts_at_root: Option<ContactsAtRoot>,
    /// What the drive did in the run at the force root, in words.
    pub notes: Vec<String>,
    /// Every evaluation of the search on the force limit.
    pub force_search: Vec<RootStep>,
    /// Driven strikes simulated (both searches).
    pub runs: usize,
    /// The run tolerance: DOP853's relative tolerance (CJ) or the modal integrator's (CL); a test
    /// bed: the adaptive contact's relative tolerance, or Rapier's contact step \[s\] when the
    /// rig steps the contact (the CL).
    pub run_tol: f64,
    /// How each run simulates the link, in words (the model and its accuracy setting).
    pub link_model: String,
    /// The root search's relative tolerance on the speed.
    pub root_rtol: f64,
    /// A test-bed scene: the operator's release angle \[deg\] of the run at the force root (the
    /// largest, 170°, when the limit is not reached); absent for a driven scene.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub release_angle_at_root_deg: Option<f64>,
    /// False when the force limit is not reached at the largest speed the scene allows (a test
    /// bed released from 170°): `by_force_mps` is then that speed, a lower bound.
    pub limit_reached: bool,
}

/// The largest peak force at each speed run so far: the force and the pressure scans walk the
/// same grid, so the second reuses the first's runs (the same speed gives the same run bit for
/// bit). Interior mutability, so that a scan's evaluation and its look-ahead
/// ([`Peaks::prefetch`]) share it.
#[derive(Debug, Default)]
pub(crate) struct Peaks {
    known: std::cell::RefCell<std::collections::HashMap<u64, f64>>,
    /// Peaks run ahead of the scan and not yet asked for.
    ahead: std::cell::RefCell<std::collections::HashMap<u64, f64>>,
    runs: std::cell::Cell<usize>,
}

impl Peaks {
    /// How many runs the searches used (runs made ahead and never asked for are not counted,
    /// so the count does not depend on the number of threads).
    pub(crate) fn runs(&self) -> usize {
        self.runs.get()
    }

    /// The peak at `v` [m/s]: remembered, run ahead, or `run` and remembered.
    pub(crate) fn at(
        &self,
        v: f64,
        run: impl FnOnce(f64) -> Result<f64, Error>,
    ) -> Result<f64, Error> {
        if let Some(p) = self.known.borrow().get(&v.to_bits()) {
            return Ok(*p);
        }
        let p = match self.ahead.borrow_mut().remove(&v.to_bits()) {
            Some(p) => p,
            None => run(v)?,
        };
        self.runs.set(self.runs.get() + 1);
        self.known.borrow_mut().insert(v.to_bits(), p);
        Ok(p)
    }

    /// When the first of `speeds` [m/s] (the one the scan asks next) is not known yet: runs it
    /// and the others not known yet side by side on the rayon pool and keeps their peaks for
    /// [`Peaks::at`] (the same run at the same speed: the same bits), so that the scan's next
    /// steps find them. A speed whose run fails is left to be run again in order, where its
    /// error counts (a run past the crossing may fail without the scan ever asking it); nothing
    /// to do for fewer than two.
    pub(crate) fn prefetch(&self, speeds: &[f64], run: impl Fn(f64) -> Result<f64, Error> + Sync) {
        use rayon::prelude::*;
        let unknown = |v: &f64| {
            !self.known.borrow().contains_key(&v.to_bits())
                && !self.ahead.borrow().contains_key(&v.to_bits())
        };
        if !speeds.first().is_some_and(unknown) {
            return;
        }
        let todo: Vec<f64> = speeds.iter().copied().filter(unknown).collect();
        if todo.len() < 2 {
            return;
        }
        let done: Vec<(f64, Result<f64, Error>)> = todo.par_iter().map(|&v| (v, run(v))).collect();
        let mut ahead = self.ahead.borrow_mut();
        for (v, p) in done {
            if let Ok(p) = p {
                ahead.insert(v.to_bits(), p);
            }
        }
    }
}

/// The lowest speed the scan of a driven scene starts from, as a fraction of the energy
/// method's speed (the driven and test-bed scenes' `simulate`).
pub const SCAN_START_OF_GUESS: f64 = 1.0 / 64.0;
