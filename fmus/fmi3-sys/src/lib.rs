//! Raw C ABI of FMI 3.0, transcribed from `fmi3PlatformTypes.h` and `fmi3FunctionTypes.h`
//! (FMI 3.0.2, the headers FMPy ships).
//!
//! One declaration of the ABI for both sides of it: the exporter (`fmu-export`, whose
//! `export_fmu!` defines the `#[no_mangle]` functions and checks each one against its
//! `fmi3…TYPE` at compile time) and the importer. [`fmi3_functions!`] lists every function of
//! `fmi3Functions.h` once, in header order.
//!
//! Names follow the C headers exactly so that each declaration can be checked against the
//! standard line by line. The enumerations (`fmi3Status`, `fmi3DependencyKind`,
//! `fmi3IntervalQualifier`) are plain `c_int` values rather than Rust `enum`s: a foreign side may
//! pass any integer, and a Rust enum holding an undeclared discriminant would be undefined
//! behaviour. `fmi3Boolean` is C's `bool`, which Rust's `bool` matches in size and ABI; a side
//! that reads a host's `bool` array should read its bytes (`u8`), since a byte other than 0 or 1
//! in a Rust `bool` is undefined behaviour.
#![allow(non_camel_case_types, non_upper_case_globals, non_snake_case)]

use std::os::raw::{c_char, c_int, c_void};

// ---------------------------------------------------------------------------
// fmi3PlatformTypes.h
// ---------------------------------------------------------------------------

/// Value of the `fmi3Version` macro of `fmi3Functions.h`.
pub const fmi3Version: &str = "3.0";

/// Pointer to an FMU instance.
pub type fmi3Instance = *mut c_void;
/// Pointer to the importer's environment, handed back to callbacks.
pub type fmi3InstanceEnvironment = *mut c_void;
/// Pointer to an internal FMU state.
pub type fmi3FMUState = *mut c_void;
/// Handle to the value of a variable (unique across all types of an FMU).
pub type fmi3ValueReference = u32;
pub type fmi3Float32 = f32;
pub type fmi3Float64 = f64;
pub type fmi3Int8 = i8;
pub type fmi3UInt8 = u8;
pub type fmi3Int16 = i16;
pub type fmi3UInt16 = u16;
pub type fmi3Int32 = i32;
pub type fmi3UInt32 = u32;
pub type fmi3Int64 = i64;
pub type fmi3UInt64 = u64;
/// C `bool`.
pub type fmi3Boolean = bool;
pub type fmi3Char = c_char;
/// `'\0'`-terminated UTF-8 string.
pub type fmi3String = *const fmi3Char;
pub type fmi3Byte = u8;
/// Binary data, its length passed out of band.
pub type fmi3Binary = *const fmi3Byte;
/// C `bool` (`fmi3ClockActive` / `fmi3ClockInactive`).
pub type fmi3Clock = bool;

pub const fmi3True: fmi3Boolean = true;
pub const fmi3False: fmi3Boolean = false;

// ---------------------------------------------------------------------------
// fmi3FunctionTypes.h: enumerations and callbacks
// ---------------------------------------------------------------------------

/// `fmi3Status` (C enum, passed as `int`).
pub type fmi3Status = c_int;
pub const fmi3OK: fmi3Status = 0;
pub const fmi3Warning: fmi3Status = 1;
pub const fmi3Discard: fmi3Status = 2;
pub const fmi3Error: fmi3Status = 3;
pub const fmi3Fatal: fmi3Status = 4;

/// `fmi3DependencyKind` (C enum, passed as `int`).
pub type fmi3DependencyKind = c_int;
pub const fmi3Independent: fmi3DependencyKind = 0;
pub const fmi3Constant: fmi3DependencyKind = 1;
pub const fmi3Fixed: fmi3DependencyKind = 2;
pub const fmi3Tunable: fmi3DependencyKind = 3;
pub const fmi3Discrete: fmi3DependencyKind = 4;
pub const fmi3Dependent: fmi3DependencyKind = 5;

/// `fmi3IntervalQualifier` (C enum, passed as `int`).
pub type fmi3IntervalQualifier = c_int;
pub const fmi3IntervalNotYetKnown: fmi3IntervalQualifier = 0;
pub const fmi3IntervalUnchanged: fmi3IntervalQualifier = 1;
pub const fmi3IntervalChanged: fmi3IntervalQualifier = 2;

/// `fmi3LogMessageCallback`: not variadic (unlike FMI 2.0's logger), `message` is the text.
pub type fmi3LogMessageCallback = Option<
    unsafe extern "C" fn(
        instanceEnvironment: fmi3InstanceEnvironment,
        status: fmi3Status,
        category: fmi3String,
        message: fmi3String,
    ),
>;
/// `fmi3ClockUpdateCallback` (Scheduled Execution).
pub type fmi3ClockUpdateCallback = Option<unsafe extern "C" fn(instanceEnvironment: fmi3InstanceEnvironment)>;
/// `fmi3IntermediateUpdateCallback` (Co-Simulation).
pub type fmi3IntermediateUpdateCallback = Option<
    unsafe extern "C" fn(
        instanceEnvironment: fmi3InstanceEnvironment,
        intermediateUpdateTime: fmi3Float64,
        intermediateVariableSetRequested: fmi3Boolean,
        intermediateVariableGetAllowed: fmi3Boolean,
        intermediateStepFinished: fmi3Boolean,
        canReturnEarly: fmi3Boolean,
        earlyReturnRequested: *mut fmi3Boolean,
        earlyReturnTime: *mut fmi3Float64,
    ),
>;
/// `fmi3LockPreemptionCallback` (Scheduled Execution).
pub type fmi3LockPreemptionCallback = Option<unsafe extern "C" fn()>;
/// `fmi3UnlockPreemptionCallback` (Scheduled Execution).
pub type fmi3UnlockPreemptionCallback = Option<unsafe extern "C" fn()>;

// ---------------------------------------------------------------------------
// fmi3FunctionTypes.h: function types (one per fmi3Functions.h entry, header order)
// ---------------------------------------------------------------------------

/// `fmi3Get…TYPE` (`values` written: `mut`) or `fmi3Set…TYPE` (`values` read: `const`) of
/// the types that hold one value per array element (all but Binary and Clock): their
/// signatures differ only in the element type, so it is spelled out once.
macro_rules! value_array_functions {
    ($access:tt; $($name:ident: $value:ty,)*) => {$(
        pub type $name = unsafe extern "C" fn(
            instance: fmi3Instance,
            valueReferences: *const fmi3ValueReference,
            nValueReferences: usize,
            values: *$access $value,
            nValues: usize,
        ) -> fmi3Status;
    )*};
}

pub type fmi3GetVersionTYPE = unsafe extern "C" fn() -> *const c_char;
pub type fmi3SetDebugLoggingTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    loggingOn: fmi3Boolean,
    nCategories: usize,
    categories: *const fmi3String,
) -> fmi3Status;
pub type fmi3InstantiateModelExchangeTYPE = unsafe extern "C" fn(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
) -> fmi3Instance;
pub type fmi3InstantiateCoSimulationTYPE = unsafe extern "C" fn(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    eventModeUsed: fmi3Boolean,
    earlyReturnAllowed: fmi3Boolean,
    requiredIntermediateVariables: *const fmi3ValueReference,
    nRequiredIntermediateVariables: usize,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    intermediateUpdate: fmi3IntermediateUpdateCallback,
) -> fmi3Instance;
pub type fmi3InstantiateScheduledExecutionTYPE = unsafe extern "C" fn(
    instanceName: fmi3String,
    instantiationToken: fmi3String,
    resourcePath: fmi3String,
    visible: fmi3Boolean,
    loggingOn: fmi3Boolean,
    instanceEnvironment: fmi3InstanceEnvironment,
    logMessage: fmi3LogMessageCallback,
    clockUpdate: fmi3ClockUpdateCallback,
    lockPreemption: fmi3LockPreemptionCallback,
    unlockPreemption: fmi3UnlockPreemptionCallback,
) -> fmi3Instance;
pub type fmi3FreeInstanceTYPE = unsafe extern "C" fn(instance: fmi3Instance);
pub type fmi3EnterInitializationModeTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    toleranceDefined: fmi3Boolean,
    tolerance: fmi3Float64,
    startTime: fmi3Float64,
    stopTimeDefined: fmi3Boolean,
    stopTime: fmi3Float64,
) -> fmi3Status;
pub type fmi3ExitInitializationModeTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3EnterEventModeTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3TerminateTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3ResetTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
value_array_functions! {
    mut;
    fmi3GetFloat32TYPE: fmi3Float32,
    fmi3GetFloat64TYPE: fmi3Float64,
    fmi3GetInt8TYPE: fmi3Int8,
    fmi3GetUInt8TYPE: fmi3UInt8,
    fmi3GetInt16TYPE: fmi3Int16,
    fmi3GetUInt16TYPE: fmi3UInt16,
    fmi3GetInt32TYPE: fmi3Int32,
    fmi3GetUInt32TYPE: fmi3UInt32,
    fmi3GetInt64TYPE: fmi3Int64,
    fmi3GetUInt64TYPE: fmi3UInt64,
    fmi3GetBooleanTYPE: fmi3Boolean,
    fmi3GetStringTYPE: fmi3String,
}
pub type fmi3GetBinaryTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    valueSizes: *mut usize,
    values: *mut fmi3Binary,
    nValues: usize,
) -> fmi3Status;
pub type fmi3GetClockTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *mut fmi3Clock,
) -> fmi3Status;
value_array_functions! {
    const;
    fmi3SetFloat32TYPE: fmi3Float32,
    fmi3SetFloat64TYPE: fmi3Float64,
    fmi3SetInt8TYPE: fmi3Int8,
    fmi3SetUInt8TYPE: fmi3UInt8,
    fmi3SetInt16TYPE: fmi3Int16,
    fmi3SetUInt16TYPE: fmi3UInt16,
    fmi3SetInt32TYPE: fmi3Int32,
    fmi3SetUInt32TYPE: fmi3UInt32,
    fmi3SetInt64TYPE: fmi3Int64,
    fmi3SetUInt64TYPE: fmi3UInt64,
    fmi3SetBooleanTYPE: fmi3Boolean,
    fmi3SetStringTYPE: fmi3String,
}
pub type fmi3SetBinaryTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    valueSizes: *const usize,
    values: *const fmi3Binary,
    nValues: usize,
) -> fmi3Status;
pub type fmi3SetClockTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    values: *const fmi3Clock,
) -> fmi3Status;
pub type fmi3GetNumberOfVariableDependenciesTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReference: fmi3ValueReference,
    nDependencies: *mut usize,
) -> fmi3Status;
pub type fmi3GetVariableDependenciesTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    dependent: fmi3ValueReference,
    elementIndicesOfDependent: *mut usize,
    independents: *mut fmi3ValueReference,
    elementIndicesOfIndependents: *mut usize,
    dependencyKinds: *mut fmi3DependencyKind,
    nDependencies: usize,
) -> fmi3Status;
pub type fmi3GetFMUStateTYPE = unsafe extern "C" fn(instance: fmi3Instance, FMUState: *mut fmi3FMUState) -> fmi3Status;
pub type fmi3SetFMUStateTYPE = unsafe extern "C" fn(instance: fmi3Instance, FMUState: fmi3FMUState) -> fmi3Status;
pub type fmi3FreeFMUStateTYPE = unsafe extern "C" fn(instance: fmi3Instance, FMUState: *mut fmi3FMUState) -> fmi3Status;
pub type fmi3SerializedFMUStateSizeTYPE =
    unsafe extern "C" fn(instance: fmi3Instance, FMUState: fmi3FMUState, size: *mut usize) -> fmi3Status;
pub type fmi3SerializeFMUStateTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    FMUState: fmi3FMUState,
    serializedState: *mut fmi3Byte,
    size: usize,
) -> fmi3Status;
pub type fmi3DeserializeFMUStateTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    serializedState: *const fmi3Byte,
    size: usize,
    FMUState: *mut fmi3FMUState,
) -> fmi3Status;
pub type fmi3GetDirectionalDerivativeTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    unknowns: *const fmi3ValueReference,
    nUnknowns: usize,
    knowns: *const fmi3ValueReference,
    nKnowns: usize,
    seed: *const fmi3Float64,
    nSeed: usize,
    sensitivity: *mut fmi3Float64,
    nSensitivity: usize,
) -> fmi3Status;
pub type fmi3GetAdjointDerivativeTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    unknowns: *const fmi3ValueReference,
    nUnknowns: usize,
    knowns: *const fmi3ValueReference,
    nKnowns: usize,
    seed: *const fmi3Float64,
    nSeed: usize,
    sensitivity: *mut fmi3Float64,
    nSensitivity: usize,
) -> fmi3Status;
pub type fmi3EnterConfigurationModeTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3ExitConfigurationModeTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3GetIntervalDecimalTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    intervals: *mut fmi3Float64,
    qualifiers: *mut fmi3IntervalQualifier,
) -> fmi3Status;
pub type fmi3GetIntervalFractionTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    counters: *mut fmi3UInt64,
    resolutions: *mut fmi3UInt64,
    qualifiers: *mut fmi3IntervalQualifier,
) -> fmi3Status;
pub type fmi3GetShiftDecimalTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    shifts: *mut fmi3Float64,
) -> fmi3Status;
pub type fmi3GetShiftFractionTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    counters: *mut fmi3UInt64,
    resolutions: *mut fmi3UInt64,
) -> fmi3Status;
pub type fmi3SetIntervalDecimalTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    intervals: *const fmi3Float64,
) -> fmi3Status;
pub type fmi3SetIntervalFractionTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    counters: *const fmi3UInt64,
    resolutions: *const fmi3UInt64,
) -> fmi3Status;
pub type fmi3SetShiftDecimalTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    shifts: *const fmi3Float64,
) -> fmi3Status;
pub type fmi3SetShiftFractionTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    counters: *const fmi3UInt64,
    resolutions: *const fmi3UInt64,
) -> fmi3Status;
pub type fmi3EvaluateDiscreteStatesTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3UpdateDiscreteStatesTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    discreteStatesNeedUpdate: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    nominalsOfContinuousStatesChanged: *mut fmi3Boolean,
    valuesOfContinuousStatesChanged: *mut fmi3Boolean,
    nextEventTimeDefined: *mut fmi3Boolean,
    nextEventTime: *mut fmi3Float64,
) -> fmi3Status;
pub type fmi3EnterContinuousTimeModeTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3CompletedIntegratorStepTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    enterEventMode: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
) -> fmi3Status;
pub type fmi3SetTimeTYPE = unsafe extern "C" fn(instance: fmi3Instance, time: fmi3Float64) -> fmi3Status;
pub type fmi3SetContinuousStatesTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    continuousStates: *const fmi3Float64,
    nContinuousStates: usize,
) -> fmi3Status;
pub type fmi3GetContinuousStateDerivativesTYPE =
    unsafe extern "C" fn(instance: fmi3Instance, derivatives: *mut fmi3Float64, nContinuousStates: usize) -> fmi3Status;
pub type fmi3GetEventIndicatorsTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    eventIndicators: *mut fmi3Float64,
    nEventIndicators: usize,
) -> fmi3Status;
pub type fmi3GetContinuousStatesTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    continuousStates: *mut fmi3Float64,
    nContinuousStates: usize,
) -> fmi3Status;
pub type fmi3GetNominalsOfContinuousStatesTYPE =
    unsafe extern "C" fn(instance: fmi3Instance, nominals: *mut fmi3Float64, nContinuousStates: usize) -> fmi3Status;
pub type fmi3GetNumberOfEventIndicatorsTYPE =
    unsafe extern "C" fn(instance: fmi3Instance, nEventIndicators: *mut usize) -> fmi3Status;
pub type fmi3GetNumberOfContinuousStatesTYPE =
    unsafe extern "C" fn(instance: fmi3Instance, nContinuousStates: *mut usize) -> fmi3Status;
pub type fmi3EnterStepModeTYPE = unsafe extern "C" fn(instance: fmi3Instance) -> fmi3Status;
pub type fmi3GetOutputDerivativesTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    valueReferences: *const fmi3ValueReference,
    nValueReferences: usize,
    orders: *const fmi3Int32,
    values: *mut fmi3Float64,
    nValues: usize,
) -> fmi3Status;
pub type fmi3DoStepTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    currentCommunicationPoint: fmi3Float64,
    communicationStepSize: fmi3Float64,
    noSetFMUStatePriorToCurrentPoint: fmi3Boolean,
    eventHandlingNeeded: *mut fmi3Boolean,
    terminateSimulation: *mut fmi3Boolean,
    earlyReturn: *mut fmi3Boolean,
    lastSuccessfulTime: *mut fmi3Float64,
) -> fmi3Status;
pub type fmi3ActivateModelPartitionTYPE = unsafe extern "C" fn(
    instance: fmi3Instance,
    clockReference: fmi3ValueReference,
    activationTime: fmi3Float64,
) -> fmi3Status;

/// Invokes `$callback! { name: nameTYPE, ... }` with every function of `fmi3Functions.h`, in
/// header order, each paired with its function type.
///
/// `$callback` is a `macro_rules!` macro in scope at the call site (given by name) or a path to
/// an exported one.
#[macro_export]
macro_rules! fmi3_functions {
    ($($callback:tt)+) => {
        $($callback)+! {
            fmi3GetVersion: fmi3GetVersionTYPE,
            fmi3SetDebugLogging: fmi3SetDebugLoggingTYPE,
            fmi3InstantiateModelExchange: fmi3InstantiateModelExchangeTYPE,
            fmi3InstantiateCoSimulation: fmi3InstantiateCoSimulationTYPE,
            fmi3InstantiateScheduledExecution: fmi3InstantiateScheduledExecutionTYPE,
            fmi3FreeInstance: fmi3FreeInstanceTYPE,
            fmi3EnterInitializationMode: fmi3EnterInitializationModeTYPE,
            fmi3ExitInitializationMode: fmi3ExitInitializationModeTYPE,
            fmi3EnterEventMode: fmi3EnterEventModeTYPE,
            fmi3Terminate: fmi3TerminateTYPE,
            fmi3Reset: fmi3ResetTYPE,
            fmi3GetFloat32: fmi3GetFloat32TYPE,
            fmi3GetFloat64: fmi3GetFloat64TYPE,
            fmi3GetInt8: fmi3GetInt8TYPE,
            fmi3GetUInt8: fmi3GetUInt8TYPE,
            fmi3GetInt16: fmi3GetInt16TYPE,
            fmi3GetUInt16: fmi3GetUInt16TYPE,
            fmi3GetInt32: fmi3GetInt32TYPE,
            fmi3GetUInt32: fmi3GetUInt32TYPE,
            fmi3GetInt64: fmi3GetInt64TYPE,
            fmi3GetUInt64: fmi3GetUInt64TYPE,
            fmi3GetBoolean: fmi3GetBooleanTYPE,
            fmi3GetString: fmi3GetStringTYPE,
            fmi3GetBinary: fmi3GetBinaryTYPE,
            fmi3GetClock: fmi3GetClockTYPE,
            fmi3SetFloat32: fmi3SetFloat32TYPE,
            fmi3SetFloat64: fmi3SetFloat64TYPE,
            fmi3SetInt8: fmi3SetInt8TYPE,
            fmi3SetUInt8: fmi3SetUInt8TYPE,
            fmi3SetInt16: fmi3SetInt16TYPE,
            fmi3SetUInt16: fmi3SetUInt16TYPE,
            fmi3SetInt32: fmi3SetInt32TYPE,
            fmi3SetUInt32: fmi3SetUInt32TYPE,
            fmi3SetInt64: fmi3SetInt64TYPE,
            fmi3SetUInt64: fmi3SetUInt64TYPE,
            fmi3SetBoolean: fmi3SetBooleanTYPE,
            fmi3SetString: fmi3SetStringTYPE,
            fmi3SetBinary: fmi3SetBinaryTYPE,
            fmi3SetClock: fmi3SetClockTYPE,
            fmi3GetNumberOfVariableDependencies: fmi3GetNumberOfVariableDependenciesTYPE,
            fmi3GetVariableDependencies: fmi3GetVariableDependenciesTYPE,
            fmi3GetFMUState: fmi3GetFMUStateTYPE,
            fmi3SetFMUState: fmi3SetFMUStateTYPE,
            fmi3FreeFMUState: fmi3FreeFMUStateTYPE,
            fmi3SerializedFMUStateSize: fmi3SerializedFMUStateSizeTYPE,
            fmi3SerializeFMUState: fmi3SerializeFMUStateTYPE,
            fmi3DeserializeFMUState: fmi3DeserializeFMUStateTYPE,
            fmi3GetDirectionalDerivative: fmi3GetDirectionalDerivativeTYPE,
            fmi3GetAdjointDerivative: fmi3GetAdjointDerivativeTYPE,
            fmi3EnterConfigurationMode: fmi3EnterConfigurationModeTYPE,
            fmi3ExitConfigurationMode: fmi3ExitConfigurationModeTYPE,
            fmi3GetIntervalDecimal: fmi3GetIntervalDecimalTYPE,
            fmi3GetIntervalFraction: fmi3GetIntervalFractionTYPE,
            fmi3GetShiftDecimal: fmi3GetShiftDecimalTYPE,
            fmi3GetShiftFraction: fmi3GetShiftFractionTYPE,
            fmi3SetIntervalDecimal: fmi3SetIntervalDecimalTYPE,
            fmi3SetIntervalFraction: fmi3SetIntervalFractionTYPE,
            fmi3SetShiftDecimal: fmi3SetShiftDecimalTYPE,
            fmi3SetShiftFraction: fmi3SetShiftFractionTYPE,
            fmi3EvaluateDiscreteStates: fmi3EvaluateDiscreteStatesTYPE,
            fmi3UpdateDiscreteStates: fmi3UpdateDiscreteStatesTYPE,
            fmi3EnterContinuousTimeMode: fmi3EnterContinuousTimeModeTYPE,
            fmi3CompletedIntegratorStep: fmi3CompletedIntegratorStepTYPE,
            fmi3SetTime: fmi3SetTimeTYPE,
            fmi3SetContinuousStates: fmi3SetContinuousStatesTYPE,
            fmi3GetContinuousStateDerivatives: fmi3GetContinuousStateDerivativesTYPE,
            fmi3GetEventIndicators: fmi3GetEventIndicatorsTYPE,
            fmi3GetContinuousStates: fmi3GetContinuousStatesTYPE,
            fmi3GetNominalsOfContinuousStates: fmi3GetNominalsOfContinuousStatesTYPE,
            fmi3GetNumberOfEventIndicators: fmi3GetNumberOfEventIndicatorsTYPE,
            fmi3GetNumberOfContinuousStates: fmi3GetNumberOfContinuousStatesTYPE,
            fmi3EnterStepMode: fmi3EnterStepModeTYPE,
            fmi3GetOutputDerivatives: fmi3GetOutputDerivativesTYPE,
            fmi3DoStep: fmi3DoStepTYPE,
            fmi3ActivateModelPartition: fmi3ActivateModelPartitionTYPE,
        }
    };
}

// Layout checks against the C definitions.
const _: () = {
    assert!(std::mem::size_of::<fmi3Boolean>() == 1);
    assert!(std::mem::size_of::<fmi3ValueReference>() == 4);
    assert!(std::mem::size_of::<fmi3LogMessageCallback>() == std::mem::size_of::<*const c_void>());
    assert!(std::mem::size_of::<fmi3IntermediateUpdateCallback>() == std::mem::size_of::<*const c_void>());
};
