//! The objective of a candidate: its compensated campaign runs against their references.
//!
//! Each compensated test of a selection (041–080, 089–096, 102–104) is a *pair* with its
//! reference (the crane off, or inverse kinematics only: [`matrix::reference_of`]) for every
//! noise seed. The references run once, with the system's own start values (the thesis' gains),
//! and stay the denominators for every candidate: a candidate cannot score better by changing
//! the uncompensated run (the inverse-kinematics references move with the joint PIDs and the
//! estimators), only by compensating better.
//!
//! A term (group g, metric m) is the mean over g's pairs of the ratio m(compensated) /
//! m(reference), i.e. 1 − the eq. 7.1 reduction: 0 is a perfect compensation, 1 none. Pairs
//! whose reference has no value of m (no decay fitted) are left out, as in Tables 7.1–7.3; a
//! compensated run without a value where its reference has one counts as ratio 1 (no
//! improvement), so that the optimiser cannot remove a swing's time constant by making the swing
//! not decay. The objective is the weighted mean of the terms plus the saturation penalty, the
//! weight times the mean fraction of recorded samples (from the release on) at which any listed
//! actuator command is at its limit. A candidate with a failed run scores [`FAILED`].

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::Value;

use cosim_engine::interrupt::Interrupt;
use cosim_engine::system::SystemFiles;
use cosim_engine::table::SignalTable;

use crate::study::{compensated, RunSelection, Saturation, Tuning};
use cosim_studies::sweep::plan::variable_seed;
use crane_campaign::evaluate::evaluate;
use crane_campaign::matrix::{self, RunSpec, Variant};
use crane_campaign::results::RunResult;
use crane_campaign::runner::{run_scenario, simulate_scenario, Recording};
use crane_campaign::summary::{applies, Group};
use crane_metrics::run::Metrics;
use crane_metrics::MetricId;

/// The objective of a candidate one of whose runs failed (worse than any compensation: the
/// ratios are at most a few units).
pub const FAILED: f64 = 10.0;

/// A run of the tuning: a campaign run with a noise seed (`None`: the system file's seeds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TuningRun {
    /// The campaign test and variant.
    pub spec: RunSpec,
    /// The noise seed; `None`: the system file's seeds.
    pub seed: Option<u64>,
}

impl TuningRun {
    /// `041-1` or `041-1 seed 7`.
    pub fn id(&self) -> String {
        match self.seed {
            Some(seed) => format!("{} seed {seed}", self.spec.id()),
            None => self.spec.id(),
        }
    }
}

/// A compensated run and its reference.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    /// The run with motion compensation.
    pub compensated: TuningRun,
    /// The same motion without compensation, which the compensated run is compared with.
    pub reference: TuningRun,
    /// The group of test pairs (a row of the objective's terms) it counts in.
    pub group: Group,
}

/// The pairs of `selection` in `variant`, test-major.
pub fn pairs(selection: &RunSelection, variant: Variant) -> Result<Vec<Pair>, String> {
    let numbers = matrix::parse_selection(&selection.tests)?;
    let tests = matrix::tests();
    let seeds: Vec<Option<u64>> =
        if selection.seeds.is_empty() { vec![None] } else { selection.seeds.iter().copied().map(Some).collect() };
    let mut pairs = Vec::new();
    for test in tests.iter().filter(|t| numbers.contains(&t.number) && compensated(t.number)) {
        let (Some(reference), Some(group)) = (matrix::reference_of(test), Group::of(test.family, test.motion)) else {
            continue;
        };
        let Some(reference) = tests.iter().find(|t| t.number == reference) else { continue };
        for &seed in &seeds {
            pairs.push(Pair {
                compensated: TuningRun { spec: RunSpec::new(*test, variant), seed },
                reference: TuningRun { spec: RunSpec::new(*reference, variant), seed },
                group,
            });
        }
    }
    Ok(pairs)
}

/// What one run gave: its metrics and the fraction of its samples at an actuator limit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// The run's §7.2.2 metrics.
    pub metrics: Metrics,
    /// Fraction (0 to 1) of the recorded samples from the release on at which a command is at a
    /// limit; 0 without saturation commands.
    pub saturation: f64,
}

/// Runs tuning runs: the system, its FMUs (loaded once) and the start values every run shares.
pub struct Runner {
    /// The system file, absolute.
    pub system: PathBuf,
    /// The tuning file, named in messages.
    pub tuning_file: PathBuf,
    /// The FMUs and system files, loaded once and shared by every run.
    pub files: SystemFiles,
    /// `"instance.variable"` integer start values set from a run's noise seed.
    pub seed_variables: Vec<String>,
    /// The commands whose time at a limit is measured; none: no saturation measured.
    pub saturation: Option<Saturation>,
    /// Stops a run between steps when a signal arrives.
    pub interrupt: Option<Interrupt>,
}

impl Runner {
    /// Runs `run` with the extra start values `tuned` and evaluates it.
    pub fn run(&self, run: &TuningRun, tuned: &BTreeMap<String, Value>) -> Result<Outcome, String> {
        let mut start = tuned.clone();
        if let Some(seed) = run.seed {
            for (k, name) in self.seed_variables.iter().enumerate() {
                start.insert(name.clone(), variable_seed(seed, k).into());
            }
        }
        let commands: Vec<String> =
            self.saturation.iter().flat_map(|s| s.commands.iter().map(|c| c.variable.clone())).collect();
        let scenario = run_scenario(&run.spec, &self.system, &start, &commands);
        let recording = Recording { scenario: &self.tuning_file, csv: None, interrupt: self.interrupt.as_ref() };
        let mut result = RunResult {
            id: run.spec.id(),
            run: run.spec,
            metrics: None,
            error: None,
            simulated_time: 0.0,
            wall_time: 0.0,
        };
        let table = simulate_scenario(&scenario, &self.files, &recording, &mut result)
            .map_err(|e| format!("run {}: {e}", run.id()))?;
        let evaluation = evaluate(&run.spec, &table).map_err(|e| format!("run {}: {e}", run.id()))?;
        let saturation = match &self.saturation {
            Some(s) => {
                saturated_fraction(&table, s, run.spec.init_time()).map_err(|e| format!("run {}: {e}", run.id()))?
            }
            None => 0.0,
        };
        Ok(Outcome { metrics: evaluation.metrics, saturation })
    }
}

/// The fraction of the samples from `from` (s) on at which any command of `saturation` is within
/// 1e-9 of its range's width of a limit (or beyond it).
fn saturated_fraction(table: &SignalTable, saturation: &Saturation, from: f64) -> Result<f64, String> {
    let columns = saturation
        .commands
        .iter()
        .map(|c| {
            let column = table.column(&c.variable).ok_or(format!("{} was not recorded", c.variable))?;
            let tolerance = 1e-9 * (c.range[1] - c.range[0]);
            Ok((&table.columns[column], c.range[0] + tolerance, c.range[1] - tolerance))
        })
        .collect::<Result<Vec<_>, String>>()?;
    let samples: Vec<usize> = (0..table.times.len()).filter(|&i| table.times[i] >= from).collect();
    if samples.is_empty() {
        return Ok(0.0);
    }
    let at_limit = samples.iter().filter(|&&i| columns.iter().any(|(v, lo, hi)| v[i] <= *lo || v[i] >= *hi)).count();
    Ok(at_limit as f64 / samples.len() as f64)
}

/// One term's value on a candidate: the mean ratio and the pairs it averages.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TermValue {
    /// The term's group of test pairs.
    pub group: Group,
    /// The term's metric name.
    pub metric: String,
    /// Mean compensated/reference ratio; `None` where no pair has a reference value.
    pub ratio: Option<f64>,
    /// The pairs the ratio averages.
    pub pairs: usize,
}

/// A candidate's score.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Score {
    /// The objective (without the bound penalty of points outside the box).
    pub objective: f64,
    /// Each term's value.
    pub terms: Vec<TermValue>,
    /// Mean fraction of samples at an actuator limit over the compensated runs.
    pub saturation: f64,
    /// The failed runs' messages.
    pub errors: Vec<String>,
}

/// The score of the compensated runs' `outcomes` (in the order of `pairs`) against the
/// references' (`references[i]` for `pairs[i]`).
pub fn score(
    tuning: &Tuning,
    pairs: &[Pair],
    references: &[Result<Outcome, String>],
    outcomes: &[Result<Outcome, String>],
) -> Score {
    let errors: Vec<String> = references.iter().chain(outcomes).filter_map(|r| r.as_ref().err().cloned()).collect();
    let terms: Vec<TermValue> = tuning
        .objective
        .terms
        .iter()
        .map(|term| {
            let ratios: Vec<f64> = pairs
                .iter()
                .zip(references.iter().zip(outcomes))
                .filter(|(pair, _)| {
                    pair.group == term.group && applies(term.metric, &pair.compensated.spec.test.theta0_deg)
                })
                .filter_map(|(_, (reference, outcome))| {
                    ratio(term.metric, reference.as_ref().ok()?, outcome.as_ref().ok()?)
                })
                .collect();
            let ratio = (!ratios.is_empty()).then(|| ratios.iter().sum::<f64>() / ratios.len() as f64);
            TermValue { group: term.group, metric: term.metric.info().name.to_string(), ratio, pairs: ratios.len() }
        })
        .collect();
    let saturation = mean(outcomes.iter().filter_map(|o| o.as_ref().ok().map(|o| o.saturation)));
    let weighted: Vec<(f64, f64)> = tuning
        .objective
        .terms
        .iter()
        .zip(&terms)
        .filter_map(|(term, value)| value.ratio.map(|r| (term.weight, r)))
        .collect();
    let total_weight: f64 = weighted.iter().map(|(w, _)| w).sum();
    let penalty = tuning.objective.saturation.as_ref().map_or(0.0, |s| s.weight * saturation);
    let objective = if !errors.is_empty() || total_weight == 0.0 {
        FAILED
    } else {
        weighted.iter().map(|(w, r)| w * r).sum::<f64>() / total_weight + penalty
    };
    Score { objective, terms, saturation, errors }
}

/// m(compensated)/m(reference); 1 where the compensated run has no value but the reference
/// has; `None` where the reference has none or it is 0.
fn ratio(metric: MetricId, reference: &Outcome, outcome: &Outcome) -> Option<f64> {
    let reference = reference.metrics.get(metric).filter(|&r| r != 0.0)?;
    Some(outcome.metrics.get(metric).map_or(1.0, |value| value / reference))
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    if n == 0 {
        0.0
    } else {
        sum / n as f64
    }
}

/// The absolute form of `path` (relative to the working directory).
pub fn absolute(path: &Path) -> Result<PathBuf, String> {
    std::path::absolute(path).map_err(|e| format!("{}: {e}", path.display()))
}
