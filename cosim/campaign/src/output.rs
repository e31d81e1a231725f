//! The campaign's output folder and the list of the files a campaign wrote into it.
//!
//! A campaign clears its folder before it runs, so that no earlier run, figure or report passes
//! for this campaign's. It may only remove what a campaign wrote: the folder's list,
//! [`LIST_FILE`], names every file the last campaign left there, and a folder holding anything
//! the list does not name — or holding files but no complete list — is refused untouched. A
//! user's `report.md` or `runs/field_trial.csv` is never deleted because its name looks like a
//! campaign's.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

/// The list of the files a campaign wrote, kept in the output folder itself.
pub const LIST_FILE: &str = "campaign-files.json";

/// At most this many foreign files are named in a refusal (the count says how many there are).
const NAMED: usize = 10;

/// Why the output folder cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("cannot use {}", path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(
        "{} holds {} that no campaign wrote ({}): nothing was removed; choose an empty or new folder, or remove them",
        folder.display(),
        files_count(foreign.len()),
        named(foreign)
    )]
    Foreign { folder: PathBuf, foreign: Vec<String> },
    #[error(
        "{} holds files but no complete {LIST_FILE} (a campaign that did not finish, or not a campaign's folder: {}): \
         nothing was removed; choose an empty or new folder, or remove it",
        folder.display(),
        named(files)
    )]
    Unlisted { folder: PathBuf, files: Vec<String> },
    #[error("{}: not a list of campaign files", path.display())]
    List {
        path: PathBuf,
        #[source]
        source: serde_json::Error,
    },
}

fn files_count(n: usize) -> String {
    if n == 1 {
        "1 file".into()
    } else {
        format!("{n} files")
    }
}

fn named(files: &[String]) -> String {
    let mut text = files.iter().take(NAMED).cloned().collect::<Vec<_>>().join(", ");
    if files.len() > NAMED {
        text.push_str(&format!(", and {} more", files.len() - NAMED));
    }
    text
}

/// The content of [`LIST_FILE`].
#[derive(Debug, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileList {
    /// False while the campaign runs: its files are not all listed yet.
    complete: bool,
    /// Every file the campaign wrote, relative to the folder, with `/` separators.
    files: Vec<String>,
}

/// Makes `out` ready for a campaign: creates it when missing, removes the files the previous
/// campaign listed, and marks the folder as being written. Refuses, removing nothing, a folder
/// that holds a file no complete list names.
pub fn prepare(out: &Path) -> Result<(), OutputError> {
    std::fs::create_dir_all(out).map_err(|source| io_error(out, source))?;
    let present: Vec<String> = files_under(out)?.into_iter().filter(|f| f != LIST_FILE).collect();
    if !present.is_empty() {
        remove_listed(out, &present)?;
    }
    write_list(out, &FileList::default())
}

/// Lists every file now in `out` as the campaign's: called when the runs are done and again
/// once everything else is written (also after a failure, so that the next campaign may clear
/// what this one left).
pub fn seal(out: &Path) -> Result<(), OutputError> {
    let files = files_under(out)?.into_iter().filter(|f| f != LIST_FILE).collect();
    write_list(out, &FileList { complete: true, files })
}

/// Removes the listed files (`present`: every file but the list) and the folders they leave
/// empty; refuses, before removing anything, when a present file is not listed.
fn remove_listed(out: &Path, present: &[String]) -> Result<(), OutputError> {
    let unlisted = || OutputError::Unlisted { folder: out.to_path_buf(), files: present.to_vec() };
    let list = read_list(out)?.filter(|list| list.complete).ok_or_else(unlisted)?;
    let foreign: Vec<String> = present.iter().filter(|f| !list.files.contains(f)).cloned().collect();
    if !foreign.is_empty() {
        return Err(OutputError::Foreign { folder: out.to_path_buf(), foreign });
    }
    for file in present {
        let path = out.join(file);
        std::fs::remove_file(&path).map_err(|source| OutputError::Io { path, source })?;
    }
    remove_empty_folders(out)
}

fn io_error(path: &Path, source: std::io::Error) -> OutputError {
    OutputError::Io { path: path.to_path_buf(), source }
}

fn read_list(out: &Path) -> Result<Option<FileList>, OutputError> {
    let path = out.join(LIST_FILE);
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(error) if error.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(source) => return Err(OutputError::Io { path, source }),
    };
    serde_json::from_str(&text).map(Some).map_err(|source| OutputError::List { path, source })
}

fn write_list(out: &Path, list: &FileList) -> Result<(), OutputError> {
    let path = out.join(LIST_FILE);
    let text = serde_json::to_string_pretty(list).map_err(|source| OutputError::List { path: path.clone(), source })?;
    std::fs::write(&path, text + "\n").map_err(|source| OutputError::Io { path, source })
}

/// Every file below `out` (symbolic links and other non-folders included, never followed),
/// relative, `/`-separated and sorted.
fn files_under(out: &Path) -> Result<Vec<String>, OutputError> {
    let mut files = Vec::new();
    collect(out, "", &mut files)?;
    files.sort();
    Ok(files)
}

fn collect(folder: &Path, prefix: &str, files: &mut Vec<String>) -> Result<(), OutputError> {
    let io = |source| OutputError::Io { path: folder.to_path_buf(), source };
    for entry in std::fs::read_dir(folder).map_err(io)? {
        let entry = entry.map_err(io)?;
        let name = format!("{prefix}{}", entry.file_name().to_string_lossy());
        if entry.file_type().map_err(io)?.is_dir() {
            collect(&entry.path(), &format!("{name}/"), files)?;
        } else {
            files.push(name);
        }
    }
    Ok(())
}

/// Removes the now-empty folders below `folder` (not `folder` itself); a folder that still holds
/// something stays.
fn remove_empty_folders(folder: &Path) -> Result<(), OutputError> {
    for entry in std::fs::read_dir(folder).map_err(|source| io_error(folder, source))? {
        let entry = entry.map_err(|source| io_error(folder, source))?;
        if entry.file_type().map_err(|source| io_error(folder, source))?.is_dir() {
            let path = entry.path();
            remove_empty_folders(&path)?;
            if std::fs::read_dir(&path).map_err(|source| io_error(&path, source))?.next().is_none() {
                std::fs::remove_dir(&path).map_err(|source| io_error(&path, source))?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(dir: &Path, file: &str) {
        let path = dir.join(file);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, "x\n").unwrap();
    }

    #[test]
    fn a_campaigns_own_files_are_cleared_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        prepare(dir.path()).unwrap();
        for file in ["report.md", "runs/001-1.csv", "figures/fig.png"] {
            write(dir.path(), file);
        }
        seal(dir.path()).unwrap();
        let list = read_list(dir.path()).unwrap().unwrap();
        assert_eq!(list.files, ["figures/fig.png", "report.md", "runs/001-1.csv"]);
        prepare(dir.path()).unwrap();
        assert_eq!(files_under(dir.path()).unwrap(), [LIST_FILE], "only the new, incomplete list is left");
        assert!(!read_list(dir.path()).unwrap().unwrap().complete);
    }

    #[test]
    fn a_file_the_list_does_not_name_keeps_every_file() {
        let dir = tempfile::tempdir().unwrap();
        prepare(dir.path()).unwrap();
        write(dir.path(), "report.md");
        seal(dir.path()).unwrap();
        write(dir.path(), "runs/field_trial_2024.csv");
        let error = prepare(dir.path()).unwrap_err().to_string();
        assert!(error.contains("holds 1 file that no campaign wrote (runs/field_trial_2024.csv)"), "{error}");
        assert_eq!(files_under(dir.path()).unwrap(), [LIST_FILE, "report.md", "runs/field_trial_2024.csv"]);
    }

    #[test]
    fn files_without_a_complete_list_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), "report.md");
        let error = prepare(dir.path()).unwrap_err().to_string();
        assert!(error.contains(&format!("holds files but no complete {LIST_FILE}")), "{error}");
        // A campaign that was killed before it listed its files.
        write_list(dir.path(), &FileList::default()).unwrap();
        assert!(matches!(prepare(dir.path()), Err(OutputError::Unlisted { .. })));
        assert!(dir.path().join("report.md").exists());
    }
}
