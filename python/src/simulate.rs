//! A run as `crane-cosim run` does it (the same loading, overrides, workload check, algorithm and
//! recording interval), recorded into memory instead of a CSV: free of Python types, so that it
//! can run without the interpreter's lock.

use std::path::{Path, PathBuf};

use cosim_engine::error::Error;
use cosim_engine::execution::Execution;
use cosim_engine::observer::TableRecorder;
use cosim_engine::system::single::{instance_name, SingleFmu};
use cosim_engine::system::{AlgorithmKind, Overrides, System, SystemFiles};
use cosim_engine::table::SignalTable;
use cosim_engine::workload::Workload;
use fmu_import::error_chain;
use fmu_import::fmi::LogEcho;
use fmu_import::fmu::ExtractLimits;
use fmu_import::slave::InstantiateOptions;
use fmu_import::value::VariableType;

/// What a run is asked for: the file and what `crane-cosim run`'s options would replace.
#[derive(Debug, Clone, Default)]
pub struct Request {
    /// A system or scenario file, SSP archive, OSP system structure or one `.fmu`.
    pub system: PathBuf,
    /// `instance.variable` (or `variable` for one `.fmu`) → value, as `--start` gives them.
    pub start: Vec<(String, serde_json::Value)>,
    pub stop_time: Option<f64>,
    pub step_size: Option<f64>,
    pub record_interval: Option<f64>,
    pub algorithm: Option<String>,
    /// Names or patterns, as `--record` takes them.
    pub record: Vec<String>,
    /// Input CSVs, as `--input` takes them.
    pub inputs: Vec<PathBuf>,
    /// Run even if the grid or the results are over the workload limits (`--force`).
    pub force: bool,
}

/// The recorded rows, bit for bit the values of the CSV `crane-cosim run` writes.
#[derive(Debug, Clone)]
pub struct Results {
    /// Recorded columns without `time`.
    pub names: Vec<String>,
    /// Each column's unit in its model description.
    pub units: Vec<Option<String>>,
    pub times: Vec<f64>,
    pub columns: Vec<Vec<f64>>,
    /// The notes and warnings the command line prints before the run.
    pub warnings: Vec<String>,
}

/// True for one FMU to run alone.
fn is_fmu(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("fmu"))
}

impl Request {
    /// The instance prefix of a lone FMU's names (`"pendulum."`), which its start values and
    /// variable names may leave out; empty for a system.
    pub fn prefix(&self) -> String {
        if is_fmu(&self.system) {
            format!("{}.", instance_name(&self.system))
        } else {
            String::new()
        }
    }

    /// The overrides `crane-cosim run` makes of the same options (a lone FMU's start values
    /// qualified with its instance name; its patterns and inputs go to [`SingleFmu`]).
    fn overrides(&self) -> Result<Overrides, String> {
        let prefix = self.prefix();
        let qualified = |name: &str| match name.strip_prefix(&prefix) {
            Some(_) if !prefix.is_empty() => name.to_string(),
            _ => format!("{prefix}{name}"),
        };
        let algorithm = self
            .algorithm
            .as_deref()
            .map(|name| name.parse::<AlgorithmKind>().map_err(|e| format!("algorithm {name:?}: {e}")))
            .transpose()?;
        Ok(Overrides {
            stop_time: self.stop_time,
            step_size: self.step_size,
            algorithm,
            record_interval: self.record_interval,
            start: self.start.iter().map(|(name, value)| (qualified(name), value.clone())).collect(),
            record: if prefix.is_empty() { self.record.clone() } else { Vec::new() },
            inputs: if prefix.is_empty() { self.inputs.clone() } else { Vec::new() },
            ..Overrides::default()
        })
    }
}

/// An error of the libraries as one line: its whole chain, in their wording.
pub fn chain(error: impl Into<Error>) -> String {
    error_chain(&error.into())
}

/// How the instances are created: no UI, no FMU logging, warnings echoed.
pub const INSTANTIATE: InstantiateOptions =
    InstantiateOptions { visible: false, logging_on: false, echo: LogEcho::Warnings };

/// Loads the file with the request's overrides and checks its workload (unless forced).
pub fn load(request: &Request) -> Result<System, String> {
    let overrides = request.overrides()?;
    let files = SystemFiles::new(ExtractLimits::default());
    let system = if is_fmu(&request.system) {
        let single = SingleFmu { inputs: request.inputs.clone(), record: request.record.clone() };
        System::load_fmu(&request.system, &single, &overrides, &files)
    } else {
        System::load(&request.system, &overrides, &files)
    };
    let system = system.map_err(chain)?;
    if !request.force {
        Workload::of(&system).check().map_err(chain)?;
    }
    Ok(system)
}

/// The notes and warnings the command line prints before a run of `system`.
pub fn warnings(system: &System) -> Vec<String> {
    let mut warnings: Vec<String> = system.notes.iter().map(|note| format!("note: {note}")).collect();
    warnings.extend(system.input_warnings().into_iter().chain(system.unconnected_warning()));
    warnings
}

/// A recorder of the system's recorded variables at its interval; refused for string variables.
pub fn recorder(system: &System) -> Result<TableRecorder, String> {
    let variables = &system.record.variables;
    TableRecorder::new(&system.file, variables, system.record.every).ok_or_else(|| {
        let strings: Vec<&str> = variables
            .iter()
            .filter(|v| v.variable.variable_type.abi_type() == VariableType::String)
            .map(|v| v.qualified_name.as_str())
            .collect();
        format!("{}: a DataFrame holds numbers, not the string variables {}", system.file.display(), strings.join(", "))
    })
}

/// The recorded rows of `system` in `table`, with the units and warnings.
pub fn results(system: &System, table: SignalTable, warnings: Vec<String>) -> Results {
    Results {
        names: table.names,
        units: system.record.variables.iter().map(|v| v.variable.unit.clone()).collect(),
        times: table.times,
        columns: table.columns,
        warnings,
    }
}

/// Loads and runs the file; an error is its whole chain on one line, in the libraries' wording.
pub fn run(request: &Request) -> Result<Results, String> {
    let system = load(request)?;
    let warnings = warnings(&system);
    let recorder = recorder(&system)?;
    let execution = Execution::from_system(&system, INSTANTIATE).map_err(chain)?;
    let table = execution.run_into_table(recorder).map_err(chain)?;
    Ok(results(&system, table, warnings))
}
