//! Running the campaign: each run's scenario written, simulated with the co-simulation engine
//! and evaluated, in parallel on a thread pool with a progress bar.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::Mutex;
use std::time::Instant;

use rayon::prelude::*;

use cosim_engine::execution::Execution;
use cosim_engine::input::InputTable;
use cosim_engine::interrupt::{signal_name, Interrupt};
use cosim_engine::observer::{CsvRecorder, TableRecorder};
use cosim_engine::system::{Overrides, RecordSpec, System, SystemFiles};
use fmu_import::error_chain;
use fmu_import::fmi::LogEcho;
use fmu_import::slave::InstantiateOptions;

use crate::evaluate::{evaluate, Evaluation, RECORDED};
use crate::matrix::RunSpec;
use crate::results::{Campaign, RunResult, DETAILED};

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
}

/// Runs `runs` in parallel and evaluates each. A failing run is reported in its result and the
/// campaign goes on.
pub fn run_campaign(runs: &[RunSpec], options: &CampaignOptions) -> Result<Campaign, CampaignError> {
    for folder in ["scenarios", "runs"] {
        let dir = options.out.join(folder);
        std::fs::create_dir_all(&dir).map_err(|source| CampaignError::Folder { folder: dir.clone(), source })?;
    }
    let system = std::path::absolute(&options.system)
        .map_err(|source| CampaignError::System { file: options.system.clone(), source })?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(options.jobs).build().map_err(CampaignError::Threads)?;
    let progress = Progress::new(runs.len() as u64, options.progress);
    let detailed = Mutex::new(Vec::new());
    // Every run builds its system from the same system file and FMUs: each is read, extracted,
    // parsed and loaded once for the whole campaign; runs instantiate their own instances.
    let files = SystemFiles::default();
    let clock = Instant::now();
    let results: Vec<RunResult> = pool.install(|| {
        runs.par_iter()
            .map(|run| {
                let (result, evaluation) = run_one(run, &system, &files, options);
                if let Some(evaluation) = evaluation.filter(|_| DETAILED.contains(&result.id.as_str())) {
                    detailed.lock().unwrap_or_else(|e| e.into_inner()).push((result.id.clone(), evaluation));
                }
                progress.advance(&result);
                result
            })
            .collect()
    });
    progress.finish();
    let mut detailed = detailed.into_inner().unwrap_or_else(|e| e.into_inner());
    detailed.sort_by(|a, b| a.0.cmp(&b.0));
    Ok(Campaign { results, detailed, wall_time: clock.elapsed().as_secs_f64(), jobs: pool.current_num_threads() })
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
    if !keep {
        // A results file of an earlier campaign would not match this run.
        let _ = std::fs::remove_file(&csv);
    }
    let paths =
        RunFiles { scenario: options.out.join("scenarios").join(format!("{id}.json")), csv: keep.then_some(csv) };
    if let Some(signal) = options.interrupt.as_ref().and_then(Interrupt::requested) {
        result.error = Some(format!("simulation {id}: not started: interrupted by {}", signal_name(signal)));
        return (result, None);
    }
    let outcome = simulate(run, system, files, &paths, options.interrupt.as_ref(), &mut result)
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
const INSTANTIATE: InstantiateOptions = InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Off };

/// Simulates the run and returns its results. They are recorded in memory for the evaluation
/// (a CSV written and parsed back gives the same bits, at several times the cost of the
/// recording) and also to the CSV file if the run's results are kept.
fn simulate(
    run: &RunSpec,
    system: &Path,
    files: &SystemFiles,
    paths: &RunFiles,
    interrupt: Option<&Interrupt>,
    result: &mut RunResult,
) -> Result<InputTable, String> {
    let mut scenario = run.scenario(system.to_path_buf());
    scenario.record =
        Some(RecordSpec { interval: None, variables: Some(RECORDED.iter().map(|s| s.to_string()).collect()) });
    let text = serde_json::to_string_pretty(&scenario).map_err(|e| e.to_string())?;
    std::fs::write(&paths.scenario, text).map_err(|e| format!("cannot write {}: {e}", paths.scenario.display()))?;
    let system =
        System::from_scenario(&scenario, &paths.scenario, &Overrides::default(), files).map_err(|e| error_chain(&e))?;
    let clock = Instant::now();
    let (variables, every) = (&system.record.variables, system.record.every);
    let table_file = paths.csv.clone().unwrap_or_else(|| PathBuf::from(format!("{}.csv", run.id())));
    let table = TableRecorder::new(&table_file, variables, every).ok_or("a recorded variable is a string")?;
    let table = Rc::new(RefCell::new(table));
    let mut execution = Execution::from_system(&system, INSTANTIATE).map_err(|e| error_chain(&e))?;
    execution.add_observer(Box::new(Rc::clone(&table)));
    if let Some(interrupt) = interrupt {
        execution.interrupt_on(interrupt.clone());
    }
    if let Some(csv) = &paths.csv {
        execution.add_observer(Box::new(CsvRecorder::create(csv, variables, every).map_err(|e| error_chain(&e))?));
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

/// A progress bar over the runs (indicatif draws nothing when stderr is not a terminal).
struct Progress(indicatif::ProgressBar);

impl Progress {
    fn new(total: u64, show: bool) -> Self {
        if !show {
            return Progress(indicatif::ProgressBar::hidden());
        }
        let bar = indicatif::ProgressBar::new(total);
        if let Ok(style) =
            indicatif::ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed} elapsed, ~{eta} left  {msg}")
        {
            bar.set_style(style);
        }
        Progress(bar)
    }

    fn advance(&self, result: &RunResult) {
        if let Some(error) = &result.error {
            self.0.println(format!("failed: {error}"));
        }
        self.0.set_message(result.id.clone());
        self.0.inc(1);
    }

    fn finish(&self) {
        self.0.finish_and_clear();
    }
}
