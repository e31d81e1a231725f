//! Running a study's cases: each is the base scenario with the case's start values, simulated
//! with the co-simulation engine and recorded in memory; its metrics go to `cases/<id>.json`.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use cosim_engine::execution::Execution;
use cosim_engine::interrupt::{signal_name, Interrupt};
use cosim_engine::observer::{RunProgress, TableRecorder};
use cosim_engine::system::json::{self, FileKind};
use cosim_engine::system::scenario::ScenarioSpec;
use cosim_engine::system::{Overrides, RecordSpec, System, SystemFiles};
use cosim_engine::table::SignalTable;
use fmu_import::error_chain;
use fmu_import::fmi::LogEcho;
use fmu_import::fmu::ExtractLimits;
use fmu_import::slave::InstantiateOptions;
use fmu_import::value::Value;

use super::plan::{self, variable_seed, Case};
use super::study::{MetricKind, Parameter, Study, Targets};
use super::{check_cases_folder, claim_folder};
use crate::files::{read_text, write_atomically, write_json_atomically};
use crate::StudyError;
use crane_metrics::catalogue::Source;
use crane_metrics::change::percent_change;
use crane_metrics::ellipsoid::ellipsoid;
use crane_metrics::run::{
    evaluate_signals, signals, Metrics, ELLIPSOID_FRACTION, MIN_ANGLE_PEAK, RECORDED, TIP_PREFIX,
};
use crane_metrics::{distance_travelled, rmse, Trace, CAPTURE_RATE, DISTANCE_THRESHOLD, LOAD_PREFIX, SETPOINT_PREFIX};

/// FMU instances of a case: hidden, without FMU logging (a case's messages would interleave
/// with the other workers').
const INSTANTIATE: InstantiateOptions = InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Off };

/// Which cases of the plan to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Selection {
    All,
    /// One case by its index (an array job's task).
    Index(usize),
    /// The cases whose index ≡ `index` (mod `count`), 0 ≤ index < count.
    Shard {
        index: usize,
        count: usize,
    },
}

impl Selection {
    /// The selected cases of a plan of `cases` cases.
    fn indices(self, cases: usize) -> Result<Vec<usize>, StudyError> {
        match self {
            Selection::All => Ok((0..cases).collect()),
            Selection::Index(index) if index < cases => Ok(vec![index]),
            Selection::Index(index) => Err(StudyError::NoSuchCase { index, cases }),
            Selection::Shard { index, count } if index < count => Ok((index..cases).step_by(count).collect()),
            Selection::Shard { index, count } => Err(StudyError::BadShard { index, count }),
        }
    }
}

/// How to run a study.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Output folder: cases/, manifest.json.
    pub out: PathBuf,
    /// Worker threads (0: one per core).
    pub jobs: usize,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Once requested, running cases stop at their next step and are recorded as failed.
    pub interrupt: Option<Interrupt>,
    /// What the FMUs may unpack to.
    pub limits: ExtractLimits,
}

/// The state of a case in the output folder.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Done,
    Failed,
    Pending,
}

/// `cases/<id>.json`: a case's inputs and outcome.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseRecord {
    /// The case's id ([`super::plan::case_id`]).
    pub id: String,
    /// 0-based index in the plan.
    pub index: usize,
    /// The case's seed, set into the study's seed variables.
    pub seed: u64,
    /// Start values by `"instance.variable"`.
    pub parameters: BTreeMap<String, f64>,
    /// Whether it is pending, done or failed.
    pub status: Status,
    /// Why the case failed, for status failed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Metric values by [`super::study::MetricSpec::name`]; `None` where no sample lies in the
    /// metric's window.
    pub metrics: BTreeMap<String, Option<f64>>,
    /// Wall-clock time of the simulation (s).
    pub wall_time: f64,
}

/// `manifest.json`: the plan's cases with their status, the columns of the collected table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// The study file, absolute.
    pub study: PathBuf,
    /// The parameters' names, the collected table's parameter columns.
    pub parameters: Vec<String>,
    /// The metrics' names, the collected table's metric columns.
    pub metrics: Vec<String>,
    /// Every planned case, in plan order.
    pub cases: Vec<ManifestEntry>,
}

/// The manifest's file name in an output folder.
pub const MANIFEST_FILE: &str = "manifest.json";

impl Manifest {
    /// Writes `out/manifest.json` (atomically).
    pub fn write(&self, out: &Path) -> Result<(), StudyError> {
        write_atomically(&out.join(MANIFEST_FILE), &to_json(self))
    }
}

/// One planned case of the manifest.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ManifestEntry {
    /// The case's id.
    pub id: String,
    /// The case's seed.
    pub seed: u64,
    /// Its state when the manifest was written.
    pub status: Status,
}

/// What a run did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunCount {
    /// Cases run to the end.
    pub done: usize,
    /// Cases whose run failed.
    pub failed: usize,
    /// Already done by an earlier run.
    pub skipped: usize,
}

/// The selected cases of `study`'s plan: one case is computed alone ([`plan::case`]), the
/// others from the whole plan.
fn selected_cases(study: &Study, selection: Selection) -> Result<Vec<Case>, StudyError> {
    if let Selection::Index(index) = selection {
        return Ok(vec![plan::case(study, index)?]);
    }
    let mut cases = plan::plan(study)?;
    let selected = selection.indices(cases.len())?;
    let keep: std::collections::BTreeSet<usize> = selected.into_iter().collect();
    cases.retain(|case| keep.contains(&case.index));
    Ok(cases)
}

/// Runs the `selection` of the cases of `study` (read from `study_file`) that are not done
/// yet, then rewrites the manifest.
pub fn run_cases(
    study_file: &Path,
    study: &Study,
    selection: Selection,
    options: &SweepOptions,
) -> Result<RunCount, StudyError> {
    let files = SystemFiles::new(options.limits);
    let base_file = study.scenario_path(study_file);
    let (base, system) = load_base(&base_file, &files)?;
    let targets = resolve_targets(study, &system)
        .map_err(|message| StudyError::Invalid { file: study_file.to_path_buf(), message })?;
    claim_folder(&options.out)?;
    check_cases_folder(&options.out.join("cases"))?;
    let mut todo = Vec::new();
    let mut count = RunCount::default();
    let selected = selected_cases(study, selection)?;
    for case in &selected {
        match read_case(&options.out, &case.id)? {
            Some(record) if !record.is_of(case) => {
                return Err(StudyError::OtherStudy { file: case_file(&options.out, &case.id) })
            }
            Some(record) if record.status == Status::Done => count.skipped += 1,
            _ => todo.push(case),
        }
    }
    let interval = system.spec.record.interval;
    let scenario = CaseScenario { study, base: &base, base_file: &base_file, interval, targets, files: &files };
    let cases = plan::case_count(study).unwrap_or(0);
    if cases > 0 {
        let first = plan::case(study, 0)?;
        let invalid = |e: String| format!("the start values the study sets (checked on case {}): {e}", first.id);
        scenario
            .check(&first)
            .map_err(|e| StudyError::Invalid { file: study_file.to_path_buf(), message: invalid(e) })?;
    }
    let folder = options.out.join("cases");
    std::fs::create_dir_all(&folder).map_err(|source| StudyError::Write { file: folder.clone(), source })?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(options.jobs).build().map_err(StudyError::Threads)?;
    let progress = RunProgress::new(todo.len() as u64, options.progress);
    let records: Vec<Result<CaseRecord, StudyError>> = pool.install(|| {
        todo.par_iter()
            .map(|case| {
                let record = scenario.run(case, options.interrupt.as_ref());
                progress.advance(&case.id, record.error.as_deref());
                write_atomically(&case_file(&options.out, &case.id), &to_json(&record)).map(|()| record)
            })
            .collect()
    });
    progress.finish();
    for record in records {
        match record?.status {
            Status::Done => count.done += 1,
            _ => count.failed += 1,
        }
    }
    write_manifest(study_file, study, cases, &options.out)?;
    Ok(count)
}

/// The base scenario and its system (with the FMUs' defaults and its recording interval: the
/// system file's unless the scenario gives a `record`, which the cases keep while recording only
/// the metrics' variables).
fn load_base(file: &Path, files: &SystemFiles) -> Result<(ScenarioSpec, System), StudyError> {
    let text = read_text(file)?;
    let invalid = |message: String| StudyError::Invalid { file: file.to_path_buf(), message };
    let base: ScenarioSpec = json::parse(&text, FileKind::Scenario)
        .map_err(|error| StudyError::Parse { file: file.to_path_buf(), error })?;
    let system =
        System::from_scenario(&base, file, &Overrides::default(), files).map_err(|e| invalid(error_chain(&e)))?;
    Ok((base, system))
}

/// A parameter's start values: `(name, None)` set to the sampled value, `(name, Some(base))`
/// set to the sampled value × base.
type ResolvedTargets = Vec<Vec<(String, Option<f64>)>>;

/// The start values of every parameter in the study's order, with the base values of the
/// scaled ones: the base scenario's start value, else the FMU's default. An error names a scaled
/// start value that is not a Real variable with a start value, before any case runs (the other
/// names are checked by [`CaseScenario::check`]).
fn resolve_targets(study: &Study, system: &System) -> Result<ResolvedTargets, String> {
    let resolve = |parameter: &Parameter| -> Result<Vec<(String, Option<f64>)>, String> {
        let Targets::Scale(names) = &parameter.targets else {
            return Ok(parameter.targets.names().iter().map(|name| (name.clone(), None)).collect());
        };
        let scaled = |name: &String| match base_value(system, name) {
            Ok(Some(Value::Real(value))) => Ok((name.clone(), Some(value))),
            Ok(_) => {
                Err(format!("parameter {}: {name} cannot be scaled: not a Real with a start value", parameter.name))
            }
            Err(e) => Err(format!("parameter {}: {name}: {e}", parameter.name)),
        };
        names.iter().map(scaled).collect()
    };
    study.parameters.iter().map(resolve).collect()
}

/// The base value of `"instance.variable"` `name` in `system`: its start value in the system or
/// the base scenario, else its FMU's default (none for an input without `start`); an error if the
/// instance or its FMU's variable does not exist.
pub fn base_value(system: &System, name: &str) -> Result<Option<Value>, String> {
    let (instance, variable) = name.split_once('.').unwrap_or((name, ""));
    let instance =
        system.instances.iter().find(|i| i.name == instance).ok_or(format!("unknown instance '{instance}'"))?;
    let declared = instance.fmu.model_description().variable(variable).cloned();
    let declared = declared.ok_or(format!("the FMU of '{}' has no variable '{variable}'", instance.name))?;
    let given = instance.start.iter().find(|(v, _)| v.name == variable).map(|(_, value)| value.clone());
    Ok(given.or(declared.start))
}

impl CaseRecord {
    /// True if the record is of this case (same seed and parameter values), not of another
    /// study's case with the same id.
    fn is_of(&self, case: &Case) -> bool {
        let same =
            |(name, value): &(String, f64)| self.parameters.get(name).is_some_and(|v| v.to_bits() == value.to_bits());
        self.seed == case.seed && self.parameters.len() == case.values.len() && case.values.iter().all(same)
    }
}

/// `DIR/cases/<id>.json`.
pub fn case_file(out: &Path, id: &str) -> PathBuf {
    out.join("cases").join(format!("{id}.json"))
}

/// A case's record: `None` if its file does not exist or does not parse (a case to run again);
/// a file that is not a regular one (a FIFO, a link to a device) or too large is an error.
pub fn read_case(out: &Path, id: &str) -> Result<Option<CaseRecord>, StudyError> {
    let file = case_file(out, id);
    match read_text(&file) {
        Ok(text) => Ok(serde_json::from_str(&text).ok()),
        Err(StudyError::Read { source, .. }) if source.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(error) => Err(error),
    }
}

fn status(out: &Path, id: &str) -> Result<Status, StudyError> {
    Ok(read_case(out, id)?.map_or(Status::Pending, |record| record.status))
}

/// Writes the manifest of the `count` cases of `study` from their ids and seeds alone (no case
/// values are drawn).
/// Each entry is made while it is written, so the manifest of a large plan is streamed; a case
/// file that cannot be read (see [`read_case`]) stops the writing with its error.
fn write_manifest(study_file: &Path, study: &Study, count: usize, out: &Path) -> Result<(), StudyError> {
    let failure = std::cell::RefCell::new(None);
    let manifest = ManifestOut {
        study: std::path::absolute(study_file).unwrap_or_else(|_| study_file.to_path_buf()),
        parameters: study.parameters.iter().map(|p| p.name.clone()).collect(),
        metrics: study.metric_names(),
        cases: StreamedEntries { study, count, out, failure: &failure },
    };
    let written = write_json_atomically(&out.join(MANIFEST_FILE), &manifest);
    match failure.into_inner() {
        Some(error) => Err(error),
        None => written,
    }
}

/// [`Manifest`] with its cases made while serialised.
#[derive(Serialize)]
struct ManifestOut<'a> {
    study: PathBuf,
    parameters: Vec<String>,
    metrics: Vec<String>,
    cases: StreamedEntries<'a>,
}

/// The entries of the `count` cases of `study`, made from ids, seeds and case files only; the
/// first error reading a case file is kept in `failure` (serde takes only a message).
struct StreamedEntries<'a> {
    study: &'a Study,
    count: usize,
    out: &'a Path,
    failure: &'a std::cell::RefCell<Option<StudyError>>,
}

impl Serialize for StreamedEntries<'_> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::{Error, SerializeSeq};
        let mut sequence = serializer.serialize_seq(Some(self.count))?;
        for index in 0..self.count {
            let id = plan::case_id(index, self.count);
            let status = status(self.out, &id).map_err(|error| {
                let message = error.to_string();
                *self.failure.borrow_mut() = Some(error);
                S::Error::custom(message)
            })?;
            sequence.serialize_element(&ManifestEntry { id, seed: plan::case_seed(self.study.seed, index), status })?;
        }
        sequence.end()
    }
}

fn to_json(value: &impl Serialize) -> String {
    // Plain data of strings, numbers and maps with string keys: serialising cannot fail.
    serde_json::to_string_pretty(value).unwrap_or_default() + "\n"
}

/// What every case of a run shares.
struct CaseScenario<'a> {
    study: &'a Study,
    base: &'a ScenarioSpec,
    /// The base scenario's file, against which its system path resolves.
    base_file: &'a Path,
    /// The base scenario's recording interval (s; `None`: every step).
    interval: Option<f64>,
    /// Every parameter's start values (see [`resolve_targets`]).
    targets: ResolvedTargets,
    /// FMUs read and loaded once for all cases.
    files: &'a SystemFiles,
}

impl CaseScenario<'_> {
    fn run(&self, case: &Case, interrupt: Option<&Interrupt>) -> CaseRecord {
        let mut record = CaseRecord {
            id: case.id.clone(),
            index: case.index,
            seed: case.seed,
            parameters: case.values.iter().cloned().collect(),
            status: Status::Failed,
            error: None,
            metrics: BTreeMap::new(),
            wall_time: 0.0,
        };
        let clock = Instant::now();
        match self.outcome(case, interrupt) {
            Ok(metrics) => {
                record.metrics = metrics;
                record.status = Status::Done;
            }
            Err(message) => record.error = Some(format!("case {}: {message}", case.id)),
        }
        record.wall_time = clock.elapsed().as_secs_f64();
        record
    }

    /// The case's metrics and, with a baseline, the baseline run's and their changes.
    fn outcome(&self, case: &Case, interrupt: Option<&Interrupt>) -> Result<BTreeMap<String, Option<f64>>, String> {
        let mut metrics = self.metrics(&self.simulate(case, false, interrupt)?)?;
        if self.study.baseline.is_none() {
            return Ok(metrics);
        }
        let baseline = self.metrics(&self.simulate(case, true, interrupt)?)?;
        for (name, reference) in baseline {
            let value = metrics.get(&name).copied().flatten();
            // Eq. 7.1; none where either is missing or the reference is 0.
            let change = value.zip(reference).map(|(v, r)| percent_change(v, r)).filter(|c| c.is_finite());
            metrics.insert(format!("{name}.baseline"), reference);
            metrics.insert(format!("{name}.change"), change);
        }
        Ok(metrics)
    }

    /// The base scenario with the case's start values and seeds (and the `baseline` start values
    /// over them for the baseline run), recording only the metrics' variables (every recorded
    /// sample counts in a statistic).
    fn scenario(&self, case: &Case, baseline: bool) -> ScenarioSpec {
        let mut scenario = self.base.clone();
        for (targets, (_, value)) in self.targets.iter().zip(&case.values) {
            for (name, base) in targets {
                scenario.start.insert(name.clone(), base.map_or(*value, |base| value * base).into());
            }
        }
        for (k, name) in self.study.seed_variables.iter().enumerate() {
            scenario.start.insert(name.clone(), variable_seed(case.seed, k).into());
        }
        if let Some(start) = self.study.baseline.as_ref().filter(|_| baseline) {
            scenario.start.extend(start.clone());
        }
        let mut variables: Vec<String> = self.study.metrics.iter().flat_map(|m| recorded(&m.kind)).collect();
        variables.sort_unstable();
        variables.dedup();
        scenario.record = Some(RecordSpec { interval: self.interval, variables: Some(variables) });
        scenario
    }

    /// Resolves `case`'s scenario, and its baseline's, against the system: every start value the
    /// study sets names a variable that takes one, or the error says which does not. Every case
    /// sets the same names, so one check before the run stands for all.
    fn check(&self, case: &Case) -> Result<(), String> {
        self.system(case, false)?;
        if self.study.baseline.is_some() {
            self.system(case, true)?;
        }
        Ok(())
    }

    /// [`Self::scenario`] resolved against the FMUs.
    fn system(&self, case: &Case, baseline: bool) -> Result<System, String> {
        System::from_scenario(&self.scenario(case, baseline), self.base_file, &Overrides::default(), self.files)
            .map_err(|e| error_chain(&e))
    }

    fn simulate(&self, case: &Case, baseline: bool, interrupt: Option<&Interrupt>) -> Result<SignalTable, String> {
        if let Some(signal) = interrupt.and_then(Interrupt::requested) {
            return Err(format!("not started: interrupted by {}", signal_name(signal)));
        }
        let system = self.system(case, baseline)?;
        let (variables, every) = (&system.record.variables, system.record.every);
        let table =
            TableRecorder::new(Path::new(&case.id), variables, every).ok_or("a metric's variable is a string")?;
        let mut execution = Execution::from_system(&system, INSTANTIATE).map_err(|e| error_chain(&e))?;
        if let Some(interrupt) = interrupt {
            execution.interrupt_on(interrupt.clone());
        }
        execution.run_into_table(table).map_err(|e| error_chain(&e))
    }

    fn metrics(&self, table: &SignalTable) -> Result<BTreeMap<String, Option<f64>>, String> {
        let end = table.times.last().copied().unwrap_or(0.0);
        let mut values = BTreeMap::new();
        // Catalogue metrics of one source over the same window share one evaluation.
        let mut evaluations: Vec<((Source, f64, f64), Option<Metrics>)> = Vec::new();
        for metric in &self.study.metrics {
            let (from, to) = (metric.from, metric.to.unwrap_or(end));
            let value = match &metric.kind {
                MetricKind::Variable { variable, stat } => {
                    let column = table.column(variable).ok_or_else(|| format!("{variable} is not recorded"))?;
                    stat.of(&table.times, &table.columns[column], from, to)
                }
                MetricKind::Catalogue(id) => {
                    let key = (id.info().source, from, to);
                    let evaluation = match evaluations.iter().find(|(k, _)| *k == key) {
                        Some((_, evaluation)) => *evaluation,
                        None => {
                            let evaluation = evaluate(key.0, table, from, to)?;
                            evaluations.push((key, evaluation));
                            evaluation
                        }
                    };
                    evaluation.and_then(|metrics| metrics.get(*id))
                }
            };
            values.insert(metric.name(), value);
        }
        Ok(values)
    }
}

/// The variables a metric needs recorded.
fn recorded(kind: &MetricKind) -> Vec<String> {
    match kind {
        MetricKind::Variable { variable, .. } => vec![variable.clone()],
        MetricKind::Catalogue(id) if id.info().source == Source::Swing => RECORDED.map(String::from).to_vec(),
        MetricKind::Catalogue(_) => {
            let axes = |prefix: &str| ["x", "y", "z"].map(|axis| format!("{prefix}{axis}"));
            [axes(LOAD_PREFIX), axes(SETPOINT_PREFIX)].concat()
        }
    }
}

/// The metrics of `source` over [from, to] (s).
fn evaluate(source: Source, table: &SignalTable, from: f64, to: f64) -> Result<Option<Metrics>, String> {
    match source {
        Source::LoadAgainstSetpoint => load_evaluation(table, from, to),
        Source::Swing => swing_evaluation(table, from, to),
    }
}

/// The §7.2.2 load metrics (distance, ellipsoid volume, RMSE; the others left at their defaults)
/// over [from, to] (s) at the capture rate, as the campaign computes them; `None` where the
/// window holds no sample. The ellipsoid volume is `None` with too few points.
fn load_evaluation(table: &SignalTable, from: f64, to: f64) -> Result<Option<Metrics>, String> {
    if table.times.last().is_none_or(|&end| end < from) {
        return Ok(None);
    }
    let load = Trace::from_table(table, LOAD_PREFIX)?.resample(CAPTURE_RATE, from, to);
    let setpoint = Trace::from_table(table, SETPOINT_PREFIX)?.resample(CAPTURE_RATE, from, to);
    let relative: Vec<[f64; 3]> =
        load.points.iter().zip(&setpoint.points).map(|(p, s)| [0, 1, 2].map(|k| p[k] - s[k])).collect();
    Ok(Some(Metrics {
        distance: distance_travelled(&load, DISTANCE_THRESHOLD),
        ellipsoid_volume: ellipsoid(&relative, ELLIPSOID_FRACTION).map(|e| e.volume),
        rmse: rmse(&load, &setpoint.points),
        ..Metrics::default()
    }))
}

/// The campaign's evaluation of the swing released at `from` (s) over the window [from, to]: the
/// pendulum length (the peaks' spacing) and the initial cable angles (the side of the peaks
/// fitted; below the smallest significant peak an angle counts as 0, i.e. no initial swing on
/// that axis) are those at `from`; `None` where the window holds no sample.
fn swing_evaluation(table: &SignalTable, from: f64, to: f64) -> Result<Option<Metrics>, String> {
    if table.times.last().is_none_or(|&end| end < from) {
        return Ok(None);
    }
    let signals = signals(table, from, to)?;
    let tip = Trace::from_table(table, TIP_PREFIX)?.resample(CAPTURE_RATE, from, from);
    let (Some(load), Some(tip)) = (signals.load.points.first(), tip.points.first()) else {
        return Ok(None);
    };
    let lp = (0..3).map(|k| (load[k] - tip[k]).powi(2)).sum::<f64>().sqrt();
    let initial = |angle: f64| if angle.abs() < MIN_ANGLE_PEAK { 0.0 } else { angle };
    let theta0 = [initial(signals.theta_x[0]), initial(signals.theta_y[0])];
    Ok(Some(evaluate_signals(signals, lp, theta0).metrics))
}
