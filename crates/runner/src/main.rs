//! `flexrig`: see `flexrig --help`.

use clap::Parser;

fn main() {
    let cli = flexrig::cli::Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    if let Err(err) = flexrig::cli::run(&cli, &mut out) {
        eprintln!("error: {err}");
        std::process::exit(err.exit_code());
    }
}
