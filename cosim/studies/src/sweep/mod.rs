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

use crate::StudyError;

/// Refuses an output folder's `cases/` folder that is a symbolic link: the case files written
/// and collected would be another folder's, perhaps another study's.
fn check_cases_folder(folder: &std::path::Path) -> Result<(), StudyError> {
    match std::fs::symlink_metadata(folder) {
        Ok(metadata) if metadata.file_type().is_symlink() => Err(StudyError::Invalid {
            file: folder.to_path_buf(),
            message: "the cases folder is a symbolic link: give an output folder of its own".into(),
        }),
        _ => Ok(()),
    }
}
