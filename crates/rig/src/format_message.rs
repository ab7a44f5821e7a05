//! The scene format's errors in the scene file's words: serde and the TOML parser describe a
//! mismatch in Rust's terms ("expected struct RobotSpec", "internally tagged enum Start",
//! "expected usize"); a user wrote TOML and should read tables, numbers and names.

/// `message` (a serde or TOML error about the scene format) with Rust's terms replaced by the
/// scene file's: structs are tables, tagged enums are tables naming their kind (with an
/// example), integer types are whole numbers, `f64` a number, a variant identifier a name.
pub fn plain(message: &str) -> String {
    let mut out = message.to_string();
    // the kinds of a tagged table, with the example a user can copy
    for (rust, example) in [
        (
            "internally tagged enum Start",
            "a table naming how the run starts, e.g. { from = \"release\", release_angle_deg = 30.0 }",
        ),
        (
            "internally tagged enum StopSpec",
            "a table naming when the run stops, e.g. { at = \"separation\" }",
        ),
        (
            "internally tagged enum DampingSpec",
            "a table naming the damping model, e.g. { model = \"none\" } or { model = \"hunt_crossley\", restitution = 0.8 }",
        ),
        (
            "internally tagged enum BeamSolverSpec",
            "a table naming the beam model, e.g. { model = \"corotational\" } or { model = \"modal\", modes = 8 }",
        ),
    ] {
        out = out.replace(rust, example);
    }
    out = replace_word_after(&out, "internally tagged enum ", "a table naming its kind");
    out = replace_word_after(&out, "struct ", "a table of fields");
    out = replace_word_after(&out, "unit variant ", "a name");
    for (rust, plain) in [
        ("expected usize", "expected a whole number ≥ 0"),
        ("expected u64", "expected a whole number ≥ 0"),
        ("expected u32", "expected a whole number ≥ 0"),
        ("expected u16", "expected a whole number ≥ 0"),
        ("expected u8", "expected a whole number ≥ 0"),
        ("expected i64", "expected a whole number"),
        ("expected i32", "expected a whole number"),
        ("expected f64", "expected a number"),
        ("expected f32", "expected a number"),
        (
            "expected variant identifier",
            "expected a name (a quoted word)",
        ),
        ("expected a borrowed string", "expected a string"),
        ("floating point ", "number "),
        ("invalid type: map", "invalid type: table"),
        ("invalid type: sequence", "invalid type: array"),
        ("expected a sequence", "expected an array"),
        ("expected a map", "expected a table"),
    ] {
        out = out.replace(rust, plain);
    }
    // serde quotes numbers in backticks: "integer `-3`" → "integer -3"
    for kind in ["integer ", "number ", "boolean "] {
        out = unquote_after(&out, kind);
    }
    compact_numbers(&escapes_named(&out))
}

/// Rust's `\u{…}` escapes in a quoted value said in words: a byte-order mark, or the code
/// point (U+XXXX).
fn escapes_named(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find("\\u{") {
        out.push_str(&rest[..at]);
        let after = &rest[at + 3..];
        match after.find('}') {
            Some(end) if end <= 6 => {
                let code = &after[..end];
                if code.eq_ignore_ascii_case("feff") {
                    out.push_str("[byte-order mark]");
                } else {
                    out.push_str(&format!("[U+{}]", code.to_uppercase()));
                }
                rest = &after[end + 1..];
            }
            _ => {
                out.push_str("\\u{");
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// Numbers written out in full (1e300 as 301 digits) in the compact form of
/// [`flexrig_contact::validate::display`]; the rest of the text unchanged.
pub fn compact_numbers(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut word = String::new();
    let flush = |word: &mut String, out: &mut String| {
        match word.parse::<f64>() {
            Ok(x) if word.len() > 20 => out.push_str(&flexrig_contact::validate::display(x)),
            _ => out.push_str(word),
        }
        word.clear();
    };
    for c in text.chars() {
        if c.is_ascii_digit() || c == '.' || c == '-' || c == 'e' || c == 'E' || c == '+' {
            word.push(c);
        } else {
            flush(&mut word, &mut out);
            out.push(c);
        }
    }
    flush(&mut word, &mut out);
    out
}

/// Replaces `prefix` and the identifier that follows it by `with`.
fn replace_word_after(text: &str, prefix: &str, with: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(prefix) {
        out.push_str(&rest[..at]);
        let after = &rest[at + prefix.len()..];
        let end = after
            .find(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
            .unwrap_or(after.len());
        if end == 0 {
            out.push_str(prefix);
        } else {
            out.push_str(with);
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// Drops the backticks around the value after `kind` ("integer `1`" → "integer 1").
fn unquote_after(text: &str, kind: &str) -> String {
    let pattern = format!("{kind}`");
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(&pattern) {
        out.push_str(&rest[..at]);
        out.push_str(kind);
        let after = &rest[at + pattern.len()..];
        match after.find('`') {
            Some(end) => {
                out.push_str(&after[..end]);
                rest = &after[end + 1..];
            }
            None => rest = after,
        }
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::plain;

    #[test]
    fn rust_terms_become_the_scene_files_words() {
        for (serde, expected) in [
            (
                "invalid type: integer `1`, expected struct RobotSpec",
                "invalid type: integer 1, expected a table of fields",
            ),
            (
                "invalid value: integer `-3`, expected usize",
                "invalid value: integer -3, expected a whole number ≥ 0",
            ),
            (
                "invalid type: floating point `1.5`, expected usize",
                "invalid type: number 1.5, expected a whole number ≥ 0",
            ),
            (
                "invalid type: integer `1`, expected variant identifier",
                "invalid type: integer 1, expected a name (a quoted word)",
            ),
            (
                "invalid type: map, expected unit variant Design::Cl",
                "invalid type: table, expected a name",
            ),
            (
                "invalid type: string \"x\", expected internally tagged enum Other",
                "invalid type: string \"x\", expected a table naming its kind",
            ),
        ] {
            assert_eq!(plain(serde), expected);
        }
        let start =
            plain("invalid type: string \"contact\", expected internally tagged enum Start");
        assert!(start.contains("{ from = \"release\""), "{start}");
        for rust in ["struct", "usize", "enum", "variant identifier", "f64", "`"] {
            assert!(!start.contains(rust), "{start}");
        }
        // nothing else is touched
        assert_eq!(
            plain("missing field `restitution`"),
            "missing field `restitution`"
        );
    }

    #[test]
    fn long_numbers_and_escapes_are_said_plainly() {
        // Regression: 1e300 quoted as 301 digits; a byte-order mark quoted as \u{feff}
        let long = format!(
            "invalid type: number 1{}.0, expected a string",
            "0".repeat(300)
        );
        assert_eq!(
            plain(&long),
            "invalid type: number 1e300, expected a string"
        );
        assert_eq!(
            plain("invalid type: string \"\\u{feff}0.2\", expected a number"),
            "invalid type: string \"[byte-order mark]0.2\", expected a number"
        );
        assert_eq!(plain("a \\u{7} bell"), "a [U+7] bell");
        // short numbers and words with e are left alone
        assert_eq!(
            plain("between 1e-3 and 0.5 here"),
            "between 1e-3 and 0.5 here"
        );
    }
}
