//! Parsing and validation of a body-model TOML file. Every field is read as optional so that a
//! missing one is reported with its region and name rather than as a bare serde message.

use serde::Deserialize;

use crate::SafetyError;
use crate::body_model::{
    BUNDLED_BODY_MODEL_TOML, BodyArea, BodyModel, BodyRegion, Provenance, TransientRule,
};

impl BodyModel {
    /// The bundled ISO/TS 15066:2016 table.
    pub fn iso_ts_15066_2016() -> Result<Self, SafetyError> {
        Self::from_toml_str(BUNDLED_BODY_MODEL_TOML)
    }

    /// Parses and validates a body-model table in the bundled format (see the header of
    /// `assets/safety/iso_ts_15066_2016.toml`).
    pub fn from_toml_str(text: &str) -> Result<Self, SafetyError> {
        parse_body_model(text)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawFile {
    document: Option<RawDocument>,
    #[serde(default)]
    region: Vec<RawRegion>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawDocument {
    title: Option<String>,
    edition: Option<String>,
    tables: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawRegion {
    key: Option<String>,
    name: Option<String>,
    spring_constant_n_per_mm: Option<f64>,
    effective_mass_kg: Option<f64>,
    max_force_n: Option<f64>,
    transient_permitted: Option<bool>,
    transient_force_multiplier: Option<f64>,
    transient_pressure_multiplier: Option<f64>,
    transient_max_force_n: Option<f64>,
    transient_not_permitted_clause: Option<String>,
    source: Option<String>,
    #[serde(default)]
    area: Vec<RawArea>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawArea {
    number: Option<u32>,
    name: Option<String>,
    max_pressure_n_per_cm2: Option<f64>,
    transient_max_pressure_n_per_cm2: Option<f64>,
}

/// Names the region in errors: its key, else its position.
struct Ctx(String);

impl Ctx {
    fn missing(&self, field: &str, allowed: &str) -> SafetyError {
        SafetyError::MissingField {
            region: self.0.clone(),
            field: field.to_string(),
            allowed: allowed.to_string(),
        }
    }

    fn invalid(&self, field: &str, value: String, allowed: &str) -> SafetyError {
        SafetyError::InvalidField {
            region: self.0.clone(),
            field: field.to_string(),
            value,
            allowed: allowed.to_string(),
        }
    }

    fn text(&self, field: &str, value: Option<String>) -> Result<String, SafetyError> {
        match value {
            Some(s) if !s.trim().is_empty() => Ok(s),
            Some(s) => Err(self.invalid(field, format!("{s:?}"), "must not be empty")),
            None => Err(self.missing(field, "a non-empty string")),
        }
    }

    fn positive(&self, field: &str, value: Option<f64>) -> Result<f64, SafetyError> {
        let v = value.ok_or_else(|| self.missing(field, "a finite number > 0"))?;
        self.check_positive(field, v)
    }

    fn optional_positive(
        &self,
        field: &str,
        value: Option<f64>,
    ) -> Result<Option<f64>, SafetyError> {
        value.map(|v| self.check_positive(field, v)).transpose()
    }

    fn check_positive(&self, field: &str, v: f64) -> Result<f64, SafetyError> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.invalid(
                field,
                flexrig_contact::validate::display(v),
                "must be a finite number > 0",
            ))
        }
    }
}

fn parse_body_model(text: &str) -> Result<BodyModel, SafetyError> {
    let raw: RawFile =
        toml::from_str(text).map_err(|e| SafetyError::BodyModelSyntax(e.to_string()))?;
    let doc_ctx = Ctx("[document]".into());
    let document = raw
        .document
        .ok_or_else(|| doc_ctx.missing("[document]", "a table with title, edition, tables"))?;
    let provenance = Provenance {
        title: doc_ctx.text("title", document.title)?,
        edition: doc_ctx.text("edition", document.edition)?,
        tables: doc_ctx.text("tables", document.tables)?,
    };
    if raw.region.is_empty() {
        return Err(SafetyError::BodyModelSyntax(
            "no [[region]] table: at least one body region is required".into(),
        ));
    }
    let mut regions = Vec::with_capacity(raw.region.len());
    for (index, r) in raw.region.into_iter().enumerate() {
        let region = parse_region(index, r)?;
        if regions.iter().any(|o: &BodyRegion| o.key == region.key) {
            return Err(Ctx(region.key.clone()).invalid(
                "key",
                format!("{:?}", region.key),
                "must be unique among the regions",
            ));
        }
        regions.push(region);
    }
    Ok(BodyModel {
        provenance,
        regions,
    })
}

fn parse_region(index: usize, r: RawRegion) -> Result<BodyRegion, SafetyError> {
    let ctx = Ctx(r.key.clone().unwrap_or_else(|| format!("region[{index}]")));
    let key = ctx.text("key", r.key)?;
    let name = ctx.text("name", r.name)?;
    let spring_constant_n_per_mm =
        ctx.positive("spring_constant_n_per_mm", r.spring_constant_n_per_mm)?;
    let effective_mass_kg = ctx.positive("effective_mass_kg", r.effective_mass_kg)?;
    let max_force_n = ctx.positive("max_force_n", r.max_force_n)?;
    let permitted = r
        .transient_permitted
        .ok_or_else(|| ctx.missing("transient_permitted", "true or false"))?;
    let transient = if permitted {
        if r.transient_not_permitted_clause.is_some() {
            return Err(ctx.invalid(
                "transient_not_permitted_clause",
                "(given)".into(),
                "only allowed with transient_permitted = false",
            ));
        }
        TransientRule::Permitted {
            force_multiplier: ctx
                .positive("transient_force_multiplier", r.transient_force_multiplier)?,
            pressure_multiplier: ctx.positive(
                "transient_pressure_multiplier",
                r.transient_pressure_multiplier,
            )?,
            max_force_n: ctx.optional_positive("transient_max_force_n", r.transient_max_force_n)?,
        }
    } else {
        for (field, given) in [
            ("transient_force_multiplier", r.transient_force_multiplier),
            (
                "transient_pressure_multiplier",
                r.transient_pressure_multiplier,
            ),
            ("transient_max_force_n", r.transient_max_force_n),
        ] {
            if let Some(v) = given {
                return Err(ctx.invalid(
                    field,
                    flexrig_contact::validate::display(v),
                    "only allowed with transient_permitted = true",
                ));
            }
        }
        TransientRule::NotPermitted {
            clause: ctx.text(
                "transient_not_permitted_clause",
                r.transient_not_permitted_clause,
            )?,
        }
    };
    let source = ctx.text("source", r.source)?;
    if r.area.is_empty() {
        return Err(ctx.missing("area", "at least one [[region.area]] with a pressure limit"));
    }
    let areas = r
        .area
        .into_iter()
        .enumerate()
        .map(|(i, a)| parse_area(&ctx, i, a, permitted))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(BodyRegion {
        key,
        name,
        spring_constant_n_per_mm,
        effective_mass_kg,
        max_force_n,
        transient,
        source,
        areas,
    })
}

fn parse_area(ctx: &Ctx, i: usize, a: RawArea, permitted: bool) -> Result<BodyArea, SafetyError> {
    let f = |field: &str| format!("area[{i}].{field}");
    let number = a
        .number
        .ok_or_else(|| ctx.missing(&f("number"), "the area's number in the standard"))?;
    let name = ctx.text(&f("name"), a.name)?;
    let max_pressure_n_per_cm2 =
        ctx.positive(&f("max_pressure_n_per_cm2"), a.max_pressure_n_per_cm2)?;
    let transient_max_pressure_n_per_cm2 = ctx.optional_positive(
        &f("transient_max_pressure_n_per_cm2"),
        a.transient_max_pressure_n_per_cm2,
    )?;
    if !permitted && let Some(v) = transient_max_pressure_n_per_cm2 {
        return Err(ctx.invalid(
            &f("transient_max_pressure_n_per_cm2"),
            flexrig_contact::validate::display(v),
            "only allowed with transient_permitted = true",
        ));
    }
    Ok(BodyArea {
        number,
        name,
        max_pressure_n_per_cm2,
        transient_max_pressure_n_per_cm2,
    })
}
