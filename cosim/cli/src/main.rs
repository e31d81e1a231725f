//! `crane-cosim`: see `crane-cosim --help`.

use std::process::ExitCode;

use clap::Parser;

mod cli;
mod commands;
mod flags;
mod process;

fn run() -> anyhow::Result<()> {
    // Parsed first: clap itself exits for --help and usage errors.
    let cli = cli::Cli::parse();
    let _guard = process::ExitGuard::arm();
    cli::execute(&cli)
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) if process::is_broken_pipe(&error) => process::end_by_broken_pipe(),
        Err(error) if process::interrupting_signal().is_some() => {
            eprintln!("{}", flags::name_flags(&format!("{error:#}")));
            // The shell convention for a command ended by a signal.
            ExitCode::from(128 + process::interrupting_signal().map_or(0, |s| s as u8))
        }
        Err(error) => {
            eprintln!("error: {}", flags::name_flags(&format!("{error:#}")));
            ExitCode::FAILURE
        }
    }
}
