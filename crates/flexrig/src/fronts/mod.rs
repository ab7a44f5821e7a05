//! What the two fronts (the `flexrig` command line and the Python package) share beyond the
//! typed API: the commands' inputs as the user gives them (flags or keyword arguments: words,
//! `FROM:TO` ranges, options that only go with others), checked into the library's settings,
//! and each command's report as the JSON that `flexrig COMMAND --json` prints and the Python
//! twin returns. One function per concern, called by both, so that the two give the same
//! numbers and the same errors.
//!
//! Errors name the command line's flag (`--c-max`); the Python package renames it to its keyword
//! argument (`c_max`).

use std::path::PathBuf;

use serde_json::{Value, json};

use crate::Error;
use crate::fe::eta::{
    ClMethod, ClSolver, DampingSpec, EtaSettings, GradedMesh, ImpactError, Joint,
};
use crate::fe::eta_map::{LogRange, MapSpec};
use crate::plots::{FigureFormat, FigureOptions, FigureWidth};
use crate::shared::output::positive_arg;

fn invalid(arg: &str, value: impl ToString, allowed: impl Into<String>) -> Error {
    Error::InvalidArgument {
        arg: arg.into(),
        value: crate::shared::output::value_text(value),
        allowed: allowed.into(),
    }
}

/// The figure options of `--size` (`1`, `2` or a width such as `5in`), `--format` (svg, pdf,
/// png; repeats dropped) and `--dpi`; errors name the flag.
pub fn figure_options(size: &str, formats: &[String], dpi: f64) -> Result<FigureOptions, Error> {
    let mut parsed = Vec::new();
    for f in formats {
        let format = FigureFormat::parse(f)?;
        if !parsed.contains(&format) {
            parsed.push(format);
        }
    }
    let options = FigureOptions {
        width: FigureWidth::parse(size)?,
        formats: parsed,
        dpi,
    };
    options.validate()?;
    Ok(options)
}

/// Damping added to the Hertz contact (`--damping`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DampingModel {
    /// The paper's elastic contact f = k_c δⁿ.
    None,
    /// Hunt–Crossley, χ = 3(1 − e)/(2 v0).
    HuntCrossley,
    /// Lankarani–Nikravesh, χ = 3(1 − e²)/(4 v0).
    LankaraniNikravesh,
    /// ADAMS IMPACT: damping ramped from 0 at first touch to c_max at a depth.
    AdamsImpact,
}

impl DampingModel {
    /// Every model, in the order of the flag's help.
    pub const ALL: [DampingModel; 4] = [
        DampingModel::None,
        DampingModel::HuntCrossley,
        DampingModel::LankaraniNikravesh,
        DampingModel::AdamsImpact,
    ];

    /// The name as typed (`none`, `hunt-crossley`, `lankarani-nikravesh`, `adams-impact`).
    pub fn name(self) -> &'static str {
        match self {
            DampingModel::None => "none",
            DampingModel::HuntCrossley => "hunt-crossley",
            DampingModel::LankaraniNikravesh => "lankarani-nikravesh",
            DampingModel::AdamsImpact => "adams-impact",
        }
    }

    /// The model named `text` (`_` for `-` accepted); the error names `--damping`.
    pub fn parse(text: &str) -> Result<Self, Error> {
        let wanted = text.replace('_', "-");
        Self::ALL
            .into_iter()
            .find(|m| m.name() == wanted)
            .ok_or_else(|| {
                invalid(
                    "--damping",
                    text,
                    "one of none, hunt-crossley, lankarani-nikravesh, adams-impact",
                )
            })
    }
}

/// The damping of `--damping` with `--restitution` (e in [0, 1]; Hunt–Crossley and
/// Lankarani–Nikravesh), `--c-max` (N·s/m in [0, 1e9]) and `--depth` (m in [1e-9, 1]; ADAMS
/// IMPACT); a missing, stray or out-of-range value is named.
pub fn damping_spec(
    model: DampingModel,
    restitution: Option<f64>,
    c_max: Option<f64>,
    depth: Option<f64>,
) -> Result<DampingSpec, Error> {
    let in_range = |arg: &str, value: Option<f64>, lo: f64, hi: f64, unit: &str, what: &str| {
        let v = value
            .ok_or_else(|| invalid("--damping", model.name(), format!("needs {arg} ({what})")))?;
        crate::shared::output::range_arg(arg, v, lo, hi, unit)
    };
    let stray = |arg: &str, value: Option<f64>, with: &str| match value {
        Some(v) => Err(invalid(
            arg,
            crate::shared::output::display_number(v),
            format!("only with --damping {with}"),
        )),
        None => Ok(()),
    };
    if matches!(model, DampingModel::None | DampingModel::AdamsImpact) {
        stray(
            "--restitution",
            restitution,
            "hunt-crossley or lankarani-nikravesh",
        )?;
    }
    if model != DampingModel::AdamsImpact {
        stray("--c-max", c_max, "adams-impact")?;
        stray("--depth", depth, "adams-impact")?;
    }
    let e = || in_range("--restitution", restitution, 0.0, 1.0, "", "e in [0, 1]");
    Ok(match model {
        DampingModel::None => DampingSpec::NONE,
        DampingModel::HuntCrossley => DampingSpec::HuntCrossley { restitution: e()? },
        DampingModel::LankaraniNikravesh => DampingSpec::LankaraniNikravesh { restitution: e()? },
        DampingModel::AdamsImpact => DampingSpec::AdamsImpact {
            c_max_n_s_per_m: in_range("--c-max", c_max, 0.0, 1e9, "N·s/m", "N·s/m")?,
            depth_m: in_range("--depth", depth, 1e-9, 1.0, "m", "m")?,
        },
    })
}

/// The joint during an FE impact (`--joint`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointKind {
    /// Driven at constant speed: the robot at rest in the joint's frame, struck at v0.
    Held,
    /// A free hub with a rotor inertia; the robot moves at v0 into the head.
    FreeHub,
}

impl JointKind {
    /// The joint named `text` (`held`, `free-hub`; `_` for `-` accepted); the error names
    /// `--joint`.
    pub fn parse(text: &str) -> Result<Self, Error> {
        match text.replace('_', "-").as_str() {
            "held" => Ok(JointKind::Held),
            "free-hub" => Ok(JointKind::FreeHub),
            _ => Err(invalid("--joint", text, "one of held, free-hub")),
        }
    }
}

/// The joint of `--joint` and `--rotor-inertia` (kg·m², only and always with the free hub).
pub fn joint(kind: JointKind, rotor_inertia: Option<f64>) -> Result<Joint, Error> {
    Ok(match (kind, rotor_inertia) {
        (JointKind::Held, None) => Joint::Held,
        (JointKind::Held, Some(j)) => {
            return Err(invalid(
                "--rotor-inertia",
                crate::shared::output::display_number(j),
                "only with --joint free-hub",
            ));
        }
        (JointKind::FreeHub, None) => {
            return Err(invalid(
                "--joint",
                "free-hub",
                "needs --rotor-inertia (kg·m², > 0)",
            ));
        }
        (JointKind::FreeHub, Some(j)) => Joint::FreeHub {
            rotor_inertia: positive_arg("--rotor-inertia", j)?,
        },
    })
}

/// An impact parameter error as the flag the user typed (`zone_elements` → `--zone-elements`).
pub fn as_flag(e: ImpactError) -> Error {
    match e {
        ImpactError::InvalidParameter {
            field,
            value,
            allowed,
        }
        | ImpactError::Contact(crate::driven::ContactError::InvalidParameter {
            field,
            value,
            allowed,
        }) => Error::InvalidArgument {
            arg: format!("--{}", field.replace('_', "-")),
            value,
            allowed,
        },
        other => Error::Impact(other),
    }
}

/// [`as_flag`] for an impact error inside a library error.
pub fn impact_as_flag(e: Error) -> Error {
    match e {
        Error::Impact(e) => as_flag(e),
        other => other,
    }
}

/// The log-spaced range `FROM:TO` of `flag` with `points` points.
pub fn parse_range(flag: &str, text: &str, points: usize) -> Result<LogRange, Error> {
    crate::fe::eta_map::parse_log_range(flag, text, points)
}

/// The inputs of `flexrig eta` as given (flags or keyword arguments).
#[derive(Debug, Clone, PartialEq)]
pub struct EtaInputs {
    /// `--joint`.
    pub joint: JointKind,
    /// `--rotor-inertia` [kg·m²].
    pub rotor_inertia: Option<f64>,
    /// `--method alpha` (otherwise modal).
    pub alpha: bool,
    /// `--tol` (modal).
    pub tol: Option<f64>,
    /// `--zone-elements` (modal).
    pub zone_elements: Option<f64>,
    /// `--window-periods` (modal).
    pub window_periods: Option<f64>,
    /// `--elements` (alpha).
    pub elements: Option<usize>,
    /// `--steps-per-contact` (alpha).
    pub steps_per_contact: Option<usize>,
    /// `--modes` (alpha).
    pub modes: Option<usize>,
    /// `--length` [m].
    pub length: f64,
    /// The contact's damping.
    pub damping: DampingSpec,
    /// The design held fixed (m_r, k_c, v0; `--m-r`, `--k-c`, `--v0`): the paper's by default.
    pub design: flexrig_lumped::fig6::Fig6Design,
}

/// The settings of `flexrig eta`; an option of the other method or a value out of range is
/// named.
pub fn eta_settings(i: &EtaInputs) -> Result<EtaSettings, Error> {
    let joint = joint(i.joint, i.rotor_inertia)?;
    let only = |flag: &str, given: bool, method: &str| {
        if given {
            Err(invalid(
                flag,
                "given",
                format!("only with --method {method}"),
            ))
        } else {
            Ok(())
        }
    };
    let method = if i.alpha {
        only("--tol", i.tol.is_some(), "modal")?;
        only("--zone-elements", i.zone_elements.is_some(), "modal")?;
        ClMethod::Alpha(ClSolver {
            elements: i.elements.unwrap_or(ClSolver::DEFAULT.elements),
            steps_per_contact: i
                .steps_per_contact
                .unwrap_or(ClSolver::DEFAULT.steps_per_contact),
            modes: i.modes,
        })
    } else {
        only("--elements", i.elements.is_some(), "alpha")?;
        only(
            "--steps-per-contact",
            i.steps_per_contact.is_some(),
            "alpha",
        )?;
        only("--modes", i.modes.is_some(), "alpha")?;
        ClMethod::Modal {
            mesh: GradedMesh {
                zone_elements: i.zone_elements.unwrap_or(GradedMesh::DEFAULT.zone_elements),
                ..GradedMesh::DEFAULT
            },
            tol: i.tol.unwrap_or(1e-6),
        }
    };
    crate::fe::eta::check_length(i.length)?;
    crate::lumped::fig6::check_design(&i.design)?;
    let settings = EtaSettings {
        length: i.length,
        joint,
        method,
        window_periods: i.window_periods,
        damping: i.damping,
        design: i.design,
        severity_dome_radius_m: Some(crate::shared::severity::paper_dome_radius_m()?),
        ..EtaSettings::DEFAULT
    };
    settings.validate().map_err(as_flag)?;
    Ok(settings)
}

/// `flexrig eta --json`.
pub fn eta_report(settings: &EtaSettings, r: &crate::fe::eta::EtaResult) -> Value {
    json!({ "settings": settings, "rows": r.rows, "csv": r.csv, "svg": r.svg, "fig6_svg": r.fig6_svg })
}

/// The maps of `flexrig eta-map`: one per head mass of `m_h` (kg), Hertz exponent `n`, ranges
/// `mass_ratio` and `stiffness_ratio` (`FROM:TO`), `points` along each axis (2 to 200).
pub fn eta_map_specs(
    m_h: &[f64],
    n: f64,
    mass_ratio: &str,
    stiffness_ratio: &str,
    points: usize,
) -> Result<Vec<MapSpec>, Error> {
    if m_h.is_empty() || m_h.len() > crate::fe::eta_map::MAX_MAPS {
        return Err(invalid(
            "--m-h",
            format!("{} values", m_h.len()),
            format!(
                "one to {} head masses, each in (0, 1e9] kg",
                crate::fe::eta_map::MAX_MAPS
            ),
        ));
    }
    m_h.iter()
        .map(|&m_h| {
            if !(2..=200).contains(&points) {
                return Err(invalid("--points", points, "must lie in [2, 200]"));
            }
            let spec = MapSpec {
                m_h,
                n,
                mass_ratio: parse_range("--mass-ratio", mass_ratio, points)?,
                stiffness_ratio: parse_range("--stiffness-ratio", stiffness_ratio, points)?,
            };
            spec.validate().map_err(as_flag)?;
            Ok(spec)
        })
        .collect()
}

/// The settings of `flexrig eta-map`: the modal method at `tol` on the default graded mesh,
/// for the fixed `design` (m_r, k_c, v0) and link `length` \[m\].
pub fn eta_map_settings(
    joint: Joint,
    tol: f64,
    damping: DampingSpec,
    design: flexrig_lumped::fig6::Fig6Design,
    length: f64,
) -> Result<EtaSettings, Error> {
    crate::lumped::fig6::check_design(&design)?;
    crate::fe::eta::check_length(length)?;
    let settings = EtaSettings {
        joint,
        method: ClMethod::Modal {
            mesh: GradedMesh::DEFAULT,
            tol,
        },
        damping,
        design,
        length,
        severity_dome_radius_m: Some(crate::shared::severity::paper_dome_radius_m()?),
        ..EtaSettings::DEFAULT
    };
    settings.method.validate().map_err(as_flag)?;
    Ok(settings)
}

/// `flexrig eta-map --json`.
pub fn eta_map_report(settings: &EtaSettings, r: &crate::fe::eta_map::EtaMapResult) -> Value {
    let paths: Vec<String> = r.files.iter().map(|p| p.display().to_string()).collect();
    json!({ "settings": settings, "maps": r.summaries, "files": paths })
}

/// The ratios and exponents of `flexrig eta-rotor`: `ratio` `FROM:TO` with `points` (2 to 200),
/// exponents `n` (one to [`crate::fe::eta_rotor::MAX_EXPONENTS`], each in [1, 3]).
pub fn eta_rotor_inputs(ratio: &str, points: usize, n: &[f64]) -> Result<LogRange, Error> {
    if !(2..=200).contains(&points) {
        return Err(invalid("--points", points, "must lie in [2, 200]"));
    }
    let ratios = parse_range("--ratio", ratio, points)?;
    if n.is_empty()
        || n.len() > crate::fe::eta_rotor::MAX_EXPONENTS
        || n.iter()
            .any(|n| !(n.is_finite() && (1.0..=3.0).contains(n)))
    {
        return Err(invalid(
            "--n",
            format!("{} values", n.len()),
            format!(
                "one to {} exponents, each in [1, 3]",
                crate::fe::eta_rotor::MAX_EXPONENTS
            ),
        ));
    }
    Ok(ratios)
}

/// The settings of `flexrig eta-rotor`: the modal method at `tol` on the default graded mesh,
/// for the fixed `design` (m_r, k_c, v0) and link `length` \[m\].
pub fn eta_rotor_settings(
    tol: f64,
    damping: DampingSpec,
    design: flexrig_lumped::fig6::Fig6Design,
    length: f64,
) -> Result<EtaSettings, Error> {
    crate::lumped::fig6::check_design(&design)?;
    crate::fe::eta::check_length(length)?;
    Ok(EtaSettings {
        method: ClMethod::Modal {
            mesh: GradedMesh::DEFAULT,
            tol,
        },
        damping,
        design,
        length,
        severity_dome_radius_m: Some(crate::shared::severity::paper_dome_radius_m()?),
        ..EtaSettings::DEFAULT
    })
}

/// An error of `flexrig eta-rotor` named by flag (the ratio range as typed, `ratio`).
pub fn eta_rotor_error(e: Error, ratio: &str) -> Error {
    match e {
        Error::Impact(ImpactError::InvalidParameter { field, .. }) if field == "inertia_ratio" => {
            invalid("--ratio", ratio, "FROM:TO with 1e-9 ≤ FROM < TO ≤ 1e9")
        }
        other => impact_as_flag(other),
    }
}

/// `flexrig eta-rotor --json`.
pub fn eta_rotor_report(settings: &EtaSettings, r: &crate::fe::eta_rotor::EtaRotorResult) -> Value {
    json!({ "settings": settings, "points": r.points, "csv": r.csv, "svg": r.svg })
}

/// `flexrig impact --json`: the method, the masses, the peak and what the method found beyond
/// it (closed form: k_o, time to peak, duration; ode: the formulation used, rtol, time to peak,
/// duration, separation speed, evaluations and steps).
pub fn impact_report(
    r: &crate::lumped::impact::ImpactResult,
    method: crate::lumped::impact::Method,
) -> Value {
    use crate::lumped::impact::{Details, Method};
    let model = &r.model;
    let mut report = json!({
        "method": method.name(),
        "m_h_kg": model.m_h(),
        "m_eff_kg": model.m_eff(),
        "mu_kg": model.reduced_mass(),
        "impact_energy_j": model.impact_energy(),
    });
    match &r.details {
        Details::Exact => {}
        Details::Analytic(a) => {
            report["k_o_n_per_m"] = json!(a.k_o);
            report["t_peak_s"] = json!(a.t_peak);
            report["contact_duration_s"] = json!(a.contact_duration);
        }
        Details::Ode {
            solution: sol,
            formulation,
        } => {
            report["formulation"] = json!(format!("{formulation:?}").to_lowercase());
            if let Method::Ode { rtol, .. } = method {
                report["rtol"] = json!(rtol);
            }
            report["t_peak_s"] = json!(sol.t_peak);
            report["contact_duration_s"] = json!(sol.contact_duration);
            report["separation_speed_mps"] = json!(sol.separation_speed);
            report["rhs_evals"] = json!(sol.rhs_evals);
            report["steps"] = json!(sol.steps);
            report["rejected_steps"] = json!(sol.rejected_steps);
        }
    }
    let peak = r.peak;
    report["f_max_n"] = json!(peak.f_max);
    report["delta_max_m"] = json!(peak.delta_max);
    report["indentation_max_m"] = json!(peak.indentation_max);
    report["link_deflection_max_m"] = json!(peak.link_deflection_max);
    report
}

/// The effective robot mass of `flexrig impact`: `--m-eff` \[kg\] alone, or all of `--gamma`,
/// `--m-r` \[kg\] and `--m-e` \[kg\] for m_eff = m_e + γ m_r/3 (Eq. 5); an incomplete or mixed
/// set names exactly the flags missing or in excess.
pub fn effective_mass(
    m_eff: Option<f64>,
    gamma: Option<f64>,
    m_r: Option<f64>,
    m_e: Option<f64>,
) -> Result<crate::lumped::impact::EffectiveMass, Error> {
    use crate::lumped::impact::EffectiveMass;
    let prb = [("--gamma", gamma), ("--m-r", m_r), ("--m-e", m_e)];
    let named = |given: bool| -> Vec<&str> {
        prb.iter()
            .filter(|(_, v)| v.is_some() == given)
            .map(|(f, _)| *f)
            .collect()
    };
    match (m_eff, gamma, m_r, m_e) {
        (Some(m_eff), None, None, None) => Ok(EffectiveMass::Given(m_eff)),
        (Some(_), ..) => Err(invalid(
            "--m-eff",
            format!("given with {}", named(true).join(" and ")),
            "give --m-eff alone, or all of --gamma, --m-r and --m-e without it",
        )),
        (None, Some(gamma), Some(m_r), Some(m_e)) => Ok(EffectiveMass::Prb { gamma, m_r, m_e }),
        (None, None, None, None) => Err(invalid(
            "--m-eff",
            "(missing)",
            "give --m-eff, or all of --gamma, --m-r and --m-e",
        )),
        (None, ..) => {
            let (given, missing) = (named(true), named(false));
            Err(invalid(
                &missing.join(" and "),
                "(missing)",
                format!(
                    "{} {} m_eff = m_e + γ m_r/3 only with all of --gamma, --m-r and --m-e: \
                     add {} (or give --m-eff alone)",
                    given.join(" and "),
                    if given.len() == 1 { "gives" } else { "give" },
                    missing.join(" and ")
                ),
            ))
        }
    }
}

/// `flexrig impact --json` whole: the peak of `input` by `method`
/// ([`crate::lumped::impact::solve`]), its report ([`impact_report`]) and, with the ode method, the
/// severity ([`impact_severity`], at `dome_radius_m` \[m\] if given).
pub fn impact_full_report(
    input: &crate::lumped::impact::ImpactInput,
    method: crate::lumped::impact::Method,
    dome_radius_m: Option<f64>,
) -> Result<(Value, Option<crate::shared::severity::Severity>), Error> {
    let r = crate::lumped::impact::solve(input, method)?;
    let severity = impact_severity(&r, method, dome_radius_m)?;
    let mut report = impact_report(&r, method);
    if let Some(s) = &severity {
        report["severity"] = json!(s);
    }
    Ok((report, severity))
}

/// The severity of a `flexrig impact` result (peak force, pressure, energy, head acceleration,
/// HIC; [`crate::lumped::impact::severity`]): with the ode method only, which integrates the time
/// history again on a fine grid; `dome_radius_m` \[m\] (`--dome-radius`, default the paper's
/// dome) is refused with another method.
pub fn impact_severity(
    r: &crate::lumped::impact::ImpactResult,
    method: crate::lumped::impact::Method,
    dome_radius_m: Option<f64>,
) -> Result<Option<crate::shared::severity::Severity>, Error> {
    use crate::lumped::impact::{Details, Method};
    match (&r.details, method) {
        (Details::Ode { formulation, .. }, Method::Ode { rtol, .. }) => Ok(Some(
            crate::lumped::impact::severity(&r.model, rtol, *formulation, dome_radius_m)?,
        )),
        _ => match dome_radius_m {
            Some(radius) => Err(invalid(
                "--dome-radius",
                flexrig_contact::validate::display(radius),
                "only with --method ode (the severity needs the time history)",
            )),
            None => Ok(None),
        },
    }
}

/// The ode method's state variables named `text` (`auto`, `indentation`, `displacement`); the
/// error names `--formulation`.
pub fn formulation(text: &str) -> Result<crate::lumped::impact::Formulation, Error> {
    use crate::lumped::impact::Formulation;
    match text {
        "auto" => Ok(Formulation::Auto),
        "indentation" => Ok(Formulation::Indentation),
        "displacement" => Ok(Formulation::Displacement),
        _ => Err(invalid(
            "--formulation",
            text,
            "one of auto, indentation, displacement",
        )),
    }
}

/// The method of `flexrig impact` named `text` (`exact`, `analytic`, `ode`; the ode method with
/// `formulation` and `rtol`); the error names `--method`.
pub fn impact_method(
    text: &str,
    formulation: crate::lumped::impact::Formulation,
    rtol: f64,
) -> Result<crate::lumped::impact::Method, Error> {
    use crate::lumped::impact::Method;
    match text {
        "exact" => Ok(Method::Exact),
        "analytic" => Ok(Method::Analytic),
        "ode" => Ok(Method::Ode { formulation, rtol }),
        _ => Err(invalid("--method", text, "one of exact, analytic, ode")),
    }
}

/// `flexrig payload --json`.
pub fn payload_report(r: &crate::fe::payload::PayloadResult) -> Value {
    json!({ "rows": r.rows, "csv": r.csv, "logs": r.logs, "figures": r.figures })
}

/// `flexrig bench --json`: the rows (model, method, setting, error, run time, evaluations), the
/// plots, the scipy peer's run-time ratio (absent when the peer could not run) and the Python
/// interpreter the peer was run with.
pub fn bench_report(r: &crate::quality::bench::BenchReport) -> Value {
    without_nulls(json!({
        "rows": r.rows,
        "plots": r.plots,
        "scipy_dop853_over_flexrig_at_1e_9": r.scipy_dop853_over_flexrig_at_1e_9,
        "peer_python": r.peer_python,
    }))
}

/// `flexrig role-switch --json`: one row per (case, design, drive) with the PD stiffness
/// κ = K_p/k_θr of a PD drive (absent for the ideal position source and the torque-free rotor),
/// the two peaks and their ratio; the files written.
pub fn role_switch_report(r: &crate::driven::role_switch::RoleSwitchResult) -> Value {
    use crate::driven::role_switch::{design_name, level_name};
    let rows: Vec<Value> = r
        .rows
        .iter()
        .map(|row| {
            let (drive, kappa) = level_name(&row.level);
            let mut v = json!({
                "case": row.case,
                "design": design_name(row.design),
                "drive": drive,
                "f_test_bed_n": row.f_test_bed_n,
                "f_driven_n": row.f_driven_n,
                "ratio": row.ratio,
                "f_switched_same_drive_n": row.f_switched_same_drive_n,
            });
            if kappa.is_finite() {
                v["kappa"] = json!(kappa);
            }
            v
        })
        .collect();
    json!({"rows": rows, "csv": r.csv, "svg": r.svg, "figures": r.figures})
}

/// `flexrig fig6 --json`: the design, one entry per case and exponent (m_h, k_delta, m_e, n,
/// η at γ = 2/3 and the sampled curve γ, η) and the files written.
pub fn fig6_report(r: &crate::lumped::fig6::Fig6Result) -> Value {
    let cases: Vec<Value> = r
        .curves
        .iter()
        .map(|c| {
            json!({
                "m_h": c.case.m_h,
                "k_delta": c.case.k_delta,
                "m_e": c.case.m_e,
                "n": c.n,
                "eta_at_2_3": c.eta_at_2_3,
                "gamma": c.gamma,
                "eta": c.eta,
            })
        })
        .collect();
    json!({"design": r.design, "cases": cases, "csv": r.csv, "svg": r.svg})
}

/// `flexrig sweep --json`: the table written, its rows, the sweep's points, the rows resumed
/// and the rows whose run failed.
pub fn sweep_report(r: &crate::study::SweepReport) -> Value {
    json!({
        "table": r.table,
        "rows": r.rows,
        "points": r.points,
        "resumed": r.resumed,
        "failed": r.failed,
    })
}

/// `flexrig experiment --json`.
pub fn experiment_report(r: &crate::testbed::experiment::ExperimentResult) -> Value {
    json!({"groups": r.groups, "ratios": r.ratios, "runs": r.runs, "csv": r.csv, "svg": r.svg, "figures": r.figures, "notes": r.notes})
}

/// The options of `flexrig prb`: `elements` (4 to 256), `model` (`ancf`, `corotational`),
/// `criterion` (`deflection`, `length`); errors name the flag.
pub fn prb_options(
    elements: usize,
    model: &str,
    criterion: &str,
    out: PathBuf,
    figures: FigureOptions,
) -> Result<crate::fe::prb::PrbOptions, Error> {
    use crate::fe::prb::{ErrorMeasure, Kinematics};
    crate::fe::prb::check_elements(elements)?;
    let criterion = match criterion {
        "deflection" => ErrorMeasure::Deflection,
        "length" => ErrorMeasure::Length,
        other => {
            return Err(invalid(
                "--criterion",
                other,
                "must be deflection or length",
            ));
        }
    };
    let kinematics = match model {
        "ancf" => Kinematics::Ancf,
        "corotational" => Kinematics::Corotational,
        other => return Err(invalid("--model", other, "must be ancf or corotational")),
    };
    Ok(crate::fe::prb::PrbOptions {
        elements,
        kinematics,
        criterion,
        out,
        figures,
    })
}

/// `flexrig prb --json`: the fit by both criteria, the published values, the spring stiffness
/// k L/EI (Howell's γ K_Θ against the paper's π γ²) and the beam's share of the tip effective
/// mass (FE k_tip/ω₁² − m_e against the lumped γ/3, paper Eq. 5).
pub fn prb_report(options: &crate::fe::prb::PrbOptions, r: &crate::fe::prb::PrbResult) -> Value {
    use crate::fe::prb::{
        CANTILEVER_BETA_L, ErrorMeasure, HOWELL_GAMMA, HOWELL_K_THETA, HOWELL_THETA_MAX_DEG,
        Kinematics, PAPER_GAMMA_SMALL,
    };
    let (fit, other) = (r.fit, r.other);
    let pi = std::f64::consts::PI;
    let stiffness = |g: f64, k: f64| json!({"gamma": g, "howell_k_l_over_ei": g * k, "paper_k_l_over_ei": pi * g * g});
    let m_eff_modal = 3.0 / CANTILEVER_BETA_L[0].powi(4);
    let shares: Vec<Value> = r
        .shares
        .iter()
        .map(|s| json!({"payload_over_m_r": s.payload_over_m_r, "fe_beam_share": s.fe_beam_share}))
        .collect();
    let name = |m: ErrorMeasure| match m {
        ErrorMeasure::Deflection => "deflection",
        ErrorMeasure::Length => "length",
    };
    let model = match options.kinematics {
        Kinematics::Corotational => "corotational",
        Kinematics::Linear => "linear",
        Kinematics::Ancf => "ancf",
    };
    json!({
        "elements": options.elements,
        "model": model,
        "criterion": name(options.criterion),
        "load_angle_deg": crate::fe::prb::LOAD_ANGLE_DEG,
        "gamma": fit.gamma,
        "k_theta": fit.k_theta,
        "theta_max_deg": fit.theta_max_deg,
        "small_deflection": {"gamma": fit.gamma_small, "k_theta": fit.k_theta_small},
        "published": {"gamma": HOWELL_GAMMA, "k_theta": HOWELL_K_THETA, "theta_max_deg": HOWELL_THETA_MAX_DEG,
                      "theta_max_deg_on_fe_path": fit.theta_max_deg_howell_gamma},
        "other_criterion": {"criterion": name(crate::fe::prb::other_measure(options.criterion)),
                            "gamma": other.gamma, "k_theta": other.k_theta, "theta_max_deg": other.theta_max_deg},
        "spring_stiffness": {
            "note": "k L/EI: Howell k = γ K_Θ EI/L vs the paper's k_θp = π EI γ²/L",
            "fitted": stiffness(fit.gamma, fit.k_theta),
            "published": stiffness(HOWELL_GAMMA, HOWELL_K_THETA),
            "paper_small_deflection": stiffness(PAPER_GAMMA_SMALL, fit.k_theta_small),
        },
        "effective_mass": {
            "note": "beam share of the tip effective mass / m_r: FE k_tip/ω₁² − m_e vs lumped γ/3 (Eq. 5)",
            "fe_modal_no_payload": m_eff_modal,
            "fe": shares,
            "lumped_gamma_2_3": PAPER_GAMMA_SMALL / 3.0,
            "lumped_gamma_fitted": fit.gamma / 3.0,
            "lumped_gamma_1": 1.0 / 3.0,
        },
        "svg": r.svg.display().to_string(),
    })
}

/// `flexrig fit --json`.
pub fn fit_report(
    fit: &flexrig_contact::HertzFit,
    warnings: &[crate::lumped::fit::Warning],
) -> Value {
    json!({
        "k": fit.k,
        "n": fit.n,
        "r2": fit.r2,
        "k_stderr": fit.k_stderr,
        "n_stderr": fit.n_stderr,
        "rms_residual_n": fit.rms_residual_n,
        "points": fit.points,
        "skipped": fit.skipped,
        "iterations": fit.iterations,
        "warnings": warnings,
    })
}

/// The beam of `flexrig beam` as the user gives it: each number a flag (or keyword), or taken
/// from the link of `scene` (a bundled name or a scene file) when not given; a flag given
/// overrides the scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BeamFlags {
    /// `--scene`: the scene whose robot link gives L, E, ρ, w, t, the tip mass (its payload)
    /// and the elements.
    pub scene: Option<PathBuf>,
    /// `--length` \[m\].
    pub length: Option<f64>,
    /// `--youngs` \[Pa\].
    pub youngs: Option<f64>,
    /// `--density` [kg/m³] (the modal analysis needs it).
    pub density: Option<f64>,
    /// `--width` \[m\].
    pub width: Option<f64>,
    /// `--thickness` \[m\].
    pub thickness: Option<f64>,
    /// `--elements` (default 16, or the scene's).
    pub elements: Option<usize>,
    /// `--tip-mass` \[kg\] (default 0, or the scene's payload).
    pub tip_mass: Option<f64>,
    /// `--root`: `clamped` or `pinned`.
    pub root: String,
    /// `--k-theta` [N·m/rad].
    pub k_theta: f64,
}

/// Elements of `flexrig beam` when neither `--elements` nor a scene gives them.
pub const BEAM_ELEMENTS: usize = 16;

/// The beam of `flexrig beam`'s flags (the scene's link filling what is not given), its
/// numbers checked before its `root` (`clamped`, `pinned`); errors name the flag, a missing
/// number says to give it or `--scene`. With the beam: the scene's origin, if one was taken.
pub fn beam_input(
    flags: &BeamFlags,
) -> Result<(crate::fe::beam::BeamInput, Option<String>), Error> {
    use crate::fe::beam::{BeamInput, Root};
    let link = match &flags.scene {
        Some(path) => Some(crate::fe::beam::scene_link("--scene", path)?),
        None => None,
    };
    let need = |flag: &str, given: Option<f64>, from_scene: Option<f64>| {
        given.or(from_scene).ok_or_else(|| {
            invalid(
                flag,
                "(missing)",
                "give it, or take the link of a scene with --scene NAME|PATH",
            )
        })
    };
    let l = link.as_ref();
    let mut beam = BeamInput {
        length: need("--length", flags.length, l.map(|l| l.length))?,
        youngs: need("--youngs", flags.youngs, l.map(|l| l.youngs))?,
        density: flags.density.or(l.map(|l| l.density)),
        width: need("--width", flags.width, l.map(|l| l.width))?,
        thickness: need("--thickness", flags.thickness, l.map(|l| l.thickness))?,
        elements: flags
            .elements
            .or(l.map(|l| l.elements))
            .unwrap_or(BEAM_ELEMENTS),
        tip_mass: flags.tip_mass.or(l.map(|l| l.tip_mass)).unwrap_or(0.0),
        root: Root::Clamped,
        k_theta: flags.k_theta,
    };
    beam.check_ranges()?;
    beam.root = match flags.root.as_str() {
        "clamped" => Root::Clamped,
        "pinned" => Root::Pinned,
        other => return Err(invalid("--root", other, "must be clamped or pinned")),
    };
    Ok((beam, link.map(|l| l.origin)))
}

/// `flexrig beam static`: the solve of `beam` under `load` with its plausibility warnings
/// (`yield_strength` \[Pa\], `--yield-strength`, checked first).
pub fn beam_static(
    beam: &crate::fe::beam::BeamInput,
    load: &crate::fe::beam::TipLoad,
    yield_strength: Option<f64>,
) -> Result<
    (
        crate::fe::beam::TipDisplacement,
        Vec<crate::fe::beam::Warning>,
    ),
    Error,
> {
    crate::fe::beam::check_yield_strength(yield_strength)?;
    let sol = crate::fe::beam::statics(beam, load)?;
    let warnings = crate::fe::beam::static_warnings(beam, load, &sol, yield_strength);
    Ok((sol, warnings))
}

/// The natural frequencies of `flexrig beam modal` [Hz] (the element count checked first).
pub fn beam_modal(beam: &crate::fe::beam::BeamInput, modes: usize) -> Result<Vec<f64>, Error> {
    crate::fe::beam::check_modal_elements(beam.elements)?;
    crate::fe::beam::modal(beam, modes)
}

/// `flexrig beam modal --json` (`scene`: where the link came from, if from a scene).
pub fn beam_modal_report(
    frequencies_hz: &[f64],
    warnings: &[crate::fe::beam::Warning],
    scene: Option<&str>,
) -> Value {
    without_nulls(json!({ "frequencies_hz": frequencies_hz, "warnings": warnings, "scene": scene }))
}

/// `report` without its absent (null) entries: a report holds no `null`.
fn without_nulls(mut report: Value) -> Value {
    if let Some(map) = report.as_object_mut() {
        map.retain(|_, v| !v.is_null());
    }
    report
}

/// The tip load of `flexrig beam static`: force [N], moment [N·m], `model` (`linear`,
/// `corotational`, `ancf`), load steps, whether they are adaptive; errors name the flag.
pub fn beam_tip_load(
    force: f64,
    moment: f64,
    model: &str,
    load_steps: usize,
    adaptive_steps: bool,
) -> Result<crate::fe::beam::TipLoad, Error> {
    use crate::fe::beam::Kinematics;
    let kinematics = match model {
        "linear" => Kinematics::Linear,
        "corotational" => Kinematics::Corotational,
        "ancf" => Kinematics::Ancf,
        other => {
            return Err(invalid(
                "--model",
                other,
                "must be linear, corotational or ancf",
            ));
        }
    };
    let load = crate::fe::beam::TipLoad {
        force,
        moment,
        kinematics,
        load_steps,
        adaptive_steps,
    };
    load.validate()?;
    Ok(load)
}

/// `flexrig beam static --json` (`model` as typed; `scene`: where the link came from, if from
/// a scene; `yield_strength` \[Pa\] if given).
pub fn beam_static_report(
    sol: &crate::fe::beam::TipDisplacement,
    model: &str,
    warnings: &[crate::fe::beam::Warning],
    scene: Option<&str>,
    yield_strength: Option<f64>,
) -> Value {
    let s = &sol.stress;
    without_nulls(json!({
        "max_stress_pa": s.max_pa,
        "max_stress": {
            "stress_pa": s.max_pa,
            "bending_pa": s.bending_pa,
            "axial_pa": s.axial_pa,
            "moment_nm": s.moment_nm,
            "axial_force_n": s.axial_n,
            "at_m": s.at_m,
        },
        "yield_strength_pa": yield_strength,
        "warnings": warnings,
        "scene": scene,
        "tip_u_m": sol.u,
        "tip_v_m": sol.v,
        "tip_angle_rad": sol.angle,
        "iterations": sol.iterations,
        "residual_n": sol.residual,
        "load_level": sol.load_level,
        "model": model,
    }))
}

/// `flexrig validate --json`.
pub fn validation_report(r: &crate::quality::validation::ValidationReport) -> Value {
    json!({ "cases": r.cases, "report": r.report })
}

#[cfg(test)]
mod tests;
