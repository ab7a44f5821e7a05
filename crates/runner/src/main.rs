//! `flexrig`: see `flexrig --help`.

use clap::Parser;

fn main() {
    let cli = flexrig::cli::Cli::parse();
    // Ctrl-C asks running simulations to stop; their MCAP logs are finished with an error record.
    let interrupt = flexrig::cli::Interrupt::default();
    let flag = interrupt.0.clone();
    let _ = ctrlc::set_handler(move || flag.store(true, std::sync::atomic::Ordering::Relaxed));
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    if let Err(err) = flexrig::cli::run_interruptible(&cli, &mut out, &interrupt) {
        eprintln!("error: {err}");
        std::process::exit(err.exit_code());
    }
}
