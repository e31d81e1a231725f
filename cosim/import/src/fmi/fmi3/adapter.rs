//! The adapter behind each FMI 3.0 component: the FMI 3.0 instance, its functions, and what the
//! FMI 2.0 calls need to remember between calls; [`instantiate`] creates it.

use std::ffi::{c_char, c_int, c_void, CString};
use std::path::Path;

use super::elements::Elements;
use super::types::Fmi3Element;
use super::Functions;
use crate::fmi::ffi;
use fmi3_sys as f3;

/// One FMI 3.0 instance as the FMI 2.0 functions of [`super::functions`] see it: the pointer they get
/// as `fmi2Component` is a `Box<Adapter>`.
pub(super) struct Adapter {
    pub(super) instance: f3::fmi3Instance,
    pub(super) functions: Functions,
    /// The log context, for the messages the adapter itself reports.
    pub(super) log: *mut c_void,
    pub(super) tolerance: Option<f64>,
    pub(super) start: f64,
    pub(super) stop: Option<f64>,
    /// What the last `fmi3DoStep` reported.
    pub(super) terminate_requested: bool,
    pub(super) last_successful_time: f64,
    /// The rows reached through a conversion or as array elements.
    pub(super) elements: Elements,
}

/// `fmi2Instantiate` for an FMI 3.0 FMU: `fmi3InstantiateCoSimulation` with the importer's log
/// context as instance environment; the component is the adapter (NULL if the FMU refused).
///
/// # Safety
/// The strings are valid and NUL-terminated; `callbacks.componentEnvironment` is a live log
/// context that outlives the instance (as for `fmi2Instantiate`).
#[allow(clippy::too_many_arguments)] // fmi3InstantiateCoSimulation's own arguments, and the elements
pub unsafe fn instantiate(
    functions: &Functions,
    name: &CString,
    token: &CString,
    resource_dir: &Path,
    callbacks: &ffi::fmi2CallbackFunctions,
    visible: bool,
    logging_on: bool,
    elements: &[Fmi3Element],
) -> ffi::fmi2Component {
    let mut folder = resource_dir.to_string_lossy().into_owned();
    if !folder.ends_with(std::path::MAIN_SEPARATOR) {
        folder.push(std::path::MAIN_SEPARATOR);
    }
    let Ok(folder) = CString::new(folder) else { return std::ptr::null_mut() };
    // SAFETY: valid strings and a live environment (this function's contract); no intermediate
    // variables are requested (NULL, 0), and the log callback matches fmi3LogMessageCallback.
    let instance = unsafe {
        (functions.fmi3InstantiateCoSimulation)(
            name.as_ptr(),
            token.as_ptr(),
            folder.as_ptr(),
            visible,
            logging_on,
            false,
            false,
            std::ptr::null(),
            0,
            callbacks.componentEnvironment,
            Some(log_message),
            None,
        )
    };
    if instance.is_null() {
        return std::ptr::null_mut();
    }
    let adapter = Adapter {
        instance,
        functions: *functions,
        log: callbacks.componentEnvironment,
        tolerance: None,
        start: 0.0,
        stop: None,
        terminate_requested: false,
        last_successful_time: 0.0,
        elements: Elements::new(elements),
    };
    Box::into_raw(Box::new(adapter)) as ffi::fmi2Component
}

/// The FMI 3.0 logger: the log context's sink, with no instance name (FMI 3.0 passes none).
unsafe extern "C" fn log_message(
    environment: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    crate::fmi::logger::sink(environment, c"".as_ptr(), status, category, message);
}

/// The adapter behind a component.
///
/// # Safety
/// `c` is a component [`instantiate`] returned and not yet freed, used by one call at a time.
pub(super) unsafe fn adapter<'a>(c: ffi::fmi2Component) -> &'a mut Adapter {
    // SAFETY: this function's contract.
    unsafe { &mut *(c as *mut Adapter) }
}

/// Reports a message of the adapter itself to the instance's log.
pub(super) fn report(adapter: &Adapter, status: c_int, message: &str) {
    let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
    crate::fmi::logger::sink(adapter.log, c"".as_ptr(), status, c"importer".as_ptr(), text.as_ptr());
}
