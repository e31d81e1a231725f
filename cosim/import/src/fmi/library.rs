//! Loading an FMU's shared library, FMI 2.0 or 3.0, and resolving its functions (the tables of
//! [`super::fmi2`] and [`super::fmi3`]).

use std::path::{Path, PathBuf};

use super::fmi2::Functions;
use super::{fmi3, header};

/// Why a shared library could not be used.
#[derive(Debug, thiserror::Error)]
pub enum LibraryError {
    /// `dlopen` failed (missing file, wrong architecture, unresolved dependency, ...).
    #[error("cannot load shared library {}", path.display())]
    Load {
        path: PathBuf,
        #[source]
        source: libloading::Error,
    },
    /// One or more functions a Co-Simulation FMU must export (the common and the
    /// Co-Simulation functions of `fmi2Functions.h`) are missing.
    #[error(
        "shared library {} does not export {}: {}",
        path.display(),
        if symbols.len() == 1 { "the FMI function" } else { "the FMI functions" },
        symbols.join(", ")
    )]
    MissingSymbols { path: PathBuf, symbols: Vec<&'static str> },
    /// The file's headers are not those of a loadable library for this platform (not ELF/PE, or
    /// cut short): loading it could crash the process instead of failing.
    #[error("{} is not a usable shared library: {reason}", path.display())]
    Unusable { path: PathBuf, reason: String },
}

/// Reads the start of the library at `path` and checks its headers (`header::check_head`) for this platform, so
/// that a truncated or foreign file is refused before `dlopen` maps it.
///
/// A bare name (no directory) is left to the loader, which searches the system's library
/// directories for it; so is a file that cannot be read, for which `dlopen` gives the reason.
pub fn check_file(path: &Path) -> Result<(), LibraryError> {
    if path.parent().is_none_or(|parent| parent.as_os_str().is_empty()) {
        return Ok(());
    }
    let Some((head, size)) = read_head(path) else { return Ok(()) };
    header::check_head(&head, size, header::Format::native())
        .map_err(|reason| LibraryError::Unusable { path: path.to_path_buf(), reason })
}

/// How much of a library [`check_file`] reads: its headers and tables lie at the start. Reading
/// the whole file (megabytes) on every load would also leave the allocator's heap grown.
const HEAD: u64 = 16 * 1024;

/// The first [`HEAD`] bytes of the file at `path` and its size (`None`: it cannot be read).
fn read_head(path: &Path) -> Option<(Vec<u8>, u64)> {
    use std::io::Read;
    let file = std::fs::File::open(path).ok()?;
    let size = file.metadata().ok()?.len();
    let mut head = Vec::new();
    file.take(HEAD).read_to_end(&mut head).ok()?;
    Some((head, size))
}

/// The function `name` (NUL-terminated) of `library`, if it exports it.
///
/// # Safety
/// `T` is the function pointer type `name` is declared with.
pub(super) unsafe fn symbol<T: Copy>(library: &libloading::Library, name: &str) -> Option<T> {
    // SAFETY: this function's contract.
    unsafe { library.get::<T>(name.as_bytes()) }.map(|symbol| *symbol).ok()
}

/// A loaded FMU shared library with its `fmi2*` functions resolved.
///
/// Share it between instances with `Arc<Library>`; it is unloaded when the
/// last owner drops it, so every instance must hold an `Arc` to it.
pub struct Library {
    functions: Functions,
    /// The FMI 3.0 functions of an FMI 3.0 library (then `functions` is the adapter table of
    /// [`super::fmi3`]), `None` for FMI 2.0.
    fmi3: Option<fmi3::Functions>,
    path: PathBuf,
    // Declared last: unloaded after everything that might still point into it.
    _library: libloading::Library,
}

impl std::fmt::Debug for Library {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Library").field("path", &self.path).finish_non_exhaustive()
    }
}

impl Library {
    /// Checks the headers of the shared library at `path` ([`check_file`]), loads it (resolving all its own symbols
    /// immediately, `RTLD_NOW | RTLD_LOCAL`) and looks up the FMI 2.0 functions: the 34
    /// common and Co-Simulation ones must be exported, the 10 Model Exchange ones may be.
    ///
    /// # Safety
    ///
    /// Loading a library runs its initialisation code; the caller must trust the
    /// file to be an FMI 2.0 binary for this platform.
    pub unsafe fn load(path: &Path) -> Result<Self, LibraryError> {
        check_file(path)?;
        // SAFETY: the caller vouches for the file (this function's contract), which is all that
        // running its initialisers requires.
        let library =
            unsafe { open(path) }.map_err(|source| LibraryError::Load { path: path.to_path_buf(), source })?;
        let functions = Functions::resolve(&library, path)?;
        Ok(Self { functions, fmi3: None, path: path.to_path_buf(), _library: library })
    }

    /// As [`Library::load`] for an FMI 3.0 binary: resolves the `fmi3*` functions the importer
    /// uses, behind the FMI 2.0 adapter table of [`super::fmi3`].
    ///
    /// # Safety
    /// As for [`Library::load`]: the file must be a trusted FMI 3.0 binary for this platform.
    pub unsafe fn load_fmi3(path: &Path) -> Result<Self, LibraryError> {
        check_file(path)?;
        // SAFETY: the caller vouches for the file (this function's contract).
        let library =
            unsafe { open(path) }.map_err(|source| LibraryError::Load { path: path.to_path_buf(), source })?;
        let fmi3 = fmi3::Functions::resolve(&library, path)?;
        Ok(Self { functions: fmi3::functions(), fmi3: Some(fmi3), path: path.to_path_buf(), _library: library })
    }

    /// The FMI 3.0 functions, for an FMI 3.0 library.
    pub fn fmi3(&self) -> Option<&fmi3::Functions> {
        self.fmi3.as_ref()
    }

    /// The resolved function pointers (valid while `self` is alive).
    pub fn functions(&self) -> &Functions {
        &self.functions
    }

    /// The file this library was loaded from.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// `dlopen` of `path` (`LoadLibraryExW` on Windows).
///
/// # Safety
/// As for [`Library::load`]: the file's initialisation code runs, so it must be trusted.
#[cfg(unix)]
unsafe fn open(path: &Path) -> Result<libloading::Library, libloading::Error> {
    use libloading::os::unix::{Library, RTLD_LOCAL, RTLD_NOW};
    // SAFETY: the caller trusts the file (this function's contract); RTLD_LOCAL keeps its
    // symbols out of the global namespace, so two FMUs exporting the same fmi2* names cannot
    // bind to each other's functions.
    unsafe { Library::open(Some(path), RTLD_NOW | RTLD_LOCAL) }.map(Into::into)
}

/// `LoadLibraryExW` of `path`.
///
/// # Safety
/// As for [`Library::load`]: the file's initialisation code runs, so it must be trusted.
#[cfg(not(unix))]
unsafe fn open(path: &Path) -> Result<libloading::Library, libloading::Error> {
    // SAFETY: the caller trusts the file (this function's contract).
    unsafe { libloading::Library::new(path) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn missing_library_is_an_error_naming_the_file() {
        // SAFETY: the file does not exist, so no code is loaded or run.
        let error = unsafe { Library::load(Path::new("no/such/library.so")) }.unwrap_err();
        assert!(error.to_string().contains("no/such/library.so"), "{error}");
    }

    #[test]
    fn library_without_fmi_symbols_names_them() {
        // The C runtime is loaded in every process and exports none of the fmi2 functions.
        // SAFETY: libc is already loaded and initialised in this process; loading it again
        // only takes a reference and runs no initialiser.
        let error = unsafe { Library::load(Path::new("libc.so.6")) }.unwrap_err();
        let message = error.to_string();
        assert!(message.contains("fmi2DoStep") && message.contains("libc.so.6"), "{message}");
        // Only the common and Co-Simulation functions are required: a Co-Simulation-only FMU
        // need not export the Model Exchange ones.
        let (_, listed) = message.split_once(": ").expect("a list of functions");
        assert_eq!(listed.split(", ").count(), 34, "{message}");
        assert!(!message.contains("fmi2EnterEventMode") && !message.contains("fmi2GetDerivatives"), "{message}");
    }
}
