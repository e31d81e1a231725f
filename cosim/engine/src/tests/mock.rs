//! A mock simulator: Real variables in a map, a law applied at every step, optional failure
//! at a chosen step, and every call written to a journal shared by all mocks of a test.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use crate::simulator::{Simulator, SimulatorError};

/// One journaled call.
#[derive(Debug, Clone, PartialEq)]
pub enum Call {
    Setup {
        start: f64,
        stop: Option<f64>,
    },
    EnterInitialization,
    ExitInitialization,
    GetReal {
        vrs: Vec<u32>,
    },
    SetReal {
        vrs: Vec<u32>,
        values: Vec<f64>,
    },
    Derivatives {
        vrs: Vec<u32>,
        values: Vec<f64>,
    },
    DoStep {
        current: f64,
        step: f64,
    },
    /// `fmi2GetBooleanStatus(fmi2Terminated)`.
    Terminated,
    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`.
    LastSuccessfulTime,
    Terminate,
}

/// Calls of every mock of a test, in the order they happened: (mock name, call).
pub type Journal = Arc<Mutex<Vec<(&'static str, Call)>>>;

/// What a mock's outputs become at the end of a step `t → t + h`.
#[derive(Debug, Clone, Copy)]
pub enum Law {
    /// Output `vr` becomes `slope · (t + h)`: a ramp the algorithms can recognise.
    Ramp { vr: u32, slope: f64 },
    /// Output `output` becomes the value input `input` had during the step.
    Echo { input: u32, output: u32 },
    /// Each output `vr` becomes `vr · (t + h)`: ramps that tell apart both the output and the
    /// communication point a value came from.
    Ramps(&'static [u32]),
}

/// How a mock fails.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Failure {
    Error,
    /// `fmi2Discard` with `fmi2Terminated` false.
    Discard,
    /// `fmi2Discard` with `fmi2Terminated` true, having reached `t + reached · h`.
    Terminate {
        reached: f64,
    },
    /// `fmi2Discard`, and `fmi2GetBooleanStatus` fails.
    DiscardWithoutStatus,
}

#[derive(Debug)]
pub struct Mock {
    name: &'static str,
    law: Law,
    reals: BTreeMap<u32, f64>,
    steps: u64,
    fail_at: Option<(u64, Failure)>,
    /// The time reached by a step that ended in `Failure::Terminate`.
    reached: Option<f64>,
    journal: Journal,
}

impl Mock {
    pub fn new(name: &'static str, law: Law, journal: &Journal) -> Self {
        Self { name, law, reals: BTreeMap::new(), steps: 0, fail_at: None, reached: None, journal: Arc::clone(journal) }
    }

    /// Fails `fmi2DoStep` number `step` (0-based) the way `failure` says.
    pub fn failing_at(mut self, step: u64, failure: Failure) -> Self {
        self.fail_at = Some((step, failure));
        self
    }

    fn note(&self, call: Call) {
        self.journal.lock().expect("journal").push((self.name, call));
    }

    fn real(&self, vr: u32) -> f64 {
        self.reals.get(&vr).copied().unwrap_or(0.0)
    }

    /// The outputs at `current + step`.
    fn advance(&mut self, current: f64, step: f64) {
        match self.law {
            Law::Ramp { vr, slope } => self.reals.insert(vr, slope * (current + step)),
            Law::Echo { input, output } => self.reals.insert(output, self.real(input)),
            Law::Ramps(vrs) => {
                for &vr in vrs {
                    self.reals.insert(vr, f64::from(vr) * (current + step));
                }
                None
            }
        };
    }
}

impl Simulator for Mock {
    fn name(&self) -> &str {
        self.name
    }

    fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Result<(), SimulatorError> {
        self.note(Call::Setup { start, stop });
        Ok(())
    }

    fn enter_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        self.note(Call::EnterInitialization);
        Ok(())
    }

    fn exit_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        self.note(Call::ExitInitialization);
        Ok(())
    }

    fn do_step(&mut self, current: f64, step: f64) -> Result<(), SimulatorError> {
        self.note(Call::DoStep { current, step });
        if let Some((at, failure)) = self.fail_at.filter(|(at, _)| *at == self.steps) {
            let message = format!("{}: step {at} at t = {current} fails", self.name);
            if let Failure::Terminate { reached } = failure {
                self.reached = Some(current + reached * step);
                // An FMU that reached the step's end has its outputs there.
                if reached == 1.0 {
                    self.advance(current, step);
                }
            }
            return Err(match failure {
                Failure::Error => SimulatorError::failed(message),
                _ => SimulatorError::discarded(self.name, message),
            });
        }
        self.advance(current, step);
        self.steps += 1;
        Ok(())
    }

    fn terminated(&self) -> Result<bool, SimulatorError> {
        self.note(Call::Terminated);
        match self.fail_at {
            Some((_, Failure::DiscardWithoutStatus)) => Err(SimulatorError::failed("fmi2Terminated is not available")),
            _ => Ok(self.reached.is_some()),
        }
    }

    fn last_successful_time(&self) -> Result<f64, SimulatorError> {
        self.note(Call::LastSuccessfulTime);
        self.reached.ok_or_else(|| SimulatorError::failed("no step was discarded"))
    }

    fn terminate(&mut self) -> Result<(), SimulatorError> {
        self.note(Call::Terminate);
        Ok(())
    }

    fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SimulatorError> {
        self.note(Call::GetReal { vrs: vrs.to_vec() });
        for (value, vr) in values.iter_mut().zip(vrs) {
            *value = self.real(*vr);
        }
        Ok(())
    }

    fn get_integer(&self, _: &[u32], _: &mut [i32]) -> Result<(), SimulatorError> {
        Err(SimulatorError::failed("the mock has only Reals"))
    }

    fn get_boolean(&self, _: &[u32], _: &mut [bool]) -> Result<(), SimulatorError> {
        Err(SimulatorError::failed("the mock has only Reals"))
    }

    fn get_string(&self, _: &[u32]) -> Result<Vec<String>, SimulatorError> {
        Err(SimulatorError::failed("the mock has only Reals"))
    }

    fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SimulatorError> {
        self.note(Call::SetReal { vrs: vrs.to_vec(), values: values.to_vec() });
        for (vr, value) in vrs.iter().zip(values) {
            self.reals.insert(*vr, *value);
        }
        Ok(())
    }

    fn set_integer(&mut self, _: &[u32], _: &[i32]) -> Result<(), SimulatorError> {
        Err(SimulatorError::failed("the mock has only Reals"))
    }

    fn set_boolean(&mut self, _: &[u32], _: &[bool]) -> Result<(), SimulatorError> {
        Err(SimulatorError::failed("the mock has only Reals"))
    }

    fn set_string(&mut self, _: &[u32], _: &[&str]) -> Result<(), SimulatorError> {
        Err(SimulatorError::failed("the mock has only Reals"))
    }

    fn set_real_input_derivatives(&mut self, vrs: &[u32], slopes: &[f64]) -> Result<(), SimulatorError> {
        self.note(Call::Derivatives { vrs: vrs.to_vec(), values: slopes.to_vec() });
        Ok(())
    }
}

/// The calls of one mock, in order.
pub fn calls_of(journal: &Journal, name: &str) -> Vec<Call> {
    journal.lock().expect("journal").iter().filter(|(who, _)| *who == name).map(|(_, c)| c.clone()).collect()
}

/// The value references of every `fmi2GetReal` call on a mock, in order.
pub fn gets_of(journal: &Journal, name: &str) -> Vec<Vec<u32>> {
    calls_of(journal, name)
        .into_iter()
        .filter_map(|call| match call {
            Call::GetReal { vrs } => Some(vrs),
            _ => None,
        })
        .collect()
}

/// The values a mock received for input `vr`, one per `SetReal` call that set it.
pub fn inputs_set(journal: &Journal, name: &str, vr: u32) -> Vec<f64> {
    values_set(journal, name, vr, |call| match call {
        Call::SetReal { vrs, values } => Some((vrs, values)),
        _ => None,
    })
}

/// The slopes a mock received for input `vr`.
pub fn slopes_set(journal: &Journal, name: &str, vr: u32) -> Vec<f64> {
    values_set(journal, name, vr, |call| match call {
        Call::Derivatives { vrs, values } => Some((vrs, values)),
        _ => None,
    })
}

/// The value references and values of a call of one kind (`None` for the other calls).
type Kind = fn(Call) -> Option<(Vec<u32>, Vec<f64>)>;

/// The value for `vr` of every call of a mock that `kind` takes and that sets `vr`, in order.
fn values_set(journal: &Journal, name: &str, vr: u32, kind: Kind) -> Vec<f64> {
    calls_of(journal, name)
        .into_iter()
        .filter_map(kind)
        .filter_map(|(vrs, values)| vrs.iter().position(|&v| v == vr).map(|i| values[i]))
        .collect()
}
