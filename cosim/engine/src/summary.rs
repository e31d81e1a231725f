//! The run summary written as JSON next to the results.

use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::execution::Termination;

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RunStatus {
    /// All steps done and every instance terminated.
    Completed,
    /// An instance asked to end the simulation (`fmi2Discard` from `fmi2DoStep`, then
    /// `fmi2Terminated` true): the run ended normally at the last communication point every
    /// instance completed ([`RunSummary::termination`]).
    Terminated,
    /// Stopped between steps by a signal (SIGINT, SIGTERM, SIGHUP): every recorded row is
    /// complete; the error says the signal and the time reached.
    Interrupted,
    /// An FMU call did not return: the process was ended by a second signal, the grace period
    /// after the first, or the step timeout. Every row computed before is in the CSV; the error
    /// names the instance, the call and its time.
    Hung,
    /// Invalid input, an FMU error (also a discard without termination), or an output that
    /// could not be written.
    Failed,
}

/// One instance in the summary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InstanceSummary {
    /// The instance's name in the system file.
    pub name: String,
    /// The `.fmu` file.
    pub fmu: String,
    /// `modelName` from the FMU's model description.
    pub model_name: String,
    /// `guid` (FMI 2) or `instantiationToken` (FMI 3) from the model description.
    pub guid: String,
}

/// One recorded column of the results CSV (after `time`, in the same order).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ColumnSummary {
    /// `"instance.variable"`, the CSV header.
    pub name: String,
    /// The variable's unit in its model description (`"m"`, `"rad"`); null when it has none
    /// (Integer, Boolean and dimensionless variables).
    pub unit: Option<String>,
}

/// Where the wall time of a run went (`crane-cosim run --timing`), in seconds.
///
/// JSON: `"timing": {"steps": N, "total_s": x, "recording_s": y, "instances": [{"name":
/// "crane", "do_step_s": a, "get_set_s": b}, ...]}`. `total_s` covers initialization, every
/// step with its recording, termination and the final flush of the results (not loading or
/// instantiation); `recording_s` is
/// the time in the CSV recorder, including its get calls, which also count in the instances'
/// `get_set_s`. What is left of `total_s` after the instances' and the recorder's shares is the
/// importer's own work.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Timing {
    /// Macro steps completed.
    pub steps: u64,
    /// From initialization to the final flush of the results (s).
    pub total_s: f64,
    /// Inside the CSV recorder, its get calls included (s).
    pub recording_s: f64,
    /// In stepping order.
    pub instances: Vec<InstanceTiming>,
}

/// Wall time inside one instance's calls, in seconds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct InstanceTiming {
    /// The instance's name in the system file.
    pub name: String,
    /// Inside `fmi2DoStep`.
    pub do_step_s: f64,
    /// Inside `fmi2Get*`, `fmi2Set*` and `fmi2SetRealInputDerivatives` (connections, inputs
    /// files, start values and recording).
    pub get_set_s: f64,
}

/// Summary of one run. Times in seconds.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RunSummary {
    /// The system file.
    pub system: String,
    /// The system's free-text description (empty if it has none).
    pub description: String,
    /// How the run ended.
    pub status: RunStatus,
    /// The full error chain, if the run did not complete.
    pub error: Option<String>,
    /// The master algorithm's name; null if the run did not get as far as choosing it.
    pub algorithm: Option<String>,
    /// Simulated start time (s); null if the system was not loaded.
    pub start_time: Option<f64>,
    /// Simulated stop time (s); null if the system was not loaded.
    pub stop_time: Option<f64>,
    /// Nominal macro step (s); null if the system was not loaded.
    pub step_size: Option<f64>,
    /// The last step's length when it is shortened to end at a stop time off the grid
    /// (`stop_time − start_time` not a whole number of steps); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shortened_last_step: Option<f64>,
    /// Steps on the grid.
    pub steps: u64,
    /// Macro steps done when the run ended.
    pub steps_completed: u64,
    /// Last communication point reached.
    pub end_time: Option<f64>,
    /// `end_time − start_time`.
    pub simulated_time: f64,
    /// Wall-clock time of the whole run, including loading.
    pub wall_time: f64,
    /// `simulated_time / wall_time` (null if the wall time is zero).
    pub real_time_factor: Option<f64>,
    /// The results CSV.
    pub output: Option<String>,
    /// Data rows written to the results CSV (the header not counted).
    pub rows_recorded: u64,
    /// The recorded columns with their units (empty if the run did not get past loading).
    pub columns: Vec<ColumnSummary>,
    /// The system's instances, in system-file order (empty if it was not loaded).
    pub instances: Vec<InstanceSummary>,
    /// Which instance ended the run early and the time it reached, for status `terminated`:
    /// `{"instance": "stair", "time": 3.0}`; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub termination: Option<Termination>,
    /// Only when asked for (`crane-cosim run --timing`); absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub timing: Option<Timing>,
}

impl RunSummary {
    /// Records how far the run got: `steps` steps, ending at `end_time` (s) of a run started at
    /// `start_time` (s), with `rows` rows recorded.
    pub fn reached(&mut self, steps: u64, end_time: f64, start_time: f64, rows: u64) {
        self.steps_completed = steps;
        self.end_time = Some(end_time);
        self.simulated_time = end_time - start_time;
        self.rows_recorded = rows;
    }

    /// Records the wall time (s) and the real-time factor it gives (none for zero).
    pub fn timed(&mut self, wall_time: f64) {
        self.wall_time = wall_time;
        self.real_time_factor = if wall_time > 0.0 { Some(self.simulated_time / wall_time) } else { None };
    }

    /// Writes the summary as pretty JSON (creating parent directories), through a temporary
    /// file renamed over `file`, so that an earlier summary is replaced whole or not at all.
    pub fn write(&self, file: &Path) -> std::io::Result<()> {
        if let Some(parent) = file.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)?;
        }
        let json = serde_json::to_string_pretty(self).map_err(std::io::Error::other)?;
        crate::partial::persist_atomically(file, (json + "\n").as_bytes())
    }
}
