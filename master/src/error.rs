//! The crate-level error and error-chain formatting.

use std::path::PathBuf;

use crate::execution::RunError;
use crate::fmu::FmuError;
use crate::observer::ObserverError;
use crate::system::SystemError;

/// Anything that can stop a command.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    System(#[from] SystemError),
    #[error(transparent)]
    Run(#[from] RunError),
    #[error(transparent)]
    Fmu(#[from] FmuError),
    #[error(transparent)]
    Output(#[from] ObserverError),
    #[error("cannot write the run summary {}", file.display())]
    Summary {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// Metrics or plots could not be made from results files.
    #[error("{0}")]
    Report(String),
}

/// An error and all its causes on one line: `error: cause: cause`.
pub fn error_chain(error: &(dyn std::error::Error + 'static)) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text
}
