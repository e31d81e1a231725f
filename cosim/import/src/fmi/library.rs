//! Loading an FMU's shared library and resolving every `fmi2*` function.

use std::path::{Path, PathBuf};

use super::ffi;

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
    /// One or more functions of `fmi2Functions.h` are not exported.
    #[error(
        "shared library {} does not export {}: {}",
        path.display(),
        if symbols.len() == 1 { "the FMI 2.0 function" } else { "the FMI 2.0 functions" },
        symbols.join(", ")
    )]
    MissingSymbols { path: PathBuf, symbols: Vec<&'static str> },
}

macro_rules! declare_functions {
    ($($name:ident : $ty:ident),* $(,)?) => {
        /// Every function declared in `fmi2Functions.h`, resolved from one library.
        ///
        /// The pointers stay valid as long as the [`Library`] they came from is alive;
        /// obtain them through [`Library::functions`].
        #[allow(non_snake_case)]
        #[derive(Clone, Copy)]
        pub struct Functions {
            $(pub $name: ffi::$ty,)*
        }

        /// Names of all functions of `fmi2Functions.h`, in header order.
        pub const SYMBOLS: &[&str] = &[$(stringify!($name)),*];

        impl Functions {
            /// Resolves every symbol; reports all missing ones at once.
            #[allow(non_snake_case)]
            fn resolve(library: &libloading::Library, path: &Path) -> Result<Self, LibraryError> {
                let mut missing = Vec::new();
                $(
                    // SAFETY: the symbol is declared with this exact type in fmi2Functions.h.
                    let $name: Option<ffi::$ty> = unsafe {
                        library
                            .get::<ffi::$ty>(concat!(stringify!($name), "\0").as_bytes())
                            .map(|symbol| *symbol)
                            .ok()
                    };
                    if $name.is_none() {
                        missing.push(stringify!($name));
                    }
                )*
                match ($($name,)*) {
                    ($(Some($name),)*) => Ok(Self { $($name,)* }),
                    _ => Err(LibraryError::MissingSymbols { path: path.to_path_buf(), symbols: missing }),
                }
            }
        }
    };
}

// One field and one symbol per function of fmi2Functions.h, from the list in fmi2-sys.
ffi::fmi2_functions!(declare_functions);

/// A loaded FMU shared library with all of its `fmi2*` functions resolved.
///
/// Share it between instances with `Arc<Library>`; it is unloaded when the
/// last owner drops it, so every instance must hold an `Arc` to it.
pub struct Library {
    functions: Functions,
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
    /// Loads the shared library at `path` (resolving all its own symbols
    /// immediately, `RTLD_NOW | RTLD_LOCAL`) and looks up all 44 FMI 2.0 functions.
    ///
    /// # Safety
    ///
    /// Loading a library runs its initialisation code; the caller must trust the
    /// file to be an FMI 2.0 binary for this platform.
    pub unsafe fn load(path: &Path) -> Result<Self, LibraryError> {
        let library = open(path).map_err(|source| LibraryError::Load { path: path.to_path_buf(), source })?;
        let functions = Functions::resolve(&library, path)?;
        Ok(Self { functions, path: path.to_path_buf(), _library: library })
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

#[cfg(unix)]
unsafe fn open(path: &Path) -> Result<libloading::Library, libloading::Error> {
    use libloading::os::unix::{Library, RTLD_LOCAL, RTLD_NOW};
    Library::open(Some(path), RTLD_NOW | RTLD_LOCAL).map(Into::into)
}

#[cfg(not(unix))]
unsafe fn open(path: &Path) -> Result<libloading::Library, libloading::Error> {
    libloading::Library::new(path)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn all_functions_of_the_header_are_listed() {
        assert_eq!(SYMBOLS.len(), 44);
        let mut sorted = SYMBOLS.to_vec();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), SYMBOLS.len());
    }

    #[test]
    fn missing_library_is_an_error_naming_the_file() {
        let error = unsafe { Library::load(Path::new("no/such/library.so")) }.unwrap_err();
        assert!(error.to_string().contains("no/such/library.so"), "{error}");
    }

    #[test]
    fn library_without_fmi_symbols_names_them() {
        // The C runtime is loaded in every process and exports none of the fmi2 functions.
        let error = unsafe { Library::load(Path::new("libc.so.6")) }.unwrap_err();
        let message = error.to_string();
        assert!(message.contains("fmi2DoStep") && message.contains("libc.so.6"), "{message}");
    }
}
