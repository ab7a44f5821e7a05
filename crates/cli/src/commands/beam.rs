//! `flexrig beam modal|static`: natural frequencies and static tip deflection of the
//! finite-element Euler–Bernoulli beam, see [`flexrig::fe::beam`].

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, Subcommand};
use flexrig::fe::beam::{BeamInput, Warning};
use flexrig::fronts::BeamFlags;

use crate::print::{line, print_json};
use flexrig::Error;

/// Beam sub-commands.
#[derive(Debug, Subcommand)]
pub enum BeamCommand {
    /// Natural frequencies of the bending modes in the thickness direction (ascending; a pinned
    /// root without spring reports its rigid mode as 0 Hz).
    Modal(ModalArgs),
    /// Tip displacement and largest stress under a dead tip load perpendicular to the
    /// undeformed beam (and an optional tip moment), linear (small deflection), corotational or
    /// ANCF (large deflection).
    Static(StaticArgs),
}

/// The beam shared by `beam modal` and `beam static`: its numbers as flags, or the link of a
/// scene (`--scene`), the flags given overriding the scene's values.
#[derive(Debug, Clone, Args)]
pub struct BeamArgs {
    /// Take the beam from the robot link of a scene (a bundled name, `flexrig scenes` lists
    /// them, or a scene file): its length, E, ρ, width, thickness, payload (the tip mass) and
    /// elements. Flags given as well override the scene's values.
    #[arg(long, value_name = "NAME|PATH")]
    pub scene: Option<PathBuf>,
    /// Beam length L [m] (required without --scene).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub length: Option<f64>,
    /// Young's modulus E [Pa] (required without --scene).
    #[arg(long, value_name = "PA", allow_negative_numbers = true)]
    pub youngs: Option<f64>,
    /// Mass density ρ [kg/m³] (`beam modal` only; required there without --scene).
    #[arg(long, value_name = "KG_M3", allow_negative_numbers = true)]
    pub density: Option<f64>,
    /// Section width w [m] (the stiff direction; required without --scene).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub width: Option<f64>,
    /// Section thickness t [m] (bending direction), I = w t³/12 (required without --scene).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub thickness: Option<f64>,
    /// Number of Hermite-cubic elements N (1 to 100000; `beam modal` at most 1000: a dense
    /// eigenproblem) [default: 16, or the scene's]. The stiffness matrix's condition grows as
    /// N⁴: on slender beams a few thousand elements already cost digits (a clear "singular"
    /// error beyond).
    #[arg(long, value_name = "N")]
    pub elements: Option<usize>,
    /// Point mass at the tip [kg] (rotary inertia neglected) [default: 0, or the scene's
    /// payload].
    #[arg(long, value_name = "KG", allow_negative_numbers = true)]
    pub tip_mass: Option<f64>,
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
    #[arg(
        long,
        value_name = "linear|corotational|ancf",
        default_value = "linear"
    )]
    pub model: String,
    /// Load increments of the large-deflection Newton solve (≥ 1).
    #[arg(long, value_name = "K", default_value_t = 10)]
    pub load_steps: usize,
    /// Adaptive load increments: the first is 1/K of the load (`--load-steps 1`: the whole
    /// load at once), halved where Newton fails and doubled after each converged one; the same
    /// equilibrium as K fixed increments, usually in far fewer Newton iterations.
    #[arg(long)]
    pub adaptive_steps: bool,
    /// Yield strength of the material [Pa]: a warning when the largest stress exceeds it
    /// (e.g. polypropylene about 3e7, aluminium 6061-T6 2.76e8).
    #[arg(long, value_name = "PA", allow_negative_numbers = true)]
    pub yield_strength: Option<f64>,
}

/// The library's beam from the flags ([`flexrig::fronts::beam_input`]; the error names the
/// flag) and the scene it was taken from, if any.
pub fn beam_input(a: &BeamArgs) -> Result<(BeamInput, Option<String>), Error> {
    flexrig::fronts::beam_input(&BeamFlags {
        scene: a.scene.clone(),
        length: a.length,
        youngs: a.youngs,
        density: a.density,
        width: a.width,
        thickness: a.thickness,
        elements: a.elements,
        tip_mass: a.tip_mass,
        root: a.root.clone(),
        k_theta: a.k_theta,
    })
}

/// The warnings on standard error, one a line.
fn print_warnings(warnings: &[Warning]) {
    for w in warnings {
        eprintln!("warning: {w}");
    }
}

/// The beam in words: `L = 0.338 m, E = 1.5e9 Pa, …` (and its scene).
fn describe(beam: &BeamInput, scene: Option<&str>) -> String {
    use flexrig::shared::output::display_number as n;
    let mut s = format!(
        "L = {} m, E = {} Pa, w = {} m, t = {} m",
        n(beam.length),
        n(beam.youngs),
        n(beam.width),
        n(beam.thickness)
    );
    if let Some(rho) = beam.density {
        s.push_str(&format!(", ρ = {} kg/m³", n(rho)));
    }
    if beam.tip_mass > 0.0 {
        s.push_str(&format!(", tip mass {} kg", n(beam.tip_mass)));
    }
    if let Some(origin) = scene {
        s.push_str(&format!(" (the link of {origin})"));
    }
    s
}

/// Runs a beam sub-command.
pub fn run(cmd: &BeamCommand, out: &mut dyn Write) -> Result<(), Error> {
    match cmd {
        BeamCommand::Modal(args) => modal(args, out),
        BeamCommand::Static(args) => statics(args, out),
    }
}

fn modal(args: &ModalArgs, out: &mut dyn Write) -> Result<(), Error> {
    if let Some(elements) = args.beam.elements {
        flexrig::fe::beam::check_modal_elements(elements)?;
    }
    let (beam, scene) = beam_input(&args.beam)?;
    let frequencies_hz = flexrig::fronts::beam_modal(&beam, args.modes)?;
    let warnings = flexrig::fe::beam::beam_warnings(&beam);
    print_warnings(&warnings);
    if args.beam.json {
        print_json(
            out,
            &flexrig::fronts::beam_modal_report(&frequencies_hz, &warnings, scene.as_deref()),
        )
    } else {
        line(out, describe(&beam, scene.as_deref()))?;
        line(
            out,
            format!(
                "bending modes ({} elements, {} root):",
                beam.elements,
                beam.root.name()
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
        args.adaptive_steps,
    )?;
    let (beam, scene) = beam_input(&args.beam)?;
    let (sol, warnings) = flexrig::fronts::beam_static(&beam, &load, args.yield_strength)?;
    print_warnings(&warnings);
    let (u, v, th) = (sol.u, sol.v, sol.angle);
    if args.beam.json {
        return print_json(
            out,
            &flexrig::fronts::beam_static_report(
                &sol,
                &args.model,
                &warnings,
                scene.as_deref(),
                args.yield_strength,
            ),
        );
    }
    line(out, describe(&beam, scene.as_deref()))?;
    line(
        out,
        format!(
            "{} static solve ({} elements, {} Newton iteration{}):",
            args.model,
            beam.elements,
            sol.iterations,
            if sol.iterations == 1 { "" } else { "s" }
        ),
    )?;
    line(out, format!("  tip u (axial)      = {u:.9e} m"))?;
    line(out, format!("  tip v (transverse) = {v:.9e} m"))?;
    line(out, format!("  tip angle          = {th:.9e} rad"))?;
    line(
        out,
        format!("  residual           = {:.3e} N", sol.residual),
    )?;
    let s = &sol.stress;
    let place = if s.at_m == 0.0 {
        "at the root".to_string()
    } else {
        format!("{:.6} m from the root", s.at_m)
    };
    line(
        out,
        format!(
            "  largest stress     = {:.6e} Pa ({:.4} MPa) {place}",
            s.max_pa,
            s.max_pa / 1e6
        ),
    )?;
    line(
        out,
        format!(
            "    bending |M| t/(2I) = {:.6e} Pa (M = {:.6e} N·m)",
            s.bending_pa, s.moment_nm
        ),
    )?;
    if load.kinematics != flexrig::fe::beam::Kinematics::Linear {
        line(
            out,
            format!(
                "    axial |N|/A        = {:.6e} Pa (N = {:.6e} N)",
                s.axial_pa, s.axial_n
            ),
        )?;
    }
    if let Some(y) = args.yield_strength {
        line(
            out,
            format!(
                "  yield strength     = {:.6e} Pa (stress / yield = {:.3})",
                y,
                s.max_pa / y
            ),
        )?;
    }
    Ok(())
}
