//! `flexrig run SCENE`: one run of the drop-pendulum test rig ([`flexrig::testbed::run`]).

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::driven::scene::DrivenSummary;
use flexrig::log::mcap::{DEFAULT_DEFORMATION_SCALE, LogRates};
use flexrig::shared::output::positive_arg;
use flexrig::testbed::link::LinkQuantities;
use flexrig::testbed::run::{LogRequest, SceneRun, run_scene_file, scene_warnings};
use flexrig::{CancelToken, Error};

use crate::print::{line, parse_overrides, print_json, print_severity};

/// Arguments of `flexrig run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// A bundled scene's name (e.g. cj_aluminium; `flexrig scenes` lists them) or a scene
    /// file's path (TOML, see docs/scenes.md).
    #[arg(value_name = "SCENE")]
    pub scene: PathBuf,
    /// File (MCAP) to write the run's traces to; it opens in Foxglove (see docs/foxglove.md).
    #[arg(long, value_name = "FILE.mcap")]
    pub out: Option<PathBuf>,
    /// Overwrite the --out file if it exists.
    #[arg(long)]
    pub force: bool,
    /// Log every step and sensor sample on every channel (default: the 3D view at 60 Hz and the
    /// sensors at 250 Hz outside contact; inside contact everything is logged either way).
    #[arg(long, requires = "out")]
    pub log_every_step: bool,
    /// Factor on the CL beam's deflection in the log's 3D view (FE post-processing style,
    /// labelled in the view and recorded in the log; 1 = true scale; the CJ link is rigid).
    #[arg(long, requires = "out", value_name = "FACTOR", default_value_t = DEFAULT_DEFORMATION_SCALE)]
    pub deformation_scale: f64,
    /// Override a scene field, e.g. `--set robot.payload_kg=0.2` or
    /// `--set operator.start.release_angle_deg=45` (repeatable; validated like the file).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Runs `flexrig run`.
pub fn run(args: &RunArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let rates = if args.log_every_step {
        LogRates::EVERY_STEP
    } else {
        LogRates::DECIMATED
    };
    let overrides = parse_overrides(&args.set)?;
    let deformation_scale = positive_arg("--deformation-scale", args.deformation_scale)?;
    // plausibility warnings before the run (on standard error; the JSON lists them too)
    for w in scene_warnings(&args.scene, &overrides) {
        eprintln!("warning: {w}");
    }
    let run = run_scene_file(
        &args.scene,
        &overrides,
        LogRequest {
            out: args.out.as_ref(),
            force: args.force,
            rates,
            deformation_scale,
        },
        cancel,
    )?;
    if args.json {
        return print_json(out, &run.summary_json());
    }
    let (s, link) = match &run {
        SceneRun::Rig(s, link) => (s, link),
        SceneRun::Driven(d, link) => return print_driven(out, args, &d.summary, link),
    };
    // a `cj_`/`cl_` name whose design was overridden is named by the design that ran
    let name = flexrig::log::mcap::name_as_run(&s.scene, s.design);
    if name == s.scene {
        line(out, format!("scene {} ({})", s.scene, s.design))?;
    } else {
        line(out, format!("scene {name}"))?;
    }
    if let Some(path) = &args.out {
        line(out, format!("  log                 {}", path.display()))?;
    }
    line(
        out,
        format!(
            "  peak force          {:.6} N at t = {:.6} s",
            s.peak_force_n, s.time_of_peak_s
        ),
    )?;
    line(
        out,
        format!(
            "  impact velocity     {:.6} m/s (onset at {:.6} s)",
            s.impact_velocity_mps, s.onset_time_s
        ),
    )?;
    match s.contact_duration_s {
        Some(d) => line(out, format!("  contact duration    {:.6e} s", d))?,
        None => line(out, "  contact duration    (stopped before separation)")?,
    }
    line(
        out,
        format!("  max indentation     {:.6e} m", s.max_indentation_m),
    )?;
    line(
        out,
        format!("  impulse             {:.6e} N·s", s.impulse_n_s),
    )?;
    let in_contact = if s.contact_integration.is_adaptive() {
        "adaptive contact".to_string()
    } else {
        format!("at {:.3e} s", s.contact_step_s)
    };
    line(
        out,
        format!(
            "  steps               {} ({} in contact, {in_contact}), {} sensor samples",
            s.steps, s.contact_steps, s.sample_count
        ),
    )?;
    if let Some(d) = &s.drive {
        line(
            out,
            format!(
                "  drive               motor work {:.6e} J (friction {:.6e} J), largest joint torque {:.6e} N·m",
                d.motor_work_j, d.friction_dissipated_j, d.peak_joint_torque_nm
            ),
        )?;
        for note in flexrig::testbed::run::drive_notes(s) {
            line(out, format!("  note: {note}"))?;
        }
        if let (Some(speed), Some(bent)) = (d.link_speed_at_onset_rad_s, d.pre_impact_deflection_m)
        {
            let commanded = d
                .commanded_speed_at_onset_rad_s
                .map_or(String::new(), |c| format!(" (commanded {c:.6} rad/s)"));
            line(
                out,
                format!(
                    "  at the onset        link {speed:.6} rad/s{commanded}, tip {bent:.6e} m from the hub's line (towards the operator)"
                ),
            )?;
        }
    }
    print_link(out, link)?;
    if let Some(severity) = &s.severity {
        print_severity(out, severity, "operator block, its accelerometer")?;
    }
    Ok(())
}

/// The text summary of a driven scene's run.
fn print_driven(
    out: &mut dyn Write,
    args: &RunArgs,
    s: &DrivenSummary,
    link: &LinkQuantities,
) -> Result<(), Error> {
    let design = match s.design {
        flexrig::driven::strike::StrikeDesign::Cj => "CJ",
        flexrig::driven::strike::StrikeDesign::Cl => "CL",
    };
    let head = match s.head {
        "wall" => "a head against a wall",
        "neck" => "a head on a neck",
        _ => "a free head",
    };
    let command = match s.command {
        "trajectory" => "prescribed trajectory",
        "controller" => "feedback controller",
        _ => "open-loop torque",
    };
    line(
        out,
        format!("scene {} (driven {design}, {command}, {head})", s.scene),
    )?;
    if let Some(path) = &args.out {
        line(out, format!("  log                 {}", path.display()))?;
    }
    line(
        out,
        format!(
            "  peak force          {:.6} N at t = {:.6} s",
            s.peak_force_n, s.time_of_peak_s
        ),
    )?;
    let commanded = s
        .commanded_tip_speed_mps
        .map(|c| format!(", commanded {c:.6} m/s"))
        .unwrap_or_default();
    line(
        out,
        format!(
            "  impact velocity     {:.6} m/s (onset at {:.6} s{commanded})",
            s.impact_velocity_mps, s.onset_time_s
        ),
    )?;
    line(
        out,
        format!("  contact duration    {:.6e} s", s.contact_duration_s),
    )?;
    line(
        out,
        format!("  max indentation     {:.6e} m", s.max_indentation_m),
    )?;
    line(
        out,
        format!("  impulse             {:.6e} N·s", s.impulse_n_s),
    )?;
    line(
        out,
        format!(
            "  pre-impact deflection {:.6e} m (tip from the hub's line)",
            s.pre_impact_deflection_m
        ),
    )?;
    line(
        out,
        format!(
            "  joint speed         {:.6} rad/s at the onset",
            s.joint_speed_at_contact_rad_s
        ),
    )?;
    line(
        out,
        format!(
            "  motor torque peak   {:.6} N·m at the motor ({:.6} N·m at the joint; {:.6} N·m at the onset)",
            s.peak_motor_torque_nm, s.peak_joint_torque_nm, s.joint_torque_at_onset_nm
        ),
    )?;
    line(
        out,
        format!(
            "  energy (contact)    motor work {:.6e} J, dissipated {:.6e} J, balance residual {:.3e} J",
            s.motor_work_j, s.dissipated_j, s.energy_residual_j
        ),
    )?;
    for note in &s.notes {
        line(out, format!("  note: {note}"))?;
    }
    line(
        out,
        format!(
            "  steps               {}, {} trace samples",
            s.steps, s.samples
        ),
    )?;
    if let Some(severity) = &s.severity {
        let struck = if s.head == "wall" {
            "the head against a wall; it does not move, so no acceleration and no HIC"
        } else {
            "the head, its acceleration from the contact and neck forces"
        };
        print_severity(out, severity, struck)?;
    }
    print_link(out, link)
}

/// The link quantities, with the paper's symbols (Eq. 1–3, 5).
fn print_link(out: &mut dyn Write, q: &LinkQuantities) -> Result<(), Error> {
    line(
        out,
        format!(
            "  link                m_r = {:.6} kg, EI = {:.6e} N·m², m_e/m_r = {:.6}",
            q.m_r_kg, q.ei_n_m2, q.m_e_over_m_r
        ),
    )?;
    line(
        out,
        format!(
            "  link stiffness      k_δ = {:.6e} N/m at the tip, k_θr = {:.6e} N·m/rad (the CJ's spring, the CL's equivalent 3EI/L)",
            q.k_delta_n_per_m, q.k_theta_r_nm_per_rad
        ),
    )
}
