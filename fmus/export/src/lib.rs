//! FMI 2.0 Co-Simulation export plumbing for FMUs written in Rust.
//!
//! A model implements [`Model`] (physics plus one variable table, both from the version-neutral
//! `fmu-model` crate, which this crate re-exports in [`model`] and [`variables`] and maps to FMI
//! 2.0: causality, variability and `initial` spelled in [`xml`], statuses and C types here);
//! `export_fmu!(MyModel)` in the FMU crate expands every function of `fmi2Functions.h` as
//! `#[no_mangle] extern "C"` symbols (they must be expanded in the cdylib itself: a
//! `#[no_mangle]` function in an rlib dependency is not reliably exported). The instance state
//! machine, argument checks, logging, panic barrier, FMU-state snapshots, `modelDescription.xml`
//! and the GUID all live here, once.
//!
//! Reliability: every entry point checks its pointers (a component or FMU state is used only
//! while the registry in `live` lists it) and the state machine and runs under `catch_unwind`;
//! a panic's message and location, formatted by this crate's panic hook, are reported to the
//! FMI logger of the instance whose call panicked (never printed to the host's stderr), and the
//! call returns `fmi2Fatal`. `fmi2DoStep` refuses a step longer than the model's
//! [`ModelInfo::max_step_size`] (a bound on the work of one call), a step that does not advance
//! time or overflows it, and a communication point more than 1 µs off ([`time_tolerance`]). No
//! Real leaves the FMU non-finite with `fmi2OK`. Serialized states carry a header naming their
//! format and build (`image`); deserialized states are validated before use
//! ([`Model::validate_state`] adds the model's own invariants). Each instance frees the FMU
//! states the host left. The library's only heap memory reachable from a static is the
//! registry's list while objects are live, released with the last one, so nothing is lost when
//! a host unloads it.
//!
//! The C types come from the `fmi2-sys` crate (re-exported as [`ffi`]), which the importer
//! (`fmu-import`) shares; every exported function is checked at compile time against its
//! `fmi2…TYPE` there. Inside, statuses are the Rust enum [`Status`], converted to the C
//! `fmi2Status` (a `c_int`) at the boundary.

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
        mod __fmi2_export {
            #![allow(non_snake_case, clippy::missing_safety_doc)]
            use super::*;
            use std::ffi::c_char;
            use $crate::ffi::*;
            type M = $model;

            // Only the GUID is cached, inline (see `xml::Guid`): nothing on the heap outlives an
            // unload of the library.
            static GUID: std::sync::OnceLock<$crate::description::Guid> = std::sync::OnceLock::new();

            /// Writes `modelDescription.xml` of this FMU (or an XML comment saying why it cannot
            /// be rendered) into `buffer` as a NUL-terminated string, truncated to `size` bytes,
            /// and returns the size the whole text needs (NUL included): call it with a null
            /// buffer for the size, then with a buffer that large.
            #[no_mangle]
            pub unsafe extern "C" fn fmi2rs_model_description(buffer: *mut c_char, size: usize) -> usize {
                // SAFETY: the caller's buffer, passed on: NULL or `size` writable bytes (see above).
                unsafe { $crate::fmi2::api::model_description::<M>(buffer, size) }
            }

            #[no_mangle]
            pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
                $crate::fmi2::api::types_platform()
            }
            #[no_mangle]
            pub extern "C" fn fmi2GetVersion() -> *const c_char {
                $crate::fmi2::api::version()
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetDebugLogging(
                c: fmi2Component,
                on: fmi2Boolean,
                n: usize,
                cat: *const fmi2String,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::set_debug_logging::<M>(c, on, n, cat) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2Instantiate(
                name: fmi2String,
                kind: fmi2Type,
                guid: fmi2String,
                resources: fmi2String,
                functions: *const fmi2CallbackFunctions,
                visible: fmi2Boolean,
                logging_on: fmi2Boolean,
            ) -> fmi2Component {
                match $crate::fmi2::xml::cached_guid::<M>(&GUID) {
                    Ok(ours) => {
                        // SAFETY: the host's strings and callbacks, passed on unchanged (contract 3 of `api`).
                        unsafe {
                            $crate::fmi2::api::instantiate::<M>(
                                ours, name, kind, guid, resources, functions, visible, logging_on,
                            )
                        }
                    }
                    Err(_) => std::ptr::null_mut(),
                }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2FreeInstance(c: fmi2Component) {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::free_instance::<M>(c) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetupExperiment(
                c: fmi2Component,
                tol_defined: fmi2Boolean,
                tol: fmi2Real,
                start: fmi2Real,
                stop_defined: fmi2Boolean,
                stop: fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::setup_experiment::<M>(c, tol_defined, tol, start, stop_defined, stop) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::enter_initialization_mode::<M>(c) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::exit_initialization_mode::<M>(c) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2Terminate(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::terminate::<M>(c) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2Reset(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::reset::<M>(c) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetReal(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *mut fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::get_real::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetInteger(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *mut fmi2Integer,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::get_integer::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetBoolean(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *mut fmi2Boolean,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::get_boolean::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetString(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *mut fmi2String,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::get_string::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetReal(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *const fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::set_real::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetInteger(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *const fmi2Integer,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::set_integer::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetBoolean(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *const fmi2Boolean,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::set_boolean::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetString(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                v: *const fmi2String,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::set_string::<M>(c, vr, n, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetFMUstate(c: fmi2Component, s: *mut fmi2FMUstate) -> fmi2Status {
                // SAFETY: the host's component, state and buffers, passed on unchanged (contracts 1 to 4 of `api`).
                unsafe { $crate::fmi2::api::get_fmu_state::<M>(c, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetFMUstate(c: fmi2Component, s: fmi2FMUstate) -> fmi2Status {
                // SAFETY: the host's component, state and buffers, passed on unchanged (contracts 1 to 4 of `api`).
                unsafe { $crate::fmi2::api::set_fmu_state::<M>(c, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2FreeFMUstate(c: fmi2Component, s: *mut fmi2FMUstate) -> fmi2Status {
                // SAFETY: the host's component, state and buffers, passed on unchanged (contracts 1 to 4 of `api`).
                unsafe { $crate::fmi2::api::free_fmu_state::<M>(c, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SerializedFMUstateSize(
                c: fmi2Component,
                s: fmi2FMUstate,
                size: *mut usize,
            ) -> fmi2Status {
                // SAFETY: the host's component, state and buffers, passed on unchanged (contracts 1 to 4 of `api`).
                unsafe { $crate::fmi2::api::serialized_fmu_state_size::<M>(c, s, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SerializeFMUstate(
                c: fmi2Component,
                s: fmi2FMUstate,
                bytes: *mut fmi2Byte,
                size: usize,
            ) -> fmi2Status {
                // SAFETY: the host's component, state and buffers, passed on unchanged (contracts 1 to 4 of `api`).
                unsafe { $crate::fmi2::api::serialize_fmu_state::<M>(c, s, bytes, size) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2DeSerializeFMUstate(
                c: fmi2Component,
                bytes: *const fmi2Byte,
                size: usize,
                s: *mut fmi2FMUstate,
            ) -> fmi2Status {
                // SAFETY: the host's component, state and buffers, passed on unchanged (contracts 1 to 4 of `api`).
                unsafe { $crate::fmi2::api::deserialize_fmu_state::<M>(c, bytes, size, s) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetDirectionalDerivative(
                c: fmi2Component,
                _u: *const fmi2ValueReference,
                _nu: usize,
                _k: *const fmi2ValueReference,
                _nk: usize,
                _dk: *const fmi2Real,
                _du: *mut fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetDirectionalDerivative") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2EnterEventMode(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2EnterEventMode") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2NewDiscreteStates(c: fmi2Component, _info: *mut fmi2EventInfo) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2NewDiscreteStates") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2EnterContinuousTimeMode(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2EnterContinuousTimeMode") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2CompletedIntegratorStep(
                c: fmi2Component,
                _no_set: fmi2Boolean,
                _event: *mut fmi2Boolean,
                _term: *mut fmi2Boolean,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2CompletedIntegratorStep") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetTime(c: fmi2Component, _t: fmi2Real) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2SetTime") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetContinuousStates(
                c: fmi2Component,
                _x: *const fmi2Real,
                _n: usize,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2SetContinuousStates") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetDerivatives(c: fmi2Component, _dx: *mut fmi2Real, _n: usize) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetDerivatives") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetEventIndicators(
                c: fmi2Component,
                _z: *mut fmi2Real,
                _n: usize,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetEventIndicators") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetContinuousStates(
                c: fmi2Component,
                _x: *mut fmi2Real,
                _n: usize,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetContinuousStates") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetNominalsOfContinuousStates(
                c: fmi2Component,
                _x: *mut fmi2Real,
                _n: usize,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetNominalsOfContinuousStates") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
                c: fmi2Component,
                vr: *const fmi2ValueReference,
                n: usize,
                order: *const fmi2Integer,
                v: *const fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::set_real_input_derivatives::<M>(c, vr, n, order, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetRealOutputDerivatives(
                c: fmi2Component,
                _vr: *const fmi2ValueReference,
                _n: usize,
                _order: *const fmi2Integer,
                _v: *mut fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetRealOutputDerivatives") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2DoStep(
                c: fmi2Component,
                t: fmi2Real,
                h: fmi2Real,
                no_set: fmi2Boolean,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::do_step::<M>(c, t, h, no_set) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2CancelStep(c: fmi2Component) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2CancelStep") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetStatus(
                c: fmi2Component,
                _k: fmi2StatusKind,
                _v: *mut fmi2Status,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetStatus") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetRealStatus(
                c: fmi2Component,
                k: fmi2StatusKind,
                v: *mut fmi2Real,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::get_real_status::<M>(c, k, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetIntegerStatus(
                c: fmi2Component,
                _k: fmi2StatusKind,
                _v: *mut fmi2Integer,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetIntegerStatus") }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetBooleanStatus(
                c: fmi2Component,
                k: fmi2StatusKind,
                v: *mut fmi2Boolean,
            ) -> fmi2Status {
                // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `api`).
                unsafe { $crate::fmi2::api::get_boolean_status::<M>(c, k, v) }
            }
            #[no_mangle]
            pub unsafe extern "C" fn fmi2GetStringStatus(
                c: fmi2Component,
                _k: fmi2StatusKind,
                _v: *mut fmi2String,
            ) -> fmi2Status {
                // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `api`).
                unsafe { $crate::fmi2::api::unsupported::<M>(c, "fmi2GetStringStatus") }
            }

            // Every function of fmi2Functions.h is defined above, with its fmi2FunctionTypes.h type.
            $crate::ffi::fmi2_functions!($crate::__assert_fmi2_signatures);
        }
        $crate::__export_fmi3!($model);
    };
}

/// Compile-time check used by [`export_fmu!`]: each `name` coerces to the function pointer type
/// `nameTYPE`, i.e. it exists and has exactly the C signature of the header.
#[doc(hidden)]
#[macro_export]
macro_rules! __assert_fmi2_signatures {
    ($($name:ident : $ty:ident),* $(,)?) => {
        const _: () = { $(let _: $ty = $name;)* };
    };
}
