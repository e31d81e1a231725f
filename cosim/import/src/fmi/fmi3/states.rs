//! FMU states: the six FMI 2.0 functions as their FMI 3.0 namesakes, which an FMU need not
//! export (then the call is an error saying which function is missing).

use std::ffi::{c_char, c_void};

use super::adapter::{adapter, report, Adapter};
use crate::fmi::ffi;

/// An FMU-state function the FMU does not export: an error with a message.
fn missing(a: &Adapter, function: &str) -> ffi::fmi2Status {
    report(a, ffi::fmi2Error, &format!("the FMU does not export {function}"));
    ffi::fmi2Error
}

pub(super) unsafe extern "C" fn get_fmu_state(c: ffi::fmi2Component, s: *mut *mut c_void) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3GetFMUState {
        // SAFETY: the live instance; the Slave's slot.
        Some(f) => unsafe { f(a.instance, s) },
        None => missing(a, "fmi3GetFMUState"),
    }
}

pub(super) unsafe extern "C" fn set_fmu_state(c: ffi::fmi2Component, s: *mut c_void) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3SetFMUState {
        // SAFETY: the live instance; a state of it.
        Some(f) => unsafe { f(a.instance, s) },
        None => missing(a, "fmi3SetFMUState"),
    }
}

pub(super) unsafe extern "C" fn free_fmu_state(c: ffi::fmi2Component, s: *mut *mut c_void) -> ffi::fmi2Status {
    // SAFETY: a live adapter.
    let a = unsafe { adapter(c) };
    match a.functions.fmi3FreeFMUState {
        // SAFETY: the live instance; the Slave's slot.
        Some(f) => unsafe { f(a.instance, s) },
        None => missing(a, "fmi3FreeFMUState"),
    }
}

pub(super) unsafe extern "C" fn serialized_fmu_state_size(
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

pub(super) unsafe extern "C" fn serialize_fmu_state(
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

pub(super) unsafe extern "C" fn deserialize_fmu_state(
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
