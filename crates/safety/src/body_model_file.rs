//! Parsing and validation of a body-model TOML file. Every field is read as optional so that a
//! missing one is reported with its region and name rather than as a bare serde message.

use serde::Deserialize;
use toml::Spanned;

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
    key: Option<Spanned<String>>,
    name: Option<Spanned<String>>,
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
    name: Option<Spanned<String>>,
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
            Some(s) => Err(self.invalid(field, quoted(&s), "must not be empty")),
            None => Err(self.missing(field, "a non-empty string")),
        }
    }

    fn positive(&self, field: &str, value: Option<f64>) -> Result<f64, SafetyError> {
        let (lo, hi, unit) = range_of(field);
        let v = value.ok_or_else(|| {
            self.missing(
                field,
                &flexrig_contact::validate::interval_in(unit, lo, hi).replacen(
                    "must lie in",
                    "a number in",
                    1,
                ),
            )
        })?;
        self.check_positive(field, v)
    }

    fn optional_positive(
        &self,
        field: &str,
        value: Option<f64>,
    ) -> Result<Option<f64>, SafetyError> {
        value.map(|v| self.check_positive(field, v)).transpose()
    }

    /// A limit or constant within its field's range ([`range_of`]).
    fn check_positive(&self, field: &str, v: f64) -> Result<f64, SafetyError> {
        let (lo, hi, unit) = range_of(field);
        if v.is_finite() && (lo..=hi).contains(&v) {
            Ok(v)
        } else {
            Err(self.invalid(
                field,
                flexrig_contact::validate::display(v),
                &flexrig_contact::validate::interval_in(unit, lo, hi),
            ))
        }
    }

    /// A name or key with its line: text without control characters (a line break or a tab in
    /// a name would break the reports and tables it is printed in).
    fn spanned_text(
        &self,
        field: &str,
        value: Option<Spanned<String>>,
        source: &str,
    ) -> Result<(String, usize), SafetyError> {
        let Some(value) = value else {
            return Err(self.missing(field, "a non-empty string"));
        };
        let line = line_of(source, value.span().start);
        let text = value.into_inner();
        if text.trim().is_empty() {
            return Err(self.invalid(
                field,
                format!("{} (line {line})", quoted(&text)),
                "must not be empty",
            ));
        }
        if text.chars().any(char::is_control) || text.chars().count() > MAX_NAME_CHARS {
            return Err(self.invalid(
                field,
                format!("{} (line {line})", quoted(&text)),
                &format!(
                    "a name on one line of at most {MAX_NAME_CHARS} characters, without line \
                     breaks, tabs or other control characters"
                ),
            ));
        }
        Ok((text, line))
    }
}

/// Longest key or name, characters.
const MAX_NAME_CHARS: usize = 120;

/// The allowed range (lo, hi, unit) of a numeric field of the body model. Wide around the
/// standard's own values (ISO/TS 15066:2016 Table A.2: forces 65–220 N, pressures 110–450 N/cm²,
/// transient factor 2; Table A.3: K 10–150 N/mm, m_H 0.6–40 kg), so a user's table of another
/// body or a stricter company limit passes, while a denormal or absurd value (a limit of 1e-310 N
/// reads as "unlimited" to the formulas) is refused.
fn range_of(field: &str) -> (f64, f64, &'static str) {
    let leaf = field.rsplit('.').next().unwrap_or(field);
    match leaf {
        "spring_constant_n_per_mm" => (1e-2, 1e5, "N/mm"),
        "effective_mass_kg" => (1e-3, 1e4, "kg"),
        "max_force_n" | "transient_max_force_n" => (1e-2, 1e6, "N"),
        "max_pressure_n_per_cm2" | "transient_max_pressure_n_per_cm2" => (1e-2, 1e6, "N/cm²"),
        _ => (0.1, 100.0, ""),
    }
}

/// The 1-based line of byte `offset` in `source`.
fn line_of(source: &str, offset: usize) -> usize {
    source
        .as_bytes()
        .iter()
        .take(offset)
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// A name quoted for a message: in double quotes, control characters and invisible format
/// characters written as their code (U+000A), never as Rust escapes.
pub(crate) fn quoted(text: &str) -> String {
    let mut s = String::from("\"");
    for c in text.chars().take(MAX_NAME_CHARS + 1) {
        if c.is_control()
            || matches!(c, '\u{200b}'..='\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{feff}')
        {
            s.push_str(&format!("U+{:04X}", c as u32));
        } else {
            s.push(c);
        }
    }
    if text.chars().count() > MAX_NAME_CHARS {
        s.push('…');
    }
    s.push('"');
    s
}

/// A region key is an identifier (letters, digits, `_`, `-`): it is typed after `--region`,
/// written unquoted in the safe-speed map's CSV and used in file names.
fn check_key(ctx: &Ctx, key: &str, line: usize) -> Result<(), SafetyError> {
    if key
        .chars()
        .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    {
        return Ok(());
    }
    Err(ctx.invalid(
        "key",
        format!("{} (line {line})", quoted(key)),
        "letters, digits, '_' and '-' only (the key is typed after --region and written in \
         tables); put the readable name in name",
    ))
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
    let mut regions: Vec<BodyRegion> = Vec::with_capacity(raw.region.len());
    // every key and name a region is found by (`--region` takes either, in any case), with its line
    let mut seen: Vec<(String, usize)> = Vec::new();
    for (index, r) in raw.region.into_iter().enumerate() {
        let (region, key_line, name_line) = parse_region(index, r, text)?;
        let ctx = Ctx(region.key.clone());
        for (field, word, line) in [
            ("key", &region.key, key_line),
            ("name", &region.name, name_line),
        ] {
            if let Some((_, first)) = seen.iter().find(|(w, _)| w.eq_ignore_ascii_case(word)) {
                // a region's name may equal its own key (bundled: not the case, but harmless)
                if field == "name" && word.eq_ignore_ascii_case(&region.key) && *first == key_line {
                    continue;
                }
                return Err(ctx.invalid(
                    field,
                    format!("{} (line {line})", quoted(word)),
                    &format!(
                        "must differ from every other region's key and name (line {first} \
                         has it; --region finds a region by either, ignoring case)"
                    ),
                ));
            }
        }
        seen.push((region.key.clone(), key_line));
        seen.push((region.name.clone(), key_line));
        regions.push(region);
    }
    Ok(BodyModel {
        provenance,
        regions,
    })
}

fn parse_region(
    index: usize,
    r: RawRegion,
    file: &str,
) -> Result<(BodyRegion, usize, usize), SafetyError> {
    let ctx = Ctx(r
        .key
        .as_ref()
        .map(|k| k.get_ref().clone())
        .filter(|k| {
            !k.is_empty()
                && k.len() <= MAX_NAME_CHARS
                && k.chars()
                    .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
        })
        .unwrap_or_else(|| format!("region[{index}]")));
    let (key, key_line) = ctx.spanned_text("key", r.key, file)?;
    check_key(&ctx, &key, key_line)?;
    let (name, name_line) = ctx.spanned_text("name", r.name, file)?;
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
    let mut areas: Vec<BodyArea> = Vec::with_capacity(r.area.len());
    let mut lines: Vec<usize> = Vec::with_capacity(r.area.len());
    for (i, a) in r.area.into_iter().enumerate() {
        let (area, line) = parse_area(&ctx, i, a, permitted, file)?;
        // --area picks an area by name, ignoring case: two of one name would make it take the
        // first silently
        if let Some(j) = areas
            .iter()
            .position(|o| o.name.eq_ignore_ascii_case(&area.name))
        {
            return Err(ctx.invalid(
                &format!("area[{i}].name"),
                format!("{} (line {line})", quoted(&area.name)),
                &format!(
                    "must differ from the other areas' names of the region (area[{j}] on line \
                     {} has it; --area finds an area by name, ignoring case)",
                    lines[j]
                ),
            ));
        }
        areas.push(area);
        lines.push(line);
    }
    let region = BodyRegion {
        key,
        name,
        spring_constant_n_per_mm,
        effective_mass_kg,
        max_force_n,
        transient,
        source,
        areas,
    };
    Ok((region, key_line, name_line))
}

fn parse_area(
    ctx: &Ctx,
    i: usize,
    a: RawArea,
    permitted: bool,
    source: &str,
) -> Result<(BodyArea, usize), SafetyError> {
    let f = |field: &str| format!("area[{i}].{field}");
    let number = a
        .number
        .ok_or_else(|| ctx.missing(&f("number"), "the area's number in the standard"))?;
    let (name, line) = ctx.spanned_text(&f("name"), a.name, source)?;
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
    Ok((
        BodyArea {
            number,
            name,
            max_pressure_n_per_cm2,
            transient_max_pressure_n_per_cm2,
        },
        line,
    ))
}
