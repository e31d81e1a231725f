//! A run of a system, scenario, SSP archive, OSP system structure or lone FMU: recorded to a
//! CSV or Parquet file with its summary (`crane-cosim run`), or into memory (Python's `run` and
//! `Simulation`).
//!
//! A run is two calls: [`load`] reads the files and returns the notes and warnings the user
//! should see before the run starts ([`Loaded::notices`]); [`Loaded::to_file`] or
//! [`Loaded::to_table`] then runs it.

use std::path::{Path, PathBuf};
use std::time::Instant;

use cosim_engine::error::Error as EngineError;
use cosim_engine::execution::Execution;
use cosim_engine::interrupt::Interrupt;
use cosim_engine::observer::{FlushPolicy, TableRecorder, STANDARD_OUTPUT};
use cosim_engine::run::{run_loaded, RunOptions};
use cosim_engine::summary::RunSummary;
use cosim_engine::system::single::SingleFmu;
use cosim_engine::system::{AlgorithmKind, Overrides, System, SystemError, SystemFiles};
use cosim_engine::table::SignalTable;
use cosim_engine::workload::Workload;
use fmu_import::fmi::LogEcho;
use fmu_import::fmu::ExtractLimits;
use fmu_import::slave::InstantiateOptions;
use fmu_import::value::VariableType;

use crate::notice::Notice;
use crate::source::Source;

/// The time grid and algorithm a request may replace (the file's, or the FMU's default
/// experiment's, where not given).
#[derive(Debug, Clone, Default)]
pub struct Grid {
    /// Stop time (s).
    pub stop_time: Option<f64>,
    /// Communication step size (s).
    pub step_size: Option<f64>,
    /// The master algorithm.
    pub algorithm: Option<AlgorithmKind>,
    /// Under Jacobi, pass the slopes of connected inputs from the last two communication points.
    pub extrapolate_inputs: bool,
    /// Recording interval (s), a whole multiple of the step size.
    pub record_interval: Option<f64>,
}

impl Grid {
    /// The overrides these replacements stand for (no start values).
    pub fn overrides(&self) -> Overrides {
        Overrides {
            stop_time: self.stop_time,
            step_size: self.step_size,
            algorithm: self.algorithm,
            extrapolate_inputs: self.extrapolate_inputs.then_some(true),
            record_interval: self.record_interval,
            ..Overrides::default()
        }
    }
}

/// What a run is asked for: the file and what replaces the file's own settings.
#[derive(Debug, Clone)]
pub struct RunRequest {
    /// The file run.
    pub source: Source,
    /// `instance.variable` (for a lone FMU also `variable`) → value, replacing the file's.
    pub start: Vec<(String, serde_json::Value)>,
    /// Replacements of the file's time grid and algorithm.
    pub grid: Grid,
    /// Names or patterns of variables recorded (after the file's; for a lone FMU instead of its
    /// outputs).
    pub record: Vec<String>,
    /// Input CSVs.
    pub inputs: Vec<PathBuf>,
    /// Pass no input derivatives, also where the file asks for them.
    pub no_input_derivatives: bool,
    /// Run even if the grid or the results are over the workload limits.
    pub force: bool,
    /// What each FMU or SSP archive may unpack to.
    pub limits: ExtractLimits,
}

impl RunRequest {
    /// A request for `path` with nothing replaced.
    pub fn new(path: &Path) -> RunRequest {
        RunRequest {
            source: Source::of(path),
            start: Vec::new(),
            grid: Grid::default(),
            record: Vec::new(),
            inputs: Vec::new(),
            no_input_derivatives: false,
            force: false,
            limits: ExtractLimits::default(),
        }
    }

    /// The overrides the request stands for: a lone FMU's start values qualified with its
    /// instance name, its patterns and inputs files left to [`SingleFmu`].
    pub fn overrides(&self) -> Overrides {
        let system = matches!(self.source, Source::System(_));
        Overrides {
            start: self.start.iter().map(|(name, value)| (self.source.qualified(name), value.clone())).collect(),
            input_derivatives: self.no_input_derivatives.then_some(false),
            record: if system { self.record.clone() } else { Vec::new() },
            inputs: if system { self.inputs.clone() } else { Vec::new() },
            ..self.grid.overrides()
        }
    }
}

/// Where a run to a file writes and what it shows while it runs.
#[derive(Debug, Clone, Default)]
pub struct FileOutput {
    /// Results CSV, Parquet when the name ends in `.parquet`, or `-` for standard output.
    pub output: PathBuf,
    /// Summary JSON (none: not written).
    pub summary: Option<PathBuf>,
    /// Show a progress bar (on a terminal only).
    pub progress: bool,
    /// Measure where the wall time goes, into the summary.
    pub timing: bool,
    /// Switch FMU debug logging on and echo every FMU message (else warnings only).
    pub fmu_log: bool,
    /// When recorded rows are written.
    pub flush: FlushPolicy,
    /// Stops the run between steps when requested (signals).
    pub interrupt: Option<Interrupt>,
}

/// `out/<file stem>.csv`: where a run of `path` writes unless told otherwise.
pub fn default_output(path: &Path) -> PathBuf {
    let stem = path.file_stem().map_or_else(|| "results".into(), |s| s.to_string_lossy().into_owned());
    Path::new("out").join(format!("{stem}.csv"))
}

/// `<output without extension>.summary.json`: where a run writes the summary of a results file
/// unless told otherwise, and where a plot looks for its units.
pub fn summary_path(output: &Path) -> PathBuf {
    output.with_extension("summary.json")
}

/// Whether `output` is standard output (`-`).
pub fn to_stdout(output: &Path) -> bool {
    output == Path::new(STANDARD_OUTPUT)
}

/// Why an in-memory run failed.
#[derive(Debug, thiserror::Error)]
pub enum TableError {
    #[error(transparent)]
    Engine(#[from] EngineError),
    #[error("{}: a table in memory holds numbers, not the string variables {}", file.display(), names.join(", "))]
    StringColumns { file: PathBuf, names: Vec<String> },
}

/// The recorded rows of an in-memory run, bit for bit the values of the CSV a run to a file
/// writes.
#[derive(Debug, Clone)]
pub struct Recording {
    /// Recorded columns without `time`.
    pub names: Vec<String>,
    /// Each column's unit in its model description.
    pub units: Vec<Option<String>>,
    /// Each row's time (s).
    pub times: Vec<f64>,
    /// Each column's values, one per row.
    pub columns: Vec<Vec<f64>>,
}

/// A request's files read: the system, or why it could not be loaded.
pub struct Loaded {
    system: Result<System, SystemError>,
    force: bool,
    limits: ExtractLimits,
    /// When loading started (a run's wall time includes it).
    clock: Instant,
}

/// Reads the request's files and applies its replacements.
pub fn load(request: &RunRequest) -> Loaded {
    let clock = Instant::now();
    let overrides = request.overrides();
    let files = SystemFiles::new(request.limits);
    let system = match &request.source {
        Source::Fmu(path) => {
            let single = SingleFmu { inputs: request.inputs.clone(), record: request.record.clone() };
            System::load_fmu(path, &single, &overrides, &files)
        }
        Source::System(path) => System::load(path, &overrides, &files),
    };
    Loaded { system, force: request.force, limits: request.limits, clock }
}

impl Loaded {
    /// The notes and warnings about the loaded system to show before it runs: defaults taken,
    /// inputs files that end before the stop time, inputs nothing feeds.
    pub fn notices(&self) -> Vec<Notice> {
        let Ok(system) = &self.system else { return Vec::new() };
        let notes = system.notes.iter().cloned().map(Notice::Note);
        let warnings = system.input_warnings().into_iter().chain(system.unconnected_warning()).map(Notice::Warning);
        notes.chain(warnings).collect()
    }

    /// Runs into `output`. The results and the summary are written when the run recorded a row,
    /// also when it then failed (with every row recorded before the error); a run that recorded
    /// none writes neither and leaves earlier files as they were.
    pub fn to_file(self, output: &FileOutput) -> Result<RunSummary, EngineError> {
        let echo = if output.fmu_log { LogEcho::All } else { LogEcho::Warnings };
        let options = RunOptions {
            output: output.output.clone(),
            summary: output.summary.clone(),
            overrides: Overrides::default(),
            limits: self.limits,
            instantiate: InstantiateOptions { visible: false, logging_on: output.fmu_log, echo },
            progress: output.progress,
            timing: output.timing,
            flush: output.flush,
            interrupt: output.interrupt.clone(),
            force: self.force,
        };
        run_loaded(self.system, &options, self.clock)
    }

    /// The loaded system, its workload checked (unless forced): for stepping it on request.
    pub fn into_system(self) -> Result<System, EngineError> {
        let system = self.system?;
        if !self.force {
            Workload::of(&system).check()?;
        }
        Ok(system)
    }

    /// Runs into memory; refused for string variables among the recorded ones.
    pub fn to_table(self) -> Result<Recording, TableError> {
        let system = self.into_system()?;
        let recorder = table_recorder(&system)?;
        let execution = Execution::from_system(&system, IN_MEMORY).map_err(EngineError::from)?;
        let table = execution.run_into_table(recorder).map_err(EngineError::from)?;
        Ok(recording(&system, table))
    }
}

/// How the instances of an in-memory run are created: no UI, no FMU logging, warnings echoed.
pub const IN_MEMORY: InstantiateOptions =
    InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Warnings };

/// A recorder of the system's recorded variables at its interval; refused for string variables.
pub fn table_recorder(system: &System) -> Result<TableRecorder, TableError> {
    let variables = &system.record.variables;
    TableRecorder::new(&system.file, variables, system.record.every).ok_or_else(|| TableError::StringColumns {
        file: system.file.clone(),
        names: variables
            .iter()
            .filter(|v| v.variable.variable_type.abi_type() == VariableType::String)
            .map(|v| v.qualified_name.clone())
            .collect(),
    })
}

/// The recorded rows of `system` in `table`, with their units.
pub fn recording(system: &System, table: SignalTable) -> Recording {
    Recording {
        names: table.names,
        units: system.record.variables.iter().map(|v| v.variable.unit.clone()).collect(),
        times: table.times,
        columns: table.columns,
    }
}
