//! The FMI 3.0 entry points of a built FMU library ([`Functions`], one field per function of
//! `fmi3Functions.h`, from `fmi3-sys`'s list) and the `logMessage` callback the fuzzer and the
//! leak cycles give their FMI 3.0 instances ([`Log`]). The importer (`fmu-import`) is FMI 2.0
//! only; this is all an FMI 3.0 host needs to call these libraries.

use fmi3_sys::*;
use std::ffi::{c_void, CStr};
use std::path::Path;
use std::sync::{Mutex, PoisonError};

macro_rules! declare_functions {
    ($($name:ident : $ty:ident),* $(,)?) => {
        /// Every function of `fmi3Functions.h`, resolved from one library (this project's FMUs
        /// export them all). Valid while the library they came from is loaded.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy)]
        pub struct Functions {
            $(pub $name: $ty,)*
        }

        impl Functions {
            /// Resolves every `fmi3*` symbol of `library`.
            ///
            /// # Safety
            /// `library` is an FMI 3.0 library: each symbol has the type `fmi3FunctionTypes.h`
            /// gives it.
            #[allow(non_snake_case)]
            unsafe fn resolve(library: &libloading::Library, path: &Path) -> Result<Functions, String> {
                $(
                    // SAFETY: the caller's contract: the symbol has this type.
                    let $name: $ty = unsafe { library.get::<$ty>(concat!(stringify!($name), "\0").as_bytes()) }
                        .map(|symbol| *symbol)
                        .map_err(|e| format!("{}: {}: {e}", path.display(), stringify!($name)))?;
                )*
                Ok(Functions { $($name,)* })
            }
        }
    };
}

fmi3_sys::fmi3_functions!(declare_functions);

/// A library opened for its FMI 3.0 entry points (the same mapping as the importer's handle of
/// it: opening a loaded library again only counts a reference).
pub struct Library3 {
    functions: Functions,
    // Declared last: closed after the pointers above are gone.
    _library: libloading::Library,
}

impl Library3 {
    /// Opens the library at `path` and resolves its `fmi3*` functions.
    ///
    /// # Safety
    /// The file is one of this project's FMU libraries (its initialisers run, and its `fmi3*`
    /// symbols have the header's types).
    pub unsafe fn load(path: &Path) -> Result<Library3, String> {
        // SAFETY: the caller vouches for the file.
        let library = unsafe { libloading::Library::new(path) }.map_err(|e| format!("{}: {e}", path.display()))?;
        // SAFETY: as above: an FMI 3.0 library.
        let functions = unsafe { Functions::resolve(&library, path) }?;
        Ok(Library3 { functions, _library: library })
    }

    pub fn functions(&self) -> &Functions {
        &self.functions
    }
}

/// What an FMI 3.0 instance's `logMessage` received: (status, message), oldest first. Boxed by
/// its owner and passed as `instanceEnvironment`, so it must outlive the instance.
#[derive(Default)]
pub struct Log(Mutex<Vec<(fmi3Status, String)>>);

impl Log {
    pub fn new() -> Box<Log> {
        Box::default()
    }

    /// The `instanceEnvironment` that makes [`log_message`] write here.
    pub fn environment(&self) -> fmi3InstanceEnvironment {
        self as *const Log as *mut c_void
    }

    pub fn messages(&self) -> Vec<(fmi3Status, String)> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner).clone()
    }

    pub fn last_message(&self) -> Option<String> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner).last().map(|(_, m)| m.clone())
    }

    /// The first message logged with `fmi3Fatal`.
    pub fn fatal(&self) -> Option<String> {
        let messages = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        messages.iter().find(|(status, _)| *status == fmi3Fatal).map(|(_, m)| m.clone())
    }
}

/// The `logMessage` callback: appends to the [`Log`] that `instanceEnvironment` points to.
///
/// # Safety
/// `environment` is NULL or a live [`Log`] (from [`Log::environment`]); `message` is NULL or
/// NUL-terminated.
pub unsafe extern "C" fn log_message(
    environment: fmi3InstanceEnvironment,
    status: fmi3Status,
    _category: fmi3String,
    message: fmi3String,
) {
    // SAFETY: the function's contract: NULL or a live Log.
    let Some(log) = (unsafe { (environment as *const Log).as_ref() }) else { return };
    let text = if message.is_null() {
        "(NULL message)".to_string()
    } else {
        // SAFETY: the function's contract: NUL-terminated.
        unsafe { CStr::from_ptr(message) }.to_string_lossy().into_owned()
    };
    log.0.lock().unwrap_or_else(PoisonError::into_inner).push((status, text));
}
