//! The cycles of the leak test: instances created, stepped and freed (some FMU states freed, some
//! left to `fmi2FreeInstance`), and libraries loaded and unloaded. Run natively they measure the
//! resident set size; run under valgrind (`fmu-leak`), whether any memory is lost.

use crate::fmu::Fmu;
use fmi2_sys::*;
use fmu_import::fmi::{LogContext, LogEcho};
use std::ptr::null_mut;

/// One instance through a short life: instantiate, initialize, three steps, two FMU states (one
/// serialized and read back) of which only one is freed, and `fmi2FreeInstance`.
pub fn instance_cycle(fmu: &Fmu) -> Result<(), String> {
    let f = fmu.library.functions();
    let log = LogContext::new(&fmu.model, LogEcho::Off);
    let callbacks = log.callbacks();
    // SAFETY: valid arguments; the context outlives the instance.
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
    let failed = |what: &str| format!("{}: {what} failed: {:?}", fmu.model, log.messages());
    // SAFETY: a live instance; the pointers are valid for each call.
    unsafe {
        let ok = |status: fmi2Status, what: &str| if status == fmi2OK { Ok(()) } else { Err(failed(what)) };
        ok((f.fmi2SetupExperiment)(c, fmi2False, 0.0, 0.0, fmi2False, 0.0), "fmi2SetupExperiment")?;
        ok((f.fmi2EnterInitializationMode)(c), "fmi2EnterInitializationMode")?;
        ok((f.fmi2ExitInitializationMode)(c), "fmi2ExitInitializationMode")?;
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
