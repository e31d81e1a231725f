//! Safe extraction of an `.fmu` (ZIP) archive.
//!
//! Every entry name is checked before anything is written: absolute paths,
//! drive prefixes, `..` components and symbolic links are refused
//! ("zip-slip"), so nothing can be written outside the destination.

use std::fs;
use std::io;
use std::path::{Component, Path, PathBuf};

/// What went wrong while extracting an archive.
#[derive(Debug, thiserror::Error)]
pub enum ArchiveError {
    #[error("cannot open {}", archive.display())]
    Open {
        archive: PathBuf,
        #[source]
        source: io::Error,
    },
    #[error("{} is not a valid ZIP archive", archive.display())]
    Zip {
        archive: PathBuf,
        #[source]
        source: zip::result::ZipError,
    },
    #[error("{}: refusing archive entry {entry:?}: {reason}", archive.display())]
    UnsafeEntry { archive: PathBuf, entry: String, reason: UnsafeEntry },
    #[error("{}: cannot extract entry {entry:?}", archive.display())]
    Extract {
        archive: PathBuf,
        entry: String,
        #[source]
        source: io::Error,
    },
}

/// Why an entry name is refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum UnsafeEntry {
    #[error("it is an absolute path")]
    Absolute,
    #[error("it contains a '..' component")]
    ParentDirectory,
    #[error("it is a symbolic link")]
    Symlink,
    #[error("its name is empty or contains a NUL character")]
    BadName,
}

/// Checks one entry name and returns the relative path it may be written to.
///
/// Both `/` and `\` count as separators so that names written on Windows are
/// judged the same way.
pub fn safe_relative_path(name: &str) -> Result<PathBuf, UnsafeEntry> {
    if name.is_empty() || name.contains('\0') {
        return Err(UnsafeEntry::BadName);
    }
    let bytes = name.as_bytes();
    let drive_prefix = bytes.len() >= 2 && bytes[1] == b':' && bytes[0].is_ascii_alphabetic();
    if name.starts_with('/') || name.starts_with('\\') || drive_prefix {
        return Err(UnsafeEntry::Absolute);
    }
    let mut path = PathBuf::new();
    for part in name.split(['/', '\\']) {
        match part {
            "" | "." => {}
            ".." => return Err(UnsafeEntry::ParentDirectory),
            part => path.push(part),
        }
    }
    // Belt and braces: the result must be a plain relative path.
    if path.components().all(|c| matches!(c, Component::Normal(_))) {
        Ok(path)
    } else {
        Err(UnsafeEntry::BadName)
    }
}

/// Extracts `archive` into the existing directory `destination`.
///
/// All entry names are validated first; on a refused entry nothing is written.
pub fn extract(archive: &Path, destination: &Path) -> Result<(), ArchiveError> {
    let file = fs::File::open(archive).map_err(|source| ArchiveError::Open { archive: archive.into(), source })?;
    let zip_error = |source| ArchiveError::Zip { archive: archive.into(), source };
    let mut zip = zip::ZipArchive::new(io::BufReader::new(file)).map_err(zip_error)?;

    let mut plan = Vec::with_capacity(zip.len());
    for index in 0..zip.len() {
        let entry = zip.by_index_raw(index).map_err(zip_error)?;
        let name = String::from_utf8_lossy(entry.name_raw()).into_owned();
        let refuse = |reason| ArchiveError::UnsafeEntry { archive: archive.into(), entry: name.clone(), reason };
        let relative = safe_relative_path(&name).map_err(refuse)?;
        if entry.is_symlink() {
            return Err(refuse(UnsafeEntry::Symlink));
        }
        plan.push((index, name, relative, entry.is_dir()));
    }

    for (index, name, relative, is_dir) in plan {
        let failed = |source| ArchiveError::Extract { archive: archive.into(), entry: name.clone(), source };
        let target = destination.join(&relative);
        if is_dir {
            fs::create_dir_all(&target).map_err(failed)?;
            continue;
        }
        if let Some(parent) = target.parent() {
            fs::create_dir_all(parent).map_err(failed)?;
        }
        let mut entry = zip.by_index(index).map_err(zip_error)?;
        let mut output = fs::File::create(&target).map_err(failed)?;
        io::copy(&mut entry, &mut output).map_err(failed)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;
    use zip::write::SimpleFileOptions;

    /// Writes a ZIP with the given regular files and symlinks into `dir`.
    fn make_zip(dir: &Path, files: &[(&str, &str)], symlinks: &[(&str, &str)]) -> PathBuf {
        let path = dir.join("test.fmu");
        let mut writer = zip::ZipWriter::new(fs::File::create(&path).expect("create zip"));
        let options = SimpleFileOptions::default();
        for (name, content) in files {
            writer.start_file(*name, options).expect("start file");
            writer.write_all(content.as_bytes()).expect("write");
        }
        for (name, target) in symlinks {
            writer.add_symlink(*name, *target, options).expect("symlink");
        }
        writer.finish().expect("finish");
        path
    }

    fn refused(files: &[(&str, &str)], symlinks: &[(&str, &str)]) -> (String, UnsafeEntry, tempfile::TempDir) {
        let dir = tempfile::tempdir().expect("tempdir");
        let zip = make_zip(dir.path(), files, symlinks);
        let out = dir.path().join("out");
        fs::create_dir(&out).expect("mkdir");
        match extract(&zip, &out) {
            Err(error @ ArchiveError::UnsafeEntry { .. }) => {
                let message = error.to_string();
                let ArchiveError::UnsafeEntry { reason, .. } = error else { unreachable!() };
                assert_eq!(fs::read_dir(&out).expect("read out").count(), 0, "nothing may be written");
                (message, reason, dir)
            }
            other => panic!("expected a refused entry, got {other:?}"),
        }
    }

    #[test]
    fn refuses_parent_directory_entries() {
        let (message, reason, dir) = refused(&[("modelDescription.xml", "<x/>"), ("../x", "evil")], &[]);
        assert_eq!(reason, UnsafeEntry::ParentDirectory);
        assert!(message.contains("\"../x\""), "{message}");
        assert!(!dir.path().join("x").exists());
    }

    #[test]
    fn refuses_nested_parent_directory_entries() {
        let (message, reason, _dir) = refused(&[("resources/../../y", "evil")], &[]);
        assert_eq!(reason, UnsafeEntry::ParentDirectory);
        assert!(message.contains("resources/../../y"), "{message}");
    }

    #[test]
    fn refuses_absolute_entries() {
        let (message, reason, _dir) = refused(&[("/abs", "evil")], &[]);
        assert_eq!(reason, UnsafeEntry::Absolute);
        assert!(message.contains("\"/abs\""), "{message}");
    }

    #[test]
    fn refuses_symlink_entries() {
        let (message, reason, _dir) =
            refused(&[("modelDescription.xml", "<x/>")], &[("resources/link", "/etc/passwd")]);
        assert_eq!(reason, UnsafeEntry::Symlink);
        assert!(message.contains("resources/link") && message.contains("symbolic link"), "{message}");
    }

    #[test]
    fn windows_style_names_are_judged_too() {
        assert_eq!(safe_relative_path("..\\x"), Err(UnsafeEntry::ParentDirectory));
        assert_eq!(safe_relative_path("C:\\x"), Err(UnsafeEntry::Absolute));
        assert_eq!(safe_relative_path("\\x"), Err(UnsafeEntry::Absolute));
        assert_eq!(safe_relative_path(""), Err(UnsafeEntry::BadName));
        assert_eq!(safe_relative_path("./a//b/"), Ok(PathBuf::from("a/b")));
        assert_eq!(safe_relative_path("a..b/c..").map(|p| p.to_string_lossy().into_owned()), Ok("a..b/c..".into()));
    }

    #[test]
    fn extracts_regular_archives() {
        let dir = tempfile::tempdir().expect("tempdir");
        let zip = make_zip(dir.path(), &[("modelDescription.xml", "<x/>"), ("resources/a b/ü.txt", "data")], &[]);
        let out = dir.path().join("out");
        fs::create_dir(&out).expect("mkdir");
        extract(&zip, &out).expect("extract");
        assert_eq!(fs::read_to_string(out.join("resources/a b/ü.txt")).expect("read"), "data");
        assert_eq!(fs::read_to_string(out.join("modelDescription.xml")).expect("read"), "<x/>");
    }

    #[test]
    fn not_a_zip_is_a_clear_error() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("bad.fmu");
        fs::write(&path, "not a zip").expect("write");
        let message = extract(&path, dir.path()).unwrap_err().to_string();
        assert!(message.contains("bad.fmu") && message.contains("not a valid ZIP"), "{message}");
    }
}
