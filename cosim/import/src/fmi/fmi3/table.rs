//! The FMI 2.0 table of the adapter ([`functions`]), the calls FMI 3.0 has no counterpart of,
//! and the FMI 3.0 names of the FMI 2.0 calls ([`call_name`]).

use std::ffi::{c_char, c_int};

use super::lifecycle::*;
use super::states::*;
use super::step::*;
use super::values::*;
use crate::fmi::{ffi, Functions};

unsafe extern "C" fn types_platform() -> *const c_char {
    c"default".as_ptr()
}

unsafe extern "C" fn version() -> *const c_char {
    c"3.0".as_ptr()
}

/// Calls FMI 3.0 has no counterpart of (`fmi2Instantiate`, done by [`super::instantiate`]; input and
/// output derivatives; asynchronous steps; directional derivatives): `fmi2Error`.
macro_rules! refused {
    ($name:ident($($arg:ident: $ty:ty),*)) => {
        unsafe extern "C" fn $name(_c: ffi::fmi2Component, $($arg: $ty),*) -> ffi::fmi2Status {
            let _ = ($($arg,)*);
            ffi::fmi2Error
        }
    };
}
refused!(set_real_input_derivatives(vr: *const u32, n: usize, order: *const i32, v: *const f64));
refused!(get_real_output_derivatives(vr: *const u32, n: usize, order: *const i32, v: *mut f64));
refused!(cancel_step());
refused!(get_status(kind: c_int, v: *mut c_int));
refused!(get_integer_status(kind: c_int, v: *mut c_int));
refused!(get_string_status(kind: c_int, v: *mut ffi::fmi2String));
refused!(get_directional_derivative(
    u: *const u32,
    nu: usize,
    k: *const u32,
    nk: usize,
    dk: *const f64,
    du: *mut f64
));

unsafe extern "C" fn refused_instantiate(
    _name: ffi::fmi2String,
    _kind: c_int,
    _guid: ffi::fmi2String,
    _resources: ffi::fmi2String,
    _functions: *const ffi::fmi2CallbackFunctions,
    _visible: ffi::fmi2Boolean,
    _logging_on: ffi::fmi2Boolean,
) -> ffi::fmi2Component {
    std::ptr::null_mut()
}

/// The FMI 2.0 table whose functions translate to the FMI 3.0 instance behind each component
/// (see the module documentation); `fmi2Instantiate` returns NULL: use [`super::instantiate`].
pub fn functions() -> Functions {
    Functions {
        fmi2GetTypesPlatform: types_platform,
        fmi2GetVersion: version,
        fmi2SetDebugLogging: set_debug_logging,
        fmi2Instantiate: refused_instantiate,
        fmi2FreeInstance: free_instance,
        fmi2SetupExperiment: setup_experiment,
        fmi2EnterInitializationMode: enter_initialization_mode,
        fmi2ExitInitializationMode: exit_initialization_mode,
        fmi2Terminate: terminate,
        fmi2Reset: reset,
        fmi2GetReal: get_real,
        fmi2GetInteger: get_integer,
        fmi2GetBoolean: get_boolean,
        fmi2GetString: get_string,
        fmi2SetReal: set_real,
        fmi2SetInteger: set_integer,
        fmi2SetBoolean: set_boolean,
        fmi2SetString: set_string,
        fmi2GetFMUstate: get_fmu_state,
        fmi2SetFMUstate: set_fmu_state,
        fmi2FreeFMUstate: free_fmu_state,
        fmi2SerializedFMUstateSize: serialized_fmu_state_size,
        fmi2SerializeFMUstate: serialize_fmu_state,
        fmi2DeSerializeFMUstate: deserialize_fmu_state,
        fmi2GetDirectionalDerivative: get_directional_derivative,
        fmi2EnterEventMode: None,
        fmi2NewDiscreteStates: None,
        fmi2EnterContinuousTimeMode: None,
        fmi2CompletedIntegratorStep: None,
        fmi2SetTime: None,
        fmi2SetContinuousStates: None,
        fmi2GetDerivatives: None,
        fmi2GetEventIndicators: None,
        fmi2GetContinuousStates: None,
        fmi2GetNominalsOfContinuousStates: None,
        fmi2SetRealInputDerivatives: set_real_input_derivatives,
        fmi2GetRealOutputDerivatives: get_real_output_derivatives,
        fmi2DoStep: do_step,
        fmi2CancelStep: cancel_step,
        fmi2GetStatus: get_status,
        fmi2GetRealStatus: get_real_status,
        fmi2GetIntegerStatus: get_integer_status,
        fmi2GetBooleanStatus: get_boolean_status,
        fmi2GetStringStatus: get_string_status,
    }
}

/// The FMI 3.0 name of the FMI 2.0 call the importer made, for messages about an FMI 3.0 FMU.
pub fn call_name(fmi2_call: &'static str) -> &'static str {
    match fmi2_call {
        "fmi2Instantiate" => "fmi3InstantiateCoSimulation",
        "fmi2SetupExperiment" | "fmi2EnterInitializationMode" => "fmi3EnterInitializationMode",
        "fmi2ExitInitializationMode" => "fmi3ExitInitializationMode",
        "fmi2DoStep" => "fmi3DoStep",
        "fmi2Terminate" => "fmi3Terminate",
        "fmi2FreeInstance" => "fmi3FreeInstance",
        "fmi2Reset" => "fmi3Reset",
        "fmi2SetDebugLogging" => "fmi3SetDebugLogging",
        "fmi2GetReal" => "fmi3GetFloat64",
        "fmi2GetInteger" => "fmi3GetInt32",
        "fmi2GetBoolean" => "fmi3GetBoolean",
        "fmi2GetString" => "fmi3GetString",
        "fmi2SetReal" => "fmi3SetFloat64",
        "fmi2SetInteger" => "fmi3SetInt32",
        "fmi2SetBoolean" => "fmi3SetBoolean",
        "fmi2SetString" => "fmi3SetString",
        "fmi2GetFMUstate" => "fmi3GetFMUState",
        "fmi2SetFMUstate" => "fmi3SetFMUState",
        "fmi2FreeFMUstate" => "fmi3FreeFMUState",
        "fmi2SerializedFMUstateSize" => "fmi3SerializedFMUStateSize",
        "fmi2SerializeFMUstate" => "fmi3SerializeFMUState",
        "fmi2DeSerializeFMUstate" => "fmi3DeserializeFMUState",
        other => other,
    }
}
