//! Running one `.fmu` without a system file (`crane-cosim run pendulum.fmu`): a system of one
//! instance, named after the file, with the FMU's default experiment as the time grid.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use fmu_import::fmu::Fmu;

use super::schema::{AlgorithmKind, InputSpec, InstanceSpec, RecordSpec, SystemSpec};
use super::{Overrides, Problem, SystemError};

/// What a single-FMU run takes besides the [`Overrides`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SingleFmu {
    /// Input CSVs (`time,<input>,…`) feeding the instance.
    pub inputs: Vec<PathBuf>,
    /// Variables to record: names or patterns with `*` (any characters) and `?` (one character);
    /// empty: every output.
    pub record: Vec<String>,
}

/// The instance name of a single-FMU run: the file name without `.fmu`, dots replaced by `_`
/// (instance names cannot contain dots), e.g. `pendulum` for `target/fmu/pendulum.fmu`.
pub fn instance_name(fmu: &Path) -> String {
    let stem = fmu.file_stem().map(|s| s.to_string_lossy().replace('.', "_")).unwrap_or_default();
    if stem.is_empty() {
        "fmu".into()
    } else {
        stem
    }
}

/// The system that runs `fmu` alone: start, stop time and step size from the command line, else
/// from the FMU's `DefaultExperiment`; start values come as `overrides.start` (`"<instance>.x"`).
/// Paths are kept as given (relative to the working directory). Problems name `file`.
pub fn spec(file: &Path, fmu: &Fmu, single: &SingleFmu, overrides: &Overrides) -> Result<SystemSpec, SystemError> {
    let name = instance_name(file);
    let experiment = fmu.model_description().default_experiment.unwrap_or_default();
    let mut problems = Vec::new();
    let mut required = |value: Option<f64>, what: &str, option: &str| {
        value.unwrap_or_else(|| {
            problems.push(Problem {
                location: option.into(),
                message: format!("the FMU's model description has no default {what}: give {option}"),
            });
            f64::NAN
        })
    };
    let stop_time = required(overrides.stop_time.or(experiment.stop_time), "stop time", "Overrides::stop_time");
    let step_size = required(overrides.step_size.or(experiment.step_size), "step size", "Overrides::step_size");
    let record = recorded(fmu, &name, &single.record, &mut problems);
    if !problems.is_empty() {
        return Err(SystemError::Invalid { file: file.to_path_buf(), problems });
    }
    Ok(SystemSpec {
        description: format!("{} alone", fmu.model_description().model_name),
        fmus: BTreeMap::from([(name.clone(), std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf()))]),
        instances: vec![InstanceSpec { name: name.clone(), fmu: name.clone(), start: BTreeMap::new() }],
        connections: Vec::new(),
        inputs: single.inputs.iter().map(|f| InputSpec { instance: name.clone(), file: f.clone() }).collect(),
        start_time: experiment.start_time.unwrap_or(0.0),
        stop_time,
        step_size,
        algorithm: AlgorithmKind::default(),
        // Inputs from CSV files are piecewise linear: their slopes are exact.
        input_derivatives: !single.inputs.is_empty(),
        record: RecordSpec { interval: None, variables: record },
    })
}

/// The qualified names matching `patterns`, in model-description order; `None` (every output)
/// for no patterns. A pattern matching nothing is a problem.
fn recorded(fmu: &Fmu, instance: &str, patterns: &[String], problems: &mut Vec<Problem>) -> Option<Vec<String>> {
    if patterns.is_empty() {
        return None;
    }
    let variables = &fmu.model_description().variables;
    for pattern in patterns {
        if !variables.iter().any(|v| glob_matches(pattern, &v.name)) {
            problems.push(Problem {
                location: format!("SingleFmu::record[{pattern:?}]"),
                message: format!("matches no variable of {}", fmu.model_description().model_name),
            });
        }
    }
    let matching = variables.iter().filter(|v| patterns.iter().any(|p| glob_matches(p, &v.name)));
    Some(matching.map(|v| format!("{instance}.{}", v.name)).collect())
}

/// True if `name` matches `pattern`, where `*` stands for any characters (also none) and `?` for
/// exactly one; everything else matches itself (`.` too).
pub fn glob_matches(pattern: &str, name: &str) -> bool {
    let (pattern, name): (Vec<char>, Vec<char>) = (pattern.chars().collect(), name.chars().collect());
    // Backtracking over the last `*` only: linear in practice, quadratic at worst.
    let (mut p, mut n, mut star, mut resume) = (0, 0, None, 0);
    while n < name.len() {
        if p < pattern.len() && (pattern[p] == '?' || pattern[p] == name[n]) {
            (p, n) = (p + 1, n + 1);
        } else if p < pattern.len() && pattern[p] == '*' {
            (star, resume, p) = (Some(p), n, p + 1);
        } else if let Some(s) = star {
            (p, resume) = (s + 1, resume + 1);
            n = resume;
        } else {
            return false;
        }
    }
    pattern[p..].iter().all(|&c| c == '*')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn glob_patterns() {
        assert!(glob_matches("load.*", "load.x") && glob_matches("load.*", "load."));
        assert!(!glob_matches("load.*", "loadx") && !glob_matches("load.*", "tip.load.x"));
        assert!(glob_matches("theta_?", "theta_x") && !glob_matches("theta_?", "theta_x0"));
        assert!(glob_matches("*.x", "pendulum.load.x") && !glob_matches("*.x", "pendulum.load.y"));
        assert!(glob_matches("*a*b*", "xaxxbx") && !glob_matches("*a*b*", "xbxa"));
        assert!(glob_matches("tension", "tension") && !glob_matches("tension", "tension2"));
    }

    #[test]
    fn instance_names_have_no_dots() {
        assert_eq!(instance_name(Path::new("target/fmu/pendulum.fmu")), "pendulum");
        assert_eq!(instance_name(Path::new("v1.2.fmu")), "v1_2");
    }
}
