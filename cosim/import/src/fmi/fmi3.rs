//! FMI 3.0 Co-Simulation FMUs behind the FMI 2.0 calling convention the rest of the importer
//! speaks: an [`Adapter`] per instance holds the FMI 3.0 instance and functions, and
//! [`functions`] is an FMI 2.0 function table whose entries are this module's `extern "C"`
//! functions, each translating one FMI 2.0 call into its FMI 3.0 counterpart on the adapter
//! behind the component pointer. So [`crate::slave::Slave`] (state tracking, errors, logs,
//! the call watch) is the same code for both versions.
//!
//! The translation, call by call (FMI 3.0.2):
//! - `fmi2Instantiate` → `fmi3InstantiateCoSimulation` (done by [`instantiate`], which has the
//!   FMI 3.0 table): no Event Mode, no early return, no intermediate update; the resource
//!   folder as a path with a trailing separator; the logger is the same log context, called
//!   through a non-variadic FMI 3.0 callback.
//! - `fmi2SetupExperiment` keeps the times; `fmi2EnterInitializationMode` passes them to
//!   `fmi3EnterInitializationMode`, which takes them.
//! - Real ↔ Float64, Integer ↔ Int32, Boolean ↔ Boolean (C `bool`, converted element-wise),
//!   String ↔ String, with `nValues = nValueReferences` (scalars only: arrays are refused when
//!   the description is read).
//! - `fmi2DoStep` → `fmi3DoStep`. A step that returns OK but asks to end the simulation
//!   (`terminateSimulation`), returns early (`earlyReturn`) or needs event handling
//!   (`eventHandlingNeeded`, which an FMU without Event Mode must not set) becomes
//!   `fmi2Discard` with a log message saying which; `fmi2GetBooleanStatus(fmi2Terminated)` and
//!   `fmi2GetRealStatus(fmi2LastSuccessfulTime)` then answer from what `fmi3DoStep` reported, so
//!   a run ends cleanly and says why, as for an FMI 2.0 discard. A step that returns
//!   `fmi3Discard` (or worse) stays what it is, and its output arguments, which FMI 3.0 leaves
//!   undefined then, are not read: no request to end the simulation, nothing completed after the
//!   step's start.
//! - `fmi2SetRealInputDerivatives`: FMI 3.0 has none; refused (the description says
//!   `canInterpolateInputs = false`, so the engine never calls it).
//! - FMU states: the same six functions under FMI 3.0 names (optional: resolved if exported).

use std::ffi::{c_char, c_int, c_void, CString};
use std::path::Path;

use std::collections::BTreeMap;

use super::ffi;
use super::library::{Functions, LibraryError};
use elements::{Elements, Failure};
pub use elements::{Fmi3Element, Fmi3Type, Start};
use fmi3_sys as f3;

#[path = "fmi3_elements.rs"]
mod elements;

/// The FMI 3.0 functions the adapter calls. Required ones are plain pointers; the FMU-state
/// functions are optional (an FMU that cannot save its state need not export them).
#[allow(non_snake_case)]
#[derive(Clone, Copy)]
pub struct Functions3 {
    pub fmi3InstantiateCoSimulation: f3::fmi3InstantiateCoSimulationTYPE,
    pub fmi3FreeInstance: f3::fmi3FreeInstanceTYPE,
    pub fmi3SetDebugLogging: f3::fmi3SetDebugLoggingTYPE,
    pub fmi3EnterInitializationMode: f3::fmi3EnterInitializationModeTYPE,
    pub fmi3ExitInitializationMode: f3::fmi3ExitInitializationModeTYPE,
    pub fmi3Terminate: f3::fmi3TerminateTYPE,
    pub fmi3Reset: f3::fmi3ResetTYPE,
    pub fmi3GetFloat64: f3::fmi3GetFloat64TYPE,
    pub fmi3GetInt32: f3::fmi3GetInt32TYPE,
    pub fmi3GetBoolean: f3::fmi3GetBooleanTYPE,
    pub fmi3GetString: f3::fmi3GetStringTYPE,
    pub fmi3SetFloat64: f3::fmi3SetFloat64TYPE,
    pub fmi3SetInt32: f3::fmi3SetInt32TYPE,
    pub fmi3SetBoolean: f3::fmi3SetBooleanTYPE,
    pub fmi3SetString: f3::fmi3SetStringTYPE,
    pub fmi3DoStep: f3::fmi3DoStepTYPE,
    pub fmi3GetFloat32: Option<f3::fmi3GetFloat32TYPE>,
    pub fmi3GetInt8: Option<f3::fmi3GetInt8TYPE>,
    pub fmi3GetUInt8: Option<f3::fmi3GetUInt8TYPE>,
    pub fmi3GetInt16: Option<f3::fmi3GetInt16TYPE>,
    pub fmi3GetUInt16: Option<f3::fmi3GetUInt16TYPE>,
    pub fmi3GetUInt32: Option<f3::fmi3GetUInt32TYPE>,
    pub fmi3GetInt64: Option<f3::fmi3GetInt64TYPE>,
    pub fmi3GetUInt64: Option<f3::fmi3GetUInt64TYPE>,
    pub fmi3SetFloat32: Option<f3::fmi3SetFloat32TYPE>,
    pub fmi3SetInt8: Option<f3::fmi3SetInt8TYPE>,
    pub fmi3SetUInt8: Option<f3::fmi3SetUInt8TYPE>,
    pub fmi3SetInt16: Option<f3::fmi3SetInt16TYPE>,
    pub fmi3SetUInt16: Option<f3::fmi3SetUInt16TYPE>,
    pub fmi3SetUInt32: Option<f3::fmi3SetUInt32TYPE>,
    pub fmi3SetInt64: Option<f3::fmi3SetInt64TYPE>,
    pub fmi3SetUInt64: Option<f3::fmi3SetUInt64TYPE>,
    pub fmi3GetFMUState: Option<f3::fmi3GetFMUStateTYPE>,
    pub fmi3SetFMUState: Option<f3::fmi3SetFMUStateTYPE>,
    pub fmi3FreeFMUState: Option<f3::fmi3FreeFMUStateTYPE>,
    pub fmi3SerializedFMUStateSize: Option<f3::fmi3SerializedFMUStateSizeTYPE>,
    pub fmi3SerializeFMUState: Option<f3::fmi3SerializeFMUStateTYPE>,
    pub fmi3DeserializeFMUState: Option<f3::fmi3DeserializeFMUStateTYPE>,
}

macro_rules! resolve {
    ($library:ident, $missing:ident; required: $($required:ident),*; optional: $($optional:ident),*) => {{
        $(
            // SAFETY: the symbol is declared with this exact type in fmi3Functions.h.
            let $required = unsafe { $library.get::<paste_type!($required)>(concat!(stringify!($required), "\0").as_bytes()) }
                .map(|symbol| *symbol)
                .ok();
            if $required.is_none() {
                $missing.push(stringify!($required));
            }
        )*
        $(
            // SAFETY: as above.
            let $optional = unsafe { $library.get::<paste_type!($optional)>(concat!(stringify!($optional), "\0").as_bytes()) }
                .map(|symbol| *symbol)
                .ok();
        )*
        (|| Some(Functions3 { $($required: $required?,)* $($optional,)* }))()
    }};
}

/// The `fmi3…TYPE` of a function name.
macro_rules! paste_type {
    (fmi3InstantiateCoSimulation) => {
        f3::fmi3InstantiateCoSimulationTYPE
    };
    (fmi3FreeInstance) => {
        f3::fmi3FreeInstanceTYPE
    };
    (fmi3SetDebugLogging) => {
        f3::fmi3SetDebugLoggingTYPE
    };
    (fmi3EnterInitializationMode) => {
        f3::fmi3EnterInitializationModeTYPE
    };
    (fmi3ExitInitializationMode) => {
        f3::fmi3ExitInitializationModeTYPE
    };
    (fmi3Terminate) => {
        f3::fmi3TerminateTYPE
    };
    (fmi3Reset) => {
        f3::fmi3ResetTYPE
    };
    (fmi3GetFloat64) => {
        f3::fmi3GetFloat64TYPE
    };
    (fmi3GetInt32) => {
        f3::fmi3GetInt32TYPE
    };
    (fmi3GetBoolean) => {
        f3::fmi3GetBooleanTYPE
    };
    (fmi3GetString) => {
        f3::fmi3GetStringTYPE
    };
    (fmi3SetFloat64) => {
        f3::fmi3SetFloat64TYPE
    };
    (fmi3SetInt32) => {
        f3::fmi3SetInt32TYPE
    };
    (fmi3SetBoolean) => {
        f3::fmi3SetBooleanTYPE
    };
    (fmi3SetString) => {
        f3::fmi3SetStringTYPE
    };
    (fmi3DoStep) => {
        f3::fmi3DoStepTYPE
    };
    (fmi3GetFloat32) => {
        f3::fmi3GetFloat32TYPE
    };
    (fmi3GetInt8) => {
        f3::fmi3GetInt8TYPE
    };
    (fmi3GetUInt8) => {
        f3::fmi3GetUInt8TYPE
    };
    (fmi3GetInt16) => {
        f3::fmi3GetInt16TYPE
    };
    (fmi3GetUInt16) => {
        f3::fmi3GetUInt16TYPE
    };
    (fmi3GetUInt32) => {
        f3::fmi3GetUInt32TYPE
    };
    (fmi3GetInt64) => {
        f3::fmi3GetInt64TYPE
    };
    (fmi3GetUInt64) => {
        f3::fmi3GetUInt64TYPE
    };
    (fmi3SetFloat32) => {
        f3::fmi3SetFloat32TYPE
    };
    (fmi3SetInt8) => {
        f3::fmi3SetInt8TYPE
    };
    (fmi3SetUInt8) => {
        f3::fmi3SetUInt8TYPE
    };
    (fmi3SetInt16) => {
        f3::fmi3SetInt16TYPE
    };
    (fmi3SetUInt16) => {
        f3::fmi3SetUInt16TYPE
    };
    (fmi3SetUInt32) => {
        f3::fmi3SetUInt32TYPE
    };
    (fmi3SetInt64) => {
        f3::fmi3SetInt64TYPE
    };
    (fmi3SetUInt64) => {
        f3::fmi3SetUInt64TYPE
    };
    (fmi3GetFMUState) => {
        f3::fmi3GetFMUStateTYPE
    };
    (fmi3SetFMUState) => {
        f3::fmi3SetFMUStateTYPE
    };
    (fmi3FreeFMUState) => {
        f3::fmi3FreeFMUStateTYPE
    };
    (fmi3SerializedFMUStateSize) => {
        f3::fmi3SerializedFMUStateSizeTYPE
    };
    (fmi3SerializeFMUState) => {
        f3::fmi3SerializeFMUStateTYPE
    };
    (fmi3DeserializeFMUState) => {
        f3::fmi3DeserializeFMUStateTYPE
    };
}

impl Functions3 {
    /// Resolves the functions from `library`; reports every missing required one at once.
    #[allow(non_snake_case)]
    pub(super) fn resolve(library: &libloading::Library, path: &Path) -> Result<Self, LibraryError> {
        let mut missing: Vec<&'static str> = Vec::new();
        let resolved = resolve!(library, missing;
            required: fmi3InstantiateCoSimulation, fmi3FreeInstance, fmi3SetDebugLogging,
                fmi3EnterInitializationMode, fmi3ExitInitializationMode, fmi3Terminate, fmi3Reset,
                fmi3GetFloat64, fmi3GetInt32, fmi3GetBoolean, fmi3GetString, fmi3SetFloat64, fmi3SetInt32,
                fmi3SetBoolean, fmi3SetString, fmi3DoStep;
            optional: fmi3GetFloat32, fmi3GetInt8, fmi3GetUInt8, fmi3GetInt16, fmi3GetUInt16, fmi3GetUInt32, fmi3GetInt64, fmi3GetUInt64, fmi3SetFloat32, fmi3SetInt8, fmi3SetUInt8, fmi3SetInt16, fmi3SetUInt16, fmi3SetUInt32, fmi3SetInt64, fmi3SetUInt64, fmi3GetFMUState, fmi3SetFMUState, fmi3FreeFMUState, fmi3SerializedFMUStateSize,
                fmi3SerializeFMUState, fmi3DeserializeFMUState);
        resolved.ok_or_else(|| LibraryError::MissingSymbols { path: path.to_path_buf(), symbols: missing })
    }
}

/// One FMI 3.0 instance as the FMI 2.0 functions of [`functions`] see it: the pointer they get
/// as `fmi2Component` is a `Box<Adapter>`.
struct Adapter {
    instance: f3::fmi3Instance,
    functions: Functions3,
    /// The log context, for the messages the adapter itself reports.
    log: *mut c_void,
    tolerance: Option<f64>,
    start: f64,
    stop: Option<f64>,
    /// What the last `fmi3DoStep` reported.
    terminate_requested: bool,
    last_successful_time: f64,
    /// The rows reached through a conversion or as array elements.
    elements: Elements,
}

/// `fmi2Instantiate` for an FMI 3.0 FMU: `fmi3InstantiateCoSimulation` with the importer's log
/// context as instance environment; the component is the adapter (NULL if the FMU refused).
///
/// # Safety
/// The strings are valid and NUL-terminated; `callbacks.componentEnvironment` is a live log
/// context that outlives the instance (as for `fmi2Instantiate`).
#[allow(clippy::too_many_arguments)] // fmi3InstantiateCoSimulation's own arguments, and the elements
pub unsafe fn instantiate(
    functions: &Functions3,
    name: &CString,
    token: &CString,
    resource_dir: &Path,
    callbacks: &ffi::fmi2CallbackFunctions,
    visible: bool,
    logging_on: bool,
    elements: &[Fmi3Element],
) -> ffi::fmi2Component {
    let mut folder = resource_dir.to_string_lossy().into_owned();
    if !folder.ends_with(std::path::MAIN_SEPARATOR) {
        folder.push(std::path::MAIN_SEPARATOR);
    }
    let Ok(folder) = CString::new(folder) else { return std::ptr::null_mut() };
    // SAFETY: valid strings and a live environment (this function's contract); no intermediate
    // variables are requested (NULL, 0), and the log callback matches fmi3LogMessageCallback.
    let instance = unsafe {
        (functions.fmi3InstantiateCoSimulation)(
            name.as_ptr(),
            token.as_ptr(),
            folder.as_ptr(),
            visible,
            logging_on,
            false,
            false,
            std::ptr::null(),
            0,
            callbacks.componentEnvironment,
            Some(log_message),
            None,
        )
    };
    if instance.is_null() {
        return std::ptr::null_mut();
    }
    let adapter = Adapter {
        instance,
        functions: *functions,
        log: callbacks.componentEnvironment,
        tolerance: None,
        start: 0.0,
        stop: None,
        terminate_requested: false,
        last_successful_time: 0.0,
        elements: Elements::new(elements),
    };
    Box::into_raw(Box::new(adapter)) as ffi::fmi2Component
}

/// The FMI 3.0 logger: the log context's sink, with no instance name (FMI 3.0 passes none).
unsafe extern "C" fn log_message(
    environment: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    super::logger::sink(environment, c"".as_ptr(), status, category, message);
}

/// The adapter behind a component.
///
/// # Safety
/// `c` is a component [`instantiate`] returned and not yet freed, used by one call at a time.
unsafe fn adapter<'a>(c: ffi::fmi2Component) -> &'a mut Adapter {
    // SAFETY: this function's contract.
    unsafe { &mut *(c as *mut Adapter) }
}

/// Reports a message of the adapter itself to the instance's log.
fn report(adapter: &Adapter, status: c_int, message: &str) {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    super::logger::sink(adapter.log, c"".as_ptr(), status, c"importer".as_ptr(), text.as_ptr());
}

unsafe extern "C" fn free_instance(c: ffi::fmi2Component) {
    // SAFETY: the Slave frees each component once, after its last call.
    let adapter = unsafe { Box::from_raw(c as *mut Adapter) };
    // SAFETY: the live FMI 3.0 instance, freed once.
    unsafe { (adapter.functions.fmi3FreeInstance)(adapter.instance) };
}

unsafe extern "C" fn setup_experiment(
    c: ffi::fmi2Component,
    tolerance_defined: ffi::fmi2Boolean,
    tolerance: f64,
    start: f64,
    stop_defined: ffi::fmi2Boolean,
    stop: f64,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter (the Slave's contract).
    let a = unsafe { adapter(c) };
    a.tolerance = (tolerance_defined != 0).then_some(tolerance);
    a.start = start;
    a.stop = (stop_defined != 0).then_some(stop);
    ffi::fmi2OK
}

unsafe extern "C" fn enter_initialization_mode(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    // SAFETY: the live instance; plain values.
    unsafe {
        (a.functions.fmi3EnterInitializationMode)(
            a.instance,
            a.tolerance.is_some(),
            a.tolerance.unwrap_or(0.0),
            a.start,
            a.stop.is_some(),
            a.stop.unwrap_or(0.0),
        )
    }
}

unsafe extern "C" fn exit_initialization_mode(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter and its instance.
    unsafe { (adapter(c).functions.fmi3ExitInitializationMode)(adapter(c).instance) }
}

unsafe extern "C" fn terminate(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter and its instance.
    unsafe { (adapter(c).functions.fmi3Terminate)(adapter(c).instance) }
}

unsafe extern "C" fn reset(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter and its instance.
    unsafe { (adapter(c).functions.fmi3Reset)(adapter(c).instance) }
}

unsafe extern "C" fn set_debug_logging(
    c: ffi::fmi2Component,
    on: ffi::fmi2Boolean,
    n: usize,
    categories: *const ffi::fmi2String,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter; the categories as the Slave passed them.
    unsafe { (adapter(c).functions.fmi3SetDebugLogging)(adapter(c).instance, on != 0, n, categories) }
}

unsafe extern "C" fn get_real(c: ffi::fmi2Component, vr: *const u32, n: usize, v: *mut f64) -> ffi::fmi2Status {
    // SAFETY: a live adapter; `n` elements in each array (the Slave checked the lengths).
    let (a, vrs, out) = unsafe { (adapter(c), slice(vr, n), slice_mut(v, n)) };
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3GetFloat64)(a.instance, vr, n, v, n) };
    }
    let mut arrays = BTreeMap::new();
    let values = vrs.iter().map(|vr| match a.elements.get(*vr) {
        None => a.direct_float(*vr),
        Some(e) => {
            cached(&mut arrays, e, || elements::read_floats(&a.functions, a.instance, e)).map(|all| all[e.index])
        }
    });
    a.collect(values, out, |x| x)
}

unsafe extern "C" fn get_integer(c: ffi::fmi2Component, vr: *const u32, n: usize, v: *mut i32) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, out) = unsafe { (adapter(c), slice(vr, n), slice_mut(v, n)) };
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3GetInt32)(a.instance, vr, n, v, n) };
    }
    let mut arrays = BTreeMap::new();
    let values = vrs.iter().map(|vr| match a.elements.get(*vr) {
        None => a.direct_int(*vr),
        Some(e) => cached(&mut arrays, e, || elements::read_ints(&a.functions, a.instance, e))
            .and_then(|all| elements::int_element(e, &all)),
    });
    a.collect(values, out, |x| x)
}

unsafe extern "C" fn get_boolean(c: ffi::fmi2Component, vr: *const u32, n: usize, v: *mut c_int) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, out) = unsafe { (adapter(c), slice(vr, n), slice_mut(v, n)) };
    if !a.elements.touches(vrs) {
        let mut values = vec![0u8; n];
        // SAFETY: as above; the FMU writes `n` C bools (one byte each) into `values`.
        let status = unsafe { (a.functions.fmi3GetBoolean)(a.instance, vr, n, values.as_mut_ptr().cast(), n) };
        for (o, b) in out.iter_mut().zip(values) {
            *o = c_int::from(b != 0);
        }
        return status;
    }
    let mut arrays = BTreeMap::new();
    let values = vrs.iter().map(|vr| match a.elements.get(*vr) {
        None => a.direct_bool(*vr),
        Some(e) => cached(&mut arrays, e, || elements::read_bools(&a.functions, a.instance, e)).map(|all| all[e.index]),
    });
    a.collect(values, out, c_int::from)
}

unsafe extern "C" fn get_string(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *mut ffi::fmi2String,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    unsafe { (adapter(c).functions.fmi3GetString)(adapter(c).instance, vr, n, v, n) }
}

unsafe extern "C" fn set_real(c: ffi::fmi2Component, vr: *const u32, n: usize, v: *const f64) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, values) = unsafe { (adapter(c), slice(vr, n), slice(v, n)) };
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3SetFloat64)(a.instance, vr, n, v, n) };
    }
    a.set_each(
        vrs,
        values,
        |a, vr, value| {
            // SAFETY: the live instance; one value.
            elements::status(unsafe { (a.functions.fmi3SetFloat64)(a.instance, &vr, 1, &value, 1) })
        },
        Elements::set_float,
    )
}

unsafe extern "C" fn set_integer(c: ffi::fmi2Component, vr: *const u32, n: usize, v: *const i32) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, values) = unsafe { (adapter(c), slice(vr, n), slice(v, n)) };
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3SetInt32)(a.instance, vr, n, v, n) };
    }
    a.set_each(
        vrs,
        values,
        |a, vr, value| {
            // SAFETY: the live instance; one value.
            elements::status(unsafe { (a.functions.fmi3SetInt32)(a.instance, &vr, 1, &value, 1) })
        },
        Elements::set_int,
    )
}

unsafe extern "C" fn set_boolean(c: ffi::fmi2Component, vr: *const u32, n: usize, v: *const c_int) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    let (a, vrs, raw) = unsafe { (adapter(c), slice(vr, n), slice(v, n)) };
    let values: Vec<bool> = raw.iter().map(|b| *b != 0).collect();
    if !a.elements.touches(vrs) {
        // SAFETY: as above.
        return unsafe { (a.functions.fmi3SetBoolean)(a.instance, vr, n, values.as_ptr(), n) };
    }
    a.set_each(
        vrs,
        &values,
        |a, vr, value| {
            // SAFETY: the live instance; one value.
            elements::status(unsafe { (a.functions.fmi3SetBoolean)(a.instance, &vr, 1, &value, 1) })
        },
        Elements::set_bool,
    )
}

/// The values of the array behind `e`, read once per call (`read`) however many of its elements
/// the call asks for.
fn cached<T: Clone>(
    arrays: &mut BTreeMap<u32, Vec<T>>,
    e: &Fmi3Element,
    read: impl FnOnce() -> Result<Vec<T>, Failure>,
) -> Result<Vec<T>, Failure> {
    if let Some(values) = arrays.get(&e.fmi3_value_reference) {
        return Ok(values.clone());
    }
    let values = read()?;
    arrays.insert(e.fmi3_value_reference, values.clone());
    Ok(values)
}

/// `n` elements at `ptr` (none for a NULL pointer, which the Slave never passes with n > 0).
///
/// # Safety
/// A non-null `ptr` has `n` readable elements for `'a`.
unsafe fn slice<'a, T>(ptr: *const T, n: usize) -> &'a [T] {
    if ptr.is_null() || n == 0 {
        &[]
    } else {
        // SAFETY: this function's contract.
        unsafe { std::slice::from_raw_parts(ptr, n) }
    }
}

/// As [`slice`], writable.
///
/// # Safety
/// A non-null `ptr` has `n` writable elements for `'a`, referenced by nothing else.
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize) -> &'a mut [T] {
    if ptr.is_null() || n == 0 {
        &mut []
    } else {
        // SAFETY: this function's contract.
        unsafe { std::slice::from_raw_parts_mut(ptr, n) }
    }
}

impl Adapter {
    /// A failed element access as a status: the FMU's, or `fmi2Error` with the refusal logged.
    fn fail(&self, failure: Failure) -> ffi::fmi2Status {
        match failure {
            Failure::Status(status) => status,
            Failure::Refused(message) => {
                report(self, ffi::fmi2Error, &message);
                ffi::fmi2Error
            }
        }
    }

    /// Writes `values` (converted by `to_c`) into `out`, or the first failure's status.
    fn collect<T, C>(
        &self,
        values: impl Iterator<Item = Result<T, Failure>>,
        out: &mut [C],
        to_c: impl Fn(T) -> C,
    ) -> ffi::fmi2Status {
        for (slot, value) in out.iter_mut().zip(values) {
            match value {
                Ok(value) => *slot = to_c(value),
                Err(failure) => return self.fail(failure),
            }
        }
        ffi::fmi2OK
    }

    /// Sets each value: `direct` for a direct row, `element` for a converted one or an element.
    fn set_each<T: Copy>(
        &mut self,
        vrs: &[u32],
        values: &[T],
        direct: impl Fn(&Adapter, u32, T) -> Result<(), Failure>,
        element: fn(&mut Elements, &Functions3, f3::fmi3Instance, &Fmi3Element, T) -> Result<(), Failure>,
    ) -> ffi::fmi2Status {
        for (vr, value) in vrs.iter().zip(values) {
            let result = match self.elements.get(*vr).cloned() {
                None => direct(self, *vr, *value),
                Some(e) => element(&mut self.elements, &self.functions, self.instance, &e, *value),
            };
            if let Err(failure) = result {
                return self.fail(failure);
            }
        }
        ffi::fmi2OK
    }

    fn direct_float(&self, vr: u32) -> Result<f64, Failure> {
        let mut value = 0.0;
        // SAFETY: the live instance; one writable value.
        elements::status(unsafe { (self.functions.fmi3GetFloat64)(self.instance, &vr, 1, &mut value, 1) })?;
        Ok(value)
    }

    fn direct_int(&self, vr: u32) -> Result<i32, Failure> {
        let mut value = 0;
        // SAFETY: as above.
        elements::status(unsafe { (self.functions.fmi3GetInt32)(self.instance, &vr, 1, &mut value, 1) })?;
        Ok(value)
    }

    fn direct_bool(&self, vr: u32) -> Result<bool, Failure> {
        let mut byte = 0u8;
        // SAFETY: as above; one C bool (a byte).
        elements::status(unsafe {
            (self.functions.fmi3GetBoolean)(self.instance, &vr, 1, (&mut byte as *mut u8).cast(), 1)
        })?;
        Ok(byte != 0)
    }
}

unsafe extern "C" fn set_string(
    c: ffi::fmi2Component,
    vr: *const u32,
    n: usize,
    v: *const ffi::fmi2String,
) -> ffi::fmi2Status {
    // SAFETY: as for `get_real`.
    unsafe { (adapter(c).functions.fmi3SetString)(adapter(c).instance, vr, n, v, n) }
}

unsafe extern "C" fn do_step(c: ffi::fmi2Component, t: f64, h: f64, no_set_prior: ffi::fmi2Boolean) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    let (mut event, mut terminate, mut early, mut last) = (false, false, false, t);
    // SAFETY: the live instance; four writable locals.
    let status = unsafe {
        (a.functions.fmi3DoStep)(a.instance, t, h, no_set_prior != 0, &mut event, &mut terminate, &mut early, &mut last)
    };
    if status > ffi::fmi2Warning {
        // FMI 3.0 leaves the output arguments undefined unless fmi3DoStep returns fmi3OK or
        // fmi3Warning: a discarded step is no request to end the simulation, whatever the FMU
        // wrote there, and it completed nothing after t.
        a.terminate_requested = false;
        a.last_successful_time = t;
        if terminate {
            let returned = match status {
                f3::fmi3Discard => "fmi3Discard".to_string(),
                f3::fmi3Error => "fmi3Error".to_string(),
                f3::fmi3Fatal => "fmi3Fatal".to_string(),
                other => format!("the invalid status {other}"),
            };
            let why = "FMI 3.0 leaves the output arguments undefined then, so the request to end the simulation is \
                       not taken";
            report(a, status, &format!("fmi3DoStep returned {returned} with terminateSimulation set; {why} (t = {t})"));
        }
        return status;
    }
    a.terminate_requested = terminate;
    a.last_successful_time = if early { last } else { t + h };
    if !(event || terminate || early) {
        return status;
    }
    let why = if terminate {
        "fmi3DoStep set terminateSimulation: the FMU asks to end the simulation"
    } else if early {
        "fmi3DoStep returned early (earlyReturn), which this importer did not allow"
    } else {
        "fmi3DoStep set eventHandlingNeeded, but the instance was created without Event Mode"
    };
    report(a, ffi::fmi2Warning, &format!("{why} (t = {t}, lastSuccessfulTime = {last})"));
    ffi::fmi2Discard
}

unsafe extern "C" fn get_real_status(c: ffi::fmi2Component, kind: c_int, v: *mut f64) -> ffi::fmi2Status {
    if kind != ffi::fmi2LastSuccessfulTime {
        return ffi::fmi2Discard;
    }
    // SAFETY: a live adapter; the Slave's writable slot.
    unsafe { *v = adapter(c).last_successful_time };
    ffi::fmi2OK
}

unsafe extern "C" fn get_boolean_status(c: ffi::fmi2Component, kind: c_int, v: *mut c_int) -> ffi::fmi2Status {
    if kind != ffi::fmi2Terminated {
        return ffi::fmi2Discard;
    }
    // SAFETY: a live adapter; the Slave's writable slot.
    unsafe { *v = c_int::from(adapter(c).terminate_requested) };
    ffi::fmi2OK
}

/// An FMU-state function the FMU does not export: an error with a message.
fn missing(a: &Adapter, function: &str) -> ffi::fmi2Status {
    report(a, ffi::fmi2Error, &format!("the FMU does not export {function}"));
    ffi::fmi2Error
}

unsafe extern "C" fn get_fmu_state(c: ffi::fmi2Component, s: *mut *mut c_void) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3GetFMUState {
        // SAFETY: the live instance; the Slave's slot.
        Some(f) => unsafe { f(a.instance, s) },
        None => missing(a, "fmi3GetFMUState"),
    }
}

unsafe extern "C" fn set_fmu_state(c: ffi::fmi2Component, s: *mut c_void) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3SetFMUState {
        // SAFETY: the live instance; a state of it.
        Some(f) => unsafe { f(a.instance, s) },
        None => missing(a, "fmi3SetFMUState"),
    }
}

unsafe extern "C" fn free_fmu_state(c: ffi::fmi2Component, s: *mut *mut c_void) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3FreeFMUState {
        // SAFETY: the live instance; the Slave's slot.
        Some(f) => unsafe { f(a.instance, s) },
        None => missing(a, "fmi3FreeFMUState"),
    }
}

unsafe extern "C" fn serialized_fmu_state_size(
    c: ffi::fmi2Component,
    s: *mut c_void,
    size: *mut usize,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3SerializedFMUStateSize {
        // SAFETY: the live instance; a state of it; the Slave's slot.
        Some(f) => unsafe { f(a.instance, s, size) },
        None => missing(a, "fmi3SerializedFMUStateSize"),
    }
}

unsafe extern "C" fn serialize_fmu_state(
    c: ffi::fmi2Component,
    s: *mut c_void,
    bytes: *mut c_char,
    size: usize,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3SerializeFMUState {
        // SAFETY: the live instance; the Slave's buffer of `size` bytes (c_char and u8 alike).
        Some(f) => unsafe { f(a.instance, s, bytes.cast(), size) },
        None => missing(a, "fmi3SerializeFMUState"),
    }
}

unsafe extern "C" fn deserialize_fmu_state(
    c: ffi::fmi2Component,
    bytes: *const c_char,
    size: usize,
    s: *mut *mut c_void,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3DeserializeFMUState {
        // SAFETY: the live instance; the Slave's `size` bytes and slot.
        Some(f) => unsafe { f(a.instance, bytes.cast(), size, s) },
        None => missing(a, "fmi3DeserializeFMUState"),
    }
}

unsafe extern "C" fn types_platform() -> *const c_char {
    c"default".as_ptr()
}

unsafe extern "C" fn version() -> *const c_char {
    c"3.0".as_ptr()
}

/// Calls FMI 3.0 has no counterpart of (`fmi2Instantiate`, done by [`instantiate`]; input and
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
/// (see the module documentation); `fmi2Instantiate` returns NULL: use [`instantiate`].
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fmi::{LogContext, LogEcho};
    use std::cell::Cell;

    /// What the fake `fmi3DoStep` returns: its status and its output arguments
    /// (eventHandlingNeeded, terminateSimulation, earlyReturn, lastSuccessfulTime).
    #[derive(Clone, Copy)]
    struct Step {
        status: f3::fmi3Status,
        event: bool,
        terminate: bool,
        early: bool,
        last: f64,
    }

    thread_local! {
        static STEP: Cell<Step> =
            const { Cell::new(Step { status: f3::fmi3OK, event: false, terminate: false, early: false, last: 0.0 }) };
    }

    unsafe extern "C" fn fake_do_step(
        _instance: f3::fmi3Instance,
        _t: f64,
        _h: f64,
        _no_set_prior: bool,
        event: *mut bool,
        terminate: *mut bool,
        early: *mut bool,
        last: *mut f64,
    ) -> f3::fmi3Status {
        let step = STEP.get();
        // SAFETY: the adapter passes four writable locals.
        unsafe { (*event, *terminate, *early, *last) = (step.event, step.terminate, step.early, step.last) };
        step.status
    }

    unsafe extern "C" fn never_instantiated(
        _name: f3::fmi3String,
        _token: f3::fmi3String,
        _resources: f3::fmi3String,
        _visible: bool,
        _logging_on: bool,
        _event_mode: bool,
        _early_return: bool,
        _required: *const f3::fmi3ValueReference,
        _n_required: usize,
        _environment: f3::fmi3InstanceEnvironment,
        _log: f3::fmi3LogMessageCallback,
        _intermediate: f3::fmi3IntermediateUpdateCallback,
    ) -> f3::fmi3Instance {
        std::ptr::null_mut()
    }
    unsafe extern "C" fn unused_free(_instance: f3::fmi3Instance) {}
    unsafe extern "C" fn unused_logging(
        _instance: f3::fmi3Instance,
        _on: bool,
        _n: usize,
        _categories: *const f3::fmi3String,
    ) -> f3::fmi3Status {
        f3::fmi3Error
    }
    unsafe extern "C" fn unused_enter(
        _instance: f3::fmi3Instance,
        _tolerance_defined: bool,
        _tolerance: f64,
        _start: f64,
        _stop_defined: bool,
        _stop: f64,
    ) -> f3::fmi3Status {
        f3::fmi3Error
    }
    unsafe extern "C" fn unused_call(_instance: f3::fmi3Instance) -> f3::fmi3Status {
        f3::fmi3Error
    }
    macro_rules! unused_values {
        ($get:ident, $set:ident, $type:ty) => {
            unsafe extern "C" fn $get(
                _i: f3::fmi3Instance,
                _vr: *const u32,
                _n: usize,
                _v: *mut $type,
                _nv: usize,
            ) -> f3::fmi3Status {
                f3::fmi3Error
            }
            unsafe extern "C" fn $set(
                _i: f3::fmi3Instance,
                _vr: *const u32,
                _n: usize,
                _v: *const $type,
                _nv: usize,
            ) -> f3::fmi3Status {
                f3::fmi3Error
            }
        };
    }
    unused_values!(unused_get_f64, unused_set_f64, f64);
    unused_values!(unused_get_i32, unused_set_i32, i32);
    unused_values!(unused_get_bool, unused_set_bool, bool);
    unused_values!(unused_get_string, unused_set_string, f3::fmi3String);

    /// An adapter onto the fake FMU (only `fmi3DoStep` answers), logging into `log`.
    fn adapter_on(log: &LogContext) -> Box<Adapter> {
        let functions = Functions3 {
            fmi3InstantiateCoSimulation: never_instantiated,
            fmi3FreeInstance: unused_free,
            fmi3SetDebugLogging: unused_logging,
            fmi3EnterInitializationMode: unused_enter,
            fmi3ExitInitializationMode: unused_call,
            fmi3Terminate: unused_call,
            fmi3Reset: unused_call,
            fmi3GetFloat64: unused_get_f64,
            fmi3GetInt32: unused_get_i32,
            fmi3GetBoolean: unused_get_bool,
            fmi3GetString: unused_get_string,
            fmi3SetFloat64: unused_set_f64,
            fmi3SetInt32: unused_set_i32,
            fmi3SetBoolean: unused_set_bool,
            fmi3SetString: unused_set_string,
            fmi3DoStep: fake_do_step,
            fmi3GetFloat32: None,
            fmi3GetInt8: None,
            fmi3GetUInt8: None,
            fmi3GetInt16: None,
            fmi3GetUInt16: None,
            fmi3GetUInt32: None,
            fmi3GetInt64: None,
            fmi3GetUInt64: None,
            fmi3SetFloat32: None,
            fmi3SetInt8: None,
            fmi3SetUInt8: None,
            fmi3SetInt16: None,
            fmi3SetUInt16: None,
            fmi3SetUInt32: None,
            fmi3SetInt64: None,
            fmi3SetUInt64: None,
            fmi3GetFMUState: None,
            fmi3SetFMUState: None,
            fmi3FreeFMUState: None,
            fmi3SerializedFMUStateSize: None,
            fmi3SerializeFMUState: None,
            fmi3DeserializeFMUState: None,
        };
        Box::new(Adapter {
            instance: std::ptr::null_mut(),
            functions,
            log: log.callbacks().componentEnvironment,
            tolerance: None,
            start: 0.0,
            stop: None,
            terminate_requested: false,
            last_successful_time: 0.0,
            elements: Elements::new(&[]),
        })
    }

    /// `fmi2DoStep` from t = 2.4 by 0.2 on the adapter when `fmi3DoStep` answers `step`: the
    /// FMI 2.0 status, `fmi2Terminated` and `fmi2LastSuccessfulTime`, and what was logged.
    fn step_with(step: Step) -> (ffi::fmi2Status, bool, f64, Vec<String>) {
        STEP.set(step);
        let log = LogContext::new("x", LogEcho::Off);
        let mut adapter = adapter_on(&log);
        let c = &mut *adapter as *mut Adapter as ffi::fmi2Component;
        let (mut terminated, mut last) = (-1, f64::NAN);
        // SAFETY: `c` is a live adapter, used by one call at a time.
        let status = unsafe { do_step(c, 2.4, 0.2, 1) };
        // SAFETY: as above; two writable slots.
        let statuses = unsafe {
            (
                get_boolean_status(c, ffi::fmi2Terminated, &mut terminated),
                get_real_status(c, ffi::fmi2LastSuccessfulTime, &mut last),
            )
        };
        assert_eq!(statuses, (ffi::fmi2OK, ffi::fmi2OK));
        (status, terminated != 0, last, log.messages().into_iter().map(|m| m.message).collect())
    }

    const OK: Step = Step { status: f3::fmi3OK, event: false, terminate: false, early: false, last: 2.6 };

    #[test]
    fn a_step_asking_to_end_the_simulation_is_a_terminating_discard_at_the_step_end_or_the_early_return() {
        assert_eq!(step_with(OK), (ffi::fmi2OK, false, 2.4 + 0.2, vec![]));
        let (status, terminated, last, log) = step_with(Step { terminate: true, ..OK });
        assert_eq!((status, terminated, last), (ffi::fmi2Discard, true, 2.4 + 0.2));
        assert!(log[0].starts_with("fmi3DoStep set terminateSimulation"), "{log:?}");
        let (status, terminated, last, _) = step_with(Step { terminate: true, early: true, last: 2.5, ..OK });
        assert_eq!((status, terminated, last), (ffi::fmi2Discard, true, 2.5));
    }

    #[test]
    fn early_returns_and_event_requests_end_the_step_as_a_discard_saying_why() {
        let (status, terminated, last, log) = step_with(Step { early: true, last: 2.5, ..OK });
        assert_eq!((status, terminated, last), (ffi::fmi2Discard, false, 2.5));
        assert!(log[0].starts_with("fmi3DoStep returned early (earlyReturn)"), "{log:?}");
        let (status, terminated, _, log) = step_with(Step { event: true, ..OK });
        assert_eq!((status, terminated), (ffi::fmi2Discard, false));
        assert!(log[0].starts_with("fmi3DoStep set eventHandlingNeeded"), "{log:?}");
    }

    #[test]
    fn the_output_arguments_of_a_discarded_step_are_not_taken() {
        // FMI 3.0 leaves them undefined after fmi3Discard: terminateSimulation written true there
        // is no request to end the simulation (the run then fails on the discard, as in FMPy),
        // and the step completed nothing.
        let discard = Step { status: f3::fmi3Discard, terminate: true, early: true, last: 2.5, ..OK };
        let (status, terminated, last, log) = step_with(discard);
        assert_eq!((status, terminated, last), (ffi::fmi2Discard, false, 2.4));
        assert!(log[0].contains("the request to end the simulation is not taken"), "{log:?}");
        let (status, terminated, _, _) = step_with(Step { status: f3::fmi3Error, terminate: true, ..OK });
        assert_eq!((status, terminated), (ffi::fmi2Error, false));
        let (status, terminated, last, log) = step_with(Step { status: f3::fmi3Discard, ..OK });
        assert_eq!((status, terminated, last, log), (ffi::fmi2Discard, false, 2.4, vec![]));
    }

    thread_local! {
        /// The fake FMU's Float64 array (value reference 7) as last set.
        static ARRAY: std::cell::RefCell<Vec<f64>> = const { std::cell::RefCell::new(Vec::new()) };
    }

    unsafe extern "C" fn array_get(
        _instance: f3::fmi3Instance,
        vr: *const u32,
        _n: usize,
        values: *mut f64,
        n_values: usize,
    ) -> f3::fmi3Status {
        // SAFETY: one value reference and `n_values` writable values, as the adapter passes.
        let (vr, out) = unsafe { (*vr, std::slice::from_raw_parts_mut(values, n_values)) };
        assert_eq!(vr, 7, "elements are read through their array");
        ARRAY.with_borrow(|array| out.copy_from_slice(&array.iter().map(|v| v * 10.0).collect::<Vec<_>>()));
        f3::fmi3OK
    }

    unsafe extern "C" fn array_set(
        _instance: f3::fmi3Instance,
        vr: *const u32,
        _n: usize,
        values: *const f64,
        n_values: usize,
    ) -> f3::fmi3Status {
        // SAFETY: as above, readable.
        let (vr, given) = unsafe { (*vr, std::slice::from_raw_parts(values, n_values)) };
        assert_eq!(vr, 7, "elements are set through their array");
        ARRAY.set(given.to_vec());
        f3::fmi3OK
    }

    #[test]
    fn array_elements_are_set_with_the_rest_of_their_array_and_read_from_it() {
        let element = |index: usize| Fmi3Element {
            value_reference: 100 + index as u32,
            name: format!("u[{}]", index + 1),
            fmi3_value_reference: 7,
            fmi3_type: Fmi3Type::Float64,
            index,
            size: 3,
            start: Some(Start::Float(index as f64 + 1.0)),
        };
        let float32 = Fmi3Element {
            value_reference: 200,
            name: "gain".into(),
            fmi3_value_reference: 8,
            fmi3_type: Fmi3Type::Float32,
            index: 0,
            size: 1,
            start: None,
        };
        let log = LogContext::new("x", LogEcho::Off);
        let mut adapter = adapter_on(&log);
        adapter.functions.fmi3GetFloat64 = array_get;
        adapter.functions.fmi3SetFloat64 = array_set;
        adapter.elements = Elements::new(&[element(0), element(1), element(2), float32]);
        let c = &mut *adapter as *mut Adapter as ffi::fmi2Component;
        // SAFETY: a live adapter; arrays of the announced lengths.
        assert_eq!(unsafe { set_real(c, [101].as_ptr(), 1, [5.0].as_ptr()) }, ffi::fmi2OK);
        assert_eq!(ARRAY.with_borrow(Clone::clone), [1.0, 5.0, 3.0], "the other elements keep their start");
        // SAFETY: as above.
        assert_eq!(unsafe { set_real(c, [102, 100].as_ptr(), 2, [6.0, 4.0].as_ptr()) }, ffi::fmi2OK);
        assert_eq!(ARRAY.with_borrow(Clone::clone), [4.0, 5.0, 6.0], "and then the values last set");
        let mut out = [0.0; 3];
        // SAFETY: as above.
        assert_eq!(unsafe { get_real(c, [102, 100, 101].as_ptr(), 3, out.as_mut_ptr()) }, ffi::fmi2OK);
        assert_eq!(out, [60.0, 40.0, 50.0]);
        // A Float32 takes only values that are exactly 32-bit floats (refused before any call).
        // SAFETY: as above.
        assert_eq!(unsafe { set_real(c, [200].as_ptr(), 1, [0.1].as_ptr()) }, ffi::fmi2Error);
        let message = log.messages().pop().expect("a message").message;
        // The nearest float32 is shown widened (as a float32, 0.1f32 would print as "0.1").
        let expected =
            "gain is an FMI 3.0 Float32: 0.1 is not exactly a 32-bit float (the nearest is 0.10000000149011612)";
        assert!(message.contains(expected), "{message}");
    }
}
