//! A complete run of a system: load, instantiate, simulate, record to CSV (or Parquet),
//! write the summary.

use std::cell::RefCell;
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::time::Instant;

use fmu_import::error_chain;
use fmu_import::fmu::ExtractLimits;
use fmu_import::slave::InstantiateOptions;

use crate::error::Error;
use crate::execution::{Execution, RunError};
use crate::interrupt::Interrupt;
use crate::observer::{FlushPolicy, Progress, Recorder, TimedObserver};
use crate::summary::{ColumnSummary, InstanceSummary, InstanceTiming, RunStatus, RunSummary, Timing};
use crate::system::{Overrides, System, SystemError, SystemFiles};
use crate::workload::Workload;

/// Options of a run.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Results CSV, or Parquet when the name ends in `.parquet` ([`Recorder`]).
    pub output: PathBuf,
    /// Summary JSON (none: not written).
    pub summary: Option<PathBuf>,
    /// Command-line replacements of `stop_time` / `step_size`.
    pub overrides: Overrides,
    /// What each FMU or SSP archive may unpack to.
    pub limits: ExtractLimits,
    /// Instantiation and FMU logging options.
    pub instantiate: InstantiateOptions,
    /// Show a progress bar (on a terminal only).
    pub progress: bool,
    /// Measure where the wall time goes and put it in the summary ([`Timing`]); off, the run
    /// pays nothing for it.
    pub timing: bool,
    /// When recorded rows are written to the CSV.
    pub flush: FlushPolicy,
    /// Stops the run between steps when requested (signals).
    pub interrupt: Option<Interrupt>,
    /// Run even if the [`Workload`] is over its limits.
    pub force: bool,
}

/// Loads and runs a system file. The results file and the summary are written when the run
/// recorded a row (also when it then failed, with every row recorded before the error); a run
/// that recorded none, because the system file is invalid or an FMU failed to start, writes
/// neither and leaves earlier ones as they were.
pub fn run_system_file(file: &Path, options: &RunOptions) -> Result<RunSummary, Error> {
    let clock = Instant::now();
    run_loaded(System::load(file, &options.overrides, &SystemFiles::new(options.limits)), options, clock)
}

/// Runs a system that was loaded (or failed to load) since `clock`, like [`run_system_file`].
/// The notes and warnings of the loaded system are the caller's to show (`System::notes`,
/// `input_warnings`, `unconnected_warning`).
pub fn run_loaded(
    loaded: Result<System, SystemError>,
    options: &RunOptions,
    clock: Instant,
) -> Result<RunSummary, Error> {
    run_system(&loaded?, options, clock)
}

/// Runs a validated system. `clock` is when the run started (for the wall time).
pub fn run_system(system: &System, options: &RunOptions, clock: Instant) -> Result<RunSummary, Error> {
    let grid = system.grid;
    let mut summary = RunSummary {
        system: system.file.display().to_string(),
        description: system.spec.description.clone(),
        status: RunStatus::Failed,
        error: None,
        algorithm: None,
        start_time: Some(grid.start()),
        stop_time: Some(system.spec.stop_time),
        step_size: Some(grid.nominal_step()),
        shortened_last_step: grid.shortened_last_step(),
        steps: grid.steps(),
        steps_completed: 0,
        end_time: None,
        simulated_time: 0.0,
        wall_time: 0.0,
        real_time_factor: None,
        output: Some(options.output.display().to_string()),
        rows_recorded: 0,
        columns: system
            .record
            .variables
            .iter()
            .map(|v| ColumnSummary { name: v.qualified_name.clone(), unit: v.variable.unit.clone() })
            .collect(),
        instances: system
            .instances
            .iter()
            .map(|instance| InstanceSummary {
                name: instance.name.clone(),
                fmu: instance.fmu.source().display().to_string(),
                model_name: instance.fmu.model_description().model_name.clone(),
                guid: instance.fmu.model_description().guid.clone(),
            })
            .collect(),
        termination: None,
        timing: None,
    };

    let result = simulate(system, options, &mut summary);

    summary.timed(clock.elapsed().as_secs_f64());
    summary.status = match &result {
        Ok(()) if summary.termination.is_some() => RunStatus::Terminated,
        Ok(()) => RunStatus::Completed,
        Err(Error::Run(RunError::Interrupted { .. })) => RunStatus::Interrupted,
        Err(_) => RunStatus::Failed,
    };
    summary.error = result.as_ref().err().map(|e| error_chain(e));

    // The summary goes with the results: none for a run that recorded no row.
    let written = match &options.summary {
        Some(path) if summary.rows_recorded > 0 => {
            summary.write(path).map_err(|source| Error::Summary { file: path.clone(), source })
        }
        _ => Ok(()),
    };
    match (result, written) {
        (Err(error), written) => {
            if let Err(write_error) = written {
                eprintln!("warning: {}", error_chain(&write_error));
            }
            Err(error)
        }
        (Ok(()), Err(write_error)) => Err(write_error),
        (Ok(()), Ok(())) => Ok(summary),
    }
}

fn simulate(system: &System, options: &RunOptions, summary: &mut RunSummary) -> Result<(), Error> {
    if !options.force {
        Workload::of(system).check()?;
    }
    let recorder = Recorder::create(&options.output, &system.record.variables, system.record.every, options.flush)?;
    let recorder = Rc::new(RefCell::new(recorder));
    let mut execution = Execution::from_system(system, options.instantiate)?;
    if let Some(interrupt) = &options.interrupt {
        execution.interrupt_on(interrupt.clone());
    }
    summary.algorithm = Some(execution.algorithm_name().to_string());
    let clocks = if options.timing {
        let (observer, recording) = TimedObserver::new(Rc::clone(&recorder));
        execution.add_observer(Box::new(observer));
        Some((execution.time_calls(), recording))
    } else {
        execution.add_observer(Box::new(Rc::clone(&recorder)));
        None
    };
    if options.progress {
        execution.add_observer(Box::new(Progress::new(system.grid.steps())));
    }

    let _live = crate::emergency::register(
        summary,
        options.summary.clone(),
        recorder.borrow().shared(),
        execution.publish_progress(),
        system.grid,
    );
    let clock = Instant::now();
    let outcome = execution.run().and_then(|()| execution.terminate());
    let flushed = execution.finish_observers();
    let total = clock.elapsed();

    summary.reached(execution.completed_steps(), execution.time(), execution.grid().start(), recorder.borrow().rows());
    summary.termination = execution.termination().cloned();
    summary.timing = clocks.map(|(instances, recording)| Timing {
        steps: execution.completed_steps(),
        total_s: total.as_secs_f64(),
        recording_s: recording.get().as_secs_f64(),
        instances: execution
            .simulators()
            .iter()
            .zip(instances)
            .map(|(simulator, times)| InstanceTiming {
                name: simulator.name().to_string(),
                do_step_s: times.do_step().as_secs_f64(),
                get_set_s: times.get_set().as_secs_f64(),
            })
            .collect(),
    });
    outcome?;
    flushed?;
    Ok(())
}
