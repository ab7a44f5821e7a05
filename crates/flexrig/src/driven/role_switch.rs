//! The role-switch table (docs/driven.md): the test bed's peak (head at v0 on the robot at rest,
//! joint held) against the driven robot's (robot at v0 under its drive into the head at rest)
//! for the test bed's link and the Fig. 6 cases, CJ and CL, from an ideal position source through
//! PD loops K_p = κ k_θr to a torque-free rotor ([`flexrig_impact::role_switch`]); written as
//! role_switch.csv and role_switch.svg.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexrig_impact::role_switch::{
    Design, DriveLevel, RoleCase, RoleRow, RoleSettings, fig6_cases, role_switch_table,
    test_bed_cases,
};

use super::{check, num};
use crate::plots::{Curve, CurveAxes, CurvePanel, FigureOptions, curves_svg, write_figure};
use crate::shared::output::{display_number, ensure_dir, range_arg, write_atomic};
use crate::{CancelToken, Error};

/// The drive levels and the cases.
#[derive(Debug, Clone, PartialEq)]
pub struct RoleSwitchOptions {
    /// PD stiffnesses κ = K_p/k_θr, each > 0 (`--kappa`; 1e4, 1e2, 1, 1e-2); the ideal position
    /// source and the torque-free rotor are always included.
    pub kappas: Vec<f64>,
    /// Rotor inertia J_R over m_r L²/3 (`--rotor-ratio`; 1).
    pub rotor_ratio: f64,
    /// Damping ratio ζ of the PD loops (`--damping-ratio`; 0.7).
    pub damping_ratio: f64,
    /// Include the Fig. 6 cases (n = 1 and 2) besides the test bed's (`--no-fig6` clears it).
    pub fig6: bool,
    /// The link's model (`--link-model`; exact: the whole table in about 2.5 min on 2 cores;
    /// linear: 8 s, every ratio within 4.3e-3 of the exact one, docs/driven.md).
    pub link_model: super::strike::LinkModel,
}

impl Default for RoleSwitchOptions {
    fn default() -> Self {
        RoleSwitchOptions {
            kappas: vec![1e4, 1e2, 1.0, 1e-2],
            rotor_ratio: 1.0,
            damping_ratio: 0.7,
            fig6: true,
            link_model: super::strike::LinkModel::Exact,
        }
    }
}

/// The rows and the files written.
#[derive(Debug, Clone)]
pub struct RoleSwitchResult {
    /// Case-major, then CJ/CL, then the levels (prescribed, the κ in order, torque-free).
    pub rows: Vec<RoleRow>,
    /// role_switch.csv.
    pub csv: PathBuf,
    /// role_switch.svg (written when SVG is among the figure formats, as by default).
    pub svg: PathBuf,
    /// The figure's files, one per format (role_switch.svg, .pdf, .png).
    pub figures: Vec<PathBuf>,
}

/// Runs the table case by case (each case's runs in parallel; stops between cases if `cancel`
/// is set) and writes role_switch.csv and role_switch.svg (two columns wide) into `out`.
pub fn run(
    options: &RoleSwitchOptions,
    out: &Path,
    cancel: &CancelToken,
) -> Result<RoleSwitchResult, Error> {
    run_with_figures(options, out, &FigureOptions::two_column_svg(), cancel)
}

/// [`run`] with the figure at the printed width and in the formats of `figures`.
pub fn run_with_figures(
    options: &RoleSwitchOptions,
    out: &Path,
    figures: &FigureOptions,
    cancel: &CancelToken,
) -> Result<RoleSwitchResult, Error> {
    figures.validate()?;
    let settings = settings(options)?;
    let mut cases: Vec<RoleCase> = test_bed_cases()?;
    if options.fig6 {
        cases.extend(fig6_cases(1.0)?);
        cases.extend(fig6_cases(2.0)?);
    }
    let mut rows = Vec::new();
    for case in &cases {
        check(cancel)?;
        rows.extend(role_switch_table(std::slice::from_ref(case), &settings)?);
    }
    check(cancel)?;
    ensure_dir(out)?;
    let csv_path = out.join("role_switch.csv");
    let svg_path = out.join("role_switch.svg");
    write_atomic(&csv_path, csv(&rows).as_bytes())?;
    let svg = figure(&rows, options, figures.width_pt()).map_err(|message| Error::Plot {
        path: svg_path.clone(),
        message,
    })?;
    let figures = write_figure(out, "role_switch", &svg, figures)?;
    Ok(RoleSwitchResult {
        rows,
        csv: csv_path,
        svg: svg_path,
        figures,
    })
}

/// Most PD stiffnesses a table takes (`--kappa`).
pub const MAX_KAPPAS: usize = 12;
/// The range of a PD stiffness κ = K_p/k_θr: from a loop 1e6 times softer than the link's
/// spring to one 1e6 times stiffer (the ideal position source, always in the table, is the
/// limit beyond).
pub const KAPPA: (f64, f64) = (1e-6, 1e6);
/// The range of the rotor ratio J_R/(m_r L²/3).
pub const ROTOR_RATIO: (f64, f64) = (1e-6, 1e6);
/// Largest damping ratio of the PD loops.
pub const MAX_DAMPING_RATIO: f64 = 1e3;

fn settings(options: &RoleSwitchOptions) -> Result<RoleSettings, Error> {
    let mut settings = RoleSettings::standard();
    if options.link_model == super::strike::LinkModel::Linear {
        settings.exact = None;
    }
    // J_R = ratio · m_r L²/3 must lie in the free hub's [1e-12, 1e12] kg·m² for every case's
    // link (the Fig. 6 and test-bed links lie within 1e-3..1e2 kg·m²): checked before the work
    settings.rotor_ratio = range_arg(
        "--rotor-ratio",
        options.rotor_ratio,
        ROTOR_RATIO.0,
        ROTOR_RATIO.1,
        "",
    )?;
    settings.damping_ratio = range_arg(
        "--damping-ratio",
        options.damping_ratio,
        0.0,
        MAX_DAMPING_RATIO,
        "",
    )?;
    if options.kappas.len() > MAX_KAPPAS {
        return Err(Error::InvalidArgument {
            arg: "--kappa".into(),
            value: format!("{} values", options.kappas.len()),
            allowed: format!(
                "at most {MAX_KAPPAS} values (each adds a driven run to every case of the table)"
            ),
        });
    }
    let mut levels = vec![DriveLevel::Prescribed];
    for (i, &kappa) in options.kappas.iter().enumerate() {
        range_arg(&format!("--kappa[{i}]"), kappa, KAPPA.0, KAPPA.1, "")?;
        if let Some(j) = options.kappas[..i].iter().position(|&k| k == kappa) {
            return Err(Error::InvalidArgument {
                arg: format!("--kappa[{i}]"),
                value: display_number(kappa),
                allowed: format!("a value not given before (it repeats --kappa[{j}])"),
            });
        }
        levels.push(DriveLevel::Pd { kappa });
    }
    levels.push(DriveLevel::TorqueFree);
    settings.levels = levels;
    Ok(settings)
}

/// The level's name in the CSV: `prescribed`, `pd`, `torque_free`.
pub fn level_name(level: &DriveLevel) -> (&'static str, f64) {
    match *level {
        DriveLevel::Prescribed => ("prescribed", f64::INFINITY),
        DriveLevel::Pd { kappa } => ("pd", kappa),
        DriveLevel::TorqueFree => ("torque_free", 0.0),
    }
}

/// The design's name in the CSV: `cj`, `cl`.
pub fn design_name(design: Design) -> &'static str {
    match design {
        Design::Cj => "cj",
        Design::Cl => "cl",
    }
}

/// `case,design,drive,kappa,f_test_bed_n,f_driven_n,ratio,f_switched_same_drive_n` (κ = inf for
/// the ideal position source, 0 for the torque-free rotor), numbers in their shortest exact form.
pub fn csv(rows: &[RoleRow]) -> String {
    let mut text = String::from(
        "case,design,drive,kappa,f_test_bed_n,f_driven_n,ratio,f_switched_same_drive_n\n",
    );
    for r in rows {
        let (drive, kappa) = level_name(&r.level);
        let _ = writeln!(
            text,
            "\"{}\",{},{drive},{},{},{},{},{}",
            r.case.replace('"', "'"),
            design_name(r.design),
            num(kappa),
            num(r.f_test_bed_n),
            num(r.f_driven_n),
            num(r.ratio),
            num(r.f_switched_same_drive_n)
        );
    }
    text
}

/// The ratio f_driven/f_test bed against the drive's compliance 1/κ, a panel per design; the
/// torque-free ratio as each curve's dashed limit; the cases whose ratio stays within 1e-3 of 1
/// at every level are left out (named in the title count). At the printed width `width_pt`
/// \[pt\]; the drive's rotor and damping from `options`.
fn figure(rows: &[RoleRow], options: &RoleSwitchOptions, width_pt: f64) -> Result<String, String> {
    use crate::shared::output::display_number as n;
    let kappas = &options.kappas;
    let mut panels = Vec::new();
    let mut flat = 0;
    for design in [Design::Cj, Design::Cl] {
        let mut curves = Vec::new();
        let mut cases: Vec<&str> = Vec::new();
        for r in rows.iter().filter(|r| r.design == design) {
            if !cases.contains(&r.case.as_str()) {
                cases.push(&r.case);
            }
        }
        for case in cases {
            let of_case: Vec<&RoleRow> = rows
                .iter()
                .filter(|r| r.design == design && r.case == case)
                .collect();
            if of_case.iter().all(|r| (r.ratio - 1.0).abs() <= 1e-3) {
                flat += 1;
                continue;
            }
            let points = of_case
                .iter()
                .filter_map(|r| match r.level {
                    DriveLevel::Pd { kappa } if kappas.contains(&kappa) => {
                        Some((1.0 / kappa, r.ratio))
                    }
                    _ => None,
                })
                .collect();
            let limit = of_case
                .iter()
                .find(|r| r.level == DriveLevel::TorqueFree)
                .map(|r| r.ratio);
            curves.push(Curve {
                label: case.to_string(),
                points,
                limit,
            });
        }
        panels.push(CurvePanel {
            title: format!("{} design", design_name(design).to_uppercase()),
            curves,
        });
    }
    let left_out = if flat == 0 {
        String::new()
    } else {
        format!("; {flat} case–design pairs within 0.1 % of 1 at every drive not drawn")
    };
    curves_svg(
        &format!(
            // the rotor's inertia as one unbreakable phrase (no-break spaces): a title wrapped
            // inside "J_R = 1 m_r L²/3" reads as two quantities
            "Role switch: the driven robot's peak over the test bed's, PD drives of rotor \
             J_R\u{a0}=\u{a0}{}\u{a0}m_r\u{a0}L²/3 and damping ratio {} (dashed: torque-free \
             rotor{left_out})",
            n(options.rotor_ratio),
            n(options.damping_ratio)
        ),
        &CurveAxes {
            x_desc: "drive compliance 1/κ = k_θr/K_p",
            y_desc: "peak-force ratio, driven / test bed",
            x_log: true,
            markers: true,
            reference_band: false,
        },
        &panels,
        width_pt,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plots::inspect::{min_text_pt, printed_width, texts};

    /// Rows of the Fig. 6 cases with n = 2 whose ratio falls from 1 (stiff drive) to `limit`
    /// (torque-free), the same for CJ and CL.
    fn rows(options: &RoleSwitchOptions) -> Vec<RoleRow> {
        let mut rows = Vec::new();
        for (i, case) in fig6_cases(2.0).unwrap().iter().enumerate() {
            let limit = 0.1 + 0.1 * i as f64;
            for design in [Design::Cj, Design::Cl] {
                let level = |level, ratio| RoleRow {
                    case: case.label.clone(),
                    design,
                    level,
                    f_test_bed_n: 1000.0,
                    f_driven_n: 1000.0 * ratio,
                    ratio,
                    f_switched_same_drive_n: 1000.0 * ratio,
                };
                rows.push(level(DriveLevel::Prescribed, 1.0));
                for &kappa in &options.kappas {
                    let ratio = limit + (1.0 - limit) * kappa / (1.0 + kappa);
                    rows.push(level(DriveLevel::Pd { kappa }, ratio));
                }
                rows.push(level(DriveLevel::TorqueFree, limit));
            }
        }
        rows
    }

    #[test]
    fn the_legend_names_each_case_once_as_a_reader_writes_it() {
        let options = RoleSwitchOptions::default();
        for width in [252.0, 504.0] {
            let svg = figure(&rows(&options), &options, width).unwrap();
            assert!((printed_width(&svg).unwrap().0 - width / 72.0).abs() < 1e-9);
            assert!(min_text_pt(&svg).unwrap() >= 8.0 - 1e-3);
            // wrapped legend lines joined again
            let text = texts(&svg).join(" ");
            // both panels show the same cases: one legend below them
            let entry = "k_δ = 10⁸ N/m, m_e = 0.1 kg, n = 2";
            assert_eq!(text.matches(entry).count(), 2, "{text}");
            assert_eq!(text.matches("dashed: the limit").count(), 1, "{text}");
            for code in ["1e8", "2e2", "1e-", "n 2", "m_h 4"] {
                assert!(!text.contains(code), "'{code}' in\n{text}");
            }
            assert!(text.contains("2·10² N/m"), "{text}");
        }
    }
}
