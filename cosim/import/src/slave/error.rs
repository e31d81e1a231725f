//! Errors of FMU instances.

use std::fmt;
use std::path::PathBuf;

use crate::fmi::{LogMessage, Status};
use crate::fmu::FmuError;
use crate::names;
use crate::value::VariableType;

/// A failed `fmi2*` or `fmi3*` call: who, what, when, the status and what the FMU logged.
#[derive(Debug, Clone)]
pub struct CallFailure {
    /// Instance name.
    pub instance: String,
    /// The C function, e.g. `"fmi2DoStep"`, or `"fmi3DoStep"` for an FMI 3.0 FMU (whose status
    /// is then spelled as FMI 3.0 does).
    pub call: &'static str,
    /// Simulation time in seconds at which the call was made, where relevant.
    pub time: Option<f64>,
    pub status: Status,
    /// Arguments worth quoting, e.g. `tip.x = NaN` or `currentCommunicationPoint = 0.5, ...`.
    pub detail: Option<String>,
    /// Messages the FMU logged during the call (oldest first).
    pub log: Vec<LogMessage>,
}

impl CallFailure {
    /// The last message the FMU logged during the call.
    pub fn last_log(&self) -> Option<&LogMessage> {
        self.log.last()
    }
}

impl fmt::Display for CallFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "instance {:?}: {}", self.instance, self.call)?;
        if let Some(detail) = &self.detail {
            write!(f, " ({detail})")?;
        }
        write!(f, " returned {}", self.status.spelled(standard(self.call)))?;
        if let Some(time) = self.time {
            write!(f, " at t = {time:?} s")?;
        }
        match self.last_log() {
            Some(message) => write!(f, "; the FMU logged: {}", message.message.trim_end()),
            None => write!(f, "; the FMU logged no message"),
        }
    }
}

/// The standard a C function belongs to, by its name: `"fmi3"` for `fmi3DoStep`, else `"fmi2"`.
fn standard(call: &str) -> &'static str {
    if call.starts_with("fmi3") {
        "fmi3"
    } else {
        "fmi2"
    }
}

/// Any failure of a [`crate::slave::Slave`] operation.
#[derive(Debug, thiserror::Error)]
pub enum SlaveError {
    /// The FMU returned `fmi2Discard`. From `fmi2DoStep` it could not complete the step:
    /// [`Slave::terminated`](crate::slave::Slave::terminated) tells whether it asks to end the
    /// simulation there.
    #[error("{0}")]
    Discard(CallFailure),
    /// The FMU returned `fmi2Error`, `fmi2Fatal`, `fmi2Pending` or an invalid status.
    #[error("{0}")]
    Failed(CallFailure),
    /// `fmi2Instantiate` (or `fmi3InstantiateCoSimulation`, the `call`) returned NULL.
    #[error(
        "instance {instance:?}: {call} of {} returned NULL; {}",
        fmu.display(),
        match log.last() { Some(m) => format!("the FMU logged: {}", m.message.trim_end()), None => "the FMU logged no message".to_string() }
    )]
    InstantiateFailed { instance: String, call: &'static str, fmu: PathBuf, log: Vec<LogMessage> },
    /// A variable name that the model description does not declare.
    #[error(
        "instance {instance:?} (model {model:?}) has no variable {name:?}{}; variables: {}",
        names::did_you_mean(suggestion),
        names::quoted_list(available.iter().map(String::as_str))
    )]
    UnknownVariable {
        instance: String,
        model: String,
        name: String,
        suggestion: Option<String>,
        available: Vec<String>,
    },
    /// A value of the wrong type for a variable.
    #[error("instance {instance:?}: variable {variable:?} is {expected}, not {actual}")]
    TypeMismatch { instance: String, variable: String, expected: VariableType, actual: VariableType },
    /// Arguments that cannot be passed to the FMU (length mismatch, NUL in a string, foreign state, ...).
    #[error("instance {instance:?}: {call}: {message}")]
    InvalidArgument { instance: String, call: &'static str, message: String },
    /// The model description does not declare a capability the call needs.
    #[error("instance {instance:?}: {call} needs {capability}=\"true\" in the model description")]
    Unsupported { instance: String, call: &'static str, capability: &'static str },
    /// The FMU's library could not be loaded.
    #[error(transparent)]
    Fmu(#[from] FmuError),
}

impl SlaveError {
    /// The failed call, for `Discard` and `Failed`.
    pub fn call_failure(&self) -> Option<&CallFailure> {
        match self {
            SlaveError::Discard(failure) | SlaveError::Failed(failure) => Some(failure),
            _ => None,
        }
    }

    /// True for `fmi2Discard`.
    pub fn is_discard(&self) -> bool {
        matches!(self, SlaveError::Discard(_))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn failure(call: &'static str) -> CallFailure {
        CallFailure {
            instance: "load".into(),
            call,
            time: Some(0.5),
            status: Status::Error,
            detail: None,
            log: Vec::new(),
        }
    }

    #[test]
    fn an_fmi3_call_is_reported_with_fmi3_statuses() {
        let message = failure("fmi3DoStep").to_string();
        assert!(message.starts_with("instance \"load\": fmi3DoStep returned fmi3Error at t = 0.5 s"), "{message}");
        assert!(!message.contains("fmi2"), "{message}");
        assert!(failure("fmi2DoStep").to_string().contains("fmi2DoStep returned fmi2Error"));
    }
}
