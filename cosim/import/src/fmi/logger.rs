//! Host callbacks handed to `fmi2Instantiate`: the logger (formatted in
//! `logger.c`, stored here per instance) and `calloc`/`free`.

use std::collections::VecDeque;
use std::ffi::CStr;
use std::os::raw::{c_char, c_int, c_void};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Mutex;

use super::ffi;
use super::status::Status;

extern "C" {
    /// Defined in `logger.c`: formats with `vsnprintf`, then calls the sink
    /// stored in the first field of the [`LogContext`] behind `componentEnvironment`.
    fn crane_cosim_fmi2_logger(
        componentEnvironment: ffi::fmi2ComponentEnvironment,
        instanceName: ffi::fmi2String,
        status: ffi::fmi2Status,
        category: ffi::fmi2String,
        message: ffi::fmi2String,
        ...
    );
    fn calloc(nobj: usize, size: usize) -> *mut c_void;
    fn free(obj: *mut c_void);
}

/// How many messages of one instance are kept (oldest are dropped first).
pub const LOG_CAPACITY: usize = 256;

/// Which FMU log messages are also printed to standard error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LogEcho {
    /// Store only.
    Off,
    /// Print messages with status `fmi2Warning` or worse.
    #[default]
    Warnings,
    /// Print every message.
    All,
}

/// One message an FMU sent to the logger callback, already formatted.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LogMessage {
    /// The `instanceName` the FMU passed.
    pub instance_name: String,
    pub status: Status,
    pub category: String,
    pub message: String,
}

impl std::fmt::Display for LogMessage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "[{}] {} {}: {}", self.instance_name, self.status, self.category, self.message)
    }
}

type Sink = extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);

/// Per-instance logging context; `componentEnvironment` points to it.
///
/// It must stay at a fixed address for the lifetime of the FMU instance:
/// create it with [`LogContext::new`] (boxed) and keep the box alive until
/// after `fmi2FreeInstance`.
#[repr(C)]
pub struct LogContext {
    /// Read by `logger.c`; must stay the first field.
    sink: Sink,
    label: String,
    echo: LogEcho,
    buffer: Mutex<Buffer>,
    /// Messages received since creation (including dropped ones); only incremented with the
    /// buffer locked, but read without the lock so that [`LogContext::mark`], taken before every
    /// FMI call, costs one load.
    received: AtomicU64,
}

#[derive(Default)]
struct Buffer {
    messages: VecDeque<LogMessage>,
}

impl std::fmt::Debug for LogContext {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("LogContext").field("label", &self.label).field("echo", &self.echo).finish_non_exhaustive()
    }
}

impl LogContext {
    /// A new, empty context. `label` prefixes echoed lines (usually the instance name).
    pub fn new(label: impl Into<String>, echo: LogEcho) -> Box<Self> {
        Box::new(Self {
            sink: log_sink,
            label: label.into(),
            echo,
            buffer: Mutex::new(Buffer::default()),
            received: AtomicU64::new(0),
        })
    }

    /// The callback table to pass to `fmi2Instantiate`, pointing back at `self`.
    ///
    /// The returned struct (and `self`) must outlive the instance.
    pub fn callbacks(&self) -> ffi::fmi2CallbackFunctions {
        ffi::fmi2CallbackFunctions {
            logger: Some(crane_cosim_fmi2_logger),
            allocateMemory: Some(calloc),
            freeMemory: Some(free),
            stepFinished: None,
            componentEnvironment: self as *const Self as *mut c_void,
        }
    }

    /// All stored messages, oldest first.
    pub fn messages(&self) -> Vec<LogMessage> {
        self.lock().messages.iter().cloned().collect()
    }

    /// The most recent message, if any.
    pub fn last_message(&self) -> Option<LogMessage> {
        self.lock().messages.back().cloned()
    }

    /// Number of stored messages.
    pub fn len(&self) -> usize {
        self.lock().messages.len()
    }

    /// True if no message is stored.
    pub fn is_empty(&self) -> bool {
        self.lock().messages.is_empty()
    }

    /// Forgets all stored messages.
    pub fn clear(&self) {
        self.lock().messages.clear();
    }

    /// A marker for "now"; pass it to [`LogContext::since`] after an FMI call
    /// to get what the FMU logged during that call.
    pub fn mark(&self) -> u64 {
        self.received.load(Ordering::Acquire)
    }

    /// Stored messages received after `mark` was taken, oldest first.
    pub fn since(&self, mark: u64) -> Vec<LogMessage> {
        let buffer = self.lock();
        let received = self.received.load(Ordering::Acquire);
        let new = received.saturating_sub(mark).min(buffer.messages.len() as u64) as usize;
        buffer.messages.iter().skip(buffer.messages.len() - new).cloned().collect()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Buffer> {
        self.buffer.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
    }

    fn push(&self, message: LogMessage) {
        let print = match self.echo {
            LogEcho::Off => false,
            LogEcho::Warnings => message.status != Status::Ok,
            LogEcho::All => true,
        };
        if print {
            eprintln!("{}: {message}", self.label);
        }
        let mut buffer = self.lock();
        if buffer.messages.len() == LOG_CAPACITY {
            buffer.messages.pop_front();
        }
        buffer.messages.push_back(message);
        self.received.fetch_add(1, Ordering::Release);
    }
}

fn lossy(text: *const c_char) -> String {
    if text.is_null() {
        String::new()
    } else {
        // SAFETY: logger.c and FMUs pass NUL-terminated strings valid for the call.
        unsafe { CStr::from_ptr(text) }.to_string_lossy().into_owned()
    }
}

/// Stores one message in the log context at `environment` (what the FMI 3.0 logger and the
/// importer's own notes use; FMI 2.0 messages come through `logger.c`).
pub(super) fn sink(
    environment: *mut c_void,
    instance_name: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    log_sink(environment, instance_name, status, category, message)
}

/// Receives every formatted message from `logger.c`. Never unwinds into C.
extern "C" fn log_sink(
    environment: *mut c_void,
    instance_name: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    let _ = std::panic::catch_unwind(|| {
        if environment.is_null() {
            return;
        }
        // SAFETY: componentEnvironment is only ever set to a live LogContext by `callbacks`.
        let context = unsafe { &*(environment as *const LogContext) };
        // FMI 3.0's logger passes no instance name: the context's label is the instance's.
        let instance_name = match lossy(instance_name) {
            name if name.is_empty() => context.label.clone(),
            name => name,
        };
        context.push(LogMessage {
            instance_name,
            status: Status::from_raw(status),
            category: lossy(category),
            message: lossy(message),
        });
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn log(context: &LogContext, status: ffi::fmi2Status, format: &CStr, argument: &CStr) {
        let callbacks = context.callbacks();
        let logger = callbacks.logger.expect("logger is set");
        // SAFETY: called as an FMU calls it: the environment is `context`, alive for the call,
        // and the format's one `%s` (or none) is matched by the one string argument.
        unsafe {
            logger(
                callbacks.componentEnvironment,
                c"inst".as_ptr(),
                status,
                c"logError".as_ptr(),
                format.as_ptr(),
                argument.as_ptr(),
            );
        }
    }

    #[test]
    fn formats_printf_style_and_stores_per_instance() {
        let a = LogContext::new("a", LogEcho::Off);
        let b = LogContext::new("b", LogEcho::Off);
        log(&a, ffi::fmi2Error, c"value %s is invalid", c"NaN");
        log(&b, ffi::fmi2OK, c"%s", c"100% literal");
        let last = a.last_message().expect("a message");
        assert_eq!(last.message, "value NaN is invalid");
        assert_eq!(last.status, Status::Error);
        assert_eq!(last.category, "logError");
        assert_eq!(last.instance_name, "inst");
        assert_eq!(b.messages().len(), 1);
        assert_eq!(b.last_message().map(|m| m.message), Some("100% literal".to_string()));
    }

    #[test]
    fn a_message_without_an_instance_name_carries_the_contexts() {
        // FMI 3.0's logger passes no instance name: the message is the context's instance's.
        let context = LogContext::new("pendulum", LogEcho::Off);
        let environment = &*context as *const LogContext as *mut c_void;
        sink(environment, c"".as_ptr(), 3, c"logStatusError".as_ptr(), c"refused".as_ptr());
        let message = context.last_message().expect("stored");
        assert_eq!(message.instance_name, "pendulum");
        assert!(message.to_string().starts_with("[pendulum] "), "{message}");
    }

    #[test]
    fn long_messages_are_not_truncated() {
        let context = LogContext::new("long", LogEcho::Off);
        let long = "x".repeat(5000);
        let argument = std::ffi::CString::new(long.clone()).expect("no NUL");
        log(&context, ffi::fmi2Warning, c"<%s>", &argument);
        assert_eq!(context.last_message().map(|m| m.message), Some(format!("<{long}>")));
    }

    #[test]
    fn keeps_only_the_newest_messages() {
        let context = LogContext::new("ring", LogEcho::Off);
        for i in 0..LOG_CAPACITY + 10 {
            let argument = std::ffi::CString::new(i.to_string()).expect("no NUL");
            log(&context, ffi::fmi2OK, c"%s", &argument);
        }
        assert_eq!(context.len(), LOG_CAPACITY);
        assert_eq!(context.messages()[0].message, "10");
        let mark = context.mark();
        assert!(context.since(mark).is_empty());
        log(&context, ffi::fmi2Error, c"%s", c"new");
        let new = context.since(mark);
        assert_eq!(new.len(), 1);
        assert_eq!(new[0].message, "new");
        assert_eq!(context.since(0).len(), LOG_CAPACITY);
    }

    #[test]
    fn allocator_callbacks_zero_memory() {
        let context = LogContext::new("alloc", LogEcho::Off);
        let callbacks = context.callbacks();
        let (allocate, release) = (callbacks.allocateMemory.expect("set"), callbacks.freeMemory.expect("set"));
        // SAFETY: 16 objects of 8 bytes are 128 bytes, all read only after the null check, and
        // the block goes back to the same allocator's free once.
        unsafe {
            let memory = allocate(16, 8) as *mut u8;
            assert!(!memory.is_null());
            assert!(std::slice::from_raw_parts(memory, 128).iter().all(|&b| b == 0));
            release(memory as *mut c_void);
        }
    }
}
