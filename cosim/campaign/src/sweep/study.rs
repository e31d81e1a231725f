//! The study file: a base scenario, the parameters to vary and how to sample them, and the
//! metrics to collect from every case (see docs/sweeps.md).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::SweepError;

/// A study as written by users (JSON).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Study {
    #[serde(default)]
    pub description: String,
    /// The scenario every case starts from, relative to the study file.
    pub scenario: PathBuf,
    pub parameters: Vec<Parameter>,
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
    pub metrics: Vec<MetricSpec>,
}

/// One varied start value: `{"name": "instance.variable", "<kind>": ...}` with exactly one of
/// the kinds of [`Values`].
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "ParameterFile")]
pub struct Parameter {
    /// `"instance.variable"`.
    pub name: String,
    pub values: Values,
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
        match (given.next(), given.next()) {
            (Some(values), None) => Ok(Parameter { name: file.name, values }),
            _ => Err(format!("{}: give exactly one of grid, uniform, normal, lognormal", file.name)),
        }
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
    pub kind: MetricKind,
    pub from: f64,
    /// `None`: to the end of the results.
    pub to: Option<f64>,
}

/// What a metric measures.
#[derive(Debug, Clone, PartialEq)]
pub enum MetricKind {
    /// A statistic of one recorded `"instance.variable"`.
    Variable { variable: String, stat: Stat },
    /// A §7.2.2 metric of the load's position against its set-point.
    Load(LoadMetric),
}

/// The §7.2.2 metrics that need no test definition: computed, as in the campaign, from the load
/// (`pendulum.load.*`) and set-point (`controller.sp.load.*`) positions in W resampled at the
/// 30 Hz capture rate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LoadMetric {
    /// RMS Euclidean distance of the load from its set-point (m).
    Rmse,
    /// Distance travelled above the 3 mm frame-to-frame threshold (m).
    Distance,
    /// Volume of the ellipsoid holding 95 % of the load positions relative to the set-point (m³).
    EllipsoidVolume,
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
    metric: Option<LoadMetric>,
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
            (None, None, Some(metric)) => MetricKind::Load(metric),
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
            MetricKind::Load(LoadMetric::Rmse) => "rmse".into(),
            MetricKind::Load(LoadMetric::Distance) => "distance".into(),
            MetricKind::Load(LoadMetric::EllipsoidVolume) => "ellipsoid_volume".into(),
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
    pub fn load(file: &Path) -> Result<Study, SweepError> {
        let text = std::fs::read_to_string(file).map_err(|source| SweepError::Read { file: file.into(), source })?;
        let study: Study = serde_json::from_str(&text)
            .map_err(|e| SweepError::Invalid { file: file.into(), message: e.to_string() })?;
        study.check().map_err(|message| SweepError::Invalid { file: file.into(), message })?;
        Ok(study)
    }

    /// The base scenario's path, resolved against the study file's folder.
    pub fn scenario_path(&self, study_file: &Path) -> PathBuf {
        study_file.parent().unwrap_or(Path::new("")).join(&self.scenario)
    }

    fn check(&self) -> Result<(), String> {
        let mut names = BTreeSet::new();
        for parameter in &self.parameters {
            if !names.insert(parameter.name.as_str()) {
                return Err(format!("parameter {} is given twice", parameter.name));
            }
            check_values(parameter, self.sampling)?;
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The error of loading `json` as a study.
    fn error(json: &str) -> String {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("study.json");
        std::fs::write(&file, json).unwrap();
        Study::load(&file).unwrap_err().to_string()
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
