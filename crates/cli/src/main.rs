//! `flexrig`: see `flexrig --help`.

use clap::Parser;

fn main() {
    let cli = flexrig_cli::cli::Cli::parse();
    // Ctrl-C asks running simulations to stop; their MCAP logs are finished with an error record.
    let cancel = flexrig::CancelToken::new();
    let handler = cancel.clone();
    let _ = ctrlc::set_handler(move || handler.cancel());
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    if let Err(err) = flexrig_cli::cli::run_cancellable(&cli, &mut out, &cancel) {
        // the reader of the report went away (`flexrig … | head`): stop quietly
        if err.is_broken_pipe() {
            std::process::exit(0);
        }
        eprintln!("error: {err}");
        std::process::exit(err.exit_code());
    }
}
