//! Results files that replace their target only once they hold a row.
//!
//! A recorder writes into `<name>.<random>.partial` beside the target and renames it into place
//! when the run ends: a run that computed rows (completed or not) replaces the target with them
//! in one rename, and a run that computed none removes its partial file and leaves an existing
//! target as it was. Nothing else may be lost on the way:
//! the partial file is created new (never over an existing file), and a process killed outright
//! (SIGKILL) leaves its rows in it for the user to rename. Whole files (a run's summary, a
//! study's manifest) are written the same way by [`persist_atomically`].

use std::fs::File;
use std::io;
use std::path::{Path, PathBuf};

/// A partial file and the target it is renamed to.
#[derive(Debug)]
pub(crate) struct PartialFile {
    target: PathBuf,
    partial: PathBuf,
    /// True once renamed or removed.
    settled: bool,
}

impl PartialFile {
    /// Creates the partial file of `target` (and the target's parent folders) and opens it for
    /// writing. `tempfile` names it at random and creates it exclusively, so two runs into one
    /// folder (or jobs on machines sharing it) never write the same one.
    pub(crate) fn create(target: &Path) -> io::Result<(File, PartialFile)> {
        let folder = parent_folder(target);
        std::fs::create_dir_all(folder)?;
        let name = target.file_name().ok_or_else(|| io::Error::other("the results path names no file"))?;
        let mut prefix = name.to_os_string();
        prefix.push(".");
        let (file, partial) =
            builder().prefix(&prefix).suffix(".partial").tempfile_in(folder)?.keep().map_err(|error| error.error)?;
        Ok((file, PartialFile { target: target.to_path_buf(), partial, settled: false }))
    }

    /// Renames the partial file to the target if the run recorded `rows > 0`, else removes it;
    /// later calls do nothing.
    pub(crate) fn settle(&mut self, rows: u64) -> io::Result<()> {
        if std::mem::replace(&mut self.settled, true) {
            return Ok(());
        }
        if rows > 0 {
            std::fs::rename(&self.partial, &self.target)
        } else {
            std::fs::remove_file(&self.partial)
        }
    }
}

impl Drop for PartialFile {
    /// Removes a partial file never settled: its recorder failed before its first row.
    fn drop(&mut self) {
        let _ = self.settle(0);
    }
}

/// Temporary files that become the user's files: readable as `File::create` would make them
/// (0o666 less the umask), not the owner-only 0o600 of scratch files.
fn builder() -> tempfile::Builder<'static, 'static> {
    let mut builder = tempfile::Builder::new();
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder
}

/// The folder a file is in (`.` for a bare name).
fn parent_folder(file: &Path) -> &Path {
    file.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

/// Writes `bytes` to `file` through a temporary file beside it and a rename, so that a reader
/// never sees a half-written file: the old one or the whole new one. The temporary file is
/// named at random and created exclusively; one that fails is deleted.
pub fn persist_atomically(file: &Path, bytes: &[u8]) -> io::Result<()> {
    use std::io::Write;
    let mut temporary = builder().tempfile_in(parent_folder(file))?;
    temporary.write_all(bytes)?;
    temporary.persist(file).map_err(|e| e.error)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    #[test]
    fn a_partial_file_replaces_its_target_only_when_it_holds_rows() {
        let dir = tempfile::tempdir().expect("tempdir");
        let target = dir.path().join("k.csv");
        std::fs::write(&target, "earlier results\n").expect("write");

        let (mut file, mut partial) = PartialFile::create(&target).expect("create");
        file.write_all(b"time\n").expect("header");
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "earlier results\n", "untouched while running");
        partial.settle(0).expect("settle");
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "earlier results\n", "no row: untouched");
        assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 1, "the partial file is removed");

        let (mut file, mut partial) = PartialFile::create(&target).expect("create");
        file.write_all(b"time\n0.0\n").expect("row");
        partial.settle(1).expect("settle");
        partial.settle(1).expect("a second settle does nothing");
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "time\n0.0\n");
        assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 1);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&target).expect("metadata").permissions().mode();
            assert_eq!(mode & 0o600, 0o600);
            let umask_allows_others = File::create(dir.path().join("plain")).and_then(|f| f.metadata()).expect("plain");
            assert_eq!(mode & 0o777, umask_allows_others.permissions().mode() & 0o777, "as File::create makes files");
        }
    }

    #[test]
    fn two_partial_files_of_one_target_do_not_collide() {
        let dir = tempfile::tempdir().expect("tempdir");
        let target = dir.path().join("sub/k.parquet");
        let (_, first) = PartialFile::create(&target).expect("first");
        let (_, second) = PartialFile::create(&target).expect("second");
        assert_ne!(first.partial, second.partial);
        assert!(first.partial.file_name().is_some_and(|n| n.to_string_lossy().ends_with(".partial")));
    }

    #[test]
    fn a_whole_write_replaces_the_file_in_one_rename() {
        let dir = tempfile::tempdir().expect("tempdir");
        let target = dir.path().join("s.json");
        std::fs::write(&target, "old").expect("write");
        persist_atomically(&target, b"new").expect("persist");
        assert_eq!(std::fs::read_to_string(&target).expect("read"), "new");
        assert_eq!(std::fs::read_dir(dir.path()).expect("dir").count(), 1);
    }
}
