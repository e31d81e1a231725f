//! The `fmi2*` half of [`crate::export_fmu!`]: one `#[no_mangle] extern "C"` function per
//! entry of `fmi2Functions.h`, each forwarding to [`crate::fmi2::api`] and checked against its
//! `fmi2…TYPE` at compile time; the plain forwards, getters, setters and refusals one line each
//! through [`crate::__forward!`] and the macros at the end of this file.

/// The FMI 2.0 C API of the model `M` but its model description entry point, expanded by
/// [`crate::export_fmu!`] inside the module [`crate::__export_module!`] opens for FMI 2.0.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_entries {
    () => {
        $crate::__static_string!(fmi2GetTypesPlatform => c"default");
        $crate::__static_string!(fmi2GetVersion => c"2.0");
        $crate::__forward!(fmi2SetDebugLogging(c: fmi2Component, on: fmi2Boolean, n: usize, cat: *const fmi2String) -> fmi2Status => fmi2::set_debug_logging);
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
            match $crate::description::cached::<$crate::fmi2::xml::Fmi2, M>(&TOKEN) {
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
        $crate::__forward!(fmi2FreeInstance(c: fmi2Component) => fmi2::free_instance);
        $crate::__forward!(fmi2SetupExperiment(c: fmi2Component, tol_defined: fmi2Boolean, tol: fmi2Real, start: fmi2Real, stop_defined: fmi2Boolean, stop: fmi2Real) -> fmi2Status => fmi2::setup_experiment);
        $crate::__forward!(fmi2EnterInitializationMode(c: fmi2Component) -> fmi2Status => fmi2::enter_initialization_mode);
        $crate::__forward!(fmi2ExitInitializationMode(c: fmi2Component) -> fmi2Status => fmi2::exit_initialization_mode);
        $crate::__forward!(fmi2Terminate(c: fmi2Component) -> fmi2Status => fmi2::terminate);
        $crate::__forward!(fmi2Reset(c: fmi2Component) -> fmi2Status => fmi2::reset);
        $crate::__fmi2_values!(fmi2GetReal(*mut fmi2Real) get_values calls::Real);
        $crate::__fmi2_values!(fmi2GetInteger(*mut fmi2Integer) get_values calls::Integer);
        $crate::__fmi2_values!(fmi2GetBoolean(*mut fmi2Boolean) get_values fmi2::api::Boolean);
        $crate::__fmi2_values!(fmi2GetString(*mut fmi2String) get_values calls::Text);
        $crate::__fmi2_values!(fmi2SetReal(*const fmi2Real) set_values calls::Real);
        $crate::__fmi2_values!(fmi2SetInteger(*const fmi2Integer) set_values calls::Integer);
        $crate::__fmi2_values!(fmi2SetBoolean(*const fmi2Boolean) set_values fmi2::api::Boolean);
        $crate::__forward!(fmi2SetString(c: fmi2Component, vr: *const fmi2ValueReference, n: usize, v: *const fmi2String) -> fmi2Status => fmi2::set_string);
        $crate::__fmu_state_entries!(
            fmi2(fmi2Component, fmi2FMUstate, fmi2Byte, fmi2Status):
            fmi2GetFMUstate, fmi2SetFMUstate, fmi2FreeFMUstate,
            fmi2SerializedFMUstateSize, fmi2SerializeFMUstate, fmi2DeSerializeFMUstate
        );
        $crate::__fmi2_unsupported!(fmi2GetDirectionalDerivative(*const fmi2ValueReference, usize, *const fmi2ValueReference, usize, *const fmi2Real, *mut fmi2Real));
        $crate::__fmi2_unsupported!(fmi2EnterEventMode());
        $crate::__fmi2_unsupported!(fmi2NewDiscreteStates(*mut fmi2EventInfo));
        $crate::__fmi2_unsupported!(fmi2EnterContinuousTimeMode());
        $crate::__fmi2_unsupported!(fmi2CompletedIntegratorStep(fmi2Boolean, *mut fmi2Boolean, *mut fmi2Boolean));
        $crate::__fmi2_unsupported!(fmi2SetTime(fmi2Real));
        $crate::__fmi2_unsupported!(fmi2SetContinuousStates(*const fmi2Real, usize));
        $crate::__fmi2_unsupported!(fmi2GetDerivatives(*mut fmi2Real, usize));
        $crate::__fmi2_unsupported!(fmi2GetEventIndicators(*mut fmi2Real, usize));
        $crate::__fmi2_unsupported!(fmi2GetContinuousStates(*mut fmi2Real, usize));
        $crate::__fmi2_unsupported!(fmi2GetNominalsOfContinuousStates(*mut fmi2Real, usize));
        $crate::__forward!(fmi2SetRealInputDerivatives(c: fmi2Component, vr: *const fmi2ValueReference, n: usize, order: *const fmi2Integer, v: *const fmi2Real) -> fmi2Status => fmi2::set_real_input_derivatives);
        $crate::__fmi2_unsupported!(fmi2GetRealOutputDerivatives(*const fmi2ValueReference, usize, *const fmi2Integer, *mut fmi2Real));
        $crate::__forward!(fmi2DoStep(c: fmi2Component, t: fmi2Real, h: fmi2Real, no_set: fmi2Boolean) -> fmi2Status => fmi2::do_step);
        $crate::__fmi2_unsupported!(fmi2CancelStep());
        $crate::__fmi2_unsupported!(fmi2GetStatus(fmi2StatusKind, *mut fmi2Status));
        $crate::__forward!(fmi2GetRealStatus(c: fmi2Component, k: fmi2StatusKind, v: *mut fmi2Real) -> fmi2Status => fmi2::get_real_status);
        $crate::__fmi2_unsupported!(fmi2GetIntegerStatus(fmi2StatusKind, *mut fmi2Integer));
        $crate::__forward!(fmi2GetBooleanStatus(c: fmi2Component, k: fmi2StatusKind, v: *mut fmi2Boolean) -> fmi2Status => fmi2::get_boolean_status);
        $crate::__fmi2_unsupported!(fmi2GetStringStatus(fmi2StatusKind, *mut fmi2String));
    };
}

/// A getter or setter of a value type the FMU has variables of: forwards to `api::$api`
/// (`get_values` or `set_values`) for the value type `$kind` (a path in this crate: a
/// [`crate::calls::ValueArrays`] type), under its own name; `$values` is the type of its values
/// array.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_values {
    ($name:ident($values:ty) $api:ident $($kind:ident)::+) => {
        #[no_mangle]
        pub unsafe extern "C" fn $name(
            c: fmi2Component,
            vr: *const fmi2ValueReference,
            n: usize,
            value: $values,
        ) -> fmi2Status {
            // SAFETY: the host's component and arrays, passed on unchanged (contracts 1 to 3 of `calls`).
            unsafe { $crate::fmi2::api::$api::<M, $crate::$($kind)::+>(c, stringify!($name), vr, n, value) }
        }
    };
}

/// A function the FMU declares but refuses with `fmi2Error` (Model Exchange, asynchronous
/// steps, derivatives, the statuses it has none of), naming itself in the message; `$arg` are
/// the types after the component, which it never reads.
#[doc(hidden)]
#[macro_export]
macro_rules! __fmi2_unsupported {
    ($name:ident($($arg:ty),*)) => {
        #[no_mangle]
        pub unsafe extern "C" fn $name(c: fmi2Component, $(_: $arg),*) -> fmi2Status {
            // SAFETY: the host's component, passed on unchanged (contracts 1 and 2 of `calls`).
            unsafe { $crate::fmi2::api::unsupported::<M>(c, stringify!($name)) }
        }
    };
}
