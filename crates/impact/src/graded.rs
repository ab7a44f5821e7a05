//! The CL link on a mesh graded towards the tip, as dense K and M for [`TipModes`].
//!
//! A short impact on the payload bends only a tip zone of length ℓ ≈ (EI/ρA)^{1/4} √t_c (t_c the
//! payload's contact time): for a soft link and a light payload that is L/60 to L/300. A uniform
//! mesh fine enough there wastes hundreds of elements on the rest of the beam, which moves in its
//! lowest modes only. The graded mesh puts elements of ℓ/`zone_elements` at the tip, grows them by
//! `ratio` towards the root up to L/`min_elements`, and stays uniform from there. Elements are
//! flexrig-beam's Hermite cubics ([`flexrig_beam::element`]: the bending block of the linear
//! stiffness and of the consistent mass), so a uniform grading is exactly flexrig-beam's model.

use faer::Mat;
use flexrig_beam::element::{consistent_inertia, linear_stiffness};
use nalgebra::Vector6;

use crate::ImpactError;
use crate::setup::{FreeMassImpact, Joint};
use crate::tip_modes::TipModes;

/// How the CL link is meshed and how many of its modes are kept.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct GradedMesh {
    /// Elements across the tip zone ℓ = (EI/ρA)^{1/4} √t_c.
    pub zone_elements: f64,
    /// Growth of the element length from one element to the next towards the root, ≥ 1.
    pub ratio: f64,
    /// The elements are at most L/`min_elements` long.
    pub min_elements: usize,
    /// Modes above `mode_cut` × π/t_c are left to the static residual (t_c: the payload's contact
    /// time); `f64::INFINITY` keeps every mode.
    pub mode_cut: f64,
}

impl GradedMesh {
    /// 8 elements across the tip zone, growing by 1.15, at most L/24, modes up to 60 π/t_c.
    pub const DEFAULT: GradedMesh = GradedMesh {
        zone_elements: 8.0,
        ratio: 1.15,
        min_elements: 24,
        mode_cut: 60.0,
    };

    /// Checks the mesh parameters; the error names the field.
    pub fn validate(&self) -> Result<(), ImpactError> {
        if !(self.zone_elements.is_finite() && (0.5..=1000.0).contains(&self.zone_elements)) {
            return Err(ImpactError::invalid(
                "zone_elements",
                self.zone_elements,
                "must lie in [0.5, 1000]",
            ));
        }
        if !(self.ratio.is_finite() && (1.0..=2.0).contains(&self.ratio)) {
            return Err(ImpactError::invalid(
                "ratio",
                self.ratio,
                "must lie in [1, 2]",
            ));
        }
        if !(2..=1000).contains(&self.min_elements) {
            return Err(ImpactError::invalid(
                "min_elements",
                self.min_elements,
                "must lie in [2, 1000]",
            ));
        }
        if !(self.mode_cut >= 1.0) {
            return Err(ImpactError::invalid(
                "mode_cut",
                self.mode_cut,
                "must be ≥ 1 (or infinite: every mode)",
            ));
        }
        Ok(())
    }

    /// Element lengths from the root to the tip \[m\] for the link of `setup`.
    pub fn element_lengths(&self, setup: &FreeMassImpact) -> Result<Vec<f64>, ImpactError> {
        self.validate()?;
        let link = setup.link;
        let l = link.length;
        let zone = (link.ei() / link.rho_a()).powf(0.25) * setup.payload_contact_time().sqrt();
        let h_max = l / self.min_elements as f64;
        let mut h = (zone / self.zone_elements).min(h_max);
        // from the tip towards the root
        let mut lengths = Vec::new();
        let mut covered = 0.0;
        while covered + h < l {
            lengths.push(h);
            covered += h;
            h = (h * self.ratio).min(h_max);
            if lengths.len() > MAX_ELEMENTS {
                return Err(ImpactError::invalid(
                    "zone_elements",
                    self.zone_elements,
                    format!(
                        "a mesh of at most {MAX_ELEMENTS} elements: fewer elements per zone or a larger ratio"
                    ),
                ));
            }
        }
        // the rest, split so that no element is shorter than half its neighbour
        let rest = l - covered;
        if rest > 0.5 * lengths.last().copied().unwrap_or(h) || lengths.is_empty() {
            lengths.push(rest);
        } else if let Some(last) = lengths.last_mut() {
            *last += rest;
        }
        lengths.reverse();
        Ok(lengths)
    }
}

/// Largest graded mesh (a dense eigen-solve of 2 × that many DOFs).
pub const MAX_ELEMENTS: usize = 1500;

/// A linear structure's dense matrices over its free DOFs, with its struck DOF and its velocity at
/// t = 0.
#[derive(Debug, Clone)]
pub struct LinkMatrices {
    /// Stiffness K [N/m, N·m/rad].
    pub k: Mat<f64>,
    /// Mass M [kg, kg·m²].
    pub m: Mat<f64>,
    /// Index of the tip's transverse DOF.
    pub tip: usize,
    /// Velocity at t = 0 [m/s, rad/s].
    pub v0: Vec<f64>,
}

/// The CL link's transverse K and M (DOFs v, θ per node, the root's v and θ held; a free hub
/// frees θ₀ and adds the rotor's inertia there), the tip's DOF, and the link's velocity at t = 0
/// (a free hub: rigid rotation with the tip at −v0 towards the head).
pub fn cl_matrices(setup: &FreeMassImpact, lengths: &[f64]) -> Result<LinkMatrices, ImpactError> {
    let link = setup.link;
    let (ei, rho_a) = (link.ei(), link.rho_a());
    let nodes = lengths.len() + 1;
    let n_all = 2 * nodes;
    let mut k = Mat::<f64>::zeros(n_all, n_all);
    let mut m = Mat::<f64>::zeros(n_all, n_all);
    const BENDING: [usize; 4] = [1, 2, 4, 5];
    for (e, &le) in lengths.iter().enumerate() {
        let ke = linear_stiffness(le, 1.0, ei);
        let me = consistent_inertia(le, rho_a, [0.0; 2], [0.0; 2], &Vector6::zeros(), false).mass;
        for (a, &ia) in BENDING.iter().enumerate() {
            for (b, &ib) in BENDING.iter().enumerate() {
                k[(2 * e + a, 2 * e + b)] += ke[(ia, ib)];
                m[(2 * e + a, 2 * e + b)] += me[(ia, ib)];
            }
        }
    }
    let tip_all = 2 * (nodes - 1);
    m[(tip_all, tip_all)] += link.m_e;
    // held: drop v₀ and θ₀; free hub: drop v₀, keep θ₀ with the rotor's inertia
    let first = match setup.joint {
        Joint::Held => 2,
        Joint::FreeHub { rotor_inertia } => {
            m[(1, 1)] += rotor_inertia;
            1
        }
    };
    let n = n_all - first;
    let k = Mat::from_fn(n, n, |i, j| k[(i + first, j + first)]);
    let m = Mat::from_fn(n, n, |i, j| m[(i + first, j + first)]);
    let mut v0 = vec![0.0; n];
    if let Joint::FreeHub { .. } = setup.joint {
        let omega = -setup.v0 / link.length;
        let mut x = 0.0;
        for node in 0..nodes {
            for (c, value) in [(0, omega * x), (1, omega)] {
                let i = 2 * node + c;
                if i >= first {
                    v0[i - first] = value;
                }
            }
            if node < lengths.len() {
                x += lengths[node];
            }
        }
    }
    Ok(LinkMatrices {
        k,
        m,
        tip: tip_all - first,
        v0,
    })
}

/// The CL link's [`TipModes`] on the graded mesh.
pub fn cl_tip_modes(setup: &FreeMassImpact, mesh: &GradedMesh) -> Result<TipModes, ImpactError> {
    let lengths = mesh.element_lengths(setup)?;
    let LinkMatrices { k, m, tip, v0 } = cl_matrices(setup, &lengths)?;
    let cut = mesh.mode_cut * std::f64::consts::PI / setup.payload_contact_time();
    let link = setup.link;
    let shift = link.ei() / (link.rho_a() * link.length.powi(4));
    TipModes::from_matrices(&k, &m, tip, &v0, cut, shift)
}
