//! FMI 2.0 and FMI 3.0 Co-Simulation export for FMUs written in Rust, both from one library.
//!
//! A model implements [`Model`] (physics plus one variable table, both from the version-neutral
//! `fmu-model` crate, which this crate re-exports in [`model`] and [`variables`]);
//! `export_fmu!(MyModel)` in the FMU crate expands every function of `fmi2Functions.h` and of
//! `fmi3Functions.h` as `#[no_mangle] extern "C"` symbols (they must be expanded in the cdylib
//! itself: a `#[no_mangle]` function in an rlib dependency is not reliably exported).
//!
//! The two versions side by side:
//! - Shared, once: the instance core ([`instance`]), the state machine ([`state`]), argument
//!   checks, logging to either version's callback ([`logging`]), the panic barrier and the work
//!   of every entry point ([`calls`]), FMU-state snapshots, and what both model descriptions
//!   share ([`description`]: units, the GUID or instantiation token, causality and variability).
//! - Per version, mirrored: [`fmi2`] and [`fmi3`], each with its C entry points (`api`, and the
//!   half of `export_fmu!` that expands them) and its spelling of `modelDescription.xml` (`xml`).
//!   FMI 3.0 keeps the FMI 2.0 variables and state machine and refuses what these FMUs do not
//!   have (Model Exchange, Scheduled Execution, Event Mode, clocks, derivatives).
//!
//! Reliability: every entry point checks its pointers (an instance or FMU state is used only
//! while the registry in `live` lists it) and the state machine and runs under `catch_unwind`;
//! a panic's message and location, formatted by this crate's panic hook, are reported to the
//! FMI logger of the instance whose call panicked (never printed to the host's stderr), and the
//! call returns `fmi2Fatal` (`fmi3Fatal`). A step is refused if it is longer than the model's
//! [`ModelInfo::max_step_size`] (a bound on the work of one call), does not advance time or
//! overflows it, or starts at a communication point more than 1 µs off ([`time_tolerance`]).
//! No Real (Float64) leaves the FMU non-finite with an OK status. Serialized states carry a
//! header naming their format and build (`image`); deserialized states are validated before use
//! ([`Model::validate_state`] adds the model's own invariants). Each instance frees the FMU
//! states the host left. The library's only heap memory reachable from a static is the
//! registry's list while objects are live, released with the last one, so nothing is lost when
//! a host unloads it.
//!
//! The C types come from the `fmi2-sys` and `fmi3-sys` crates (re-exported as [`ffi`] and
//! [`ffi3`]), which the importer (`fmu-import`) shares; every exported function is checked at
//! compile time against its `fmi2…TYPE` or `fmi3…TYPE` there. Inside, statuses are the Rust enum
//! [`Status`], converted to the C status (a `c_int`) at the boundary.

pub mod calls;
pub mod description;
mod finite;
pub mod fmi2;
pub mod fmi3;
#[cfg(feature = "harness")]
pub mod harness;
mod image;
pub mod instance;
mod live;
pub mod logging;
mod lookup;
pub mod model;
mod panics;
pub mod state;
pub mod status;
pub mod variables;

#[cfg(test)]
mod tests;

/// The C types of the FMI 2.0 API (the `fmi2-sys` crate): every function `export_fmu!` defines
/// takes and returns exactly these, and is checked against its `fmi2…TYPE` at compile time.
pub use fmi2_sys as ffi;
/// The C types of the FMI 3.0 API (the `fmi3-sys` crate), likewise for the `fmi3*` functions.
pub use fmi3_sys as ffi3;
pub use fmu_model::time_tolerance;
pub use model::{Environment, Model, ModelInfo};
pub use status::Status;
pub use variables::{Causality, Value, Variability, Variable};

/// Exports the complete FMI 2.0 and FMI 3.0 C APIs for `$model` from one library (their symbols
/// are disjoint: `fmi2*` and `fmi3*`; an importer of either version finds its own), plus
/// `fmi2rs_model_description(buffer, size)` and `fmi3rs_model_description(buffer, size)`, which
/// write each version's `modelDescription.xml` rendered from the same table (used by the
/// packager). The same binary goes into the FMI 2.0 and the FMI 3.0 archive.
#[macro_export]
macro_rules! export_fmu {
    ($model:ty) => {
        $crate::__export_fmi2!($model);
        $crate::__export_fmi3!($model);
    };
}

/// One `#[no_mangle] extern "C"` entry point that passes its arguments unchanged to
/// `$crate::$version::api::$api::<M>`: the plain forwards of both halves of [`export_fmu!`],
/// one line each (after its doc comment, if any), with the C signature spelled as in the
/// version's header (checked against its `…TYPE` there). It expands inside a half's module,
/// where `M` is the model.
#[doc(hidden)]
#[macro_export]
macro_rules! __forward {
    ($(#[$attr:meta])* $name:ident($($arg:ident: $ty:ty),*) $(-> $ret:ty)? => $version:ident::$api:ident) => {
        $(#[$attr])*
        #[no_mangle]
        pub unsafe extern "C" fn $name($($arg: $ty),*) $(-> $ret)? {
            // SAFETY: the host's arguments, passed on unchanged (contracts 1 to 4 of `calls`).
            unsafe { $crate::$version::api::$api::<M>($($arg),*) }
        }
    };
}

/// Compile-time check used by both halves of [`export_fmu!`], given the list of a version's
/// header (`fmi2_functions!`, `fmi3_functions!`): each `name` coerces to the function pointer
/// type `nameTYPE`, i.e. it exists and has exactly the C signature of the header.
#[doc(hidden)]
#[macro_export]
macro_rules! __assert_signatures {
    ($($name:ident : $ty:ident),* $(,)?) => {
        const _: () = { $(let _: $ty = $name;)* };
    };
}

/// An entry point without arguments that returns a static C string, `$text`
/// (`fmi2GetTypesPlatform`, `fmi2GetVersion`, `fmi3GetVersion`).
#[doc(hidden)]
#[macro_export]
macro_rules! __static_string {
    ($name:ident => $text:literal) => {
        #[no_mangle]
        pub extern "C" fn $name() -> *const std::ffi::c_char {
            $text.as_ptr()
        }
    };
}
