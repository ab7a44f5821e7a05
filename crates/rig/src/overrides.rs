//! Scene overrides by dotted path: `robot.payload_kg=0.2`, `operator.start.release_angle_deg=45`,
//! `robot.design=cl`. Applied to the scene's TOML before it is parsed and validated, so an
//! overridden value is checked exactly like one in the file; an error names the path.

use crate::RigError;

/// One `PATH=VALUE` override.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// Dotted path of the field, e.g. `operator.start.release_angle_deg`.
    pub path: String,
    /// The value (TOML: a number, a boolean, a quoted string, an inline table or array; a bare
    /// word is taken as a string).
    pub value: toml::Value,
}

/// Most characters of an override quoted in an error.
const QUOTE_LIMIT: usize = 120;

/// Most levels of a dotted override path. The scene's deepest field is three levels down
/// (`operator.start.release_angle_deg`); the bound keeps a hostile path from building tables
/// deep enough to exhaust the stack or the memory.
pub const MAX_PATH_DEPTH: usize = 8;

/// Most characters of an override path.
pub const MAX_PATH_LENGTH: usize = 256;

/// Most levels of nested arrays and tables in an override's value (a scene value is at most a
/// table of arrays, two levels).
pub const MAX_VALUE_DEPTH: usize = 8;

fn quoted(text: &str) -> String {
    if text.chars().count() <= QUOTE_LIMIT {
        text.to_string()
    } else {
        format!("{}…", text.chars().take(QUOTE_LIMIT).collect::<String>())
    }
}

fn bad(path: &str, value: &str, allowed: &str) -> RigError {
    RigError::InvalidScene {
        field: path.to_string(),
        value: quoted(&crate::format_message::compact_numbers(value)),
        allowed: allowed.to_string(),
    }
}

impl Override {
    /// Parses `PATH=VALUE`.
    pub fn parse(text: &str) -> Result<Self, RigError> {
        let Some((path, value)) = text.split_once('=') else {
            return Err(bad(
                "--set",
                text,
                "must be PATH=VALUE, e.g. robot.payload_kg=0.2",
            ));
        };
        let path = path.trim();
        check_path_size(path)?;
        let valid_segment =
            |s: &str| !s.is_empty() && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        if !path.split('.').all(valid_segment) {
            return Err(bad(
                "--set",
                text,
                "the path must be dotted field names, e.g. operator.start.release_angle_deg",
            ));
        }
        Ok(Override {
            path: path.to_string(),
            value: parse_value(value.trim()),
        })
    }

    /// `PATH=VALUE` with a value already in hand.
    pub fn new(path: &str, value: toml::Value) -> Self {
        Override {
            path: path.to_string(),
            value,
        }
    }
}

/// Refuses a path longer than [`MAX_PATH_LENGTH`] characters or deeper than
/// [`MAX_PATH_DEPTH`] levels, naming the path (quoted, shortened).
pub fn check_path_size(path: &str) -> Result<(), RigError> {
    let levels = path.split('.').count();
    if path.chars().count() > MAX_PATH_LENGTH || levels > MAX_PATH_DEPTH {
        return Err(bad(
            "--set",
            path,
            &format!(
                "the path has {levels} levels and {} characters; a scene field is at most \
                 {MAX_PATH_DEPTH} levels and {MAX_PATH_LENGTH} characters deep, e.g. \
                 operator.start.release_angle_deg",
                path.chars().count()
            ),
        ));
    }
    Ok(())
}

/// The nesting depth of `value` (a scalar is 0, an array or table of scalars 1), counted
/// without recursion and no further than `limit + 1`.
pub fn value_depth(value: &toml::Value, limit: usize) -> usize {
    let mut deepest = 0;
    let mut stack = vec![(value, 0usize)];
    while let Some((v, depth)) = stack.pop() {
        let children: Box<dyn Iterator<Item = &toml::Value>> = match v {
            toml::Value::Array(items) => Box::new(items.iter()),
            toml::Value::Table(t) => Box::new(t.values()),
            _ => continue,
        };
        deepest = deepest.max(depth + 1);
        if deepest > limit {
            return deepest;
        }
        stack.extend(children.map(|c| (c, depth + 1)));
    }
    deepest
}

/// Refuses an override whose path or value nests deeper than the bounds, naming its path.
fn check_size(path: &str, value: &toml::Value) -> Result<(), RigError> {
    check_path_size(path)?;
    if value_depth(value, MAX_VALUE_DEPTH) > MAX_VALUE_DEPTH {
        return Err(bad(
            path,
            "(a nested value)",
            &format!(
                "the value nests arrays or tables more than {MAX_VALUE_DEPTH} levels deep; a \
                 scene value is a number, a string, a boolean, or a table or array of them"
            ),
        ));
    }
    Ok(())
}

/// A TOML value from its text; a bare word that is not TOML is a string.
pub fn parse_value(text: &str) -> toml::Value {
    toml::from_str::<toml::Table>(&format!("v = {text}"))
        .ok()
        .and_then(|mut t| t.remove("v"))
        .unwrap_or_else(|| toml::Value::String(text.to_string()))
}

/// Sets `value` at the dotted `path` of `table`, creating tables on the way where a section or
/// an optional field is absent; a path that runs through a non-table value is an error naming
/// the path.
fn set(table: &mut toml::Table, path: &str, value: toml::Value) -> Result<(), RigError> {
    check_size(path, &value)?;
    let mut segments: Vec<&str> = path.split('.').collect();
    let last = segments.pop().expect("a parsed path has a segment");
    let mut current = table;
    let mut walked = String::new();
    for segment in segments {
        if !walked.is_empty() {
            walked.push('.');
        }
        walked.push_str(segment);
        let entry = current
            .entry(segment.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        current = match entry {
            toml::Value::Table(t) => t,
            other => {
                return Err(bad(
                    path,
                    &other.to_string(),
                    &format!("{walked} is a value, not a section: no field below it"),
                ));
            }
        };
    }
    current.insert(last.to_string(), value);
    Ok(())
}

/// The scene text `text` with `overrides` applied, in order. The result is TOML text for
/// [`crate::Scene::from_toml_str`]; a value of the wrong type or an unknown field is reported
/// there, and [`scene_with_overrides`] names the override that caused it.
pub fn apply(text: &str, overrides: &[Override]) -> Result<String, RigError> {
    if overrides.is_empty() {
        return Ok(text.to_string());
    }
    let mut table: toml::Table = toml::from_str(text).map_err(|e| {
        RigError::SceneSyntax(format!(
            "{} (before the overrides)",
            crate::format_message::plain(e.message().trim())
        ))
    })?;
    for o in overrides {
        set(&mut table, &o.path, o.value.clone())?;
    }
    Ok(toml::to_string(&table).expect("a TOML table serialises"))
}

/// Parses `text` with `overrides` and validates the scene; an error caused by an override names
/// its path and value.
pub fn scene_with_overrides(
    text: &str,
    overrides: &[Override],
    materials: &flexrig_contact::Materials,
) -> Result<crate::Scene, RigError> {
    if overrides.is_empty() {
        return crate::Scene::from_toml_str(text, materials);
    }
    let base: toml::Table = toml::from_str(text).map_err(|e| {
        // the file itself is broken: report it with its line
        match crate::Scene::from_toml_str(text, materials) {
            Err(syntax) => syntax,
            Ok(_) => RigError::SceneSyntax(crate::format_message::plain(e.message().trim())),
        }
    })?;
    scene_from_table(&base, overrides, materials)
}

/// The scene of the parsed base `table` with `overrides` applied (no text round trip: the fast
/// path of a sweep); an error caused by an override names its path and value.
pub fn scene_from_table(
    base: &toml::Table,
    overrides: &[Override],
    materials: &flexrig_contact::Materials,
) -> Result<crate::Scene, RigError> {
    let mut table = base.clone();
    for o in overrides {
        set(&mut table, &o.path, o.value.clone())?;
    }
    match parse_table(table, materials) {
        Ok(scene) => Ok(scene),
        Err(e @ RigError::InvalidScene { .. }) => Err(e),
        Err(e) => {
            // A format error (type, unknown field): name the first override that causes it on
            // its own, if the base is fine without it.
            if parse_table(base.clone(), materials).is_err() {
                return Err(e);
            }
            for o in overrides {
                let mut single = base.clone();
                set(&mut single, &o.path, o.value.clone())?;
                if let Err(RigError::SceneSyntax(message)) = parse_table(single, materials) {
                    return Err(bad(
                        &o.path,
                        &o.value.to_string(),
                        &format!("not accepted by the scene format: {message}"),
                    ));
                }
            }
            Err(e)
        }
    }
}

fn parse_table(
    table: toml::Table,
    materials: &flexrig_contact::Materials,
) -> Result<crate::Scene, RigError> {
    crate::Scene::from_file(deserialize(table)?, materials)
}

fn deserialize(table: toml::Table) -> Result<crate::SceneFile, RigError> {
    toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| {
            RigError::SceneSyntax(crate::format_message::plain(e.message().trim()))
        })
}

/// Checks that `o` fits the scene format on the parsed `base` (a known field, a value of its
/// type) without validating ranges: a sweep refuses a bad path or type before it runs anything.
pub fn check_format(base: &toml::Table, o: &Override) -> Result<(), RigError> {
    let mut table = base.clone();
    set(&mut table, &o.path, o.value.clone())?;
    match deserialize(table) {
        Ok(_) => Ok(()),
        Err(RigError::SceneSyntax(message)) => Err(bad(
            &o.path,
            &o.value.to_string(),
            &format!("not accepted by the scene format: {message}"),
        )),
        Err(e) => Err(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_parse_as_toml_or_strings() {
        assert_eq!(parse_value("0.2"), toml::Value::Float(0.2));
        assert_eq!(parse_value("800"), toml::Value::Integer(800));
        assert_eq!(parse_value("cl"), toml::Value::String("cl".into()));
        assert_eq!(parse_value("\"cl\""), toml::Value::String("cl".into()));
        assert!(matches!(
            parse_value("{ model = \"modal\", modes = 8 }"),
            toml::Value::Table(_)
        ));
    }

    #[test]
    fn malformed_overrides_name_the_problem() {
        assert!(Override::parse("robot.payload_kg").is_err());
        assert!(Override::parse("robot..payload_kg=1").is_err());
        assert!(Override::parse("robot.pay load=1").is_err());
        let o = Override::parse(" robot.payload_kg = 0.2 ").unwrap();
        assert_eq!(o.path, "robot.payload_kg");
    }
}
