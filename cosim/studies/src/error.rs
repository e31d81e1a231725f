//! The one error type of studies: the files they read and write, the plans, the case
//! selections and the worker threads.

use std::path::PathBuf;

use cosim_engine::system::ParseError;

/// Why a study cannot be read, run or collected (a failing case does not stop a run: it is
/// recorded with status "failed"). The tuning wraps it with the reasons of its own.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    #[error("cannot read {}", file.display())]
    Read {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot write {}", file.display())]
    Write {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{}: {message}", file.display())]
    Invalid { file: PathBuf, message: String },
    /// A study or base scenario that is not JSON, or has a field its kind does not.
    #[error("{}:{}:{}: {error}", file.display(), error.line, error.column)]
    Parse { file: PathBuf, error: ParseError },
    #[error("case index {index} is not in the plan (cases 0 to {})", cases.saturating_sub(1))]
    NoSuchCase { index: usize, cases: usize },
    #[error("shard {index}/{count}: expected 0 ≤ i < N")]
    BadShard { index: usize, count: usize },
    #[error("{} holds a case of another study (other seed or parameter values): choose a new output folder", file.display())]
    OtherStudy { file: PathBuf },
    #[error("study {} plans {cases} cases, more than the {max} allowed (raise the case limit max_cases)", file.display())]
    TooManyCases { file: PathBuf, cases: String, max: usize },
    #[error("parameter '{parameter}': sample {sample} is {value} ({distribution}): choose a distribution whose samples are finite")]
    InfiniteSample { parameter: String, sample: usize, value: f64, distribution: String },
    #[error("cannot start the worker threads")]
    Threads(#[source] rayon::ThreadPoolBuildError),
}
