//! The ISO/TS 15066:2016 body model (Annex A) as validated data.
//!
//! The bundled table is `assets/safety/iso_ts_15066_2016.toml` (Table A.2 biomechanical limits,
//! Table A.3 effective masses and spring constants, the transient factor of A.3.2 and the
//! head/face prohibition of 5.5.5.4); its header cites the document, edition, table and clause of
//! every value, and `docs/safety.md` lists the transcriptions it was checked against. A user table
//! in the same format is loaded with [`BodyModel::from_toml_str`]; a missing field or a
//! non-positive limit is refused naming the region and the field.
//!
//! The accessors return SI units (N/m, Pa); the `*_n_per_mm` / `*_n_per_cm2` accessors return the
//! file's own numbers unchanged.

use serde::{Deserialize, Serialize};

use crate::SafetyError;

/// The bundled ISO/TS 15066:2016 table.
pub const BUNDLED_BODY_MODEL_TOML: &str =
    include_str!("../../../assets/safety/iso_ts_15066_2016.toml");

/// Pressure of 1 N/cm² in Pa.
pub const PA_PER_N_PER_CM2: f64 = 1.0e4;

/// Stiffness of 1 N/mm in N/m.
pub const N_PER_M_PER_N_PER_MM: f64 = 1.0e3;

/// Quasi-static (clamping) or transient (free impact) contact (ISO/TS 15066:2016, 5.5.5.4 and
/// Table A.2's two column groups).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactKind {
    /// The body region is clamped (e.g. against a wall): quasi-static limits of Table A.2, and the
    /// body does not recoil (its effective mass is infinite).
    QuasiStatic,
    /// The body region is free to recoil: transient limits (Table A.2 multipliers), the body's
    /// effective mass m_H of Table A.3.
    Transient,
}

/// Where a table comes from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Provenance {
    /// Document title.
    pub title: String,
    /// Edition and date.
    pub edition: String,
    /// The tables and clauses used.
    pub tables: String,
}

/// Whether, and with which factors, transient contact is permitted for a region.
#[derive(Debug, Clone, PartialEq)]
pub enum TransientRule {
    /// Transient contact is not permitted (head and face), with the clause that says so.
    NotPermitted {
        /// Clause of the standard, as given in the file.
        clause: String,
    },
    /// Transient limits are the quasi-static ones times these factors, unless an explicit value
    /// is given.
    Permitted {
        /// F_T: transient force = F_T × quasi-static force.
        force_multiplier: f64,
        /// P_T: transient pressure = P_T × quasi-static pressure.
        pressure_multiplier: f64,
        /// Explicit transient force limit \[N\], overriding the multiplier when present.
        max_force_n: Option<f64>,
    },
}

/// One of the specific body areas of Table A.2 (numbered 1–29 in the standard).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyArea {
    pub(crate) number: u32,
    pub(crate) name: String,
    pub(crate) max_pressure_n_per_cm2: f64,
    pub(crate) transient_max_pressure_n_per_cm2: Option<f64>,
}

impl BodyArea {
    /// Number of the area in the standard (1–29).
    pub fn number(&self) -> u32 {
        self.number
    }

    /// Name, e.g. `Forefinger pad D`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Quasi-static maximum permissible pressure p_s [N/cm²], as in the file (Table A.2).
    pub fn max_pressure_n_per_cm2(&self) -> f64 {
        self.max_pressure_n_per_cm2
    }

    /// Explicit transient pressure [N/cm²] if the file gives one.
    pub fn transient_max_pressure_n_per_cm2(&self) -> Option<f64> {
        self.transient_max_pressure_n_per_cm2
    }
}

/// One body region: Table A.3's K and m_H, Table A.2's force limit and its specific areas.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyRegion {
    pub(crate) key: String,
    pub(crate) name: String,
    pub(crate) spring_constant_n_per_mm: f64,
    pub(crate) effective_mass_kg: f64,
    pub(crate) max_force_n: f64,
    pub(crate) transient: TransientRule,
    pub(crate) source: String,
    pub(crate) areas: Vec<BodyArea>,
}

/// The force and pressure limits that apply to one contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Limits {
    /// Maximum permissible force \[N\].
    pub force: f64,
    /// Maximum permissible pressure \[Pa\], if a body area was named.
    pub pressure: Option<f64>,
}

impl BodyRegion {
    /// Key, e.g. `hands_and_fingers`.
    pub fn key(&self) -> &str {
        &self.key
    }

    /// Name as in the standard, e.g. `Hands and fingers`.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Effective spring constant K [N/mm], as in the file (Table A.3).
    pub fn spring_constant_n_per_mm(&self) -> f64 {
        self.spring_constant_n_per_mm
    }

    /// Effective spring constant k [N/m] (Table A.3, converted).
    pub fn spring_constant(&self) -> f64 {
        self.spring_constant_n_per_mm * N_PER_M_PER_N_PER_MM
    }

    /// Effective mass m_H \[kg\] (Table A.3).
    pub fn effective_mass_kg(&self) -> f64 {
        self.effective_mass_kg
    }

    /// Quasi-static maximum permissible force \[N\] (Table A.2).
    pub fn max_force_n(&self) -> f64 {
        self.max_force_n
    }

    /// The transient-contact rule.
    pub fn transient(&self) -> &TransientRule {
        &self.transient
    }

    /// Where the values come from (free text from the file).
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The specific body areas, in file order.
    pub fn areas(&self) -> &[BodyArea] {
        &self.areas
    }

    /// The area called `name` (case-insensitive), or an error listing the known areas.
    pub fn area(&self, name: &str) -> Result<&BodyArea, SafetyError> {
        self.areas
            .iter()
            .find(|a| a.name.eq_ignore_ascii_case(name))
            .ok_or_else(|| SafetyError::Unknown {
                what: "body area",
                name: name.to_string(),
                known: self
                    .areas
                    .iter()
                    .map(|a| a.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// The area with the lowest pressure limit (the conservative choice when the exact area of
    /// contact is not known).
    pub fn most_sensitive_area(&self) -> &BodyArea {
        self.areas
            .iter()
            .min_by(|a, b| {
                a.max_pressure_n_per_cm2
                    .total_cmp(&b.max_pressure_n_per_cm2)
            })
            .expect("a validated region has at least one area")
    }

    /// Maximum permissible force \[N\] for `kind`; an error citing the clause for transient
    /// contact where it is not permitted.
    pub fn force_limit(&self, kind: ContactKind) -> Result<f64, SafetyError> {
        match (kind, &self.transient) {
            (ContactKind::QuasiStatic, _) => Ok(self.max_force_n),
            (ContactKind::Transient, TransientRule::NotPermitted { clause }) => {
                Err(self.not_permitted(clause))
            }
            (
                ContactKind::Transient,
                TransientRule::Permitted {
                    force_multiplier,
                    max_force_n,
                    ..
                },
            ) => Ok(max_force_n.unwrap_or(force_multiplier * self.max_force_n)),
        }
    }

    /// Maximum permissible pressure \[Pa\] on `area` for `kind` (Table A.2 × P_T for transient
    /// contact, or the file's explicit transient value).
    pub fn pressure_limit(&self, area: &BodyArea, kind: ContactKind) -> Result<f64, SafetyError> {
        let n_per_cm2 = match (kind, &self.transient) {
            (ContactKind::QuasiStatic, _) => area.max_pressure_n_per_cm2,
            (ContactKind::Transient, TransientRule::NotPermitted { clause }) => {
                return Err(self.not_permitted(clause));
            }
            (
                ContactKind::Transient,
                TransientRule::Permitted {
                    pressure_multiplier,
                    ..
                },
            ) => area
                .transient_max_pressure_n_per_cm2
                .unwrap_or(pressure_multiplier * area.max_pressure_n_per_cm2),
        };
        Ok(n_per_cm2 * PA_PER_N_PER_CM2)
    }

    /// Force and (if `area` is given) pressure limits for `kind`.
    pub fn limits(
        &self,
        area: Option<&BodyArea>,
        kind: ContactKind,
    ) -> Result<Limits, SafetyError> {
        Ok(Limits {
            force: self.force_limit(kind)?,
            pressure: area.map(|a| self.pressure_limit(a, kind)).transpose()?,
        })
    }

    /// The effective human mass \[kg\] of this contact: m_H of Table A.3 for transient contact,
    /// +∞ for quasi-static (clamped) contact.
    pub fn human_mass(&self, kind: ContactKind) -> f64 {
        match kind {
            ContactKind::QuasiStatic => f64::INFINITY,
            ContactKind::Transient => self.effective_mass_kg,
        }
    }

    fn not_permitted(&self, clause: &str) -> SafetyError {
        SafetyError::ContactNotPermitted {
            region: self.name.clone(),
            clause: clause.to_string(),
        }
    }
}

/// A validated body model: its provenance and its regions.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyModel {
    pub(crate) provenance: Provenance,
    pub(crate) regions: Vec<BodyRegion>,
}

// The constructors from TOML (`BodyModel::iso_ts_15066_2016`, `BodyModel::from_toml_str`) are
// in body_model_file.rs, which reads the file into these types (the dependency goes one way).
impl BodyModel {
    /// Where the table comes from.
    pub fn provenance(&self) -> &Provenance {
        &self.provenance
    }

    /// All regions, in file order.
    pub fn regions(&self) -> &[BodyRegion] {
        &self.regions
    }

    /// The region with key or name `name` (case-insensitive), or an error listing the keys.
    pub fn region(&self, name: &str) -> Result<&BodyRegion, SafetyError> {
        self.regions
            .iter()
            .find(|r| r.key.eq_ignore_ascii_case(name) || r.name.eq_ignore_ascii_case(name))
            .ok_or_else(|| SafetyError::Unknown {
                what: "body region",
                name: name.to_string(),
                known: self
                    .regions
                    .iter()
                    .map(|r| r.key.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }

    /// Number of specific body areas over all regions (29 in the standard).
    pub fn area_count(&self) -> usize {
        self.regions.iter().map(|r| r.areas.len()).sum()
    }
}
