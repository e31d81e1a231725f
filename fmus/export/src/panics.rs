//! Panics inside an FMU are reported to the FMI logger of the instance whose call panicked, never
//! printed to the host's stderr: Rust's default panic hook would write a message (and maybe a
//! backtrace) into the host's console, although the entry points catch every panic and turn it
//! into `fmi2Fatal`.
//!
//! The hook is process-wide for the copy of `std` it is installed in; an FMU library (a cdylib)
//! has its own copy, so the FMU's hook never sees the host's panics.
//!
//! How a report reaches the right logger without per-call thread-local state: every entry point
//! runs its work through [`catch`], which counts the calls in progress (one atomic increment and
//! decrement, where a thread-local costs a `__tls_get_addr` call per access in a shared library).
//! While a call is in progress the hook only formats the report (message and location) and
//! leaves it in a thread-local slot; the `catch` on the same thread that stopped the unwinding
//! hands it to the caller ([`take_report`]), which logs it to its instance's logger. So the
//! thread-local is touched only when a panic happens, and the report goes to the logger of the
//! call it unwound out of: the hook and the catch run on the panicking thread, and the innermost
//! `catch` takes it. An FMU library runs code only inside its entry points, so there every panic
//! is inside a call. Where the exporter is linked into a Rust program (the in-process tests),
//! a panic outside FMI calls prints as usual while no FMI call is in progress in the process; one
//! that happens on another thread during an FMI call is left in that thread's slot unprinted
//! (replaced by its next report, if any).

use std::any::Any;
use std::cell::Cell;
use std::panic::{catch_unwind, AssertUnwindSafe, PanicHookInfo};
use std::ptr::null_mut;
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::sync::Once;

/// FMI calls in progress in this library, on every thread. Relaxed: the hook reads the count on
/// the thread whose own increment it has to see, which program order guarantees.
static CALLS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// The report of the last panic of this thread during an FMI call that no `catch` has taken
    /// yet, from `Box::into_raw`, or null. A plain pointer (no destructor): a thread-local with a
    /// destructor would pin the library in memory after `dlclose` on some platforms.
    static REPORT: Cell<*mut String> = const { Cell::new(null_mut()) };
}

/// Installs the hook, once per library. The hook is a function item, so the box that holds it
/// allocates nothing that an unload of the library could leak.
pub fn install_hook() {
    static INSTALLED: Once = Once::new();
    INSTALLED.call_once(|| std::panic::set_hook(Box::new(hook)));
}

fn hook(info: &PanicHookInfo) {
    if CALLS.load(Relaxed) == 0 {
        eprintln!("{info}");
        return;
    }
    let report = Box::into_raw(Box::new(info.to_string()));
    let unclaimed = REPORT.replace(report);
    if !unclaimed.is_null() {
        // SAFETY: every non-null pointer in the slot came from `Box::into_raw` above, and was just
        // taken out of it, so this is its only owner.
        drop(unsafe { Box::from_raw(unclaimed) });
    }
}

/// Runs `f`, catching a panic, as an FMI call: a panic inside is reported through the hook to
/// [`take_report`] instead of stderr.
#[inline]
pub fn catch<T>(f: impl FnOnce() -> T) -> Result<T, Box<dyn Any + Send>> {
    CALLS.fetch_add(1, Relaxed);
    let result = catch_unwind(AssertUnwindSafe(f));
    CALLS.fetch_sub(1, Relaxed);
    result
}

/// The report (message and location) of the panic that [`catch`] just caught on this thread, if
/// the hook wrote one.
#[cold]
pub fn take_report() -> Option<String> {
    let report = REPORT.replace(null_mut());
    // SAFETY: a non-null pointer in the slot came from `Box::into_raw` in the hook, and was just
    // taken out of it, so this is its only owner.
    (!report.is_null()).then(|| *unsafe { Box::from_raw(report) })
}
