//! Messages to the host's logger callback.

use crate::ffi::fmi2CallbackFunctions;
use crate::status::Status;
use std::ffi::{CStr, CString};

/// The host's logger and environment, copied at instantiation.
#[derive(Clone, Copy)]
pub struct Logger {
    callbacks: fmi2CallbackFunctions,
}

// SAFETY: the callback struct is plain data given by the host; FMI 2.0 lets a host call an
// instance from any thread (one at a time), and the logger is the host's to make thread-safe.
unsafe impl Send for Logger {}

impl Logger {
    /// `None` when the host passed no logger function.
    pub fn new(callbacks: &fmi2CallbackFunctions) -> Option<Logger> {
        callbacks.logger.map(|_| Logger { callbacks: *callbacks })
    }

    /// Sends `message` with the literal format `"%s"`, so '%' in messages is harmless.
    pub fn log(&self, instance: &CStr, status: Status, category: &str, message: &str) {
        let Some(logger) = self.callbacks.logger else { return };
        let category = c_string(category);
        let message = c_string(message);
        // SAFETY: every pointer is a valid NUL-terminated string for the duration of the call.
        unsafe {
            logger(
                self.callbacks.componentEnvironment,
                instance.as_ptr(),
                status.to_c(),
                category.as_ptr(),
                c"%s".as_ptr(),
                message.as_ptr(),
            )
        }
    }
}

/// A C string of `text`, with interior NUL bytes replaced so nothing is lost silently.
pub fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', "\\0")).unwrap_or_default()
}
