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
//! Output folder: `sweep-folder.json` (the mark of a folder a sweep wrote), `cases/<id>.json`
//! (one per case), `manifest.json` (every case's status), `results.csv`, `results.parquet` and
//! `plots/` (after collecting). A folder holding any of these names but no mark is refused by
//! `run` and `collect` untouched: the files are not the sweep's to replace.

pub mod collect;
pub mod execute;
pub mod normal;
pub mod parquet;
pub mod plan;
pub mod plots;
pub mod study;
pub mod table;

use std::path::Path;

use crate::files::{read_text, write_atomically};
use crate::StudyError;

/// The file that marks an output folder as a sweep's, written before anything else of it.
pub const FOLDER_MARK: &str = "sweep-folder.json";

/// The mark's text: a user's file of the same name without it does not pass for one.
const MARK_TEXT: &str = "{\n  \"written_by\": \"crane-cosim sweep run\"\n}\n";

/// What a sweep writes in its output folder besides the mark.
const WRITTEN: [&str; 5] = [execute::MANIFEST_FILE, "cases", "results.csv", "results.parquet", "plots"];

/// Whether `out` holds the sweep's mark.
fn is_marked(out: &Path) -> Result<bool, StudyError> {
    match read_text(&out.join(FOLDER_MARK)) {
        Ok(text) => Ok(text == MARK_TEXT),
        Err(StudyError::Read { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => Ok(false),
        Err(error) => Err(error),
    }
}

/// The names of [`WRITTEN`] that exist in `out`.
fn present(out: &Path) -> Vec<&'static str> {
    WRITTEN.into_iter().filter(|name| std::fs::symlink_metadata(out.join(name)).is_ok()).collect()
}

/// Marks `out` (created if needed) as a sweep's output folder.
pub fn mark_folder(out: &Path) -> Result<(), StudyError> {
    std::fs::create_dir_all(out).map_err(|source| StudyError::Write { file: out.to_path_buf(), source })?;
    write_atomically(&out.join(FOLDER_MARK), MARK_TEXT)
}

/// Before `sweep run` writes into `out`: a marked folder is the sweep's own (resumed), one
/// without the sweep's files is marked, and one holding a sweep's file names but no mark (a
/// user's `manifest.json` or `cases/`) is refused untouched. Jobs starting side by side on one
/// folder all find it unmarked and empty, or marked: each writes the mark before any other file.
pub(crate) fn claim_folder(out: &Path) -> Result<(), StudyError> {
    if is_marked(out)? {
        return Ok(());
    }
    let found = present(out);
    if !found.is_empty() {
        return Err(StudyError::Invalid {
            file: out.to_path_buf(),
            message: format!(
                "holds {} but no {FOLDER_MARK}: not files a sweep wrote, nothing was written; choose an empty or new folder",
                found.join(", ")
            ),
        });
    }
    mark_folder(out)
}

/// Before `sweep collect` writes into `out`: only a folder `sweep run` marked.
pub(crate) fn check_marked(out: &Path) -> Result<(), StudyError> {
    if is_marked(out)? {
        return Ok(());
    }
    Err(StudyError::Invalid {
        file: out.to_path_buf(),
        message: format!(
            "holds no {FOLDER_MARK}: not an output folder of `sweep run`, nothing was written; collect a folder the sweep ran in"
        ),
    })
}

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn run_and_collect_refuse_a_folder_of_files_they_did_not_write() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        std::fs::create_dir_all(out.join("cases")).unwrap();
        std::fs::write(out.join("manifest.json"), "mine").unwrap();
        std::fs::write(out.join("cases/0000.json"), "mine too").unwrap();
        let error = claim_folder(&out).unwrap_err().to_string();
        assert!(error.ends_with("out: holds manifest.json, cases but no sweep-folder.json: not files a sweep wrote, nothing was written; choose an empty or new folder"), "{error}");
        let error = check_marked(&out).unwrap_err().to_string();
        assert!(error.contains("out: holds no sweep-folder.json"), "{error}");
        assert_eq!(std::fs::read_to_string(out.join("manifest.json")).unwrap(), "mine");
        // A user's file named as the mark is not one.
        std::fs::write(out.join(FOLDER_MARK), "{}").unwrap();
        claim_folder(&out).unwrap_err();
        // A new folder is marked, then resumed and collected.
        let new = dir.path().join("new");
        claim_folder(&new).unwrap();
        std::fs::create_dir(new.join("cases")).unwrap();
        claim_folder(&new).unwrap();
        check_marked(&new).unwrap();
    }
}
