//! Scenario files: a system file plus overrides, so one wired system (e.g. the closed loop)
//! serves many tests.
//!
//! ```json
//! {
//!   "description": "700 mm pendulum released at -23 deg, compensated",
//!   "system": "../systems/closed_loop.json",
//!   "start": { "pendulum.theta_x0": -0.4014, "controller.mode": 2 },
//!   "stop_time": 130.0
//! }
//! ```
//!
//! `start` keys are `"instance.variable"` and are added to (or replace) that instance's start
//! values; `stop_time`, `step_size`, `algorithm` and `record` replace the system's. The system
//! path is relative to the scenario file; the system's own paths stay relative to the system file.
//! A start value `{"path": "waves.csv"}` is a file relative to the file that gives it (scenario
//! or system), passed to the FMU as an absolute path (`resolve_path_value`).
//!
//! Loading a scenario reads and parses its system file and applies the scenario's settings to it:
//! a scenario parses to the [`SystemSpec`] it stands for.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::json::{self, FileKind};
use super::overrides::{apply_start, resolve_path_value};
use super::schema::{AlgorithmKind, RecordSpec, SystemSpec};
use super::{Problem, SystemError, SystemFiles};

/// A scenario file as written by users.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioSpec {
    /// Free text.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub description: String,
    /// The system file this scenario runs.
    pub system: PathBuf,
    /// `"instance.variable"` → start value.
    #[serde(default)]
    pub start: BTreeMap<String, serde_json::Value>,
    /// Replaces the system file's stop time (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop_time: Option<f64>,
    /// Replaces the system file's step size (s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub step_size: Option<f64>,
    /// Replaces the system file's algorithm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub algorithm: Option<AlgorithmKind>,
    /// Replaces the system file's recording.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub record: Option<RecordSpec>,
}

/// The system file of a scenario with its overrides applied, and that system file's path.
pub fn resolve(text: &str, file: &Path, files: &SystemFiles) -> Result<(SystemSpec, PathBuf), SystemError> {
    let scenario: ScenarioSpec = json::parse(text, FileKind::Scenario)
        .map_err(|error| SystemError::Parse { file: file.to_path_buf(), error })?;
    resolve_spec(&scenario, file, files)
}

/// The system file of an in-memory scenario with its overrides applied, and that system file's
/// path; `file` is where the scenario is (or would be) written: its `system` path is relative to
/// it, and problems are reported against it. The system file is taken from `files`.
pub fn resolve_spec(
    scenario: &ScenarioSpec,
    file: &Path,
    files: &SystemFiles,
) -> Result<(SystemSpec, PathBuf), SystemError> {
    let system_file = file.parent().unwrap_or_else(|| Path::new("")).join(&scenario.system);
    let mut spec = files.spec(&system_file)?;
    apply(scenario, file, &mut spec).map_err(|problems| SystemError::Invalid { file: file.to_path_buf(), problems })?;
    Ok((spec, system_file))
}

fn apply(scenario: &ScenarioSpec, file: &Path, spec: &mut SystemSpec) -> Result<(), Vec<Problem>> {
    let folder = file.parent().unwrap_or_else(|| Path::new(""));
    let start = scenario.start.iter().map(|(key, value)| (key.as_str(), resolve_path_value(value, folder)));
    let problems = apply_start(start, |key| format!("start[{key:?}]"), spec);
    spec.replace_grid(scenario.stop_time, scenario.step_size, scenario.algorithm);
    if let Some(record) = &scenario.record {
        spec.record = record.clone();
    }
    if !scenario.description.is_empty() {
        spec.description = scenario.description.clone();
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems)
    }
}
