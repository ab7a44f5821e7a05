//! A permissible-speed report a safety engineer can attach to a risk assessment
//! (`flexrig safety --report report.md|report.html`): the inputs, every limit used with its
//! source (document, edition, table and the data file's own field and value), the calculation
//! trace of each method (the standard's formula and the energy method as equations with their
//! numbers, the simulation's root search iteration by iteration with its tolerances), a figure
//! of the peak force against the speed, the verdict and the caveat of ISO/PAS 5672 that the
//! values must be confirmed by measurement.
//!
//! The report is one [`Document`] rendered as Markdown or as a self-contained HTML page. The
//! body model's values are printed in Rust's shortest round-trip form, so each parses back to
//! the data file's number exactly (tested).

use std::path::{Path, PathBuf};

use flexrig_contact::Hertz;
use flexrig_safety::{
    BodyModel, BodyRegion, ContactAreaModel, ContactKind, EnergyContact, GoverningLimit,
    LinkStiffness, PressureCrossing, TransientRule,
};

use crate::Error;
use crate::safety::{
    ContactLaw, FeLink, MapJoint, MethodResult, RobotEffectiveMass, SafetyInput, SafetyMethod,
    SafetyReport, safety, simulated_peak_forces, simulation_trace as traced_simulation,
};
use crate::safety_map::RootStep;

/// The caveat every report carries (ISO/PAS 5672:2023 and the standard itself).
pub const CAVEAT: &str = "These permissible speeds are a design-phase estimate, not a \
certification. ISO/TS 15066:2016 states that its pressure limits come from a single study and \
may change, and ISO/PAS 5672:2023 (Robotics — Collaborative applications — Test methods for \
measuring forces and pressures in human-robot contacts) requires the forces and pressures of \
the real application to be confirmed by measurement with a pressure and force measuring device \
on the real robot, tool and body region. Use these values to choose designs and speeds to test, \
never instead of the test.";

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

fn md_cell(s: &str) -> String {
    s.replace('|', "\\|")
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

impl Document {
    fn push(&mut self, b: Block) {
        self.blocks.push(b);
    }

    /// The report as Markdown (tables in the pipe syntax).
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        for b in &self.blocks {
            match b {
                Block::Heading(level, text) => {
                    s.push_str(&format!("{} {text}\n\n", "#".repeat(*level as usize)));
                }
                Block::Paragraph(text) => s.push_str(&format!("{text}\n\n")),
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
                        s.push_str(l);
                        s.push('\n');
                    }
                    s.push_str("```\n\n");
                }
                Block::Figure(file, caption) => {
                    s.push_str(&format!("![{caption}]({file})\n\n*{caption}*\n\n"));
                }
                Block::Caveat(text) => s.push_str(&format!("> **Caveat.** {text}\n\n")),
            }
        }
        s
    }

    /// The report as one HTML page (inline style; the figure linked beside it).
    pub fn html(&self) -> String {
        let mut s = String::from(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <title>Permissible speed report</title>\n<style>\n\
             body{font-family:'DejaVu Sans',Arial,sans-serif;max-width:52em;margin:2em auto;\
             padding:0 1em;line-height:1.4;color:#111}\n\
             table{border-collapse:collapse;margin:0.5em 0 1em}\n\
             th,td{border:1px solid #999;padding:0.2em 0.5em;text-align:left;vertical-align:top}\n\
             th{background:#eee}\npre{background:#f6f6f6;padding:0.6em;overflow-x:auto}\n\
             blockquote{border-left:4px solid #c00;margin:1em 0;padding:0.3em 1em;background:#fff4f4}\n\
             img{max-width:100%}\n@media print{body{max-width:none}}\n</style>\n</head>\n<body>\n",
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
                Block::Figure(file, caption) => s.push_str(&format!(
                    "<figure><img src=\"{}\" alt=\"{}\"><figcaption>{}</figcaption></figure>\n",
                    html_escape(file),
                    html_escape(caption),
                    html_escape(caption)
                )),
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

/// A number in its shortest round-trip form (as the data file and JSON give it).
fn n(v: f64) -> String {
    format!("{v}")
}

/// A computed number to 7 significant digits.
fn g(v: f64) -> String {
    if !v.is_finite() {
        return "unlimited".into();
    }
    let a = v.abs();
    if a != 0.0 && !(1e-3..1e6).contains(&a) {
        format!("{v:.6e}")
    } else {
        let digits = if a == 0.0 {
            6
        } else {
            (6 - a.log10().floor() as i32).clamp(0, 12) as usize
        };
        format!("{v:.digits$}")
    }
}

fn method_name(m: SafetyMethod) -> &'static str {
    match m {
        SafetyMethod::Standard => "standard's formula",
        SafetyMethod::Energy => "energy method",
        SafetyMethod::Simulation => "simulation",
    }
}

fn governing(g: GoverningLimit) -> &'static str {
    match g {
        GoverningLimit::Force => "force",
        GoverningLimit::Pressure => "pressure",
    }
}

/// The report of `input` (with the ISO/TS 15066:2016 body model, or `model`), its document,
/// and the simulation's root-search trace (empty without the simulation method). The figure is
/// referenced as `figure` (a file name beside the report) when given.
pub fn report_document(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    figure: Option<&str>,
) -> Result<(SafetyReport, Document, Vec<RootStep>), Error> {
    let bundled;
    let model = match model {
        Some(m) => m,
        None => {
            bundled = BodyModel::iso_ts_15066_2016()?;
            &bundled
        }
    };
    let input = &crate::safety::design_input(input)?;
    let r = safety(input, Some(model))?;
    let region = model.region(&r.region)?;
    let area = region.area(&r.area)?;
    let mut d = Document::default();
    d.push(Block::Heading(
        1,
        format!(
            "Permissible speed near the {} — power and force limiting",
            r.region_name.to_lowercase()
        ),
    ));
    d.push(Block::Paragraph(format!(
        "Body region {} ({}), area {} ({}), {} contact. Generated by flexrig {} from the body \
         model \"{}\".",
        r.region_name,
        r.region,
        area.number(),
        r.area,
        contact_words(r.contact),
        env!("CARGO_PKG_VERSION"),
        model.provenance().title
    )));
    d.push(Block::Caveat(CAVEAT.into()));
    verdict(&mut d, input, &r);
    inputs(&mut d, input, &r);
    limits(&mut d, model, region, area, &r)?;
    let mut trace = Vec::new();
    for m in &r.methods {
        match m.method {
            SafetyMethod::Standard => standard_trace(&mut d, input, &r, m),
            SafetyMethod::Energy => energy_trace(&mut d, input, &r, m)?,
            SafetyMethod::Simulation => match &r.scene {
                Some(sc) => {
                    scene_trace(&mut d, sc, &r, m);
                    trace = sc.force_search.clone();
                }
                None => trace = simulation_trace(&mut d, input, Some(model), &r, m)?,
            },
        }
    }
    if let Some(file) = figure {
        d.push(Block::Heading(2, "Figure".into()));
        d.push(Block::Figure(
            file.into(),
            "Peak force against the relative speed by each method, with the force limit; the \
             permissible speed is where a curve meets the limit."
                .into(),
        ));
    }
    d.push(Block::Heading(2, "Caveat".into()));
    d.push(Block::Caveat(CAVEAT.into()));
    Ok((r, d, trace))
}

fn contact_words(k: ContactKind) -> &'static str {
    match k {
        ContactKind::Transient => "transient (the body region free to recoil)",
        ContactKind::QuasiStatic => "quasi-static (the body region clamped)",
    }
}

fn verdict(d: &mut Document, input: &SafetyInput, r: &SafetyReport) {
    d.push(Block::Heading(2, "Verdict".into()));
    let mut rows = Vec::new();
    for m in &r.methods {
        let (at, pass) = match &m.verdict {
            Some(v) => (
                format!("{} m/s", n(v.speed_mps)),
                if v.pass { "pass" } else { "FAIL" }.to_string(),
            ),
            None => ("—".into(), "—".into()),
        };
        rows.push(vec![
            method_name(m.method).into(),
            g(m.v_max_mps.value()),
            governing(m.governing).into(),
            at,
            pass,
        ]);
    }
    d.push(Block::Table(
        vec![
            "method".into(),
            "permissible speed v_max [m/s]".into(),
            "governing limit".into(),
            "judged speed".into(),
            "verdict".into(),
        ],
        rows,
    ));
    let lowest = r
        .methods
        .iter()
        .map(|m| m.v_max_mps.value())
        .fold(f64::INFINITY, f64::min);
    d.push(Block::Paragraph(match input.speed {
        Some(v) => {
            let all = r.methods.iter().all(|m| m.verdict.is_some_and(|x| x.pass));
            format!(
                "At {} m/s the design {} by every method evaluated; the lowest permissible speed \
                 is {} m/s.",
                n(v),
                if all { "passes" } else { "does not pass" },
                g(lowest)
            )
        }
        None => format!(
            "No speed was given to judge. The lowest permissible speed of the methods evaluated \
             is {} m/s.",
            g(lowest)
        ),
    }));
}

fn inputs(d: &mut Document, input: &SafetyInput, r: &SafetyReport) {
    d.push(Block::Heading(2, "Inputs".into()));
    let mut rows: Vec<Vec<String>> = Vec::new();
    let mut row = |q: &str, v: String, flag: &str| rows.push(vec![q.into(), v, flag.into()]);
    row(
        "body region",
        format!("{} ({})", r.region_name, r.region),
        "--region",
    );
    row("specific body area", r.area.clone(), "--area");
    row("contact", contact_words(r.contact).into(), "--contact");
    match input.m_eff {
        Some(RobotEffectiveMass::Given(m)) => row(
            "effective robot mass m_eff",
            format!("{} kg", n(m)),
            "--m-eff",
        ),
        Some(RobotEffectiveMass::Prb { gamma, m_r, m_e }) => {
            row("link mass m_r", format!("{} kg", n(m_r)), "--m-r");
            row("payload (end mass) m_e", format!("{} kg", n(m_e)), "--m-e");
            row("PRB characteristic radius γ", n(gamma), "--gamma");
        }
        None => {}
    }
    if let Some(m) = input.moving_mass {
        row(
            "robot's total moving mass M",
            format!("{} kg", n(m)),
            "--moving-mass",
        );
        row(
            "payload m_L",
            format!("{} kg", n(input.payload)),
            "--payload",
        );
    }
    row(
        "link stiffness k_δ",
        r.k_delta_n_per_m
            .map_or("rigid link".into(), |k| format!("{} N/m", n(k))),
        "--k-delta",
    );
    row(
        "skin contact law f = k_c δⁿ",
        match &input.law {
            ContactLaw::BodySpring => format!(
                "the region's body spring: k_c = K = {} N/m, n = 1",
                n(r.k_c)
            ),
            ContactLaw::Hertz { k_c, n: e } => format!("k_c = {} N/mⁿ, n = {}", n(*k_c), n(*e)),
            ContactLaw::Material(name) => {
                format!("material {name}: k_c = {} N/mⁿ, n = {}", n(r.k_c), n(r.n))
            }
        },
        "--k-c --n / --material",
    );
    row(
        "contact-area model",
        area_words(r.area_model.as_ref()),
        "--area-model",
    );
    row(
        "speed judged",
        input
            .speed
            .map_or("none".into(), |v| format!("{} m/s", n(v))),
        "--speed",
    );
    row(
        "methods",
        r.methods
            .iter()
            .map(|m| method_name(m.method))
            .collect::<Vec<_>>()
            .join(", "),
        "--method",
    );
    d.push(Block::Table(
        vec!["quantity".into(), "value".into(), "flag".into()],
        rows,
    ));
}

fn area_words(a: Option<&ContactAreaModel>) -> String {
    match a {
        Some(ContactAreaModel::HertzSphere { radius_m }) => {
            format!("Hertz sphere, A = π R δ, R = {} m", n(*radius_m))
        }
        Some(ContactAreaModel::ThinLayer { radius_m }) => format!(
            "thin layer on a rigid backing, A = π(2Rδ − δ²), R = {} m",
            n(*radius_m)
        ),
        Some(ContactAreaModel::Fixed { area_m2 }) => format!("fixed area A = {} m²", n(*area_m2)),
        None => "none (pressure not assessed)".into(),
    }
}

fn limits(
    d: &mut Document,
    model: &BodyModel,
    region: &BodyRegion,
    area: &flexrig_safety::BodyArea,
    r: &SafetyReport,
) -> Result<(), Error> {
    let p = model.provenance();
    d.push(Block::Heading(2, "Limits and their source".into()));
    d.push(Block::Paragraph(format!(
        "Document: {}, {}. Tables and clauses: {}. Source of the region's row: {}.",
        p.title,
        p.edition,
        p.tables,
        region.source()
    )));
    let mut rows = vec![
        vec![
            "body spring constant K".into(),
            format!("{} N/mm", n(region.spring_constant_n_per_mm())),
            "spring_constant_n_per_mm".into(),
            "Table A.3".into(),
        ],
        vec![
            "effective body mass m_H".into(),
            format!("{} kg", n(region.effective_mass_kg())),
            "effective_mass_kg".into(),
            "Table A.3".into(),
        ],
        vec![
            "maximum permissible force, quasi-static".into(),
            format!("{} N", n(region.max_force_n())),
            "max_force_n".into(),
            "Table A.2".into(),
        ],
        vec![
            format!(
                "maximum permissible pressure p_s, area {} {}",
                area.number(),
                area.name()
            ),
            format!("{} N/cm²", n(area.max_pressure_n_per_cm2())),
            "max_pressure_n_per_cm2".into(),
            "Table A.2".into(),
        ],
    ];
    if r.contact == ContactKind::Transient {
        match region.transient() {
            TransientRule::Permitted {
                force_multiplier,
                pressure_multiplier,
                max_force_n,
            } => {
                rows.push(vec![
                    "transient force multiplier F_T".into(),
                    n(*force_multiplier),
                    "transient_force_multiplier".into(),
                    "Table A.2 footnote c, A.3.2".into(),
                ]);
                rows.push(vec![
                    "transient pressure multiplier P_T".into(),
                    n(*pressure_multiplier),
                    "transient_pressure_multiplier".into(),
                    "Table A.2 footnote c, A.3.2".into(),
                ]);
                if let Some(f) = max_force_n {
                    rows.push(vec![
                        "explicit transient force".into(),
                        format!("{} N", n(*f)),
                        "transient_max_force_n".into(),
                        "Table A.2".into(),
                    ]);
                }
                if let Some(pt) = area.transient_max_pressure_n_per_cm2() {
                    rows.push(vec![
                        "explicit transient pressure".into(),
                        format!("{} N/cm²", n(pt)),
                        "transient_max_pressure_n_per_cm2".into(),
                        "Table A.2".into(),
                    ]);
                }
            }
            TransientRule::NotPermitted { clause } => {
                rows.push(vec![
                    "transient contact".into(),
                    "not permitted".into(),
                    "transient_not_permitted_clause".into(),
                    clause.clone(),
                ]);
            }
        }
    }
    d.push(Block::Table(
        vec![
            "value".into(),
            "in the data file".into(),
            "field".into(),
            "table".into(),
        ],
        rows,
    ));
    let pressure = region.pressure_limit(area, r.contact)?;
    d.push(Block::Paragraph(format!(
        "Limits applied ({} contact): force F_max = {} N, pressure p_max = {} N/cm²{}. Body \
         model: K = {} N/m, m_H = {}.",
        match r.contact {
            ContactKind::Transient => "transient",
            ContactKind::QuasiStatic => "quasi-static",
        },
        n(r.force_limit_n),
        n(pressure / 1e4),
        if r.area_model.is_none() {
            " (pressure not assessed: no contact-area model)"
        } else {
            ""
        },
        n(r.body_stiffness_n_per_m),
        r.human_mass_kg
            .map_or("∞ (clamped: the body cannot recoil)".into(), |m| format!(
                "{} kg",
                n(m)
            ))
    )));
    Ok(())
}

fn human_mass(r: &SafetyReport) -> f64 {
    r.human_mass_kg.unwrap_or(f64::INFINITY)
}

fn mu_line(r: &SafetyReport, m_robot: f64, mu: f64, eq: &str) -> String {
    match r.human_mass_kg {
        Some(m_h) => format!(
            "μ = (1/m_H + 1/m_R)⁻¹ = (1/{} + 1/{})⁻¹ = {} kg{eq}",
            n(m_h),
            g(m_robot),
            g(mu)
        ),
        None => format!("μ = m_R = {} kg (clamped body, m_H = ∞){eq}", g(mu)),
    }
}

fn standard_trace(d: &mut Document, input: &SafetyInput, r: &SafetyReport, m: &MethodResult) {
    d.push(Block::Heading(
        2,
        "Method a: the standard's formula (ISO/TS 15066:2016 Annex A)".into(),
    ));
    let k = r.body_stiffness_n_per_m;
    let root = (m.reduced_mass_kg * k).sqrt();
    let mut eqs = Vec::new();
    if let Some(mm) = input.moving_mass {
        eqs.push(format!(
            "m_R = M/2 + m_L = {}/2 + {} = {} kg   (Eq. A.4)",
            n(mm),
            n(input.payload),
            g(m.robot_mass_kg)
        ));
    } else {
        eqs.push(format!("m_R = m_eff = {} kg", g(m.robot_mass_kg)));
    }
    eqs.push(mu_line(
        r,
        m.robot_mass_kg,
        m.reduced_mass_kg,
        "   (Eq. A.3)",
    ));
    eqs.push(format!("k = K = {} N/m", n(k)));
    eqs.push(format!(
        "v_F = F_max/√(μk) = {} / √({} × {}) = {} m/s   (Eq. A.5)",
        n(r.force_limit_n),
        g(m.reduced_mass_kg),
        n(k),
        g(m.by_force_mps.value())
    ));
    match (m.by_pressure_mps, r.area_model) {
        (Some(v), Some(ContactAreaModel::Fixed { area_m2 })) => eqs.push(format!(
            "v_p = p_max A/√(μk) = {} × {} / {} = {} m/s   (Eq. A.6)",
            n(r.pressure_limit_pa),
            n(area_m2),
            g(root),
            g(v.value())
        )),
        _ => eqs.push(
            "pressure: not assessed by the formula (Eq. A.6 needs a fixed contact area)".into(),
        ),
    }
    eqs.push(format!(
        "v_max = {} m/s, governed by the {} limit",
        g(m.v_max_mps.value()),
        governing(m.governing)
    ));
    d.push(Block::Equations(eqs));
}

fn energy_contact(r: &SafetyReport, m: &MethodResult) -> Result<EnergyContact, Error> {
    Ok(EnergyContact::new(
        human_mass(r),
        m.robot_mass_kg,
        Hertz::new(r.k_c, r.n)?,
        match r.k_delta_n_per_m {
            Some(k) => LinkStiffness::Finite(k),
            None => LinkStiffness::Rigid,
        },
        r.area_model,
    )?)
}

fn energy_trace(
    d: &mut Document,
    input: &SafetyInput,
    r: &SafetyReport,
    m: &MethodResult,
) -> Result<(), Error> {
    d.push(Block::Heading(
        2,
        "Method b: the lumped energy method (the paper's Eq. 13 generalised)".into(),
    ));
    let c = energy_contact(r, m)?;
    let mut eqs = Vec::new();
    if let Some(RobotEffectiveMass::Prb { gamma, m_r, m_e }) = input.m_eff {
        eqs.push(format!(
            "m_eff = m_e + γ m_r/3 = {} + {} × {}/3 = {} kg   (Eq. 5)",
            n(m_e),
            n(gamma),
            n(m_r),
            g(m.robot_mass_kg)
        ));
    } else {
        eqs.push(format!("m_eff = {} kg", g(m.robot_mass_kg)));
    }
    eqs.push(mu_line(r, m.robot_mass_kg, m.reduced_mass_kg, ""));
    let f = r.force_limit_n;
    let delta = c.indentation(f);
    eqs.push(format!(
        "δ_c(F_max) = (F_max/k_c)^(1/n) = ({} / {})^(1/{}) = {} m   (Eq. 4)",
        n(f),
        n(r.k_c),
        n(r.n),
        g(delta)
    ));
    let link = match r.k_delta_n_per_m {
        Some(k) => format!(
            "F²/(2k_δ) = {}² / (2 × {}) = {} J",
            n(f),
            n(k),
            g(f * f / (2.0 * k))
        ),
        None => "F²/(2k_δ) = 0 J (rigid link)".into(),
    };
    eqs.push(format!(
        "U(F_max) = F²/(2k_δ) + F δ_c/(n + 1):  {link};  F δ_c/(n + 1) = {} × {} / {} = {} J",
        n(f),
        g(delta),
        g(r.n + 1.0),
        g(f * delta / (r.n + 1.0))
    ));
    let u = c.stored_energy(f);
    eqs.push(format!("U(F_max) = {} J   (Eq. 6–9, 13)", g(u)));
    eqs.push(format!(
        "v_F = √(2U/μ) = √(2 × {} / {}) = {} m/s",
        g(u),
        g(m.reduced_mass_kg),
        g(m.by_force_mps.value())
    ));
    match (m.by_pressure_mps, c.force_at_pressure(r.pressure_limit_pa)) {
        (Some(v), Some(PressureCrossing::AtForce(fp))) => {
            eqs.push(format!(
                "pressure: the mean pressure f/A(δ_c) reaches p_max = {} Pa at f_p = {} N ({})",
                n(r.pressure_limit_pa),
                g(fp),
                area_words(r.area_model.as_ref())
            ));
            eqs.push(format!(
                "v_p = √(2U(f_p)/μ) = √(2 × {} / {}) = {} m/s",
                g(c.stored_energy(fp)),
                g(m.reduced_mass_kg),
                g(v.value())
            ));
        }
        (Some(_), Some(PressureCrossing::Always)) => {
            eqs.push("pressure: the mean pressure exceeds p_max at any force, v_p = 0".into())
        }
        (Some(_), Some(PressureCrossing::Never)) => {
            eqs.push("pressure: the mean pressure never reaches p_max, v_p unlimited".into())
        }
        _ => eqs.push("pressure: not assessed (no contact-area model)".into()),
    }
    eqs.push(format!(
        "v_max = {} m/s, governed by the {} limit",
        g(m.v_max_mps.value()),
        governing(m.governing)
    ));
    d.push(Block::Equations(eqs));
    Ok(())
}

fn simulation_trace(
    d: &mut Document,
    input: &SafetyInput,
    model: Option<&BodyModel>,
    r: &SafetyReport,
    m: &MethodResult,
) -> Result<Vec<RootStep>, Error> {
    d.push(Block::Heading(
        2,
        "Method c: simulation (the finite-element impact and a root search)".into(),
    ));
    let (traced, trace, fe) = traced_simulation(input, model)?;
    let v = traced.by_force_mps.value();
    let f = r.force_limit_n;
    let guess = trace.first().map_or(v, |s| s.speed_mps * 1.01);
    let settings = fe.settings;
    let link = match fe.link {
        FeLink::CompliantJoint => format!(
            "the compliant joint: a rigid link on the torsion spring k_θr = k_δL² \
             (k_δ = {} N/m), integrated by DOP853 at relative tolerance {:e}",
            g(fe.k_delta),
            settings.cj_rtol
        ),
        FeLink::CompliantLink => format!(
            "the compliant link: the Euler–Bernoulli beam of lateral tip stiffness k_δ = {} N/m \
             on a mesh graded towards the tip, by its modes and the exact modal integrator \
             (force-hold tolerance {:e})",
            g(fe.k_delta),
            settings.tol
        ),
    };
    let joint = match settings.joint {
        MapJoint::Held => "held (driven at constant speed; the body region arrives at v)".into(),
        MapJoint::FreeHub { rotor_inertia } => format!(
            "a free hub with rotor inertia J_R = {} kg·m² (the robot moves at v into the body)",
            g(rotor_inertia)
        ),
    };
    d.push(Block::Paragraph(format!(
        "The first contact of a body of mass m_h = {} with the tip payload m_e = {} kg of a link \
         of mass m_r = {} kg and length {} m is simulated: {link}; joint {joint}. The speed at \
         which the peak force reaches F_max = {} N is bracketed by factors of 2 around the \
         energy method's {} m/s and found by the Illinois false position on ln v until the \
         bracket is narrower than {:e} (relative). Both tolerances lie below the 1e-4 the \
         result is quoted to.",
        if fe.m_h >= crate::safety::CLAMPED_HUMAN_MASS {
            format!("{} kg (clamped body)", g(fe.m_h))
        } else {
            format!("{} kg", n(fe.m_h))
        },
        g(fe.m_e),
        g(fe.m_r),
        g(settings.length),
        n(f),
        g(guess),
        settings.root_rtol
    )));
    let rows = trace
        .iter()
        .enumerate()
        .map(|(i, s)| {
            vec![
                (i + 1).to_string(),
                format!("{:.12}", s.speed_mps),
                format!("{:.9}", s.ratio * f),
                format!("{:+.3e}", s.ratio - 1.0),
            ]
        })
        .collect();
    d.push(Block::Table(
        vec![
            "iteration".into(),
            "speed v [m/s]".into(),
            "simulated peak force [N]".into(),
            "peak/F_max − 1".into(),
        ],
        rows,
    ));
    let mut eqs = vec![format!(
        "v_F = {} m/s after {} simulated impacts (the method's result: {} m/s)",
        g(v),
        trace.len(),
        g(m.by_force_mps.value())
    )];
    if let Some(vp) = m.by_pressure_mps {
        eqs.push(format!(
            "v_p = {} m/s (the same search on the force at which the mean pressure reaches p_max)",
            g(vp.value())
        ));
    }
    eqs.push(format!(
        "v_max = {} m/s, governed by the {} limit",
        g(m.v_max_mps.value()),
        governing(m.governing)
    ));
    d.push(Block::Equations(eqs));
    Ok(trace)
}

/// Method c on a driven scene: the scene, the search's every evaluation and the result.
fn scene_trace(
    d: &mut Document,
    sc: &crate::safety_scene::SceneSimulation,
    r: &SafetyReport,
    m: &MethodResult,
) {
    if let Some(angle) = sc.release_angle_at_root_deg {
        return test_bed_trace(d, sc, r, m, angle);
    }
    d.push(Block::Heading(
        2,
        "Method c: simulation (the driven scene and a root search on its commanded speed)".into(),
    ));
    let design = match sc.design {
        crate::driven::strike::StrikeDesign::Cj => {
            "the compliant joint (a rigid link on its torsion spring, integrated by DOP853 at \
             relative tolerance"
        }
        crate::driven::strike::StrikeDesign::Cl => {
            "the compliant link (the Euler–Bernoulli beam clamped to the hub, by its modes and \
             the exact modal integrator at force-hold tolerance"
        }
    };
    let f = r.force_limit_n;
    d.push(Block::Paragraph(format!(
        "The driven scene {} ({}) is simulated whole at each commanded speed: the drive's ramp, \
         the approach and the first contact with the drive acting, for {design} {:e}); the head \
         is {}, so the contact is {}. The commanded tip speed L ω_c (the scene as written: {} \
         m/s) at which the first contact's peak force reaches F_max = {} N is bracketed by \
         factors of 2 around the energy method's speed and found by the Illinois false \
         position on ln v until the bracket is narrower than {:e} (relative). Both tolerances \
         lie below the 1e-4 the result is quoted to.",
        sc.name,
        sc.scene,
        sc.run_tol,
        match sc.support {
            "wall" => "backed by a wall (clamped)",
            "neck" => "on a neck",
            _ => "free",
        },
        contact_words(r.contact),
        g(sc.scene_tip_speed_mps),
        n(f),
        sc.root_rtol
    )));
    let rows = sc
        .force_search
        .iter()
        .enumerate()
        .map(|(i, s)| {
            vec![
                (i + 1).to_string(),
                format!("{:.12}", s.speed_mps),
                format!("{:.9}", s.ratio * f),
                format!("{:+.3e}", s.ratio - 1.0),
            ]
        })
        .collect();
    d.push(Block::Table(
        vec![
            "iteration".into(),
            "commanded tip speed [m/s]".into(),
            "simulated peak force [N]".into(),
            "peak/F_max − 1".into(),
        ],
        rows,
    ));
    let mut eqs = vec![format!(
        "v_F = {} m/s commanded (the link arrives at {} m/s; peak force {} N) after {} \
             driven runs",
        g(sc.by_force_mps),
        g(sc.approach_speed_at_root_mps),
        g(sc.peak_force_at_root_n),
        sc.runs
    )];
    if let Some(vp) = m.by_pressure_mps {
        eqs.push(format!(
            "v_p = {} m/s (the same search on the force at which the mean pressure reaches p_max)",
            g(vp.value())
        ));
    }
    eqs.push(format!(
        "v_max = {} m/s, governed by the {} limit",
        g(m.v_max_mps.value()),
        governing(m.governing)
    ));
    d.push(Block::Equations(eqs));
    for note in &sc.notes {
        d.push(Block::Paragraph(format!(
            "At the limit the drive reports: {note}."
        )));
    }
}

/// Method c on a test-bed scene: the scene, the search's every evaluation and the result.
fn test_bed_trace(
    d: &mut Document,
    sc: &crate::safety_scene::SceneSimulation,
    r: &SafetyReport,
    m: &MethodResult,
    angle: f64,
) {
    d.push(Block::Heading(
        2,
        "Method c: simulation (the test bed and a root search on the operator's speed)".into(),
    ));
    let f = r.force_limit_n;
    d.push(Block::Paragraph(format!(
        "The test-bed scene {} ({}, the {} on its axis) is run whole at each speed: the \
         operator's pendulum is released at rest from the angle whose swing reaches the dome at \
         that speed (the pendulum's energy, ½ J ω_b² = M g l_c (1 − cos θ₀), v = ω_b l), and the \
         first contact is integrated with a contact step of {:e} s. The operator's block is the \
         struck body and its pendulum is free, so the contact is transient. The speed at which \
         the peak force reaches F_max = {} N is found by the Illinois false position on ln v \
         until the bracket is narrower than {:e} (relative); release angles are bounded by \
         170°. Methods a and b use the region's body mass, this one the operator's pendulum.",
        sc.name,
        sc.scene,
        match sc.design {
            crate::driven::strike::StrikeDesign::Cj => "compliant joint",
            crate::driven::strike::StrikeDesign::Cl => "compliant link",
        },
        sc.run_tol,
        n(f),
        sc.root_rtol
    )));
    let rows = sc
        .force_search
        .iter()
        .enumerate()
        .map(|(i, s)| {
            vec![
                (i + 1).to_string(),
                format!("{:.12}", s.speed_mps),
                format!("{:.9}", s.ratio * f),
                format!("{:+.3e}", s.ratio - 1.0),
            ]
        })
        .collect();
    d.push(Block::Table(
        vec![
            "iteration".into(),
            "operator speed at contact [m/s]".into(),
            "simulated peak force [N]".into(),
            "peak/F_max − 1".into(),
        ],
        rows,
    ));
    let mut eqs = vec![format!(
        "v_F {} {} m/s (released from {}°; the run's impact speed {} m/s; peak force {} N) \
         after {} test-bed runs",
        if sc.limit_reached { "=" } else { "≥" },
        g(sc.by_force_mps),
        g(angle),
        g(sc.approach_speed_at_root_mps),
        g(sc.peak_force_at_root_n),
        sc.runs
    )];
    eqs.push(format!(
        "v_max = {} m/s, governed by the {} limit",
        g(m.v_max_mps.value()),
        governing(m.governing)
    ));
    d.push(Block::Equations(eqs));
    for note in &sc.notes {
        d.push(Block::Paragraph(format!("Note: {note}.")));
    }
}

/// The figure: peak force against speed by each method, and the force limit.
pub fn figure_svg(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    r: &SafetyReport,
) -> Result<String, Error> {
    use crate::plots::{Curve, CurvePanel, log_x_curves_svg};
    let top = r
        .methods
        .iter()
        .map(|m| m.v_max_mps.value())
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(0.0_f64, f64::max);
    let low = r
        .methods
        .iter()
        .map(|m| m.v_max_mps.value())
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    let (a, b) = if top > 0.0 {
        (low / 10.0, top * 3.0)
    } else {
        (0.01, 10.0)
    };
    let speeds: Vec<f64> = (0..=48)
        .map(|i| (a.ln() + (b.ln() - a.ln()) * i as f64 / 48.0).exp())
        .collect();
    let mut curves = Vec::new();
    for m in &r.methods {
        let points = match m.method {
            SafetyMethod::Standard => {
                let root = (m.reduced_mass_kg * r.body_stiffness_n_per_m).sqrt();
                speeds.iter().map(|&v| (v, v * root)).collect()
            }
            SafetyMethod::Energy => {
                let c = energy_contact(r, m)?;
                speeds
                    .iter()
                    .map(|&v| c.peak_force(v).map(|f| (v, f)))
                    .collect::<Result<Vec<_>, _>>()?
            }
            SafetyMethod::Simulation => {
                let sampled: Vec<f64> = speeds.iter().step_by(4).copied().collect();
                simulated_peak_forces(input, model, &sampled)?
            }
        };
        curves.push(Curve {
            label: format!(
                "{} (v_max = {} m/s)",
                method_name(m.method),
                g(m.v_max_mps.value())
            ),
            points,
            limit: None,
        });
    }
    curves.push(Curve {
        label: format!("force limit F_max = {} N", n(r.force_limit_n)),
        points: vec![(a, r.force_limit_n), (b, r.force_limit_n)],
        limit: None,
    });
    log_x_curves_svg(
        &format!(
            "Peak force against speed: {} ({}), {}",
            r.region_name,
            r.area,
            match r.contact {
                ContactKind::Transient => "transient",
                ContactKind::QuasiStatic => "quasi-static",
            }
        ),
        "relative speed v [m/s]",
        "peak force [N]",
        &[CurvePanel {
            title: String::new(),
            curves,
        }],
    )
    .map_err(|message| Error::Plot {
        path: PathBuf::from("figure"),
        message,
    })
}

/// The report's format, from the file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReportFormat {
    /// `.md`, `.markdown`.
    Markdown,
    /// `.html`, `.htm`.
    Html,
}

impl ReportFormat {
    /// The format of `path` by its extension; an error naming `--report` otherwise.
    pub fn of(path: &Path) -> Result<ReportFormat, Error> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase)
            .as_deref()
        {
            Some("md" | "markdown") => Ok(ReportFormat::Markdown),
            Some("html" | "htm") => Ok(ReportFormat::Html),
            _ => Err(Error::InvalidArgument {
                arg: "--report".into(),
                value: path.display().to_string(),
                allowed: "a file ending in .md (Markdown) or .html (HTML)".into(),
            }),
        }
    }
}

/// Writes the report of `input` to `path` (Markdown or HTML by its extension) and its figure
/// beside it (`<stem>_peak_force.svg`), atomically; returns the safety report and the files.
pub fn write_report(
    input: &SafetyInput,
    model: Option<&BodyModel>,
    path: &Path,
) -> Result<(SafetyReport, Vec<PathBuf>), Error> {
    let format = ReportFormat::of(path)?;
    let stem = path
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("report")
        .to_string();
    let figure_name = format!("{stem}_peak_force.svg");
    let (r, doc, _) = report_document(input, model, Some(&figure_name))?;
    let figure = figure_svg(input, model, &r)?;
    let text = match format {
        ReportFormat::Markdown => doc.markdown(),
        ReportFormat::Html => doc.html(),
    };
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty());
    if let Some(dir) = dir {
        crate::output::ensure_dir(dir)?;
    }
    let figure_path = dir.map_or(PathBuf::from(&figure_name), |d| d.join(&figure_name));
    crate::output::write_atomic(&figure_path, figure.as_bytes())?;
    crate::output::write_atomic(path, text.as_bytes())?;
    Ok((r, vec![path.to_path_buf(), figure_path]))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The number in the report's limits row `label` (its "in the data file" cell).
    fn cell(md: &str, label: &str) -> f64 {
        let row = md
            .lines()
            .find(|l| l.starts_with(&format!("| {label}")))
            .unwrap_or_else(|| panic!("no row {label} in\n{md}"));
        let value = row.split('|').nth(2).unwrap().trim();
        value
            .split_whitespace()
            .next()
            .unwrap()
            .parse()
            .unwrap_or_else(|_| panic!("not a number in {row}"))
    }

    #[test]
    fn every_table_value_round_trips_from_the_data_file_to_the_report() {
        // the data file parsed independently of the body model's loader
        let file: toml::Value =
            toml::from_str(flexrig_safety::BUNDLED_BODY_MODEL_TOML).expect("the data file parses");
        let regions = file["region"].as_array().unwrap();
        let mut checked = 0;
        for region in regions {
            let key = region["key"].as_str().unwrap();
            let permitted = region["transient_permitted"].as_bool().unwrap();
            let kind = if permitted {
                ContactKind::Transient
            } else {
                ContactKind::QuasiStatic
            };
            for area in region["area"].as_array().unwrap() {
                let name = area["name"].as_str().unwrap();
                let input = SafetyInput {
                    region: key.into(),
                    area: Some(name.into()),
                    contact: kind,
                    m_eff: Some(RobotEffectiveMass::Given(2.0)),
                    k_delta: None,
                    law: ContactLaw::BodySpring,
                    area_model: Some(ContactAreaModel::Fixed { area_m2: 1e-4 }),
                    moving_mass: None,
                    payload: 0.0,
                    speed: Some(0.2),
                    methods: vec![SafetyMethod::Standard, SafetyMethod::Energy],
                    link: None,
                    simulation: None,
                    scene: None,
                };
                let (_, doc, _) = report_document(&input, None, None).unwrap();
                let md = doc.markdown();
                let f = |k: &str| region[k].as_float().unwrap();
                assert_eq!(
                    cell(&md, "body spring constant K"),
                    f("spring_constant_n_per_mm")
                );
                assert_eq!(cell(&md, "effective body mass m_H"), f("effective_mass_kg"));
                assert_eq!(
                    cell(&md, "maximum permissible force, quasi-static"),
                    f("max_force_n")
                );
                assert_eq!(
                    cell(&md, "maximum permissible pressure p_s"),
                    area["max_pressure_n_per_cm2"].as_float().unwrap()
                );
                if permitted {
                    assert_eq!(
                        cell(&md, "transient force multiplier F_T"),
                        f("transient_force_multiplier")
                    );
                    assert_eq!(
                        cell(&md, "transient pressure multiplier P_T"),
                        f("transient_pressure_multiplier")
                    );
                }
                // the provenance as the file states it
                for k in ["title", "edition", "tables"] {
                    assert!(md.contains(file["document"][k].as_str().unwrap()), "{k}");
                }
                assert!(md.contains(region["source"].as_str().unwrap()));
                assert!(md.contains("ISO/PAS 5672"));
                // and the HTML carries the same numbers
                let html = doc.html();
                assert!(html.contains(&format!("<td>{} N/mm</td>", f("spring_constant_n_per_mm"))));
                checked += 1;
            }
        }
        assert_eq!(checked, 29, "every specific area of Table A.2");
    }

    #[test]
    fn the_simulation_trace_ends_on_the_methods_own_speed() {
        let input = SafetyInput {
            region: "hands_and_fingers".into(),
            area: None,
            contact: ContactKind::Transient,
            m_eff: Some(RobotEffectiveMass::Prb {
                gamma: 1.0,
                m_r: 0.051,
                m_e: 0.412,
            }),
            k_delta: Some(1e4),
            law: ContactLaw::Material("skinned_aluminium".into()),
            area_model: None,
            moving_mass: None,
            payload: 0.0,
            speed: Some(1.5),
            methods: vec![
                SafetyMethod::Standard,
                SafetyMethod::Energy,
                SafetyMethod::Simulation,
            ],
            link: None,
            simulation: None,
            scene: None,
        };
        let (r, doc, trace) = report_document(&input, None, None).unwrap();
        let sim = r
            .methods
            .iter()
            .find(|m| m.method == SafetyMethod::Simulation)
            .unwrap();
        assert!(trace.len() >= 3);
        // the traced search is the method's own: it ends on the method's speed, and it ran the
        // finite-element CJ (γ = 1 implies the compliant joint)
        let (again, steps, fe) = traced_simulation(&input, None).unwrap();
        assert_eq!(again, *sim);
        assert_eq!(steps, trace);
        assert_eq!(fe.link, FeLink::CompliantJoint);
        let last = trace.last().unwrap();
        assert!((last.speed_mps / sim.by_force_mps.value() - 1.0).abs() < 1e-6);
        let md = doc.markdown();
        assert!(md.contains("Method c: simulation"));
        assert!(md.contains("| iteration |"));
        assert!(md.contains("U(F_max) ="));
        assert!(md.contains("(Eq. A.5)"));
        assert!(figure_svg(&input, None, &r).unwrap().starts_with("<svg"));
    }
}
