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
        $crate::__export_module!(__fmi2_export for $model: ffi::fmi2_functions, fmi2rs_model_description($crate::fmi2::xml::Fmi2) {
            $crate::__fmi2_entries!();
        });
        $crate::__export_module!(__fmi3_export for $model: ffi3::fmi3_functions, fmi3rs_model_description($crate::fmi3::xml::Fmi3) {
            $crate::__fmi3_entries!();
        });
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

/// The module one half of [`export_fmu!`] expands into, `$module`: the model as `M` and the
/// C types of the version (`$ffi`) in scope; `TOKEN`, the GUID (FMI 2.0) or instantiation token
/// (FMI 3.0) rendered once, inline in the static so that nothing on the heap outlives an unload
/// of the library; `$description`, the entry point that writes the version's
/// `modelDescription.xml` (in `$dialect`); the half's own `$entries`; and the check of every
/// function of the version's header (listed by `$functions!`) against its `…TYPE`.
#[doc(hidden)]
#[macro_export]
macro_rules! __export_module {
    (
        $module:ident for $model:ty: $ffi:ident::$functions:ident, $description:ident($dialect:path) {
            $($entries:tt)*
        }
    ) => {
        mod $module {
            #![allow(non_snake_case, clippy::missing_safety_doc, clippy::too_many_arguments)]
            use super::*;
            use $crate::$ffi::*;
            type M = $model;

            static TOKEN: std::sync::OnceLock<$crate::description::Guid> = std::sync::OnceLock::new();

            /// Writes this version's `modelDescription.xml` of this FMU (or an XML comment saying
            /// why it cannot be rendered) into `buffer` (NULL or `size` writable bytes) as a
            /// NUL-terminated string, truncated to `size` bytes, and returns the size the whole
            /// text needs (NUL included): call it with a null buffer for the size, then with a
            /// buffer that large.
            #[no_mangle]
            pub unsafe extern "C" fn $description(buffer: *mut std::ffi::c_char, size: usize) -> usize {
                // SAFETY: the caller's buffer, passed on.
                unsafe { $crate::calls::model_description::<$dialect, M>(buffer, size) }
            }

            $($entries)*

            // Every function of the header is defined above, with its type.
            $crate::$ffi::$functions!($crate::__assert_signatures);
        }
    };
}

/// The six FMU-state entry points of one version (get, set, free, serialized size, serialize,
/// deserialize, named as in its header), forwarded to the version's `api`: their C signatures
/// differ only in the version's types (`$instance`, `$state`, `$byte`, `$status`).
#[doc(hidden)]
#[macro_export]
macro_rules! __fmu_state_entries {
    (
        $version:ident($instance:ty, $state:ty, $byte:ty, $status:ty):
        $get:ident, $set:ident, $free:ident, $size:ident, $serialize:ident, $deserialize:ident
    ) => {
        $crate::__forward!($get(instance: $instance, state: *mut $state) -> $status => $version::get_fmu_state);
        $crate::__forward!($set(instance: $instance, state: $state) -> $status => $version::set_fmu_state);
        $crate::__forward!($free(instance: $instance, state: *mut $state) -> $status => $version::free_fmu_state);
        $crate::__forward!(
            $size(instance: $instance, state: $state, size: *mut usize) -> $status => $version::serialized_fmu_state_size
        );
        $crate::__forward!(
            $serialize(instance: $instance, state: $state, bytes: *mut $byte, size: usize) -> $status
                => $version::serialize_fmu_state
        );
        $crate::__forward!(
            $deserialize(instance: $instance, bytes: *const $byte, size: usize, state: *mut $state) -> $status
                => $version::deserialize_fmu_state
        );
    };
}
