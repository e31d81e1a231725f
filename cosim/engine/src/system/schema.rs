//! The JSON system file, as written by users (before validation).
//!
//! ```json
//! {
//!   "description": "free pendulum",
//!   "fmus": { "pendulum": "../target/fmu/pendulum.fmu" },
//!   "instances": [ { "name": "load", "fmu": "pendulum", "start": { "theta_x0": -0.349, "lp": 0.7 } } ],
//!   "connections": [ { "from": "a.out", "to": "b.in" } ],
//!   "inputs": [ { "instance": "load", "file": "load_in.csv" } ],
//!   "start_time": 0.0, "stop_time": 60.0, "step_size": 0.01,
//!   "algorithm": "gauss-seidel",
//!   "input_derivatives": false,
//!   "record": { "interval": 0.01, "variables": ["load.theta_x", "load.load.x"] }
//! }
//! ```
//!
//! Paths are relative to the system file. Times are in seconds. Unknown keys
//! are errors.

use std::collections::BTreeMap;
use std::path::PathBuf;

pub use crate::algorithm::AlgorithmKind;
use serde::{Deserialize, Serialize};

/// Top level of a system file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SystemSpec {
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// FMU alias → path of the `.fmu` file.
    pub fmus: BTreeMap<String, PathBuf>,
    /// Instances, in stepping order (Gauss–Seidel order).
    pub instances: Vec<InstanceSpec>,
    /// Output → input connections `"instance.variable"`.
    #[serde(default)]
    pub connections: Vec<ConnectionSpec>,
    /// Input signals from CSV files.
    #[serde(default)]
    pub inputs: Vec<InputSpec>,
    /// Start of the simulation (s), default 0.
    #[serde(default)]
    pub start_time: f64,
    /// End of the simulation (s).
    pub stop_time: f64,
    /// Communication step `h` (s).
    pub step_size: f64,
    /// Co-simulation algorithm.
    #[serde(default)]
    pub algorithm: AlgorithmKind,
    /// Pass first-order input derivatives (slopes of the CSV inputs) to FMUs
    /// that declare `canInterpolateInputs`.
    #[serde(default)]
    pub input_derivatives: bool,
    /// Under Jacobi, pass each connected Real input of an FMU that declares
    /// `canInterpolateInputs` the slope from the last two communication points,
    /// `(u_k − u_{k−1}) / (t_k − t_{k−1})`, as its first derivative (linear extrapolation over
    /// the step; none at the first step). No effect under Gauss–Seidel. Off by default: other
    /// Jacobi masters (libcosim) pass no derivatives.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub extrapolate_inputs: bool,
    /// What to record (default: all outputs at every step).
    #[serde(default)]
    pub record: RecordSpec,
}

impl SystemSpec {
    /// Replaces the stop time, step size and algorithm by those given: what a scenario and the
    /// command line's options may replace alike.
    pub(crate) fn replace_grid(
        &mut self,
        stop_time: Option<f64>,
        step_size: Option<f64>,
        algorithm: Option<AlgorithmKind>,
    ) {
        if let Some(stop) = stop_time {
            self.stop_time = stop;
        }
        if let Some(step) = step_size {
            self.step_size = step;
        }
        if let Some(algorithm) = algorithm {
            self.algorithm = algorithm;
        }
    }
}

/// One FMU instance.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InstanceSpec {
    /// Instance name: non-empty, unique, without dots.
    pub name: String,
    /// Alias of an entry of `fmus`.
    pub fmu: String,
    /// Start values (SI) of inputs and of non-constant variables with `initial` exact or
    /// approx (parameters, some outputs and locals), set before initialization:
    /// a number for Real/Integer/Enumeration, `true`/`false` for Boolean, a
    /// string for String.
    #[serde(default)]
    pub start: BTreeMap<String, serde_json::Value>,
}

/// A connection from an output to an input.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ConnectionSpec {
    /// `"instance.output"`.
    pub from: String,
    /// `"instance.input"`.
    pub to: String,
}

/// A CSV file feeding inputs of one instance.
#[derive(Debug, Clone, PartialEq, Eq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InputSpec {
    /// The instance whose inputs it feeds.
    pub instance: String,
    /// CSV with header `time,<input>,<input>,...`.
    pub file: PathBuf,
}

/// Recording options.
#[derive(Debug, Clone, PartialEq, Default, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct RecordSpec {
    /// Sampling interval (s): a whole multiple of `step_size`; default `step_size`.
    #[serde(default)]
    pub interval: Option<f64>,
    /// `"instance.variable"` names; default all outputs of all instances.
    #[serde(default)]
    pub variables: Option<Vec<String>>,
}
