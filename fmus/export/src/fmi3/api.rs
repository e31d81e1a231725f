//! The FMI 3.0 C entry points as generic functions; [`crate::export_fmu!`] expands one
//! `#[no_mangle] extern "C"` wrapper per function of `fmi3Functions.h` inside the FMU crate and
//! forwards here.
//!
//! Every function checks its pointers, that the instance is one this library lists as live and
//! created through FMI 3.0, and the state machine (FMI 2.0's, see [`crate::state`]), and runs
//! the work under `catch_unwind` ([`crate::calls`], shared with FMI 2.0): nothing unwinds across
//! the C ABI (a panic becomes `fmi3Fatal`).
//!
//! # Safety
//! Each `pub unsafe fn` here relies on what FMI 3.0 requires of the host (§2.2.1: one call at a
//! time per instance; arrays of the announced lengths), and on nothing else: the contracts 1
//! to 4 of [`crate::calls`]. Booleans from the host are read as bytes (any byte but 0 is
//! true), never as Rust `bool`s.
#![allow(clippy::missing_safety_doc)]

use crate::calls::{self, slice, slice_mut, string_arg, with_instance, Handle, Request, Resources, ValueArrays};
use crate::instance::{error, Instance, Outcome};
use crate::logging::Logger;
use crate::model::Model;
use crate::state::{self, Mask, Standard};
use fmi3_sys::*;

/// The instance behind `c`, if it is a live FMI 3.0 instance of `M` (contracts 1 and 2).
unsafe fn instance_ref<'a, M: Model>(c: fmi3Instance) -> Option<&'a mut Instance<M>> {
    // SAFETY: the caller's contracts 1 and 2, passed on.
    unsafe { calls::instance_ref::<M>(c, Standard::Fmi3) }
}

/// The arguments of `fmi3InstantiateCoSimulation`, as the host passed them.
pub struct CoSimulationArguments {
    pub name: fmi3String,
    pub token: fmi3String,
    pub resource_path: fmi3String,
    pub logging_on: bool,
    pub event_mode_used: bool,
    pub early_return_allowed: bool,
    pub required_intermediate: *const fmi3ValueReference,
    pub n_required_intermediate: usize,
    pub environment: fmi3InstanceEnvironment,
    pub log_message: fmi3LogMessageCallback,
}

/// `fmi3InstantiateCoSimulation`: an instance, or NULL with the reason sent to `log_message`
/// (if the host gave one).
pub unsafe fn instantiate_co_simulation<M: Model>(our_token: &str, args: CoSimulationArguments) -> fmi3Instance {
    let logger = Logger::Fmi3 { environment: args.environment, callback: args.log_message };
    let request = Request {
        function: "fmi3InstantiateCoSimulation",
        ours: our_token,
        name: args.name,
        token: args.token,
        resources: Resources::Path(args.resource_path),
        logging_on: args.logging_on,
        time_vr: Some(crate::fmi3::xml::TIME_VR),
    };
    let refuse = || {
        if args.event_mode_used {
            return Err("eventModeUsed is true, but this FMU has no Event Mode (hasEventMode=\"false\")".to_owned());
        }
        if args.n_required_intermediate > 0 {
            return Err(format!(
                "{} requiredIntermediateVariables given, but this FMU provides no intermediate update",
                args.n_required_intermediate
            ));
        }
        // Early return is never used: the flag is accepted either way.
        let _ = (args.early_return_allowed, args.required_intermediate);
        Ok(())
    };
    // SAFETY: the host's strings, NULL or NUL-terminated (contract 3).
    unsafe { calls::instantiate::<M>(request, Standard::Fmi3, logger, refuse) }
}

/// `fmi3InstantiateModelExchange` and `fmi3InstantiateScheduledExecution`: NULL, with the
/// reason sent to the host's logger.
pub unsafe fn refuse_interface<M: Model>(
    function: &str,
    name: fmi3String,
    environment: fmi3InstanceEnvironment,
    log_message: fmi3LogMessageCallback,
) -> fmi3Instance {
    let logger = Logger::Fmi3 { environment, callback: log_message };
    // SAFETY: `name` is NULL or NUL-terminated (contract 3).
    let label = crate::logging::c_string(unsafe { string_arg(name, "") }.unwrap_or_default());
    let message = format!(
        "{function}: {} is a Co-Simulation FMU only (use fmi3InstantiateCoSimulation)",
        M::INFO.model_identifier
    );
    logger.log(&label, crate::status::Status::Error, "logStatusError", &message);
    std::ptr::null_mut()
}

pub unsafe fn free_instance<M: Model>(c: fmi3Instance) {
    // SAFETY: contracts 1 and 2, passed on.
    unsafe { calls::free_instance::<M>(c, Standard::Fmi3) }
}

pub unsafe fn set_debug_logging<M: Model>(
    c: fmi3Instance,
    on: fmi3Boolean,
    n: usize,
    categories: *const fmi3String,
) -> fmi3Status {
    // SAFETY: contracts 1 to 3, passed on.
    unsafe { calls::set_debug_logging(instance_ref::<M>(c), "fmi3SetDebugLogging", on, n, categories) }
}

/// `fmi3EnterInitializationMode`: FMI 2.0's `fmi2SetupExperiment` and
/// `fmi2EnterInitializationMode` in one call, refused as a whole if the times are.
pub unsafe fn enter_initialization_mode<M: Model>(
    c: fmi3Instance,
    tolerance_defined: fmi3Boolean,
    tolerance: fmi3Float64,
    start: fmi3Float64,
    stop_defined: fmi3Boolean,
    stop: fmi3Float64,
) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi3EnterInitializationMode", state::ENTER_INITIALIZATION, |inst| {
        inst.setup_experiment(tolerance_defined.then_some(tolerance), start, stop_defined.then_some(stop))?;
        inst.enter_initialization()
    })
}

pub unsafe fn exit_initialization_mode<M: Model>(c: fmi3Instance) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    let instance = unsafe { instance_ref::<M>(c) };
    with_instance(instance, "fmi3ExitInitializationMode", state::EXIT_INITIALIZATION, Instance::exit_initialization)
}

pub unsafe fn terminate<M: Model>(c: fmi3Instance) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi3Terminate", state::TERMINATE, Instance::terminate)
}

pub unsafe fn reset<M: Model>(c: fmi3Instance) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi3Reset", state::ANY_BUT_FATAL, Instance::reset)
}

/// FMI 3.0 passes the number of values beside the number of value references (they differ
/// for arrays); every variable of these FMUs is a scalar, so they must be equal.
fn check_scalars(n_vr: usize, n_values: usize) -> Outcome {
    if n_vr == n_values {
        Ok(())
    } else {
        error(format!(
            "nValues = {n_values} differs from nValueReferences = {n_vr} (every variable of this FMU is a scalar)"
        ))
    }
}

/// The C arrays of a get: value references and writable values, `n_vr` of each.
///
/// # Safety
/// Contract 3 for both arrays.
unsafe fn get_arrays<'a, T>(
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *mut T,
    n_values: usize,
) -> Outcome<(&'a [u32], &'a mut [T])> {
    check_scalars(n_vr, n_values)?;
    // SAFETY: the host announced `n_vr` elements in each array (contract 3).
    Ok((unsafe { slice(vr, n_vr, "valueReferences") }?, unsafe { slice_mut(values, n_values, "values") }?))
}

/// The C arrays of a set: value references and values, `n_vr` of each.
///
/// # Safety
/// Contract 3 for both arrays.
unsafe fn set_arrays<'a, T>(
    vr: *const fmi3ValueReference,
    n_vr: usize,
    values: *const T,
    n_values: usize,
) -> Outcome<(&'a [u32], &'a [T])> {
    check_scalars(n_vr, n_values)?;
    // SAFETY: the host announced `n_vr` elements in each array (contract 3).
    Ok((unsafe { slice(vr, n_vr, "valueReferences") }?, unsafe { slice(values, n_values, "values") }?))
}

/// `fmi3GetFloat64`, `fmi3GetInt32`, `fmi3GetBoolean`, `fmi3GetString` (named `function`):
/// the values of `V` at the `n_vr` value references `vr` written to `v` (`n_v` elements).
pub unsafe fn get_values<M: Model, V: ValueArrays>(
    c: fmi3Instance,
    function: &str,
    vr: *const u32,
    n_vr: usize,
    v: *mut V::C,
    n_v: usize,
) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, function, state::GET_VALUES, |inst| {
        // SAFETY: contract 3.
        let (vrs, out) = unsafe { get_arrays(vr, n_vr, v, n_v) }?;
        V::get(inst, vrs, out)
    })
}

/// Parameters and inputs may be set in several states; the per-variable rules are checked in
/// the instance, so the function-level mask admits every state that allows any.
const SET_ANY: Mask = state::SET_INPUTS;

/// `fmi3SetFloat64`, `fmi3SetInt32`, `fmi3SetBoolean`, `fmi3SetString` (named `function`):
/// the `n_vr` value references `vr` set to the values of `V` at `v` (`n_v` elements), all or
/// none.
pub unsafe fn set_values<M: Model, V: ValueArrays>(
    c: fmi3Instance,
    function: &str,
    vr: *const u32,
    n_vr: usize,
    v: *const V::C,
    n_v: usize,
) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, function, SET_ANY, |inst| {
        // SAFETY: contract 3; a boolean is read as its byte (a C bool has one byte), see the
        // module safety note.
        let (vrs, values) = unsafe { set_arrays(vr, n_vr, v.cast::<V::Read>(), n_v) }?;
        // SAFETY: strings NUL-terminated (contract 3).
        unsafe { V::set(inst, vrs, values) }
    })
}

/// FMI 3.0 Booleans: C `bool`s written, read as bytes (any nonzero byte is true).
pub struct Boolean;

impl ValueArrays for Boolean {
    type C = fmi3Boolean;
    type Read = u8;
    fn get<M: Model>(inst: &mut Instance<M>, vrs: &[u32], out: &mut [fmi3Boolean]) -> Outcome {
        inst.get_boolean(vrs, out, |b| b)
    }
    unsafe fn set<M: Model>(inst: &mut Instance<M>, vrs: &[u32], values: &[u8]) -> Outcome {
        inst.set_boolean(vrs, values, |b| b != 0)
    }
}

/// Gets and sets of a type no variable of this FMU has (Float32, the 8- to 64-bit integers but
/// Int32, Binary): an empty call (`nValues` 0 too) succeeds where the state allows values at
/// all, any value reference is unknown. `fmi3GetClock` and `fmi3SetClock` are not among them:
/// FMI 3.0 allows them only in Event Mode (and Scheduled Execution's modes), which these FMUs
/// never enter, so they are [`unsupported`].
pub unsafe fn no_variables_of_type<M: Model>(
    c: fmi3Instance,
    function: &str,
    mask: Mask,
    type_name: &str,
    vr: *const u32,
    n_vr: usize,
    n_values: usize,
) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, function, mask, |_| {
        check_scalars(n_vr, n_values)?;
        // SAFETY: contract 3.
        match unsafe { slice(vr, n_vr, "valueReferences") }?.first() {
            None => Ok(()),
            Some(first) => {
                error(format!("unknown {type_name} value reference {first} (this FMU has no {type_name} variables)"))
            }
        }
    })
}

calls::fmu_state_api!(
    fmi3Instance, fmi3FMUState, fmi3Byte, fmi3Status;
    "fmi3GetFMUState", "fmi3SetFMUState", "fmi3FreeFMUState", "fmi3SerializedFMUStateSize",
    "fmi3SerializeFMUState", "fmi3DeserializeFMUState"
);

/// The outputs of `fmi3DoStep` besides its status.
pub struct StepOutputs {
    pub event_handling_needed: *mut fmi3Boolean,
    pub terminate_simulation: *mut fmi3Boolean,
    pub early_return: *mut fmi3Boolean,
    pub last_successful_time: *mut fmi3Float64,
}

/// `fmi3DoStep`: the step, then no event, no termination, no early return, and the time
/// reached (after a refused or failed step: the time before it, which the instance keeps).
pub unsafe fn do_step<M: Model>(c: fmi3Instance, t: f64, h: f64, outputs: StepOutputs) -> fmi3Status {
    // SAFETY: `c` per contracts 1 and 2.
    let instance = unsafe { instance_ref::<M>(c) };
    let mut reached = None;
    let status = with_instance(instance, "fmi3DoStep", state::DO_STEP, |inst| {
        let null = [outputs.event_handling_needed, outputs.terminate_simulation, outputs.early_return]
            .iter()
            .any(|p| p.is_null())
            || outputs.last_successful_time.is_null();
        if null {
            return error("an output argument (eventHandlingNeeded, terminateSimulation, earlyReturn or lastSuccessfulTime) is NULL");
        }
        let result = inst.do_step(t, h);
        reached = Some(inst.core.time);
        result
    });
    if let Some(time) = reached {
        // SAFETY: all four checked non-null above; the host's writable slots (contract 3). Written
        // as bytes: a C bool is one byte.
        unsafe {
            *(outputs.event_handling_needed as *mut u8) = 0;
            *(outputs.terminate_simulation as *mut u8) = 0;
            *(outputs.early_return as *mut u8) = 0;
            *outputs.last_successful_time = time;
        }
    }
    status
}

/// Entry points the FMU declares but does not support: `fmi3Error` with a message naming the
/// function and why.
pub unsafe fn unsupported<M: Model>(c: fmi3Instance, function: &str, why: &str) -> fmi3Status {
    // SAFETY: contracts 1 and 2, passed on.
    calls::unsupported(unsafe { instance_ref::<M>(c) }, function, why)
}

/// Why the Model Exchange functions are refused.
pub const NOT_MODEL_EXCHANGE: &str = "a Co-Simulation FMU only";
/// Why the clock (`fmi3GetClock`, `fmi3SetClock`, intervals, shifts), configuration and
/// discrete-state functions are refused.
pub const NO_CLOCKS: &str = "the FMU has no clocks, structural parameters or Event Mode";
/// Why derivatives and dependencies are refused.
pub const NO_DERIVATIVES: &str =
    "providesDirectionalDerivatives, providesAdjointDerivatives and providesPerElementDependencies are false, maxOutputDerivativeOrder is 0";

// `Handle` is the type every instance and state pointer converts to in `calls`.
const _: () = assert!(std::mem::size_of::<Handle>() == std::mem::size_of::<fmi3Instance>());
