//! The finite-element Euler–Bernoulli beam (flexrig-beam) of a rectangular section bending in
//! the thickness direction, as `flexrig beam` computes it: its natural frequencies, and its tip
//! displacement under a dead tip load (linear or large deflection) with the largest normal
//! stress in the beam. Inputs are checked against physical ranges; errors name the flag of
//! `flexrig beam` (`--length`). What is valid but looks like a mistake (a unit slip in E, a
//! linear solve far beyond small deflections, a stress above the yield strength) is a
//! plausibility [`Warning`]. The beam can be the link of a scene ([`scene_link`]).

use flexrig_beam::{
    BeamModel, BeamSpec, Material, ModalDirection, NodalLoads, PointMass, RootSupport, Section,
    StaticOptions, modal_analysis, solve_static,
};
use serde::{Deserialize, Serialize};

use crate::Error;
use crate::shared::output::{display_number, range_arg};

/// A plausibility warning (the scene's kind): the flag it is about and what looks wrong.
pub use flexrig_rig::plausibility::Warning;

/// The element kinematics (flexrig-beam's), for callers of this module.
pub use flexrig_beam::Kinematics;

/// The root's support.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Root {
    /// Clamped: u = v = θ = 0.
    Clamped,
    /// Pinned, restrained by the torsion spring [`BeamInput::k_theta`] (0: a free hinge).
    Pinned,
}

impl Root {
    /// Its name (`clamped`, `pinned`).
    pub fn name(self) -> &'static str {
        match self {
            Root::Clamped => "clamped",
            Root::Pinned => "pinned",
        }
    }
}

/// A uniform cantilever of rectangular section (SI units).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BeamInput {
    /// Length L \[m\], in [1e-4, 1e3] (`--length`).
    pub length: f64,
    /// Young's modulus E \[Pa\], in [1e3, 1e13] (`--youngs`).
    pub youngs: f64,
    /// Mass density ρ [kg/m³], in [1e-3, 1e6] (`--density`); needed by the modal analysis only
    /// (the static solve has no mass and no gravity).
    pub density: Option<f64>,
    /// Section width w \[m\] (the stiff direction), in [1e-6, 10] (`--width`).
    pub width: f64,
    /// Section thickness t \[m\] (the bending direction, I = w t³/12), in [1e-7, 10]
    /// (`--thickness`).
    pub thickness: f64,
    /// Hermite-cubic elements, 1 to 100000 (`--elements`).
    pub elements: usize,
    /// Point mass at the tip \[kg\] (rotary inertia neglected), in [0, 1e6] (`--tip-mass`).
    pub tip_mass: f64,
    /// The root's support (`--root`).
    pub root: Root,
    /// Torsion spring of a pinned root [N·m/rad], in [0, 1e12] (`--k-theta`).
    pub k_theta: f64,
}

fn invalid(arg: &str, value: impl ToString, allowed: &str) -> Error {
    Error::InvalidArgument {
        arg: arg.into(),
        value: crate::shared::output::value_text(value),
        allowed: allowed.into(),
    }
}

impl BeamInput {
    /// Checks every number against its range (the error names the flag).
    pub fn check_ranges(&self) -> Result<(), Error> {
        range_arg("--length", self.length, 1e-4, 1e3, "m")?;
        range_arg("--youngs", self.youngs, 1e3, 1e13, "Pa")?;
        if let Some(density) = self.density {
            range_arg("--density", density, 1e-3, 1e6, "kg/m³")?;
        }
        range_arg("--width", self.width, 1e-6, 10.0, "m")?;
        range_arg("--thickness", self.thickness, 1e-7, 10.0, "m")?;
        range_arg("--tip-mass", self.tip_mass, 0.0, 1e6, "kg")?;
        range_arg("--k-theta", self.k_theta, 0.0, 1e12, "N·m/rad")?;
        if self.elements == 0 || self.elements > flexrig_beam::model::MAX_ELEMENTS {
            return Err(invalid(
                "--elements",
                self.elements,
                "must be an integer from 1 to 100000",
            ));
        }
        Ok(())
    }

    /// Second moment of area of the section about its bending axis, I = w t³/12 \[m⁴\].
    pub fn second_moment(&self) -> f64 {
        self.width * self.thickness.powi(3) / 12.0
    }

    /// Section area A = w t \[m²\].
    pub fn area(&self) -> f64 {
        self.width * self.thickness
    }

    /// The validated model with elements of `kinematics`. Without a density (a static solve)
    /// the mass matrix, which no static result uses, is built with ρ = 1 kg/m³.
    pub fn model(&self, kinematics: Kinematics) -> Result<BeamModel, Error> {
        self.check_ranges()?;
        let root = RootSupport::parse(self.root.name(), self.k_theta)?;
        let material = Material::new(self.youngs, self.density.unwrap_or(1.0))?;
        let section = Section::rectangular(&material, self.width, self.thickness)?;
        let mut spec = BeamSpec::cantilever(self.length, section, self.elements, kinematics);
        spec.root = root;
        if self.tip_mass > 0.0 {
            spec.point_masses.push(PointMass {
                node: self.elements,
                mass: self.tip_mass,
                inertia: 0.0,
            });
        }
        Ok(BeamModel::new(spec)?)
    }
}

/// Checks the mesh of a modal analysis (a dense eigenproblem).
pub fn check_modal_elements(elements: usize) -> Result<(), Error> {
    if elements > flexrig_beam::modal::MAX_MODAL_ELEMENTS {
        return Err(invalid(
            "--elements",
            elements,
            &format!(
                "must be at most {} for beam modal (a dense eigenproblem, O(n³))",
                flexrig_beam::modal::MAX_MODAL_ELEMENTS
            ),
        ));
    }
    Ok(())
}

/// The natural frequencies \[Hz\] of the lowest `modes` (≥ 1, `--modes`) bending modes in the
/// thickness direction, ascending (a pinned root without spring reports its rigid mode as 0 Hz).
pub fn modal(beam: &BeamInput, modes: usize) -> Result<Vec<f64>, Error> {
    check_modal_elements(beam.elements)?;
    if beam.density.is_none() {
        return Err(invalid(
            "--density",
            "(missing)",
            "the natural frequencies depend on the mass: give the density in kg/m³ (or take the \
             link of a scene with --scene)",
        ));
    }
    let model = beam.model(Kinematics::Linear)?;
    if modes == 0 {
        return Err(invalid("--modes", 0, "must be an integer >= 1"));
    }
    let r = modal_analysis(&model, modes, ModalDirection::Transverse).map_err(|e| match e {
        flexrig_beam::BeamError::InvalidParameter {
            field,
            value,
            allowed,
        } if field == "modes" => Error::InvalidArgument {
            arg: "--modes".into(),
            value,
            allowed,
        },
        e => e.into(),
    })?;
    Ok(r.frequencies_hz)
}

/// The static load case of `beam static`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TipLoad {
    /// Dead tip force perpendicular to the undeformed beam \[N\] (+ toward +v), within ±1e12
    /// (`--tip-load`).
    pub force: f64,
    /// Tip moment [N·m] (counter-clockwise, + bends toward +v), within ±1e12 (`--tip-moment`).
    pub moment: f64,
    /// Kinematic model: linear (small deflection), corotational or ANCF (large deflection).
    pub kinematics: Kinematics,
    /// Load increments of the Newton solve, 1 to 1000000 (`--load-steps`).
    pub load_steps: usize,
    /// Adaptive load increments (`--adaptive-steps`): the first is 1/`load_steps` of the load,
    /// halved where Newton fails and doubled after each converged increment; the same
    /// equilibrium as fixed increments in as few Newton solves as the load needs.
    #[serde(default)]
    pub adaptive_steps: bool,
}

/// The tip's static displacement and how the solve went.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TipDisplacement {
    /// Axial displacement u \[m\].
    pub u: f64,
    /// Transverse displacement v \[m\].
    pub v: f64,
    /// Rotation θ \[rad\].
    pub angle: f64,
    /// Newton iterations (all increments).
    pub iterations: usize,
    /// Final residual norm \[N\].
    pub residual: f64,
    /// Load level reached (1 when converged).
    pub load_level: f64,
    /// The largest normal stress in the beam and where it occurs.
    pub stress: Stress,
}

/// The largest normal stress of a static solution: bending σ_b = |M| (t/2)/I plus, for the
/// large-deflection models, the axial σ_a = |N|/A, at the node of the mesh where their sum is
/// largest. The section forces come from equilibrium of the part of the beam beyond the node
/// under the dead tip load (F, M_tip): M = M_tip + F (X_tip − X) and N = F sin θ, with X the
/// node's deformed axial position (undeformed for the linear model, which has no axial force).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Stress {
    /// σ_max = σ_b + σ_a \[Pa\].
    pub max_pa: f64,
    /// Its bending part |M| t/(2I) \[Pa\].
    pub bending_pa: f64,
    /// Its axial part |N|/A \[Pa\] (0 for the linear model).
    pub axial_pa: f64,
    /// Bending moment there [N·m] (+ bends toward +v).
    pub moment_nm: f64,
    /// Axial force there \[N\] (+ tension).
    pub axial_n: f64,
    /// Where: the distance of the node from the root along the undeformed beam \[m\].
    pub at_m: f64,
}

/// [`Stress`] of the deformed nodes `nodes` ((u, v, θ) per node, root first) of `beam` under
/// `load` (see there for the equilibrium used).
fn stress_of(beam: &BeamInput, load: &TipLoad, nodes: &[(f64, f64, f64)]) -> Stress {
    let n = nodes.len().max(2) - 1;
    let h = beam.length / n as f64;
    let linear = load.kinematics == Kinematics::Linear;
    let x_of = |i: usize| {
        let x = h * i as f64;
        if linear { x } else { x + nodes[i].0 }
    };
    let x_tip = x_of(nodes.len() - 1);
    let c_over_i = 0.5 * beam.thickness / beam.second_moment();
    let area = beam.area();
    let mut best: Option<Stress> = None;
    for (i, &(_, _, theta)) in nodes.iter().enumerate() {
        let moment = load.moment + load.force * (x_tip - x_of(i));
        let axial = if linear {
            0.0
        } else {
            load.force * theta.sin()
        };
        let bending_pa = moment.abs() * c_over_i;
        let axial_pa = axial.abs() / area;
        let candidate = Stress {
            max_pa: bending_pa + axial_pa,
            bending_pa,
            axial_pa,
            moment_nm: moment,
            axial_n: axial,
            at_m: h * i as f64,
        };
        if best.is_none_or(|b| candidate.max_pa > b.max_pa) {
            best = Some(candidate);
        }
    }
    best.unwrap_or(Stress {
        max_pa: 0.0,
        bending_pa: 0.0,
        axial_pa: 0.0,
        moment_nm: 0.0,
        axial_n: 0.0,
        at_m: 0.0,
    })
}

impl TipLoad {
    /// Checks the load and the number of increments (the error names the flag).
    pub fn validate(&self) -> Result<(), Error> {
        range_arg("--tip-load", self.force, -1e12, 1e12, "N")?;
        range_arg("--tip-moment", self.moment, -1e12, 1e12, "N·m")?;
        if self.load_steps == 0 || self.load_steps > 1_000_000 {
            return Err(invalid(
                "--load-steps",
                self.load_steps,
                "must be an integer from 1 to 1000000",
            ));
        }
        Ok(())
    }
}

/// Solves the beam under the tip load.
pub fn statics(beam: &BeamInput, load: &TipLoad) -> Result<TipDisplacement, Error> {
    load.validate()?;
    if beam.root.name() == "pinned" && beam.k_theta == 0.0 {
        // a free hinge: the stiffness matrix has the rigid rotation in its null space
        return Err(invalid(
            "--k-theta",
            0.0,
            "a torsion spring > 0 N·m/rad for a static solve: a pinned root without one is a \
             free hinge, the beam turns about it as a mechanism and has no static equilibrium \
             under a tip load (or use --root clamped)",
        ));
    }
    let model = beam.model(load.kinematics)?;
    let tip = model.tip_node();
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(tip, 0.0, load.force)?;
    loads.set_moment(tip, load.moment)?;
    let mut options = StaticOptions::with_load_steps(load.load_steps)?;
    if load.adaptive_steps {
        options = options.with_adaptive_steps();
    }
    let sol = solve_static(&model, &loads, &options)?;
    let (u, v, angle) = sol.node(tip);
    let nodes: Vec<_> = (0..=tip).map(|i| sol.node(i)).collect();
    Ok(TipDisplacement {
        u,
        v,
        angle,
        iterations: sol.iterations,
        residual: sol.residual,
        load_level: sol.load_level,
        stress: stress_of(beam, load, &nodes),
    })
}

/// A linear solve whose tip deflection exceeds this fraction of L is far outside small
/// deflections.
pub const LINEAR_DEFLECTION_LIMIT: f64 = 0.1;
/// Below this Young's modulus \[Pa\] a solid is softer than soft rubber (≈ 1 MPa): the number
/// looks like MPa or GPa written in the pascal flag.
pub const SOFTEST_SOLID_PA: f64 = 1e6;
/// Above this Young's modulus \[Pa\] a solid is stiffer than diamond (≈ 1.05 TPa).
pub const STIFFEST_SOLID_PA: f64 = 1.2e12;
/// The bar speed √(E/ρ) \[m/s\] of a stiff structural metal (steel, aluminium, titanium:
/// 4.9–5.2 km/s); above it only fibre composites, ceramics and beryllium are stiffer for their
/// weight, so a faster beam is unusual (a note, not an error).
pub const FASTEST_METAL_BAR_SPEED: f64 = 5.5e3;
/// The bar speed \[m/s\] of soft rubber (E ≈ 1 MPa, ρ ≈ 1100 kg/m³); a slower beam is softer
/// for its weight than any solid.
pub const SLOWEST_SOLID_BAR_SPEED: f64 = 30.0;

fn note(flag: &str, message: String) -> Warning {
    Warning {
        field: flag.to_string(),
        message,
    }
}

/// What is valid but looks like a mistake in the beam: a Young's modulus softer than rubber or
/// stiffer than diamond (a unit slip), a material stiffer or softer for its weight than
/// structural solids are ([`FASTEST_METAL_BAR_SPEED`], [`SLOWEST_SOLID_BAR_SPEED`]).
pub fn beam_warnings(beam: &BeamInput) -> Vec<Warning> {
    let mut out = Vec::new();
    let e = beam.youngs;
    if e < SOFTEST_SOLID_PA {
        out.push(note(
            "--youngs",
            format!(
                "E = {} Pa is softer than soft rubber (about 1e6 Pa): the number looks like MPa \
                 or GPa; E is in pascals (polypropylene 1.5e9, aluminium 7e10, steel 2e11)",
                display_number(e)
            ),
        ));
    } else if e > STIFFEST_SOLID_PA {
        out.push(note(
            "--youngs",
            format!(
                "E = {} Pa is stiffer than diamond (about 1.05e12 Pa): check the unit; E is in \
                 pascals (steel 2e11)",
                display_number(e)
            ),
        ));
    } else if let Some(rho) = beam.density {
        let speed = (e / rho).sqrt();
        if speed > FASTEST_METAL_BAR_SPEED {
            out.push(note(
                "--youngs",
                format!(
                    "E = {} Pa with ρ = {} kg/m³ is stiffer for its weight than steel or \
                     aluminium (bar speed √(E/ρ) = {} km/s against about 5 km/s): usual only \
                     for fibre composites and ceramics; check E and ρ",
                    display_number(e),
                    display_number(rho),
                    display_number((speed / 100.0).round() / 10.0)
                ),
            ));
        } else if speed < SLOWEST_SOLID_BAR_SPEED {
            out.push(note(
                "--youngs",
                format!(
                    "E = {} Pa with ρ = {} kg/m³ is softer for its weight than soft rubber \
                     (bar speed √(E/ρ) = {} m/s, rubber about 30 m/s): check the units of E (Pa) \
                     and ρ (kg/m³)",
                    display_number(e),
                    display_number(rho),
                    display_number(speed.round())
                ),
            ));
        }
    }
    out
}

/// [`beam_warnings`] and what looks wrong in the static result `sol` of `load`: a linear
/// solve deflecting more than [`LINEAR_DEFLECTION_LIMIT`] of L (the small-deflection model no
/// longer holds), a largest stress above `yield_strength` \[Pa\] when one is given.
pub fn static_warnings(
    beam: &BeamInput,
    load: &TipLoad,
    sol: &TipDisplacement,
    yield_strength: Option<f64>,
) -> Vec<Warning> {
    let mut out = beam_warnings(beam);
    let ratio = sol.v.abs() / beam.length;
    if load.kinematics == Kinematics::Linear && ratio > LINEAR_DEFLECTION_LIMIT {
        out.push(note(
            "--model",
            format!(
                "the linear (small-deflection) tip deflection is {} % of the length, beyond the \
                 {} % where the model holds: solve the large deflection with --model ancf",
                display_number((ratio * 1e3).round() / 10.0),
                LINEAR_DEFLECTION_LIMIT * 100.0
            ),
        ));
    }
    if let Some(yield_pa) = yield_strength
        && sol.stress.max_pa > yield_pa
    {
        out.push(note(
            "--yield-strength",
            format!(
                "the largest stress {} MPa (at {} m from the root) exceeds the yield strength \
                 {} MPa: the beam yields there and the elastic result does not hold",
                display_number((sol.stress.max_pa / 1e3).round() / 1e3),
                display_number((sol.stress.at_m * 1e6).round() / 1e6),
                display_number(yield_pa / 1e6)
            ),
        ));
    }
    out
}

/// Checks a yield strength \[Pa\] (`--yield-strength`), in [1e3, 1e11].
pub fn check_yield_strength(yield_strength: Option<f64>) -> Result<(), Error> {
    if let Some(y) = yield_strength {
        range_arg("--yield-strength", y, 1e3, 1e11, "Pa")?;
    }
    Ok(())
}

/// The link of a scene as `flexrig beam` takes it (`--scene`): its robot link's length,
/// modulus, density, section, payload (the tip mass) and elements.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SceneLink {
    /// Where the scene came from (`bundled cl_aluminium` or the path).
    pub origin: String,
    /// Link length L \[m\].
    pub length: f64,
    /// Young's modulus E \[Pa\].
    pub youngs: f64,
    /// Density ρ [kg/m³].
    pub density: f64,
    /// Section width w \[m\].
    pub width: f64,
    /// Section thickness t \[m\] (the bending direction).
    pub thickness: f64,
    /// The payload at the tip \[kg\].
    pub tip_mass: f64,
    /// The scene's beam elements.
    pub elements: usize,
}

/// The link of scene `given` (a bundled name or a scene file; errors name `arg`, e.g.
/// `--scene`).
pub fn scene_link(arg: &str, given: &std::path::Path) -> Result<SceneLink, Error> {
    let source = crate::testbed::scenes::resolve(arg, given)?;
    let materials = flexrig_contact::Materials::bundled()?;
    let scene = flexrig_rig::Scene::from_toml_str(&source.text, &materials)?;
    let r = &scene.file.robot;
    Ok(SceneLink {
        origin: source.origin,
        length: r.length_m,
        youngs: r.youngs_modulus_pa,
        density: r.density_kg_m3,
        width: r.width_m,
        thickness: r.thickness_m,
        tip_mass: r.payload_kg,
        elements: r.beam_elements,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use flexrig_beam::canonical::ELASTICA;

    /// A steel strip: L = 1 m, 20 mm × 5 mm, clamped, 32 elements, no density (a static solve).
    fn strip() -> BeamInput {
        BeamInput {
            length: 1.0,
            youngs: 2e11,
            density: None,
            width: 0.02,
            thickness: 0.005,
            elements: 32,
            tip_mass: 0.0,
            root: Root::Clamped,
            k_theta: 0.0,
        }
    }

    fn load(force: f64, moment: f64, kinematics: Kinematics) -> TipLoad {
        TipLoad {
            force,
            moment,
            kinematics,
            load_steps: 20,
            adaptive_steps: false,
        }
    }

    #[test]
    fn linear_root_stress_is_the_analytic_cantilever_stress() {
        // σ_root = (P L + M) (t/2) / I (Euler–Bernoulli cantilever; the Hermite cubic is exact)
        let beam = strip();
        for (p, m) in [(10.0, 0.0), (-3.0, 0.0), (10.0, 4.0), (0.0, -2.5)] {
            let s = statics(&beam, &load(p, m, Kinematics::Linear))
                .unwrap()
                .stress;
            let want = (p * beam.length + m).abs() * 0.5 * beam.thickness / beam.second_moment();
            assert!(
                (s.max_pa / want - 1.0).abs() < 1e-12,
                "{p} N, {m} N·m: {} Pa against {want} Pa",
                s.max_pa
            );
            assert_eq!(s.axial_pa, 0.0);
            // a tip force puts the largest moment at the root; a pure moment is uniform (the
            // root is the first node of equal stress)
            assert_eq!(s.at_m, 0.0);
            assert!(
                (s.moment_nm - (p * beam.length + m)).abs() < 1e-12 * (1.0 + s.moment_nm.abs())
            );
        }
    }

    #[test]
    fn large_deflection_root_stress_matches_the_elastica_and_the_fe_root_moment() {
        // Inextensible elastica (Bisshopp & Drucker): the root moment is P (L − u_tip); the FE
        // reaction moment at the clamped root is the same moment from the element forces.
        let beam = strip();
        let ei = beam.youngs * beam.second_moment();
        let c_over_i = 0.5 * beam.thickness / beam.second_moment();
        for kinematics in [Kinematics::Corotational, Kinematics::Ancf] {
            for &(alpha, _v, u, _th) in &ELASTICA[..3] {
                let p = alpha * ei / beam.length.powi(2);
                let l = load(p, 0.0, kinematics);
                let s = statics(&beam, &l).unwrap().stress;
                let elastica = p * beam.length * (1.0 - u) * c_over_i;
                assert!(
                    (s.bending_pa / elastica - 1.0).abs() < 2e-3,
                    "{kinematics:?} PL²/EI = {alpha}: {} Pa against the elastica's {elastica} Pa",
                    s.bending_pa
                );
                assert_eq!(s.at_m, 0.0, "{kinematics:?} {alpha}");
                // the FE root moment: the clamped root's reaction
                let model = beam.model(kinematics).unwrap();
                let mut loads = NodalLoads::zeros(&model);
                loads.set_force(model.tip_node(), 0.0, p).unwrap();
                let sol =
                    solve_static(&model, &loads, &StaticOptions::with_load_steps(20).unwrap())
                        .unwrap();
                let fe = sol.reactions[2].abs();
                assert!(
                    (s.moment_nm.abs() / fe - 1.0).abs() < 1e-6,
                    "{kinematics:?} {alpha}: equilibrium {} N·m, FE reaction {fe} N·m",
                    s.moment_nm
                );
            }
        }
    }

    #[test]
    fn large_deflection_axial_stress_is_the_tip_force_along_the_tangent() {
        // a tip moment and force: N = F sin θ at each node, 0 at the clamped root
        let beam = strip();
        let ei = beam.youngs * beam.second_moment();
        let p = 2.0 * ei / beam.length.powi(2);
        let sol = statics(&beam, &load(p, 0.0, Kinematics::Ancf)).unwrap();
        // at the root (θ = 0) there is no axial force; the bending part dominates
        assert_eq!(sol.stress.at_m, 0.0);
        assert!(sol.stress.axial_n.abs() < 1e-9 * p);
        // a tip moment alone: a uniform moment and no axial force
        let m = 0.5 * ei / beam.length;
        let s = statics(&beam, &load(0.0, m, Kinematics::Ancf))
            .unwrap()
            .stress;
        assert!(
            (s.bending_pa / (m * 0.5 * beam.thickness / beam.second_moment()) - 1.0).abs() < 1e-12
        );
        assert_eq!(s.axial_pa, 0.0);
    }

    #[test]
    fn warnings_flag_unit_slips_far_linear_deflections_and_yield() {
        let beam = strip();
        assert!(beam_warnings(&beam).is_empty());
        // 200e3: steel's modulus in MPa written as pascals
        let soft = BeamInput {
            youngs: 2e5,
            ..beam
        };
        assert_eq!(beam_warnings(&soft)[0].field, "--youngs");
        // 30 GPa with a polymer's density: stiffer for its weight than any metal
        let odd = BeamInput {
            youngs: 3e10,
            density: Some(905.0),
            ..beam
        };
        let w = beam_warnings(&odd);
        assert!(w.len() == 1 && w[0].message.contains("5.8 km/s"), "{w:?}");
        // aluminium is no warning
        let al = BeamInput {
            youngs: 7e10,
            density: Some(2700.0),
            ..beam
        };
        assert!(beam_warnings(&al).is_empty());
        // the linear model at 12 % of L (PL³/3EI = 0.12 L) and at 8 %
        let ei = beam.youngs * beam.second_moment();
        for (ratio, warned) in [(0.12, true), (0.08, false)] {
            let l = load(
                ratio * 3.0 * ei / beam.length.powi(2),
                0.0,
                Kinematics::Linear,
            );
            let sol = statics(&beam, &l).unwrap();
            let w = static_warnings(&beam, &l, &sol, None);
            assert_eq!(w.iter().any(|w| w.field == "--model"), warned, "{w:?}");
            // the same load with ANCF is no warning
            let a = load(l.force, 0.0, Kinematics::Ancf);
            assert!(static_warnings(&beam, &a, &statics(&beam, &a).unwrap(), None).is_empty());
            // yield: just below and just above the largest stress
            let s = sol.stress.max_pa;
            assert!(
                static_warnings(&beam, &l, &sol, Some(s * 1.001))
                    .iter()
                    .all(|w| w.field != "--yield-strength")
            );
            assert!(
                static_warnings(&beam, &l, &sol, Some(s * 0.999))
                    .iter()
                    .any(|w| w.field == "--yield-strength")
            );
        }
        assert!(check_yield_strength(Some(-1.0)).is_err());
    }

    #[test]
    fn a_scene_gives_its_link() {
        let link = scene_link("--scene", std::path::Path::new("cl_aluminium")).unwrap();
        let scene = crate::testbed::scenes::bundled_scene("cl_aluminium", &[]).unwrap();
        let r = &scene.file.robot;
        assert_eq!(link.length, r.length_m);
        assert_eq!(link.youngs, r.youngs_modulus_pa);
        assert_eq!(link.density, r.density_kg_m3);
        assert_eq!(link.thickness, r.thickness_m);
        assert_eq!(link.tip_mass, r.payload_kg);
        assert_eq!(link.origin, "bundled cl_aluminium");
        let e = scene_link("--scene", std::path::Path::new("cl_aluminum")).unwrap_err();
        assert!(e.to_string().contains("--scene"), "{e}");
    }
}
