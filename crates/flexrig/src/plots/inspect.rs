//! Reading a drawn figure back: its text, and the size of its smallest text at its printed
//! width. The tests use these to check every figure's labels against the inputs that ran and its
//! text against [`super::MIN_TEXT_PT`]; they read the SVG as a reader's program would.

/// The printed width \[in\] and the viewBox width of an SVG's root (`width="7in"`,
/// `viewBox="0 0 2016 …"`), if both are there.
pub fn printed_width(svg: &str) -> Option<(f64, f64)> {
    let root = &svg[svg.find("<svg")?..];
    let root = &root[..root.find('>')?];
    let width = attribute_text(root, "width")?;
    let inches: f64 = width.strip_suffix("in")?.parse().ok()?;
    let view_box = attribute_text(root, "viewBox")?;
    let vb_width: f64 = view_box.split_whitespace().nth(2)?.parse().ok()?;
    Some((inches, vb_width))
}

/// The printed height \[in\] of an SVG's root (`height="8.97in"`), if it is there.
pub fn printed_height(svg: &str) -> Option<f64> {
    let root = &svg[svg.find("<svg")?..];
    let root = &root[..root.find('>')?];
    attribute_text(root, "height")?
        .strip_suffix("in")?
        .parse()
        .ok()
}

/// The text of attribute `name` of the element text `element`.
fn attribute_text<'a>(element: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = element.find(&key)? + key.len();
    let end = start + element[start..].find('"')?;
    Some(&element[start..end])
}

/// Every `font-size` of the SVG's text (the `<text>` elements and their `<tspan>`s) in points at
/// the printed width: font-size × width \[in\] / viewBox width × 72.
pub fn text_sizes_pt(svg: &str) -> Vec<f64> {
    let Some((inches, vb_width)) = printed_width(svg) else {
        return Vec::new();
    };
    let mut sizes = Vec::new();
    for tag in ["<text", "<tspan"] {
        for (i, _) in svg.match_indices(tag) {
            let element = &svg[i..];
            let element = &element[..element.find('>').unwrap_or(element.len())];
            if let Some(size) = attribute_text(element, "font-size").and_then(|s| s.parse().ok()) {
                let size: f64 = size;
                sizes.push(size * inches / vb_width * 72.0);
            }
        }
    }
    sizes
}

/// The smallest text of the SVG at its printed width \[pt\]; `None` without text.
pub fn min_text_pt(svg: &str) -> Option<f64> {
    text_sizes_pt(svg).into_iter().reduce(f64::min)
}

/// The text of every `<text>` element, one per line, its subscripts written back as the
/// figures' code writes them (`m<tspan baseline-shift="sub" …>e</tspan>` reads `m_e`) and XML
/// entities decoded.
pub fn texts(svg: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find("<text") {
        let after = &rest[start..];
        let Some(open_end) = after.find('>') else {
            break;
        };
        let Some(close) = after.find("</text>") else {
            break;
        };
        let inner = after[open_end + 1..close].replace("<tspan baseline-shift=\"sub\"", "_<tspan");
        out.push(decode(&strip_tags(&inner)).trim().to_string());
        rest = &after[close + "</text>".len()..];
    }
    out
}

/// The advance of character `c` in DejaVu Sans over the font size (the font's advance widths in
/// units of 1/2048 em, rounded up by class: narrow punctuation and i, l, j, t, f, r; lower case;
/// wide m, w and the relations; upper case).
fn advance(c: char) -> f64 {
    match c {
        ' ' | ',' | '.' | ':' | ';' | '\'' | '|' | '!' | '·' => 0.32,
        'i' | 'l' | 'j' | 'I' | 'J' => 0.28,
        '(' | ')' | '[' | ']' | '/' | 't' | 'f' | 'r' | '-' => 0.42,
        'm' | 'w' | 'M' | 'W' | '=' | '+' | '<' | '>' | '≤' | '≥' | '±' | '×' | '→' | '–' | '—' => {
            0.98
        }
        'A'..='Z' => 0.78,
        _ => 0.64,
    }
}

/// Every horizontal `<text>` whose estimated extent leaves the drawing: (its text, left and
/// right edge in viewBox units). The extent is the sum of the characters' [`advance`]s × the
/// font size from its `x` and `text-anchor`, subscripts counted at the base size (an estimate on
/// the wide side); rotated texts (a `transform`) are skipped.
pub fn texts_outside(svg: &str) -> Vec<(String, f64, f64)> {
    let Some((_, vb_width)) = printed_width(svg) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find("<text") {
        let after = &rest[start..];
        let (Some(open_end), Some(close)) = (after.find('>'), after.find("</text>")) else {
            break;
        };
        let element = &after[..open_end];
        let content = decode(&strip_tags(&after[open_end + 1..close]))
            .trim()
            .to_string();
        rest = &after[close + "</text>".len()..];
        if element.contains("transform") {
            continue;
        }
        let number = |name: &str| attribute_text(element, name).and_then(|v| v.parse::<f64>().ok());
        let (Some(x), Some(size)) = (number("x"), number("font-size")) else {
            continue;
        };
        let width = size * content.chars().map(advance).sum::<f64>();
        let left = match attribute_text(element, "text-anchor") {
            Some("middle") => x - width / 2.0,
            Some("end") => x - width,
            _ => x,
        };
        if left < 0.0 || left + width > vb_width {
            out.push((content, left, left + width));
        }
    }
    out
}

/// `s` without its tags.
fn strip_tags(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut in_tag = false;
    for c in s.chars() {
        match c {
            '<' => in_tag = true,
            '>' => in_tag = false,
            c if !in_tag => out.push(c),
            _ => {}
        }
    }
    out
}

/// XML's five entities decoded.
fn decode(s: &str) -> String {
    s.replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&quot;", "\"")
        .replace("&apos;", "'")
        .replace("&amp;", "&")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_and_texts_read_back() {
        // 7 in over a 2016-unit viewBox: 1 unit = 1/4 pt; font-size 32 = 8 pt, 24 = 6 pt
        let svg = "<svg width=\"7in\" height=\"1in\" viewBox=\"0 0 2016 288\">\n\
                   <text x=\"1\" y=\"2\" font-size=\"32\">m<tspan baseline-shift=\"sub\" \
                   font-size=\"24\">e</tspan> = 412 g &amp; more</text>\n\
                   <text font-size=\"40\">B</text></svg>";
        let sizes = text_sizes_pt(svg);
        assert_eq!(sizes, [8.0, 10.0, 6.0]);
        assert_eq!(min_text_pt(svg), Some(6.0));
        assert_eq!(texts(svg), ["m_e = 412 g & more", "B"]);
        assert_eq!(printed_width(svg), Some((7.0, 2016.0)));
        assert_eq!(min_text_pt("<svg width=\"100\">"), None);
    }

    #[test]
    fn texts_beyond_the_edge_are_found() {
        // 32 units = 8 pt; "mmmm" is about 4 × 0.98 × 32 = 125 units wide
        let svg = |x: u32, anchor: &str| {
            format!(
                "<svg width=\"1in\" height=\"1in\" viewBox=\"0 0 288 288\">\
                 <text x=\"{x}\" y=\"9\" text-anchor=\"{anchor}\" font-size=\"32\">mmmm</text>\
                 <text x=\"0\" y=\"9\" transform=\"rotate(-90)\" font-size=\"32\">rotated, skipped</text></svg>"
            )
        };
        assert!(texts_outside(&svg(144, "middle")).is_empty());
        assert!(texts_outside(&svg(150, "start")).is_empty());
        assert_eq!(texts_outside(&svg(200, "start")).len(), 1);
        assert_eq!(texts_outside(&svg(40, "middle")).len(), 1);
        assert_eq!(texts_outside(&svg(100, "end")).len(), 1);
    }
}
