//! Opening `.fmu` files: safe extraction into a private temporary directory,
//! `modelDescription.xml`, the platform binary and its [`Library`].

mod archive;
mod description;
mod uri;

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

pub use archive::{
    entry_names, extract_for_platform, extract_within, safe_relative_path, ArchiveError, ExtractLimits, LimitExceeded,
    UnsafeEntry,
};
pub use description::{
    Causality, CoSimulation, DefaultExperiment, Fmi3Element, Fmi3Start, Fmi3Type, Initial, ModelDescription,
    ModelDescriptionError, ScalarVariable, Variability,
};
pub use uri::file_uri;

use crate::file::{read_regular_text, MAX_TEXT_FILE_BYTES};
use crate::fmi::{check_file, Library, LibraryError};

/// Why an FMU cannot be used. Every variant names the `.fmu` file.
#[derive(Debug, thiserror::Error)]
pub enum FmuError {
    #[error("cannot create a temporary directory for {}", fmu.display())]
    TempDir {
        fmu: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Archive(#[from] ArchiveError),
    #[error("{}: cannot read modelDescription.xml", fmu.display())]
    ReadModelDescription {
        fmu: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{}: modelDescription.xml", fmu.display())]
    ModelDescription {
        fmu: PathBuf,
        #[source]
        source: ModelDescriptionError,
    },
    #[error("{}: the archive has no {expected} (binaries found: {})", fmu.display(), if found.is_empty() { "none".to_string() } else { found.join(", ") })]
    MissingBinary { fmu: PathBuf, expected: String, found: Vec<String> },
    /// The platform binary's headers are not those of a loadable library (see
    /// [`crate::fmi::check_file`]); `entry` is its name inside the archive.
    #[error("{}: {entry} is not a usable shared library: {reason}", fmu.display())]
    UnusableBinary { fmu: PathBuf, entry: String, reason: String },
    #[error("{}", fmu.display())]
    Library {
        fmu: PathBuf,
        #[source]
        source: LibraryError,
    },
}

/// The FMI 3.0 platform tuple of this build (`<arch>-<os>`, FMI 3.0 §2.5.1.4), the folder of
/// `binaries/` an FMI 3.0 archive keeps its library for this platform in.
pub fn platform_tuple() -> &'static str {
    match (std::env::consts::ARCH, std::env::consts::OS) {
        ("x86_64", "linux") => "x86_64-linux",
        ("aarch64", "linux") => "aarch64-linux",
        ("x86_64", "windows") => "x86_64-windows",
        ("x86", "windows") => "x86-windows",
        ("x86_64", "macos") => "x86_64-darwin",
        ("aarch64", "macos") => "aarch64-darwin",
        _ => "unknown-platform",
    }
}

/// The folders of `binaries/` an FMI 2.0 archive may keep this platform's library in, in the order
/// they are tried. FMI 2.0 names no folder for aarch64 Linux: this project's archives use the
/// FMI 3.0 tuple `aarch64-linux` (a vendor name, as FMI 2.0 §2.3 allows), FMPy and the Reference
/// FMUs `linux64`; both are tried there.
pub fn fmi2_folders() -> &'static [&'static str] {
    match (std::env::consts::ARCH, std::env::consts::OS) {
        ("aarch64", "linux") => &["aarch64-linux", "linux64"],
        _ => std::slice::from_ref(&PLATFORM.0),
    }
}

/// FMI 2.0's folder name and the shared-library suffix of this build.
const PLATFORM: (&str, &str) = if cfg!(target_os = "windows") {
    (if cfg!(target_pointer_width = "64") { "win64" } else { "win32" }, "dll")
} else if cfg!(target_os = "macos") {
    ("darwin64", "dylib")
} else if cfg!(target_pointer_width = "64") {
    ("linux64", "so")
} else {
    ("linux32", "so")
};

/// Platform directory and shared-library suffix inside `binaries/` (FMI 2.0's names).
pub fn platform() -> (&'static str, &'static str) {
    PLATFORM
}

struct Inner {
    source: PathBuf,
    model_description: Arc<ModelDescription>,
    binary: PathBuf,
    resources: PathBuf,
    library: Mutex<Option<Arc<Library>>>,
    // Dropped last: the extracted files outlive the library handle above.
    directory: NotedTempDir,
}

/// An opened FMU: extracted, described and checked. Cheap to clone.
///
/// The extraction directory is deleted when the last clone (and every
/// [`crate::slave::Slave`] created from it) is dropped.
#[derive(Clone)]
pub struct Fmu {
    inner: Arc<Inner>,
}

impl std::fmt::Debug for Fmu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Fmu")
            .field("source", &self.inner.source)
            .field("model_name", &self.inner.model_description.model_name)
            .finish_non_exhaustive()
    }
}

impl Fmu {
    /// Extracts `path` into a private temporary directory, parses and checks
    /// `modelDescription.xml` (FMI 2.0 or 3.0, Co-Simulation) and checks that
    /// `binaries/<platform>/<modelIdentifier>.<so|dll|dylib>` exists (`<platform>`: FMI 2.0's
    /// folder name, or FMI 3.0's platform tuple).
    /// The archive must keep within `limits`. The shared library is not loaded yet (see
    /// [`Fmu::library`]).
    pub fn open(path: &Path, limits: &ExtractLimits) -> Result<Self, FmuError> {
        let fmu = path.to_path_buf();
        let directory = tempfile::Builder::new()
            .prefix("fmu-")
            .tempdir()
            .map_err(|source| FmuError::TempDir { fmu: fmu.clone(), source })?;
        let directory = NotedTempDir::new(directory);
        // Both versions' folders for this platform: which one applies is known once the
        // description is read.
        let mut folders = fmi2_folders().to_vec();
        folders.push(platform_tuple());
        extract_for_platform(path, directory.path(), &folders, limits)?;

        let xml = read_regular_text(&directory.path().join("modelDescription.xml"), MAX_TEXT_FILE_BYTES)
            .map_err(|source| FmuError::ReadModelDescription { fmu: fmu.clone(), source })?;
        let model_description =
            ModelDescription::parse(&xml).map_err(|source| FmuError::ModelDescription { fmu: fmu.clone(), source })?;

        let suffix = platform().1;
        let candidates: &[&str] = if model_description.is_fmi3() { &[platform_tuple()] } else { fmi2_folders() };
        let identifier = &model_description.co_simulation.model_identifier;
        let relative_in = |folder: &str| format!("binaries/{folder}/{identifier}.{suffix}");
        let folder = candidates
            .iter()
            .find(|folder| directory.path().join(relative_in(folder)).is_file())
            .unwrap_or(&candidates[0]);
        let relative = relative_in(folder);
        let binary = directory.path().join(&relative);
        if !binary.is_file() {
            return Err(FmuError::MissingBinary { fmu, expected: relative, found: list_binaries(path) });
        }
        let resources = directory.path().join("resources");
        let resources = std::fs::canonicalize(&resources).unwrap_or(resources);

        Ok(Self {
            inner: Arc::new(Inner {
                source: fmu,
                model_description: Arc::new(model_description),
                binary,
                resources,
                library: Mutex::new(None),
                directory,
            }),
        })
    }

    /// The `.fmu` file this was opened from.
    pub fn source(&self) -> &Path {
        &self.inner.source
    }

    /// The parsed model description.
    pub fn model_description(&self) -> &Arc<ModelDescription> {
        &self.inner.model_description
    }

    /// The directory the archive was extracted to.
    pub fn directory(&self) -> &Path {
        self.inner.directory.path()
    }

    /// The extracted platform binary.
    pub fn binary(&self) -> &Path {
        &self.inner.binary
    }

    /// The extracted `resources/` directory (which may not exist if the FMU has none): FMI 3.0's
    /// `resourcePath`.
    pub fn resource_dir(&self) -> &Path {
        &self.inner.resources
    }

    /// `fmuResourceLocation`: percent-encoded `file:` URI of the extracted
    /// `resources/` directory (which may not exist if the FMU has none).
    pub fn resource_uri(&self) -> String {
        file_uri(&self.inner.resources)
    }

    /// The binary's name inside the archive (`binaries/<platform>/<model>.<suffix>`).
    fn binary_entry(&self) -> String {
        let relative = self.inner.binary.strip_prefix(self.inner.directory.path()).unwrap_or(&self.inner.binary);
        relative.components().map(|part| part.as_os_str().to_string_lossy()).collect::<Vec<_>>().join("/")
    }

    /// Loads the shared library on first use and returns it (shared by all
    /// instances of this FMU).
    pub fn library(&self) -> Result<Arc<Library>, FmuError> {
        let mut slot = self.inner.library.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some(library) = slot.as_ref() {
            return Ok(Arc::clone(library));
        }
        check_binary(&self.inner.source, &self.inner.binary, self.binary_entry())?;
        // SAFETY: the binary is the one declared by the FMU, its headers checked above; loading
        // it is what the user asked for.
        let library = if self.inner.model_description.is_fmi3() {
            // SAFETY: as above.
            unsafe { Library::load_fmi3(&self.inner.binary) }
        } else {
            // SAFETY: as above.
            unsafe { Library::load(&self.inner.binary) }
        };
        let library = library.map_err(|source| FmuError::Library { fmu: self.inner.source.clone(), source })?;
        let library = Arc::new(library);
        *slot = Some(Arc::clone(&library));
        Ok(library)
    }
}

/// Refuses a platform binary whose headers say it cannot be loaded (named by its archive entry),
/// before `dlopen` maps it: a truncated library would crash the process with `SIGBUS`.
fn check_binary(fmu: &Path, binary: &Path, entry: String) -> Result<(), FmuError> {
    match check_file(binary) {
        Ok(()) => Ok(()),
        Err(LibraryError::Unusable { reason, .. }) => {
            Err(FmuError::UnusableBinary { fmu: fmu.to_path_buf(), entry, reason })
        }
        Err(source) => Err(FmuError::Library { fmu: fmu.to_path_buf(), source }),
    }
}

/// The files under `binaries/` in the archive (whatever was extracted), sorted.
fn list_binaries(archive: &Path) -> Vec<String> {
    let mut found: Vec<String> = entry_names(archive)
        .unwrap_or_default()
        .into_iter()
        .filter(|name| name.starts_with("binaries/") && !name.ends_with('/'))
        .collect();
    found.sort();
    found
}

/// Writes test archives.
#[cfg(test)]
pub(crate) mod test_archive {
    use std::io::Write;
    use std::path::{Path, PathBuf};

    /// `dir/m.fmu` holding `files` (name, content), stored.
    pub fn fmu_with(dir: &Path, files: &[(&str, &str)]) -> PathBuf {
        let path = dir.join("m.fmu");
        let mut writer = zip::ZipWriter::new(std::fs::File::create(&path).expect("create"));
        for (name, content) in files {
            writer.start_file(*name, zip::write::SimpleFileOptions::default()).expect("start");
            writer.write_all(content.as_bytes()).expect("write");
        }
        writer.finish().expect("finish");
        path
    }
}

#[cfg(test)]
mod tests {
    use super::test_archive::fmu_with;
    use super::*;

    const XML: &str = r#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g">
<CoSimulation modelIdentifier="model"/><ModelVariables/></fmiModelDescription>"#;

    #[test]
    fn opens_a_well_formed_archive() {
        let dir = tempfile::tempdir().expect("tempdir");
        let binary = format!("binaries/{}/model.{}", platform().0, platform().1);
        let path = fmu_with(dir.path(), &[("modelDescription.xml", XML), (&binary, "not really a library")]);
        let fmu = Fmu::open(&path, &ExtractLimits::default()).expect("opens");
        assert_eq!(fmu.model_description().guid, "g");
        assert!(fmu.binary().ends_with(&binary));
        assert!(fmu.resource_uri().starts_with("file:///") && fmu.resource_uri().ends_with("/resources"));
        let extracted = fmu.directory().to_path_buf();
        assert!(extracted.join("modelDescription.xml").is_file());
        let message = crate::chain::error_chain(&fmu.library().expect_err("not a real library"));
        assert!(message.contains("m.fmu") && message.contains("model.so"), "{message}");
        drop(fmu);
        assert!(!extracted.exists(), "the extraction directory is removed on drop");
    }

    #[test]
    fn missing_binary_is_named() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = fmu_with(dir.path(), &[("modelDescription.xml", XML), ("binaries/win64/model.dll", "")]);
        let message = Fmu::open(&path, &ExtractLimits::default()).expect_err("no linux binary").to_string();
        assert!(message.contains("m.fmu"), "{message}");
        assert!(message.contains("binaries/linux64/model.so"), "{message}");
        assert!(message.contains("binaries/win64/model.dll"), "{message}");
    }

    #[test]
    fn missing_and_bad_model_description_are_named() {
        let dir = tempfile::tempdir().expect("tempdir");
        let path = fmu_with(dir.path(), &[("other.txt", "")]);
        let message = Fmu::open(&path, &ExtractLimits::default()).expect_err("no description").to_string();
        assert!(message.contains("m.fmu") && message.contains("modelDescription.xml"), "{message}");

        let path = fmu_with(dir.path(), &[("modelDescription.xml", "<fmiModelDescription fmiVersion=\"2.0\"")]);
        let message = crate::chain::error_chain(&Fmu::open(&path, &ExtractLimits::default()).expect_err("bad xml"));
        assert!(message.contains("m.fmu: modelDescription.xml: line 1"), "{message}");
    }

    #[test]
    fn missing_file_is_named() {
        let message =
            Fmu::open(Path::new("does/not/exist.fmu"), &ExtractLimits::default()).expect_err("missing").to_string();
        assert!(message.contains("does/not/exist.fmu"), "{message}");
    }
}

/// A temporary folder noted for an emergency end ([`crate::watch`]) from its creation, also
/// while it is being extracted into, until it is removed: forgotten on drop, just before its
/// `TempDir` removes it.
struct NotedTempDir(tempfile::TempDir);

impl NotedTempDir {
    fn new(directory: tempfile::TempDir) -> Self {
        crate::watch::register_temp_dir(directory.path().to_path_buf());
        Self(directory)
    }

    fn path(&self) -> &Path {
        self.0.path()
    }
}

impl Drop for NotedTempDir {
    fn drop(&mut self) {
        crate::watch::forget_temp_dir(self.0.path());
    }
}
