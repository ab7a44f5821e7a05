//! The finite-element Euler–Bernoulli beam (flexrig-beam) of a rectangular section bending in
//! the thickness direction, as `flexrig beam` computes it: its natural frequencies, and its tip
//! displacement under a dead tip load (linear or large deflection). Inputs are checked against
//! physical ranges; errors name the flag of `flexrig beam` (`--length`).

use flexrig_beam::{
    BeamModel, BeamSpec, Material, ModalDirection, NodalLoads, PointMass, RootSupport, Section,
    StaticOptions, modal_analysis, solve_static,
};
use serde::{Deserialize, Serialize};

use crate::Error;
use crate::output::range_arg;

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
    /// Mass density ρ [kg/m³], in [1e-3, 1e6] (`--density`).
    pub density: f64,
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
        value: value.to_string(),
        allowed: allowed.into(),
    }
}

impl BeamInput {
    /// Checks every number against its range (the error names the flag).
    pub fn check_ranges(&self) -> Result<(), Error> {
        range_arg("--length", self.length, 1e-4, 1e3)?;
        range_arg("--youngs", self.youngs, 1e3, 1e13)?;
        range_arg("--density", self.density, 1e-3, 1e6)?;
        range_arg("--width", self.width, 1e-6, 10.0)?;
        range_arg("--thickness", self.thickness, 1e-7, 10.0)?;
        range_arg("--tip-mass", self.tip_mass, 0.0, 1e6)?;
        range_arg("--k-theta", self.k_theta, 0.0, 1e12)?;
        if self.elements == 0 || self.elements > flexrig_beam::model::MAX_ELEMENTS {
            return Err(invalid(
                "--elements",
                self.elements,
                "must be an integer from 1 to 100000",
            ));
        }
        Ok(())
    }

    /// The validated model with elements of `kinematics`.
    pub fn model(&self, kinematics: Kinematics) -> Result<BeamModel, Error> {
        self.check_ranges()?;
        let root = RootSupport::parse(self.root.name(), self.k_theta)?;
        let material = Material::new(self.youngs, self.density)?;
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
}

impl TipLoad {
    /// Checks the load and the number of increments (the error names the flag).
    pub fn validate(&self) -> Result<(), Error> {
        range_arg("--tip-load", self.force, -1e12, 1e12)?;
        range_arg("--tip-moment", self.moment, -1e12, 1e12)?;
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
    let model = beam.model(load.kinematics)?;
    let tip = model.tip_node();
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(tip, 0.0, load.force)?;
    loads.set_moment(tip, load.moment)?;
    let sol = solve_static(
        &model,
        &loads,
        &StaticOptions::with_load_steps(load.load_steps)?,
    )?;
    let (u, v, angle) = sol.node(tip);
    Ok(TipDisplacement {
        u,
        v,
        angle,
        iterations: sol.iterations,
        residual: sol.residual,
        load_level: sol.load_level,
    })
}
