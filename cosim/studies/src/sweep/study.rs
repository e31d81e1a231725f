//! The study file: a base scenario, the parameters to vary and how to sample them, and the
//! metrics to collect from every case (see docs/sweeps.md).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use cosim_engine::system::json::{self, FileKind};
use serde::Deserialize;

use crate::StudyError;
use crane_metrics::MetricId;

/// A study as written by users (JSON).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Study {
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// The scenario every case starts from, relative to the study file.
    pub scenario: PathBuf,
    /// The sampled values.
    pub parameters: Vec<Parameter>,
    /// How the cases are drawn.
    pub sampling: Sampling,
    /// Number of cases of "random", "latin-hypercube" and "sobol" sampling ("grid": the product of the
    /// grids' lengths, so none may be given).
    #[serde(default)]
    pub cases: Option<usize>,
    /// The study seed: it draws the samples and derives every case's seed.
    #[serde(default)]
    pub seed: u64,
    /// `"instance.variable"` integer start values set from the case seed (e.g. the IMUs'
    /// `seed`), so that every case has its own noise.
    #[serde(default)]
    pub seed_variables: Vec<String>,
    /// What is collected from every case.
    pub metrics: Vec<MetricSpec>,
    /// `"instance.variable"` start values of a second run of every case (e.g.
    /// `{"controller.mode": 0}`: the crane off), laid over the case's own: each metric is also
    /// collected from it (`<metric>.baseline`) and compared (`<metric>.change`, eq. 7.1, %).
    #[serde(default)]
    pub baseline: Option<BTreeMap<String, serde_json::Value>>,
}

/// One sampled value: `{"name": ..., "<kind>": ...}` with exactly one of the kinds of
/// [`Values`], and optionally `"set"` or `"scale"` (see [`Targets`]).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "ParameterFile")]
pub struct Parameter {
    /// The plan's and results' column: the `"instance.variable"` it sets when it has no
    /// `set` or `scale`, else any label (e.g. `cable_length`).
    pub name: String,
    /// Where its values come from.
    pub values: Values,
    /// The start values the sampled value gives.
    pub targets: Targets,
}

/// The start values one sampled value gives (`"instance.variable"` names).
#[derive(Debug, Clone, PartialEq)]
pub enum Targets {
    /// Each start value is the sampled value (`"set"`, or the parameter's `name` alone).
    Set(Vec<String>),
    /// Each start value is the sampled value (dimensionless) × its base value: the base
    /// scenario's start value, else the FMU's default (its modelDescription `start`).
    Scale(Vec<String>),
}

impl Targets {
    /// The `"instance.variable"` names, set or scaled.
    pub fn names(&self) -> &[String] {
        match self {
            Targets::Set(names) | Targets::Scale(names) => names,
        }
    }
}

/// A parameter as written: the kinds as optional fields, so that a misspelt or second kind
/// is reported by name.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct ParameterFile {
    name: String,
    #[serde(default)]
    grid: Option<Vec<f64>>,
    #[serde(default)]
    uniform: Option<[f64; 2]>,
    #[serde(default)]
    normal: Option<[f64; 2]>,
    #[serde(default)]
    lognormal: Option<[f64; 2]>,
    #[serde(default)]
    set: Option<Vec<String>>,
    #[serde(default)]
    scale: Option<Vec<String>>,
}

impl TryFrom<ParameterFile> for Parameter {
    type Error = String;

    fn try_from(file: ParameterFile) -> Result<Self, String> {
        let kinds = [
            file.grid.map(Values::Grid),
            file.uniform.map(Values::Uniform),
            file.normal.map(Values::Normal),
            file.lognormal.map(Values::Lognormal),
        ];
        let mut given = kinds.into_iter().flatten();
        let values = match (given.next(), given.next()) {
            (Some(values), None) => values,
            _ => return Err(format!("{}: give exactly one of grid, uniform, normal, lognormal", file.name)),
        };
        let targets = match (file.set, file.scale) {
            (None, None) => Targets::Set(vec![file.name.clone()]),
            (Some(names), None) => Targets::Set(names),
            (None, Some(names)) => Targets::Scale(names),
            (Some(_), Some(_)) => return Err(format!("{}: give at most one of set, scale", file.name)),
        };
        Ok(Parameter { name: file.name, values, targets })
    }
}

/// Where a parameter's values come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Listed values: all of them with "grid" sampling, one at random (equally likely) per case
    /// otherwise.
    Grid(Vec<f64>),
    /// Uniform on [a, b].
    Uniform([f64; 2]),
    /// Normal with mean μ and standard deviation σ.
    Normal([f64; 2]),
    /// exp of a normal with mean μ and standard deviation σ (of the logarithm).
    Lognormal([f64; 2]),
}

impl Values {
    /// The distribution as in a study file, e.g. `normal [0, 1e300]`, for messages.
    pub fn describe(&self) -> String {
        match self {
            Values::Grid(values) => format!("grid of {} values", values.len()),
            Values::Uniform([a, b]) => format!("uniform [{a:?}, {b:?}]"),
            Values::Normal([mu, sigma]) => format!("normal [{mu:?}, {sigma:?}]"),
            Values::Lognormal([mu, sigma]) => format!("lognormal [{mu:?}, {sigma:?}]"),
        }
    }
}

/// How the cases are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sampling {
    /// The cartesian product of the grids, the first parameter varying slowest.
    Grid,
    /// Independent draws.
    Random,
    /// One draw in each of `cases` equal-probability strata of every parameter, strata paired
    /// at random.
    LatinHypercube,
    /// The first `cases` points of an Owen-scrambled Sobol sequence (low discrepancy; best with
    /// a power of two cases).
    Sobol,
}

/// Most cases and parameters of "sobol" sampling (the limits of the Sobol generator).
pub const SOBOL_LIMITS: (usize, usize) = (1 << 16, 256);

/// A metric collected from every case, over the results at times in [`from`, `to`] (s).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "MetricFile")]
pub struct MetricSpec {
    /// What it measures.
    pub kind: MetricKind,
    /// Start of the window (s).
    pub from: f64,
    /// `None`: to the end of the results.
    pub to: Option<f64>,
}

/// What a metric measures.
#[derive(Debug, Clone, PartialEq)]
pub enum MetricKind {
    /// A statistic of one recorded `"instance.variable"`.
    Variable { variable: String, stat: Stat },
    /// A §7.2.2 metric of the catalogue, computed as in the campaign from what its
    /// [`Source`](crane_metrics::catalogue::Source) names, resampled at the 30 Hz capture rate.
    Catalogue(MetricId),
}

/// A metric as written: `{"variable": ..., "stat": ...}` or `{"metric": ...}`, with `from`
/// and `to`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct MetricFile {
    #[serde(default)]
    variable: Option<String>,
    #[serde(default)]
    stat: Option<Stat>,
    #[serde(default)]
    metric: Option<MetricId>,
    #[serde(default)]
    from: f64,
    #[serde(default)]
    to: Option<f64>,
}

impl TryFrom<MetricFile> for MetricSpec {
    type Error = String;

    fn try_from(file: MetricFile) -> Result<Self, String> {
        let kind = match (file.variable, file.stat, file.metric) {
            (Some(variable), Some(stat), None) => MetricKind::Variable { variable, stat },
            (None, None, Some(metric)) => MetricKind::Catalogue(metric),
            _ => return Err("a metric is {\"variable\": ..., \"stat\": ...} or {\"metric\": ...}".into()),
        };
        match file.to {
            Some(to) if !(to >= file.from) => Err(format!("a metric's window [{}, {to}] is empty", file.from)),
            _ => Ok(MetricSpec { kind, from: file.from, to: file.to }),
        }
    }
}

impl MetricSpec {
    /// The metric's column name, e.g. `pendulum.theta_x.rms` or `rmse`.
    pub fn name(&self) -> String {
        match &self.kind {
            MetricKind::Variable { variable, stat } => format!("{variable}.{}", stat.name()),
            MetricKind::Catalogue(id) => id.name().into(),
        }
    }
}

/// A statistic of a recorded variable over its samples (one per recorded step).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Stat {
    /// Root mean square √(Σx²/n).
    Rms,
    /// Largest value.
    Max,
    /// Mean Σx/n.
    Mean,
    /// Population standard deviation √(Σ(x − mean)²/n).
    Std,
}

impl Stat {
    pub fn name(self) -> &'static str {
        match self {
            Stat::Rms => "rms",
            Stat::Max => "max",
            Stat::Mean => "mean",
            Stat::Std => "std",
        }
    }

    /// The statistic of `values` at the `times` in [`from`, `to`]; `None` if no sample is.
    pub fn of(self, times: &[f64], values: &[f64], from: f64, to: f64) -> Option<f64> {
        let inside = |t: f64| t >= from && t <= to;
        let window: Vec<f64> = times.iter().zip(values).filter(|(t, _)| inside(**t)).map(|(_, v)| *v).collect();
        if window.is_empty() {
            return None;
        }
        let n = window.len() as f64;
        let mean = window.iter().sum::<f64>() / n;
        Some(match self {
            Stat::Rms => (window.iter().map(|v| v * v).sum::<f64>() / n).sqrt(),
            Stat::Max => window.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            Stat::Mean => mean,
            Stat::Std => (window.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n).sqrt(),
        })
    }
}

impl Study {
    /// Reads and checks a study file.
    pub fn load(file: &Path) -> Result<Study, StudyError> {
        let text = crate::files::read_text(file)?;
        let study: Study =
            json::parse(&text, FileKind::Study).map_err(|error| StudyError::Parse { file: file.into(), error })?;
        study.check().map_err(|message| StudyError::Invalid { file: file.into(), message })?;
        Ok(study)
    }

    /// The base scenario's path, resolved against the study file's folder.
    pub fn scenario_path(&self, study_file: &Path) -> PathBuf {
        study_file.parent().unwrap_or(Path::new("")).join(&self.scenario)
    }

    /// The metrics' columns: each metric's [`MetricSpec::name`], followed with a `baseline` by
    /// `<name>.baseline` and `<name>.change`.
    pub fn metric_names(&self) -> Vec<String> {
        let suffixes: &[&str] = if self.baseline.is_some() { &["", ".baseline", ".change"] } else { &[""] };
        self.metrics.iter().flat_map(|m| suffixes.iter().map(move |suffix| format!("{}{suffix}", m.name()))).collect()
    }

    fn check(&self) -> Result<(), String> {
        let mut names = BTreeSet::new();
        for parameter in &self.parameters {
            if !names.insert(parameter.name.as_str()) {
                return Err(format!("parameter {} is given twice", parameter.name));
            }
            check_values(parameter, self.sampling)?;
        }
        self.check_targets()?;
        match (self.sampling, self.cases) {
            (Sampling::Grid, Some(_)) => Err("grid sampling has as many cases as grid points: drop \"cases\"".into()),
            (_, None | Some(0)) if self.sampling != Sampling::Grid => {
                Err("random, latin-hypercube and sobol sampling need \"cases\" ≥ 1".into())
            }
            (Sampling::Sobol, Some(cases)) if cases > SOBOL_LIMITS.0 || self.parameters.len() > SOBOL_LIMITS.1 => {
                Err(format!("sobol sampling takes at most {} cases and {} parameters", SOBOL_LIMITS.0, SOBOL_LIMITS.1))
            }
            _ if self.metrics.is_empty() => Err("no metrics to collect".into()),
            _ => Ok(()),
        }
    }

    /// Every start value is given by one parameter, seed variable or baseline entry at most
    /// (a second would silently override the first), and is named `"instance.variable"`.
    fn check_targets(&self) -> Result<(), String> {
        let mut owners: BTreeMap<&str, String> = BTreeMap::new();
        let parameters = self.parameters.iter().map(|p| (format!("parameter {}", p.name), p.targets.names()));
        let seeds = std::iter::once(("seed_variables".to_string(), self.seed_variables.as_slice()));
        if let Some(parameter) = self.parameters.iter().find(|p| p.targets.names().is_empty()) {
            return Err(format!("parameter {}: \"set\" or \"scale\" lists no start value", parameter.name));
        }
        for (owner, targets) in parameters.chain(seeds) {
            for target in targets {
                check_name(target).map_err(|message| format!("{owner}: {message}"))?;
                if let Some(first) = owners.insert(target, owner.clone()) {
                    return Err(format!("{target} is given by both {first} and {owner}"));
                }
            }
        }
        match &self.baseline {
            Some(baseline) if baseline.is_empty() => Err("baseline: give the start values of the baseline run".into()),
            Some(baseline) => baseline.keys().try_for_each(|key| match owners.get(key.as_str()) {
                Some(owner) => Err(format!("baseline: {key} is already given by {owner}")),
                None => check_name(key).map_err(|message| format!("baseline: {message}")),
            }),
            None => Ok(()),
        }
    }
}

/// Checks that `name` reads `"instance.variable"`.
fn check_name(name: &str) -> Result<(), String> {
    match name.split_once('.') {
        Some((instance, variable)) if !instance.is_empty() && !variable.is_empty() => Ok(()),
        _ => Err(format!("{name:?} is not \"instance.variable\"")),
    }
}

fn check_values(parameter: &Parameter, sampling: Sampling) -> Result<(), String> {
    let name = &parameter.name;
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    match (&parameter.values, sampling) {
        (Values::Grid(values), _) if !values.is_empty() && finite(values) => Ok(()),
        (Values::Grid(_), _) => Err(format!("{name}: a grid needs at least one finite value")),
        (_, Sampling::Grid) => Err(format!("{name}: grid sampling needs a \"grid\" for every parameter")),
        (Values::Uniform([a, b]), _) if finite(&[*a, *b]) && a <= b => Ok(()),
        (Values::Uniform(_), _) => Err(format!("{name}: uniform [a, b] needs finite a ≤ b")),
        (Values::Normal([mu, sigma]) | Values::Lognormal([mu, sigma]), _)
            if finite(&[*mu, *sigma]) && *sigma >= 0.0 =>
        {
            Ok(())
        }
        _ => Err(format!("{name}: [μ, σ] needs finite μ and σ ≥ 0")),
    }
}

/// Loads `json` from a study file of its own (in a temporary folder), for the tests of the sweep's
/// modules.
#[cfg(test)]
pub(super) fn load_json(json: &str) -> Result<Study, StudyError> {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("study.json");
    std::fs::write(&file, json).unwrap();
    Study::load(&file)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The error of loading `json` as a study.
    fn error(json: &str) -> String {
        load_json(json).unwrap_err().to_string()
    }

    const METRICS: &str = r#""metrics": [{"variable": "pendulum.theta_x", "stat": "rms"}]"#;

    #[test]
    fn inconsistent_studies_are_refused_with_the_reason() {
        let grid = |parameters: &str, extra: &str| {
            format!(r#"{{"scenario": "s.json", "sampling": "grid", {METRICS}, "parameters": [{parameters}]{extra}}}"#)
        };
        let lp = r#"{"name": "crane.lp0", "grid": [0.5]}"#;
        assert!(error(&grid(lp, r#", "cases": 3"#)).ends_with("drop \"cases\""));
        assert!(error(&grid(&format!("{lp}, {lp}"), "")).ends_with("parameter crane.lp0 is given twice"));
        let uniform = r#"{"name": "crane.lp0", "uniform": [1, 0]}"#;
        assert!(error(&grid(uniform, "")).ends_with("crane.lp0: grid sampling needs a \"grid\" for every parameter"));
        let random = format!(
            r#"{{"scenario": "s.json", "sampling": "random", "cases": 2, {METRICS}, "parameters": [{uniform}]}}"#
        );
        assert!(error(&random).ends_with("crane.lp0: uniform [a, b] needs finite a ≤ b"), "{}", error(&random));
        let sobol = random.replace(r#""random", "cases": 2"#, r#""sobol", "cases": 65537"#).replace("[1, 0]", "[0, 1]");
        assert!(
            error(&sobol).ends_with("sobol sampling takes at most 65536 cases and 256 parameters"),
            "{}",
            error(&sobol)
        );
        let typo = format!(r#"{{"scenario": "s.json", "sampling": "grid", "metric": [], "parameters": [{lp}]}}"#);
        assert!(error(&typo).contains("unknown field `metric`"), "{}", error(&typo));
        let misspelt = grid(r#"{"name": "crane.lp0", "grdi": [0.5]}"#, "");
        assert!(error(&misspelt).contains("unknown field `grdi`"), "{}", error(&misspelt));
        let two = grid(r#"{"name": "crane.lp0", "grid": [0.5], "normal": [0, 1]}"#, "");
        assert!(
            error(&two).contains("crane.lp0: give exactly one of grid, uniform, normal, lognormal"),
            "{}",
            error(&two)
        );
        let both = grid(lp, "").replace(r#""stat": "rms""#, r#""stat": "rms", "metric": "rmse""#);
        assert!(error(&both).contains("a metric is {\"variable\""), "{}", error(&both));
        let window = grid(lp, "")
            .replace(r#""variable": "pendulum.theta_x", "stat": "rms""#, r#""metric": "distance", "from": 5, "to": 4"#);
        assert!(error(&window).contains("a metric's window [5, 4] is empty"), "{}", error(&window));
        let stat = grid(lp, "").replace("\"rms\"", "\"median\"");
        assert!(error(&stat).contains("unknown variant `median`"), "{}", error(&stat));
    }

    #[test]
    fn malformed_linked_scaled_and_baseline_start_values_are_refused() {
        let study = |parameters: &str, extra: &str| {
            format!(
                r#"{{"scenario": "s.json", "sampling": "random", "cases": 2, {METRICS}, "seed_variables": ["imu1.seed"],
                    "parameters": [{parameters}]{extra}}}"#
            )
        };
        let both = r#"{"name": "l", "set": ["crane.lp0"], "scale": ["crane.lp0"], "uniform": [0, 1]}"#;
        assert!(error(&study(both, "")).contains("l: give at most one of set, scale"), "{}", error(&study(both, "")));
        let empty = r#"{"name": "noise", "scale": [], "uniform": [0, 1]}"#;
        let message = error(&study(empty, ""));
        assert!(message.ends_with("parameter noise: \"set\" or \"scale\" lists no start value"), "{message}");
        let no_instance = r#"{"name": "l", "set": ["crane.lp0", "lp0"], "uniform": [0, 1]}"#;
        let message = error(&study(no_instance, ""));
        assert!(message.ends_with("parameter l: \"lp0\" is not \"instance.variable\""), "{message}");
        let twice = r#"{"name": "l", "set": ["crane.lp0", "controller.sp.lp"], "uniform": [0.4, 1]},
                       {"name": "controller.sp.lp", "grid": [0.7]}"#;
        let message = error(&study(twice, ""));
        assert!(
            message.ends_with("controller.sp.lp is given by both parameter l and parameter controller.sp.lp"),
            "{message}"
        );
        let seed = r#"{"name": "s", "scale": ["imu1.seed"], "uniform": [0, 1]}"#;
        let message = error(&study(seed, ""));
        assert!(message.ends_with("imu1.seed is given by both parameter s and seed_variables"), "{message}");
        let lp = r#"{"name": "crane.lp0", "uniform": [0.4, 1]}"#;
        let message = error(&study(lp, r#", "baseline": {"crane.lp0": 0.7}"#));
        assert!(message.ends_with("baseline: crane.lp0 is already given by parameter crane.lp0"), "{message}");
        let message = error(&study(lp, r#", "baseline": {}"#));
        assert!(message.ends_with("baseline: give the start values of the baseline run"), "{message}");
        let message = error(&study(lp, r#", "baseline": {"mode": 0}"#));
        assert!(message.ends_with("baseline: \"mode\" is not \"instance.variable\""), "{message}");
        let swing =
            study(lp, "").replace(r#""variable": "pendulum.theta_x", "stat": "rms""#, r#""metric": "tau_theta""#);
        let message = error(&swing);
        assert!(message.contains("unknown variant `tau_theta`, expected one of `tau_theta_x`"), "{message}");
    }

    #[test]
    fn studies_accept_every_catalogue_metric_by_its_name_and_no_other() {
        // The names study files have always used: the catalogue must not rename one.
        let mut names = crane_metrics::catalogue::NAMES.to_vec();
        names.sort_unstable();
        let expected = [
            "distance",
            "ellipsoid_volume",
            "peak_height",
            "peak_theta_x",
            "peak_theta_y",
            "rmse",
            "tau_height",
            "tau_theta_x",
            "tau_theta_y",
        ];
        assert_eq!(names, expected);
        for id in MetricId::ALL {
            let file = format!(r#"{{"metric": "{id}", "from": 10}}"#);
            let spec: MetricSpec = serde_json::from_str(&file).unwrap();
            assert_eq!((spec.name(), spec.kind), (id.name().to_string(), MetricKind::Catalogue(id)));
        }
    }

    #[test]
    fn linked_and_scaled_parameters_name_their_column_and_start_values() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("study.json");
        let json = format!(
            r#"{{"scenario": "s.json", "sampling": "grid", {METRICS}, "baseline": {{"controller.mode": 0}},
                "parameters": [{{"name": "cable_length", "set": ["crane.lp0", "controller.sp.lp"], "grid": [0.5]}},
                               {{"name": "noise", "scale": ["imu1.gyro.sigma.x"], "grid": [2]}},
                               {{"name": "crane.d0.jib", "grid": [0.01]}}]}}"#
        );
        std::fs::write(&file, json).unwrap();
        let study = Study::load(&file).unwrap();
        let targets: Vec<&Targets> = study.parameters.iter().map(|p| &p.targets).collect();
        let names = |list: &[&str]| list.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(targets[0], &Targets::Set(names(&["crane.lp0", "controller.sp.lp"])));
        assert_eq!(targets[1], &Targets::Scale(names(&["imu1.gyro.sigma.x"])));
        assert_eq!(targets[2], &Targets::Set(names(&["crane.d0.jib"])));
        assert_eq!(
            study.metric_names(),
            ["pendulum.theta_x.rms", "pendulum.theta_x.rms.baseline", "pendulum.theta_x.rms.change"]
        );
    }

    #[test]
    fn statistics_cover_the_samples_from_the_start_of_their_window() {
        let times = [0.0, 1.0, 2.0, 3.0];
        let values = [100.0, 3.0, -4.0, 1.0];
        let end = f64::INFINITY;
        assert_eq!(Stat::Mean.of(&times, &values, 1.0, end), Some(0.0));
        assert_eq!(Stat::Max.of(&times, &values, 1.0, end), Some(3.0));
        assert_eq!(Stat::Max.of(&times, &values, 0.0, 0.5), Some(100.0));
        assert_eq!(Stat::Rms.of(&times, &values, 1.0, end), Some((26.0f64 / 3.0).sqrt()));
        assert_eq!(Stat::Std.of(&times, &values, 2.0, end), Some(2.5));
        assert_eq!(Stat::Mean.of(&times, &values, 1.0, 2.0), Some(-0.5));
        assert_eq!(Stat::Max.of(&times, &values, 3.5, end), None);
    }
}
