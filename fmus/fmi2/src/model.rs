//! The trait an FMU's model implements; everything FMI-specific lives in this crate.

use crate::variables::Variable;
use serde::{de::DeserializeOwned, Serialize};
use std::path::PathBuf;

/// Static facts about a model, rendered into `modelDescription.xml`.
pub struct ModelInfo {
    /// `modelIdentifier` and `modelName`: the cdylib's file stem (`lib` prefix removed).
    pub model_identifier: &'static str,
    pub description: &'static str,
    /// Suggested `DefaultExperiment` (s).
    pub default_stop_time: f64,
    pub default_step_size: f64,
    /// Whether the model uses input derivatives (`canInterpolateInputs`).
    pub can_interpolate_inputs: bool,
    /// Largest `communicationStepSize` (s) one `fmi2DoStep` accepts: a bound on the work of one
    /// call for models whose work grows with the step (internal substeps, samples), so that a
    /// huge step is refused with `fmi2Error` naming the limit instead of computing for hours.
    /// `f64::MAX` where a step costs the same whatever its size.
    pub max_step_size: f64,
}

/// What the host told the FMU at instantiation.
#[derive(Debug, Clone, Default)]
pub struct Environment {
    pub instance_name: String,
    /// Decoded `fmuResourceLocation` (the FMU's `resources/` folder), if the host gave one.
    pub resource_dir: Option<PathBuf>,
}

/// A co-simulation model. The instance layer owns the FMI state machine, logging, argument
/// checks and FMU-state snapshots; the model owns only physics.
///
/// Snapshots (`fmi2GetFMUstate`, serialization) are clones / serde images of the model, so the
/// model must hold its whole state by value (no pointers, no handles).
pub trait Model: Clone + Send + Serialize + DeserializeOwned + 'static {
    const INFO: ModelInfo;

    /// The variable table (see [`crate::variables`]).
    fn variables() -> &'static [Variable<Self>];

    /// A model before start values are applied; the instance applies every table start next.
    fn new(env: &Environment) -> Self;

    /// Computes the initial state and outputs from parameters and current inputs at `start_time`.
    /// Called during initialization mode (before outputs are read) and at its exit; it must be
    /// idempotent. An `Err` is reported to the host as `fmi2Error`.
    fn initialize(&mut self, start_time: f64) -> Result<(), String>;

    /// Advances from `t` to `t + h` (h > 0) and updates outputs. The model reads input values set
    /// before the call and their first derivatives (the derivative setter received `None` when the
    /// host set a value without a derivative for this step).
    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String>;

    /// Checks a model decoded from a serialized FMU state (bytes from the host, so possibly
    /// corrupted) for what the instance's own checks cannot see: it has already found every
    /// number finite and every parameter and input within its declared range. A model that keeps
    /// copies of its parameters (built at initialization) checks them here; an `Err` refuses the
    /// state.
    fn validate_state(&self) -> Result<(), String> {
        Ok(())
    }
}
