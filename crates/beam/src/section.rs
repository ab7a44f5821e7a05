//! Cross-section properties of the planar beam.

use serde::{Deserialize, Serialize};

use crate::BeamError;
use crate::error::positive;

/// A linear-elastic isotropic material.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MaterialSpec", into = "MaterialSpec")]
pub struct Material {
    youngs: f64,
    density: f64,
}

#[derive(Serialize, Deserialize)]
struct MaterialSpec {
    youngs: f64,
    density: f64,
}

impl TryFrom<MaterialSpec> for Material {
    type Error = BeamError;
    fn try_from(s: MaterialSpec) -> Result<Self, BeamError> {
        Material::new(s.youngs, s.density)
    }
}

impl From<Material> for MaterialSpec {
    fn from(m: Material) -> Self {
        MaterialSpec {
            youngs: m.youngs,
            density: m.density,
        }
    }
}

impl Material {
    /// Young's modulus `youngs` E \[Pa\] and mass density `density` ρ [kg/m³], both finite and > 0.
    pub fn new(youngs: f64, density: f64) -> Result<Self, BeamError> {
        Ok(Material {
            youngs: positive("youngs", youngs)?,
            density: positive("density", density)?,
        })
    }
    /// Young's modulus E \[Pa\].
    pub fn youngs(&self) -> f64 {
        self.youngs
    }
    /// Density ρ [kg/m³].
    pub fn density(&self) -> f64 {
        self.density
    }
}

/// Section properties: axial stiffness EA \[N\], bending stiffness EI [N·m²] and mass per length
/// ρA [kg/m]. Rotary inertia of the section is neglected (Euler–Bernoulli).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "SectionSpec", into = "SectionSpec")]
pub struct Section {
    ea: f64,
    ei: f64,
    rho_a: f64,
}

#[derive(Serialize, Deserialize)]
struct SectionSpec {
    ea: f64,
    ei: f64,
    rho_a: f64,
}

impl TryFrom<SectionSpec> for Section {
    type Error = BeamError;
    fn try_from(s: SectionSpec) -> Result<Self, BeamError> {
        Section::from_stiffness(s.ea, s.ei, s.rho_a)
    }
}

impl From<Section> for SectionSpec {
    fn from(s: Section) -> Self {
        SectionSpec {
            ea: s.ea,
            ei: s.ei,
            rho_a: s.rho_a,
        }
    }
}

impl Section {
    /// A solid rectangle of `width` w \[m\] and `thickness` t \[m\] bending in the thickness
    /// direction: A = w t, I = w t³/12, EA = E A, EI = E I, ρA = ρ w t.
    pub fn rectangular(material: &Material, width: f64, thickness: f64) -> Result<Self, BeamError> {
        let w = positive("width", width)?;
        let t = positive("thickness", thickness)?;
        let area = w * t;
        let inertia = w * t * t * t / 12.0;
        Section::from_stiffness(
            material.youngs * area,
            material.youngs * inertia,
            material.density * area,
        )
    }

    /// Section from `ea` EA \[N\], `ei` EI [N·m²] and `rho_a` ρA [kg/m], all finite and > 0.
    pub fn from_stiffness(ea: f64, ei: f64, rho_a: f64) -> Result<Self, BeamError> {
        Ok(Section {
            ea: positive("ea", ea)?,
            ei: positive("ei", ei)?,
            rho_a: positive("rho_a", rho_a)?,
        })
    }
    /// Axial stiffness EA \[N\].
    pub fn ea(&self) -> f64 {
        self.ea
    }
    /// Bending stiffness EI [N·m²].
    pub fn ei(&self) -> f64 {
        self.ei
    }
    /// Mass per unit length ρA [kg/m].
    pub fn rho_a(&self) -> f64 {
        self.rho_a
    }
}
