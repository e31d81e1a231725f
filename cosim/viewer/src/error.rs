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
    /// A system lacks instances or variables the view draws: which, the instances it has, and
    /// how the view's names go (there is no mapping: the instances must be named so).
    #[error(
        "{} lacks what the view draws: {}\n  the view reads {}\n  there is no option to map other \
         names: name the instances platform, crane (knuckle_boom for the full-scale crane), pendulum \
         and controller, as systems/closed_loop.json and systems/full_scale.json do, with FMUs \
         that have these variables",
        file.display(),
        lacking(missing_instances, missing_variables, instances),
        needed.join(", ")
    )]
    MissingVariables {
        file: PathBuf,
        /// The instances the view needs that the system lacks.
        missing_instances: Vec<String>,
        /// `"instance.variable"` of present instances whose FMU lacks the variable.
        missing_variables: Vec<String>,
        /// The system's instances.
        instances: Vec<String>,
        /// Every `"instance.variable"` the view reads.
        needed: Vec<String>,
    },
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

/// "no instance a, b (its instances: c, d); no variable c.x".
fn lacking(missing_instances: &[String], missing_variables: &[String], instances: &[String]) -> String {
    let mut parts = Vec::new();
    if !missing_instances.is_empty() {
        parts.push(format!("no instance {} (its instances: {})", missing_instances.join(", "), instances.join(", ")));
    }
    if !missing_variables.is_empty() {
        parts.push(format!("no variable {}", missing_variables.join(", ")));
    }
    parts.join("; ")
}
