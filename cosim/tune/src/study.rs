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

/// The most parameters a tuning may tune: CMA-ES keeps an n × n covariance and decomposes it
/// every generation, so n sizes both memory and time (the controller has about a dozen).
pub const MAX_PARAMETERS: usize = 100;
/// The largest population (λ) a tuning may ask for: each generation allocates λ points and
/// runs λ candidates' campaign runs (the default for 100 parameters is 17).
pub const MAX_POPULATION: usize = 10_000;
/// The most generations a tuning may ask for (the replay walks every earlier generation).
pub const MAX_GENERATIONS: usize = 100_000;
/// The most noise seeds a run selection may list (each multiplies the runs of every candidate).
pub const MAX_SEEDS: usize = 10_000;

/// A tuning study as written by users (JSON).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Tuning {
    /// Free text, for the report.
    #[serde(default)]
    pub description: String,
    /// The closed-loop system file, relative to the tuning file [default: the campaign's].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub system: Option<PathBuf>,
    /// The feedback variant tuned for: 1 truth, 2 sensors with noise.
    pub variant: u8,
    /// The start values tuned, with their ranges.
    pub parameters: Vec<TunedParameter>,
    /// What the optimiser minimises.
    pub objective: Objective,
    /// The runs the optimiser sees.
    pub training: RunSelection,
    /// The runs the result is judged on and the optimiser never sees.
    pub held_out: RunSelection,
    /// The search's settings (population, generations, step size, seed).
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
    /// The `"instance.variable"` start value it sets, or a label when `set` is given.
    pub name: String,
    /// The `"instance.variable"` start values it sets (all to the same value); empty: `name`.
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
    /// The weighted terms, one per row of Tables 7.1–7.3 tuned for.
    pub terms: Vec<Term>,
    /// The penalty for commands at their limits; none: no penalty.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub saturation: Option<Saturation>,
}

/// A row of Tables 7.1–7.3: the group of test pairs and the metric.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Term {
    /// The group of test pairs.
    pub group: Group,
    /// The metric compared within each pair.
    #[serde(with = "metric_name")]
    pub metric: MetricId,
    /// Its weight in the objective [default: 1].
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
    /// Objective added per unit of the mean fraction of samples at a limit.
    pub weight: f64,
    /// The commands watched.
    pub commands: Vec<Command>,
}

/// An actuator command (`"instance.variable"`, an output) and its [lower, upper] limits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Command {
    /// The command, `"instance.variable"`.
    pub variable: String,
    /// [lower, upper] limits, in the command's unit.
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
    /// Generations searched [default: 30].
    pub generations: usize,
    /// The initial step, as a fraction of each parameter's range (in its scale).
    pub sigma: f64,
    /// Seed of the search's random draws [default: 0].
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

    /// Every count that sizes an allocation or a loop against its limit, before anything is
    /// allocated from it (a population of 10⁹ would otherwise abort on a failed allocation).
    fn check_sizes(&self) -> Result<(), String> {
        let counts = [
            ("parameters", Some(self.parameters.len()), MAX_PARAMETERS),
            ("optimizer.population", self.optimizer.population, MAX_POPULATION),
            ("optimizer.generations", Some(self.optimizer.generations), MAX_GENERATIONS),
            ("training.seeds", Some(self.training.seeds.len()), MAX_SEEDS),
            ("held_out.seeds", Some(self.held_out.seeds.len()), MAX_SEEDS),
        ];
        match counts.into_iter().find(|(_, count, limit)| count.is_some_and(|c| c > *limit)) {
            Some((element, Some(count), limit)) => Err(format!("{element} {count} is more than the limit of {limit}")),
            _ => Ok(()),
        }
    }

    fn check(&self) -> Result<(), String> {
        self.check_sizes()?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn tuning(optimizer: &str) -> String {
        format!(
            r#"{{ "variant": 1, "parameters": [{{ "name": "controller.k.angle", "bounds": [0.1, 2] }}],
                "objective": {{ "terms": [{{ "group": "energy-dissipation", "metric": "tau_theta_x" }}] }},
                "training": {{ "tests": "41" }}, "held_out": {{ "tests": "42" }}, "optimizer": {optimizer} }}"#
        )
    }

    fn load(dir: &Path, optimizer: &str) -> Result<Tuning, String> {
        let file = dir.join("tuning.json");
        std::fs::write(&file, tuning(optimizer)).unwrap();
        Tuning::load(&file).map_err(|e| e.to_string())
    }

    #[test]
    fn sizes_are_refused_above_their_limits_before_anything_is_allocated() {
        let dir = tempfile::tempdir().unwrap();
        let settings = |population: &str, generations: &str| {
            format!(r#"{{ "population": {population}, "generations": {generations}, "sigma": 0.2, "seed": 0 }}"#)
        };
        load(dir.path(), &settings("8", "3")).expect("within the limits");
        let error = load(dir.path(), &settings("1000000000", "3")).unwrap_err();
        assert!(
            error.ends_with("tuning.json: optimizer.population 1000000000 is more than the limit of 10000"),
            "{error}"
        );
        let error = load(dir.path(), &settings("8", "1000000000")).unwrap_err();
        assert!(error.ends_with("optimizer.generations 1000000000 is more than the limit of 100000"), "{error}");
    }
}
