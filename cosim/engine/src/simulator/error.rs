//! The one error type every [`Simulator`](super::Simulator) call returns.

use fmu_import::slave::SlaveError;

/// Why a simulator call failed: the simulator's own error (kept whole, so messages and their
/// causes read exactly as the simulator wrote them) and whether it was a discard.
#[derive(Debug)]
pub struct SimulatorError {
    error: Box<dyn std::error::Error + Send + Sync>,
    discard: bool,
}

impl SimulatorError {
    /// A failure (`fmi2Error` or worse).
    pub fn failed(error: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> Self {
        Self { error: error.into(), discard: false }
    }

    /// An `fmi2Discard`: the simulator cannot go on, and the run can only end early.
    pub fn discarded(error: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> Self {
        Self { error: error.into(), discard: true }
    }

    /// True for a discard.
    pub fn is_discard(&self) -> bool {
        self.discard
    }

    /// The simulator's error, e.g. to downcast to a [`SlaveError`].
    pub fn inner(&self) -> &(dyn std::error::Error + Send + Sync + 'static) {
        &*self.error
    }
}

// Display and source are the wrapped error's own, so an error chain reads as if the wrapper
// were not there.
impl std::fmt::Display for SimulatorError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for SimulatorError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.error.source()
    }
}

impl From<SlaveError> for SimulatorError {
    fn from(error: SlaveError) -> Self {
        let discard = error.is_discard();
        Self { error: Box::new(error), discard }
    }
}
