//! `flexrig role-switch`: the test bed's peak against the driven robot's for the test-bed link
//! and the Fig. 6 cases, see [`flexrig::driven::role_switch`]; a table or JSON.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use flexrig::driven::role_switch::{RoleSwitchOptions, design_name, run_with_figures as run_table};
use flexrig::{CancelToken, Error};

use crate::print::{line, print_json};

/// Arguments of `flexrig role-switch`.
#[derive(Debug, Args)]
pub struct RoleSwitchArgs {
    /// Directory for role_switch.csv and the figure role_switch.svg (or .pdf, .png; created if
    /// missing).
    #[arg(long, value_name = "DIR", default_value = "out")]
    pub out: PathBuf,
    /// PD loop stiffnesses κ = K_p/k_θr, comma-separated, each > 0 (the ideal position source
    /// and the torque-free rotor are always added).
    #[arg(
        long,
        value_name = "K,...",
        value_delimiter = ',',
        default_value = "10000,100,1,0.01"
    )]
    pub kappa: Vec<f64>,
    /// Rotor inertia J_R over the link's m_r L²/3 (> 0).
    #[arg(long, value_name = "RATIO", default_value_t = RoleSwitchOptions::default().rotor_ratio)]
    pub rotor_ratio: f64,
    /// Damping ratio ζ of the PD loops (≥ 0).
    #[arg(long, value_name = "ZETA", default_value_t = RoleSwitchOptions::default().damping_ratio)]
    pub damping_ratio: f64,
    /// Only the test bed's cases (leave out the Fig. 6 cases).
    #[arg(long)]
    pub no_fig6: bool,
    /// The link's model: exact (the link bends and turns geometrically exactly; the whole table
    /// takes minutes) or linear (seconds; every ratio within 4.3e-3 of the exact one,
    /// docs/driven.md).
    #[arg(long, value_enum, default_value_t = super::strike::LinkModelArg::Exact)]
    pub link_model: super::strike::LinkModelArg,
    /// Print JSON instead of the table.
    #[arg(long)]
    pub json: bool,
    /// The figure's printed width and formats.
    #[command(flatten)]
    pub figure: super::figure_args::FigureArgs,
}

/// Runs `flexrig role-switch`.
pub fn run(args: &RoleSwitchArgs, out: &mut dyn Write, cancel: &CancelToken) -> Result<(), Error> {
    let options = RoleSwitchOptions {
        kappas: args.kappa.clone(),
        rotor_ratio: args.rotor_ratio,
        damping_ratio: args.damping_ratio,
        fig6: !args.no_fig6,
        link_model: args.link_model.model(),
    };
    let r = run_table(&options, &args.out, &args.figure.options()?, cancel)?;
    if args.json {
        return print_json(out, &flexrig::fronts::role_switch_report(&r));
    }
    line(
        out,
        "Role switch: f_driven/f_test bed (robot at v0 under its drive into the head at rest, over the head at v0 on the held robot)",
    )?;
    let per_case = options.kappas.len() + 2;
    // the case column as wide as its longest name (in characters: κ, δ, ⁸ and · are one each)
    let width = r
        .rows
        .iter()
        .map(|row| row.case.chars().count())
        .max()
        .unwrap_or(0)
        .max("case".len());
    let pad = |text: &str| format!("{text}{}", " ".repeat(width - text.chars().count()));
    let mut header = format!("{} {:>3} {:>11}", pad("case"), "", "test bed[N]");
    header.push_str(&format!(" {:>9}", "prescr."));
    for k in &options.kappas {
        header.push_str(&format!(
            " {:>9}",
            format!("κ={}", flexrig::shared::output::display_number(*k))
        ));
    }
    header.push_str(&format!(" {:>9}", "free"));
    line(out, header)?;
    for chunk in r.rows.chunks(per_case) {
        let mut text = format!(
            "{} {:>3} {:>11.1}",
            pad(&chunk[0].case),
            design_name(chunk[0].design),
            chunk[0].f_test_bed_n
        );
        for row in chunk {
            text.push_str(&format!(" {:>9.4}", row.ratio));
        }
        line(out, text)?;
    }
    line(
        out,
        format!(
            "Wrote {} and {}",
            r.csv.display(),
            r.figures
                .iter()
                .map(|p| p.display().to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    )
}
