//! Safe extraction of an `.fmu` (ZIP) archive.
//!
//! Every entry name is checked before anything is written: absolute paths,
//! drive prefixes, `..` components and symbolic links are refused
//! ("zip-slip"), so nothing can be written outside the destination. The archive must also keep
//! within [`ExtractLimits`] (entry count, unpacked size, compression ratio), judged from the
//! declared sizes before anything is written and enforced on the bytes actually inflated, so a
//! "zip bomb" is refused instead of filling the disk.

use std::fs;
use std::io::{self, Read};
use std::path::{Component, Path, PathBuf};

use crate::file::{human_bytes, open_regular};

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
    #[error("{}: refusing to extract: {limit}", archive.display())]
    Limit { archive: PathBuf, limit: LimitExceeded },
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

/// How much one archive may unpack to. Every extraction is given its limits as a value (a program
/// that opens FMUs decides them once and passes them down); an exceeded limit's message names the
/// field to raise, e.g. `ExtractLimits::max_entries`, so a front end can say how it is raised.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ExtractLimits {
    /// Sum of the entries' uncompressed sizes (bytes); default 2 GiB.
    pub max_unpacked_bytes: u64,
    /// Number of entries; default 10,000.
    pub max_entries: u64,
    /// Uncompressed over compressed size of any entry of more than 1 MiB; default 200. Deflate
    /// reaches about 1,000 on runs of zeros, ordinary text and binaries stay far below 50.
    pub max_ratio: u64,
}

/// Entries up to this size are exempt from the ratio limit: small files of zeros are harmless.
const RATIO_EXEMPT_BYTES: u64 = 1 << 20;

impl Default for ExtractLimits {
    fn default() -> Self {
        Self { max_unpacked_bytes: 2 << 30, max_entries: 10_000, max_ratio: 200 }
    }
}

/// Which [`ExtractLimits`] an archive exceeds; the message names the field that raises it.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum LimitExceeded {
    #[error("{count} entries, more than the limit of {max} (raise ExtractLimits::max_entries)")]
    Entries { count: u64, max: u64 },
    #[error(
        "the entries unpack to {}, more than the limit of {} (raise ExtractLimits::max_unpacked_bytes)",
        human_bytes(*bytes),
        human_bytes(*max)
    )]
    Unpacked { bytes: u64, max: u64 },
    #[error(
        "entry {entry:?} is compressed {ratio}:1, more than the limit of {max}:1 \
         (raise ExtractLimits::max_ratio)"
    )]
    Ratio { entry: String, ratio: u64, max: u64 },
    #[error("entry {entry:?} unpacks to more than the {} its header declares", human_bytes(*declared))]
    LongerThanDeclared { entry: String, declared: u64 },
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

/// Like [`extract_within`], leaving out the binaries of other platforms than `platforms` (folder names)
/// (`binaries/<other>/…`): an FMU with Windows and Linux libraries is opened on Linux without
/// unpacking the DLLs. Every entry's name is still judged.
pub fn extract_for_platform(
    archive: &Path,
    destination: &Path,
    platforms: &[&str],
    limits: &ExtractLimits,
) -> Result<(), ArchiveError> {
    let other_platform = |relative: &Path| {
        let mut parts = relative.components();
        parts.next().is_some_and(|first| first.as_os_str() == "binaries")
            && parts.next().is_some_and(|folder| platforms.iter().all(|p| folder.as_os_str() != *p))
    };
    extract_filtered(archive, destination, limits, &other_platform)
}

/// The names of the archive's entries, as stored.
pub fn entry_names(archive: &Path) -> Result<Vec<String>, ArchiveError> {
    let file = open_regular(archive).map_err(|source| ArchiveError::Open { archive: archive.into(), source })?;
    let zip = zip::ZipArchive::new(io::BufReader::new(file))
        .map_err(|source| ArchiveError::Zip { archive: archive.into(), source })?;
    Ok(zip.file_names().map(str::to_string).collect())
}

/// One entry to write, after its name and sizes were judged.
struct PlannedEntry {
    index: usize,
    name: String,
    relative: PathBuf,
    is_dir: bool,
    declared_size: u64,
}

/// Extracts `archive` into the existing directory `destination`.
///
/// All entry names and declared sizes are judged first; on a refused entry or an exceeded limit
/// nothing is written. An entry that inflates to more than it declares stops the extraction.
pub fn extract_within(archive: &Path, destination: &Path, limits: &ExtractLimits) -> Result<(), ArchiveError> {
    extract_filtered(archive, destination, limits, &|_| false)
}

/// [`extract_within`] without the entries whose relative path `skip` accepts (they count as
/// entries but neither are written nor count towards the unpacked size).
fn extract_filtered(
    archive: &Path,
    destination: &Path,
    limits: &ExtractLimits,
    skip: &dyn Fn(&Path) -> bool,
) -> Result<(), ArchiveError> {
    let file = open_regular(archive).map_err(|source| ArchiveError::Open { archive: archive.into(), source })?;
    let zip_error = |source| ArchiveError::Zip { archive: archive.into(), source };
    let mut zip = zip::ZipArchive::new(io::BufReader::new(file)).map_err(zip_error)?;
    let plan = plan_extraction(&mut zip, archive, limits, skip)?;

    for planned in plan {
        let failed = |source| ArchiveError::Extract { archive: archive.into(), entry: planned.name.clone(), source };
        let target = destination.join(&planned.relative);
        if planned.is_dir {
            fs::create_dir_all(&target).map_err(failed)?;
            continue;
        }
        if let Some(parent) = target.parent() {
            fs::create_dir_all(parent).map_err(failed)?;
        }
        let entry = zip.by_index(planned.index).map_err(zip_error)?;
        let mut output = fs::File::create(&target).map_err(failed)?;
        // One byte more than declared is enough to tell a lying header.
        let written = io::copy(&mut entry.take(planned.declared_size + 1), &mut output).map_err(failed)?;
        if written > planned.declared_size {
            let limit = LimitExceeded::LongerThanDeclared { entry: planned.name, declared: planned.declared_size };
            return Err(ArchiveError::Limit { archive: archive.into(), limit });
        }
    }
    Ok(())
}

/// Judges every entry's name, kind and declared sizes against `limits` without writing anything.
fn plan_extraction<R: io::Read + io::Seek>(
    zip: &mut zip::ZipArchive<R>,
    archive: &Path,
    limits: &ExtractLimits,
    skip: &dyn Fn(&Path) -> bool,
) -> Result<Vec<PlannedEntry>, ArchiveError> {
    let exceeded = |limit| ArchiveError::Limit { archive: archive.into(), limit };
    let count = zip.len() as u64;
    if count > limits.max_entries {
        return Err(exceeded(LimitExceeded::Entries { count, max: limits.max_entries }));
    }
    let mut plan = Vec::with_capacity(zip.len());
    let mut unpacked = 0u64;
    for index in 0..zip.len() {
        let entry = zip.by_index_raw(index).map_err(|source| ArchiveError::Zip { archive: archive.into(), source })?;
        let name = String::from_utf8_lossy(entry.name_raw()).into_owned();
        let refuse = |reason| ArchiveError::UnsafeEntry { archive: archive.into(), entry: name.clone(), reason };
        let relative = safe_relative_path(&name).map_err(refuse)?;
        if entry.is_symlink() {
            return Err(refuse(UnsafeEntry::Symlink));
        }
        if skip(&relative) {
            continue;
        }
        let declared_size = entry.size();
        let ratio = declared_size / entry.compressed_size().max(1);
        if declared_size > RATIO_EXEMPT_BYTES && ratio > limits.max_ratio {
            return Err(exceeded(LimitExceeded::Ratio { entry: name, ratio, max: limits.max_ratio }));
        }
        unpacked = unpacked.saturating_add(declared_size);
        plan.push(PlannedEntry { index, name, relative, is_dir: entry.is_dir(), declared_size });
    }
    if unpacked > limits.max_unpacked_bytes {
        return Err(exceeded(LimitExceeded::Unpacked { bytes: unpacked, max: limits.max_unpacked_bytes }));
    }
    Ok(plan)
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
        match extract_within(&zip, &out, &ExtractLimits::default()) {
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
        extract_within(&zip, &out, &ExtractLimits::default()).expect("extract");
        assert_eq!(fs::read_to_string(out.join("resources/a b/ü.txt")).expect("read"), "data");
        assert_eq!(fs::read_to_string(out.join("modelDescription.xml")).expect("read"), "<x/>");
    }

    /// A ZIP of one deflated entry `name` of `size` zero bytes, and the folder it lies in.
    fn zeros_zip(name: &str, size: usize) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("zeros.fmu");
        let mut writer = zip::ZipWriter::new(fs::File::create(&path).expect("create zip"));
        let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
        writer.start_file(name, options).expect("start file");
        writer.write_all(&vec![0u8; size]).expect("write");
        writer.finish().expect("finish");
        (dir, path)
    }

    fn limit_error(archive: &Path, limits: &ExtractLimits) -> (LimitExceeded, String, usize) {
        let out = tempfile::tempdir_in(archive.parent().expect("folder")).expect("output folder");
        let out = out.path();
        match extract_within(archive, out, limits) {
            Err(error @ ArchiveError::Limit { .. }) => {
                let message = error.to_string();
                let ArchiveError::Limit { limit, .. } = error else { unreachable!() };
                (limit, message, fs::read_dir(out).expect("read out").count())
            }
            other => panic!("expected an exceeded limit, got {other:?}"),
        }
    }

    #[test]
    fn a_highly_compressed_entry_is_refused_before_writing() {
        let (_dir, zip) = zeros_zip("resources/zeros.bin", 8 << 20);
        let (limit, message, written) = limit_error(&zip, &ExtractLimits::default());
        let LimitExceeded::Ratio { ratio, max: 200, .. } = limit else { panic!("{limit:?}") };
        assert!(ratio > 500, "deflate packs zeros about 1000:1, got {ratio}");
        assert!(
            message.contains("resources/zeros.bin") && message.contains("(raise ExtractLimits::max_ratio)"),
            "{message}"
        );
        assert_eq!(written, 0, "nothing may be written");
        // Raising the limit lets it through.
        let limits = ExtractLimits { max_ratio: 2_000, ..ExtractLimits::default() };
        let out = zip.with_extension("ok");
        fs::create_dir(&out).expect("mkdir");
        extract_within(&zip, &out, &limits).expect("within raised limits");
        assert_eq!(fs::metadata(out.join("resources/zeros.bin")).expect("written").len(), 8 << 20);
    }

    #[test]
    fn total_size_and_entry_count_are_limited() {
        let dir = tempfile::tempdir().expect("tempdir");
        let zip = make_zip(dir.path(), &[("a", "0123456789"), ("b", "0123456789"), ("c", "0123456789")], &[]);
        let small = ExtractLimits { max_unpacked_bytes: 25, ..ExtractLimits::default() };
        let (limit, message, written) = limit_error(&zip, &small);
        assert_eq!(limit, LimitExceeded::Unpacked { bytes: 30, max: 25 });
        assert!(
            message.ends_with(
                "the entries unpack to 30 bytes, more than the limit of 25 bytes (raise ExtractLimits::max_unpacked_bytes)"
            ),
            "{message}"
        );
        assert_eq!(written, 0);
        let few = ExtractLimits { max_entries: 2, ..ExtractLimits::default() };
        let (limit, message, _) = limit_error(&zip, &few);
        assert_eq!(limit, LimitExceeded::Entries { count: 3, max: 2 });
        assert!(
            message.ends_with("3 entries, more than the limit of 2 (raise ExtractLimits::max_entries)"),
            "{message}"
        );
    }

    #[test]
    fn an_entry_longer_than_its_header_says_is_stopped() {
        let (_dir, zip) = zeros_zip("big.bin", 4096);
        // Declare 100 bytes in the local and the central header (uncompressed size fields).
        let mut bytes = fs::read(&zip).expect("read");
        for (signature, offset) in [(b"PK\x03\x04", 22), (b"PK\x01\x02", 24)] {
            let at = bytes.windows(4).position(|w| w == signature).expect("header") + offset;
            bytes[at..at + 4].copy_from_slice(&100u32.to_le_bytes());
        }
        fs::write(&zip, bytes).expect("write");
        let (limit, message, _) = limit_error(&zip, &ExtractLimits::default());
        assert_eq!(limit, LimitExceeded::LongerThanDeclared { entry: "big.bin".into(), declared: 100 });
        assert!(message.contains("unpacks to more than the 100 bytes its header declares"), "{message}");
    }

    #[test]
    fn binaries_of_other_platforms_are_left_out() {
        let dir = tempfile::tempdir().expect("tempdir");
        let files = [
            ("modelDescription.xml", "<x/>"),
            ("binaries/linux64/m.so", "elf"),
            ("binaries/win64/m.dll", "pe"),
            ("binaries/win64/../../evil", "x"),
            ("resources/binaries/win64/data.txt", "kept"),
        ];
        let out = dir.path().join("out");
        fs::create_dir(&out).expect("mkdir");
        let zip_all = make_zip(dir.path(), &[files[0], files[1], files[2], files[4]], &[]);
        extract_for_platform(&zip_all, &out, &["linux64"], &ExtractLimits::default()).expect("extract");
        assert!(out.join("binaries/linux64/m.so").is_file());
        assert!(!out.join("binaries/win64").exists(), "the DLL is not unpacked on Linux");
        assert!(out.join("resources/binaries/win64/data.txt").is_file(), "only the top-level binaries folder");
        // A skipped entry's name is judged all the same.
        let evil = make_zip(dir.path(), &[files[0], files[3]], &[]);
        let error = extract_for_platform(&evil, &out, &["linux64"], &ExtractLimits::default()).expect_err("refused");
        assert!(matches!(error, ArchiveError::UnsafeEntry { reason: UnsafeEntry::ParentDirectory, .. }), "{error}");
    }

    #[test]
    fn not_a_zip_is_a_clear_error() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = dir.path().join("bad.fmu");
        fs::write(&path, "not a zip").expect("write");
        let message = extract_within(&path, dir.path(), &ExtractLimits::default()).unwrap_err().to_string();
        assert!(message.contains("bad.fmu") && message.contains("not a valid ZIP"), "{message}");
    }
}
