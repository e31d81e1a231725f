//! Panics inside an FMU are reported to the FMI logger of the instance whose call panicked, never
//! printed to the host's stderr: Rust's default panic hook would write a message (and maybe a
//! backtrace) into the host's console, although the entry points catch every panic and turn it
//! into `fmi2Fatal`.
//!
//! The hook is process-wide for the copy of `std` it is installed in; an FMU library (a cdylib)
//! has its own copy, so the FMU's hook never sees the host's panics. Where the exporter is linked
//! into a Rust program (the in-process tests), panics outside FMI calls still print as usual.

use crate::logging::Logger;
use crate::status::Status;
use std::cell::Cell;
use std::ffi::{c_char, CStr};
use std::panic::PanicHookInfo;
use std::ptr::null;
use std::sync::Once;

thread_local! {
    /// The logger and instance name of the FMI call this thread is running, or nulls. Plain
    /// pointers (no destructor): a thread-local with a destructor would pin the library in
    /// memory after `dlclose` on some platforms.
    static CALLER: Cell<(*const Logger, *const c_char)> = const { Cell::new((null(), null())) };
}

/// Installs the hook, once per library. The hook is a function item, so the box that holds it
/// allocates nothing that an unload of the library could leak.
pub fn install_hook() {
    static INSTALLED: Once = Once::new();
    INSTALLED.call_once(|| std::panic::set_hook(Box::new(hook)));
}

fn hook(info: &PanicHookInfo) {
    let (logger, name) = CALLER.get();
    // SAFETY: `reporting_to` sets the pointers only for the duration of a call that borrows both.
    match unsafe { (logger.as_ref(), name.as_ref()) } {
        (Some(logger), Some(_)) => {
            // SAFETY: as above; the name is a NUL-terminated string.
            let name = unsafe { CStr::from_ptr(name) };
            logger.log(name, Status::Fatal, "logStatusError", &format!("internal error: {info}"));
        }
        _ => eprintln!("{info}"),
    }
}

/// Runs `f` (which must not unwind: callers wrap their work in `catch_unwind`) with panics
/// reported to `logger` under `name`.
///
/// # Safety
/// `logger` and `name` (a NUL-terminated string) must stay valid until `f` returns.
pub unsafe fn reporting_to<T>(logger: *const Logger, name: *const c_char, f: impl FnOnce() -> T) -> T {
    // One lookup of the thread-local (in a shared library each costs a call), for both writes.
    CALLER.with(|caller| {
        let previous = caller.replace((logger, name));
        let result = f();
        caller.set(previous);
        result
    })
}
