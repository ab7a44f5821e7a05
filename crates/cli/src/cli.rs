//! Command-line interface (clap): the commands and their dispatch.

use std::io::Write;
use std::path::PathBuf;

use clap::{Parser, Subcommand};

use crate::commands;
use flexrig::{CancelToken, Error};

/// flexrig: flexible-multibody impact simulator — compliant joint (CJ) versus compliant link (CL).
///
/// Without a command, runs the main job on the bundled defaults and says where its output is.
#[derive(Debug, Parser)]
#[command(
    name = "flexrig",
    version,
    about = "flexrig: impact simulation of flexible robot links for safe human–robot interaction \
             — the compliant joint (CJ) against the compliant link (CL)",
    long_about = None,
    after_help = "Without a command, flexrig replays the paper's §VI experiment (Fig. 9) as \
                  `flexrig experiment --out out` does: 5 repeats of each scene with release-angle \
                  jitter, a table, out/experiment.csv, out/fig9.svg and an MCAP log per run. \
                  `flexrig <COMMAND> --help` describes each command."
)]
pub struct Cli {
    /// The command to run; none runs the default job.
    #[command(subcommand)]
    pub command: Option<Command>,
}

impl Cli {
    /// Parses the process's arguments as [`Cli::try_parse`] does, except that every command
    /// takes a negative number as a flag's value (`--speed -1` reaches the range check and its
    /// message instead of clap's "unexpected argument '-1'").
    pub fn try_parse_args() -> Result<Cli, clap::Error> {
        use clap::{CommandFactory, FromArgMatches};
        fn negatives(c: clap::Command) -> clap::Command {
            c.allow_negative_numbers(true).mut_subcommands(negatives)
        }
        let matches = negatives(Cli::command()).try_get_matches()?;
        Cli::from_arg_matches(&matches)
    }
}

/// The `flexrig` commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Replay the paper's §VI experiment (Fig. 9): CJ vs CL, two operators, repeats with
    /// release-angle jitter, and the light-load case; an MCAP log per run.
    Experiment(commands::experiment::ExperimentArgs),
    /// Run a scene of the drop-pendulum test rig (CJ or CL) and print its impact summary.
    Run(commands::run::RunArgs),
    /// The bundled scenes, one line each; `--write NAME` writes one to edit.
    Scenes(commands::scenes::ScenesArgs),
    /// Run a base scene over a grid (or zip) of scene fields, in parallel, into one table;
    /// resumable, shardable for a cluster (`flexrig sweep merge` joins the shards).
    Sweep(commands::sweep::SweepArgs),
    /// Peak force of the lumped two-mass impact (paper Eq. 10–14) by the exact energy balance,
    /// the n = 1 closed form, or time integration.
    Impact(commands::impact::ImpactArgs),
    /// The paper's Fig. 6: η(γ) = f_max(γ)/f_max(1) for the eight design cases, n = 1 and n = 2.
    Fig6(commands::fig6::Fig6Args),
    /// The Fig. 6 cases at finite-element fidelity: a free head on the FE compliant link and the
    /// rigid compliant joint, η_FE beside the lumped η(2/3), and the effective γ.
    Eta(commands::eta::EtaArgs),
    /// Maps of η_FE, the lumped model's error, the effective γ and the placed model's error over
    /// m_e/m_r × k_δ/k_c, one heat-map figure per head mass.
    EtaMap(commands::eta_map::EtaMapArgs),
    /// η_FE of the Fig. 6 cases along the free hub's rotor inertia, from a freely pivoting link
    /// to the held joint.
    EtaRotor(commands::eta_rotor::EtaRotorArgs),
    /// The test bed's CL/CJ peak ratio over the payload (the paper's Fig. 9b light-load study as
    /// a curve), with MCAP logs of three payloads.
    Payload(commands::payload::PayloadArgs),
    /// Least-squares fit of the Hertz law f = k δ^n to compression data (CSV).
    Fit(commands::fit::FitArgs),
    /// Finite-element Euler–Bernoulli beam: natural frequencies and static deflection.
    #[command(subcommand)]
    Beam(commands::beam::BeamCommand),
    /// Work–precision benchmarks (run time against error) of the lumped impact, the beam and the
    /// rig, with plots.
    Bench(commands::bench::BenchArgs),
    /// Run the verification suite against every reference; writes validation.md.
    Validate(commands::validate::ValidateArgs),
    /// Check the Pseudo-Rigid-Body model (γ, K_Θ) against the large-deflection FE beam (ANCF or
    /// corotational).
    Prb(commands::prb::PrbArgs),
    /// Permissible speed near a body region (ISO/TS 15066): the standard's formula, the energy
    /// method and the simulated impact side by side.
    Safety(commands::safety::SafetyArgs),
    /// A real arm from its URDF along a trajectory: at every sample and contact point the
    /// reflected mass along the point's velocity, the permissible speed of the compliant impact
    /// into a body region, the speed-scaling factor of the trajectory and the verdict (no
    /// arguments: the bundled UR5 and its swing).
    Arm(commands::arm::ArmArgs),
    /// Safe-speed map: the permissible speed of the CJ and the CL design over two design
    /// parameters and their ratio, by the standard's formula, the energy method or simulation.
    SafetyMap(commands::safety_map::SafetyMapArgs),
    /// The spin-up beam benchmark (Simo & Vu-Quoc's 10 m beam; `--case kane`: Kane, Ryan &
    /// Banerjee's 8 m aluminium beam): tip deflection by FE, an independent reference and the
    /// linear model.
    SpinUp(commands::spin_up::SpinUpArgs),
    /// One driven CJ or CL strike (motor, gear, controller) from a drive description or flags.
    Strike(commands::strike::StrikeArgs),
    /// The role-switch table: the test bed's peak against the driven robot's.
    RoleSwitch(commands::role_switch::RoleSwitchArgs),
}

/// Where the default job writes its files.
pub const DEFAULT_OUT_DIR: &str = "out";

/// Runs the parsed command line, writing the report to `out`.
pub fn run(cli: &Cli, out: &mut dyn Write) -> Result<(), Error> {
    run_cancellable(cli, out, &CancelToken::new())
}

/// As [`run`], stopping simulations when `cancel` is set (by the binary's Ctrl-C handler); logs
/// are finished with an `error` record.
pub fn run_cancellable(cli: &Cli, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    match &cli.command {
        None => commands::default_job(&PathBuf::from(DEFAULT_OUT_DIR), out, cancel),
        Some(Command::Experiment(args)) => commands::experiment::run(args, out, cancel),
        Some(Command::Run(args)) => commands::run::run(args, out, cancel),
        Some(Command::Scenes(args)) => commands::scenes::run(args, out),
        Some(Command::Sweep(args)) => commands::sweep::run(args, out, cancel),
        Some(Command::Impact(args)) => commands::impact::run(args, out),
        Some(Command::Fig6(args)) => commands::fig6::run(args, out),
        Some(Command::Eta(args)) => commands::eta::run(args, out, cancel),
        Some(Command::EtaMap(args)) => commands::eta_map::run(args, out, cancel),
        Some(Command::EtaRotor(args)) => commands::eta_rotor::run(args, out, cancel),
        Some(Command::Fit(args)) => commands::fit::run(args, out),
        Some(Command::Payload(args)) => commands::payload::run(args, out, cancel),
        Some(Command::Beam(cmd)) => commands::beam::run(cmd, out),
        Some(Command::Prb(args)) => commands::prb::run(args, out),
        Some(Command::Validate(args)) => commands::validate::run(args, out),
        Some(Command::Bench(args)) => commands::bench::run(args, out, cancel),
        Some(Command::Safety(args)) => commands::safety::run(args, out, cancel),
        Some(Command::Arm(args)) => commands::arm::run(args, out, cancel),
        Some(Command::SafetyMap(args)) => commands::safety_map::run(args, out, cancel),
        Some(Command::SpinUp(args)) => commands::spin_up::run(args, out, cancel),
        Some(Command::Strike(args)) => commands::strike::run(args, out, cancel),
        Some(Command::RoleSwitch(args)) => commands::role_switch::run(args, out, cancel),
    }
}

/// A hint for a list given with spaces (`--m-h 4 1000`, as the help of a comma list could be
/// misread): when clap rejects an unexpected argument that is a number, the flag before it
/// and the list written as it is meant (`--m-h 4,1000`). `args` are the command line's
/// arguments (the program name first, as `std::env::args`).
pub fn list_hint(err: &clap::Error, args: &[String]) -> Option<String> {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if err.kind() == ErrorKind::InvalidValue {
        // `--method standard,`: clap sees an empty item after the comma
        let (i, list) = args.iter().enumerate().skip(1).find_map(|(i, a)| {
            let value = a.split_once('=').map_or(a.as_str(), |(_, v)| v);
            let empty_item = value.contains(',')
                && (value.starts_with(',') || value.ends_with(',') || value.contains(",,"));
            empty_item.then_some((i, value))
        })?;
        let flag = match args[i].split_once('=') {
            Some((f, _)) if f.starts_with("--") => f,
            _ => args[..i]
                .iter()
                .rev()
                .find(|a| a.starts_with("--"))?
                .as_str(),
        };
        return Some(format!(
            "tip: the list {flag} {list} has an empty item: remove the stray comma"
        ));
    }
    if err.kind() != ErrorKind::UnknownArgument {
        return None;
    }
    let Some(ContextValue::String(stray)) = err.get(ContextKind::InvalidArg) else {
        return None;
    };
    stray.parse::<f64>().ok()?;
    let at = args.iter().position(|a| a == stray)?;
    let flag_at = (1..at).rev().find(|&i| args[i].starts_with("--"))?;
    let values = &args[flag_at + 1..=at];
    Some(format!(
        "tip: a list is written with commas and no spaces: {} {}",
        args[flag_at],
        values.join(",")
    ))
}
