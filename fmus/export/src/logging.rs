//! Messages to the host's logger callback, FMI 2.0's or FMI 3.0's.

use crate::ffi::fmi2CallbackFunctions;
use crate::status::Status;
use fmi3_sys::{fmi3InstanceEnvironment, fmi3LogMessageCallback};
use std::ffi::{CStr, CString};

/// Log categories declared in the model description.
pub const LOG_CATEGORIES: &[(&str, &str)] = &[
    ("logStatusError", "Errors (always reported)"),
    ("logStatusWarning", "Warnings"),
    ("logCalls", "Every FMI function call"),
];

/// The host's logger and environment, copied at instantiation.
#[derive(Clone, Copy)]
pub enum Logger {
    /// FMI 2.0: a variadic, printf-style logger that also takes the instance name.
    Fmi2(fmi2CallbackFunctions),
    /// FMI 3.0: `(environment, status, category, message)`; the host may pass no logger.
    Fmi3 { environment: fmi3InstanceEnvironment, callback: fmi3LogMessageCallback },
}

// SAFETY: the callbacks and environments are plain data given by the host; FMI lets a host call
// an instance from any thread (one call at a time), and the logger is the host's to make
// thread-safe.
unsafe impl Send for Logger {}

impl Logger {
    /// `None` when the host passed no logger function (FMI 2.0 requires one).
    pub fn new(callbacks: &fmi2CallbackFunctions) -> Option<Logger> {
        callbacks.logger.map(|_| Logger::Fmi2(*callbacks))
    }

    /// Sends `message` of the instance `instance`. FMI 2.0: with the literal format `"%s"`, so
    /// '%' in messages is harmless; FMI 3.0 passes the text as it is and has no instance name
    /// argument (the host knows its instance by the environment).
    pub fn log(&self, instance: &CStr, status: Status, category: &str, message: &str) {
        let category = c_string(category);
        let message = c_string(message);
        match self {
            Logger::Fmi2(callbacks) => {
                let Some(logger) = callbacks.logger else { return };
                // SAFETY: every pointer is a valid NUL-terminated string for the duration of the call.
                unsafe {
                    logger(
                        callbacks.componentEnvironment,
                        instance.as_ptr(),
                        status.to_c(),
                        category.as_ptr(),
                        c"%s".as_ptr(),
                        message.as_ptr(),
                    )
                }
            }
            Logger::Fmi3 { environment, callback } => {
                let Some(logger) = callback else { return };
                // SAFETY: both strings are valid and NUL-terminated for the duration of the call;
                // the environment is the host's own pointer, handed back unchanged.
                unsafe { logger(*environment, status.to_c(), category.as_ptr(), message.as_ptr()) }
            }
        }
    }
}

/// A C string of `text`, with interior NUL bytes replaced so nothing is lost silently.
pub fn c_string(text: &str) -> CString {
    CString::new(text.replace('\0', "\\0")).unwrap_or_default()
}

/// A number in a message, written as Rust writes an `f64` (the shortest text that reads back as
/// the same number) but in exponent form when it is very small or very large: `{}` alone spells
/// out every digit, 330 characters for a step of 5e-324 s and 301 for 1e300.
#[derive(Clone, Copy, Debug)]
pub struct Short(pub f64);

impl std::fmt::Display for Short {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        // The thresholds of `{:?}`, which however writes integers as `12.0`.
        if v.is_finite() && v != 0.0 && !(1e-4..1e16).contains(&v.abs()) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
        }
    }
}
