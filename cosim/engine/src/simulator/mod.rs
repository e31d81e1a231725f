//! What an algorithm steps: anything that behaves like an FMI 2.0 Co-Simulation instance.
//!
//! [`Simulator`] is the seam between the engine and FMU instances: the engine's algorithms,
//! observers and input signals only see this trait, so they can be tested against in-process
//! mock simulators, and the FMU import crate's [`Slave`](fmu_import::slave::Slave) is one
//! implementation (`fmu`). Value references are those of the simulator's model description;
//! times are in seconds.

mod error;
mod fmu;
mod timed;
mod wrapped;

pub use error::SimulatorError;
pub use timed::{timed, CallTimes, Timed, Timing};
pub use wrapped::{Wrapped, Wrapper};

use fmu_import::value::Value;

/// One co-simulation instance, driven through the FMI 2.0 Co-Simulation call sequence:
/// setup → start values → initialization mode (inputs) → exit → steps (inputs, `do_step`) →
/// terminate.
pub trait Simulator: Send {
    /// The instance name (for messages).
    fn name(&self) -> &str;

    /// `fmi2SetupExperiment` without a tolerance: start time and optional stop time.
    fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Result<(), SimulatorError>;

    /// `fmi2EnterInitializationMode`.
    fn enter_initialization_mode(&mut self) -> Result<(), SimulatorError>;

    /// `fmi2ExitInitializationMode`.
    fn exit_initialization_mode(&mut self) -> Result<(), SimulatorError>;

    /// `fmi2DoStep(current, step)`.
    fn do_step(&mut self, current: f64, step: f64) -> Result<(), SimulatorError>;

    /// `fmi2GetBooleanStatus(fmi2Terminated)`: after `do_step` was discarded, true if the
    /// simulator asks to end the simulation.
    fn terminated(&self) -> Result<bool, SimulatorError>;

    /// `fmi2GetRealStatus(fmi2LastSuccessfulTime)`: after `do_step` was discarded, the time (s)
    /// up to which the simulator computed the step.
    fn last_successful_time(&self) -> Result<f64, SimulatorError>;

    /// `fmi2Terminate`.
    fn terminate(&mut self) -> Result<(), SimulatorError>;

    /// Tells the simulator which communication point its next calls belong to (messages only).
    fn set_time_hint(&mut self, _time: f64) {}

    /// `fmi2GetReal`.
    fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SimulatorError>;
    /// `fmi2GetInteger` (also enumerations).
    fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SimulatorError>;
    /// `fmi2GetBoolean`.
    fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SimulatorError>;
    /// `fmi2GetString`.
    fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SimulatorError>;

    /// `fmi2SetReal`.
    fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SimulatorError>;
    /// `fmi2SetInteger` (also enumerations).
    fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SimulatorError>;
    /// `fmi2SetBoolean`.
    fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SimulatorError>;
    /// `fmi2SetString`.
    fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SimulatorError>;

    /// `fmi2SetRealInputDerivatives` of order 1: `slopes[i]` is the time derivative of the Real
    /// input `vrs[i]` over the coming step (its unit per second).
    fn set_real_input_derivatives(&mut self, vrs: &[u32], slopes: &[f64]) -> Result<(), SimulatorError>;

    /// The simulator's complete state as bytes (`fmi2GetFMUstate`, `fmi2SerializeFMUstate`,
    /// `fmi2FreeFMUstate`), for [`Simulator::restore_state`] of this or another instance of the
    /// same FMU. Fails for a simulator that cannot serialize its state (the default).
    fn save_state(&mut self) -> Result<Vec<u8>, SimulatorError> {
        Err(SimulatorError::failed(format!("instance {:?} cannot save its state", self.name())))
    }

    /// Puts the simulator back into a state [`Simulator::save_state`] returned
    /// (`fmi2DeSerializeFMUstate`, `fmi2SetFMUstate`, `fmi2FreeFMUstate`).
    fn restore_state(&mut self, _state: &[u8]) -> Result<(), SimulatorError> {
        Err(SimulatorError::failed(format!("instance {:?} cannot restore a state", self.name())))
    }

    /// Sets one start value of any type.
    fn set_value(&mut self, vr: u32, value: &Value) -> Result<(), SimulatorError> {
        match value {
            Value::Real(v) => self.set_real(&[vr], &[*v]),
            Value::Integer(v) => self.set_integer(&[vr], &[*v]),
            Value::Boolean(v) => self.set_boolean(&[vr], &[*v]),
            Value::String(v) => self.set_string(&[vr], &[v.as_str()]),
        }
    }
}
