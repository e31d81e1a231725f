//! Parameter studies (sweeps) over any scenario: a [`study::Study`] file names a base scenario,
//! the values to sample (each setting one start value, several linked ones, or scaling several
//! defaults) and the metrics to collect, optionally against a baseline run of every case;
//! [`plan::plan`] expands it into numbered deterministic cases; [`execute::run_cases`] runs a
//! selection of them (one index, a shard or all, on a thread pool), each case writing its own
//! result file so that reruns skip finished cases and separate jobs (array jobs of a batch
//! system) can share one output folder;
//! [`collect::collect`] merges the case files into one [`table::Table`], written as CSV and
//! Parquet, with summary plots.
//!
//! Output folder: `cases/<id>.json` (one per case), `manifest.json` (every case's status),
//! `results.csv`, `results.parquet` and `plots/` (after collecting).

pub mod collect;
pub mod execute;
pub mod normal;
pub mod parquet;
pub mod plan;
pub mod plots;
pub mod study;
pub mod table;

use std::path::PathBuf;

use cosim_engine::system::ParseError;
use fmu_import::file::{read_regular_text, MAX_TEXT_FILE_BYTES};

/// Why a study cannot be read, run or collected (a failing case does not stop a run: it is
/// recorded with status "failed").
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
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

/// The text of a study, scenario, manifest or case file: a regular file (a FIFO or a device such
/// as `/dev/zero` is refused from its metadata, before it could block or fill memory) of at most
/// [`MAX_TEXT_FILE_BYTES`], in UTF-8, as system files are read.
fn read_text(file: &std::path::Path) -> Result<String, SweepError> {
    read_regular_text(file, MAX_TEXT_FILE_BYTES).map_err(|source| SweepError::Read { file: file.to_path_buf(), source })
}

/// Refuses an output folder's `cases/` folder that is a symbolic link: the case files written
/// and collected would be another folder's, perhaps another study's.
fn check_cases_folder(folder: &std::path::Path) -> Result<(), SweepError> {
    match std::fs::symlink_metadata(folder) {
        Ok(metadata) if metadata.file_type().is_symlink() => Err(SweepError::Invalid {
            file: folder.to_path_buf(),
            message: "the cases folder is a symbolic link: give an output folder of its own".into(),
        }),
        _ => Ok(()),
    }
}

/// Writes `value` as pretty JSON and a newline to `file`, streamed through a buffer into a
/// temporary file renamed over `file` (as [`write_bytes_atomically`]), so that a manifest of
/// millions of cases is never held whole in memory.
fn write_json_atomically(file: &std::path::Path, value: &impl serde::Serialize) -> Result<(), SweepError> {
    use std::io::Write;
    let error = |source| SweepError::Write { file: file.to_path_buf(), source };
    let folder = file.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
    let temporary = tempfile::NamedTempFile::new_in(folder).map_err(error)?;
    let mut writer = std::io::BufWriter::new(temporary);
    serde_json::to_writer_pretty(&mut writer, value).map_err(|e| error(e.into()))?;
    writer.write_all(b"\n").map_err(error)?;
    let temporary = writer.into_inner().map_err(|e| error(e.into_error()))?;
    temporary.persist(file).map_err(|e| error(e.error))?;
    Ok(())
}

/// Writes `text` to `file` through [`write_bytes_atomically`].
fn write_atomically(file: &std::path::Path, text: &str) -> Result<(), SweepError> {
    write_bytes_atomically(file, text.as_bytes())
}

/// Writes `bytes` to `file` through a temporary file beside it and a rename, so that a reader
/// (another shard, a collect) never sees a half-written file. `tempfile` names the temporary
/// file at random and creates it exclusively, so jobs on different machines sharing the folder
/// (containers, where every job may have the same process id) never write the same one; one
/// that fails is deleted.
fn write_bytes_atomically(file: &std::path::Path, bytes: &[u8]) -> Result<(), SweepError> {
    persist_atomically(file, bytes).map_err(|source| SweepError::Write { file: file.to_path_buf(), source })
}

/// The I/O of [`write_bytes_atomically`], also the tuning's output files'.
pub(crate) fn persist_atomically(file: &std::path::Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let folder = file.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(std::path::Path::new("."));
    let mut temporary = tempfile::NamedTempFile::new_in(folder)?;
    temporary.write_all(bytes)?;
    temporary.persist(file).map_err(|e| e.error)?;
    Ok(())
}
