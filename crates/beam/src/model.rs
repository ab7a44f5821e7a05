//! The beam model (immutable, validated, serialisable) and the nodal loads applied to it.

use serde::{Deserialize, Serialize};

use crate::BeamError;
use crate::error::{finite, non_negative, positive};
use crate::section::Section;

/// Kinematic model of the elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kinematics {
    /// Small displacements and rotations: constant K and M.
    Linear,
    /// Large displacements and rotations (Crisfield's corotational element), small strains.
    Corotational,
    /// Large displacements and rotations with the ANCF cable element ([`crate::ancf`]): cubic
    /// Hermite positions from nodal positions and slopes, constant consistent mass, exact for
    /// rigid motion. Node `i` carries 4 DOFs, the displacements of (x, y, r′ᵧ, r′ₓ) from the
    /// straight reference: (u, v, r′ᵧ, r′ₓ − 1) at `4i … 4i+3` (r′ᵧ ≈ θ for small rotations);
    /// the node angle is θ = atan2(r′ᵧ, r′ₓ). Loads, point masses and node queries stay in
    /// (u, v, θ) terms.
    Ancf,
}

impl Kinematics {
    /// DOFs per node: 3 (u, v, θ), or 4 for ANCF (u, v, r′ᵧ, r′ₓ − 1).
    pub fn dofs_per_node(self) -> usize {
        match self {
            Kinematics::Ancf => 4,
            _ => 3,
        }
    }
    /// Parses `linear`, `corotational` or `ancf`, naming `field` on error.
    pub fn parse(field: &str, text: &str) -> Result<Self, BeamError> {
        match text {
            "linear" => Ok(Kinematics::Linear),
            "corotational" => Ok(Kinematics::Corotational),
            "ancf" => Ok(Kinematics::Ancf),
            other => Err(BeamError::invalid(
                field,
                other,
                "one of linear, corotational, ancf",
            )),
        }
    }
}

/// Mass discretisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MassMatrix {
    /// Consistent mass of the Hermite-cubic position field (rotation invariant, see
    /// [`crate::element`]); ω₁ converges from above as O(h⁴).
    Consistent,
    /// Diagonal (row-sum) mass: ρA l/2 per node and direction, and a rotary inertia ρA l³/78
    /// per node (HRZ scaling); ω₁ converges from below as O(h²).
    Lumped,
}

/// Boundary condition at the root node (node 0, x = 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum RootSupport {
    /// u = v = θ = 0 at the root (ANCF: u = v = r′ᵧ = 0, the slope's length stays free).
    Clamped,
    /// u = v = 0; θ free, restrained by a linear torsion spring `k_theta` [N·m/rad] and a
    /// viscous damper `c_theta` [N·m·s/rad] (both may be 0: a free hinge).
    Pinned {
        /// Torsion spring stiffness [N·m/rad], ≥ 0.
        k_theta: f64,
        /// Torsion damper [N·m·s/rad], ≥ 0.
        c_theta: f64,
    },
    /// Pinned to a hub of rotary inertia `inertia` [kg·m²] with a torsion spring and damper to
    /// ground; the hub torque is the nodal moment at node 0 ([`NodalLoads::set_moment`]).
    Hub {
        /// Hub rotary inertia about the pin [kg·m²], ≥ 0.
        inertia: f64,
        /// Torsion spring stiffness [N·m/rad], ≥ 0.
        k_theta: f64,
        /// Torsion damper [N·m·s/rad], ≥ 0.
        c_theta: f64,
    },
}

impl RootSupport {
    /// Parses `clamped` or `pinned` (a pinned root with spring `k_theta`), naming the field on
    /// error.
    pub fn parse(kind: &str, k_theta: f64) -> Result<Self, BeamError> {
        match kind {
            "clamped" => Ok(RootSupport::Clamped),
            "pinned" => Ok(RootSupport::Pinned {
                k_theta: non_negative("k_theta", k_theta)?,
                c_theta: 0.0,
            }),
            other => Err(BeamError::invalid("root", other, "one of clamped, pinned")),
        }
    }

    /// Number of constrained DOFs at the root (3 clamped, 2 pinned).
    pub fn n_fixed(&self) -> usize {
        match self {
            RootSupport::Clamped => 3,
            _ => 2,
        }
    }

    /// (k_θ, c_θ, J_hub) of the root rotation (zeros when clamped).
    pub fn spring_damper_inertia(&self) -> (f64, f64, f64) {
        match *self {
            RootSupport::Clamped => (0.0, 0.0, 0.0),
            RootSupport::Pinned { k_theta, c_theta } => (k_theta, c_theta, 0.0),
            RootSupport::Hub {
                inertia,
                k_theta,
                c_theta,
            } => (k_theta, c_theta, inertia),
        }
    }
}

/// A point mass and rotary inertia attached to a node (payload, dome, sensor).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PointMass {
    /// Node index, 0..=N.
    pub node: usize,
    /// Mass \[kg\], ≥ 0.
    pub mass: f64,
    /// Rotary inertia about the node [kg·m²], ≥ 0.
    pub inertia: f64,
}

/// Rayleigh damping C = a₀ M + a₁ K (for the corotational model a₁ multiplies the rate of the
/// local deformations, so rigid motion is not damped by the a₁ term).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Rayleigh {
    /// Mass-proportional coefficient a₀ [1/s], ≥ 0.
    pub alpha_mass: f64,
    /// Stiffness-proportional coefficient a₁ \[s\], ≥ 0.
    pub beta_stiffness: f64,
}

impl Rayleigh {
    /// No damping.
    pub const NONE: Rayleigh = Rayleigh {
        alpha_mass: 0.0,
        beta_stiffness: 0.0,
    };
}

/// The parameters of a beam, before validation (the serialised form of [`BeamModel`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BeamSpec {
    /// Beam length L \[m\], > 0.
    pub length: f64,
    /// Section properties.
    pub section: Section,
    /// Number of elements N, 1..=100 000.
    pub elements: usize,
    /// Root support.
    pub root: RootSupport,
    /// Point masses and inertias at nodes.
    pub point_masses: Vec<PointMass>,
    /// Linear or corotational elements.
    pub kinematics: Kinematics,
    /// Consistent or lumped mass.
    pub mass: MassMatrix,
    /// Rayleigh damping.
    pub damping: Rayleigh,
}

impl BeamSpec {
    /// A clamped, undamped beam with consistent mass and no point masses.
    pub fn cantilever(
        length: f64,
        section: Section,
        elements: usize,
        kinematics: Kinematics,
    ) -> Self {
        BeamSpec {
            length,
            section,
            elements,
            root: RootSupport::Clamped,
            point_masses: Vec::new(),
            kinematics,
            mass: MassMatrix::Consistent,
            damping: Rayleigh::NONE,
        }
    }
}

/// A validated straight beam along x from the root (x = 0) to the tip (x = L), meshed in N equal
/// two-node elements.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "BeamSpec", into = "BeamSpec")]
pub struct BeamModel {
    spec: BeamSpec,
    element_length: f64,
    /// The mesh's ANCF element and its tangent tables (derived from `spec`, built once: every
    /// assembly of an ANCF model uses them).
    ancf: Box<AncfParts>,
}

/// The ANCF element of a uniform mesh and its tangent tables.
#[derive(Clone, PartialEq)]
pub(crate) struct AncfParts {
    pub(crate) element: crate::ancf::AncfElement,
    pub(crate) tables: crate::ancf::TangentTables,
}

impl std::fmt::Debug for AncfParts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // (derived from the spec, which the model's debug output shows)
        f.write_str("AncfParts { .. }")
    }
}

impl TryFrom<BeamSpec> for BeamModel {
    type Error = BeamError;
    fn try_from(spec: BeamSpec) -> Result<Self, BeamError> {
        BeamModel::new(spec)
    }
}

impl From<BeamModel> for BeamSpec {
    fn from(m: BeamModel) -> Self {
        m.spec
    }
}

/// Largest accepted number of elements.
pub const MAX_ELEMENTS: usize = 100_000;

impl BeamModel {
    /// Validates `spec`: L > 0, 1 ≤ N ≤ [`MAX_ELEMENTS`], non-negative finite spring, damper,
    /// inertia, masses and damping coefficients, point masses on existing nodes.
    pub fn new(spec: BeamSpec) -> Result<Self, BeamError> {
        positive("length", spec.length)?;
        if spec.elements == 0 || spec.elements > MAX_ELEMENTS {
            return Err(BeamError::invalid(
                "elements",
                spec.elements,
                format!("an integer from 1 to {MAX_ELEMENTS}"),
            ));
        }
        match spec.root {
            RootSupport::Clamped => {}
            RootSupport::Pinned { k_theta, c_theta } => {
                non_negative("k_theta", k_theta)?;
                non_negative("c_theta", c_theta)?;
            }
            RootSupport::Hub {
                inertia,
                k_theta,
                c_theta,
            } => {
                non_negative("hub inertia", inertia)?;
                non_negative("k_theta", k_theta)?;
                non_negative("c_theta", c_theta)?;
            }
        }
        for pm in &spec.point_masses {
            if pm.node > spec.elements {
                return Err(BeamError::invalid(
                    "point mass node",
                    pm.node,
                    format!("a node index from 0 to {} (the tip)", spec.elements),
                ));
            }
            non_negative("point mass", pm.mass)?;
            non_negative("point inertia", pm.inertia)?;
        }
        non_negative("rayleigh alpha_mass", spec.damping.alpha_mass)?;
        non_negative("rayleigh beta_stiffness", spec.damping.beta_stiffness)?;
        let element_length = spec.length / spec.elements as f64;
        let element =
            crate::ancf::AncfElement::new(element_length, spec.section.ea(), spec.section.ei());
        let tables = element.tangent_tables();
        Ok(BeamModel {
            spec,
            element_length,
            ancf: Box::new(AncfParts { element, tables }),
        })
    }

    /// The ANCF element of this mesh and its tangent tables.
    pub(crate) fn ancf_parts(&self) -> &AncfParts {
        &self.ancf
    }

    /// The parameters.
    pub fn spec(&self) -> &BeamSpec {
        &self.spec
    }
    /// Length L \[m\].
    pub fn length(&self) -> f64 {
        self.spec.length
    }
    /// Section.
    pub fn section(&self) -> &Section {
        &self.spec.section
    }
    /// Number of elements N.
    pub fn n_elements(&self) -> usize {
        self.spec.elements
    }
    /// Number of nodes N + 1.
    pub fn n_nodes(&self) -> usize {
        self.spec.elements + 1
    }
    /// DOFs per node: 3, or 4 for [`Kinematics::Ancf`].
    pub fn dofs_per_node(&self) -> usize {
        self.spec.kinematics.dofs_per_node()
    }
    /// Number of DOFs 3(N + 1) (ANCF: 4(N + 1)), constrained ones included.
    pub fn n_dofs(&self) -> usize {
        self.dofs_per_node() * self.n_nodes()
    }
    /// Half-bandwidth of the node-ordered system matrices (one element couples two nodes).
    pub fn half_bandwidth(&self) -> usize {
        2 * self.dofs_per_node() - 1
    }
    /// Number of constrained DOFs (the first ones, at the root).
    pub fn n_fixed(&self) -> usize {
        self.spec.root.n_fixed()
    }
    /// Number of free DOFs.
    pub fn n_free(&self) -> usize {
        self.n_dofs() - self.n_fixed()
    }
    /// Element length l = L/N \[m\].
    pub fn element_length(&self) -> f64 {
        self.element_length
    }
    /// Kinematic model.
    pub fn kinematics(&self) -> Kinematics {
        self.spec.kinematics
    }
    /// Root support.
    pub fn root(&self) -> RootSupport {
        self.spec.root
    }
    /// Undeformed x of node `i` \[m\].
    pub fn node_x(&self, i: usize) -> f64 {
        i as f64 * self.element_length
    }
    /// Index of the tip node.
    pub fn tip_node(&self) -> usize {
        self.spec.elements
    }
    /// Total mass of the beam ρAL \[kg\] (point masses excluded).
    pub fn beam_mass(&self) -> f64 {
        self.spec.section.rho_a() * self.spec.length
    }
    /// The same model with other kinematics.
    pub fn with_kinematics(&self, kinematics: Kinematics) -> Self {
        let mut m = self.clone();
        m.spec.kinematics = kinematics;
        m
    }
}

/// Nodal forces \[N\] and moments [N·m] in the global (x, y) frame, three entries per node
/// (fx, fy, m; for the 3-DOF elements one entry per DOF); dead loads (their direction does not
/// follow the deformation). On an ANCF node the moment does work on the node angle
/// θ = atan2(r′ᵧ, r′ₓ): its generalized force on the slope is m ∂θ/∂r′ = m (−r′ᵧ, r′ₓ)/|r′|²,
/// configuration dependent (its derivative enters the tangent). May be changed between steps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NodalLoads {
    values: Vec<f64>,
}

impl NodalLoads {
    /// Zero loads for `model`.
    pub fn zeros(model: &BeamModel) -> Self {
        NodalLoads {
            values: vec![0.0; 3 * model.n_nodes()],
        }
    }
    fn check_node(&self, node: usize) -> Result<(), BeamError> {
        if 3 * node + 2 < self.values.len() {
            Ok(())
        } else {
            Err(BeamError::invalid(
                "load node",
                node,
                format!("a node index from 0 to {}", self.values.len() / 3 - 1),
            ))
        }
    }
    /// Sets the force (fx, fy) \[N\] at `node`; NaN or infinite values are rejected.
    pub fn set_force(&mut self, node: usize, fx: f64, fy: f64) -> Result<(), BeamError> {
        self.check_node(node)?;
        self.values[3 * node] = finite("force x", fx)?;
        self.values[3 * node + 1] = finite("force y", fy)?;
        Ok(())
    }
    /// Sets the moment m [N·m] at `node` (at node 0 of a hub: the applied hub torque).
    pub fn set_moment(&mut self, node: usize, m: f64) -> Result<(), BeamError> {
        self.check_node(node)?;
        self.values[3 * node + 2] = finite("moment", m)?;
        Ok(())
    }
    /// Loads from a vector of one entry per DOF.
    pub(crate) fn from_values(values: Vec<f64>) -> Self {
        NodalLoads { values }
    }
    /// (1 − s) self + s other, entry by entry.
    pub fn lerp(&self, other: &NodalLoads, s: f64) -> Self {
        NodalLoads {
            values: self
                .values
                .iter()
                .zip(&other.values)
                .map(|(a, b)| a + (b - a) * s)
                .collect(),
        }
    }
    /// Zeroes every load.
    pub fn clear(&mut self) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
    }
    /// The load vector (one entry per DOF).
    pub fn as_slice(&self) -> &[f64] {
        &self.values
    }
    /// Scales every load by `s`.
    pub fn scaled(&self, s: f64) -> Self {
        NodalLoads {
            values: self.values.iter().map(|v| v * s).collect(),
        }
    }
    pub(crate) fn check(&self, model: &BeamModel) -> Result<(), BeamError> {
        if self.values.len() != 3 * model.n_nodes() {
            return Err(BeamError::invalid(
                "loads length",
                self.values.len(),
                format!("{} entries (3 per node)", 3 * model.n_nodes()),
            ));
        }
        for (i, v) in self.values.iter().enumerate() {
            if !v.is_finite() {
                return Err(BeamError::invalid(
                    format!("load at node {} ({})", i / 3, ["fx", "fy", "moment"][i % 3]),
                    v,
                    "a finite number",
                ));
            }
        }
        Ok(())
    }
}
