//! The spin-up beam benchmark (Simo & Vu-Quoc 1986's 10 m beam, the default; Kane, Ryan &
//! Banerjee 1987's 8 m aluminium beam, [`SpinUpCase`]): a cantilever on
//! a hub spun up by θ(t) = (ω_s/T_s)[t²/2 + (T_s/2π)²(cos(2πt/T_s) − 1)] (t < T_s), then
//! ω_s(t − T_s/2). The tip's deflection in the hub frame by the corotational FE beam on a
//! rotating clamp, by the independent elastica reference (Ritz on the section angle) and by the
//! linear rotating-frame beam ([`flexrig_impact::spin_up`]); written as spin_up.csv
//! (`t,fe,reference,linear`), spin_up.json and spin_up.svg.

use std::fmt::Write as _;
use std::path::PathBuf;

use flexrig_impact::spin_up::{
    SpinUp, SpinUpSeries, spin_up_fe_until, spin_up_linear_until, spin_up_reference_until,
};
use serde::Serialize;

use super::{check, num};
use crate::plots::{Curve, CurveAxes, CurvePanel, FigureOptions, curves_svg, write_figure};
use crate::shared::output::{ensure_dir, positive_arg, write_atomic};
use crate::{CancelToken, Error};

/// The benchmark's beam, spin-up and discretisation (SI units; defaults: the literature case).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpinUpOptions {
    /// Beam length L \[m\] (`--length`; 10 for Simo & Vu-Quoc's beam).
    pub length: f64,
    /// Cross-section area A \[m²\] (`--area`; 4e-4).
    pub area: f64,
    /// Second moment of area I \[m⁴\] (`--second-moment`; 2e-7).
    pub second_moment: f64,
    /// Young's modulus E \[Pa\] (`--youngs-modulus`; 7e10).
    pub youngs_modulus: f64,
    /// Density ρ \[kg/m³\] (`--density`; 3000).
    pub density: f64,
    /// Spin-up time T_s \[s\] (`--t-s`; 15).
    pub t_s: f64,
    /// Final hub speed ω_s \[rad/s\] (`--omega-s`; 6).
    pub omega_s: f64,
    /// FE elements (`--elements`; 16: 2.2e-3 of the max from the reference, docs/driven.md).
    pub elements: usize,
    /// Run length \[s\] (`--duration`; `None`: T_s + 5 s as in the benchmark).
    pub duration: Option<f64>,
    /// Reporting interval \[s\] (`--sample-every`; 0.1).
    pub sample_every: f64,
    /// Largest FE time step \[s\] (`--max-step`; 5e-3).
    pub max_step: f64,
    /// Modes of the reference and the linear model (`--modes`, 2 to 12; 5).
    pub modes: usize,
}

impl SpinUpOptions {
    /// Simo & Vu-Quoc's 10 m beam (1986; [`SpinUp::simo_vu_quoc`]), spun up to 6 rad/s: the
    /// defaults of `flexrig spin-up` (`--case simo-vu-quoc`).
    pub const SIMO_VU_QUOC: SpinUpOptions = SpinUpOptions {
        length: 10.0,
        area: 4e-4,
        second_moment: 2e-7,
        youngs_modulus: 7e10,
        density: 3000.0,
        t_s: 15.0,
        omega_s: 6.0,
        elements: DEFAULT_ELEMENTS,
        duration: None,
        sample_every: 0.1,
        max_step: DEFAULT_MAX_STEP,
        modes: DEFAULT_MODES,
    };

    /// Kane, Ryan & Banerjee's 8 m aluminium beam (1987; [`SpinUp::kane_ryan_banerjee`]),
    /// spun up to 4 rad/s (`--case kane`).
    pub const KANE_RYAN_BANERJEE: SpinUpOptions = SpinUpOptions {
        length: 8.0,
        area: flexrig_impact::spin_up::KANE_AREA,
        second_moment: flexrig_impact::spin_up::KANE_I,
        youngs_modulus: flexrig_impact::spin_up::KANE_E,
        density: flexrig_impact::spin_up::KANE_RHO,
        t_s: 15.0,
        omega_s: 4.0,
        elements: DEFAULT_ELEMENTS,
        duration: None,
        sample_every: 0.1,
        max_step: DEFAULT_MAX_STEP,
        modes: DEFAULT_MODES,
    };

    /// The defaults before the two beams had names: [`SpinUpOptions::SIMO_VU_QUOC`] (the
    /// 10 m beam, long credited here to Kane et al.).
    pub const LITERATURE: SpinUpOptions = SpinUpOptions::SIMO_VU_QUOC;
}

/// FE elements by default: 16 (the FE's error 2.2e-3 of the max at ω_s = 6 rad/s with the
/// default step; 1.8e-3 at 1e-3 s, 6.7e-3 with 8 elements, 9e-4 with 24; docs/driven.md).
pub const DEFAULT_ELEMENTS: usize = 16;
/// The FE's largest step by default \[s\]: 5e-3 (the error 2.2e-3 of the max against 1.8e-3
/// at 1e-3 s, at a quarter of the cost).
pub const DEFAULT_MAX_STEP: f64 = 5e-3;
/// The reference's (and the linear model's) modes by default: 5, within 2.3e-6 of the max of
/// the 7-mode reference (4 modes: 8.9e-5; 6: 7.3e-8) — three orders below the FE's error, at a
/// sixth of the 7 modes' cost.
pub const DEFAULT_MODES: usize = 5;

/// The spin-up beams by name (`--case`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpinUpCase {
    /// Simo & Vu-Quoc (1986): L = 10 m, EA = 2.8e7 N, EI = 1.4e4 N·m², ρA = 1.2 kg/m.
    SimoVuQuoc,
    /// Kane, Ryan & Banerjee (1987): the 8 m aluminium beam.
    Kane,
}

impl SpinUpCase {
    /// The case's options (its beam, spin-up and the default discretisation).
    pub fn options(self) -> SpinUpOptions {
        match self {
            SpinUpCase::SimoVuQuoc => SpinUpOptions::SIMO_VU_QUOC,
            SpinUpCase::Kane => SpinUpOptions::KANE_RYAN_BANERJEE,
        }
    }

    /// The source, for headings.
    pub fn source(self) -> &'static str {
        match self {
            SpinUpCase::SimoVuQuoc => "Simo & Vu-Quoc 1986",
            SpinUpCase::Kane => "Kane, Ryan & Banerjee 1987",
        }
    }

    /// The case's name as `--case` takes it.
    pub fn name(self) -> &'static str {
        match self {
            SpinUpCase::SimoVuQuoc => "simo-vu-quoc",
            SpinUpCase::Kane => "kane",
        }
    }

    /// The case named `word` (`simo-vu-quoc` or `kane`); an error names `flag`, the word and
    /// the names allowed.
    pub fn parse(flag: &str, word: &str) -> Result<SpinUpCase, Error> {
        [SpinUpCase::SimoVuQuoc, SpinUpCase::Kane]
            .into_iter()
            .find(|c| c.name() == word)
            .ok_or_else(|| Error::InvalidArgument {
                arg: flag.into(),
                value: word.into(),
                allowed: "one of simo-vu-quoc, kane".into(),
            })
    }
}

/// The benchmark as `flexrig spin-up`'s flags and its Python twin's keyword arguments describe
/// it: a named beam ([`SpinUpCase`]) whose numbers a flag may override, and the
/// discretisation. [`SpinUpFlags::DEFAULT`] is the command without flags.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpinUpFlags {
    /// The beam and its spin-up (`--case`).
    pub case: SpinUpCase,
    /// Beam length L \[m\] (`--length`; `None`: the case's).
    pub length: Option<f64>,
    /// Cross-section area A \[m²\] (`--area`; `None`: the case's).
    pub area: Option<f64>,
    /// Second moment of area I \[m⁴\] (`--second-moment`; `None`: the case's).
    pub second_moment: Option<f64>,
    /// Young's modulus E \[Pa\] (`--youngs-modulus`; `None`: the case's).
    pub youngs_modulus: Option<f64>,
    /// Density ρ \[kg/m³\] (`--density`; `None`: the case's).
    pub density: Option<f64>,
    /// Spin-up time T_s \[s\] (`--t-s`; `None`: the case's).
    pub t_s: Option<f64>,
    /// Final hub speed ω_s \[rad/s\] (`--omega-s`; `None`: the case's).
    pub omega_s: Option<f64>,
    /// FE elements (`--elements`).
    pub elements: usize,
    /// Run length \[s\] (`--duration`; `None`: T_s + 5 s).
    pub duration: Option<f64>,
    /// Reporting interval \[s\] (`--sample-every`).
    pub sample_every: f64,
    /// Largest FE time step \[s\] (`--max-step`).
    pub max_step: f64,
    /// Modes of the reference and the linear model (`--modes`).
    pub modes: usize,
}

impl SpinUpFlags {
    /// The flags' defaults: Simo & Vu-Quoc's beam as it is, the default discretisation.
    pub const DEFAULT: SpinUpFlags = SpinUpFlags {
        case: SpinUpCase::SimoVuQuoc,
        length: None,
        area: None,
        second_moment: None,
        youngs_modulus: None,
        density: None,
        t_s: None,
        omega_s: None,
        elements: DEFAULT_ELEMENTS,
        duration: None,
        sample_every: 0.1,
        max_step: DEFAULT_MAX_STEP,
        modes: DEFAULT_MODES,
    };

    /// The options to run: the case's beam and spin-up with each number a flag gives in its
    /// place.
    pub fn options(&self) -> SpinUpOptions {
        let c = self.case.options();
        SpinUpOptions {
            length: self.length.unwrap_or(c.length),
            area: self.area.unwrap_or(c.area),
            second_moment: self.second_moment.unwrap_or(c.second_moment),
            youngs_modulus: self.youngs_modulus.unwrap_or(c.youngs_modulus),
            density: self.density.unwrap_or(c.density),
            t_s: self.t_s.unwrap_or(c.t_s),
            omega_s: self.omega_s.unwrap_or(c.omega_s),
            elements: self.elements,
            duration: self.duration,
            sample_every: self.sample_every,
            max_step: self.max_step,
            modes: self.modes,
        }
    }

    /// The heading's source: the case's, or the case's "edited" when a flag changed its beam.
    pub fn source(&self) -> String {
        let edited = [
            self.length,
            self.area,
            self.second_moment,
            self.youngs_modulus,
            self.density,
        ]
        .iter()
        .any(Option::is_some);
        if edited {
            format!("{}, edited", self.case.source())
        } else {
            self.case.source().to_string()
        }
    }
}

impl Default for SpinUpFlags {
    fn default() -> Self {
        SpinUpFlags::DEFAULT
    }
}

impl Default for SpinUpOptions {
    fn default() -> Self {
        SpinUpOptions::SIMO_VU_QUOC
    }
}

/// The three series and the files written.
#[derive(Debug, Clone, Serialize)]
pub struct SpinUpResult {
    /// The inputs.
    pub options: SpinUpOptions,
    /// Reported times \[s\].
    pub t: Vec<f64>,
    /// FE tip deflection in the hub frame \[m\].
    pub fe: Vec<f64>,
    /// The elastica reference \[m\].
    pub reference: Vec<f64>,
    /// The linear rotating-frame beam \[m\] (diverges once θ̇ exceeds its first frequency).
    pub linear: Vec<f64>,
    /// Largest |reference| \[m\].
    pub reference_max_m: f64,
    /// Largest |FE − reference| over the largest |reference|.
    pub fe_error_of_max: f64,
    /// spin_up.csv.
    pub csv: PathBuf,
    /// spin_up.json.
    pub json: PathBuf,
    /// spin_up.svg (written when SVG is among the figure formats, as by default).
    pub svg: PathBuf,
    /// The figure's files, one per format (spin_up.svg, .pdf, .png).
    pub figures: Vec<PathBuf>,
}

impl SpinUpOptions {
    /// The physics crate's model; errors name the flag.
    fn spec(&self) -> Result<SpinUp, Error> {
        let e = positive_arg("--youngs-modulus", self.youngs_modulus)?;
        let a = positive_arg("--area", self.area)?;
        let i = positive_arg("--second-moment", self.second_moment)?;
        let rho = positive_arg("--density", self.density)?;
        let t_s = positive_arg("--t-s", self.t_s)?;
        if !(self.omega_s.is_finite() && self.omega_s != 0.0) {
            return Err(invalid(
                "--omega-s",
                flexrig_contact::validate::display(self.omega_s),
                "a finite speed other than 0 rad/s (at 0 the beam stays at rest: there is no \
                 deflection to compare)",
            ));
        }
        let t_end = match self.duration {
            Some(d) => positive_arg("--duration", d)?,
            None => t_s + 5.0,
        };
        let sample_every = positive_arg("--sample-every", self.sample_every)?;
        if sample_every > t_end {
            return Err(invalid(
                "--sample-every",
                sample_every,
                &format!(
                    "at most the duration, {} s",
                    flexrig_contact::validate::display(t_end)
                ),
            ));
        }
        if !(1..=10_000).contains(&self.elements) {
            return Err(invalid(
                "--elements",
                self.elements,
                "must lie in [1, 10000]",
            ));
        }
        if !(2..=12).contains(&self.modes) {
            return Err(invalid("--modes", self.modes, "must lie in [2, 12]"));
        }
        let max_step = positive_arg("--max-step", self.max_step)?;
        if max_step > sample_every {
            return Err(invalid("--max-step", max_step, "at most --sample-every"));
        }
        let spec = SpinUp {
            length: positive_arg("--length", self.length)?,
            ea: e * a,
            ei: e * i,
            rho_a: rho * a,
            omega_s: self.omega_s,
            t_s,
            t_end,
            sample_every,
        };
        spec.validate().map_err(|err| self.by_flag(err))?;
        Ok(spec)
    }

    /// A range error of the model's field in the flags' words: the flag and the value typed,
    /// and for a product of flags (EA, EI, ρA) the other factor and the product.
    fn by_flag(&self, err: flexrig_impact::ImpactError) -> Error {
        use crate::shared::output::display_number as n;
        let flexrig_impact::ImpactError::InvalidParameter { field, allowed, .. } = &err else {
            return err.into();
        };
        let product =
            |flag: &str, v: f64, other: &str, w: f64, what: &str| Error::InvalidArgument {
                arg: flag.into(),
                value: n(v),
                allowed: format!("with {other} = {}, {what} = {} {allowed}", n(w), n(v * w)),
            };
        let single = |flag: &str, v: f64| Error::InvalidArgument {
            arg: flag.into(),
            value: n(v),
            allowed: allowed.clone(),
        };
        match field.as_str() {
            "length" => single("--length", self.length),
            "omega_s" => single("--omega-s", self.omega_s),
            "t_s" => single("--t-s", self.t_s),
            "t_end" => single("--duration", self.duration.unwrap_or(self.t_s + 5.0)),
            "sample_every" => single("--sample-every", self.sample_every),
            "ea" => product(
                "--youngs-modulus",
                self.youngs_modulus,
                "--area",
                self.area,
                "the axial stiffness E·A",
            ),
            "ei" => product(
                "--youngs-modulus",
                self.youngs_modulus,
                "--second-moment",
                self.second_moment,
                "the bending stiffness E·I",
            ),
            "rho_a" => product(
                "--density",
                self.density,
                "--area",
                self.area,
                "the mass per length ρ·A",
            ),
            _ => err.into(),
        }
    }
}

/// The most reported times of a spin-up (`--duration` / `--sample-every` + 1): each is a stop of
/// both integrators and a row of the CSV, JSON and figure.
pub const MAX_REPORTED_TIMES: f64 = 100_000.0;

/// The most FE work of a spin-up, in element steps (`--elements` × the time steps, the
/// steps `--duration` / `--max-step` or more): about 3 µs each on the project machine
/// (16 elements × 4 000 steps: 0.19 s), so at most ≈ 12 s.
pub const MAX_FE_ELEMENT_STEPS: f64 = 4.0e6;

/// The most work of the reference and the linear model, in the units of
/// [`SpinUpOptions::reference_work`] (duration × the highest mode's frequency scale × the
/// modes²: the explicit integrator's steps are bounded by the highest mode, each costs ∝ the
/// modes²): 5 modes over Simo & Vu-Quoc's 20 s are 1.1e4 (0.7 s), so at most ≈ 30 s — 12 modes
/// over 20 s (4.1e5) still run.
pub const MAX_REFERENCE_WORK: f64 = 5.0e5;

impl SpinUpOptions {
    /// The reference's work estimate: duration \[s\] × √(EI/(ρA L⁴)) \[1/s\] × (modes − ½)²
    /// × modes² (the highest Ritz mode's frequency grows as (modes − ½)² times the scale, and
    /// bounds DOP853's step; a right-hand side costs ∝ modes²).
    pub fn reference_work(spec: &SpinUp, modes: usize) -> f64 {
        let m = modes as f64;
        spec.t_end
            * (spec.ei / (spec.rho_a * spec.length.powi(4))).sqrt()
            * (m - 0.5).powi(2)
            * m
            * m
    }

    /// The work the run will take, checked before it starts (errors name the flags): at most
    /// [`MAX_REPORTED_TIMES`] reported times, [`MAX_REFERENCE_WORK`] for the reference and
    /// [`MAX_FE_ELEMENT_STEPS`] FE element steps.
    fn check_work(&self, spec: &SpinUp) -> Result<(), Error> {
        use crate::shared::output::display_number as n;
        let times = (spec.t_end / spec.sample_every + 1e-9).floor() + 1.0;
        if !(times <= MAX_REPORTED_TIMES) {
            return Err(invalid(
                "--sample-every",
                n(spec.sample_every),
                &format!(
                    "at least {} s for a {} s run (at most {} reported times)",
                    n(spec.t_end / (MAX_REPORTED_TIMES - 1.0)),
                    n(spec.t_end),
                    MAX_REPORTED_TIMES
                ),
            ));
        }
        let work = Self::reference_work(spec, self.modes);
        if !(work <= MAX_REFERENCE_WORK) {
            return Err(invalid(
                "--duration",
                n(spec.t_end),
                &format!(
                    "at most {} s with {} modes for this beam (the reference's work \
                     duration × its highest mode's frequency scale × modes² at most {:e}; \
                     fewer --modes allow longer runs)",
                    n((spec.t_end * MAX_REFERENCE_WORK / work).floor()),
                    self.modes,
                    MAX_REFERENCE_WORK
                ),
            ));
        }
        let steps_per_sample = (spec.sample_every / self.max_step).ceil().max(1.0);
        let steps = steps_per_sample * (times - 1.0);
        let work = steps * self.elements as f64;
        if !(work <= MAX_FE_ELEMENT_STEPS) {
            let (arg, value, allowed) = if self.max_step < SpinUpOptions::LITERATURE.max_step {
                (
                    "--max-step",
                    n(self.max_step),
                    format!(
                        "at least {} s with {} elements over {} s (the FE run's elements × steps \
                         at most {:e})",
                        n(spec.t_end * self.elements as f64 / MAX_FE_ELEMENT_STEPS),
                        self.elements,
                        n(spec.t_end),
                        MAX_FE_ELEMENT_STEPS
                    ),
                )
            } else {
                (
                    "--elements",
                    self.elements.to_string(),
                    format!(
                        "at most {} with {} time steps over {} s (the FE run's elements × steps \
                         at most {:e})",
                        (MAX_FE_ELEMENT_STEPS / steps).floor().max(1.0),
                        steps,
                        n(spec.t_end),
                        MAX_FE_ELEMENT_STEPS
                    ),
                )
            };
            return Err(invalid(arg, value, &allowed));
        }
        Ok(())
    }
}

/// Largest hub rotation per FE time step \[rad\], |ω_s| × `--max-step`: the corotational step's
/// Newton iteration converges at 0.075 rad and not at 0.1 on both literature beams (measured:
/// Simo & Vu-Quoc and Kane at 15 and 20 rad/s with the 5 ms step, and at 20 rad/s with 1 ms).
pub const MAX_ROTATION_PER_STEP: f64 = 0.08;

/// Largest growth exponent of the linear rotating-frame beam: above its first bending
/// frequency ω₁ it has no centrifugal stiffening and its first mode grows as
/// exp ∫ √(ω² − ω₁²) dt; past e^650 (1e282) it leaves double precision before its end
/// (measured: Simo & Vu-Quoc's beam at 60 rad/s reaches e^706 and the run fails at 19.26 s).
pub const MAX_LINEAR_GROWTH: f64 = 650.0;

/// ∫₀^t_end √(max(ω(t)² − ω₁², 0)) dt of the spin-up ω(t) to `omega_s` in `t_s` (the trapezoid
/// rule on 4 000 intervals: the integrand is smooth but for the kink where ω crosses ω₁).
fn linear_growth(omega_s: f64, t_s: f64, t_end: f64, omega_1: f64) -> f64 {
    let n = 4000;
    let h = t_end / n as f64;
    let f = |t: f64| {
        let w = flexrig_impact::drive::spin_up(omega_s.abs(), t_s, t).1;
        (w * w - omega_1 * omega_1).max(0.0).sqrt()
    };
    (0..n)
        .map(|i| 0.5 * h * (f(i as f64 * h) + f((i + 1) as f64 * h)))
        .sum()
}

impl SpinUpOptions {
    /// What the integrators can solve, checked before the work: the FE step's rotation
    /// ([`MAX_ROTATION_PER_STEP`]) and the linear model's growth ([`MAX_LINEAR_GROWTH`]); the
    /// errors name `--omega-s` with the largest speed that works, or `--max-step`.
    fn check_solvable(&self, spec: &SpinUp) -> Result<(), Error> {
        use crate::shared::output::display_number as n;
        let omega = spec.omega_s.abs();
        if omega * self.max_step > MAX_ROTATION_PER_STEP {
            return Err(invalid(
                "--omega-s",
                n(spec.omega_s),
                &format!(
                    "at most {} rad/s in magnitude with --max-step = {} s: the FE step turns the \
                     hub by |ω_s| × the step, at most {MAX_ROTATION_PER_STEP} rad for its Newton \
                     iteration to converge (or a smaller --max-step: at most {} s)",
                    n(MAX_ROTATION_PER_STEP / self.max_step),
                    n(self.max_step),
                    n(MAX_ROTATION_PER_STEP / omega)
                ),
            ));
        }
        // the cantilever's first bending frequency, (β₁L)² √(EI/(ρA L⁴)), β₁L = 1.8751040687
        let omega_1 =
            1.875_104_068_7_f64.powi(2) * (spec.ei / (spec.rho_a * spec.length.powi(4))).sqrt();
        let growth = |w: f64| linear_growth(w, spec.t_s, spec.t_end, omega_1);
        if growth(omega) <= MAX_LINEAR_GROWTH {
            return Ok(());
        }
        let (mut lo, mut hi) = (omega_1, omega);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if growth(mid) <= MAX_LINEAR_GROWTH {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Err(invalid(
            "--omega-s",
            n(spec.omega_s),
            &format!(
                "at most {} rad/s in magnitude over this {} s run: above the beam's first bending \
                 frequency ω₁ = {} rad/s the linear rotating-frame beam (no stiffening) grows as \
                 exp ∫√(ω² − ω₁²) dt and leaves double precision past e^{MAX_LINEAR_GROWTH} (or a \
                 shorter --duration)",
                n((lo * 1e3).floor() / 1e3),
                n(spec.t_end),
                n(omega_1)
            ),
        ))
    }
}

fn invalid(arg: &str, value: impl std::fmt::Display, allowed: &str) -> Error {
    Error::InvalidArgument {
        arg: arg.into(),
        value: crate::shared::output::value_text(value),
        allowed: allowed.into(),
    }
}

/// Relative tolerance of the reference's and the linear model's DOP853: the modes, not the
/// tolerance, set the reference's error (5 modes: 2.3e-6 of the max at 1e-5, 1e-7 and 1e-9
/// alike; docs/driven.md).
const RTOL: f64 = 1e-8;

/// Runs the three models (stopping between them if `cancel` is set) and writes spin_up.csv,
/// spin_up.json and spin_up.svg (two columns wide) into `out` (created if missing).
pub fn run(
    options: &SpinUpOptions,
    out: &std::path::Path,
    cancel: &CancelToken,
) -> Result<SpinUpResult, Error> {
    run_with_figures(options, out, &FigureOptions::two_column_svg(), cancel)
}

/// [`run`] with the figure at the printed width and in the formats of `figures`.
pub fn run_with_figures(
    options: &SpinUpOptions,
    out: &std::path::Path,
    figures: &FigureOptions,
    cancel: &CancelToken,
) -> Result<SpinUpResult, Error> {
    figures.validate()?;
    let spec = options.spec()?;
    options.check_work(&spec)?;
    options.check_solvable(&spec)?;
    // the files' places before the work
    ensure_dir(out)?;
    for name in ["spin_up.csv", "spin_up.json", "spin_up.svg"] {
        crate::shared::output::check_output_target(&out.join(name))?;
    }
    check(cancel)?;
    let stop = cancel.flag();
    let reference = spin_up_reference_until(&spec, options.modes, RTOL, &stop)?;
    check(cancel)?;
    let fe = spin_up_fe_until(&spec, options.elements, options.max_step, &stop)?;
    check(cancel)?;
    let linear = spin_up_linear_until(&spec, options.modes, RTOL, &stop)?;
    check(cancel)?;
    let aligned = |s: &SpinUpSeries| s.t.len() == reference.t.len();
    if !(aligned(&fe) && aligned(&linear)) {
        return Err(Error::NonFinite {
            what: "spin-up series".into(),
            value: "of unequal lengths".into(),
            advice: "report this as a bug".into(),
        });
    }
    let mut result = SpinUpResult {
        options: options.clone(),
        reference_max_m: reference.max_abs(),
        fe_error_of_max: fe.difference(&reference),
        t: reference.t,
        fe: fe.tip_deflection_m,
        reference: reference.tip_deflection_m,
        linear: linear.tip_deflection_m,
        csv: out.join("spin_up.csv"),
        json: out.join("spin_up.json"),
        svg: out.join("spin_up.svg"),
        figures: Vec::new(),
    };
    result.options.duration = Some(spec.t_end);
    write_atomic(&result.csv, csv(&result).as_bytes())?;
    let svg = figure(&result, figures.width_pt()).map_err(|message| Error::Plot {
        path: result.svg.clone(),
        message,
    })?;
    result.figures = write_figure(out, "spin_up", &svg, figures)?;
    let json = serde_json::to_string_pretty(&result).map_err(|e| Error::NonFinite {
        what: "spin-up result".into(),
        value: e.to_string(),
        advice: "a non-finite value cannot be written as JSON".into(),
    })?;
    write_atomic(&result.json, json.as_bytes())?;
    Ok(result)
}

/// `t,fe,reference,linear`, one row per reported time, each number in its shortest exact form.
pub fn csv(r: &SpinUpResult) -> String {
    let mut text = String::from("t,fe,reference,linear\n");
    for i in 0..r.t.len() {
        let _ = writeln!(
            text,
            "{},{},{},{}",
            num(r.t[i]),
            num(r.fe[i]),
            num(r.reference[i]),
            num(r.linear[i])
        );
    }
    text
}

/// The FE and reference tip deflections over time at the printed width `width_pt` \[pt\], the
/// reference a pale band under the FE line (the linear model is in the CSV only: it diverges).
/// Every label from the inputs that ran.
fn figure(r: &SpinUpResult, width_pt: f64) -> Result<String, String> {
    use crate::shared::output::display_number as n;
    let series = |label: String, y: &[f64]| Curve {
        label,
        points: r.t.iter().copied().zip(y.iter().copied()).collect(),
        limit: None,
    };
    let o = &r.options;
    curves_svg(
        &format!(
            "Spin-up beam (L = {} m, hub to ω_s = {} rad/s in T_s = {} s): tip deflection in the \
             hub frame",
            n(o.length),
            n(o.omega_s),
            n(o.t_s)
        ),
        &CurveAxes {
            x_desc: "time t [s]",
            y_desc: "tip deflection [m]",
            x_log: false,
            markers: false,
            reference_band: true,
        },
        &[CurvePanel {
            title: format!(
                "FE against the reference: largest difference {} % of the largest deflection",
                n(significant(100.0 * r.fe_error_of_max, 2))
            ),
            // the reference first: a wide pale band under the thin FE line
            curves: vec![
                series(
                    format!("reference (elastica, {} modes)", o.modes),
                    &r.reference,
                ),
                series(
                    format!("finite elements, {} corotational elements", o.elements),
                    &r.fe,
                ),
            ],
        }],
        width_pt,
    )
}

/// `x` rounded to `digits` significant digits.
fn significant(x: f64, digits: i32) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    let scale = 10f64.powi(digits - 1 - x.abs().log10().floor() as i32);
    (x * scale).round() / scale
}

#[cfg(test)]
mod tests {
    use super::*;

    /// With the token already cancelled, whatever is checked before the work says so, and
    /// valid options stop at once (exit 130): the output place and the work estimate come
    /// first.
    #[test]
    fn the_output_and_the_work_are_checked_before_the_work() {
        let cancelled = CancelToken::new();
        cancelled.cancel();
        let dir = std::env::temp_dir().join(format!("flexrig-spin-up-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let file = dir.join("a_file");
        std::fs::write(&file, "x").unwrap();
        let refused = |options: &SpinUpOptions, out: &std::path::Path, flag: &str| match run(
            options, out, &cancelled,
        ) {
            Err(Error::InvalidArgument { arg, .. }) => assert_eq!(arg, flag),
            other => panic!("{flag}: {other:?}"),
        };
        let d = SpinUpOptions::default();
        refused(&d, &file, "--out");
        refused(
            &SpinUpOptions {
                max_step: 1e-300,
                ..d.clone()
            },
            &dir,
            "--max-step",
        );
        refused(
            &SpinUpOptions {
                elements: 10_000,
                ..d.clone()
            },
            &dir,
            "--elements",
        );
        refused(
            &SpinUpOptions {
                sample_every: 1e-4,
                max_step: 1e-4,
                ..d.clone()
            },
            &dir,
            "--sample-every",
        );
        refused(
            &SpinUpOptions {
                duration: Some(1e6),
                sample_every: 100.0,
                ..d.clone()
            },
            &dir,
            "--duration",
        );
        match run(&d, &dir, &cancelled) {
            Err(Error::Impact(flexrig_impact::ImpactError::Interrupted)) => {}
            other => panic!("{other:?}"),
        }
        let _ = std::fs::remove_dir_all(&dir);
    }

    /// Each case by its name, a wrong name refused naming the flag, the word and the names;
    /// a flag overrides only its own number of the case's beam.
    #[test]
    fn cases_are_named_and_a_flag_overrides_only_its_number() {
        for case in [SpinUpCase::SimoVuQuoc, SpinUpCase::Kane] {
            assert_eq!(SpinUpCase::parse("--case", case.name()).unwrap(), case);
            // the name is the serialised one (what a JSON reader sees)
            assert_eq!(
                serde_json::to_value(case).unwrap(),
                serde_json::json!(case.name())
            );
        }
        match SpinUpCase::parse("--case", "kane-ryan") {
            Err(Error::InvalidArgument {
                arg,
                value,
                allowed,
            }) => {
                assert_eq!((arg.as_str(), value.as_str()), ("--case", "kane-ryan"));
                assert_eq!(allowed, "one of simo-vu-quoc, kane");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(SpinUpFlags::DEFAULT.options(), SpinUpOptions::SIMO_VU_QUOC);
        assert_eq!(SpinUpFlags::DEFAULT.source(), "Simo & Vu-Quoc 1986");
        let kane = SpinUpFlags {
            case: SpinUpCase::Kane,
            ..SpinUpFlags::DEFAULT
        };
        assert_eq!(kane.options(), SpinUpOptions::KANE_RYAN_BANERJEE);
        let edited = SpinUpFlags {
            density: Some(2700.0),
            omega_s: Some(2.0),
            ..kane
        };
        assert_eq!(
            edited.options(),
            SpinUpOptions {
                density: 2700.0,
                omega_s: 2.0,
                ..SpinUpOptions::KANE_RYAN_BANERJEE
            }
        );
        assert_eq!(edited.source(), "Kane, Ryan & Banerjee 1987, edited");
        // the spin-up's numbers are not the beam's: the heading keeps the case's name
        let faster = SpinUpFlags {
            omega_s: Some(2.0),
            ..kane
        };
        assert_eq!(faster.source(), "Kane, Ryan & Banerjee 1987");
    }
}
