//! Canonical problems and their published references (see `docs/references.md`),
//! shared by tests, benches and the CLI.

use crate::BeamError;
use crate::dynamics::{GeneralizedAlpha, State, Workspace};
use crate::model::{BeamModel, BeamSpec, Kinematics, NodalLoads, PointMass};
use crate::section::Section;

/// Roots β_nL of 1 + cos β cosh β = 0 (clamped–free Euler–Bernoulli beam).
pub const CANTILEVER_BETA_L: [f64; 4] = [1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349];

/// Pinned–free beam (free hinge): after the rigid mode, β_nL.
pub const PINNED_FREE_BETA_L: [f64; 3] = [3.92660, 7.06858, 10.21018];

/// Cantilever with a tip mass M, μ = M/(ρAL): (μ, β₁L), roots of
/// 1 + cos β cosh β + μβ (cos β sinh β − sin β cosh β) = 0.
pub const TIP_MASS_BETA1: [(f64, f64); 7] = [
    (0.1, 1.72274),
    (0.2, 1.61640),
    (0.5, 1.41996),
    (1.0, 1.24792),
    (2.0, 1.07620),
    (5.0, 0.87002),
    (10.0, 0.73578),
];

/// Inextensible elastica, cantilever under a perpendicular dead tip load:
/// (PL²/EI, v/L, u/L shortening, tip angle \[rad\]).
pub const ELASTICA: [(f64, f64, f64, f64); 4] = [
    (1.0, 0.3017207738, 0.0564332363, 0.4613519497),
    (2.0, 0.4934574804, 0.1606417208, 0.7817498316),
    (5.0, 0.7137915236, 0.3876283607, 1.2153681176),
    (10.0, 0.8106090249, 0.5549955978, 1.4302855388),
];

/// Howell's PRB cantilever with a vertical end load: γ.
pub const HOWELL_GAMMA: f64 = 0.8517;
/// Howell's stiffness coefficient K_Θ (k = γ K_Θ EI/L), quoted from the book.
pub const HOWELL_K_THETA: f64 = 2.67617;
/// Howell's parametric limit Θ_max \[deg\] for γ = 0.8517 (tip error ≤ 0.5 % of L).
pub const HOWELL_THETA_MAX_DEG: f64 = 64.3;
/// The paper's small-deflection characteristic radius.
pub const PAPER_GAMMA_SMALL: f64 = 2.0 / 3.0;

/// The thin polypropylene cantilever of the Exudyn comparison: L = 0.3 m, E = 1.5 GPa, ρ = 900 kg/m³,
/// 25 × 1 mm (EA L²/EI = 1.08e6), clamped, `elements` elements, and the tip load P = EI/L² of
/// its step-load transient (from rest, 1000 steps of 1 ms in the benches).
pub fn polypropylene_cantilever(
    elements: usize,
    kinematics: Kinematics,
) -> Result<(BeamModel, NodalLoads), BeamError> {
    let mat = crate::section::Material::new(1.5e9, 900.0)?;
    let sec = Section::rectangular(&mat, 0.025, 0.001)?;
    let model = BeamModel::new(BeamSpec::cantilever(0.3, sec, elements, kinematics))?;
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(model.tip_node(), 0.0, sec.ei() / 0.09)?;
    Ok((model, loads))
}

/// The step-load transient: [`polypropylene_cantilever`] from rest under its tip load
/// P = EI/L² applied at t = 0, stepped by `integrator` with the fixed step `h` \[s\] to `duration` \[s\].
/// Returns the tip deflection v \[m\] at every multiple of `sample` \[s\] (rounded to whole
/// steps, at least one step apart) and the Newton iterations per step.
pub fn polypropylene_step_load(
    elements: usize,
    kinematics: Kinematics,
    integrator: &GeneralizedAlpha,
    h: f64,
    duration: f64,
    sample: f64,
) -> Result<(Vec<f64>, f64), BeamError> {
    let (model, loads) = polypropylene_cantilever(elements, kinematics)?;
    let mut state = State::at_rest(&model, &loads)?;
    let mut workspace = Workspace::new(&model);
    let steps = (duration / h).round() as usize;
    let every = ((sample / h).round() as usize).max(1);
    let mut tip = Vec::with_capacity(steps / every + 1);
    let mut iterations = 0;
    for k in 1..=steps {
        iterations += integrator
            .step(&model, &mut state, &mut workspace, h, &loads)?
            .iterations;
        if k % every == 0 {
            tip.push(state.node(model.tip_node()).1);
        }
    }
    Ok((tip, iterations as f64 / steps.max(1) as f64))
}

/// Natural frequency ω = (βL)² √(EI/(ρA L⁴)) [rad/s].
pub fn beam_omega(beta_l: f64, ei: f64, rho_a: f64, length: f64) -> f64 {
    beta_l * beta_l * (ei / (rho_a * length.powi(4))).sqrt()
}

/// The nondimensional beam used by the canonical problems: L = 1 m, EI = 1 N·m², ρA = 1 kg/m,
/// EA = 1e7 N (so P/EA ≤ 1e-6: practically inextensible).
pub fn unit_section() -> Section {
    Section::from_stiffness(1.0e7, 1.0, 1.0).expect("valid constants")
}

/// A unit cantilever with `elements` elements.
pub fn unit_cantilever(elements: usize, kinematics: Kinematics) -> Result<BeamModel, BeamError> {
    BeamModel::new(BeamSpec::cantilever(
        1.0,
        unit_section(),
        elements,
        kinematics,
    ))
}

/// A unit cantilever with a tip mass μ ρAL.
pub fn unit_cantilever_with_tip_mass(elements: usize, mu: f64) -> Result<BeamModel, BeamError> {
    let mut spec = BeamSpec::cantilever(1.0, unit_section(), elements, Kinematics::Linear);
    spec.point_masses.push(PointMass {
        node: elements,
        mass: mu,
        inertia: 0.0,
    });
    BeamModel::new(spec)
}

/// Elastica problem: the unit corotational cantilever with a perpendicular dead tip load
/// P = `load_index`·EI/L² (+y), and the reference (v/L, u/L, tip angle) when tabulated.
pub fn elastica_problem(
    load_index: f64,
    elements: usize,
) -> Result<(BeamModel, NodalLoads), BeamError> {
    elastica_problem_with(Kinematics::Corotational, load_index, elements)
}

/// [`elastica_problem`] with the large-deflection element `kinematics`.
pub fn elastica_problem_with(
    kinematics: Kinematics,
    load_index: f64,
    elements: usize,
) -> Result<(BeamModel, NodalLoads), BeamError> {
    let model = unit_cantilever(elements, kinematics)?;
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(model.tip_node(), 0.0, load_index)?;
    Ok((model, loads))
}
