//! The materials file (`assets/materials.toml`): the paper's fitted Hertz materials with their
//! block masses, and the dome radius. Parsed with serde and validated; errors name the field path
//! (e.g. `material.abs.n`).

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::{ContactError, Hertz, validate};

/// The materials file shipped with flexrig (paper §III-B).
pub const BUNDLED_MATERIALS_TOML: &str = include_str!("../../../assets/materials.toml");

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialsFile {
    dome: DomeSpec,
    material: BTreeMap<String, MaterialSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct DomeSpec {
    radius_m: f64,
    #[serde(default)]
    source: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MaterialSpec {
    description: String,
    k: f64,
    n: f64,
    block_mass_kg: f64,
    #[serde(default)]
    source: String,
}

/// A skinned block material: its Hertz fit against the dome and the block's mass.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Key in the materials file, e.g. `skinned_aluminium`.
    pub name: String,
    /// Human-readable description.
    pub description: String,
    /// Fitted Hertz law f = k δ^n (k in N/m^n).
    pub hertz: Hertz,
    /// Mass of the block \[kg\].
    pub block_mass_kg: f64,
    /// Where the numbers come from.
    pub source: String,
}

/// A validated set of materials and the dome radius.
#[derive(Debug, Clone, PartialEq)]
pub struct Materials {
    dome_radius_m: f64,
    dome_source: String,
    materials: Vec<Material>,
}

impl Materials {
    /// The bundled materials (paper §III-B).
    pub fn bundled() -> Result<Self, ContactError> {
        Self::from_toml_str(BUNDLED_MATERIALS_TOML)
    }

    /// Parses and validates a materials file.
    pub fn from_toml_str(text: &str) -> Result<Self, ContactError> {
        let file: MaterialsFile =
            toml::from_str(text).map_err(|e| ContactError::MaterialsSyntax(e.to_string()))?;
        let dome_radius_m = validate::positive("dome.radius_m", file.dome.radius_m)?;
        let materials = file
            .material
            .into_iter()
            .map(|(name, spec)| {
                let field = |f: &str| format!("material.{name}.{f}");
                Ok(Material {
                    hertz: Hertz::named(spec.k, spec.n, &field("k"), &field("n"))?,
                    block_mass_kg: validate::positive(&field("block_mass_kg"), spec.block_mass_kg)?,
                    description: spec.description,
                    source: spec.source,
                    name,
                })
            })
            .collect::<Result<Vec<_>, ContactError>>()?;
        if materials.is_empty() {
            return Err(ContactError::MaterialsSyntax(
                "no [material.NAME] table: at least one material is required".into(),
            ));
        }
        Ok(Materials {
            dome_radius_m,
            dome_source: file.dome.source,
            materials,
        })
    }

    /// Dome radius \[m\].
    pub fn dome_radius_m(&self) -> f64 {
        self.dome_radius_m
    }

    /// Where the dome radius comes from.
    pub fn dome_source(&self) -> &str {
        &self.dome_source
    }

    /// All materials, sorted by name.
    pub fn all(&self) -> &[Material] {
        &self.materials
    }

    /// The material called `name`, or an error listing the known names.
    pub fn get(&self, name: &str) -> Result<&Material, ContactError> {
        self.materials
            .iter()
            .find(|m| m.name == name)
            .ok_or_else(|| ContactError::UnknownMaterial {
                name: name.to_string(),
                known: self
                    .materials
                    .iter()
                    .map(|m| m.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}
