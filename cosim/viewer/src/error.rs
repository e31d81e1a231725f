//! Why a view cannot be made or a live session cannot run.

use std::path::PathBuf;

use cosim_engine::execution::RunError;

/// Why a view cannot be made or a live session cannot run.
#[derive(Debug, thiserror::Error)]
pub enum ViewerError {
    /// A results file lacks variables the view draws.
    #[error(
        "{} has no column {}: record {} (the scenario's \"record\" variables), or give the scenario \
         file itself to `crane-cosim view`, which records what the view needs",
        file.display(), missing.join(", "), if missing.len() == 1 { "it" } else { "them" }
    )]
    MissingColumns { file: PathBuf, missing: Vec<String> },
    /// A system lacks an instance or variable the view draws.
    #[error("{} has no variable {name}; the view needs the closed loop's platform, crane, pendulum and controller", file.display())]
    UnknownVariable { file: PathBuf, name: String },
    /// A variable the view draws is a string in this system.
    #[error("{}: a variable the view draws is a string, not a number", file.display())]
    NotANumber { file: PathBuf },
    #[error("the simulation failed")]
    Run(#[from] RunError),
    #[error("{what}")]
    Io {
        what: String,
        #[source]
        source: std::io::Error,
    },
}
