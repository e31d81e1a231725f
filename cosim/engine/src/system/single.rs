//! Running one `.fmu` without a system file (`crane-cosim run pendulum.fmu`): a system of one
//! instance, named after the file, with the FMU's default experiment as the time grid.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use fmu_import::fmu::{DefaultExperiment, Fmu};

use super::schema::{AlgorithmKind, InputSpec, InstanceSpec, RecordSpec, SystemSpec};
use super::{Overrides, SystemError};

/// What a single-FMU run takes besides the [`Overrides`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SingleFmu {
    /// Input CSVs (`time,<input>,…`) feeding the instance.
    pub inputs: Vec<PathBuf>,
    /// Variables to record: names or patterns with `*` (any characters) and `?` (one character),
    /// expanded as a system file's `record.variables` are (a pattern matches outputs and locals,
    /// an exact name any variable); empty: every output.
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
/// from the FMU's `DefaultExperiment`, else chosen as FMPy chooses them ([`fmpy_defaults`]); start
/// values come as `overrides.start` (`"<instance>.x"`). Paths are kept as given (relative to the
/// working directory). Problems name `file`.
pub fn spec(file: &Path, fmu: &Fmu, single: &SingleFmu, overrides: &Overrides) -> Result<SystemSpec, SystemError> {
    let name = instance_name(file);
    let experiment = fmu.model_description().default_experiment.unwrap_or_default();
    let (stop_time, step_size) = grid(&experiment, overrides);
    // Patterns are given to validation as `Overrides::record` (`System::load_fmu`): none here.
    let record = (!single.record.is_empty()).then(Vec::new);
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
        extrapolate_inputs: false,
        record: RecordSpec { interval: None, variables: record },
    })
}

/// Stop time and step size (s): the command line's, else the default experiment's, else
/// [`fmpy_defaults`].
fn grid(experiment: &DefaultExperiment, overrides: &Overrides) -> (f64, f64) {
    let start = experiment.start_time.unwrap_or(0.0);
    let stop = overrides.stop_time.or(experiment.stop_time).unwrap_or(start + FMPY_DURATION);
    let step = overrides.step_size.or(experiment.step_size).unwrap_or_else(|| fmpy_interval(stop - start));
    (stop, step)
}

/// What the run of a lone FMU took from neither the command line nor the FMU's default experiment,
/// as lines to print: empty when both gave everything.
pub fn fmpy_defaults(fmu: &Fmu, overrides: &Overrides) -> Vec<String> {
    let experiment = fmu.model_description().default_experiment.unwrap_or_default();
    let (stop, step) = grid(&experiment, overrides);
    let mut notes = Vec::new();
    if overrides.stop_time.or(experiment.stop_time).is_none() {
        notes.push(format!(
            "the FMU's model description gives no stop time: running to {stop} s, {FMPY_DURATION} s after the start \
             as FMPy does (--stop-time changes it)"
        ));
    }
    if overrides.step_size.or(experiment.step_size).is_none() {
        notes.push(format!(
            "the FMU's model description gives no step size: stepping {step} s, FMPy's 500 to 1000 steps of a \
             round size over the run (--step-size changes it)"
        ));
    }
    notes
}

/// FMPy's run length (s) when neither the caller nor the model description gives a stop time.
const FMPY_DURATION: f64 = 1.0;

/// The communication step FMPy takes for a run of `duration` (s) without a step size from the
/// caller or the model description (`fmpy.util.auto_interval`): 10^(round(log10 d) − 3), scaled by
/// 5, 4, 2, 1/5, 1/4 or 1/2 so that the run takes 500 to 1000 steps, e.g. 2 ms for 1 s.
pub fn fmpy_interval(duration: f64) -> f64 {
    // np.round rounds halves to even.
    let h = 10f64.powf(duration.log10().round_ties_even() - 3.0);
    match duration / h {
        n if n >= 2500.0 => h * 5.0,
        n if n >= 2000.0 => h * 4.0,
        n if n >= 1000.0 => h * 2.0,
        n if n <= 200.0 => h / 5.0,
        n if n <= 250.0 => h / 4.0,
        n if n <= 500.0 => h / 2.0,
        _ => h,
    }
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
    fn the_step_fmpy_would_choose() {
        // fmpy.util.auto_interval(d) for these durations (FMPy 0.3.32), to the bit.
        let expected = [
            (1.0, 0.002),
            (3.0, 0.005),
            (10.0, 0.02),
            (60.0, 0.1),
            (0.1, 0.0002),
            (130.0, 0.2),
            (400.0, 0.5),
            (0.03, 5e-05),
        ];
        for (duration, step) in expected {
            assert_eq!(fmpy_interval(duration), step, "{duration} s");
        }
    }

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
