//! `flexrig beam modal|static`: natural frequencies and static tip deflection of the
//! finite-element Euler–Bernoulli beam (flexrig-beam) with a rectangular section bending in the
//! thickness direction.

use std::io::Write;

use clap::{Args, Subcommand};
use flexrig_beam::{
    BeamModel, BeamSpec, Kinematics, Material, ModalDirection, NodalLoads, PointMass, RootSupport,
    Section, StaticOptions, modal_analysis, solve_static,
};
use serde_json::json;

use crate::CliError;
use crate::output::{line, print_json, range_arg};

/// Beam sub-commands.
#[derive(Debug, Subcommand)]
pub enum BeamCommand {
    /// Natural frequencies of the bending modes in the thickness direction (ascending; a pinned
    /// root without spring reports its rigid mode as 0 Hz).
    Modal(ModalArgs),
    /// Tip displacement under a dead tip load perpendicular to the undeformed beam (and an
    /// optional tip moment), linear or corotational (large deflection).
    Static(StaticArgs),
}

/// The beam shared by `beam modal` and `beam static`.
#[derive(Debug, Clone, Args)]
pub struct BeamArgs {
    /// Beam length L (m).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub length: f64,
    /// Young's modulus E (Pa).
    #[arg(long, value_name = "PA", allow_negative_numbers = true)]
    pub youngs: f64,
    /// Mass density ρ [kg/m³].
    #[arg(long, value_name = "KG_M3", allow_negative_numbers = true)]
    pub density: f64,
    /// Section width w (m) (the stiff direction).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub width: f64,
    /// Section thickness t (m) (bending direction), I = w t³/12.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub thickness: f64,
    /// Number of Hermite-cubic elements N (1 to 100000; `beam modal` at most 1000: a dense
    /// eigenproblem). The stiffness matrix's condition grows as N⁴: on slender beams a few
    /// thousand elements already cost digits (a clear "singular" error beyond).
    #[arg(long, value_name = "N", default_value_t = 16)]
    pub elements: usize,
    /// Point mass at the tip (kg) (rotary inertia neglected).
    #[arg(
        long,
        value_name = "KG",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub tip_mass: f64,
    /// Root support: clamped, or pinned with the torsion spring --k-theta.
    #[arg(long, value_name = "clamped|pinned", default_value = "clamped")]
    pub root: String,
    /// Torsion spring of a pinned root [N·m/rad] (0: a free hinge).
    #[arg(
        long,
        value_name = "NM_PER_RAD",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub k_theta: f64,
    /// Print JSON instead of text.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of `flexrig beam modal`.
#[derive(Debug, Args)]
pub struct ModalArgs {
    /// The beam.
    #[command(flatten)]
    pub beam: BeamArgs,
    /// Number of modes K (≥ 1).
    #[arg(long, value_name = "K", default_value_t = 4)]
    pub modes: usize,
}

/// Arguments of `flexrig beam static`.
#[derive(Debug, Args)]
pub struct StaticArgs {
    /// The beam.
    #[command(flatten)]
    pub beam: BeamArgs,
    /// Dead tip force perpendicular to the undeformed beam (N) (+ toward +v).
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub tip_load: f64,
    /// Tip moment [N·m] (counter-clockwise, + bends toward +v).
    #[arg(
        long,
        value_name = "NM",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub tip_moment: f64,
    /// Kinematic model: linear (small deflection), corotational or ancf (large deflection; the
    /// ANCF cable element is O(h⁴) accurate against O(h²) for the corotational one).
    #[arg(long, value_name = "linear|corotational", default_value = "linear")]
    pub model: String,
    /// Load increments of the corotational Newton solve (≥ 1).
    #[arg(long, value_name = "K", default_value_t = 10)]
    pub load_steps: usize,
}

fn invalid(arg: &str, value: impl ToString, allowed: &str) -> CliError {
    CliError::InvalidArgument {
        arg: arg.into(),
        value: value.to_string(),
        allowed: allowed.into(),
    }
}

/// Builds the validated model from the flags, naming the flag on bad input.
pub fn build_model(a: &BeamArgs, kinematics: Kinematics) -> Result<BeamModel, CliError> {
    range_arg("--length", a.length, 1e-4, 1e3)?;
    range_arg("--youngs", a.youngs, 1e3, 1e13)?;
    range_arg("--density", a.density, 1e-3, 1e6)?;
    range_arg("--width", a.width, 1e-6, 10.0)?;
    range_arg("--thickness", a.thickness, 1e-7, 10.0)?;
    range_arg("--tip-mass", a.tip_mass, 0.0, 1e6)?;
    range_arg("--k-theta", a.k_theta, 0.0, 1e12)?;
    if a.elements == 0 || a.elements > flexrig_beam::model::MAX_ELEMENTS {
        return Err(invalid(
            "--elements",
            a.elements,
            "must be an integer from 1 to 100000",
        ));
    }
    let root = match a.root.as_str() {
        "clamped" | "pinned" => RootSupport::parse(&a.root, a.k_theta)?,
        other => return Err(invalid("--root", other, "must be clamped or pinned")),
    };
    let material = Material::new(a.youngs, a.density)?;
    let section = Section::rectangular(&material, a.width, a.thickness)?;
    let mut spec = BeamSpec::cantilever(a.length, section, a.elements, kinematics);
    spec.root = root;
    if a.tip_mass > 0.0 {
        spec.point_masses.push(PointMass {
            node: a.elements,
            mass: a.tip_mass,
            inertia: 0.0,
        });
    }
    Ok(BeamModel::new(spec)?)
}

/// Runs a beam sub-command.
pub fn run(cmd: &BeamCommand, out: &mut dyn Write) -> Result<(), CliError> {
    match cmd {
        BeamCommand::Modal(args) => modal(args, out),
        BeamCommand::Static(args) => statics(args, out),
    }
}

fn modal(args: &ModalArgs, out: &mut dyn Write) -> Result<(), CliError> {
    if args.beam.elements > flexrig_beam::modal::MAX_MODAL_ELEMENTS {
        return Err(invalid(
            "--elements",
            args.beam.elements,
            &format!(
                "must be at most {} for beam modal (a dense eigenproblem, O(n³))",
                flexrig_beam::modal::MAX_MODAL_ELEMENTS
            ),
        ));
    }
    let model = build_model(&args.beam, Kinematics::Linear)?;
    if args.modes == 0 {
        return Err(invalid("--modes", 0, "must be an integer >= 1"));
    }
    let r =
        modal_analysis(&model, args.modes, ModalDirection::Transverse).map_err(|e| match e {
            flexrig_beam::BeamError::InvalidParameter {
                field,
                value,
                allowed,
            } if field == "modes" => CliError::InvalidArgument {
                arg: "--modes".into(),
                value,
                allowed,
            },
            e => e.into(),
        })?;
    if args.beam.json {
        print_json(out, &json!({ "frequencies_hz": r.frequencies_hz }))
    } else {
        line(
            out,
            format!(
                "bending modes ({} elements, {} root):",
                args.beam.elements, args.beam.root
            ),
        )?;
        for (i, f) in r.frequencies_hz.iter().enumerate() {
            line(out, format!("  mode {}: {f:.6} Hz", i + 1))?;
        }
        Ok(())
    }
}

fn statics(args: &StaticArgs, out: &mut dyn Write) -> Result<(), CliError> {
    let kinematics = match args.model.as_str() {
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
    range_arg("--tip-load", args.tip_load, -1e12, 1e12)?;
    range_arg("--tip-moment", args.tip_moment, -1e12, 1e12)?;
    if args.load_steps == 0 || args.load_steps > 1_000_000 {
        return Err(invalid(
            "--load-steps",
            args.load_steps,
            "must be an integer from 1 to 1000000",
        ));
    }
    let model = build_model(&args.beam, kinematics)?;
    let tip = model.tip_node();
    let mut loads = NodalLoads::zeros(&model);
    loads.set_force(tip, 0.0, args.tip_load)?;
    loads.set_moment(tip, args.tip_moment)?;
    let sol = solve_static(
        &model,
        &loads,
        &StaticOptions::with_load_steps(args.load_steps)?,
    )?;
    let (u, v, th) = sol.node(tip);
    if args.beam.json {
        print_json(
            out,
            &json!({
                "tip_u_m": u,
                "tip_v_m": v,
                "tip_angle_rad": th,
                "iterations": sol.iterations,
                "residual_n": sol.residual,
                "load_level": sol.load_level,
                "model": args.model,
            }),
        )
    } else {
        line(
            out,
            format!(
                "{} static solve ({} elements, {} Newton iterations):",
                args.model, args.beam.elements, sol.iterations
            ),
        )?;
        line(out, format!("  tip u (axial)      = {u:.9e} m"))?;
        line(out, format!("  tip v (transverse) = {v:.9e} m"))?;
        line(out, format!("  tip angle          = {th:.9e} rad"))?;
        line(
            out,
            format!("  residual           = {:.3e} N", sol.residual),
        )
    }
}
