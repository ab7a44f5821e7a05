//! `flexrig`: see `flexrig --help`.

fn main() {
    let cli = match flexrig_cli::cli::Cli::try_parse_args() {
        Ok(cli) => cli,
        Err(err) => {
            let args: Vec<String> = std::env::args().collect();
            let hint = flexrig_cli::cli::list_hint(&err, &args);
            let _ = err.print();
            if let Some(hint) = hint {
                eprintln!("\n{hint}");
            }
            std::process::exit(err.exit_code());
        }
    };
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
