//! `crane-cosim`: see `crane-cosim --help`.

use std::process::ExitCode;

use clap::Parser;

mod cli;

fn run() -> anyhow::Result<()> {
    cli::execute(&cli::Cli::parse())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}
