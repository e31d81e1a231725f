//! How the process ends: cleanly on SIGINT/SIGTERM/SIGHUP, conventional for pipes, and never
//! silently from inside an FMU.

use std::sync::OnceLock;

use cosim_engine::interrupt::Interrupt;

static INTERRUPT: OnceLock<Interrupt> = OnceLock::new();

/// The request that SIGINT, SIGTERM and SIGHUP make (handlers installed on first use): runs
/// stop at the next communication point with complete rows, a summary and no temporary folder
/// left, instead of dying mid-row.
pub fn interrupt() -> Interrupt {
    INTERRUPT
        .get_or_init(|| {
            let interrupt = Interrupt::new();
            #[cfg(unix)]
            for signal in [signal_hook::consts::SIGINT, signal_hook::consts::SIGTERM, signal_hook::consts::SIGHUP] {
                // Failing to install leaves that signal's default (end the process): nothing worse than before.
                let _ =
                    signal_hook::flag::register_usize(signal, std::sync::Arc::clone(interrupt.flag()), signal as usize);
            }
            interrupt
        })
        .clone()
}

/// The signal that interrupted the command, if one did.
pub fn interrupting_signal() -> Option<usize> {
    INTERRUPT.get().and_then(Interrupt::requested)
}

/// Ends the process as command-line tools do when the reader of their output went away
/// (`crane-cosim info x.fmu | head`): killed by SIGPIPE, which shells show as status 141 and
/// report quietly. Called after everything was dropped, so no temporary folder is left.
pub fn end_by_broken_pipe() -> ! {
    #[cfg(unix)]
    // SAFETY: restoring the default disposition and raising a signal have no preconditions.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
        libc::raise(libc::SIGPIPE);
    }
    std::process::exit(141)
}

/// True if the error (or one of its causes) is a write to a closed pipe.
pub fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error
        .chain()
        .any(|cause| cause.downcast_ref::<std::io::Error>().is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe))
}

#[cfg(unix)]
mod exit_guard {
    use std::sync::atomic::{AtomicBool, Ordering};

    static MAIN_IS_EXITING: AtomicBool = AtomicBool::new(false);

    /// Runs at `exit()`: unless `main` is the one exiting, code loaded into the process (an FMU's
    /// library constructor or one of its functions) called `exit`, and its status — often 0 —
    /// would pass an unfinished run off as a success.
    extern "C" fn refuse_foreign_exit() {
        if !MAIN_IS_EXITING.load(Ordering::SeqCst) {
            let message = b"error: an FMU library ended the process by calling exit(); the run did not finish\n";
            // SAFETY: writing a static buffer to stderr and leaving without further atexit handlers.
            unsafe {
                libc::write(libc::STDERR_FILENO, message.as_ptr().cast(), message.len());
                libc::_exit(1);
            }
        }
    }

    /// Armed while alive; dropping it (also while unwinding) lets `main` exit normally.
    pub struct ExitGuard(());

    impl ExitGuard {
        pub fn arm() -> Self {
            // SAFETY: registers a handler that only reads an atomic and calls async-signal-safe functions.
            unsafe { libc::atexit(refuse_foreign_exit) };
            Self(())
        }
    }

    impl Drop for ExitGuard {
        fn drop(&mut self) {
            MAIN_IS_EXITING.store(true, Ordering::SeqCst);
        }
    }
}

#[cfg(unix)]
pub use exit_guard::ExitGuard;

/// Without `atexit` nothing is guarded.
#[cfg(not(unix))]
pub struct ExitGuard(());

#[cfg(not(unix))]
impl ExitGuard {
    pub fn arm() -> Self {
        Self(())
    }
}
