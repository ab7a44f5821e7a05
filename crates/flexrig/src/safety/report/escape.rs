//! Escaping of the text a report carries from its user (a body model's region and area names,
//! a scene's name and file): in Markdown no forged heading, list, quote, table break or raw HTML;
//! in both formats a figure link that survives spaces, `#`, `?` and non-ASCII names.

/// `s` as Markdown text on one line: line breaks and other control characters become spaces
/// (a heading, a list or a quote starts only at a line's start, so none can be forged), and
/// `&`, `<`, `>` become character references (no raw HTML; they render as themselves).
pub(crate) fn md_text(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            c if c.is_control() => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// `s` as a Markdown table cell: [`md_text`] with `|` escaped (a cell never splits).
pub(crate) fn md_cell(s: &str) -> String {
    md_text(s).replace('|', "\\|")
}

/// `s` as a line inside a fenced code block: one line (control characters become spaces), and a
/// run of three backticks broken so that the fence cannot be closed from inside.
pub(crate) fn md_code_line(s: &str) -> String {
    let line: String = s
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    line.replace("```", "`\u{200b}``")
}

/// A relative file link, percent-encoded (RFC 3986): unreserved characters and `/` as they are,
/// every other byte of its UTF-8 as `%XX` (a space, `#`, `?`, `(`, `)` or `%` in a file name no
/// longer breaks the link).
pub(crate) fn url_path(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'.' | b'_' | b'~' | b'/') {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// `s` as HTML text or attribute value.
pub(crate) fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&#39;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn user_text_cannot_forge_markdown_structure() {
        assert_eq!(md_text("Chest\n# Forged"), "Chest # Forged");
        assert_eq!(
            md_text("<script>x</script>"),
            "&lt;script&gt;x&lt;/script&gt;"
        );
        assert_eq!(md_cell("a|b\n|c"), "a\\|b \\|c");
        assert_eq!(md_code_line("x\n```\ny"), "x `\u{200b}`` y");
    }

    #[test]
    fn links_are_percent_encoded_byte_by_byte() {
        assert_eq!(
            url_path("my report_peak force.svg"),
            "my%20report_peak%20force.svg"
        );
        assert_eq!(url_path("a#b?(c).svg"), "a%23b%3F%28c%29.svg");
        // U+00E9 is C3 A9 in UTF-8 (RFC 3629)
        assert_eq!(url_path("é.svg"), "%C3%A9.svg");
        assert_eq!(url_path("100%.svg"), "100%25.svg");
    }
}
