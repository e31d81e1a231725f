//! The lifecycle calls: free, experiment setup, initialization, terminate, reset and debug
//! logging, each the FMI 3.0 call on the instance behind the component.

use super::adapter::{adapter, Adapter};
use crate::fmi::ffi;

pub(super) unsafe extern "C" fn free_instance(c: ffi::fmi2Component) {
    // SAFETY: the Slave frees each component once, after its last call.
    let adapter = unsafe { Box::from_raw(c as *mut Adapter) };
    // SAFETY: the live FMI 3.0 instance, freed once.
    unsafe { (adapter.functions.fmi3FreeInstance)(adapter.instance) };
}

pub(super) unsafe extern "C" fn setup_experiment(
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

pub(super) unsafe extern "C" fn enter_initialization_mode(c: ffi::fmi2Component) -> ffi::fmi2Status {
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

pub(super) unsafe extern "C" fn exit_initialization_mode(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter and its instance.
    unsafe { (adapter(c).functions.fmi3ExitInitializationMode)(adapter(c).instance) }
}

pub(super) unsafe extern "C" fn terminate(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter and its instance.
    unsafe { (adapter(c).functions.fmi3Terminate)(adapter(c).instance) }
}

pub(super) unsafe extern "C" fn reset(c: ffi::fmi2Component) -> ffi::fmi2Status {
    // SAFETY: a live adapter and its instance.
    unsafe { (adapter(c).functions.fmi3Reset)(adapter(c).instance) }
}

pub(super) unsafe extern "C" fn set_debug_logging(
    c: ffi::fmi2Component,
    on: ffi::fmi2Boolean,
    n: usize,
    categories: *const ffi::fmi2String,
) -> ffi::fmi2Status {
    // SAFETY: a live adapter; the categories as the Slave passed them.
    unsafe { (adapter(c).functions.fmi3SetDebugLogging)(adapter(c).instance, on != 0, n, categories) }
}
