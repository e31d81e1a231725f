//! `crane-cosim`: see `crane-cosim --help`.

use std::process::ExitCode;

use clap::Parser;

fn run() -> anyhow::Result<()> {
    let cli = master::cli::Cli::parse();
    master::cli::execute(&cli)?;
    Ok(())
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
