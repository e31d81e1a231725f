//! The `fmi2*` half of [`crate::export_fmu!`]: one `#[no_mangle] extern "C"` function per
//! entry of `fmi2Functions.h`, each forwarding to [`crate::fmi2::api`] and checked against its
//! `fmi2…TYPE` at compile time.

/// Expands the FMI 2.0 C API of `$model` (called by [`crate::export_fmu!`]).
#[doc(hidden)]
#[macro_export]
macro_rules! __export_fmi2 {
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
    };
}

/// Compile-time check used by [`crate::export_fmu!`]: each `name` coerces to the function pointer type
/// `nameTYPE`, i.e. it exists and has exactly the C signature of the header.
#[doc(hidden)]
#[macro_export]
macro_rules! __assert_fmi2_signatures {
    ($($name:ident : $ty:ident),* $(,)?) => {
        const _: () = { $(let _: $ty = $name;)* };
    };
}
