//! The FMI 2.0 C entry points as generic functions; [`crate::export_fmu!`] expands one
//! `#[no_mangle] extern "C"` wrapper per function inside the FMU crate and forwards here.
//!
//! Every function checks its pointers, that the instance is one this library lists as live
//! (`crate::live`) and created through FMI 2.0, and the state machine, and runs the work under
//! `catch_unwind` ([`crate::calls`], shared with FMI 3.0): nothing unwinds across the C ABI (a
//! panic becomes `fmi2Fatal`).
//!
//! # Safety
//! Each `pub unsafe fn` here relies on what FMI 2.0 requires of the host (§2.1.5, §2.1.7), and
//! on nothing else: the contracts 1 to 4 of [`crate::calls`].
#![allow(clippy::missing_safety_doc)]

use crate::calls::{self, host_slot, slice, slice_mut, string_args, with_instance, Request, Resources, ValueArrays};
use crate::ffi::*;
use crate::instance::{error, Instance, Outcome};
use crate::logging::Logger;
use crate::model::Model;
use crate::state::{self, Mask, Standard};

/// The instance behind `c`, if it is a live FMI 2.0 instance of `M` (contracts 1 and 2).
unsafe fn instance_ref<'a, M: Model>(c: fmi2Component) -> Option<&'a mut Instance<M>> {
    // SAFETY: the caller's contracts 1 and 2, passed on.
    unsafe { calls::instance_ref::<M>(c, Standard::Fmi2) }
}

#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate<M: Model>(
    our_guid: &str,
    name: fmi2String,
    fmu_type: fmi2Type,
    guid: fmi2String,
    resource_location: fmi2String,
    functions: *const fmi2CallbackFunctions,
    _visible: fmi2Boolean,
    logging_on: fmi2Boolean,
) -> fmi2Component {
    // SAFETY: a non-null callback struct is readable (FMI 2.0 §2.1.5).
    let Some(logger) = (unsafe { functions.as_ref() }).and_then(Logger::new) else {
        return std::ptr::null_mut();
    };
    let request = Request {
        function: "fmi2Instantiate",
        ours: our_guid,
        name,
        token: guid,
        resources: Resources::Uri(resource_location),
        logging_on: logging_on != fmi2False,
        time_vr: None,
    };
    let refuse = || {
        if fmu_type == fmi2CoSimulation {
            Ok(())
        } else {
            Err(format!("{} supports Co-Simulation only (fmuType = {fmu_type})", M::INFO.model_identifier))
        }
    };
    // SAFETY: the host's strings, NULL or NUL-terminated (contract 3).
    unsafe { calls::instantiate::<M>(request, Standard::Fmi2, logger, refuse) }
}

pub unsafe fn free_instance<M: Model>(c: fmi2Component) {
    // SAFETY: contracts 1 and 2, passed on.
    unsafe { calls::free_instance::<M>(c, Standard::Fmi2) }
}

pub unsafe fn set_debug_logging<M: Model>(
    c: fmi2Component,
    on: fmi2Boolean,
    n: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    // SAFETY: contracts 1 to 3, passed on.
    unsafe { calls::set_debug_logging(instance_ref::<M>(c), "fmi2SetDebugLogging", on != fmi2False, n, categories) }
}

pub unsafe fn setup_experiment<M: Model>(
    c: fmi2Component,
    tolerance_defined: fmi2Boolean,
    tolerance: fmi2Real,
    start: fmi2Real,
    stop_defined: fmi2Boolean,
    stop: fmi2Real,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetupExperiment", state::SETUP_EXPERIMENT, |inst| {
        let tolerance = (tolerance_defined != fmi2False).then_some(tolerance);
        inst.setup_experiment(tolerance, start, (stop_defined != fmi2False).then_some(stop))
    })
}

pub unsafe fn enter_initialization_mode<M: Model>(c: fmi2Component) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(
        unsafe { instance_ref::<M>(c) },
        "fmi2EnterInitializationMode",
        state::ENTER_INITIALIZATION,
        Instance::enter_initialization,
    )
}

pub unsafe fn exit_initialization_mode<M: Model>(c: fmi2Component) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(
        unsafe { instance_ref::<M>(c) },
        "fmi2ExitInitializationMode",
        state::EXIT_INITIALIZATION,
        Instance::exit_initialization,
    )
}

pub unsafe fn terminate<M: Model>(c: fmi2Component) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2Terminate", state::TERMINATE, Instance::terminate)
}

pub unsafe fn reset<M: Model>(c: fmi2Component) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2Reset", state::ANY_BUT_FATAL, Instance::reset)
}

/// `fmi2GetReal`, `fmi2GetInteger`, `fmi2GetBoolean`, `fmi2GetString` (named `function`):
/// the values of `V` at the `n` value references `vr` written to `value`.
pub unsafe fn get_values<M: Model, V: ValueArrays>(
    c: fmi2Component,
    function: &str,
    vr: *const u32,
    n: usize,
    value: *mut V::C,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, function, state::GET_VALUES, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        V::get(inst, unsafe { slice(vr, n, "vr") }?, unsafe { slice_mut(value, n, "value") }?)
    })
}

/// Parameters and inputs may be set in several states; the per-variable rules are checked in
/// [`Instance::set_real`], so the function-level mask admits every state that allows any.
const SET_ANY: Mask = state::SET_INPUTS;

/// `fmi2SetReal`, `fmi2SetInteger`, `fmi2SetBoolean` (named `function`): the `n` value
/// references `vr` set to the values of `V` at `value`, all or none (`fmi2SetString` reads
/// its strings before the references, see [`set_string`]).
pub unsafe fn set_values<M: Model, V: ValueArrays>(
    c: fmi2Component,
    function: &str,
    vr: *const u32,
    n: usize,
    value: *const V::C,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, function, SET_ANY, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements (contract 3); a boolean is read as its
        // integer.
        unsafe { V::set(inst, slice(vr, n, "vr")?, slice(value.cast::<V::Read>(), n, "value")?) }
    })
}

/// FMI 2.0 Booleans: `fmi2True` (1) or `fmi2False` (0) written, any nonzero integer read as true.
pub struct Boolean;

impl ValueArrays for Boolean {
    type C = fmi2Boolean;
    type Read = fmi2Boolean;
    fn get<M: Model>(inst: &mut Instance<M>, vrs: &[u32], out: &mut [fmi2Boolean]) -> Outcome {
        inst.get_boolean(vrs, out, |b| if b { fmi2True } else { fmi2False })
    }
    unsafe fn set<M: Model>(inst: &mut Instance<M>, vrs: &[u32], values: &[fmi2Boolean]) -> Outcome {
        inst.set_boolean(vrs, values, |b| b != fmi2False)
    }
}

pub unsafe fn set_string<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *const fmi2String) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetString", SET_ANY, |inst| {
        // SAFETY: `value` holds `n` NUL-terminated strings (contract 3).
        let values = unsafe { string_args(slice(value, n, "value")?, "value") }?;
        // SAFETY: `vr` holds `n` elements (contract 3).
        inst.set_string(unsafe { slice(vr, n, "vr") }?, &values)
    })
}

calls::fmu_state_api!(
    fmi2Component, fmi2FMUstate, fmi2Byte, fmi2Status;
    "fmi2GetFMUstate", "fmi2SetFMUstate", "fmi2FreeFMUstate", "fmi2SerializedFMUstateSize",
    "fmi2SerializeFMUstate", "fmi2DeSerializeFMUstate"
);

pub unsafe fn set_real_input_derivatives<M: Model>(
    c: fmi2Component,
    vr: *const u32,
    n: usize,
    order: *const fmi2Integer,
    value: *const f64,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetRealInputDerivatives", SET_ANY, |inst| {
        // SAFETY: `vr`, `order` and `value` each hold `n` elements (contract 3).
        inst.set_real_input_derivatives(unsafe { slice(vr, n, "vr") }?, unsafe { slice(order, n, "order") }?, unsafe {
            slice(value, n, "value")
        }?)
    })
}

pub unsafe fn do_step<M: Model>(c: fmi2Component, t: f64, h: f64, _no_set_prior: fmi2Boolean) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2DoStep", state::DO_STEP, |inst| inst.do_step(t, h))
}

pub unsafe fn get_real_status<M: Model>(c: fmi2Component, kind: fmi2StatusKind, value: *mut f64) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetRealStatus", state::STATUS, |inst| {
        // SAFETY: a non-null `value` is the host's writable slot (contract 3).
        let out = unsafe { host_slot(value, "value") }?;
        if kind != fmi2LastSuccessfulTime {
            return error(format!("status kind {kind} has no Real value (only fmi2LastSuccessfulTime)"));
        }
        *out = inst.core.time;
        Ok(())
    })
}

pub unsafe fn get_boolean_status<M: Model>(
    c: fmi2Component,
    kind: fmi2StatusKind,
    value: *mut fmi2Boolean,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetBooleanStatus", state::STATUS, |_| {
        // SAFETY: a non-null `value` is the host's writable slot (contract 3).
        let out = unsafe { host_slot(value, "value") }?;
        if kind != fmi2Terminated {
            return error(format!("status kind {kind} has no Boolean value (only fmi2Terminated)"));
        }
        // The FMUs never ask the importer to end the simulation.
        *out = fmi2False;
        Ok(())
    })
}

/// Entry points the FMU declares but does not support (Model Exchange, asynchronous steps,
/// directional and output derivatives): `fmi2Error` with a message naming the function.
pub unsafe fn unsupported<M: Model>(c: fmi2Component, function: &str) -> fmi2Status {
    // SAFETY: contracts 1 and 2, passed on.
    let instance = unsafe { instance_ref::<M>(c) };
    calls::unsupported(instance, function, "a Co-Simulation FMU with synchronous steps")
}
