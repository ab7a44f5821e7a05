//! Work–precision studies (`flexrig bench`) — run time against error — for the lumped impact,
//! the beam and the rig, as tables, JSON rows and log–log SVG plots. Timings are medians of
//! repeated runs in this process; errors are against independent references (the exact energy
//! solution, the elastica table, a converged run).

use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::time::Instant;

use flexrig_beam::canonical::{self, ELASTICA};
use flexrig_beam::{Kinematics, ModalDirection, StaticOptions, modal_analysis, solve_static};
use flexrig_contact::{Hertz, SeriesCompliance};
use flexrig_lumped::ode::{Formulation, OdeOptions, StopAt, integrate};
use flexrig_lumped::{ImpactModel, peak_exact};
use flexrig_rig::{LinkVariant, NoRecorder, RunOptions, Scene, Simulation};
use serde::Serialize;

use crate::Error;
use crate::log::mcap::{LogRates, McapRecorder};
use crate::plots::{Panel, Series};
use crate::shared::output::ensure_dir;
use crate::testbed::scenes::bundled_scene;

/// One measured point.
#[derive(Debug, Clone, Serialize)]
pub struct Row {
    /// `lumped`, `beam` or `rig`.
    pub model: String,
    /// Method or variant.
    pub method: String,
    /// The setting varied (tolerance, elements, steps).
    pub setting: String,
    /// Error against the reference.
    pub error: f64,
    /// Median run time [s].
    pub seconds: f64,
    /// Right-hand-side evaluations (time integrations only; absent from the JSON otherwise).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub evaluations: Option<usize>,
}

/// Median wall time [s] of `f` over `samples` samples of `reps` calls each.
fn median_seconds<T>(samples: usize, reps: usize, mut f: impl FnMut() -> T) -> f64 {
    let mut times: Vec<f64> = (0..samples)
        .map(|_| {
            let start = Instant::now();
            for _ in 0..reps {
                std::hint::black_box(f());
            }
            start.elapsed().as_secs_f64() / reps as f64
        })
        .collect();
    times.sort_by(f64::total_cmp);
    times[times.len() / 2]
}

/// What the study measured and drew.
#[derive(Debug, Clone, Serialize)]
pub struct BenchReport {
    /// Every measured point.
    pub rows: Vec<Row>,
    /// The plots (bench_lumped.svg, bench_beam.svg, bench_rig.svg).
    pub plots: Vec<PathBuf>,
    /// scipy's DOP853 run time over flexrig's at a peak error ≤ 1e-9; none when the peer could
    /// not run (its interpreter, [`BenchReport::peer_python`], lacks numpy or scipy).
    pub scipy_dop853_over_flexrig_at_1e_9: Option<f64>,
    /// The Python interpreter the scipy peer was run with ([`peer_python`]).
    pub peer_python: String,
}

/// The Python interpreter for the scipy peer: `FLEXRIG_PYTHON`, else the project's virtual
/// environment (`.venv/bin/python`, made with numpy and scipy by `scripts/python-env.sh`), else
/// `python3` on the PATH — the order the tests' independent checks use.
pub fn peer_python() -> String {
    if let Some(p) = std::env::var_os("FLEXRIG_PYTHON").filter(|p| !p.is_empty()) {
        return p.to_string_lossy().into_owned();
    }
    // the project's root written out (the interpreter itself is a link that must stay one: a
    // virtual environment is known by the path it is called by)
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let root = root.canonicalize().unwrap_or_else(|_| root.to_path_buf());
    let venv = root.join(".venv/bin/python");
    if venv.exists() {
        return venv.display().to_string();
    }
    "python3".into()
}

/// Why the scipy peer did not run, for the table and the plot's note: the interpreter it asked
/// and how to give it one with numpy and scipy.
pub fn peer_missing_note(python: &str) -> String {
    format!(
        "scipy peer not run: {python} has no numpy and scipy (bash scripts/python-env.sh makes \
         the project's .venv with them; FLEXRIG_PYTHON names another interpreter)"
    )
}

/// Runs every study (fewer settings and repetitions if `quick`: well under a minute) and draws
/// the plots into `out`.
pub fn run(
    quick: bool,
    out: &Path,
    figures: &crate::plots::FigureOptions,
) -> Result<BenchReport, Error> {
    run_cancellable(quick, out, figures, &crate::CancelToken::new())
}

/// [`run`], stopped between its studies once `cancel` is set (nothing is written then: the
/// plots are drawn at the end).
pub fn run_cancellable(
    quick: bool,
    out: &Path,
    figures: &crate::plots::FigureOptions,
    cancel: &crate::CancelToken,
) -> Result<BenchReport, Error> {
    figures.validate()?;
    let stop = || -> Result<(), Error> {
        if cancel.is_cancelled() {
            return Err(Error::Impact(flexrig_impact::ImpactError::Interrupted));
        }
        Ok(())
    };
    let mut rows = Vec::new();
    lumped(&mut rows, quick)?;
    stop()?;
    let python = peer_python();
    let peer_ratio = peer(&mut rows, quick, &python)?;
    stop()?;
    beam(&mut rows, quick)?;
    stop()?;
    rig(&mut rows, quick, cancel)?;
    stop()?;
    driven(&mut rows, quick)?;
    stop()?;
    safety_maps(&mut rows, quick, cancel)?;
    stop()?;
    ensure_dir(out)?;
    let mut files = Vec::new();
    for (model, title, y_desc, share_y) in PLOTS {
        let stem = format!("bench_{model}");
        let path = out.join(format!("{stem}.svg"));
        let subset: Vec<&Row> = rows.iter().filter(|r| r.model == model).collect();
        let svg = crate::plots::work_precision_svg(
            title,
            y_desc,
            &plot_panels(&subset),
            share_y,
            figures.width_pt(),
        )
        .map_err(|message| Error::Plot { path, message })?;
        files.extend(crate::plots::write_figure(out, &stem, &svg, figures)?);
    }
    Ok(BenchReport {
        rows,
        plots: files,
        scipy_dop853_over_flexrig_at_1e_9: peer_ratio,
        peer_python: python,
    })
}

/// The plots: model, title, y-axis description, whether the panels share the error scale (they
/// do where they compare the same methods).
const PLOTS: [(&str, &str, &str, bool); 3] = [
    (
        "lumped",
        "Work–precision, lumped impact (m_h = 4 kg, n = 1, 2): peak force against the exact solution",
        "relative error of f_max",
        true,
    ),
    (
        "beam",
        "Work–precision, beam: against a converged run or the exact solution",
        "relative error",
        false,
    ),
    (
        "rig",
        "Work–precision, test rig (aluminium operator): peak force against 6400 steps/contact",
        "relative error of the peak force",
        true,
    ),
];

/// Panel title (without its letter) and series label of a row; `None` for a row not plotted
/// (the exact lumped solution, error 0).
fn plot_place(row: &Row) -> Option<(String, String)> {
    let method = row.method.as_str();
    match row.model.as_str() {
        "lumped" => {
            if let Some((solver, _)) = method.split_once(" to the peak") {
                return Some(("Fig. 6 CJ case (n = 2), to the peak".into(), solver.into()));
            }
            let rest = method.strip_prefix("ode ")?;
            let mut words = rest.split_whitespace();
            let (formulation, n, link) = (words.next()?, words.next()?, words.next()?);
            let title = match link {
                "stiff" => "stiff link, k_δ = 10⁸ N/m",
                _ => "soft link, k_δ = 2·10² N/m",
            };
            let label = format!("{formulation} state, {}", n.replace('=', " = "));
            Some((title.into(), label))
        }
        "beam" => {
            let title = if method.starts_with("transient") || method.starts_with("tip step load") {
                "transients: elements × time step"
            } else {
                "modes and statics: elements"
            };
            Some((title.into(), method.into()))
        }
        _ => {
            let (scene, label) = method.split_once(": ")?;
            let design = match scene.split('_').next() {
                Some("cj") => "compliant joint",
                Some("cl") => "compliant link",
                _ => "",
            };
            Some((format!("{design} ({scene})"), label.into()))
        }
    }
}

/// The panels of one model's plot: rows grouped by [`plot_place`], panels lettered in order.
fn plot_panels(rows: &[&Row]) -> Vec<Panel> {
    let mut panels: Vec<Panel> = Vec::new();
    for row in rows {
        let Some((title, label)) = plot_place(row) else {
            continue;
        };
        let index = match panels.iter().position(|p| p.title == title) {
            Some(i) => i,
            None => {
                panels.push(Panel {
                    title,
                    series: Vec::new(),
                    note: None,
                });
                panels.len() - 1
            }
        };
        let panel = &mut panels[index];
        let point = (row.seconds, row.error);
        match panel.series.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push(point),
            None => panel.series.push(Series {
                label,
                points: vec![point],
            }),
        }
    }
    for (i, panel) in panels.iter_mut().enumerate() {
        if panel.title.ends_with("to the peak")
            && !panel.series.iter().any(|s| s.label.starts_with("scipy"))
        {
            panel.note = Some(
                "scipy peer not run (no numpy and scipy in FLEXRIG_PYTHON, the project's .venv \
                 or python3)"
                    .into(),
            );
        }
        panel.title = format!("({}) {}", (b'a' + i as u8) as char, panel.title);
    }
    panels
}

fn lumped(rows: &mut Vec<Row>, quick: bool) -> Result<(), Error> {
    let tolerances: &[f64] = if quick {
        &[1e-6, 1e-9, 1e-12]
    } else {
        &[1e-4, 1e-6, 1e-8, 1e-10, 1e-12]
    };
    let (samples, reps) = if quick { (3, 20) } else { (7, 100) };
    for (link, k_delta) in [("stiff", 1e8), ("soft", 2e2)] {
        for n in [1.0, 2.0] {
            let spring = SeriesCompliance::new(k_delta, Hertz::new(1e8, n)?)?;
            let model = ImpactModel::new(4.0, 10.0 / 3.0 + 0.1, spring, 2.0)?;
            let exact = peak_exact(&model).f_max;
            rows.push(Row {
                model: "lumped".into(),
                method: format!("exact n={n} {link}"),
                setting: "-".into(),
                error: 0.0,
                seconds: median_seconds(samples, reps * 10, || peak_exact(&model)),
                evaluations: None,
            });
            for formulation in [Formulation::Indentation, Formulation::Displacement] {
                for &rtol in tolerances {
                    let options = OdeOptions::new(rtol)?.formulation(formulation);
                    let sol = integrate(&model, &options)?;
                    rows.push(Row {
                        model: "lumped".into(),
                        method: format!("ode {formulation:?} n={n} {link}").to_lowercase(),
                        setting: format!("rtol {rtol:e}"),
                        error: (sol.peak.f_max / exact - 1.0).abs(),
                        seconds: median_seconds(samples, reps, || integrate(&model, &options)),
                        evaluations: Some(sol.rhs_evals),
                    });
                }
            }
        }
    }
    Ok(())
}

/// The paper's Fig. 6 CJ case (m_h = 4 kg, m_eff = 3.433 kg, k_δ = k_c = 1e8, n = 2, v0 = 2 m/s)
/// integrated to the peak by flexrig and, when Python with scipy is present, by
/// `scripts/peer_scipy.py` (solve_ivp DOP853, Radau, LSODA) over the same tolerances, run by the
/// interpreter `python`. Returns the ratio of the fastest DOP853 time to the fastest flexrig time
/// with a peak error ≤ 1e-9.
fn peer(rows: &mut Vec<Row>, quick: bool, python: &str) -> Result<Option<f64>, Error> {
    let spring = SeriesCompliance::new(1e8, Hertz::new(1e8, 2.0)?)?;
    let model = ImpactModel::new(4.0, 10.0 / 3.0 + 0.1, spring, 2.0)?;
    let exact = peak_exact(&model).f_max;
    let rtols = [1e-6, 1e-9, 1e-12];
    let (samples, reps) = if quick { (3, 20) } else { (7, 100) };
    for rtol in rtols {
        let options = OdeOptions::new(rtol)?.stop(StopAt::Peak);
        let sol = integrate(&model, &options)?;
        rows.push(Row {
            model: "lumped".into(),
            method: "flexrig ode to the peak, Fig. 6 CJ n=2".into(),
            setting: format!("rtol {rtol:e}"),
            error: (sol.peak.f_max / exact - 1.0).abs(),
            seconds: median_seconds(samples, reps, || integrate(&model, &options)),
            evaluations: Some(sol.rhs_evals),
        });
    }
    let script = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scripts/peer_scipy.py");
    let mut command = std::process::Command::new(python);
    command.arg(script);
    for v in [4.0, 10.0 / 3.0 + 0.1, 1e8, 1e8, 2.0, 2.0] {
        command.arg(format!("{v:e}"));
    }
    for rtol in rtols {
        command.arg(format!("{rtol:e}"));
    }
    let Ok(output) = command.output() else {
        return Ok(None);
    };
    if !output.status.success() {
        return Ok(None);
    }
    for text in String::from_utf8_lossy(&output.stdout).lines() {
        let Ok(v) = serde_json::from_str::<serde_json::Value>(text) else {
            continue;
        };
        rows.push(Row {
            model: "lumped".into(),
            method: format!(
                "scipy {} to the peak, Fig. 6 CJ n=2",
                v["method"].as_str().unwrap_or("?")
            ),
            setting: format!("rtol {:e}", v["rtol"].as_f64().unwrap_or(f64::NAN)),
            error: v["error"].as_f64().unwrap_or(f64::NAN),
            seconds: v["seconds"].as_f64().unwrap_or(f64::NAN),
            evaluations: v["nfev"].as_u64().map(|n| n as usize),
        });
    }
    let fastest = |prefix: &str| {
        rows.iter()
            .filter(|r| r.method.starts_with(prefix) && r.error <= 1e-9)
            .map(|r| r.seconds)
            .fold(f64::INFINITY, f64::min)
    };
    let ratio = fastest("scipy DOP853") / fastest("flexrig ode to the peak");
    Ok(ratio.is_finite().then_some(ratio))
}

/// Tip displacement [m] at t = 0.3 s of the unit cantilever (corotational, `elements`) released
/// from rest under a suddenly applied tip force 0.5 EI/L², stepped by generalized-α (ρ∞ = 0.9)
/// with step `h` (the first bending period is 1.79 s).
fn beam_transient(elements: usize, h: f64) -> Result<f64, Error> {
    let model = canonical::unit_cantilever(elements, flexrig_beam::Kinematics::Corotational)?;
    let mut loads = flexrig_beam::NodalLoads::zeros(&model);
    loads.set_force(model.tip_node(), 0.0, 0.5)?;
    let mut state = flexrig_beam::State::at_rest(&model, &loads)?;
    let mut workspace = flexrig_beam::Workspace::new(&model);
    let integrator = flexrig_beam::GeneralizedAlpha::new(0.9)?;
    let steps = (0.3 / h).round() as usize;
    for _ in 0..steps {
        integrator.step(&model, &mut state, &mut workspace, h, &loads)?;
    }
    Ok(state.q[3 * model.tip_node() + 1])
}

fn beam(rows: &mut Vec<Row>, quick: bool) -> Result<(), Error> {
    // Transient: elements × time step against a converged run (64 elements, h = 1.25e-4 s).
    let reference = beam_transient(64, 1.25e-4)?;
    let (meshes, steps): (&[usize], &[f64]) = if quick {
        (&[8, 16], &[1e-2, 2.5e-3])
    } else {
        (&[8, 16, 32], &[1e-2, 5e-3, 2.5e-3, 1.25e-3])
    };
    for &n in meshes {
        for &h in steps {
            // A step too large for Newton (unresolved stiff axial modes) leaves no row.
            let v = match beam_transient(n, h) {
                Ok(v) => v,
                Err(Error::Beam(flexrig_beam::BeamError::NotConverged { .. })) => continue,
                Err(e) => return Err(e),
            };
            rows.push(Row {
                model: "beam".into(),
                method: format!("transient, {n} corotational elements"),
                setting: format!("h {h:e} s"),
                error: (v / reference - 1.0).abs(),
                seconds: median_seconds(3, 1, || beam_transient(n, h)),
                evaluations: None,
            });
        }
    }
    polypropylene_transient(rows, quick)?;
    let elements: &[usize] = if quick {
        &[4, 8, 16]
    } else {
        &[4, 8, 16, 32, 64]
    };
    // Frequencies: ω₁–₄ of the unit cantilever against (βᵢL)² (Euler–Bernoulli), consistent mass.
    for &n in elements {
        let model = canonical::unit_cantilever(n, flexrig_beam::Kinematics::Linear)?;
        let modes = || modal_analysis(&model, 4, ModalDirection::Transverse);
        let omegas = modes()?.omegas;
        let error = canonical::CANTILEVER_BETA_L
            .iter()
            .zip(&omegas)
            .map(|(beta_l, w)| (w / canonical::beam_omega(*beta_l, 1.0, 1.0, 1.0) - 1.0).abs())
            .fold(0.0, f64::max);
        rows.push(Row {
            model: "beam".into(),
            method: "frequencies ω₁–₄ (max error), consistent mass".into(),
            setting: format!("{n} elements"),
            error,
            seconds: median_seconds(if quick { 3 } else { 5 }, 3, modes),
            evaluations: None,
        });
    }
    // The elastica: 10 fixed load steps, and adaptive ones from the full load (the same
    // equilibrium in fewer Newton iterations), corotational and ANCF.
    let (load, v_over_l, _, _) = ELASTICA[2];
    let fixed = StaticOptions::new(10, 50, 1e-10)?;
    let adaptive = StaticOptions::new(1, 50, 1e-10)?.with_adaptive_steps();
    let cases = [
        (
            Kinematics::Corotational,
            fixed,
            "elastica PL²/EI=5, corotational",
        ),
        (
            Kinematics::Corotational,
            adaptive,
            "elastica PL²/EI=5, corotational, adaptive load steps",
        ),
        (
            Kinematics::Ancf,
            adaptive,
            "elastica PL²/EI=5, ANCF, adaptive load steps",
        ),
    ];
    for (kinematics, options, method) in cases {
        for &n in elements {
            let (model, loads) = canonical::elastica_problem_with(kinematics, load, n)?;
            let s = solve_static(&model, &loads, &options)?;
            rows.push(Row {
                model: "beam".into(),
                method: method.into(),
                setting: format!("{n} elements"),
                error: (s.node(model.tip_node()).1 / v_over_l - 1.0).abs(),
                seconds: median_seconds(if quick { 3 } else { 5 }, 3, || {
                    solve_static(&model, &loads, &options)
                }),
                evaluations: None,
            });
        }
    }
    Ok(())
}

/// The polypropylene cantilever's work–precision problem (the Exudyn comparison of
/// docs/performance-beam.md): the 0.3 m cantilever under a step tip load EI/L² from rest, 1000 generalized-α steps of 1 ms at
/// ρ∞ = 0.9. Error: max over t = 1 … 1000 ms of |v − v_ref| / max |v_ref| of the tip deflection,
/// against 16 ANCF elements at h = 0.25 and 0.125 ms extrapolated to h → 0 (the error is first
/// order in h: the step load excites modes no step resolves; the extrapolated reference is good
/// to about 1e-5, docs/performance-beam.md).
fn polypropylene_transient(rows: &mut Vec<Row>, quick: bool) -> Result<(), Error> {
    use flexrig_beam::{GeneralizedAlpha, Kinematics};
    let ga = GeneralizedAlpha::new(0.9)?;
    let trajectory = |kin, elements, h| {
        canonical::polypropylene_step_load(elements, kin, &ga, h, 1.0, 1e-3).map(|(v, _)| v)
    };
    let coarse = trajectory(Kinematics::Ancf, 16, 2.5e-4)?;
    let fine = trajectory(Kinematics::Ancf, 16, 1.25e-4)?;
    let reference: Vec<f64> = fine.iter().zip(&coarse).map(|(f, c)| 2.0 * f - c).collect();
    let scale = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let cases: &[(Kinematics, &str, usize)] = if quick {
        &[
            (Kinematics::Ancf, "ANCF", 4),
            (Kinematics::Corotational, "corotational", 8),
        ]
    } else {
        &[
            (Kinematics::Ancf, "ANCF", 4),
            (Kinematics::Ancf, "ANCF", 8),
            (Kinematics::Ancf, "ANCF", 32),
            (Kinematics::Corotational, "corotational", 8),
            (Kinematics::Corotational, "corotational", 32),
        ]
    };
    for &(kin, name, elements) in cases {
        let v = trajectory(kin, elements, 1e-3)?;
        let error = v
            .iter()
            .zip(&reference)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()))
            / scale;
        rows.push(Row {
            model: "beam".into(),
            method: format!("tip step load P = EI/L², 1000 steps of 1 ms, ρ∞ 0.9, {name}"),
            setting: format!("{elements} elements"),
            error,
            seconds: median_seconds(3, 1, || trajectory(kin, elements, 1e-3)),
            evaluations: None,
        });
    }
    Ok(())
}

/// A bundled scene with owned replacement texts (see [`bundled_scene`]).
fn scene(name: &str, edits: &[(&str, String)]) -> Result<Scene, Error> {
    let edits: Vec<(&str, &str)> = edits.iter().map(|(a, b)| (*a, b.as_str())).collect();
    bundled_scene(name, &edits)
}

/// A CJ built from the FE beam (EI, EA × 1e4, pinned on the torsion spring): what the Rapier
/// rigid link saves.
const STIFF_FE_CJ: RunOptions = RunOptions {
    cl_link: LinkVariant::StiffOnTorsionSpring {
        stiffness_factor: 1e4,
    },
    ..RunOptions::DEFAULT
};

/// A rig bench variant: label, scene text edits, a suffix for the solver line, run options.
type RigVariant = (
    &'static str,
    Vec<(&'static str, String)>,
    &'static str,
    RunOptions,
);

/// A run as `flexrig run` makes it: lean sampling (the samples nobody reads not computed).
fn run_scene(s: &Scene, options: RunOptions) -> Result<flexrig_rig::RunSummary, Error> {
    Ok(Simulation::new(s, options)?
        .with_lean_samples()
        .run(&mut NoRecorder)?)
}

/// A run that computes every sensor sample (what every run did before lean sampling).
fn run_scene_full(s: &Scene, options: RunOptions) -> Result<flexrig_rig::RunSummary, Error> {
    Ok(Simulation::new(s, options)?.run(&mut NoRecorder)?)
}

/// The setting of a bundled scene's row: its contact integration (the adaptive contact or
/// Rapier's steps per contact).
fn bundled_setting(run: &flexrig_rig::RunSummary) -> String {
    if run.contact_integration.is_adaptive() {
        "bundled (adaptive contact)".into()
    } else {
        "bundled (800 steps/contact)".into()
    }
}

/// Release → separation with the MCAP recorder writing to memory at `rates`: (summary, bytes).
fn run_logged(s: &Scene, rates: LogRates) -> Result<(flexrig_rig::RunSummary, usize), Error> {
    let mut log = McapRecorder::new(Cursor::new(Vec::new()), s, "")
        .map_err(|e| Error::Plot {
            path: "memory".into(),
            message: e.to_string(),
        })?
        .with_rates(rates);
    let summary = Simulation::new(s, RunOptions::default())?
        .with_lean_samples()
        .run(&mut log)?;
    let bytes = log.finish_into_inner().map_err(|e| Error::Plot {
        path: "memory".into(),
        message: e.to_string(),
    })?;
    Ok((summary, bytes.into_inner().len()))
}

fn rig(rows: &mut Vec<Row>, quick: bool, cancel: &crate::CancelToken) -> Result<(), Error> {
    let steps: &[usize] = if quick {
        &[50, 200, 800]
    } else {
        &[25, 50, 100, 200, 400, 800, 1600]
    };
    let samples = if quick { 3 } else { 5 };
    let modal = "\nbeam = { model = \"modal\", modes = 8 }";
    for name in ["cj_aluminium", "cl_aluminium"] {
        let reference = run_scene(
            &scene(
                name,
                &[(
                    "contact_steps = 800",
                    "contact_steps = 6400\ncontact = \"fixed\"".into(),
                )],
            )?,
            RunOptions::default(),
        )?
        .peak_force_n;
        let cl = name.starts_with("cl");
        for &n in steps {
            if cancel.is_cancelled() {
                return Err(Error::Impact(flexrig_impact::ImpactError::Interrupted));
            }
            let from_contact = ("from = \"release\"", "from = \"contact\"".to_string());
            let to_peak = ("at = \"separation\"", "at = \"peak\"".to_string());
            let slow_sensors = (
                "sample_rate_hz = 50000.0",
                "sample_rate_hz = 1.0".to_string(),
            );
            // (label, edits, solver line suffix, options)
            let mut variants: Vec<RigVariant> = vec![
                ("release to separation", vec![], "", RunOptions::DEFAULT),
                (
                    "release to separation, sensors at 1 Hz",
                    vec![slow_sensors.clone()],
                    "",
                    RunOptions::DEFAULT,
                ),
                (
                    "start at contact",
                    vec![from_contact.clone()],
                    "",
                    RunOptions::DEFAULT,
                ),
                (
                    "start at contact, stop at peak",
                    vec![from_contact.clone(), to_peak.clone()],
                    "",
                    RunOptions::DEFAULT,
                ),
            ];
            if cl {
                variants.push((
                    "release to separation, modal beam (8 modes)",
                    vec![],
                    modal,
                    RunOptions::DEFAULT,
                ));
                variants.push((
                    "start at contact, stop at peak, modal beam (8 modes)",
                    vec![from_contact.clone(), to_peak.clone()],
                    modal,
                    RunOptions::DEFAULT,
                ));
            } else {
                variants.push((
                    "release to separation, as a stiff FE beam (no rigid-link shortcut)",
                    vec![("design = \"cj\"", "design = \"cl\"".into())],
                    "",
                    STIFF_FE_CJ,
                ));
            }
            for (label, mut edits, suffix, options) in variants {
                edits.push((
                    "contact_steps = 800",
                    format!("contact_steps = {n}\ncontact = \"fixed\"{suffix}"),
                ));
                let s = scene(name, &edits)?;
                // Too coarse a contact step is caught by the energy check: no row for it. Any
                // other error is a defect of the bench and is reported.
                let result = match run_scene(&s, options) {
                    Ok(result) => result,
                    Err(Error::Rig(flexrig_rig::RigError::Unstable { .. })) => continue,
                    Err(e) => return Err(e),
                };
                // The swing from release adds its own (tiny) impact-speed error; the shortcuts are
                // compared with the same converged release run.
                rows.push(Row {
                    model: "rig".into(),
                    method: format!("{name}: {label}"),
                    setting: format!("{n} steps/contact"),
                    error: (result.peak_force_n / reference - 1.0).abs(),
                    seconds: median_seconds(samples, 1, || run_scene(&s, options)),
                    evaluations: None,
                });
            }
        }
        // The CJ's contact integrated adaptively (DOP853 on the two hinges, Rapier not stepped),
        // at the bundled 50 kHz sensors and at 1 Hz.
        if !cl {
            let tolerances: &[f64] = if quick {
                &[1e-4, 1e-8]
            } else {
                &[1e-4, 1e-6, 1e-8, 1e-10]
            };
            for &rtol in tolerances {
                for (label, rate) in [("", "50000.0"), (", sensors at 1 Hz", "1.0")] {
                    let s = scene(
                        name,
                        &[
                            (
                                "contact_steps = 800",
                                format!(
                                    "contact_steps = 800\ncontact = \"adaptive\"\n\
                                     contact_rtol = {rtol:e}"
                                ),
                            ),
                            (
                                "sample_rate_hz = 50000.0",
                                format!("sample_rate_hz = {rate}"),
                            ),
                        ],
                    )?;
                    let result = run_scene(&s, RunOptions::DEFAULT)?;
                    rows.push(Row {
                        model: "rig".into(),
                        method: format!("{name}: release to separation, adaptive contact{label}"),
                        setting: format!("rtol {rtol:e}"),
                        error: (result.peak_force_n / reference - 1.0).abs(),
                        seconds: median_seconds(samples, 1, || run_scene(&s, RunOptions::DEFAULT)),
                        evaluations: None,
                    });
                }
            }
        }
        // The bundled scene with every sensor sample computed (before lean sampling).
        let s = scene(name, &[])?;
        let full = run_scene_full(&s, RunOptions::DEFAULT)?;
        let bundled = bundled_setting(&full);
        rows.push(Row {
            model: "rig".into(),
            method: format!("{name}: release to separation, every sensor sample computed"),
            setting: bundled.clone(),
            error: (full.peak_force_n / reference - 1.0).abs(),
            seconds: median_seconds(samples, 1, || run_scene_full(&s, RunOptions::DEFAULT)),
            evaluations: None,
        });
        // Logging: decimated outside contact (the default) against every step.
        for (label, rates) in [
            ("decimated outside contact", LogRates::DECIMATED),
            ("every step", LogRates::EVERY_STEP),
        ] {
            let (summary, bytes) = run_logged(&s, rates)?;
            rows.push(Row {
                model: "rig".into(),
                method: format!(
                    "{name}: release to separation, MCAP log {label} ({:.2} MB)",
                    bytes as f64 / 1e6
                ),
                setting: bundled.clone(),
                error: (summary.peak_force_n / reference - 1.0).abs(),
                seconds: median_seconds(samples, 1, || run_logged(&s, rates)),
                evaluations: None,
            });
        }
    }
    Ok(())
}

/// A driven CL strike (assets/drives/cl_free_head.toml: PD ramp to 2 rad/s, contact 0.3 s after,
/// stiff link, free 4 kg head), from the drive's start to the separation: the exact link (the
/// default model) at its default settings (the mesh check included) and fast settings, error of
/// the peak against the exact link on 2× the checked mesh with 4× the steps (docs/driven.md:
/// converged to ≤ 2e-6 there); the linear option at tol 1e-6 against the same reference (its
/// model error). Model `driven`: in the table and JSON, not plotted.
fn driven(rows: &mut Vec<Row>, quick: bool) -> Result<(), Error> {
    use flexrig_impact::driven_cl::{ClDriveSettings, run_driven_cl};
    use flexrig_impact::exact_link::{ExactSettings, run_exact_cl, run_exact_cl_meshed};
    let description = crate::driven::strike::StrikeDescription::parse(
        include_str!("../../../../assets/drives/cl_free_head.toml"),
        "assets/drives/cl_free_head.toml",
    )?;
    let strike = description.strike();
    let default = ExactSettings {
        dome: description.dome,
        ..ExactSettings::DEFAULT
    };
    let (_, elements) = run_exact_cl_meshed(&strike, &default)?;
    let fine = ExactSettings {
        elements: 2 * elements,
        approach_steps: 4 * default.approach_steps,
        contact_steps: 4 * default.contact_steps,
        mesh_tolerance: None,
        ..default
    };
    let reference = run_exact_cl(&strike, &fine)?.contact.peak_force_n;
    let samples = if quick { 3 } else { 5 };
    let fast = ExactSettings {
        dome: description.dome,
        ..ExactSettings::FAST
    };
    for (label, settings) in [
        ("default (mesh checked)", default),
        ("fast (8 elements)", fast),
    ] {
        let outcome = run_exact_cl(&strike, &settings)?;
        rows.push(Row {
            model: "driven".into(),
            method: "driven CL strike, exact link (cl_free_head.toml), drive start to separation"
                .into(),
            setting: label.into(),
            error: (outcome.contact.peak_force_n - reference).abs() / reference,
            seconds: median_seconds(samples, 1, || run_exact_cl(&strike, &settings)),
            evaluations: Some(outcome.work),
        });
    }
    let settings = ClDriveSettings::DEFAULT;
    let outcome = run_driven_cl(&strike, &settings)?;
    rows.push(Row {
        model: "driven".into(),
        method: "driven CL strike, linear option (cl_free_head.toml), drive start to separation"
            .into(),
        setting: "tol 1e-6, approach 1e-5".into(),
        error: (outcome.contact.peak_force_n - reference).abs() / reference,
        seconds: median_seconds(samples, 1, || run_driven_cl(&strike, &settings)),
        evaluations: Some(outcome.work),
    });
    driven_test_bed(rows, quick)
}

/// The driven CL in the test bed (`rig_driven_cl`: PD ramp over 1.5 s bending the corotational
/// link, 0.2 s of settling, contact with the hanging block), from the drive's start to the
/// separation; error of the peak against the same run with the swing step and the contact's
/// step quartered (docs/scenes.md: converged to 2.2e-6 at the default). Model `driven`.
fn driven_test_bed(rows: &mut Vec<Row>, quick: bool) -> Result<(), Error> {
    let refine = |k: u32| {
        vec![
            (
                "swing_step_s = 6e-4",
                format!("swing_step_s = {:e}", 6e-4 / f64::from(k)),
            ),
            (
                "contact_steps = 800",
                format!("contact_steps = {}", 800 * k),
            ),
        ]
    };
    let reference =
        run_scene(&scene("rig_driven_cl", &refine(4))?, RunOptions::DEFAULT)?.peak_force_n;
    let levels: &[u32] = if quick { &[1] } else { &[1, 2] };
    for &k in levels {
        let s = scene("rig_driven_cl", &refine(k))?;
        let result = run_scene(&s, RunOptions::DEFAULT)?;
        rows.push(Row {
            model: "driven".into(),
            method: "rig_driven_cl (test bed, CL on a PD-driven hub), drive start to separation"
                .into(),
            setting: format!(
                "swing step {:.2e} s, {} steps/contact",
                6e-4 / f64::from(k),
                800 * k
            ),
            error: (result.peak_force_n / reference - 1.0).abs(),
            seconds: median_seconds(if quick { 3 } else { 5 }, 1, || {
                run_scene(&s, RunOptions::DEFAULT)
            }),
            evaluations: Some(result.steps),
        });
    }
    Ok(())
}

/// The 30 × 30 safe-speed maps of the hand (transient, skinned aluminium, m_r = 51 g, payload
/// 0.01–5 kg × k_δ = 10–1e7 N/m), CJ and CL: by the lumped energy method (error: the largest
/// relative difference of a cell from the single-point `safety` answer, which must be 0) and by
/// simulation (FE CJ and modal CL; error: the largest relative difference of the four corner
/// cells from a map at modal tol 1e-8 and root tolerance 1e-10). Model `safety`: in the table
/// and JSON, not plotted.
fn safety_maps(rows: &mut Vec<Row>, quick: bool, cancel: &crate::CancelToken) -> Result<(), Error> {
    use crate::safety::map::{
        GAMMA_CJ, MapMethod, SafetyMapInput, SimulationSettings, parse_axis, safety_map,
    };
    let model = flexrig_safety::BodyModel::iso_ts_15066_2016()?;
    let points = if quick { 10 } else { 30 };
    let input = |method: MapMethod, points: usize| -> Result<SafetyMapInput, Error> {
        Ok(SafetyMapInput {
            region: "hands_and_fingers".into(),
            area: None,
            contact: flexrig_safety::ContactKind::Transient,
            m_r: Some(0.051),
            m_e: None,
            k_delta: None,
            law: crate::safety::point::ContactLaw::Material("skinned_aluminium".into()),
            area_model: None,
            x: parse_axis("--x", &format!("m-e=0.01:5:{points}:log"))?,
            y: parse_axis("--y", &format!("k-delta=10:1e7:{points}:log"))?,
            method,
            simulation: SimulationSettings::DEFAULT,
            speed: None,
        })
    };
    let lumped = input(MapMethod::Energy, points)?;
    let map = safety_map(&lumped, Some(&model), cancel)?;
    let mut error = 0.0_f64;
    for c in map.cells.iter().step_by(7) {
        let single = crate::safety::point::safety(
            &crate::safety::point::SafetyInput {
                region: lumped.region.clone(),
                area: None,
                contact: lumped.contact,
                m_eff: Some(crate::safety::point::RobotEffectiveMass::Prb {
                    gamma: GAMMA_CJ,
                    m_r: c.m_r_kg,
                    m_e: c.m_e_kg,
                }),
                k_delta: c.k_delta_n_per_m,
                law: lumped.law.clone(),
                area_model: None,
                moving_mass: None,
                payload: 0.0,
                speed: None,
                methods: vec![crate::safety::point::SafetyMethod::Energy],
                link: None,
                simulation: None,
                scene: None,
            },
            Some(&model),
        )?;
        let (a, b) = (
            c.cj.map_or(f64::NAN, |d| d.v_max_mps.value()),
            single.methods[0].v_max_mps.value(),
        );
        error = error.max(((a - b) / b).abs());
    }
    rows.push(Row {
        model: "safety".into(),
        method: format!("safety map {points} × {points}, lumped energy method, CJ and CL"),
        setting: "exact (closed form)".into(),
        error,
        seconds: median_seconds(if quick { 3 } else { 5 }, 1, || {
            safety_map(&lumped, Some(&model), cancel)
        }),
        evaluations: None,
    });
    let simulated = input(MapMethod::Simulation, points)?;
    let start = Instant::now();
    let map = safety_map(&simulated, Some(&model), cancel)?;
    let seconds = start.elapsed().as_secs_f64();
    let mut corners = input(MapMethod::Simulation, 2)?;
    corners.simulation = SimulationSettings {
        tol: 1e-8,
        root_rtol: 1e-10,
        ..SimulationSettings::DEFAULT
    };
    let fine = safety_map(&corners, Some(&model), cancel)?;
    let n = points;
    let mut error = 0.0_f64;
    for (i, &at) in [0, n - 1, n * (n - 1), n * n - 1].iter().enumerate() {
        let (c, f) = (&map.cells[at], &fine.cells[i]);
        for (a, b) in [(c.cj, f.cj), (c.cl, f.cl)] {
            let (a, b) = (
                a.map_or(f64::NAN, |d| d.v_max_mps.value()),
                b.map_or(f64::NAN, |d| d.v_max_mps.value()),
            );
            error = error.max(((a - b) / b).abs());
        }
    }
    let runs: usize = map
        .cells
        .iter()
        .flat_map(|c| [c.cj, c.cl])
        .flatten()
        .filter_map(|d| d.runs)
        .sum();
    rows.push(Row {
        model: "safety".into(),
        method: format!(
            "safety map {points} × {points}, simulation (FE CJ, modal CL, joint held), rayon on the machine's cores"
        ),
        setting: "modal tol 1e-6, CJ rtol 1e-10, root 1e-6".into(),
        error,
        seconds,
        evaluations: Some(runs),
    });
    Ok(())
}
