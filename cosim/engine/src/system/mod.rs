//! System files: which FMUs, instances, start values, connections, input
//! files, time grid and recorded variables.
//!
//! Loading a system is one pipeline of four steps, each in its own module and taken once, in
//! this order:
//!
//! 1. **read** (`read`): the file's text, or an SSP archive extracted, or a lone FMU opened
//!    (every archive within the [`SystemFiles::limits`]);
//! 2. **parse** (`parse`): a system file ([`SystemSpec`]), a scenario file (its system file
//!    with the scenario's settings, [`scenario`]), an SSP 1.0 archive's `SystemStructure.ssd`
//!    ([`ssp`]), an OSP system structure ([`osp`]) or a lone FMU ([`single`]) as one
//!    [`SystemSpec`] and the folder its paths are relative to;
//! 3. **apply overrides** (`overrides`): the caller's stop time, step size, algorithm and
//!    start values ([`Overrides`]);
//! 4. **validate** (`validate`): opens every FMU (extraction and model description only —
//!    nothing is instantiated and no library is loaded) and resolves every name, check by check
//!    (time grid, FMUs, instances, start values, connections, inputs files, recording).
//!
//! [`System::load`] and [`System::load_fmu`] take all four; [`System::from_scenario`] starts at
//! step 2 with an in-memory scenario, [`System::from_spec`] at step 3 with an in-memory
//! specification. Systems built from the same files can share the opened FMUs and parsed files
//! through [`SystemFiles`]. A step that finds problems ends the pipeline; all problems of a step
//! are reported together, each with its location, the offending name, a suggestion and the names
//! that exist.

mod files;
pub mod json;
pub mod osp;
mod overrides;
mod parse;
mod read;
pub mod scenario;
mod schema;
pub mod single;
pub mod ssp;
mod validate;

use std::path::{Path, PathBuf};

pub use files::SystemFiles;
pub use json::{FileKind, ParseError};
pub use overrides::Overrides;
pub use parse::parse_spec;
pub use schema::{AlgorithmKind, ConnectionSpec, InputSpec, InstanceSpec, RecordSpec, SystemSpec};

use fmu_import::fmu::{ArchiveError, Fmu, ScalarVariable};
use fmu_import::value::Value;

use crate::input::InputBinding;
use crate::text::Decimal;
use crate::time::{is_close, TimeGrid};
pub use crate::variable::VariableRef;

/// One problem in a system file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// JSON location, e.g. `instances[0].start["theta_x9"]`.
    pub location: String,
    /// What is wrong there.
    pub message: String,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.location, self.message)
    }
}

/// Why a system file cannot be used. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum SystemError {
    #[error("cannot read system file {}", file.display())]
    Read {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A file or folder of another kind than a system can be read from.
    #[error("{}: expected {EXPECTED}, but this is {found}", file.display())]
    Kind { file: PathBuf, found: String },
    /// A `.fmu` run alone ([`System::load_fmu`]) that cannot be opened.
    #[error(transparent)]
    Fmu(#[from] fmu_import::fmu::FmuError),
    #[error("{}: cannot extract the SSP archive", file.display())]
    Archive {
        file: PathBuf,
        #[source]
        source: ArchiveError,
    },
    /// Not JSON (or XML), or a field its kind of file does not have.
    #[error("{}:{}:{}: {error}", file.display(), error.line, error.column)]
    Parse { file: PathBuf, error: ParseError },
    #[error(
        "{}: invalid system file ({} problem{}):\n{}",
        file.display(),
        problems.len(),
        if problems.len() == 1 { "" } else { "s" },
        problems.iter().map(|p| format!("  {p}")).collect::<Vec<_>>().join("\n")
    )]
    Invalid { file: PathBuf, problems: Vec<Problem> },
    /// Only the start values given on top of the file (the command line's) are wrong.
    #[error(
        "{}: invalid start value{} ({} problem{}):\n{}",
        file.display(),
        if problems.len() == 1 { "" } else { "s" },
        problems.len(),
        if problems.len() == 1 { "" } else { "s" },
        problems.iter().map(|p| format!("  {p}")).collect::<Vec<_>>().join("\n")
    )]
    Options { file: PathBuf, problems: Vec<Problem> },
}

/// A start value's problem located where the value came from: a start value the overrides gave
/// (the command line's `--start`) is named `Overrides::start["instance.variable"]`, not by the
/// place in the file it was merged into (`instances[0].start["variable"]`), so that the command
/// line can name its option; when every problem is of the overrides, the file itself is not
/// called invalid.
fn blame_overrides(error: SystemError, instances: &[String], overrides: &Overrides) -> SystemError {
    let SystemError::Invalid { file, mut problems } = error else { return error };
    let mut all = true;
    for problem in &mut problems {
        match overridden_start(&problem.location, instances, overrides) {
            Some((merged, name)) => {
                problem.location = problem.location.replacen(&merged, &format!("Overrides::start[\"{name}\"]"), 1)
            }
            None => all = false,
        }
    }
    if all {
        SystemError::Options { file, problems }
    } else {
        SystemError::Invalid { file, problems }
    }
}

/// For a location `instances[i].start["v"]…` of a start value the overrides gave, that prefix and
/// the override's name `instance.v`.
fn overridden_start(location: &str, instances: &[String], overrides: &Overrides) -> Option<(String, String)> {
    let rest = location.strip_prefix("instances[")?;
    let (index, rest) = rest.split_once("].start[\"")?;
    let (variable, _) = rest.split_once("\"]")?;
    let instance = instances.get(index.parse::<usize>().ok()?)?;
    let name = format!("{instance}.{variable}");
    overrides
        .start
        .iter()
        .any(|(key, _)| *key == name)
        .then(|| (format!("instances[{index}].start[\"{variable}\"]"), name))
}

impl SystemError {
    /// The individual problems (empty for read and parse errors).
    pub fn problems(&self) -> &[Problem] {
        match self {
            SystemError::Invalid { problems, .. } | SystemError::Options { problems, .. } => problems,
            _ => &[],
        }
    }
}

/// What [`System::load`] reads, for messages.
pub const EXPECTED: &str = "a system or scenario file (JSON), an SSP archive (.ssp) or an OSP system structure \
                            (a folder holding OspSystemStructure.xml, or that file)";

/// A resolved instance.
#[derive(Debug, Clone)]
pub struct Instance {
    /// The instance's name, unique in the system.
    pub name: String,
    /// Alias in `fmus`.
    pub fmu_alias: String,
    /// The loaded FMU it instantiates.
    pub fmu: Fmu,
    /// Start values, type-checked, in the order they are set.
    pub start: Vec<(ScalarVariable, Value)>,
}

/// A resolved connection (same ABI type on both ends).
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    /// The output read.
    pub from: VariableRef,
    /// The input it sets.
    pub to: VariableRef,
}

/// A resolved inputs file.
#[derive(Debug, Clone)]
pub struct BoundInput {
    /// Index into [`System::instances`].
    pub instance: usize,
    /// The table's columns bound to the instance's inputs.
    pub binding: InputBinding,
}

/// What to record, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordPlan {
    /// Record every `every`-th communication point (k = 0, every, 2·every, ...).
    pub every: u64,
    /// The recorded variables, in column order.
    pub variables: Vec<VariableRef>,
}

/// A validated system, ready to be instantiated.
#[derive(Debug, Clone)]
pub struct System {
    /// The system file (or a label for in-memory specs).
    pub file: PathBuf,
    /// The specification after overrides.
    pub spec: SystemSpec,
    /// In stepping order.
    pub instances: Vec<Instance>,
    /// Output-to-input connections, resolved.
    pub connections: Vec<Connection>,
    /// Inputs files bound to their instances.
    pub inputs: Vec<BoundInput>,
    /// The communication points from the start to the stop time.
    pub grid: TimeGrid,
    /// What is recorded and how often.
    pub record: RecordPlan,
    /// The inputs that nothing feeds (no connection, no input table) and that have no start value
    /// in the file, qualified (`"instance.variable"`), in stepping and model-description order:
    /// they keep the FMU's default start value for the whole run.
    pub unconnected_inputs: Vec<String>,
    /// What the run chose because nothing gave it (a lone FMU without a default experiment:
    /// [`single::fmpy_defaults`]), as lines to print.
    pub notes: Vec<String>,
}

impl System {
    /// Reads, parses and validates a system file, a scenario file, an SSP archive (`.ssp`) or an
    /// OSP system structure (a folder holding `OspSystemStructure.xml`, or that file), with its
    /// FMUs taken from `files`. Anything else is refused saying what it is ([`SystemError::Kind`]).
    pub fn load(file: &Path, overrides: &Overrides, files: &SystemFiles) -> Result<Self, SystemError> {
        // The FMUs are extracted again when opened, so the archive's folder is not needed later.
        Self::load_keeping_archive(file, overrides, files).map(|(system, _)| system)
    }

    /// Like [`System::load`], also returning the folder an `.ssp` archive was extracted to, which
    /// holds the `.fmu` files the instances were opened from until it is dropped.
    pub fn load_keeping_archive(
        file: &Path,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<(Self, Option<tempfile::TempDir>), SystemError> {
        let source = read::read(file, files)?;
        let parsed = parse::parse(&source, file, overrides, files)?;
        let system = Self::from_spec(parsed.spec, file, &parsed.base, overrides, files)?;
        let archive = match source {
            read::Source::Ssp(directory) => Some(directory),
            read::Source::Json(_) | read::Source::Xml { .. } => None,
        };
        Ok((system, archive))
    }

    /// Opens the `.fmu` file `file` and validates the system that runs it alone
    /// ([`single::spec`]).
    pub fn load_fmu(
        file: &Path,
        single: &single::SingleFmu,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<Self, SystemError> {
        let fmu = read::read_fmu(file, files)?;
        let parsed = parse::parse_fmu(file, &fmu, single, overrides)?;
        // The patterns of `--record` are expanded like a system's, qualified with the instance
        // name (as the columns are named) unless they are already.
        let prefix = format!("{}.", single::instance_name(file));
        let qualified =
            single.record.iter().map(|p| if p.starts_with(&prefix) { p.clone() } else { format!("{prefix}{p}") });
        let overrides =
            Overrides { record: overrides.record.iter().cloned().chain(qualified).collect(), ..overrides.clone() };
        let system = Self::from_spec(parsed.spec, file, &parsed.base, &overrides, files)?;
        // A lone FMU runs its inputs at their defaults unless fed: nothing to warn about.
        Ok(Self { notes: single::fmpy_defaults(&fmu, &overrides), unconnected_inputs: Vec::new(), ..system })
    }

    /// Validates an in-memory scenario as if it were the file `file` (its `system` path is
    /// relative to that file's folder), with its system file and FMUs taken from `files`. Names
    /// are reported against the scenario; the system's paths stay relative to its file.
    pub fn from_scenario(
        spec: &scenario::ScenarioSpec,
        file: &Path,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<Self, SystemError> {
        let parsed = parse::parse_scenario(spec, file, files)?;
        Self::from_spec(parsed.spec, file, &parsed.base, overrides, files)
    }

    /// Applies `overrides` to an in-memory specification and validates it (steps 3 and 4);
    /// relative paths are resolved against `base`, FMUs are taken from `files`, and messages
    /// name `file`.
    pub fn from_spec(
        spec: SystemSpec,
        file: &Path,
        base: &Path,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<Self, SystemError> {
        let spec = overrides::apply(spec, file, base, overrides)?;
        let instances: Vec<String> = spec.instances.iter().map(|i| i.name.clone()).collect();
        validate::validate(spec, file, base, files, overrides)
            .map_err(|error| blame_overrides(error, &instances, overrides))
    }

    /// One line for each inputs file that ends before the stop time: its last row is held from
    /// there on, which a run with a stop time meant for another file does without a sign.
    pub fn input_warnings(&self) -> Vec<String> {
        let end = self.grid.end();
        let tables = self.inputs.iter().map(|input| input.binding.table());
        let short = tables.filter(|table| table.times.last().is_some_and(|&last| last < end && !is_close(last, end)));
        short
            .map(|table| {
                let last = table.times.last().copied().unwrap_or_default();
                format!(
                    "input table {} ends at {} s, the run goes to {} s: the last row is held",
                    table.file.display(),
                    Decimal(last),
                    Decimal(end)
                )
            })
            .collect()
    }

    /// One line naming the inputs nothing feeds ([`System::unconnected_inputs`]), if any.
    pub fn unconnected_warning(&self) -> Option<String> {
        (!self.unconnected_inputs.is_empty()).then(|| {
            format!(
                "{} fed by no connection or input table and given no start value, keeping the FMU's default: {}",
                if self.unconnected_inputs.len() == 1 { "1 input is" } else { "inputs are" },
                self.unconnected_inputs.join(", ")
            )
        })
    }

    /// The instance index of `name`.
    pub fn instance_index(&self, name: &str) -> Option<usize> {
        self.instances.iter().position(|i| i.name == name)
    }
}

#[cfg(test)]
mod tests;
