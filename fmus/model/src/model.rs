//! The trait a co-simulation model implements, and what an export layer needs to know of it.

use crate::variables::Variable;
use serde::{de::DeserializeOwned, Serialize};
use std::path::PathBuf;

/// Static facts about a model, which an export layer renders into its model description.
pub struct ModelInfo {
    /// The model's identifier and name: the cdylib's file stem (`lib` prefix removed).
    pub model_identifier: &'static str,
    pub description: &'static str,
    /// Suggested default experiment (s).
    pub default_stop_time: f64,
    pub default_step_size: f64,
    /// Whether the model uses the first derivatives of its inputs over a step.
    pub can_interpolate_inputs: bool,
    /// Largest communication step (s) one step call accepts: a bound on the work of one call for
    /// models whose work grows with the step (internal substeps, samples), so that a huge step
    /// is refused with an error naming the limit instead of computing for hours. `f64::MAX`
    /// where a step costs the same whatever its size.
    pub max_step_size: f64,
}

impl ModelInfo {
    /// The facts of model `model_identifier` with the defaults most models share, so that a model
    /// states only where it differs: a 10 s default experiment in 10 ms steps, inputs held over a
    /// step (not interpolated) and no bound on a step's size.
    pub const fn new(model_identifier: &'static str, description: &'static str) -> Self {
        ModelInfo {
            model_identifier,
            description,
            default_stop_time: 10.0,
            default_step_size: 0.01,
            can_interpolate_inputs: false,
            max_step_size: f64::MAX,
        }
    }

    /// The suggested stop time (s) instead of 10 s.
    pub const fn stop_time(self, default_stop_time: f64) -> Self {
        ModelInfo { default_stop_time, ..self }
    }

    /// The model uses the first derivatives of its inputs over a step.
    pub const fn interpolating_inputs(self) -> Self {
        ModelInfo { can_interpolate_inputs: true, ..self }
    }

    /// The largest communication step (s) one step call accepts (see [`ModelInfo::max_step_size`]).
    pub const fn max_step(self, max_step_size: f64) -> Self {
        ModelInfo { max_step_size, ..self }
    }
}

/// What the host told the model's instance when it was created.
#[derive(Debug, Clone, Default)]
pub struct Environment {
    pub instance_name: String,
    /// The FMU's `resources/` folder (decoded from the host's location), if the host gave one.
    pub resource_dir: Option<PathBuf>,
}

/// A co-simulation model. An export layer owns the host's state machine, logging, argument
/// checks and state snapshots; the model owns only physics and its variable table.
///
/// Snapshots are clones / serde images of the model, so the model must hold its whole state by
/// value (no pointers, no handles).
pub trait Model: Clone + Send + Serialize + DeserializeOwned + 'static {
    const INFO: ModelInfo;

    /// The variable table (see [`crate::variables`] and [`crate::builder`]).
    fn variables() -> &'static [Variable<Self>];

    /// A model before start values are applied; the export layer applies every table start next.
    fn new(env: &Environment) -> Self;

    /// Computes the initial state and outputs from parameters and current inputs at `start_time`.
    /// Called during initialization (before outputs are read) and at its end; it must be
    /// idempotent. An `Err` is reported to the host as an error.
    fn initialize(&mut self, start_time: f64) -> Result<(), String>;

    /// Advances from `t` to `t + h` (h > 0) and updates outputs. The model reads input values set
    /// before the call and their first derivatives (the derivative setter received `None` when the
    /// host set a value without a derivative for this step).
    fn do_step(&mut self, t: f64, h: f64) -> Result<(), String>;

    /// The longest communication step (s) over which this model's results still mean what they
    /// should, if it has one. A sampled controller reads its inputs once per communication
    /// step: a longer step than its sample period runs several samples on inputs held since the
    /// last communication point, an open loop the host did not ask for. The export layer logs a
    /// warning, once per instance, on the first step longer than this (the step itself runs).
    fn largest_sensible_step(&self) -> Option<f64> {
        None
    }

    /// What happened in the last step that the host should hear about although the step
    /// succeeded (a tip below the deck, a limit reached): the export layer logs each message as
    /// a warning after every step. Taking them empties the list.
    fn take_warnings(&mut self) -> Vec<String> {
        Vec::new()
    }

    /// Checks a model decoded from a serialized state (bytes from the host, so possibly
    /// corrupted) for what the export layer's own checks cannot see: it has already found every
    /// number finite and every parameter and input within its declared range. A model that keeps
    /// copies of its parameters (built at initialization) checks them here; an `Err` refuses the
    /// state.
    fn validate_state(&self) -> Result<(), String> {
        Ok(())
    }
}
