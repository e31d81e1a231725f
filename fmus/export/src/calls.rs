//! The entry points' work that FMI 2.0 and FMI 3.0 share, as generic functions: the panic
//! barrier and state-machine check of every call ([`with_instance`]), the pointer and array
//! checks, instantiation's common part, freeing, and the FMU-state functions (get, set, free,
//! serialize), whose C signatures are the same in both versions up to names. The version
//! layers ([`crate::fmi2::api`], [`crate::fmi3::api`]) convert their C types and name the
//! function for messages.
//!
//! # Safety
//! Each `pub unsafe fn` here relies on what both standards require of the host, and on nothing
//! else:
//! 1. *Instance*: any `c` is accepted: it is dereferenced only while `crate::live` lists it as
//!    an instance of this model (NULL, foreign and freed pointers are refused unread).
//! 2. *One call at a time per instance* (FMI 2.0 §2.1.5, FMI 3.0 §2.2.1: an FMU need not be
//!    thread safe for one instance), so the `&mut Instance` of a call is the only reference to
//!    it, and no call frees an instance or FMU state that another call is using.
//! 3. *Arrays*: a non-null array argument holds the announced number of elements, readable for
//!    inputs and writable for outputs, for the duration of the call; strings are
//!    NUL-terminated.
//! 4. *FMU states*: as instances, dereferenced only while listed as live states of this model.
#![allow(clippy::missing_safety_doc)]

use crate::instance::{error, Core, Creation, Failure, Instance, Outcome};
use crate::live;
use crate::logging::Logger;
use crate::model::{Environment, Model};
use crate::panics;
use crate::state::{self, Mask, Standard, State};
use crate::status::Status;
use std::ffi::{c_char, c_int, c_void, CStr};
use std::path::PathBuf;

/// An instance or FMU state as the C API passes it (`fmi2Component`, `fmi3Instance`,
/// `fmi2FMUstate`, `fmi3FMUState` are all `void*`).
pub type Handle = *mut c_void;

/// An FMU state (`fmi2FMUstate`, `fmi3FMUState`): a snapshot of an instance's core. `crate::live` lists it with the
/// instance that created it (its owner), which frees it in `fmi2FreeInstance` if the host has
/// not freed it by then; other instances of the same FMU may use it.
struct StateBox<M: Model> {
    core: Core<M>,
}

impl<M: Model> StateBox<M> {
    /// A new state owned by `owner`, listed as live, as the handle the host gets.
    fn create(owner: &Instance<M>, core: Core<M>) -> Handle {
        let handle = Box::into_raw(Box::new(StateBox { core }));
        live::add(handle as *const StateBox<M>, owner as *const Instance<M> as usize);
        handle as Handle
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

/// Runs `f` on `instance` (`None`: the host passed no instance of this FMU) if `function` is
/// allowed in its state.
pub fn with_instance<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    mask: Mask,
    f: impl FnOnce(&mut Instance<M>) -> Outcome,
) -> c_int {
    // A null or foreign pointer (or an instance of the other FMI version) has no logger to
    // report to; the status is all we can give.
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

/// The instance behind `c`, if `crate::live` lists `c` as a live instance of `M` created
/// through the API of `standard` (an instance is driven through the API that created it).
///
/// # Safety
/// Contracts 1 and 2 of the module: the returned reference is the only one for the call.
pub unsafe fn instance_ref<'a, M: Model>(c: Handle, standard: Standard) -> Option<&'a mut Instance<M>> {
    let ptr = c as *mut Instance<M>;
    if !live::contains(ptr as *const Instance<M>) {
        return None;
    }
    // SAFETY: listed, so a live Box<Instance<M>> from `instantiate` (nothing else is listed as
    // an Instance<M>); contract 2 makes this the only reference during the call.
    let instance = unsafe { &mut *ptr };
    (instance.standard == standard).then_some(instance)
}

/// Sends the panic hook's report (message and location) of the panic just caught to `logger`
/// under `name`, see `crate::panics`.
#[cold]
pub fn log_panic_report(logger: &Logger, name: &CStr) {
    if let Some(report) = panics::take_report() {
        logger.log(name, Status::Fatal, "logStatusError", &format!("internal error: {report}"));
    }
}

pub fn panic_message(panic: &Box<dyn std::any::Any + Send>) -> String {
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
pub unsafe fn slice<'a, T>(ptr: *const T, n: usize, what: &str) -> Outcome<&'a [T]> {
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
pub unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize, what: &str) -> Outcome<&'a mut [T]> {
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

/// The host's writable output slot `ptr`, refused as "`what` is NULL" if it is NULL.
///
/// # Safety
/// A non-null `ptr` is writable for `'a` and referenced by nothing else (contract 3).
pub unsafe fn host_slot<'a, T>(ptr: *mut T, what: &str) -> Outcome<&'a mut T> {
    // SAFETY: as the caller guarantees for a non-null `ptr`.
    unsafe { ptr.as_mut() }.map_or_else(|| error(format!("{what} is NULL")), Ok)
}

/// The host's strings `pointers`, each refused if NULL or not UTF-8 (as `what`).
///
/// # Safety
/// Each non-null element is NUL-terminated and valid for `'a` (contract 3).
pub unsafe fn string_args<'a>(pointers: &[*const c_char], what: &str) -> Outcome<Vec<&'a str>> {
    // SAFETY: as the caller guarantees, for each element.
    pointers.iter().map(|p| unsafe { string_arg(*p, what) }).collect()
}

/// A string from the host, borrowed for the duration of the call.
///
/// # Safety
/// A non-null `ptr` is NUL-terminated and valid for `'a` (contract 3).
pub unsafe fn string_arg<'a>(ptr: *const c_char, what: &str) -> Outcome<&'a str> {
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

/// `fmi2rs_model_description`, `fmi3rs_model_description`: the description of `M` in dialect
/// `D` copied into the host's buffer (see [`copy_description`]), rendered at each call so that
/// the library keeps no copy.
///
/// # Safety
/// A non-null `buffer` has `size` writable bytes.
pub unsafe fn model_description<D: crate::description::Dialect, M: Model>(buffer: *mut c_char, size: usize) -> usize {
    let text = crate::description::render::<D, M>().map(|description| description.xml);
    // SAFETY: the caller's buffer, passed on.
    unsafe { copy_description(text, buffer, size) }
}

/// A model description's text copied into the host's buffer as a NUL-terminated string,
/// truncated to `size` bytes; returns the size the whole text needs (NUL included).
///
/// # Safety
/// A non-null `buffer` has `size` writable bytes.
pub unsafe fn copy_description(text: Result<String, String>, buffer: *mut c_char, size: usize) -> usize {
    let text = text.unwrap_or_else(|e| format!("<!-- error: {e} -->"));
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

/// What a host passes to instantiate, once both versions' arguments are decoded.
pub struct Request<'a> {
    /// `fmi2Instantiate` or `fmi3InstantiateCoSimulation`, for messages.
    pub function: &'static str,
    /// The GUID (FMI 2.0) or instantiation token (FMI 3.0) of this binary's description.
    pub ours: &'a str,
    pub name: *const c_char,
    pub token: *const c_char,
    /// FMI 2.0 passes a `file:` URI, FMI 3.0 a path.
    pub resources: Resources,
    pub logging_on: bool,
    /// FMI 3.0's `time` variable (see [`Creation::time_vr`]).
    pub time_vr: Option<u32>,
}

/// Where the host says the FMU's resources are.
pub enum Resources {
    Uri(*const c_char),
    Path(*const c_char),
}

/// Creates an instance for `request`, or logs why not and returns NULL; `refuse` is the
/// version layer's own check of its other arguments (run inside the panic barrier).
///
/// # Safety
/// The strings in `request` are NULL or NUL-terminated (contract 3).
pub unsafe fn instantiate<M: Model>(
    request: Request,
    standard: Standard,
    logger: Logger,
    refuse: impl FnOnce() -> Result<(), String>,
) -> Handle {
    panics::install_hook();
    // SAFETY: `name` is NULL or NUL-terminated (contract 3).
    let label = crate::logging::c_string(unsafe { string_arg(request.name, "") }.unwrap_or_default());
    let function = request.function;
    let result = panics::catch(|| {
        refuse()?;
        // SAFETY: this function's contract, passed on.
        let (env, guid) = unsafe { decode_request(&request) }?;
        let creation = Creation { standard, logger, logging_on: request.logging_on, guid, time_vr: request.time_vr };
        Instance::<M>::new(env, creation).map(Box::new).map_err(|f| f.message)
    });
    let message = match result {
        Ok(Ok(instance)) => {
            let c = Box::into_raw(instance);
            live::add(c as *const Instance<M>, 0);
            return c as Handle;
        }
        Ok(Err(message)) => message,
        Err(panic) => {
            log_panic_report(&logger, &label);
            format!("internal error: {}", panic_message(&panic))
        }
    };
    logger.log(&label, Status::Error, "logStatusError", &format!("{function}: {message}"));
    std::ptr::null_mut()
}

/// The environment and GUID of an instance for `request`, or why there is none.
///
/// # Safety
/// As [`instantiate`].
unsafe fn decode_request(request: &Request) -> Result<(Environment, String), String> {
    // SAFETY: this function's contract (each string NULL or NUL-terminated), for all three.
    let instance_name = unsafe { string_arg(request.name, "instanceName") }.map_err(|f| f.message)?.to_owned();
    if instance_name.trim().is_empty() {
        return Err("instanceName is empty or blank (FMI requires a non-empty name)".to_owned());
    }
    let token_name = if request.function.starts_with("fmi2") { "fmuGUID" } else { "instantiationToken" };
    // SAFETY: as above.
    let given = unsafe { string_arg(request.token, token_name) }.map_err(|f| f.message)?;
    if given != request.ours {
        return Err(format!("{token_name} {} does not match this binary's {}", excerpt(given), request.ours));
    }
    let resource_dir = match request.resources {
        Resources::Uri(uri) if !uri.is_null() => {
            // SAFETY: as above.
            let uri = unsafe { string_arg(uri, "fmuResourceLocation") }.map_err(|f| f.message)?;
            resource_dir(uri).ok()
        }
        Resources::Path(path) if !path.is_null() => {
            // SAFETY: as above.
            let path = unsafe { string_arg(path, "resourcePath") }.map_err(|f| f.message)?;
            Some(PathBuf::from(path))
        }
        _ => None,
    };
    Ok((Environment { instance_name, resource_dir }, request.ours.to_owned()))
}

/// The most characters of a caller's string that a message quotes: a token or name can be as
/// long as the caller likes (a hostile modelDescription.xml, say), and the host echoes every
/// message, often twice.
const QUOTED_CHARACTERS: usize = 80;

/// `text` as a message quotes it: whole when short, else its start and how long it is.
fn excerpt(text: &str) -> String {
    match text.char_indices().nth(QUOTED_CHARACTERS) {
        None => text.to_owned(),
        Some((end, _)) => format!("{}… ({} characters)", &text[..end], text.chars().count()),
    }
}

pub unsafe fn free_instance<M: Model>(c: Handle, standard: Standard) {
    let ptr = c as *mut Instance<M>;
    // SAFETY: contract 1: `c` is dereferenced only if listed (inside `instance_ref`).
    if unsafe { instance_ref::<M>(c, standard) }.is_none() || !live::remove(ptr as *const Instance<M>) {
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
pub(crate) fn unfreed_states<M: Model>(c: Handle) -> usize {
    live::owned_count::<StateBox<M>>(c as usize)
}

/// `fmi?SetDebugLogging`.
///
/// # Safety
/// `c` per contracts 1 and 2; `n` category strings at `categories` (contract 3).
pub unsafe fn set_debug_logging<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    on: bool,
    n: usize,
    categories: *const *const c_char,
) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `n` category strings at `categories`, each NUL-terminated (contract 3).
        let names = unsafe { string_args(slice(categories, n, "categories")?, "category") }?;
        inst.set_debug_logging(on, &names)
    })
}

/// `fmi?GetFMUstate`.
///
/// # Safety
/// Contracts 1 to 4: `state_out` is NULL or the host's writable slot.
pub unsafe fn get_fmu_state<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    state_out: *mut Handle,
) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |inst| {
        // SAFETY: a non-null `state_out` is the host's writable slot (contract 3).
        let slot = unsafe { host_slot(state_out, "FMUstate") }?;
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

/// `fmi?SetFMUstate`.
///
/// # Safety
/// Contracts 1, 2 and 4.
pub unsafe fn set_fmu_state<M: Model>(instance: Option<&mut Instance<M>>, function: &str, fmu_state: Handle) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `fmu_state` is NULL or a state of this library (contract 4).
        let saved = unsafe { saved_state::<M>(fmu_state) }?;
        inst.restore(&saved.core);
        Ok(())
    })
}

/// `fmi?FreeFMUstate`.
///
/// # Safety
/// Contracts 1 to 4: `state_io` is NULL or the host's writable slot.
pub unsafe fn free_fmu_state<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    state_io: *mut Handle,
) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |_| {
        // SAFETY: a non-null `state_io` is the host's writable slot (contract 3).
        let slot = unsafe { host_slot(state_io, "FMUstate") }?;
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
unsafe fn state_box<'a, M: Model>(ptr: Handle) -> Option<&'a mut StateBox<M>> {
    let ptr = ptr as *mut StateBox<M>;
    if !live::contains(ptr as *const StateBox<M>) {
        return None;
    }
    // SAFETY: listed, so a live Box<StateBox<M>> from `create`; the only reference (contract 2).
    Some(unsafe { &mut *ptr })
}

/// The state at `fmu_state`, refused unless it is a live state of this FMU.
///
/// # Safety
/// As [`state_box`].
unsafe fn saved_state<'a, M: Model>(fmu_state: Handle) -> Outcome<&'a mut StateBox<M>> {
    // SAFETY: the caller's contract, passed on.
    unsafe { state_box::<M>(fmu_state) }.map_or_else(|| error("FMUstate is NULL or not a state of this FMU"), Ok)
}

/// `fmi?SerializedFMUstateSize`.
///
/// # Safety
/// Contracts 1 to 4: `size` is NULL or the host's writable slot.
pub unsafe fn serialized_fmu_state_size<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    fmu_state: Handle,
    size: *mut usize,
) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `fmu_state` is NULL or a state of this library (contract 4).
        let saved = unsafe { saved_state::<M>(fmu_state) }?;
        // SAFETY: a non-null `size` is the host's writable slot (contract 3).
        let out = unsafe { host_slot(size, "size") }?;
        *out = inst.serialize(&saved.core)?.len();
        Ok(())
    })
}

/// `fmi?SerializeFMUstate`.
///
/// # Safety
/// Contracts 1 to 4: `size` writable bytes at `bytes`.
pub unsafe fn serialize_fmu_state<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    fmu_state: Handle,
    bytes: *mut u8,
    size: usize,
) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `fmu_state` is NULL or a state of this library (contract 4).
        let saved = unsafe { saved_state::<M>(fmu_state) }?;
        let image = inst.serialize(&saved.core)?;
        if size < image.len() {
            return error(format!("buffer of {size} bytes is smaller than the state ({} bytes)", image.len()));
        }
        // SAFETY: the host announced `size` writable bytes at `bytes` (contract 3), and
        // `image.len() <= size` was checked above.
        let out = unsafe { slice_mut(bytes, image.len(), "serializedState") }?;
        out.copy_from_slice(&image);
        Ok(())
    })
}

/// `fmi?DeSerializeFMUstate`.
///
/// # Safety
/// Contracts 1 to 4: `size` readable bytes at `bytes`; `state_out` NULL or writable.
pub unsafe fn deserialize_fmu_state<M: Model>(
    instance: Option<&mut Instance<M>>,
    function: &str,
    bytes: *const u8,
    size: usize,
    state_out: *mut Handle,
) -> c_int {
    with_instance(instance, function, state::ANY_BUT_FATAL, |inst| {
        // SAFETY: `size` readable bytes at `bytes` (contract 3).
        let image = unsafe { slice(bytes, size, "serializedState") }?;
        // SAFETY: a non-null `state_out` is the host's writable slot (contract 3).
        let slot = unsafe { host_slot(state_out, "FMUstate") }?;
        let core = inst.deserialize(image)?;
        // SAFETY: `*slot` is NULL or a state of this library (contract 4).
        match unsafe { state_box::<M>(*slot) } {
            Some(existing) => existing.core = core,
            None => *slot = StateBox::create(inst, core),
        }
        Ok(())
    })
}

/// Entry points an FMU declares but does not support: an error with a message naming the
/// function and why.
pub fn unsupported<M: Model>(instance: Option<&mut Instance<M>>, function: &str, why: &str) -> c_int {
    let reason = format!("{function} is not supported by {} ({why})", M::INFO.model_identifier);
    with_instance(instance, function, state::ANY, |_| error(reason.clone()))
}

/// A value type of the variable tables as a C API passes its arrays, with the instance's getter
/// and setter for it: each version's getters and setters are one generic function over it
/// (`get_values` and `set_values` in [`crate::fmi2::api`] and [`crate::fmi3::api`]).
pub trait ValueArrays {
    /// The element type of the host's values array (`fmi2Real`, `fmi3Boolean`, ...).
    type C;
    /// An element as a set reads it: `C`, but a C boolean as its integer or byte, so that any
    /// nonzero value is true.
    type Read;
    /// Writes the values of `vrs` into `out` (the instance's getter of the type).
    fn get<M: Model>(inst: &mut Instance<M>, vrs: &[u32], out: &mut [Self::C]) -> Outcome;
    /// Sets `vrs` to `values`, all or none (the instance's setter of the type).
    ///
    /// # Safety
    /// String values are NUL-terminated (contract 3).
    unsafe fn set<M: Model>(inst: &mut Instance<M>, vrs: &[u32], values: &[Self::Read]) -> Outcome;
}

/// Real (FMI 3.0: Float64) values.
pub struct Real;
/// Integer (FMI 3.0: Int32) values.
pub struct Integer;
/// String values, NUL-terminated UTF-8 in the host's arrays.
pub struct Text;

/// [`ValueArrays`] for value types whose C elements are the instance's own values, read and
/// written as they are.
macro_rules! plain_value_arrays {
    ($($kind:ident: $c:ty => $get:ident, $set:ident;)*) => {$(
        impl ValueArrays for $kind {
            type C = $c;
            type Read = $c;
            fn get<M: Model>(inst: &mut Instance<M>, vrs: &[u32], out: &mut [$c]) -> Outcome {
                inst.$get(vrs, out)
            }
            unsafe fn set<M: Model>(inst: &mut Instance<M>, vrs: &[u32], values: &[$c]) -> Outcome {
                inst.$set(vrs, values)
            }
        }
    )*};
}

plain_value_arrays! {
    Real: f64 => get_real, set_real;
    Integer: i32 => get_integer, set_integer;
}

impl ValueArrays for Text {
    type C = *const c_char;
    type Read = *const c_char;
    fn get<M: Model>(inst: &mut Instance<M>, vrs: &[u32], out: &mut [*const c_char]) -> Outcome {
        inst.get_string(vrs, out)
    }
    unsafe fn set<M: Model>(inst: &mut Instance<M>, vrs: &[u32], values: &[*const c_char]) -> Outcome {
        // SAFETY: each element NUL-terminated (the caller's contract 3).
        inst.set_string(vrs, &unsafe { string_args(values, "value") }?)
    }
}

/// The six FMU-state functions of one version's `api` (get, set, free, serialized size,
/// serialize, deserialize), each the shared work above for that version's instances under
/// that version's C names: their signatures differ only in the C types. It expands where the
/// version's `instance_ref` and `Model` are in scope; `$byte` has `u8`'s layout.
macro_rules! fmu_state_api {
    (
        $instance:ty, $state:ty, $byte:ty, $status:ty;
        $get:literal, $set:literal, $free:literal, $size:literal, $serialize:literal, $deserialize:literal
    ) => {
        pub unsafe fn get_fmu_state<M: Model>(c: $instance, s: *mut $state) -> $status {
            // SAFETY: contracts 1 to 4, passed on.
            unsafe { $crate::calls::get_fmu_state(instance_ref::<M>(c), $get, s) }
        }

        pub unsafe fn set_fmu_state<M: Model>(c: $instance, s: $state) -> $status {
            // SAFETY: contracts 1 to 4, passed on.
            unsafe { $crate::calls::set_fmu_state(instance_ref::<M>(c), $set, s) }
        }

        pub unsafe fn free_fmu_state<M: Model>(c: $instance, s: *mut $state) -> $status {
            // SAFETY: contracts 1 to 4, passed on.
            unsafe { $crate::calls::free_fmu_state(instance_ref::<M>(c), $free, s) }
        }

        pub unsafe fn serialized_fmu_state_size<M: Model>(c: $instance, s: $state, size: *mut usize) -> $status {
            // SAFETY: contracts 1 to 4, passed on.
            unsafe { $crate::calls::serialized_fmu_state_size(instance_ref::<M>(c), $size, s, size) }
        }

        pub unsafe fn serialize_fmu_state<M: Model>(
            c: $instance,
            s: $state,
            bytes: *mut $byte,
            size: usize,
        ) -> $status {
            // SAFETY: contracts 1 to 4, passed on; the byte type has u8's layout.
            unsafe { $crate::calls::serialize_fmu_state(instance_ref::<M>(c), $serialize, s, bytes.cast(), size) }
        }

        pub unsafe fn deserialize_fmu_state<M: Model>(
            c: $instance,
            bytes: *const $byte,
            size: usize,
            s: *mut $state,
        ) -> $status {
            // SAFETY: contracts 1 to 4, passed on; the byte type has u8's layout.
            unsafe { $crate::calls::deserialize_fmu_state(instance_ref::<M>(c), $deserialize, bytes.cast(), size, s) }
        }
    };
}
pub(crate) use fmu_state_api;
