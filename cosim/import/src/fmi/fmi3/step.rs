//! `fmi2DoStep` as `fmi3DoStep`, and the two statuses that answer from what the step reported
//! (see the module documentation of [`super`]).

use std::ffi::c_int;

use super::adapter::{adapter, report};
use crate::fmi::ffi;
use fmi3_sys as f3;

pub(super) unsafe extern "C" fn do_step(
    c: ffi::fmi2Component,
    t: f64,
    h: f64,
    no_set_prior: ffi::fmi2Boolean,
) -> ffi::fmi2Status {
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

pub(super) unsafe extern "C" fn get_real_status(c: ffi::fmi2Component, kind: c_int, v: *mut f64) -> ffi::fmi2Status {
    if kind != ffi::fmi2LastSuccessfulTime {
        return ffi::fmi2Discard;
    }
    // SAFETY: a live adapter; the Slave's writable slot.
    unsafe { *v = adapter(c).last_successful_time };
    ffi::fmi2OK
}

pub(super) unsafe extern "C" fn get_boolean_status(
    c: ffi::fmi2Component,
    kind: c_int,
    v: *mut c_int,
) -> ffi::fmi2Status {
    if kind != ffi::fmi2Terminated {
        return ffi::fmi2Discard;
    }
    // SAFETY: a live adapter; the Slave's writable slot.
    unsafe { *v = c_int::from(adapter(c).terminate_requested) };
    ffi::fmi2OK
}
