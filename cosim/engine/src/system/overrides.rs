//! Step 3 of loading a system: what the caller changes in the parsed specification (a command
//! line's stop time, step size, algorithm and start values), and the start values given as files.

use std::path::Path;

use super::schema::{AlgorithmKind, SystemSpec};
use super::{Problem, SystemError};

/// Changes to a parsed specification, applied before validation. A problem they cause is located
/// at the field, e.g. `Overrides::start["pendulum.x"]`, so that a front end can name its own
/// option instead.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// Replaces `stop_time` (s).
    pub stop_time: Option<f64>,
    /// Replaces `step_size` (s).
    pub step_size: Option<f64>,
    /// Replaces `algorithm` (also a scenario's).
    pub algorithm: Option<AlgorithmKind>,
    /// Replaces `record.interval` (s), also a scenario's.
    pub record_interval: Option<f64>,
    /// Replaces `input_derivatives` (for one FMU run alone: on with inputs files).
    pub input_derivatives: Option<bool>,
    /// Replaces `extrapolate_inputs` (Jacobi).
    pub extrapolate_inputs: Option<bool>,
    /// `"instance.variable"` → start value, added to (or replacing) the file's; a value
    /// `{"path": "file"}` is a path relative to the working directory.
    pub start: Vec<(String, serde_json::Value)>,
    /// `"instance.variable"` names or patterns (`*` any characters, `?` one) recorded after the
    /// file's own (or after every output when the file names none), each column once. A problem
    /// is located at `Overrides::record["name"]`.
    pub record: Vec<String>,
    /// Input tables (CSV, relative to the working directory) whose columns are named
    /// `instance.variable` after `time`, each feeding that input. A problem is located at
    /// `Overrides::inputs["file"]`.
    pub inputs: Vec<std::path::PathBuf>,
}

/// Makes the start values of `spec` given as `{"path": …}` absolute (relative to `base`), then
/// applies `overrides`; problems are reported against `file`.
pub(super) fn apply(
    mut spec: SystemSpec,
    file: &Path,
    base: &Path,
    overrides: &Overrides,
) -> Result<SystemSpec, SystemError> {
    for instance in &mut spec.instances {
        for value in instance.start.values_mut() {
            *value = resolve_path_value(value, base);
        }
    }
    spec.replace_grid(overrides.stop_time, overrides.step_size, overrides.algorithm);
    if let Some(interval) = overrides.record_interval {
        spec.record.interval = Some(interval);
    }
    if let Some(derivatives) = overrides.input_derivatives {
        spec.input_derivatives = derivatives;
    }
    if let Some(extrapolate) = overrides.extrapolate_inputs {
        spec.extrapolate_inputs = extrapolate;
    }
    let start = overrides.start.iter().map(|(key, value)| (key.as_str(), resolve_path_value(value, Path::new(""))));
    let problems = apply_start(start, |key| format!("Overrides::start[{key:?}]"), &mut spec);
    if problems.is_empty() {
        Ok(spec)
    } else {
        Err(SystemError::Invalid { file: file.to_path_buf(), problems })
    }
}

/// Adds `"instance.variable"` → value start values to the instances of `spec` (replacing any
/// they had); `location` names a key in problems (a scenario's `start[...]`, an override's).
pub fn apply_start<'a>(
    start: impl IntoIterator<Item = (&'a str, serde_json::Value)>,
    location: impl Fn(&str) -> String,
    spec: &mut SystemSpec,
) -> Vec<Problem> {
    let mut problems = Vec::new();
    for (key, value) in start {
        let (instance, variable) = key.split_once('.').unwrap_or((key, ""));
        match spec.instances.iter_mut().find(|i| i.name == instance) {
            Some(target) if !variable.is_empty() => {
                target.start.insert(variable.to_string(), value);
            }
            Some(_) => {
                problems.push(Problem { location: location(key), message: "expected \"instance.variable\"".into() })
            }
            None => problems.push(Problem {
                location: location(key),
                message: format!(
                    "unknown instance '{instance}' (instances: {})",
                    spec.instances.iter().map(|i| i.name.as_str()).collect::<Vec<_>>().join(", ")
                ),
            }),
        }
    }
    problems
}

/// A start value written `{"path": "motion.csv"}` becomes the string of that path resolved
/// against `folder` (the folder of the file that gives the value) and made absolute: an FMU
/// resolves a relative path against its own working folder, which is not the user's. Every other
/// value is returned as it is.
pub fn resolve_path_value(value: &serde_json::Value, folder: &Path) -> serde_json::Value {
    let relative = value.as_object().filter(|o| o.len() == 1).and_then(|o| o.get("path")).and_then(|p| p.as_str());
    match relative {
        Some(relative) => {
            let joined = folder.join(relative);
            let path = std::path::absolute(&joined).unwrap_or(joined);
            serde_json::Value::String(path.to_string_lossy().into_owned())
        }
        None => value.clone(),
    }
}
