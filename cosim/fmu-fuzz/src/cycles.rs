//! The cycles of the leak test: instances created, stepped and freed (some FMU states freed, some
//! left to `fmi2FreeInstance`), and libraries loaded and unloaded. Run natively they measure the
//! resident set size; run under valgrind (`fmu-leak`), whether any memory is lost. The
//! cross-library cycle hands one library's instance and state to another library's functions,
//! which must refuse them without reading through the foreign pointers (valgrind reports any
//! such read).

use crate::fmu::Fmu;
use fmi2_sys::*;
use fmu_import::fmi::{LogContext, LogEcho};
use std::ptr::null_mut;

/// One instance through a short life: instantiate and initialize ([`initialized`]), three steps, two FMU states (one
/// serialized and read back) of which only one is freed, and `fmi2FreeInstance`.
pub fn instance_cycle(fmu: &Fmu) -> Result<(), String> {
    let f = fmu.library.functions();
    let log = LogContext::new(&fmu.model, LogEcho::Off);
    let c = initialized(fmu, &log)?;
    let ok = |status: fmi2Status, what: &str| succeeded(fmu, &log, status, what);
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

/// `Ok` for fmi2OK; otherwise "`what` failed" with what the FMU logged.
fn succeeded(fmu: &Fmu, log: &LogContext, status: fmi2Status, what: &str) -> Result<(), String> {
    if status == fmi2OK {
        Ok(())
    } else {
        Err(format!("{}: {what} failed: {:?}", fmu.model, log.messages()))
    }
}

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
    let ok = |status: fmi2Status, what: &str| succeeded(fmu, log, status, what);
    // SAFETY: a live instance of `fmu`.
    unsafe {
        ok((f.fmi2SetupExperiment)(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), "fmi2SetupExperiment")?;
        ok((f.fmi2EnterInitializationMode)(c), "fmi2EnterInitializationMode")?;
        ok((f.fmi2ExitInitializationMode)(c), "fmi2ExitInitializationMode")?;
    }
    Ok(c)
}

/// Hands an instance and a state of `a` to the functions of `b` (and `a`'s state to an
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

/// Loads the library of `model`, runs one instance cycle and unloads it again.
pub fn load_cycle(model: &str) -> Result<(), String> {
    let fmu = Fmu::load(model)?;
    instance_cycle(&fmu)
}

/// The resident set size of this process (bytes), from `/proc/self/status`.
pub fn resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
