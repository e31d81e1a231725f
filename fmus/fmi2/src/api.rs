//! The FMI 2.0 C entry points as generic functions; [`crate::export_fmu!`] expands one
//! `#[no_mangle] extern "C"` wrapper per function inside the FMU crate and forwards here.
//!
//! Every function checks its pointers, that the instance is one this library lists as live
//! (`crate::live`) and the state machine, and runs the work under `catch_unwind`: nothing
//! unwinds across the C ABI (a panic becomes `fmi2Fatal`).
//!
//! # Safety
//! Each `pub unsafe fn` here relies on what FMI 2.0 requires of the host, and on nothing else:
//! 1. *Component*: any `c` is accepted: it is dereferenced only while `crate::live` lists it
//!    as an instance of this model (NULL, foreign and freed pointers are refused unread).
//! 2. *One call at a time per instance* (FMI 2.0 §2.1.5: an FMU need not be thread safe for one
//!    instance), so the `&mut Instance` of a call is the only reference to it, and no call frees
//!    an instance or FMU state that another call is using.
//! 3. *Arrays*: a non-null array argument holds the announced number of elements, readable for
//!    inputs and writable for outputs, for the duration of the call (§2.1.7); strings are
//!    NUL-terminated.
//! 4. *FMU states*: as components, dereferenced only while listed as live states of this model.
#![allow(clippy::missing_safety_doc)]

use crate::ffi::*;
use crate::instance::{error, Core, Failure, Instance, Outcome};
use crate::live;
use crate::logging::Logger;
use crate::model::{Environment, Model};
use crate::panics;
use crate::state::{self, Mask, State};
use crate::status::Status;
use std::ffi::{c_char, CStr};
use std::path::PathBuf;

/// An `fmi2FMUstate`: a snapshot of an instance's core. `crate::live` lists it with the
/// instance that created it (its owner), which frees it in `fmi2FreeInstance` if the host has
/// not freed it by then; other instances of the same FMU may use it.
struct StateBox<M: Model> {
    core: Core<M>,
}

impl<M: Model> StateBox<M> {
    /// A new state owned by `owner`, listed as live, as the handle the host gets.
    fn create(owner: &Instance<M>, core: Core<M>) -> fmi2FMUstate {
        let handle = Box::into_raw(Box::new(StateBox { core }));
        live::add(handle as *const StateBox<M>, owner as *const Instance<M> as usize);
        handle as fmi2FMUstate
    }

    /// Frees the state at `address` after `crate::live` stopped listing it.
    ///
    /// # Safety
    /// `address` was listed as a live `StateBox<M>` until the caller unlisted it, and no call is
    /// using it (contract 2).
    unsafe fn free_unlisted(address: usize) {
        // SAFETY: listed addresses of `StateBox<M>` come from Box::into_raw in `create`, and
        // only the one call that unlisted it (the caller) can reach it now.
        drop(unsafe { Box::from_raw(address as *mut StateBox<M>) });
    }
}

pub fn types_platform() -> *const c_char {
    c"default".as_ptr()
}

pub fn version() -> *const c_char {
    c"2.0".as_ptr()
}

/// Runs `f` on `instance` (`None`: the host passed no instance of this FMU) if `function` is
/// allowed in its state.
fn with_instance<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    mask: Mask,
    f: impl FnOnce(&mut Instance<M>) -> Outcome,
) -> fmi2Status {
    // A null or foreign pointer has no logger to report to; the status is all we can give.
    let Some(instance) = instance else { return Status::Error.to_c() };
    instance.log_call(function);
    let result = panics::catch(|| {
        instance.check_state(function, mask)?;
        f(instance)
    });
    match result {
        Ok(Ok(())) => Status::Ok.to_c(),
        failed => report_failure(instance, function, failed).to_c(),
    }
}

/// Logs why a call failed and, for a panic, puts the instance in `Fatal`: out of line, so that
/// the successful path of every entry point carries none of it.
#[cold]
#[inline(never)]
fn report_failure<M: Model>(
    instance: &mut Instance<M>,
    function: &str,
    result: std::thread::Result<Outcome>,
) -> Status {
    match result {
        Ok(Ok(())) => Status::Ok,
        Ok(Err(Failure { status, message })) => {
            instance.log_error(status, &format!("{function}: {message}"));
            status
        }
        Err(panic) => {
            log_panic_report(&instance.logger, &instance.name);
            let what = panic_message(&panic);
            instance.core.state = State::Fatal;
            instance.log_error(Status::Fatal, &format!("{function}: internal error: {what}"));
            Status::Fatal
        }
    }
}

/// The instance behind `c`, if `crate::live` lists `c` as a live instance of `M`.
///
/// # Safety
/// Contracts 1 and 2 of the module: the returned reference is the only one for the call.
unsafe fn instance_ref<'a, M: Model>(c: fmi2Component) -> Option<&'a mut Instance<M>> {
    let ptr = c as *mut Instance<M>;
    if !live::contains(ptr as *const Instance<M>) {
        return None;
    }
    // SAFETY: listed, so a live Box<Instance<M>> from `instantiate` (nothing else is listed as
    // an Instance<M>); contract 2 makes this the only reference during the call.
    Some(unsafe { &mut *ptr })
}

/// Sends the panic hook's report (message and location) of the panic just caught to `logger`
/// under `name`, see `crate::panics`.
#[cold]
fn log_panic_report(logger: &Logger, name: &CStr) {
    if let Some(report) = panics::take_report() {
        logger.log(name, Status::Fatal, "logStatusError", &format!("internal error: {report}"));
    }
}

fn panic_message(panic: &Box<dyn std::any::Any + Send>) -> String {
    if let Some(s) = panic.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = panic.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic".to_string()
    }
}

/// A slice from a C array; a null pointer is refused unless the length is zero.
///
/// # Safety
/// A non-null `ptr` has `n` readable elements for `'a` (contract 3).
unsafe fn slice<'a, T>(ptr: *const T, n: usize, what: &str) -> Outcome<&'a [T]> {
    if n == 0 {
        Ok(&[])
    } else if ptr.is_null() {
        null_array(what, n)
    } else {
        // SAFETY: the host guarantees `n` readable elements at a non-null `ptr`.
        Ok(unsafe { std::slice::from_raw_parts(ptr, n) })
    }
}

/// A mutable slice from a C array; a null pointer is refused unless the length is zero.
///
/// # Safety
/// A non-null `ptr` has `n` writable elements for `'a`, referenced by nothing else (contract 3).
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize, what: &str) -> Outcome<&'a mut [T]> {
    if n == 0 {
        Ok(&mut [])
    } else if ptr.is_null() {
        null_array(what, n)
    } else {
        // SAFETY: the host guarantees `n` writable elements at a non-null `ptr`.
        Ok(unsafe { std::slice::from_raw_parts_mut(ptr, n) })
    }
}

/// The refusal of a NULL array with `n` announced elements (out of line: it never happens in a
/// correct call).
#[cold]
#[inline(never)]
fn null_array<T>(what: &str, n: usize) -> Outcome<T> {
    error(format!("{what} is NULL but {n} values were announced"))
}

/// A string from the host, borrowed for the duration of the call.
///
/// # Safety
/// A non-null `ptr` is NUL-terminated and valid for `'a` (contract 3).
unsafe fn string_arg<'a>(ptr: *const c_char, what: &str) -> Outcome<&'a str> {
    if ptr.is_null() {
        return error(format!("{what} is NULL"));
    }
    // SAFETY: non-null strings from the host are NUL-terminated and outlive the call.
    let text = unsafe { CStr::from_ptr(ptr) };
    text.to_str().or_else(|_| error(format!("{what} is not valid UTF-8")))
}

/// Decodes `fmuResourceLocation` (a percent-encoded `file:` URI) into a path.
pub fn resource_dir(uri: &str) -> Result<PathBuf, String> {
    let url = url::Url::parse(uri).map_err(|e| format!("'{uri}' is not a URI: {e}"))?;
    if url.scheme() != "file" {
        return Err(format!("'{uri}' is not a file: URI"));
    }
    url.to_file_path().map_err(|()| format!("'{uri}' does not name a local path"))
}

/// `fmi2rs_model_description`: the rendered XML copied into the host's buffer (see
/// [`crate::export_fmu!`]), rendered at each call so that the library keeps no copy.
///
/// # Safety
/// A non-null `buffer` has `size` writable bytes.
pub unsafe fn model_description<M: Model>(buffer: *mut c_char, size: usize) -> usize {
    let text = match crate::xml::render::<M>() {
        Ok(description) => description.xml,
        Err(e) => format!("<!-- error: {e} -->"),
    };
    let text = crate::logging::c_string(&text);
    let bytes = text.as_bytes_with_nul();
    if !buffer.is_null() && size > 0 {
        let n = bytes.len().min(size);
        // SAFETY: the caller provides `size` writable bytes at a non-null `buffer`.
        let out = unsafe { std::slice::from_raw_parts_mut(buffer as *mut u8, n) };
        out.copy_from_slice(&bytes[..n]);
        out[n - 1] = 0;
    }
    bytes.len()
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
    panics::install_hook();
    // SAFETY: `name` is NULL or NUL-terminated (contract 3).
    let label = crate::logging::c_string(unsafe { string_arg(name, "") }.unwrap_or_default());
    // SAFETY: the strings are the host's, NULL or NUL-terminated (contract 3).
    let result =
        unsafe { instantiate_caught::<M>(our_guid, name, fmu_type, guid, resource_location, logger, logging_on) };
    let message = match result {
        Ok(Ok(instance)) => {
            let c = Box::into_raw(instance);
            live::add(c as *const Instance<M>, 0);
            return c as fmi2Component;
        }
        Ok(Err(message)) => message,
        Err(panic) => {
            log_panic_report(&logger, &label);
            format!("internal error: {}", panic_message(&panic))
        }
    };
    logger.log(&label, Status::Error, "logStatusError", &format!("fmi2Instantiate: {message}"));
    std::ptr::null_mut()
}

/// The work of [`instantiate`] under [`panics::catch`]: the instance, or why there is none.
///
/// # Safety
/// Each string is NULL or NUL-terminated (contract 3).
unsafe fn instantiate_caught<M: Model>(
    our_guid: &str,
    name: fmi2String,
    fmu_type: fmi2Type,
    guid: fmi2String,
    resource_location: fmi2String,
    logger: Logger,
    logging_on: fmi2Boolean,
) -> std::thread::Result<Result<Box<Instance<M>>, String>> {
    panics::catch(|| -> Result<Box<Instance<M>>, String> {
        // SAFETY: this function's contract (each string NULL or NUL-terminated), for all three.
        let instance_name = unsafe { string_arg(name, "instanceName") }.map_err(|f| f.message)?.to_owned();
        if instance_name.trim().is_empty() {
            return Err("instanceName is empty or blank (FMI 2.0 requires a non-empty name)".to_owned());
        }
        if fmu_type != fmi2CoSimulation {
            return Err(format!("{} supports Co-Simulation only (fmuType = {fmu_type})", M::INFO.model_identifier));
        }
        // SAFETY: as for `name` above.
        let given = unsafe { string_arg(guid, "fmuGUID") }.map_err(|f| f.message)?;
        if given != our_guid {
            return Err(format!("GUID {given} does not match this binary's {our_guid}"));
        }
        let resource_dir = if resource_location.is_null() {
            None
        } else {
            // SAFETY: as for `name` above.
            let uri = unsafe { string_arg(resource_location, "fmuResourceLocation") }.map_err(|f| f.message)?;
            resource_dir(uri).ok()
        };
        let env = Environment { instance_name, resource_dir };
        Instance::<M>::new(env, logger, logging_on != fmi2False, our_guid.to_owned())
            .map(Box::new)
            .map_err(|f| f.message)
    })
}

pub unsafe fn free_instance<M: Model>(c: fmi2Component) {
    let ptr = c as *mut Instance<M>;
    if !live::remove(ptr as *const Instance<M>) {
        return;
    }
    // States the host did not free go with their instance.
    for state in live::take_owned::<StateBox<M>>(ptr as usize) {
        // SAFETY: unlisted just now by `take_owned`; contract 2: no call is using it.
        unsafe { StateBox::<M>::free_unlisted(state) };
    }
    // SAFETY: listed until just now, so the Box from `instantiate`; unlisted, no later call can
    // reach it, and contract 2: no call is using it now.
    let boxed = unsafe { Box::from_raw(ptr) };
    // Copies: the instance's own logger and name are gone before the drop has ended.
    let (logger, name) = (boxed.logger, boxed.name.clone());
    if panics::catch(move || drop(boxed)).is_err() {
        log_panic_report(&logger, &name);
    }
}

/// How many FMU states the instance at `c` created that are not freed yet.
#[cfg(test)]
pub(crate) fn unfreed_states<M: Model>(c: fmi2Component) -> usize {
    live::owned_count::<StateBox<M>>(c as usize)
}

pub unsafe fn set_debug_logging<M: Model>(
    c: fmi2Component,
    on: fmi2Boolean,
    n: usize,
    categories: *const fmi2String,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetDebugLogging", state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `n` category strings at `categories`, each NUL-terminated (contract 3).
        let pointers = unsafe { slice(categories, n, "categories") }?;
        // SAFETY: as above, for each element.
        let names = pointers.iter().map(|p| unsafe { string_arg(*p, "category") }).collect::<Outcome<Vec<_>>>()?;
        inst.set_debug_logging(on != fmi2False, &names)
    })
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

pub unsafe fn get_real<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *mut f64) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetReal", state::GET_VALUES, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        inst.get_real(unsafe { slice(vr, n, "vr") }?, unsafe { slice_mut(value, n, "value") }?)
    })
}

pub unsafe fn get_integer<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *mut i32) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetInteger", state::GET_VALUES, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        inst.get_integer(unsafe { slice(vr, n, "vr") }?, unsafe { slice_mut(value, n, "value") }?)
    })
}

pub unsafe fn get_boolean<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *mut fmi2Boolean) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetBoolean", state::GET_VALUES, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        inst.get_boolean(unsafe { slice(vr, n, "vr") }?, unsafe { slice_mut(value, n, "value") }?)
    })
}

pub unsafe fn get_string<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *mut fmi2String) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetString", state::GET_VALUES, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable (contract 3).
        inst.get_string(unsafe { slice(vr, n, "vr") }?, unsafe { slice_mut(value, n, "value") }?)
    })
}

/// Parameters and inputs may be set in several states; the per-variable rules are checked in
/// [`Instance::set_real`], so the function-level mask admits every state that allows any.
const SET_ANY: Mask = state::SET_INPUTS;

pub unsafe fn set_real<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *const f64) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetReal", SET_ANY, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        inst.set_real(unsafe { slice(vr, n, "vr") }?, unsafe { slice(value, n, "value") }?)
    })
}

pub unsafe fn set_integer<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *const i32) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetInteger", SET_ANY, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        inst.set_integer(unsafe { slice(vr, n, "vr") }?, unsafe { slice(value, n, "value") }?)
    })
}

pub unsafe fn set_boolean<M: Model>(
    c: fmi2Component,
    vr: *const u32,
    n: usize,
    value: *const fmi2Boolean,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetBoolean", SET_ANY, |inst| {
        // SAFETY: `vr` and `value` each hold `n` elements, `value` writable for a get (contract 3).
        inst.set_boolean(unsafe { slice(vr, n, "vr") }?, unsafe { slice(value, n, "value") }?)
    })
}

pub unsafe fn set_string<M: Model>(c: fmi2Component, vr: *const u32, n: usize, value: *const fmi2String) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetString", SET_ANY, |inst| {
        // SAFETY: `value` holds `n` NUL-terminated strings (contract 3).
        let values = unsafe { slice(value, n, "value") }?
            .iter()
            // SAFETY: as above, for each element.
            .map(|p| unsafe { string_arg(*p, "value") })
            .collect::<Outcome<Vec<&str>>>()?;
        // SAFETY: `vr` holds `n` elements (contract 3).
        inst.set_string(unsafe { slice(vr, n, "vr") }?, &values)
    })
}

pub unsafe fn get_fmu_state<M: Model>(c: fmi2Component, state_out: *mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2GetFMUstate", state::ANY_BUT_FATAL, |inst| {
        // SAFETY: a non-null `state_out` is the host's writable slot (contract 3).
        let slot = unsafe { state_out.as_mut() }.map_or_else(|| error("FMUstate is NULL"), Ok)?;
        let core = inst.snapshot();
        // SAFETY: `*slot` is NULL or a state of this library (contract 4).
        match unsafe { state_box::<M>(*slot) } {
            Some(existing) => existing.core = core,
            None if slot.is_null() => *slot = StateBox::create(inst, core),
            None => return error("*FMUstate is neither NULL nor a state of this FMU"),
        }
        Ok(())
    })
}

pub unsafe fn set_fmu_state<M: Model>(c: fmi2Component, fmu_state: fmi2FMUstate) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SetFMUstate", state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `fmu_state` is NULL or a state of this library (contract 4).
        let saved = unsafe { state_box::<M>(fmu_state) }
            .map_or_else(|| error("FMUstate is NULL or not a state of this FMU"), Ok)?;
        inst.restore(&saved.core);
        Ok(())
    })
}

pub unsafe fn free_fmu_state<M: Model>(c: fmi2Component, state_io: *mut fmi2FMUstate) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2FreeFMUstate", state::ANY_BUT_FATAL, |_| {
        // SAFETY: a non-null `state_io` is the host's writable slot (contract 3).
        let slot = unsafe { state_io.as_mut() }.map_or_else(|| error("FMUstate is NULL"), Ok)?;
        if slot.is_null() {
            return Ok(());
        }
        if !live::remove(*slot as *const StateBox<M>) {
            return error("not a state of this FMU");
        }
        // SAFETY: unlisted just now; contract 2: no call is using it. The host gives up its
        // handle, which is cleared.
        unsafe { StateBox::<M>::free_unlisted(*slot as usize) };
        *slot = std::ptr::null_mut();
        Ok(())
    })
}

/// The state behind `ptr`, if `crate::live` lists `ptr` as a live state of `M`.
///
/// # Safety
/// Contract 2 of the module: no other call uses the state meanwhile.
unsafe fn state_box<'a, M: Model>(ptr: fmi2FMUstate) -> Option<&'a mut StateBox<M>> {
    let ptr = ptr as *mut StateBox<M>;
    if !live::contains(ptr as *const StateBox<M>) {
        return None;
    }
    // SAFETY: listed, so a live Box<StateBox<M>> from `create`; the only reference (contract 2).
    Some(unsafe { &mut *ptr })
}

pub unsafe fn serialized_fmu_state_size<M: Model>(
    c: fmi2Component,
    fmu_state: fmi2FMUstate,
    size: *mut usize,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SerializedFMUstateSize", state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `fmu_state` is NULL or a state of this library (contract 4).
        let saved = unsafe { state_box::<M>(fmu_state) }
            .map_or_else(|| error("FMUstate is NULL or not a state of this FMU"), Ok)?;
        // SAFETY: a non-null `size` is the host's writable slot (contract 3).
        let out = unsafe { size.as_mut() }.map_or_else(|| error("size is NULL"), Ok)?;
        *out = inst.serialize(&saved.core)?.len();
        Ok(())
    })
}

pub unsafe fn serialize_fmu_state<M: Model>(
    c: fmi2Component,
    fmu_state: fmi2FMUstate,
    bytes: *mut fmi2Byte,
    size: usize,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2SerializeFMUstate", state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `fmu_state` is NULL or a state of this library (contract 4).
        let saved = unsafe { state_box::<M>(fmu_state) }
            .map_or_else(|| error("FMUstate is NULL or not a state of this FMU"), Ok)?;
        let image = inst.serialize(&saved.core)?;
        if size < image.len() {
            return error(format!("buffer of {size} bytes is smaller than the state ({} bytes)", image.len()));
        }
        // SAFETY: the host announced `size` writable bytes at `bytes` (contract 3), and
        // `image.len() <= size` was checked above; `fmi2Byte` (c_char) has u8's layout.
        let out = unsafe { slice_mut(bytes as *mut u8, image.len(), "serializedState") }?;
        out.copy_from_slice(&image);
        Ok(())
    })
}

pub unsafe fn deserialize_fmu_state<M: Model>(
    c: fmi2Component,
    bytes: *const fmi2Byte,
    size: usize,
    state_out: *mut fmi2FMUstate,
) -> fmi2Status {
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, "fmi2DeSerializeFMUstate", state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `size` readable bytes at `bytes` (contract 3); c_char has u8's layout.
        let image = unsafe { slice(bytes as *const u8, size, "serializedState") }?;
        // SAFETY: a non-null `state_out` is the host's writable slot (contract 3).
        let slot = unsafe { state_out.as_mut() }.map_or_else(|| error("FMUstate is NULL"), Ok)?;
        let core = inst.deserialize(image)?;
        // SAFETY: `*slot` is NULL or a state of this library (contract 4).
        match unsafe { state_box::<M>(*slot) } {
            Some(existing) => existing.core = core,
            None => *slot = StateBox::create(inst, core),
        }
        Ok(())
    })
}

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
        let out = unsafe { value.as_mut() }.map_or_else(|| error("value is NULL"), Ok)?;
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
        let out = unsafe { value.as_mut() }.map_or_else(|| error("value is NULL"), Ok)?;
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
    let reason = format!(
        "{function} is not supported by {} (a Co-Simulation FMU with synchronous steps)",
        M::INFO.model_identifier
    );
    // SAFETY: `c` per contracts 1 and 2.
    with_instance(unsafe { instance_ref::<M>(c) }, function, state::ANY, |_| error(reason.clone()))
}
