//! The report as a document: blocks (headings, paragraphs, tables, figures, calculation lines)
//! rendered to Markdown or to self-contained HTML.

/// One block of a report.
#[derive(Debug, Clone, PartialEq)]
pub enum Block {
    /// A heading of level 1–3.
    Heading(u8, String),
    /// A paragraph of plain text.
    Paragraph(String),
    /// A table: header and rows of cells.
    Table(Vec<String>, Vec<Vec<String>>),
    /// Equations with their numbers, one per line (preformatted).
    Equations(Vec<String>),
    /// A figure: file name (relative to the report) and caption.
    Figure(String, String),
    /// A caveat (block quote).
    Caveat(String),
}

/// A report: its blocks in order.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Document {
    /// The blocks.
    pub blocks: Vec<Block>,
}

pub(crate) use super::escape::{html_escape, md_cell, md_code_line, md_text, url_path};

impl Document {
    pub(crate) fn push(&mut self, b: Block) {
        self.blocks.push(b);
    }

    /// The report as Markdown (tables in the pipe syntax).
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        for b in &self.blocks {
            match b {
                Block::Heading(level, text) => {
                    s.push_str(&format!(
                        "{} {}\n\n",
                        "#".repeat(*level as usize),
                        md_text(text)
                    ));
                }
                Block::Paragraph(text) => s.push_str(&format!("{}\n\n", md_text(text))),
                Block::Table(head, rows) => {
                    let line = |cells: &[String]| {
                        format!(
                            "| {} |\n",
                            cells
                                .iter()
                                .map(|c| md_cell(c))
                                .collect::<Vec<_>>()
                                .join(" | ")
                        )
                    };
                    s.push_str(&line(head));
                    s.push_str(&format!("|{}\n", "---|".repeat(head.len())));
                    for r in rows {
                        s.push_str(&line(r));
                    }
                    s.push('\n');
                }
                Block::Equations(lines) => {
                    s.push_str("```text\n");
                    for l in lines {
                        s.push_str(&md_code_line(l));
                        s.push('\n');
                    }
                    s.push_str("```\n\n");
                }
                Block::Figure(file, caption) => {
                    let caption = md_text(caption).replace(['[', ']'], "");
                    s.push_str(&format!(
                        "![{caption}]({})\n\n*{caption}*\n\n",
                        url_path(file)
                    ));
                }
                Block::Caveat(text) => s.push_str(&format!("> **Caveat.** {}\n\n", md_text(text))),
            }
        }
        s
    }

    /// The report as one HTML page (inline style; the figure linked beside it).
    pub fn html(&self) -> String {
        self.html_with(&[])
    }

    /// The report as one self-contained HTML page: each figure named in `inline` (file name,
    /// SVG text) is embedded in the page; any other is linked.
    pub fn html_with(&self, inline: &[(&str, &str)]) -> String {
        let mut s = String::from(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <title>Permissible speed report</title>\n<style>\n\
             body{font-family:'DejaVu Sans',Arial,sans-serif;max-width:52em;margin:2em auto;\
             padding:0 1em;line-height:1.4;color:#111}\n\
             table{border-collapse:collapse;margin:0.5em 0 1em}\n\
             th,td{border:1px solid #999;padding:0.2em 0.5em;text-align:left;vertical-align:top}\n\
             th{background:#eee}\npre{background:#f6f6f6;padding:0.6em;white-space:pre-wrap}\n\
             blockquote{border-left:4px solid #c00;margin:1em 0;padding:0.3em 1em;background:#fff4f4}\n\
             img,svg{max-width:100%;height:auto}\n@media print{body{max-width:none}}\n</style>\n</head>\n<body>\n",
        );
        for b in &self.blocks {
            match b {
                Block::Heading(level, text) => {
                    s.push_str(&format!("<h{level}>{}</h{level}>\n", html_escape(text)));
                }
                Block::Paragraph(text) => s.push_str(&format!("<p>{}</p>\n", html_escape(text))),
                Block::Table(head, rows) => {
                    s.push_str("<table>\n<tr>");
                    for h in head {
                        s.push_str(&format!("<th>{}</th>", html_escape(h)));
                    }
                    s.push_str("</tr>\n");
                    for r in rows {
                        s.push_str("<tr>");
                        for c in r {
                            s.push_str(&format!("<td>{}</td>", html_escape(c)));
                        }
                        s.push_str("</tr>\n");
                    }
                    s.push_str("</table>\n");
                }
                Block::Equations(lines) => {
                    s.push_str("<pre>");
                    for l in lines {
                        s.push_str(&html_escape(l));
                        s.push('\n');
                    }
                    s.push_str("</pre>\n");
                }
                Block::Figure(file, caption) => match inline.iter().find(|(f, _)| f == file) {
                    Some((_, svg)) => s.push_str(&format!(
                        "<figure>{}<figcaption>{}</figcaption></figure>\n",
                        svg_body(svg),
                        html_escape(caption)
                    )),
                    None => s.push_str(&format!(
                        "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                        html_escape(&url_path(file)),
                        html_escape(caption),
                        html_escape(caption)
                    )),
                },
                Block::Caveat(text) => s.push_str(&format!(
                    "<blockquote><p><strong>Caveat.</strong> {}</p></blockquote>\n",
                    html_escape(text)
                )),
            }
        }
        s.push_str("</body>\n</html>\n");
        s
    }
}

/// An SVG document's `<svg …>…</svg>` element, for embedding in HTML (the XML declaration and
/// anything before the element dropped).
fn svg_body(svg: &str) -> &str {
    svg.find("<svg").map_or(svg, |i| &svg[i..])
}
