//! Running the campaign: each run's scenario written, simulated with the co-simulation engine
//! and evaluated, in parallel on a thread pool with a progress bar.

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Mutex;
use std::time::Instant;

use rayon::prelude::*;
use serde_json::Value;

use cosim_engine::execution::Execution;
use cosim_engine::interrupt::{signal_name, Interrupt};
use cosim_engine::observer::{CsvRecorder, RunProgress, TableRecorder};
use cosim_engine::summary::ColumnSummary;
use cosim_engine::system::scenario::ScenarioSpec;
use cosim_engine::system::{Overrides, RecordSpec, System, SystemFiles, VariableRef};
use cosim_engine::table::SignalTable;
use fmu_import::error_chain;
use fmu_import::fmi::LogEcho;
use fmu_import::fmu::ExtractLimits;
use fmu_import::slave::InstantiateOptions;

use crate::evaluate::evaluate;
use crate::matrix::RunSpec;
use crate::output::{self, OutputError};
use crate::results::{Campaign, RunResult, DETAILED};
use crate::scale::CampaignScale;
use crane_metrics::run::Evaluation;

/// Why a campaign could not start (a failing run does not stop it: see [`RunResult::error`]).
#[derive(Debug, thiserror::Error)]
pub enum CampaignError {
    #[error("cannot create {}", folder.display())]
    Folder {
        folder: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{}", file.display())]
    System {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Output(#[from] OutputError),
    #[error("start value {name}: simulation {run} sets it itself (the test matrix's start values cannot be replaced)")]
    MatrixStart { name: String, run: String },
    #[error("cannot start the worker threads")]
    Threads(#[source] rayon::ThreadPoolBuildError),
}

/// How to run a campaign.
#[derive(Debug, Clone)]
pub struct CampaignOptions {
    /// The closed-loop system file every scenario starts from.
    pub system: PathBuf,
    /// Output folder: scenarios/, runs/, metrics.csv, metrics.json, report.md, figures/.
    pub out: PathBuf,
    /// Worker threads (0: one per core).
    pub jobs: usize,
    /// Keep every run's results CSV (otherwise only those of [`DETAILED`]).
    pub keep_results: bool,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Once requested (a signal), running runs stop at their next step and the rest are not
    /// started; each is reported as failed with the reason.
    pub interrupt: Option<Interrupt>,
    /// Start values (`"instance.variable"`) every run gets on top of the system file's, e.g. a
    /// controller option under study; none may be one the test matrix sets itself.
    pub start: BTreeMap<String, Value>,
    /// What the FMUs may unpack to.
    pub limits: ExtractLimits,
}

/// Runs `runs` in parallel and evaluates each. A failing run is reported in its result and the
/// campaign goes on.
pub fn run_campaign(runs: &[RunSpec], options: &CampaignOptions) -> Result<Campaign, CampaignError> {
    check_start(runs, &options.start)?;
    output::prepare(&options.out)?;
    for folder in ["scenarios", "runs"] {
        let dir = options.out.join(folder);
        std::fs::create_dir_all(&dir).map_err(|source| CampaignError::Folder { folder: dir.clone(), source })?;
    }
    // Scenarios name the system relative to their folder, so that the output folder and the
    // repository can move together.
    let absolute = |path: &Path| {
        std::path::absolute(path).map_err(|source| CampaignError::System { file: path.to_path_buf(), source })
    };
    let system = relative_path(&absolute(&options.system)?, &absolute(&options.out.join("scenarios"))?);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(options.jobs).build().map_err(CampaignError::Threads)?;
    let progress = RunProgress::new(runs.len() as u64, options.progress);
    let detailed = Mutex::new(Vec::new());
    // Every run builds its system from the same system file and FMUs: each is read, extracted,
    // parsed and loaded once for the whole campaign; runs instantiate their own instances.
    let files = SystemFiles::new(options.limits);
    let clock = Instant::now();
    let results: Vec<RunResult> = pool.install(|| {
        runs.par_iter()
            .map(|run| {
                let (result, evaluation) = run_one(run, &system, &files, options);
                if let Some(evaluation) = evaluation.filter(|_| DETAILED.contains(&result.id.as_str())) {
                    detailed.lock().unwrap_or_else(|e| e.into_inner()).push((result.id.clone(), evaluation));
                }
                progress.advance(&result.id, result.error.as_deref());
                result
            })
            .collect()
    });
    progress.finish();
    // Listed now so that the folder can be cleared by the next campaign even if the caller
    // writes nothing more; a caller adding figures and a report lists them again.
    output::seal(&options.out)?;
    let mut detailed = detailed.into_inner().unwrap_or_else(|e| e.into_inner());
    detailed.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(Campaign {
        results,
        detailed,
        wall_time: clock.elapsed().as_secs_f64(),
        jobs: pool.current_num_threads(),
        start: options.start.clone(),
        system: options.system.clone(),
    })
}

/// Refuses an extra start value that a run's test definition sets (a variant's feedback, a test's
/// cable length…): replacing it would silently run another test under the same label.
fn check_start(runs: &[RunSpec], start: &BTreeMap<String, Value>) -> Result<(), CampaignError> {
    for run in runs {
        let matrix = run.start_values();
        if let Some(name) = start.keys().find(|name| matrix.contains_key(*name)) {
            return Err(CampaignError::MatrixStart { name: name.clone(), run: run.id() });
        }
    }
    Ok(())
}

/// `target` relative to the folder `base` (both absolute), e.g. `../../systems/x.json`;
/// `target` itself if they share no root (another drive).
pub fn relative_path(target: &Path, base: &Path) -> PathBuf {
    let (target_parts, base_parts): (Vec<_>, Vec<_>) = (target.components().collect(), base.components().collect());
    let common = target_parts.iter().zip(&base_parts).take_while(|(a, b)| a == b).count();
    if common == 0 {
        return target.to_path_buf();
    }
    let mut relative: PathBuf = base_parts[common..].iter().map(|_| std::path::Component::ParentDir).collect();
    relative.extend(&target_parts[common..]);
    relative
}

/// Writes the run's scenario file, runs it, evaluates the results.
fn run_one(
    run: &RunSpec,
    system: &Path,
    files: &SystemFiles,
    options: &CampaignOptions,
) -> (RunResult, Option<Evaluation>) {
    let id = run.id();
    let mut result =
        RunResult { id: id.clone(), run: *run, metrics: None, error: None, simulated_time: 0.0, wall_time: 0.0 };
    let csv = options.out.join("runs").join(format!("{id}.csv"));
    let keep = options.keep_results || DETAILED.contains(&id.as_str());
    let paths =
        RunFiles { scenario: options.out.join("scenarios").join(format!("{id}.json")), csv: keep.then_some(csv) };
    if let Some(signal) = options.interrupt.as_ref().and_then(Interrupt::requested) {
        result.error = Some(format!("simulation {id}: not started: interrupted by {}", signal_name(signal)));
        return (result, None);
    }
    let outcome = simulate(run, system, files, &paths, options.interrupt.as_ref(), &options.start, &mut result)
        .and_then(|table| evaluate(run, &table));
    match outcome {
        Ok(evaluation) => {
            result.metrics = Some(evaluation.metrics);
            (result, Some(evaluation))
        }
        Err(message) => {
            result.error = Some(format!("simulation {id}: {message}"));
            (result, None)
        }
    }
}

/// The files a run writes: its scenario, and its results CSV if kept.
struct RunFiles {
    scenario: PathBuf,
    csv: Option<PathBuf>,
}

/// FMU instances of a campaign run: hidden, without FMU logging.
pub(crate) const INSTANTIATE: InstantiateOptions =
    InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Off };

/// Simulates the run and returns its results. They are recorded in memory for the evaluation
/// (a CSV written and parsed back gives the same bits, at several times the cost of the
/// recording) and also to the CSV file if the run's results are kept.
fn simulate(
    run: &RunSpec,
    system: &Path,
    files: &SystemFiles,
    paths: &RunFiles,
    interrupt: Option<&Interrupt>,
    start: &BTreeMap<String, Value>,
    result: &mut RunResult,
) -> Result<SignalTable, String> {
    let scenario = run_scenario(run, system, start, &[]);
    let text = serde_json::to_string_pretty(&scenario).map_err(|e| e.to_string())?;
    std::fs::write(&paths.scenario, text).map_err(|e| format!("cannot write {}: {e}", paths.scenario.display()))?;
    let recording = Recording { scenario: &paths.scenario, csv: paths.csv.as_deref(), interrupt };
    simulate_scenario(&scenario, files, &recording, result)
}

/// The scenario of `run` over the system file `system` with the extra start values `start`,
/// recording the campaign's variables and `extra` ones.
pub fn run_scenario(run: &RunSpec, system: &Path, start: &BTreeMap<String, Value>, extra: &[String]) -> ScenarioSpec {
    let mut scenario = run.scenario(system.to_path_buf());
    scenario.start.extend(start.iter().map(|(name, value)| (name.clone(), value.clone())));
    let recorded = run.scale.recorded().iter().map(|s| s.to_string()).chain(extra.iter().cloned()).collect();
    scenario.record = Some(RecordSpec { interval: None, variables: Some(recorded) });
    scenario
}

/// Where a simulated scenario comes from and goes: the scenario file it is named by (relative
/// paths resolve against its folder), the kept results CSV, and the stop request.
pub struct Recording<'a> {
    /// The scenario file the run is named by.
    pub scenario: &'a Path,
    /// Where the results CSV is kept; none: not kept.
    pub csv: Option<&'a Path>,
    /// Stops the run between steps when requested.
    pub interrupt: Option<&'a Interrupt>,
}

/// Runs `scenario` (built by [`run_scenario`]) and returns its recorded results; sets the
/// result's simulated and wall times.
pub fn simulate_scenario(
    scenario: &ScenarioSpec,
    files: &SystemFiles,
    recording: &Recording,
    result: &mut RunResult,
) -> Result<SignalTable, String> {
    let system = System::from_scenario(scenario, recording.scenario, &Overrides::default(), files)
        .map_err(|e| error_chain(&e))?;
    let clock = Instant::now();
    let (variables, every) = (&system.record.variables, system.record.every);
    let table_file = recording.csv.map_or_else(|| PathBuf::from(format!("{}.csv", result.id)), Path::to_path_buf);
    let table = TableRecorder::new(&table_file, variables, every).ok_or("a recorded variable is a string")?;
    let table = Rc::new(RefCell::new(table));
    let mut execution = Execution::from_system(&system, INSTANTIATE).map_err(|e| error_chain(&e))?;
    execution.add_observer(Box::new(Rc::clone(&table)));
    if let Some(interrupt) = recording.interrupt {
        execution.interrupt_on(interrupt.clone());
    }
    if let Some(csv) = recording.csv {
        execution.add_observer(Box::new(CsvRecorder::create(csv, variables, every).map_err(|e| error_chain(&e))?));
        write_columns(csv, recording.scenario, variables)?;
    }
    let outcome = execution.run().and_then(|()| execution.terminate());
    let flushed = execution.finish_observers();
    result.wall_time = clock.elapsed().as_secs_f64();
    outcome.and(flushed).map_err(|e| error_chain(&e))?;
    result.simulated_time = execution.time() - execution.grid().start();
    drop(execution);
    let table = Rc::into_inner(table).ok_or("the recorder is still shared")?;
    Ok(table.into_inner().into_table())
}

/// `<id>.summary.json` beside a kept results CSV: its scenario and its columns with their units,
/// as `crane-cosim run` writes them (`crane-cosim plot` labels its axes from them).
fn write_columns(csv: &Path, scenario: &Path, variables: &[VariableRef]) -> Result<(), String> {
    let columns: Vec<ColumnSummary> = variables
        .iter()
        .map(|v| ColumnSummary { name: v.qualified_name.clone(), unit: v.variable.unit.clone() })
        .collect();
    let summary = serde_json::json!({ "system": scenario.display().to_string(), "columns": columns });
    let file = csv.with_extension("summary.json");
    let text = serde_json::to_string_pretty(&summary).map_err(|e| e.to_string())?;
    std::fs::write(&file, text + "\n").map_err(|e| format!("cannot write {}: {e}", file.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_paths_climb_to_the_common_folder() {
        let relative = relative_path(Path::new("/repo/systems/loop.json"), Path::new("/repo/out/campaign/scenarios"));
        assert_eq!(relative, Path::new("../../../systems/loop.json"));
        assert_eq!(relative_path(Path::new("/a/b.json"), Path::new("/a")), Path::new("b.json"));
    }
}
