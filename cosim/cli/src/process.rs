//! How the process ends: cleanly on SIGINT/SIGTERM/SIGHUP, conventional for pipes, and never
//! silently from inside an FMU.

use std::sync::OnceLock;
use std::time::Duration;

use cosim_engine::interrupt::Interrupt;

static INTERRUPT: OnceLock<Interrupt> = OnceLock::new();

/// How long a run may take to stop after the first SIGINT/SIGTERM/SIGHUP before it is ended
/// as hung (an FMU call that does not return cannot be stopped between steps).
pub const GRACE: Duration = Duration::from_secs(5);

/// The request that SIGINT, SIGTERM and SIGHUP make (handlers installed on first use): runs
/// stop at the next communication point with complete rows, a summary and no temporary folder
/// left, instead of dying mid-row. If an FMU call still has not returned [`GRACE`] after the
/// first signal, or a second signal comes, the process ends at once ([`watchdog`]).
pub fn interrupt() -> Interrupt {
    INTERRUPT
        .get_or_init(|| {
            let interrupt = Interrupt::new();
            #[cfg(unix)]
            watchdog::watch_signals(&interrupt);
            interrupt
        })
        .clone()
}

/// Ends the run whose single FMU call takes longer than `limit` (`--step-timeout`).
pub fn set_step_timeout(limit: Duration) {
    #[cfg(unix)]
    watchdog::watch_calls(limit);
    #[cfg(not(unix))]
    let _ = limit;
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
    /// would pass an unfinished run off as a success. The run's computed rows and summary are
    /// written and the temporary folders removed first (the handler runs in the exiting thread,
    /// not in a signal handler, so it may lock and write files).
    extern "C" fn refuse_foreign_exit() {
        if !MAIN_IS_EXITING.load(Ordering::SeqCst) {
            // Unwinding out of an atexit handler is undefined: any panic ends here.
            let _ = std::panic::catch_unwind(|| {
                let message = match fmu_import::watch::current() {
                    Some(call) => format!(
                        "error: an FMU library ended the process by calling exit() in {call} of instance '{}'; \
                         the run did not finish (the rows computed so far are written)",
                        call.instance
                    ),
                    None => "error: an FMU library ended the process by calling exit(); the run did not finish".into(),
                };
                super::watchdog::end_now(cosim_engine::summary::RunStatus::Failed, &message, 1);
            });
            // SAFETY: leaving without further atexit handlers.
            unsafe { libc::_exit(1) };
        }
    }

    /// Armed while alive; dropping it (also while unwinding) lets `main` exit normally.
    pub struct ExitGuard(());

    impl ExitGuard {
        /// Guards `exit()` and crashes inside an FMU (see [`super::crash`]).
        pub fn arm() -> Self {
            // SAFETY: registers a handler that neither unwinds nor returns while a run is on.
            unsafe { libc::atexit(refuse_foreign_exit) };
            super::crash::watch();
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

/// A crash inside an FMU library (the FMUs run in this process) ends the run as `exit()` does:
/// with every computed row in the results file, the summary and no temporary folder left, and
/// a message naming the signal and the FMU call, instead of losing the rows not yet written.
///
/// The work cannot be done in the signal handler (it locks, allocates and writes files), so the
/// handler only wakes a thread waiting on a pipe (one `write`, which is async-signal-safe) and
/// waits for it to end the process. Should that thread not manage within `CRASH_WAIT` (10 s; the
/// crashed code holds a lock it needs), the crash goes on as it would have without the handler.
/// A SIGSEGV or SIGBUS outside an FMU call goes first to the handler that was there before (the
/// Rust runtime's, which reports a stack overflow and aborts, which is then handled here).
#[cfg(unix)]
mod crash {
    use std::os::raw::{c_int, c_void};
    use std::sync::atomic::{AtomicBool, AtomicI32, Ordering};
    use std::sync::OnceLock;
    use std::time::Duration;

    use cosim_engine::summary::RunStatus;
    use fmu_import::watch;

    /// How long the handler waits for the process to be ended.
    const CRASH_WAIT: Duration = Duration::from_secs(10);

    /// The signals of a crash, with what they mean.
    const SIGNALS: [(c_int, &str, &str); 5] = [
        (libc::SIGSEGV, "SIGSEGV", "invalid memory access"),
        (libc::SIGBUS, "SIGBUS", "bus error"),
        (libc::SIGFPE, "SIGFPE", "arithmetic fault"),
        (libc::SIGILL, "SIGILL", "illegal instruction"),
        (libc::SIGABRT, "SIGABRT", "abort"),
    ];

    /// The pipe's write end, for the handler (-1: not watching).
    static WAKE: AtomicI32 = AtomicI32::new(-1);
    /// Set by the first crash: a second one (in another thread, or in the ending) is not waited on.
    static CRASHED: AtomicBool = AtomicBool::new(false);
    /// The dispositions the handler replaced, in the order of [`SIGNALS`].
    static PREVIOUS: OnceLock<[libc::sigaction; 5]> = OnceLock::new();

    /// Installs the handlers and the thread that ends the process (once per process).
    pub fn watch() {
        if WAKE.load(Ordering::SeqCst) >= 0 {
            return;
        }
        let mut ends = [-1; 2];
        // SAFETY: `pipe2` fills the two descriptors of a valid array.
        if unsafe { libc::pipe2(ends.as_mut_ptr(), libc::O_CLOEXEC) } != 0 {
            return;
        }
        let [read_end, write_end] = ends;
        if std::thread::Builder::new().name("crash-report".into()).spawn(move || report(read_end)).is_err() {
            return;
        }
        WAKE.store(write_end, Ordering::SeqCst);
        // SAFETY: a zeroed `sigaction` is a valid value for `sigaction` to fill.
        let mut previous: [libc::sigaction; 5] = unsafe { std::mem::zeroed() };
        for ((signal, _, _), previous) in SIGNALS.iter().zip(&mut previous) {
            // SAFETY: reads the current disposition into a valid `sigaction`.
            unsafe { libc::sigaction(*signal, std::ptr::null(), previous) };
        }
        // Stored before any handler is installed, so the handler always finds it.
        if PREVIOUS.set(previous).is_err() {
            return;
        }
        for (signal, _, _) in SIGNALS {
            // SAFETY: the handler has the SA_SIGINFO signature, never unwinds and makes only
            // async-signal-safe calls.
            unsafe {
                let mut action: libc::sigaction = std::mem::zeroed();
                action.sa_sigaction = on_crash as *const () as usize;
                action.sa_flags = libc::SA_SIGINFO | libc::SA_ONSTACK;
                libc::sigemptyset(&mut action.sa_mask);
                libc::sigaction(signal, &action, std::ptr::null_mut());
            }
        }
    }

    /// The handler: async-signal-safe calls only (`write`, `nanosleep`, `sigaction`, `raise`).
    extern "C" fn on_crash(signal: c_int, _info: *mut libc::siginfo_t, _context: *mut c_void) {
        let outside_call = !watch::in_call() && (signal == libc::SIGSEGV || signal == libc::SIGBUS);
        if !outside_call && !CRASHED.swap(true, Ordering::SeqCst) {
            let byte = signal as u8;
            // SAFETY: writing one byte from a live local to the pipe, then sleeping.
            unsafe {
                libc::write(WAKE.load(Ordering::SeqCst), (&byte as *const u8).cast(), 1);
                let wait = libc::timespec { tv_sec: CRASH_WAIT.as_secs() as libc::time_t, tv_nsec: 0 };
                libc::nanosleep(&wait, std::ptr::null_mut());
            }
        }
        restore_and_raise(signal);
    }

    /// Puts back the disposition the handler replaced and raises `signal` again, so that it ends
    /// the process as it would have (a fault re-runs its instruction once the handler returns).
    fn restore_and_raise(signal: c_int) {
        let index = SIGNALS.iter().position(|(known, _, _)| *known == signal);
        // SAFETY: restoring a disposition read by `sigaction` (or the default), then raising.
        unsafe {
            match (PREVIOUS.get(), index) {
                (Some(previous), Some(index)) => libc::sigaction(signal, &previous[index], std::ptr::null_mut()),
                _ => {
                    libc::signal(signal, libc::SIG_DFL);
                    0
                }
            };
            libc::raise(signal);
        }
    }

    /// Waits for a crash and ends the process with the rows, the summary and the message.
    fn report(read_end: c_int) {
        let mut byte = 0u8;
        // SAFETY: reading one byte into a live local; the loop retries an interrupted read.
        while unsafe { libc::read(read_end, (&mut byte as *mut u8).cast(), 1) } != 1 {}
        let signal = c_int::from(byte);
        let (name, meaning) =
            SIGNALS.iter().find(|(known, _, _)| *known == signal).map_or(("a signal", ""), |(_, n, m)| (*n, *m));
        let place = match watch::current() {
            Some(call) => format!("instance '{}' crashed ({name}, {meaning}) in {call}", call.instance),
            None => format!("the process crashed ({name}, {meaning}) outside an FMU call"),
        };
        let message = format!("error: {place}; the run did not finish (the rows computed so far are written)");
        super::watchdog::end_now(RunStatus::Failed, &message, 128 + signal);
    }
}

/// The watchers that end the process when a run cannot end itself, and the one way they do it.
#[cfg(unix)]
mod watchdog {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Mutex;
    use std::time::{Duration, Instant};

    use cosim_engine::emergency;
    use cosim_engine::interrupt::{signal_name, Interrupt};
    use cosim_engine::summary::RunStatus;
    use fmu_import::watch;

    use super::GRACE;

    /// Held by the one thread that ends the process.
    static ENDING: Mutex<()> = Mutex::new(());
    /// The first signal's number (0: none yet).
    static FIRST: AtomicUsize = AtomicUsize::new(0);

    /// Writes the computed rows and summaries, removes the temporary folders, prints `message`
    /// and leaves with `status`, skipping destructors and atexit handlers (the main thread may
    /// be stuck inside an FMU).
    pub fn end_now(run_status: RunStatus, message: &str, status: i32) -> ! {
        let _ending = ENDING.lock();
        emergency::end(run_status, message);
        eprintln!("{message}");
        // SAFETY: `_exit` has no preconditions.
        unsafe { libc::_exit(status) }
    }

    /// What the run was doing: `instance 'h' did not return from fmi2DoStep(...)` or `the run
    /// did not stop`.
    fn stuck() -> String {
        match watch::current() {
            Some(call) => format!("instance '{}' did not return from {call}", call.instance),
            None => "the run did not stop".into(),
        }
    }

    /// Signals in a thread (not in a handler): the first asks the run to stop between steps,
    /// a second one ends the process; so does [`GRACE`] passing after the first.
    pub fn watch_signals(interrupt: &Interrupt) {
        use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
        let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP]) else {
            // The signals keep their default (end the process): nothing worse than before.
            return;
        };
        let interrupt = interrupt.clone();
        let spawned = std::thread::Builder::new().name("signals".into()).spawn(move || {
            for signal in signals.forever() {
                let signal = signal as usize;
                match FIRST.compare_exchange(0, signal, Ordering::SeqCst, Ordering::SeqCst) {
                    Ok(_) => {
                        interrupt.request(signal);
                        end_after_grace(signal);
                    }
                    Err(first) => end_now(
                        RunStatus::Hung,
                        &format!("error: {} before {} came again", stuck(), signal_name(first)),
                        128 + signal as i32,
                    ),
                }
            }
        });
        drop(spawned);
    }

    /// After [`GRACE`], ends the process once one FMU call is seen in progress at two polls in a
    /// row: the run cannot reach its next step. Work of the program's own after the last step (a
    /// campaign's figures and report) is left to finish; a second signal still ends it.
    fn end_after_grace(signal: usize) {
        let _ = std::thread::Builder::new().name("grace".into()).spawn(move || {
            std::thread::sleep(GRACE);
            let mut seen = None;
            loop {
                let now = watch::current().map(|call| call.sequence);
                if now.is_some() && now == seen {
                    let message = format!("error: {} within {} s of {}", stuck(), GRACE.as_secs(), signal_name(signal));
                    end_now(RunStatus::Hung, &message, 128 + signal as i32);
                }
                seen = now;
                std::thread::sleep(Duration::from_millis(100));
            }
        });
    }

    /// Ends the process with status 1 when one FMU call lasts more than `limit`: the call in
    /// progress is sampled a few times per second; the same call seen for `limit` is stuck.
    pub fn watch_calls(limit: Duration) {
        let poll = (limit / 10).clamp(Duration::from_millis(1), Duration::from_millis(100));
        let _ = std::thread::Builder::new().name("step-timeout".into()).spawn(move || {
            let mut seen: Option<(u64, Instant)> = None;
            loop {
                std::thread::sleep(poll);
                let Some(call) = watch::current() else {
                    seen = None;
                    continue;
                };
                match seen {
                    Some((sequence, since)) if sequence == call.sequence => {
                        if since.elapsed() >= limit {
                            let message = format!(
                                "error: instance '{}' did not return from {call} within {} s (--step-timeout)",
                                call.instance,
                                limit.as_secs_f64()
                            );
                            end_now(RunStatus::Hung, &message, 1);
                        }
                    }
                    _ => seen = Some((call.sequence, Instant::now())),
                }
            }
        });
    }
}
