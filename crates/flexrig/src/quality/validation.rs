//! The verification suite behind `flexrig validate`: every case computes a value with flexrig and
//! compares it with an independent reference (analytic solution, published table, converged
//! solution of another method, conservation law), with a stated tolerance. The references come
//! from the canonical problems of the crates (`flexrig_lumped::samples`,
//! `flexrig_beam::canonical`) and `docs/references.md`.

use flexrig_beam::canonical::{self, CANTILEVER_BETA_L, ELASTICA, TIP_MASS_BETA1};
use flexrig_beam::prb::{ErrorMeasure, default_load_indices, fit_prb, trace_tip_path};
use flexrig_beam::{Kinematics, ModalDirection, StaticOptions, modal_analysis, solve_static};
use flexrig_contact::tolerance::relative_error;
use flexrig_lumped::ode::{OdeOptions, integrate};
use flexrig_lumped::{peak_analytic, peak_exact, samples};
use flexrig_rig::canonical::{compound_pendulum_period, simulated_pendulum};
use flexrig_rig::{NoRecorder, RunOptions, Scene, Simulation};
use serde::Serialize;
use std::path::{Path, PathBuf};

use crate::Error;
use crate::shared::output::{ensure_dir, write_atomic};
use crate::testbed::scenes::bundled_scene;

/// How a case's error is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ErrorKind {
    /// |value − reference| / |reference|.
    Relative,
    /// |value − reference|.
    Absolute,
}

/// One verification case and its outcome.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Case {
    /// Case name, `area.what`.
    pub name: String,
    /// Reference value.
    pub reference: f64,
    /// Where the reference comes from.
    pub source: String,
    /// Computed value.
    pub value: f64,
    /// Error (relative or absolute, see `kind`).
    pub error: f64,
    /// Largest error accepted.
    pub tolerance: f64,
    /// Error measure.
    pub kind: ErrorKind,
    /// error ≤ tolerance and the value is finite.
    pub pass: bool,
}

impl Case {
    /// Compares `value` with `reference`.
    pub fn new(
        name: &str,
        value: f64,
        reference: f64,
        source: &str,
        tolerance: f64,
        kind: ErrorKind,
    ) -> Self {
        let error = match kind {
            ErrorKind::Relative => relative_error(value, reference, f64::MIN_POSITIVE),
            ErrorKind::Absolute => (value - reference).abs(),
        };
        Case {
            name: name.into(),
            reference,
            source: source.into(),
            value,
            error,
            tolerance,
            kind,
            pass: value.is_finite() && error <= tolerance,
        }
    }
}

fn rel(name: &str, value: f64, reference: f64, source: &str, tolerance: f64) -> Case {
    Case::new(
        name,
        value,
        reference,
        source,
        tolerance,
        ErrorKind::Relative,
    )
}

fn abs(name: &str, value: f64, reference: f64, source: &str, tolerance: f64) -> Case {
    Case::new(
        name,
        value,
        reference,
        source,
        tolerance,
        ErrorKind::Absolute,
    )
}

/// Runs every case; `quick` skips the slowest (the PRB path and the rig convergence study).
pub fn suite(quick: bool) -> Result<Vec<Case>, Error> {
    let mut cases = Vec::new();
    lumped_cases(&mut cases)?;
    beam_cases(&mut cases, quick)?;
    rig_cases(&mut cases, quick)?;
    Ok(cases)
}

fn lumped_cases(cases: &mut Vec<Case>) -> Result<(), Error> {
    for r in samples::peak_references()? {
        cases.push(rel(
            &format!("lumped.exact {}", r.name),
            peak_exact(&r.model).f_max,
            r.f_max,
            r.source,
            r.reference_accuracy,
        ));
        let ode = integrate(&r.model, &OdeOptions::new(1e-12)?)?;
        cases.push(rel(
            &format!("lumped.ode {}", r.name),
            ode.peak.f_max,
            r.f_max,
            r.source,
            1e-9,
        ));
        if r.model.spring().contact().n() == 1.0 {
            let a = peak_analytic(&r.model)?;
            cases.push(rel(
                &format!("lumped.exact vs Eq. 13 {}", r.name),
                peak_exact(&r.model).f_max,
                a.peak.f_max,
                "paper Eq. 13 (closed form)",
                1e-12,
            ));
            cases.push(rel(
                &format!("lumped.ode contact duration {}", r.name),
                ode.contact_duration.unwrap_or(f64::NAN),
                a.contact_duration,
                "half period π√(μ/k_o)",
                1e-9,
            ));
        }
    }
    for (i, (model, reference)) in samples::high_precision_peaks()?.into_iter().enumerate() {
        let n = model.spring().contact().n();
        cases.push(rel(
            &format!("lumped.exact mpmath case {i} (n = {n})"),
            peak_exact(&model).f_max,
            reference,
            "scripts/reference_exact.py (mpmath, 50 digits, quadrature + findroot)",
            1e-12,
        ));
    }
    for r in samples::eta_references() {
        cases.push(abs(
            &format!("fig6.eta(2/3) m_h = {} n = {}", r.case.m_h, r.n),
            r.case.eta(r.n, 2.0 / 3.0)?,
            r.eta,
            r.source,
            r.reference_accuracy,
        ));
    }
    Ok(())
}

fn beam_cases(cases: &mut Vec<Case>, quick: bool) -> Result<(), Error> {
    let section = canonical::unit_section();
    for elements in [16, 32] {
        let model = canonical::unit_cantilever(elements, Kinematics::Linear)?;
        let modal = modal_analysis(&model, 4, ModalDirection::Transverse)?;
        let tol = if elements == 16 { 2e-4 } else { 1e-5 };
        for (k, beta) in CANTILEVER_BETA_L.iter().enumerate() {
            let reference = canonical::beam_omega(*beta, section.ei(), section.rho_a(), 1.0);
            cases.push(rel(
                &format!("beam.cantilever ω{} ({elements} elements)", k + 1),
                modal.omegas[k],
                reference,
                "roots of 1 + cos βL cosh βL = 0 (references.md)",
                tol,
            ));
        }
    }
    for (mu, beta) in TIP_MASS_BETA1 {
        if mu != 1.0 && quick {
            continue;
        }
        let model = canonical::unit_cantilever_with_tip_mass(32, mu)?;
        let modal = modal_analysis(&model, 1, ModalDirection::Transverse)?;
        cases.push(rel(
            &format!("beam.tip mass μ = {mu}: ω₁"),
            modal.omegas[0],
            canonical::beam_omega(beta, section.ei(), section.rho_a(), 1.0),
            "tip-mass frequency equation (references.md)",
            1e-4,
        ));
    }
    // Modal reduction: one mode plus the tip correction shape gives the exact static tip
    // deflection, Σ φᵢ(tip)² P/ωᵢ² = PL³/3EI.
    let model = canonical::unit_cantilever(16, Kinematics::Linear)?;
    let tip_v = 3 * model.tip_node() + 1;
    let reduced = flexrig_beam::ReducedModel::new(&model, 1, &[tip_v])?;
    let static_tip: f64 = (0..reduced.n_coordinates())
        .map(|i| (reduced.shape(i)[tip_v] / reduced.omegas()[i]).powi(2))
        .sum();
    cases.push(rel(
        "beam.modal reduction (1 mode + correction): static tip deflection",
        static_tip,
        1.0 / 3.0,
        "PL³/3EI (Euler–Bernoulli)",
        1e-10,
    ));
    // Linear statics: tip deflection PL³/3EI under a tip force, ML²/2EI under a tip moment.
    let linear = canonical::unit_cantilever(8, Kinematics::Linear)?;
    let tip = linear.tip_node();
    let mut loads = flexrig_beam::NodalLoads::zeros(&linear);
    loads.set_force(tip, 0.0, 1e-3)?;
    let s = solve_static(&linear, &loads, &StaticOptions::new(1, 5, 1e-12)?)?;
    cases.push(rel(
        "beam.linear tip deflection PL³/3EI",
        s.q[3 * tip + 1],
        1e-3 / (3.0 * section.ei()),
        "Euler–Bernoulli closed form",
        1e-12,
    ));
    let mut loads = flexrig_beam::NodalLoads::zeros(&linear);
    loads.set_moment(tip, 1e-3)?;
    let s = solve_static(&linear, &loads, &StaticOptions::new(1, 5, 1e-12)?)?;
    cases.push(rel(
        "beam.linear tip deflection ML²/2EI",
        s.q[3 * tip + 1],
        1e-3 / (2.0 * section.ei()),
        "Euler–Bernoulli closed form",
        1e-12,
    ));
    // A tip moment 2πEI/L rolls the corotational beam into a full circle: the tip returns to the
    // root (u = −L, v = 0).
    let (model, _) = canonical::elastica_problem(1.0, 32)?;
    let mut loads = flexrig_beam::NodalLoads::zeros(&model);
    loads.set_moment(model.tip_node(), 2.0 * std::f64::consts::PI * section.ei())?;
    let s = solve_static(&model, &loads, &StaticOptions::new(40, 50, 1e-10)?)?;
    let t = 3 * model.tip_node();
    let gap = ((1.0 + s.q[t]).powi(2) + s.q[t + 1].powi(2)).sqrt();
    cases.push(abs(
        "beam.full-circle roll-up: tip to root distance / L",
        gap,
        0.0,
        "M = 2πEI/L closes the circle (references.md)",
        2e-3,
    ));
    cases.push(rel(
        "beam.full-circle roll-up: tip rotation",
        s.q[t + 2],
        2.0 * std::f64::consts::PI,
        "uniform curvature φ = ML/EI = 2π",
        1e-9,
    ));
    let options = StaticOptions::new(20, 50, 1e-10)?;
    for (load, v_over_l, _, _) in ELASTICA {
        let (model, loads) = canonical::elastica_problem(load, 32)?;
        let s = solve_static(&model, &loads, &options)?;
        cases.push(rel(
            &format!("beam.elastica PL²/EI = {load}: v/L (32 elements)"),
            s.q[3 * model.tip_node() + 1],
            v_over_l,
            "elliptic integrals (references.md)",
            5e-4,
        ));
    }
    if !quick {
        let path = trace_tip_path(32, &default_load_indices())?;
        let fit = fit_prb(&path, ErrorMeasure::Deflection)?;
        cases.push(abs(
            "prb.gamma (Howell's error measure)",
            fit.gamma,
            canonical::HOWELL_GAMMA,
            "Howell 2001: γ = 0.8517",
            2e-3,
        ));
        cases.push(abs(
            "prb.K_Theta (least squares)",
            fit.k_theta,
            canonical::HOWELL_K_THETA,
            "Howell 2001: 2.67617; an independent least-squares fit gives ≈ 2.70 (references.md)",
            0.03,
        ));
        cases.push(abs(
            "prb.theta_max [deg]",
            fit.theta_max_deg,
            canonical::HOWELL_THETA_MAX_DEG,
            "Howell 2001: Θ_max ≈ 64.3°",
            0.5,
        ));
        cases.push(abs(
            "prb.small-deflection gamma",
            fit.gamma_small,
            canonical::PAPER_GAMMA_SMALL,
            "PL³/3EI and slope: γ = 2/3",
            1e-3,
        ));
    }
    Ok(())
}

fn rig_cases(cases: &mut Vec<Case>, quick: bool) -> Result<(), Error> {
    let run = |scene: &Scene, options: RunOptions| -> Result<flexrig_rig::RunSummary, Error> {
        Ok(Simulation::new(scene, options)?.run(&mut NoRecorder)?)
    };
    // The operator pendulum alone against the elliptic-integral period (default swing step).
    let scene = bundled_scene("cj_aluminium", &[])?;
    let g = flexrig_rig::geometry::RigGeometry::of(&scene);
    let op = g.operator;
    let theta0 = 30f64.to_radians();
    let (period, _) = simulated_pendulum(&op, 9.81, theta0, scene.file.solver.swing_step_s, 10);
    cases.push(rel(
        "rig.pendulum period (30°, dt = 5e-4 s)",
        period,
        compound_pendulum_period(&op, 9.81, theta0),
        "T = 4√(J/(M g l_c)) K(sin(θ₀/2)) (references.md)",
        1e-6,
    ));
    // Point-like contact: the rig against the lumped model with the same effective masses.
    let point = [
        ("from = \"release\"", "from = \"contact\""),
        ("contact_steps = 800", "contact_steps = 3200"),
        ("dome_radius_m = 0.0715", "dome_radius_m = 0.002"),
        ("dome_standoff_m = 0.030", "dome_standoff_m = 0.002"),
        (
            "block_size_m = [0.0799, 0.0799, 0.0799]",
            "block_size_m = [0.0799, 0.002, 0.0799]",
        ),
    ];
    let scene = bundled_scene("cj_iron", &point)?;
    let rig = run(&scene, RunOptions::default())?;
    let g = flexrig_rig::geometry::RigGeometry::of(&scene);
    let spring = flexrig_contact::SeriesCompliance::new(1e15, scene.hertz)?;
    let lumped = flexrig_lumped::ImpactModel::new(
        g.operator.effective_mass(),
        g.robot.effective_mass(),
        spring,
        rig.impact_velocity_mps,
    )?;
    cases.push(rel(
        "rig.CJ peak vs lumped (point contact)",
        rig.peak_force_n,
        peak_exact(&lumped).f_max,
        "lumped two-mass model, same masses",
        1e-4,
    ));
    let v = g.operator.bottom_angular_speed(30f64.to_radians(), 9.81) * g.operator.arm_length;
    cases.push(rel(
        "rig.impact speed vs pendulum energy",
        rig.impact_velocity_mps,
        v,
        "½Jω² = M g l_c (1 − cos θ₀)",
        1e-6,
    ));
    let (before, after) = rig.energy_through_contact_j.unwrap_or((f64::NAN, f64::NAN));
    cases.push(abs(
        "rig.energy through an undamped contact (relative)",
        (after - before) / before,
        0.0,
        "energy conservation",
        1e-6,
    ));
    // The Rapier CJ against the CJ built from a stiff FE beam on the same spring.
    let stiff = bundled_scene(
        "cl_iron",
        &[
            ("from = \"release\"", "from = \"contact\""),
            ("contact_steps = 800", "contact_steps = 1600"),
        ],
    )?;
    let cj = bundled_scene(
        "cj_iron",
        &[
            ("from = \"release\"", "from = \"contact\""),
            (
                "contact_steps = 800",
                "contact_steps = 1600\ncontact = \"fixed\"",
            ),
        ],
    )?;
    let fe = run(
        &stiff,
        RunOptions {
            cl_link: flexrig_rig::LinkVariant::StiffOnTorsionSpring {
                stiffness_factor: 1e4,
            },
            ..RunOptions::default()
        },
    )?;
    let rapier = run(&cj, RunOptions::default())?;
    cases.push(rel(
        "rig.Rapier CJ vs stiff FE CJ: peak",
        rapier.peak_force_n,
        fe.peak_force_n,
        "FE beam ×1e4 stiffness on k_θr",
        1e-3,
    ));
    // The modal-reduced CL link against the full linear FE link it is built from (truncation).
    let beam = |model: &str| {
        bundled_scene(
            "cl_iron",
            &[
                ("from = \"release\"", "from = \"contact\""),
                (
                    "contact_steps = 800",
                    &format!("contact_steps = 800\nbeam = {model}"),
                ),
            ],
        )
    };
    let full = run(&beam("{ model = \"linear\" }")?, RunOptions::default())?;
    let modal = run(
        &beam("{ model = \"modal\", modes = 12 }")?,
        RunOptions::default(),
    )?;
    cases.push(rel(
        "rig.CL modal beam (12 modes) vs full linear FE: peak",
        modal.peak_force_n,
        full.peak_force_n,
        "full linear FE link, same steps (measured 1.5e-8)",
        3e-7,
    ));
    if !quick {
        let peaks: Vec<f64> = [200usize, 400, 800]
            .iter()
            .map(|n| {
                let s = bundled_scene(
                    "cj_aluminium",
                    &[(
                        "contact_steps = 800",
                        &format!("contact_steps = {n}\ncontact = \"fixed\""),
                    )],
                )?;
                Ok(run(&s, RunOptions::default())?.peak_force_n)
            })
            .collect::<Result<_, Error>>()?;
        let order = ((peaks[0] - peaks[1]) / (peaks[1] - peaks[2])).log2();
        cases.push(abs(
            "rig.CJ peak convergence order in the contact step",
            order,
            2.0,
            "leapfrog (symplectic Euler) is second order",
            0.3,
        ));
    }
    Ok(())
}

/// The Markdown report written as `validation.md`.
pub fn markdown(cases: &[Case]) -> String {
    let passed = cases.iter().filter(|c| c.pass).count();
    let mut s = format!(
        "# Verification report\n\nGenerated by `flexrig validate`: {passed} of {} cases pass.\n\n| case | reference (source) | value | error | tolerance | pass |\n|---|---|---|---|---|---|\n",
        cases.len()
    );
    for c in cases {
        let kind = if c.kind == ErrorKind::Relative {
            "rel"
        } else {
            "abs"
        };
        s.push_str(&format!(
            "| {} | {:.10e} ({}) | {:.10e} | {:.2e} {kind} | {:.1e} | {} |\n",
            c.name,
            c.reference,
            c.source,
            c.value,
            c.error,
            c.tolerance,
            if c.pass { "yes" } else { "**NO**" }
        ));
    }
    s
}

/// The suite's cases and the report written.
#[derive(Debug, Clone, Serialize)]
pub struct ValidationReport {
    /// Every case, in suite order.
    pub cases: Vec<Case>,
    /// validation.md.
    pub report: PathBuf,
}

impl ValidationReport {
    /// The names of the failing cases.
    pub fn failed(&self) -> Vec<&str> {
        self.cases
            .iter()
            .filter(|c| !c.pass)
            .map(|c| c.name.as_str())
            .collect()
    }

    /// An error ([`Error::ValidationFailed`], a run failure) if any case failed.
    pub fn check(&self) -> Result<(), Error> {
        let failed = self.failed();
        if failed.is_empty() {
            Ok(())
        } else {
            Err(Error::ValidationFailed {
                failed: failed.join("; "),
            })
        }
    }
}

/// Runs the suite (without its slowest cases if `quick`) and writes `out/validation.md`. Failing
/// cases are reported, not an error: see [`ValidationReport::check`].
pub fn run(quick: bool, out: &Path) -> Result<ValidationReport, Error> {
    let cases = suite(quick)?;
    ensure_dir(out)?;
    let report = out.join("validation.md");
    write_atomic(&report, markdown(&cases).as_bytes())?;
    Ok(ValidationReport { cases, report })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_wrong_reference_fails_the_case() {
        let good = rel("x", 1.0 + 1e-13, 1.0, "exact", 1e-12);
        let wrong = rel("x", 1.0 + 1e-13, 1.001, "deliberately wrong", 1e-12);
        assert!(good.pass && !wrong.pass);
        assert!(!abs("nan", f64::NAN, 0.0, "", 1.0).pass);
        assert!(markdown(&[good, wrong]).contains("**NO**"));
    }
}
