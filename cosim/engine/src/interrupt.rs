//! Asking a running execution to stop at the next communication point (Ctrl-C, `kill`).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

/// A shared request to stop, carrying the number of the signal that asked (0: none yet).
///
/// The execution looks at it once per macro step (one relaxed atomic load), so a run stops
/// between steps: every row recorded so far is complete and the instances are terminated and
/// freed as after any other early end. The flag is an `AtomicUsize` so that signal handlers can
/// set it directly (e.g. `signal_hook::flag::register_usize`).
#[derive(Debug, Clone, Default)]
pub struct Interrupt(Arc<AtomicUsize>);

impl Interrupt {
    /// A request nobody made yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Asks to stop on behalf of the signal numbered `signal`, or of the program itself
    /// ([`NO_SIGNAL`]).
    pub fn request(&self, signal: usize) {
        self.0.store(signal, Ordering::Relaxed);
    }

    /// The signal number of the request, if one was made.
    pub fn requested(&self) -> Option<usize> {
        match self.0.load(Ordering::Relaxed) {
            0 => None,
            signal => Some(signal),
        }
    }

    /// The flag itself, for a signal handler to store a signal number in.
    pub fn flag(&self) -> &Arc<AtomicUsize> {
        &self.0
    }
}

/// The "signal number" of a request the program made itself.
pub const NO_SIGNAL: usize = usize::MAX;

/// The conventional name of a signal number, for messages ("SIGTERM"); `signal N` otherwise.
pub fn signal_name(signal: usize) -> String {
    match signal {
        NO_SIGNAL => "a stop request".into(),
        1 => "SIGHUP".into(),
        2 => "SIGINT".into(),
        15 => "SIGTERM".into(),
        other => format!("signal {other}"),
    }
}
