//! The FMI 2.0 function table: every function of `fmi2Functions.h` resolved from one library
//! ([`Functions`], [`SYMBOLS`]). The importer calls every FMU, FMI 2.0 or 3.0, through this table
//! (an FMI 3.0 FMU through the adapter of [`crate::fmi::fmi3`]).

use std::path::Path;

use crate::fmi::ffi;
use crate::fmi::library::{symbol, LibraryError};

/// Expands to its first group for the Model Exchange functions and to its second for all
/// others.
///
/// FMI 2.0 requires an FMU to export the common functions and those of the kinds it declares.
/// This importer only uses Co-Simulation, so a Co-Simulation-only FMU need not export the Model
/// Exchange functions: their fields are `Option`s, resolved when present (an FMU declaring both
/// kinds) and never called by the importer.
macro_rules! by_kind {
    (fmi2EnterEventMode, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2NewDiscreteStates, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2EnterContinuousTimeMode, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2CompletedIntegratorStep, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2SetTime, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2SetContinuousStates, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2GetDerivatives, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2GetEventIndicators, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2GetContinuousStates, ($($me:tt)*), $other:tt) => { $($me)* };
    (fmi2GetNominalsOfContinuousStates, ($($me:tt)*), $other:tt) => { $($me)* };
    ($name:ident, $me:tt, ($($other:tt)*)) => { $($other)* };
}

macro_rules! declare_functions {
    ($($name:ident : $ty:ident),* $(,)?) => {
        /// Every function declared in `fmi2Functions.h`, resolved from one library: the common
        /// and Co-Simulation functions as plain pointers (they must be exported), the Model
        /// Exchange functions as `Option`s (see `by_kind!`).
        ///
        /// The pointers stay valid as long as the [`Library`](crate::fmi::Library) they came from is
        /// alive; obtain them through [`Library::functions`](crate::fmi::Library::functions). An FMI 3.0 library has this table too: the
        /// adapter of [`crate::fmi::fmi3`] fills it.
        #[allow(non_snake_case)]
        #[derive(Clone, Copy)]
        pub struct Functions {
            $(pub $name: by_kind!($name, (Option<ffi::$ty>), (ffi::$ty)),)*
        }

        /// Names of all functions of `fmi2Functions.h`, in header order.
        pub const SYMBOLS: &[&str] = &[$(stringify!($name)),*];

        impl Functions {
            /// Resolves every symbol; reports all missing required ones at once.
            #[allow(non_snake_case)]
            pub(in crate::fmi) fn resolve(library: &libloading::Library, path: &Path) -> Result<Self, LibraryError> {
                $(
                    // SAFETY: the symbol is declared with this exact type in fmi2Functions.h.
                    let $name: Option<ffi::$ty> = unsafe { symbol(library, concat!(stringify!($name), "\0")) };
                )*
                // Called for the first missing required function; lists all of them.
                let missing = || {
                    let mut symbols = Vec::new();
                    $(by_kind!($name, (), (if $name.is_none() { symbols.push(stringify!($name)); }));)*
                    LibraryError::MissingSymbols { path: path.to_path_buf(), symbols }
                };
                Ok(Self { $($name: by_kind!($name, ($name), ($name.ok_or_else(missing)?)),)* })
            }
        }
    };
}

// One field and one symbol per function of fmi2Functions.h, from the list in fmi2-sys.
ffi::fmi2_functions!(declare_functions);

#[cfg(test)]
mod tests {
    use super::SYMBOLS;

    #[test]
    fn all_functions_of_the_header_are_listed() {
        assert_eq!(SYMBOLS.len(), 44);
        let mut sorted = SYMBOLS.to_vec();
        sorted.sort_unstable();
        sorted.dedup();
        assert_eq!(sorted.len(), SYMBOLS.len());
    }
}
