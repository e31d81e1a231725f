//! Raw C ABI of FMI 2.0, transcribed from `fmi2TypesPlatform.h` and
//! `fmi2FunctionTypes.h` (FMI 2.0.1, platform "default").
//!
//! One declaration of the ABI for both sides of it: the importer (`fmu-import`,
//! which calls FMUs through the `fmi2…TYPE` function pointers) and the
//! exporter (`fmi2`, whose `export_fmu!` defines the `#[no_mangle]` functions
//! and checks each one against its `fmi2…TYPE` at compile time).
//! [`fmi2_functions!`] lists every function of `fmi2Functions.h` once.
//!
//! Names follow the C headers exactly so that each declaration can be checked
//! against the standard line by line. Enumerations that cross the ABI
//! (`fmi2Status`, `fmi2Type`, `fmi2StatusKind`) are plain `c_int` values
//! rather than Rust `enum`s: an FMU may return any integer, and a Rust enum
//! holding an undeclared discriminant would be undefined behaviour.
#![allow(non_camel_case_types, non_upper_case_globals, non_snake_case)]

use std::os::raw::{c_char, c_double, c_int, c_uint, c_void};

// ---------------------------------------------------------------------------
// fmi2TypesPlatform.h
// ---------------------------------------------------------------------------

/// Value of the `fmi2TypesPlatform` macro.
pub const fmi2TypesPlatform: &str = "default";
/// Value of the `fmi2Version` macro.
pub const fmi2Version: &str = "2.0";

/// Pointer to an FMU instance.
pub type fmi2Component = *mut c_void;
/// Pointer to the importer's environment, handed back to callbacks.
pub type fmi2ComponentEnvironment = *mut c_void;
/// Pointer to an internal FMU state.
pub type fmi2FMUstate = *mut c_void;
/// Handle to the value of a variable.
pub type fmi2ValueReference = c_uint;
/// Double precision floating point.
pub type fmi2Real = c_double;
/// Signed integer.
pub type fmi2Integer = c_int;
/// Boolean as signed integer (`fmi2True` = 1, `fmi2False` = 0).
pub type fmi2Boolean = c_int;
/// Character type.
pub type fmi2Char = c_char;
/// `'\0'`-terminated UTF-8 string.
pub type fmi2String = *const fmi2Char;
/// Smallest addressable unit of the machine.
pub type fmi2Byte = c_char;

pub const fmi2True: fmi2Boolean = 1;
pub const fmi2False: fmi2Boolean = 0;

// ---------------------------------------------------------------------------
// fmi2FunctionTypes.h: enumerations and structures
// ---------------------------------------------------------------------------

/// A C enum of the header, passed as `int`: the type `$name` and one constant per enumerator,
/// with the header's value.
macro_rules! c_enum {
    ($(#[$doc:meta])* $name:ident { $($enumerator:ident = $value:literal,)* }) => {
        $(#[$doc])*
        pub type $name = c_int;
        $(pub const $enumerator: $name = $value;)*
    };
}

c_enum!(
    /// `fmi2Status`.
    fmi2Status {
        fmi2OK = 0,
        fmi2Warning = 1,
        fmi2Discard = 2,
        fmi2Error = 3,
        fmi2Fatal = 4,
        fmi2Pending = 5,
    }
);
c_enum!(
    /// `fmi2Type`.
    fmi2Type {
        fmi2ModelExchange = 0,
        fmi2CoSimulation = 1,
    }
);
c_enum!(
    /// `fmi2StatusKind`.
    fmi2StatusKind {
        fmi2DoStepStatus = 0,
        fmi2PendingStatus = 1,
        fmi2LastSuccessfulTime = 2,
        fmi2Terminated = 3,
    }
);

/// `fmi2CallbackLogger`: variadic, printf-style `message`.
///
/// Stable Rust can name but not define variadic functions; the host
/// implementation lives in `logger.c`.
pub type fmi2CallbackLogger = Option<
    unsafe extern "C" fn(
        componentEnvironment: fmi2ComponentEnvironment,
        instanceName: fmi2String,
        status: fmi2Status,
        category: fmi2String,
        message: fmi2String,
        ...
    ),
>;
/// `fmi2CallbackAllocateMemory`: `calloc` semantics.
pub type fmi2CallbackAllocateMemory = Option<unsafe extern "C" fn(nobj: usize, size: usize) -> *mut c_void>;
/// `fmi2CallbackFreeMemory`: `free` semantics.
pub type fmi2CallbackFreeMemory = Option<unsafe extern "C" fn(obj: *mut c_void)>;
/// `fmi2StepFinished`: completion callback of an asynchronous `fmi2DoStep`.
pub type fmi2StepFinished =
    Option<unsafe extern "C" fn(componentEnvironment: fmi2ComponentEnvironment, status: fmi2Status)>;

/// `fmi2CallbackFunctions`. The header packs with `#pragma pack(push,8)`,
/// which equals natural alignment for these members on 64-bit targets.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct fmi2CallbackFunctions {
    pub logger: fmi2CallbackLogger,
    pub allocateMemory: fmi2CallbackAllocateMemory,
    pub freeMemory: fmi2CallbackFreeMemory,
    pub stepFinished: fmi2StepFinished,
    pub componentEnvironment: fmi2ComponentEnvironment,
}

/// `fmi2EventInfo` (Model Exchange).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct fmi2EventInfo {
    pub newDiscreteStatesNeeded: fmi2Boolean,
    pub terminateSimulation: fmi2Boolean,
    pub nominalsOfContinuousStatesChanged: fmi2Boolean,
    pub valuesOfContinuousStatesChanged: fmi2Boolean,
    pub nextEventTimeDefined: fmi2Boolean,
    pub nextEventTime: fmi2Real,
}

// ---------------------------------------------------------------------------
// fmi2FunctionTypes.h: function pointer types (one per fmi2Functions.h entry)
// ---------------------------------------------------------------------------

// Common functions
pub type fmi2GetTypesPlatformTYPE = unsafe extern "C" fn() -> *const c_char;
pub type fmi2GetVersionTYPE = unsafe extern "C" fn() -> *const c_char;
pub type fmi2SetDebugLoggingTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    loggingOn: fmi2Boolean,
    nCategories: usize,
    categories: *const fmi2String,
) -> fmi2Status;
pub type fmi2InstantiateTYPE = unsafe extern "C" fn(
    instanceName: fmi2String,
    fmuType: fmi2Type,
    fmuGUID: fmi2String,
    fmuResourceLocation: fmi2String,
    functions: *const fmi2CallbackFunctions,
    visible: fmi2Boolean,
    loggingOn: fmi2Boolean,
) -> fmi2Component;
pub type fmi2FreeInstanceTYPE = unsafe extern "C" fn(c: fmi2Component);
pub type fmi2SetupExperimentTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    toleranceDefined: fmi2Boolean,
    tolerance: fmi2Real,
    startTime: fmi2Real,
    stopTimeDefined: fmi2Boolean,
    stopTime: fmi2Real,
) -> fmi2Status;
pub type fmi2EnterInitializationModeTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2ExitInitializationModeTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2TerminateTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2ResetTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2GetRealTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Real,
) -> fmi2Status;
pub type fmi2GetIntegerTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Integer,
) -> fmi2Status;
pub type fmi2GetBooleanTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2Boolean,
) -> fmi2Status;
pub type fmi2GetStringTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *mut fmi2String,
) -> fmi2Status;
pub type fmi2SetRealTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Real,
) -> fmi2Status;
pub type fmi2SetIntegerTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Integer,
) -> fmi2Status;
pub type fmi2SetBooleanTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2Boolean,
) -> fmi2Status;
pub type fmi2SetStringTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    value: *const fmi2String,
) -> fmi2Status;
pub type fmi2GetFMUstateTYPE = unsafe extern "C" fn(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status;
pub type fmi2SetFMUstateTYPE = unsafe extern "C" fn(c: fmi2Component, FMUstate: fmi2FMUstate) -> fmi2Status;
pub type fmi2FreeFMUstateTYPE = unsafe extern "C" fn(c: fmi2Component, FMUstate: *mut fmi2FMUstate) -> fmi2Status;
pub type fmi2SerializedFMUstateSizeTYPE =
    unsafe extern "C" fn(c: fmi2Component, FMUstate: fmi2FMUstate, size: *mut usize) -> fmi2Status;
pub type fmi2SerializeFMUstateTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    FMUstate: fmi2FMUstate,
    serializedState: *mut fmi2Byte,
    size: usize,
) -> fmi2Status;
pub type fmi2DeSerializeFMUstateTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    serializedState: *const fmi2Byte,
    size: usize,
    FMUstate: *mut fmi2FMUstate,
) -> fmi2Status;
pub type fmi2GetDirectionalDerivativeTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vUnknown_ref: *const fmi2ValueReference,
    nUnknown: usize,
    vKnown_ref: *const fmi2ValueReference,
    nKnown: usize,
    dvKnown: *const fmi2Real,
    dvUnknown: *mut fmi2Real,
) -> fmi2Status;

// Model Exchange
pub type fmi2EnterEventModeTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2NewDiscreteStatesTYPE =
    unsafe extern "C" fn(c: fmi2Component, fmi2eventInfo: *mut fmi2EventInfo) -> fmi2Status;
pub type fmi2EnterContinuousTimeModeTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2CompletedIntegratorStepTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
    enterEventMode: *mut fmi2Boolean,
    terminateSimulation: *mut fmi2Boolean,
) -> fmi2Status;
pub type fmi2SetTimeTYPE = unsafe extern "C" fn(c: fmi2Component, time: fmi2Real) -> fmi2Status;
pub type fmi2SetContinuousStatesTYPE =
    unsafe extern "C" fn(c: fmi2Component, x: *const fmi2Real, nx: usize) -> fmi2Status;
pub type fmi2GetDerivativesTYPE =
    unsafe extern "C" fn(c: fmi2Component, derivatives: *mut fmi2Real, nx: usize) -> fmi2Status;
pub type fmi2GetEventIndicatorsTYPE =
    unsafe extern "C" fn(c: fmi2Component, eventIndicators: *mut fmi2Real, ni: usize) -> fmi2Status;
pub type fmi2GetContinuousStatesTYPE =
    unsafe extern "C" fn(c: fmi2Component, x: *mut fmi2Real, nx: usize) -> fmi2Status;
pub type fmi2GetNominalsOfContinuousStatesTYPE =
    unsafe extern "C" fn(c: fmi2Component, x_nominal: *mut fmi2Real, nx: usize) -> fmi2Status;

// Co-Simulation
pub type fmi2SetRealInputDerivativesTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *const fmi2Real,
) -> fmi2Status;
pub type fmi2GetRealOutputDerivativesTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    vr: *const fmi2ValueReference,
    nvr: usize,
    order: *const fmi2Integer,
    value: *mut fmi2Real,
) -> fmi2Status;
pub type fmi2DoStepTYPE = unsafe extern "C" fn(
    c: fmi2Component,
    currentCommunicationPoint: fmi2Real,
    communicationStepSize: fmi2Real,
    noSetFMUStatePriorToCurrentPoint: fmi2Boolean,
) -> fmi2Status;
pub type fmi2CancelStepTYPE = unsafe extern "C" fn(c: fmi2Component) -> fmi2Status;
pub type fmi2GetStatusTYPE =
    unsafe extern "C" fn(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Status) -> fmi2Status;
pub type fmi2GetRealStatusTYPE =
    unsafe extern "C" fn(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Real) -> fmi2Status;
pub type fmi2GetIntegerStatusTYPE =
    unsafe extern "C" fn(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Integer) -> fmi2Status;
pub type fmi2GetBooleanStatusTYPE =
    unsafe extern "C" fn(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2Boolean) -> fmi2Status;
pub type fmi2GetStringStatusTYPE =
    unsafe extern "C" fn(c: fmi2Component, s: fmi2StatusKind, value: *mut fmi2String) -> fmi2Status;

/// Invokes `$callback! { name: nameTYPE, ... }` with every function of
/// `fmi2Functions.h`, in header order, each paired with its function type.
///
/// `$callback` is a `macro_rules!` macro in scope at the call site (given by
/// name) or a path to an exported one.
#[macro_export]
macro_rules! fmi2_functions {
    ($($callback:tt)+) => {
        $($callback)+! {
            // Common functions
            fmi2GetTypesPlatform: fmi2GetTypesPlatformTYPE,
            fmi2GetVersion: fmi2GetVersionTYPE,
            fmi2SetDebugLogging: fmi2SetDebugLoggingTYPE,
            fmi2Instantiate: fmi2InstantiateTYPE,
            fmi2FreeInstance: fmi2FreeInstanceTYPE,
            fmi2SetupExperiment: fmi2SetupExperimentTYPE,
            fmi2EnterInitializationMode: fmi2EnterInitializationModeTYPE,
            fmi2ExitInitializationMode: fmi2ExitInitializationModeTYPE,
            fmi2Terminate: fmi2TerminateTYPE,
            fmi2Reset: fmi2ResetTYPE,
            fmi2GetReal: fmi2GetRealTYPE,
            fmi2GetInteger: fmi2GetIntegerTYPE,
            fmi2GetBoolean: fmi2GetBooleanTYPE,
            fmi2GetString: fmi2GetStringTYPE,
            fmi2SetReal: fmi2SetRealTYPE,
            fmi2SetInteger: fmi2SetIntegerTYPE,
            fmi2SetBoolean: fmi2SetBooleanTYPE,
            fmi2SetString: fmi2SetStringTYPE,
            fmi2GetFMUstate: fmi2GetFMUstateTYPE,
            fmi2SetFMUstate: fmi2SetFMUstateTYPE,
            fmi2FreeFMUstate: fmi2FreeFMUstateTYPE,
            fmi2SerializedFMUstateSize: fmi2SerializedFMUstateSizeTYPE,
            fmi2SerializeFMUstate: fmi2SerializeFMUstateTYPE,
            fmi2DeSerializeFMUstate: fmi2DeSerializeFMUstateTYPE,
            fmi2GetDirectionalDerivative: fmi2GetDirectionalDerivativeTYPE,
            // Model Exchange
            fmi2EnterEventMode: fmi2EnterEventModeTYPE,
            fmi2NewDiscreteStates: fmi2NewDiscreteStatesTYPE,
            fmi2EnterContinuousTimeMode: fmi2EnterContinuousTimeModeTYPE,
            fmi2CompletedIntegratorStep: fmi2CompletedIntegratorStepTYPE,
            fmi2SetTime: fmi2SetTimeTYPE,
            fmi2SetContinuousStates: fmi2SetContinuousStatesTYPE,
            fmi2GetDerivatives: fmi2GetDerivativesTYPE,
            fmi2GetEventIndicators: fmi2GetEventIndicatorsTYPE,
            fmi2GetContinuousStates: fmi2GetContinuousStatesTYPE,
            fmi2GetNominalsOfContinuousStates: fmi2GetNominalsOfContinuousStatesTYPE,
            // Co-Simulation
            fmi2SetRealInputDerivatives: fmi2SetRealInputDerivativesTYPE,
            fmi2GetRealOutputDerivatives: fmi2GetRealOutputDerivativesTYPE,
            fmi2DoStep: fmi2DoStepTYPE,
            fmi2CancelStep: fmi2CancelStepTYPE,
            fmi2GetStatus: fmi2GetStatusTYPE,
            fmi2GetRealStatus: fmi2GetRealStatusTYPE,
            fmi2GetIntegerStatus: fmi2GetIntegerStatusTYPE,
            fmi2GetBooleanStatus: fmi2GetBooleanStatusTYPE,
            fmi2GetStringStatus: fmi2GetStringStatusTYPE,
        }
    };
}

// Layout checks against the C definitions (LP64, `#pragma pack(8)`).
#[cfg(target_pointer_width = "64")]
const _: () = {
    assert!(std::mem::size_of::<fmi2CallbackFunctions>() == 40);
    assert!(std::mem::align_of::<fmi2CallbackFunctions>() == 8);
    assert!(std::mem::size_of::<fmi2EventInfo>() == 32);
    assert!(std::mem::offset_of!(fmi2EventInfo, nextEventTime) == 24);
    assert!(std::mem::size_of::<fmi2ValueReference>() == 4);
    assert!(std::mem::size_of::<fmi2Boolean>() == 4);
    assert!(std::mem::size_of::<fmi2CallbackLogger>() == 8);
};
