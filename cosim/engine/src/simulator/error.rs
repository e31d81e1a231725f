//! The one error type every [`Simulator`](super::Simulator) call returns.

use fmu_import::slave::SlaveError;

/// Why a simulator call failed: the simulator's own error (kept whole, so messages and their
/// causes read exactly as the simulator wrote them) and, for a discard, which simulator.
///
/// One pointer wide, so that `Result<(), SimulatorError>`, which every get, set and step call
/// returns, fits in a register: the successful calls of the hot path pay nothing for the error.
#[derive(Debug)]
pub struct SimulatorError(Box<Failure>);

// The hot path's return type stays one register wide.
const _: () = assert!(std::mem::size_of::<Result<(), SimulatorError>>() == std::mem::size_of::<usize>());

#[derive(Debug)]
struct Failure {
    error: Box<dyn std::error::Error + Send + Sync>,
    /// The name of the simulator that returned `fmi2Discard`.
    discarded_by: Option<String>,
}

impl SimulatorError {
    /// A failure (`fmi2Error` or worse).
    pub fn failed(error: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> Self {
        Self(Box::new(Failure { error: error.into(), discarded_by: None }))
    }

    /// An `fmi2Discard` from the simulator named `simulator`: it could not complete the step,
    /// and may ask to end the simulation ([`Simulator::terminated`](super::Simulator::terminated)).
    pub fn discarded(simulator: &str, error: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> Self {
        Self(Box::new(Failure { error: error.into(), discarded_by: Some(simulator.to_string()) }))
    }

    /// The name of the simulator that discarded, for a discard.
    pub fn discarded_by(&self) -> Option<&str> {
        self.0.discarded_by.as_deref()
    }

    /// The simulator's error, e.g. to downcast to a [`SlaveError`].
    pub fn inner(&self) -> &(dyn std::error::Error + Send + Sync + 'static) {
        &*self.0.error
    }
}

// Display and source are the wrapped error's own, so an error chain reads as if the wrapper
// were not there.
impl std::fmt::Display for SimulatorError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.error.fmt(f)
    }
}

impl std::error::Error for SimulatorError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        self.0.error.source()
    }
}

impl From<SlaveError> for SimulatorError {
    fn from(error: SlaveError) -> Self {
        let discarded_by = match &error {
            SlaveError::Discard(failure) => Some(failure.instance.clone()),
            _ => None,
        };
        Self(Box::new(Failure { error: Box::new(error), discarded_by }))
    }
}
