//! What an arm's answer writes besides itself: the summary lines the command prints first, the
//! report for a risk assessment (Markdown or HTML, like `flexrig safety --report`: the arm, the
//! question, the verdict with the governing sample, point and method, a table per point, the
//! figure, then the governing sample's full `flexrig safety` report — its inputs, limits with
//! their sources, each method's calculation), and the checks and writing of the figure, the log
//! and the report ([`Outputs`]), none of which replaces an existing file without `force`.

use std::path::{Path, PathBuf};

use flexrig_robot::Robot;

use crate::Error;
use crate::arm::judge::{ArmDrive, ArmJoints, ArmReport};
use crate::safety::overall::method_name;
use crate::safety::report::{Block, Document, ReportFormat};
use crate::safety::{FeLink, Speed};

fn n(v: f64) -> String {
    crate::shared::output::display_number(v)
}

/// Where the arm and its trajectory came from (as the answer names them).
#[derive(Debug, Clone, PartialEq)]
pub struct Sources {
    /// The URDF.
    pub urdf: String,
    /// The trajectory CSV.
    pub trajectory: String,
}

/// The files to write besides the answer.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Outputs {
    /// The figure (`--figure`: .svg, .pdf or .png).
    pub figure: Option<PathBuf>,
    /// The MCAP log (`--log`: .mcap), its layout beside it.
    pub log: Option<PathBuf>,
    /// The report (`--report`: .md or .html), its figure beside it.
    pub report: Option<PathBuf>,
    /// Overwrite existing files (`--force`).
    pub force: bool,
}

fn target(flag: &str, path: &Path, force: bool) -> Result<(), Error> {
    crate::shared::output::check_output_target(path).map_err(|e| match e {
        Error::InvalidArgument { value, allowed, .. } => Error::InvalidArgument {
            arg: flag.into(),
            value,
            allowed,
        },
        other => other,
    })?;
    if !force && path.exists() {
        return Err(Error::InvalidArgument {
            arg: flag.into(),
            value: path.display().to_string(),
            allowed: "a file that does not exist yet (or add --force to overwrite it)".into(),
        });
    }
    Ok(())
}

/// The report's figure beside it: `<stem>_arm.svg`.
pub fn report_figure_path(report: &Path) -> PathBuf {
    let stem = report
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("report");
    let name = format!("{stem}_arm.svg");
    match report.parent().filter(|p| !p.as_os_str().is_empty()) {
        Some(d) => d.join(name),
        None => PathBuf::from(name),
    }
}

impl Outputs {
    /// Checks every target before the work: a regular file or nothing, not an existing file
    /// without `force`, the right extension; the error names the flag.
    pub fn check(&self) -> Result<(), Error> {
        if let Some(f) = &self.figure {
            let ext = f
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            if !matches!(ext.as_deref(), Some("svg" | "pdf" | "png")) {
                return Err(Error::InvalidArgument {
                    arg: "--figure".into(),
                    value: f.display().to_string(),
                    allowed: "a file name ending in .svg, .pdf or .png".into(),
                });
            }
            target("--figure", f, self.force)?;
        }
        if let Some(l) = &self.log {
            if l.extension().and_then(|e| e.to_str()) != Some("mcap") {
                return Err(Error::InvalidArgument {
                    arg: "--log".into(),
                    value: l.display().to_string(),
                    allowed: "a file name ending in .mcap (its layout is written beside it)".into(),
                });
            }
            target("--log", l, self.force)?;
            target("--log", &crate::log::layout::path_beside(l), self.force)?;
        }
        if let Some(r) = &self.report {
            ReportFormat::of(r)?;
            target("--report", r, self.force)?;
            target("--report", &report_figure_path(r), self.force)?;
        }
        Ok(())
    }

    /// Writes the files asked for; returns their paths.
    pub fn write(
        &self,
        robot: &Robot,
        report: &ArmReport,
        sources: &Sources,
        model: Option<&crate::safety::BodyModel>,
    ) -> Result<Vec<PathBuf>, Error> {
        let mut written = Vec::new();
        for p in [&self.figure, &self.log, &self.report]
            .into_iter()
            .flatten()
        {
            if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
                crate::shared::output::ensure_dir(dir)?;
            }
        }
        if let Some(f) = &self.figure {
            written.push(crate::arm::plot::write_figure(report, f)?);
        }
        if let Some(l) = &self.log {
            written.extend(crate::arm::log::write_log(robot, report, l)?);
        }
        if let Some(r) = &self.report {
            written.extend(write_report(report, sources, r, model)?);
        }
        Ok(written)
    }
}

fn speed(s: &Speed) -> String {
    match s {
        Speed::Finite(v) => format!("{v:.4} m/s"),
        Speed::Unlimited(_) => "unlimited".into(),
    }
}

/// The answer's first lines, in words: the verdict, the governing sample, point and method,
/// the speed-scaling factor, the question.
pub fn summary_lines(r: &ArmReport, s: &Sources) -> Vec<String> {
    let mut out = Vec::new();
    let verdict = if r.pass { "PASS" } else { "FAIL" };
    match &r.governing {
        Some(g) => {
            out.push(format!(
                "verdict            {verdict}: the largest speed / permissible speed is {:.4}, \
                 at {} at t = {} s ({} m/s against {}, governed by {})",
                r.max_ratio,
                g.label,
                n(g.time_s),
                n(g.speed_mps),
                speed(&g.v_max_mps),
                method_name(g.method)
            ));
            out.push(format!(
                "speed scaling      the whole trajectory may run at {} × its speed{}",
                match r.speed_scale_factor {
                    Speed::Finite(v) => format!("{v:.4}"),
                    Speed::Unlimited(_) => "any".into(),
                },
                if r.speed_scale != 1.0 {
                    format!(" (as judged: {} × the file's)", n(r.speed_scale))
                } else {
                    String::new()
                }
            ));
            out.push(format!(
                "governing mass     reflected {} kg along the velocity, judged at {} kg",
                n(g.reflected_mass_kg),
                n(g.effective_mass_kg)
            ));
        }
        None => out.push(format!(
            "verdict            {verdict}: no point moves towards a limit (speed scaling: any)"
        )),
    }
    out.push(format!(
        "arm                {} from {}, {} joints ({}), trajectory {} ({} samples)",
        r.robot,
        s.urdf,
        r.joint_names.len(),
        match &r.joints {
            ArmJoints::Rigid => "rigid".to_string(),
            ArmJoints::Armature(_) => "rigid with the rotors' armature".to_string(),
            ArmJoints::Elastic => "elastic: rotors decoupled".to_string(),
        },
        s.trajectory,
        r.samples.len()
    ));
    out.push(format!(
        "compliance         {} with k_δ {}, the compliant link's mass m_r = {} kg; drive {}",
        match r.link {
            FeLink::CompliantJoint => "a compliant joint (CJ)",
            FeLink::CompliantLink => "a compliant link (CL)",
        },
        r.k_delta_n_per_m
            .map_or("rigid".to_string(), |k| format!("{} N/m", n(k))),
        n(r.link_mass_kg),
        match r.drive {
            ArmDrive::Held => "held (carries the joint on)",
            ArmDrive::Free => "free (the reflected mass coasts)",
        }
    ));
    out.push(format!(
        "body region        {} ({}), area {}, {}; force limit {} N, pressure limit {} N/cm²; \
         skin k_c {} N/mⁿ, n {}",
        r.region_name,
        r.region,
        r.area,
        match r.contact {
            crate::safety::ContactKind::Transient => "transient",
            crate::safety::ContactKind::QuasiStatic => "quasi-static",
        },
        n(r.force_limit_n),
        n(r.pressure_limit_pa / 1e4),
        n(r.k_c),
        n(r.n)
    ));
    out.push(format!(
        "masses judged      {} distinct ({}), one `flexrig safety` answer each",
        r.masses.len(),
        if r.mass_step > 0.0 {
            format!(
                "each reflected mass rounded up to the {} % grid",
                n(r.mass_step * 100.0)
            )
        } else {
            "every reflected mass exactly".into()
        }
    ));
    out
}

/// Writes the report to `path` (Markdown or HTML by its extension) with its figure beside it
/// (`<stem>_arm.svg`), atomically; returns both paths. The governing sample's full `flexrig
/// safety` report follows the arm's part.
pub fn write_report(
    r: &ArmReport,
    s: &Sources,
    path: &Path,
    model: Option<&crate::safety::BodyModel>,
) -> Result<Vec<PathBuf>, Error> {
    let format = ReportFormat::of(path)?;
    let figure_path = report_figure_path(path);
    let figure_name = figure_path
        .file_name()
        .and_then(|f| f.to_str())
        .unwrap_or("arm.svg")
        .to_string();
    let svg = crate::arm::plot::arm_svg(r, 504.0).map_err(|message| Error::Plot {
        path: figure_path.clone(),
        message,
    })?;
    let doc = document(r, s, &figure_name, model)?;
    let text = match format {
        ReportFormat::Markdown => doc.markdown(),
        ReportFormat::Html => doc.html_with(&[(&figure_name, &svg)]),
    };
    crate::shared::output::write_atomic(&figure_path, svg.as_bytes())?;
    crate::shared::output::write_atomic(path, text.as_bytes())?;
    Ok(vec![path.to_path_buf(), figure_path])
}

/// The report as a document.
pub fn document(
    r: &ArmReport,
    s: &Sources,
    figure: &str,
    model: Option<&crate::safety::BodyModel>,
) -> Result<Document, Error> {
    let mut blocks = vec![
        Block::Heading(
            1,
            format!(
                "Permissible speed of {} along its trajectory near the {}",
                r.robot,
                r.region_name.to_lowercase()
            ),
        ),
        Block::Heading(2, "Verdict".into()),
    ];
    for l in summary_lines(r, s) {
        blocks.push(Block::Paragraph(
            l.split_whitespace().collect::<Vec<_>>().join(" "),
        ));
    }
    blocks.push(Block::Heading(2, "What was computed".into()));
    blocks.push(Block::Paragraph(format!(
        "At every sample of the trajectory and every contact point: the point's velocity v = J q̇, \
         its speed, the contact direction u = v/|v|, and the arm's reflected mass along it, m_u = \
         1/(uᵀ J M⁻¹ Jᵀ u) (Khatib 1987; Haddadin et al. 2009). The arm is then the single link \
         of flexrig's safety methods with the compliant link's mass m_r = {} kg and the payload \
         m_e = m − m_r/3 at its tip (m the effective mass: the reflected mass{}), and each \
         distinct effective mass is answered once by `flexrig safety` (the standard's formula, \
         the energy method and the simulated impact with every contact; the overall permissible \
         speed the smallest, its method named). The ratio of a point's speed to its permissible \
         speed governs where it is largest; 1/ratio scales the whole trajectory's speed, since \
         scaling time leaves postures, directions and reflected masses unchanged.",
        n(r.link_mass_kg),
        if r.mass_step > 0.0 {
            format!(
                " rounded up to the next of the masses (1 + {})^k kg",
                n(r.mass_step)
            )
        } else {
            String::new()
        }
    )));
    blocks.push(Block::Heading(2, "Contact points".into()));
    let mut rows = Vec::new();
    for (p, point) in r.points.iter().enumerate() {
        let (mut top, mut lo, mut hi, mut vmin, mut worst, mut at) =
            (0.0f64, f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64, 0.0);
        for smp in &r.samples {
            let pr = &smp.points[p];
            top = top.max(pr.speed_mps);
            if let Some(m) = pr.reflected_mass_kg {
                lo = lo.min(m);
                hi = hi.max(m);
            }
            if let Some(v) = pr.v_max_mps {
                vmin = vmin.min(v.value());
            }
            if pr.ratio > worst {
                worst = pr.ratio;
                at = smp.time_s;
            }
        }
        rows.push(vec![
            point.label(),
            format!("{top:.4}"),
            if lo.is_finite() {
                format!("{lo:.3} – {hi:.3}")
            } else {
                "at rest".into()
            },
            speed(&Speed::from_f64(vmin)),
            format!("{worst:.4}"),
            format!("{at:.3}"),
        ]);
    }
    blocks.push(Block::Table(
        vec![
            "point (link: x, y, z in m)".into(),
            "largest speed [m/s]".into(),
            "reflected mass [kg]".into(),
            "smallest permissible speed".into(),
            "largest ratio".into(),
            "at t [s]".into(),
        ],
        rows,
    ));
    blocks.push(Block::Figure(
        figure.to_string(),
        "Along the path, per contact point: the reflected mass along the velocity, the point's \
         speed and its permissible speed."
            .into(),
    ));
    blocks.push(Block::Heading(
        2,
        "Permissible speed per effective mass".into(),
    ));
    blocks.push(Block::Table(
        vec![
            "effective mass [kg]".into(),
            "payload m_e [kg]".into(),
            "permissible speed".into(),
            "governed by".into(),
        ],
        r.masses
            .iter()
            .step_by((r.masses.len() / 20).max(1))
            .map(|m| {
                vec![
                    format!("{:.4}", m.effective_mass_kg),
                    format!("{:.4}", m.m_e_kg),
                    speed(&m.v_max_mps),
                    method_name(m.method).into(),
                ]
            })
            .collect(),
    ));
    if let Some(g) = &r.governing {
        blocks.push(Block::Heading(
            2,
            format!(
                "The governing sample: {} at t = {} s, {} m/s",
                g.label,
                n(g.time_s),
                n(g.speed_mps)
            ),
        ));
        let (_, sub, _) = crate::safety::report::report_document(&g.question, model, None)?;
        for b in sub.blocks {
            blocks.push(match b {
                Block::Heading(level, t) => Block::Heading((level + 1).min(3), t),
                other => other,
            });
        }
    }
    Ok(Document { blocks })
}
