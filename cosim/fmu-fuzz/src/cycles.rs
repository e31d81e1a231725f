//! The cycles of the leak test, through either API of a library: instances created, stepped and
//! freed (some FMU states freed, some left to the instance's free), and libraries loaded and
//! unloaded. Run natively they measure the resident set size; run under valgrind (`fmu-leak`),
//! whether any memory is lost. The cross-library cycles hand one library's instance and state
//! to another library's functions (FMI 3.0 ones also to its FMI 2.0 functions), which must
//! refuse them without reading through the foreign pointers (valgrind reports any such read).

use crate::fmi3::{log_message, Log};
use crate::fmu::{Api, Fmu};
use fmi2_sys::*;
use fmi3_sys::*;
use fmu_import::fmi::{LogContext, LogEcho};
use std::ffi::c_int;
use std::fmt::Debug;
use std::ptr::{null, null_mut};

/// One instance through a short life: instantiate and initialize, three steps, two FMU states
/// (one serialized and read back) of which only one is freed, and the instance's free (FMI 3.0
/// terminates it first).
pub fn instance_cycle(fmu: &Fmu, api: Api) -> Result<(), String> {
    match api {
        Api::Fmi2 => instance_cycle2(fmu),
        Api::Fmi3 => instance_cycle3(fmu),
    }
}

fn instance_cycle2(fmu: &Fmu) -> Result<(), String> {
    let f = fmu.library.functions();
    let log = LogContext::new(&fmu.model, LogEcho::Off);
    let c = initialized(fmu, &log)?;
    let ok = |status: fmi2Status, what: &str| succeeded(fmu, || log.messages(), status, what);
    // SAFETY: a live instance; the pointers are valid for each call.
    unsafe {
        for k in 0..3 {
            ok((f.fmi2DoStep)(c, k as f64 * 0.01, 0.01, fmi2True), "fmi2DoStep")?;
        }
        let (mut kept, mut freed) = (null_mut(), null_mut());
        ok((f.fmi2GetFMUstate)(c, &mut kept), "fmi2GetFMUstate")?;
        let mut size = 0;
        ok((f.fmi2SerializedFMUstateSize)(c, kept, &mut size), "fmi2SerializedFMUstateSize")?;
        let mut bytes = vec![0 as fmi2Byte; size];
        ok((f.fmi2SerializeFMUstate)(c, kept, bytes.as_mut_ptr(), size), "fmi2SerializeFMUstate")?;
        ok((f.fmi2DeSerializeFMUstate)(c, bytes.as_ptr(), size, &mut freed), "fmi2DeSerializeFMUstate")?;
        ok((f.fmi2FreeFMUstate)(c, &mut freed), "fmi2FreeFMUstate")?;
        // `kept` is left to fmi2FreeInstance.
        (f.fmi2FreeInstance)(c);
    }
    Ok(())
}

/// `Ok` for an OK status of either version (fmi2OK and fmi3OK are both 0); otherwise "`what`
/// failed" with what the FMU logged (`messages`).
fn succeeded<L: Debug>(fmu: &Fmu, messages: impl FnOnce() -> L, status: c_int, what: &str) -> Result<(), String> {
    if status == fmi2OK {
        Ok(())
    } else {
        Err(format!("{}: {what} failed: {:?}", fmu.model, messages()))
    }
}

const _: () = assert!(fmi2OK == fmi3OK);

/// An initialized instance of `fmu` logging to `log`.
fn initialized(fmu: &Fmu, log: &LogContext) -> Result<fmi2Component, String> {
    let f = fmu.library.functions();
    let callbacks = log.callbacks();
    // SAFETY: valid arguments; the context outlives the instance (the caller keeps it).
    let c = unsafe {
        (f.fmi2Instantiate)(
            c"leak".as_ptr(),
            fmi2CoSimulation,
            fmu.guid.as_ptr(),
            std::ptr::null(),
            &callbacks,
            fmi2False,
            fmi2False,
        )
    };
    if c.is_null() {
        return Err(format!("{}: fmi2Instantiate failed: {:?}", fmu.model, log.messages()));
    }
    let ok = |status: fmi2Status, what: &str| succeeded(fmu, || log.messages(), status, what);
    // SAFETY: a live instance of `fmu`.
    unsafe {
        ok((f.fmi2SetupExperiment)(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), "fmi2SetupExperiment")?;
        ok((f.fmi2EnterInitializationMode)(c), "fmi2EnterInitializationMode")?;
        ok((f.fmi2ExitInitializationMode)(c), "fmi2ExitInitializationMode")?;
    }
    Ok(c)
}

/// Hands an FMI 2.0 instance and state of `a` to the FMI 2.0 functions of `b` (and `a`'s state to an
/// instance of `b`): every call must be refused with fmi2Error, `fmi2FreeInstance` must leave
/// the foreign instance alone, and `a`'s instance and state must still work afterwards.
/// Returns the number of refusals seen.
pub fn cross_library_cycle(a: &Fmu, b: &Fmu) -> Result<usize, String> {
    let (fa, fb) = (a.library.functions(), b.library.functions());
    let (log_a, log_b) = (LogContext::new(&a.model, LogEcho::Off), LogContext::new(&b.model, LogEcho::Off));
    let (ca, cb) = (initialized(a, &log_a)?, initialized(b, &log_b)?);
    let pair = format!("{}'s instance passed to {}", a.model, b.model);
    let mut state = null_mut();
    // SAFETY: a live instance of `a`.
    if unsafe { (fa.fmi2GetFMUstate)(ca, &mut state) } != fmi2OK {
        return Err(format!("{pair}: fmi2GetFMUstate of {} failed", a.model));
    }
    let vr = b.references.real.first().copied().unwrap_or(0);
    let (mut value, mut size, mut taken, mut foreign) = (0.0, 0usize, null_mut(), state);
    // SAFETY: `b`'s functions receive `a`'s live instance and state, which they must recognise
    // as not theirs; every other pointer is valid for its call.
    let calls = unsafe {
        [
            ("fmi2DoStep", (fb.fmi2DoStep)(ca, 0.0, 0.01, fmi2True)),
            ("fmi2GetReal", (fb.fmi2GetReal)(ca, &vr, 1, &mut value)),
            ("fmi2SetReal", (fb.fmi2SetReal)(ca, &vr, 1, &value)),
            ("fmi2GetFMUstate", (fb.fmi2GetFMUstate)(ca, &mut taken)),
            ("fmi2SerializedFMUstateSize", (fb.fmi2SerializedFMUstateSize)(ca, state, &mut size)),
            ("fmi2SetFMUstate", (fb.fmi2SetFMUstate)(ca, state)),
            ("fmi2SetFMUstate(own instance)", (fb.fmi2SetFMUstate)(cb, state)),
            ("fmi2SerializedFMUstateSize(own instance)", (fb.fmi2SerializedFMUstateSize)(cb, state, &mut size)),
            ("fmi2FreeFMUstate", (fb.fmi2FreeFMUstate)(ca, &mut foreign)),
            ("fmi2FreeFMUstate(own instance)", (fb.fmi2FreeFMUstate)(cb, &mut foreign)),
            ("fmi2Terminate", (fb.fmi2Terminate)(ca)),
            ("fmi2Reset", (fb.fmi2Reset)(ca)),
        ]
    };
    if let Some((name, status)) = calls.iter().find(|(_, status)| *status != fmi2Error) {
        return Err(format!("{pair}: {name} returned {status}, not fmi2Error"));
    }
    if foreign != state || !taken.is_null() {
        return Err(format!("{pair}: a refused call changed the state pointer it was given"));
    }
    // SAFETY: `b` must ignore a foreign instance; `a`'s instance and state are live.
    unsafe {
        (fb.fmi2FreeInstance)(ca);
        if (fa.fmi2SetFMUstate)(ca, state) != fmi2OK || (fa.fmi2DoStep)(ca, 0.0, 0.01, fmi2True) != fmi2OK {
            return Err(format!("{pair}: {}'s instance no longer works: {:?}", a.model, log_a.messages()));
        }
        if (fa.fmi2FreeFMUstate)(ca, &mut state) != fmi2OK {
            return Err(format!("{pair}: fmi2FreeFMUstate of {} failed", a.model));
        }
        (fa.fmi2FreeInstance)(ca);
        (fb.fmi2FreeInstance)(cb);
    }
    Ok(calls.len())
}

/// Loads the library of `model`, runs one instance cycle through `api` and unloads it again.
pub fn load_cycle(model: &str, api: Api) -> Result<(), String> {
    let fmu = Fmu::load(model)?;
    instance_cycle(&fmu, api)
}

fn instance_cycle3(fmu: &Fmu) -> Result<(), String> {
    let f = fmu.f3();
    let log = Log::new();
    let c = initialized3(fmu, &log)?;
    let ok = |status: fmi3Status, what: &str| succeeded(fmu, || log.messages(), status, what);
    // SAFETY: a live instance; the pointers are valid for each call.
    unsafe {
        for k in 0..3 {
            let (mut event, mut terminate, mut early, mut last) = (false, false, false, 0.0);
            let t = k as f64 * 0.01;
            ok((f.fmi3DoStep)(c, t, 0.01, true, &mut event, &mut terminate, &mut early, &mut last), "fmi3DoStep")?;
        }
        let (mut kept, mut freed) = (null_mut(), null_mut());
        ok((f.fmi3GetFMUState)(c, &mut kept), "fmi3GetFMUState")?;
        let mut size = 0;
        ok((f.fmi3SerializedFMUStateSize)(c, kept, &mut size), "fmi3SerializedFMUStateSize")?;
        let mut bytes = vec![0u8; size];
        ok((f.fmi3SerializeFMUState)(c, kept, bytes.as_mut_ptr(), size), "fmi3SerializeFMUState")?;
        ok((f.fmi3DeserializeFMUState)(c, bytes.as_ptr(), size, &mut freed), "fmi3DeserializeFMUState")?;
        ok((f.fmi3FreeFMUState)(c, &mut freed), "fmi3FreeFMUState")?;
        ok((f.fmi3Terminate)(c), "fmi3Terminate")?;
        // `kept` is left to fmi3FreeInstance.
        (f.fmi3FreeInstance)(c);
    }
    Ok(())
}

/// An FMI 3.0 instance of `fmu` in Step Mode, logging to `log` (which the caller keeps).
fn initialized3(fmu: &Fmu, log: &Log) -> Result<fmi3Instance, String> {
    let f = fmu.f3();
    // SAFETY: valid arguments; the log outlives the instance (the caller keeps it).
    let c = unsafe {
        (f.fmi3InstantiateCoSimulation)(
            c"leak".as_ptr(),
            fmu.token.as_ptr(),
            null(),
            false,
            false,
            false,
            false,
            null(),
            0,
            log.environment(),
            Some(log_message),
            None,
        )
    };
    if c.is_null() {
        return Err(format!("{}: fmi3InstantiateCoSimulation failed: {:?}", fmu.model, log.messages()));
    }
    let ok = |status: fmi3Status, what: &str| succeeded(fmu, || log.messages(), status, what);
    // SAFETY: a live instance of `fmu`.
    unsafe {
        ok((f.fmi3EnterInitializationMode)(c, false, 0.0, 0.0, false, 0.0), "fmi3EnterInitializationMode")?;
        ok((f.fmi3ExitInitializationMode)(c), "fmi3ExitInitializationMode")?;
    }
    Ok(c)
}

/// [`cross_library_cycle`] for FMI 3.0: an FMI 3.0 instance and state of `a` handed to the FMI
/// 3.0 functions of `b` (and `a`'s state to an FMI 3.0 instance of `b`), and the instance to
/// `b`'s FMI 2.0 functions: every call must be refused with fmi3Error or fmi2Error, the frees
/// of both versions must leave the foreign instance alone, and `a`'s instance and state must
/// still work afterwards. Returns the number of refusals seen.
pub fn cross_library_cycle3(a: &Fmu, b: &Fmu) -> Result<usize, String> {
    let (fa, fb, fb2) = (a.f3(), b.f3(), b.library.functions());
    let (log_a, log_b) = (Log::new(), Log::new());
    let (ca, cb) = (initialized3(a, &log_a)?, initialized3(b, &log_b)?);
    let pair = format!("{}'s FMI 3.0 instance passed to {}", a.model, b.model);
    let mut state = null_mut();
    // SAFETY: a live instance of `a`.
    if unsafe { (fa.fmi3GetFMUState)(ca, &mut state) } != fmi3OK {
        return Err(format!("{pair}: fmi3GetFMUState of {} failed", a.model));
    }
    let vr = b.variables3.by_type.real.first().copied().unwrap_or(0);
    let (mut value, mut size, mut taken, mut taken2, mut foreign) = (0.0, 0usize, null_mut(), null_mut(), state);
    let (mut event, mut terminate, mut early, mut last) = (false, false, false, 0.0);
    // SAFETY: `b`'s functions receive `a`'s live instance and state, which they must recognise
    // as not theirs; every other pointer is valid for its call.
    let calls = unsafe {
        [
            ("fmi3DoStep", (fb.fmi3DoStep)(ca, 0.0, 0.01, true, &mut event, &mut terminate, &mut early, &mut last)),
            ("fmi3GetFloat64", (fb.fmi3GetFloat64)(ca, &vr, 1, &mut value, 1)),
            ("fmi3SetFloat64", (fb.fmi3SetFloat64)(ca, &vr, 1, &value, 1)),
            ("fmi3GetFMUState", (fb.fmi3GetFMUState)(ca, &mut taken)),
            ("fmi3SerializedFMUStateSize", (fb.fmi3SerializedFMUStateSize)(ca, state, &mut size)),
            ("fmi3SetFMUState", (fb.fmi3SetFMUState)(ca, state)),
            ("fmi3SetFMUState(own instance)", (fb.fmi3SetFMUState)(cb, state)),
            ("fmi3SerializedFMUStateSize(own instance)", (fb.fmi3SerializedFMUStateSize)(cb, state, &mut size)),
            ("fmi3FreeFMUState", (fb.fmi3FreeFMUState)(ca, &mut foreign)),
            ("fmi3FreeFMUState(own instance)", (fb.fmi3FreeFMUState)(cb, &mut foreign)),
            ("fmi3Terminate", (fb.fmi3Terminate)(ca)),
            ("fmi3Reset", (fb.fmi3Reset)(ca)),
            ("fmi3EnterInitializationMode", (fb.fmi3EnterInitializationMode)(ca, false, 0.0, 0.0, false, 0.0)),
            ("fmi2DoStep", (fb2.fmi2DoStep)(ca, 0.0, 0.01, fmi2True)),
            ("fmi2GetFMUstate", (fb2.fmi2GetFMUstate)(ca, &mut taken2)),
            ("fmi2SetFMUstate", (fb2.fmi2SetFMUstate)(ca, state)),
        ]
    };
    // fmi2Error and fmi3Error are both 3.
    if let Some((name, status)) = calls.iter().find(|(_, status)| *status != fmi3Error) {
        return Err(format!("{pair}: {name} returned {status}, not fmi3Error / fmi2Error"));
    }
    if foreign != state || !taken.is_null() || !taken2.is_null() {
        return Err(format!("{pair}: a refused call changed the state pointer it was given"));
    }
    // SAFETY: `b` must ignore a foreign instance; `a`'s instance and state are live.
    unsafe {
        (fb.fmi3FreeInstance)(ca);
        (fb2.fmi2FreeInstance)(ca);
        let (mut event, mut terminate, mut early, mut last) = (false, false, false, 0.0);
        if (fa.fmi3SetFMUState)(ca, state) != fmi3OK
            || (fa.fmi3DoStep)(ca, 0.0, 0.01, true, &mut event, &mut terminate, &mut early, &mut last) != fmi3OK
        {
            return Err(format!("{pair}: {}'s instance no longer works: {:?}", a.model, log_a.messages()));
        }
        if (fa.fmi3FreeFMUState)(ca, &mut state) != fmi3OK {
            return Err(format!("{pair}: fmi3FreeFMUState of {} failed", a.model));
        }
        (fa.fmi3FreeInstance)(ca);
        (fb.fmi3FreeInstance)(cb);
    }
    Ok(calls.len())
}

/// The resident set size of this process (bytes), from `/proc/self/status`.
pub fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
