//! The tuning file (docs/tuning.md): the parameters to tune with their bounds, the objective,
//! the training and held-out runs, and the optimiser's settings.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use cosim_engine::system::json::{self, FileKind};
use fmu_import::file::{read_regular_text, MAX_TEXT_FILE_BYTES};
use serde::{Deserialize, Serialize};

use crate::TuneError;
use cosim_studies::StudyError;
use crane_campaign::matrix::{self, Family, Variant};
use crane_campaign::summary::Group;
use crane_metrics::MetricId;

/// A tuning study as written by users (JSON).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tuning {
    #[serde(default)]
    pub description: String,
    /// The closed-loop system file, relative to the tuning file [default: the campaign's].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub system: Option<PathBuf>,
    /// The feedback variant tuned for: 1 truth, 2 sensors with noise.
    pub variant: u8,
    pub parameters: Vec<TunedParameter>,
    pub objective: Objective,
    /// The runs the optimiser sees.
    pub training: RunSelection,
    /// The runs the result is judged on and the optimiser never sees.
    pub held_out: RunSelection,
    #[serde(default)]
    pub optimizer: OptimizerSettings,
    /// `"instance.variable"` integer start values set from each seed of a [`RunSelection`]
    /// (the sensors' noise) [default: the IMUs' and the crane's `seed`].
    #[serde(default = "default_seed_variables")]
    pub seed_variables: Vec<String>,
}

fn default_seed_variables() -> Vec<String> {
    crane_names::TEST_SCALE.noise_seeds.iter().map(|name| name.to_string()).collect()
}

/// One tuned value: `name` is the `"instance.variable"` start value it sets, or a label when
/// `set` lists the start values it sets (e.g. both complementary filters' gain).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TunedParameter {
    pub name: String,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub set: Vec<String>,
    /// [lower, upper], finite, lower < upper (lower > 0 on a logarithmic scale).
    pub bounds: [f64; 2],
    /// Where the search starts [default: the system file's start value, else the FMU's].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    /// How the optimiser sees the range: `linear`, or `log` for a value spanning decades.
    #[serde(default)]
    pub scale: AxisScale,
}

impl TunedParameter {
    /// The start values it sets.
    pub fn targets(&self) -> Vec<String> {
        if self.set.is_empty() {
            vec![self.name.clone()]
        } else {
            self.set.clone()
        }
    }
}

/// The optimiser's coordinate along one parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AxisScale {
    #[default]
    Linear,
    Log,
}

/// What is minimised: the weighted mean over `terms` of the compensated-to-reference ratio of a
/// metric (1 − the eq. 7.1 reduction), plus `saturation.weight` × the fraction of time an actuator
/// command sits at a limit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Objective {
    pub terms: Vec<Term>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub saturation: Option<Saturation>,
}

/// A row of Tables 7.1–7.3: the group of test pairs and the metric.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Term {
    pub group: Group,
    #[serde(with = "metric_name")]
    pub metric: MetricId,
    #[serde(default = "one")]
    pub weight: f64,
}

fn one() -> f64 {
    1.0
}

/// The actuator commands and the ranges they saturate at.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Saturation {
    pub weight: f64,
    pub commands: Vec<Command>,
}

/// An actuator command (`"instance.variable"`, an output) and its [lower, upper] limits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Command {
    pub variable: String,
    pub range: [f64; 2],
}

/// Campaign tests and noise seeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunSelection {
    /// Test numbers, e.g. "41-60,89,92-94,102"; only the compensated tests count (each is
    /// compared with its reference, which runs once with the start values).
    pub tests: String,
    /// Noise seeds; none: the system file's own seeds (those of the campaign).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub seeds: Vec<u64>,
}

/// CMA-ES settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OptimizerSettings {
    /// Candidates per generation (λ) [default: 4 + ⌊3 ln n⌋ for n parameters].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub population: Option<usize>,
    pub generations: usize,
    /// The initial step, as a fraction of each parameter's range (in its scale).
    pub sigma: f64,
    pub seed: u64,
}

impl Default for OptimizerSettings {
    fn default() -> Self {
        OptimizerSettings { population: None, generations: 30, sigma: 0.2, seed: 0 }
    }
}

mod metric_name {
    use serde::{Deserialize, Deserializer, Serializer};

    use crane_metrics::MetricId;

    pub fn serialize<S: Serializer>(metric: &MetricId, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(metric.info().name)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<MetricId, D::Error> {
        let name = String::deserialize(deserializer)?;
        MetricId::compared().find(|m| m.info().name == name).ok_or_else(|| {
            let names: Vec<&str> = MetricId::compared().map(|m| m.info().name).collect();
            serde::de::Error::custom(format!("unknown metric '{name}', expected one of {}", names.join(", ")))
        })
    }
}

impl Tuning {
    /// Reads and checks a tuning file.
    pub fn load(file: &Path) -> Result<Tuning, TuneError> {
        let text = read_regular_text(file, MAX_TEXT_FILE_BYTES)
            .map_err(|source| StudyError::Read { file: file.into(), source })?;
        let tuning: Tuning =
            json::parse(&text, FileKind::Tuning).map_err(|error| StudyError::Parse { file: file.into(), error })?;
        tuning.check().map_err(|message| StudyError::Invalid { file: file.into(), message })?;
        Ok(tuning)
    }

    /// The feedback variant.
    pub fn variant(&self) -> Variant {
        // Checked by `check`.
        Variant::from_number(self.variant).unwrap_or(Variant::Truth)
    }

    /// The system file, resolved against the tuning file's folder.
    pub fn system_path(&self, tuning_file: &Path) -> Option<PathBuf> {
        self.system.as_ref().map(|system| tuning_file.parent().unwrap_or(Path::new("")).join(system))
    }

    /// λ: the population size.
    pub fn population(&self) -> usize {
        let n = self.parameters.len() as f64;
        self.optimizer.population.unwrap_or(4 + (3.0 * n.ln()).floor() as usize)
    }

    fn check(&self) -> Result<(), String> {
        if !matches!(self.variant, 1 | 2) {
            return Err(format!("variant {}: expected 1 (truth) or 2 (sensors)", self.variant));
        }
        if self.parameters.is_empty() {
            return Err("no parameters to tune".into());
        }
        let mut targets = BTreeSet::new();
        for parameter in &self.parameters {
            check_parameter(parameter)?;
            for target in parameter.targets() {
                if !targets.insert(target.clone()) {
                    return Err(format!("{target} is tuned twice"));
                }
            }
        }
        if let Some(seed) = self.seed_variables.iter().find(|s| targets.contains(*s)) {
            return Err(format!("{seed} is both tuned and a seed variable"));
        }
        self.check_objective()?;
        for (name, selection) in [("training", &self.training), ("held_out", &self.held_out)] {
            let tests = matrix::parse_selection(&selection.tests).map_err(|e| format!("{name}.tests: {e}"))?;
            if !tests.iter().any(|&n| compensated(n)) {
                return Err(format!("{name}.tests: no compensated test (041-080, 089-096, 102-104) among them"));
            }
        }
        let o = &self.optimizer;
        if o.generations == 0 || self.population() < 2 || !(o.sigma > 0.0 && o.sigma <= 1.0) {
            return Err("optimizer: generations ≥ 1, population ≥ 2 and 0 < sigma ≤ 1 are needed".into());
        }
        Ok(())
    }

    fn check_objective(&self) -> Result<(), String> {
        let objective = &self.objective;
        if objective.terms.is_empty() {
            return Err("objective: no terms".into());
        }
        if let Some(term) = objective.terms.iter().find(|t| !(t.weight > 0.0 && t.weight.is_finite())) {
            return Err(format!(
                "objective: term {:?}/{}: weight must be finite and > 0",
                term.group,
                term.metric.info().name
            ));
        }
        if let Some(saturation) = &objective.saturation {
            if !(saturation.weight >= 0.0 && saturation.weight.is_finite()) {
                return Err("objective.saturation.weight must be finite and ≥ 0".into());
            }
            if let Some(c) = saturation.commands.iter().find(|c| !(c.range[0] < c.range[1])) {
                return Err(format!(
                    "objective.saturation: {}: range must be [lower, upper], lower < upper",
                    c.variable
                ));
            }
        }
        Ok(())
    }
}

fn check_parameter(parameter: &TunedParameter) -> Result<(), String> {
    let [lower, upper] = parameter.bounds;
    let name = &parameter.name;
    if !(lower.is_finite() && upper.is_finite() && lower < upper) {
        return Err(format!("parameter {name}: bounds must be finite, [lower, upper] with lower < upper"));
    }
    if parameter.scale == AxisScale::Log && !(lower > 0.0) {
        return Err(format!("parameter {name}: a log scale needs bounds > 0"));
    }
    if let Some(start) = parameter.start.filter(|s| !(*s >= lower && *s <= upper)) {
        return Err(format!("parameter {name}: start {start} is outside the bounds [{lower}, {upper}]"));
    }
    match parameter.targets().iter().find(|t| t.split_once('.').is_none_or(|(i, v)| i.is_empty() || v.is_empty())) {
        Some(target) => Err(format!("parameter {name}: {target} is not written \"instance.variable\"")),
        None => Ok(()),
    }
}

/// Whether campaign test `number` is a compensated test of one of Tables 7.1–7.3.
pub fn compensated(number: u16) -> bool {
    matrix::tests().iter().any(|t| {
        t.number == number
            && t.control.compensated()
            && matrix::reference_of(t).is_some()
            && !(t.family == Family::VariableSetpoint && t.motion == matrix::Motion::Still)
    })
}
