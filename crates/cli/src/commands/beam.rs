//! `flexrig beam modal|static`: natural frequencies and static tip deflection of the
//! finite-element Euler–Bernoulli beam, see [`flexrig::beam`].

use std::io::Write;

use clap::{Args, Subcommand};
use flexrig::beam::{BeamInput, check_modal_elements};

use crate::print::{line, print_json};
use flexrig::Error;

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
    /// Beam length L [m].
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub length: f64,
    /// Young's modulus E [Pa].
    #[arg(long, value_name = "PA", allow_negative_numbers = true)]
    pub youngs: f64,
    /// Mass density ρ [kg/m³].
    #[arg(long, value_name = "KG_M3", allow_negative_numbers = true)]
    pub density: f64,
    /// Section width w [m] (the stiff direction).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub width: f64,
    /// Section thickness t [m] (bending direction), I = w t³/12.
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub thickness: f64,
    /// Number of Hermite-cubic elements N (1 to 100000; `beam modal` at most 1000: a dense
    /// eigenproblem). The stiffness matrix's condition grows as N⁴: on slender beams a few
    /// thousand elements already cost digits (a clear "singular" error beyond).
    #[arg(long, value_name = "N", default_value_t = 16)]
    pub elements: usize,
    /// Point mass at the tip [kg] (rotary inertia neglected).
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
    /// Dead tip force perpendicular to the undeformed beam [N] (+ toward +v).
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

/// The library's beam from the flags ([`flexrig::fronts::beam_input`]; the error names the flag).
pub fn beam_input(a: &BeamArgs) -> Result<BeamInput, Error> {
    flexrig::fronts::beam_input(
        a.length,
        a.youngs,
        a.density,
        a.width,
        a.thickness,
        a.elements,
        a.tip_mass,
        &a.root,
        a.k_theta,
    )
}

/// Runs a beam sub-command.
pub fn run(cmd: &BeamCommand, out: &mut dyn Write) -> Result<(), Error> {
    match cmd {
        BeamCommand::Modal(args) => modal(args, out),
        BeamCommand::Static(args) => statics(args, out),
    }
}

fn modal(args: &ModalArgs, out: &mut dyn Write) -> Result<(), Error> {
    check_modal_elements(args.beam.elements)?;
    let frequencies_hz = flexrig::fronts::beam_modal(&beam_input(&args.beam)?, args.modes)?;
    if args.beam.json {
        print_json(out, &flexrig::fronts::beam_modal_report(&frequencies_hz))
    } else {
        line(
            out,
            format!(
                "bending modes ({} elements, {} root):",
                args.beam.elements, args.beam.root
            ),
        )?;
        for (i, f) in frequencies_hz.iter().enumerate() {
            line(out, format!("  mode {}: {f:.6} Hz", i + 1))?;
        }
        Ok(())
    }
}

fn statics(args: &StaticArgs, out: &mut dyn Write) -> Result<(), Error> {
    let load = flexrig::fronts::beam_tip_load(
        args.tip_load,
        args.tip_moment,
        &args.model,
        args.load_steps,
    )?;
    let sol = flexrig::beam::statics(&beam_input(&args.beam)?, &load)?;
    let (u, v, th) = (sol.u, sol.v, sol.angle);
    if args.beam.json {
        print_json(out, &flexrig::fronts::beam_static_report(&sol, &args.model))
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
