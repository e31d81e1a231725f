//! System files: which FMUs, instances, start values, connections, input
//! files, time grid and recorded variables.
//!
//! [`System::load`] reads the JSON ([`SystemSpec`]), opens every FMU
//! (extraction and model description only — nothing is instantiated and no
//! library is loaded) and resolves every name; systems built from the same files can share
//! the opened FMUs and parsed files through [`SystemFiles`]. All problems are reported
//! together, each with the JSON location, the offending name, a suggestion
//! and the names that exist.
//!
//! [`System::load`] also runs scenario files ([`scenario`]) and SSP 1.0 archives ([`ssp`]),
//! which are read into the same [`SystemSpec`]; [`System::load_fmu`] runs one `.fmu` alone
//! ([`single`]).

mod files;
pub mod scenario;
mod schema;
pub mod single;
pub mod ssp;
mod validate;

use std::path::{Path, PathBuf};

pub use files::SystemFiles;
pub use schema::{AlgorithmKind, ConnectionSpec, InputSpec, InstanceSpec, RecordSpec, SystemSpec};

use fmu_import::fmu::{ArchiveError, Fmu, ScalarVariable};
use fmu_import::value::Value;

use crate::input::InputBinding;
use crate::time::TimeGrid;
pub use crate::variable::VariableRef;

/// One problem in a system file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// JSON location, e.g. `instances[0].start["theta_x9"]`.
    pub location: String,
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
    /// A `.fmu` run alone ([`System::load_fmu`]) that cannot be opened.
    #[error(transparent)]
    Fmu(#[from] fmu_import::fmu::FmuError),
    #[error("{}: cannot extract the SSP archive", file.display())]
    Archive {
        file: PathBuf,
        #[source]
        source: ArchiveError,
    },
    #[error("{}:{line}:{column}: invalid system file: {message}", file.display())]
    Parse { file: PathBuf, line: usize, column: usize, message: String },
    #[error(
        "{}: invalid system file ({} problem{}):\n{}",
        file.display(),
        problems.len(),
        if problems.len() == 1 { "" } else { "s" },
        problems.iter().map(|p| format!("  {p}")).collect::<Vec<_>>().join("\n")
    )]
    Invalid { file: PathBuf, problems: Vec<Problem> },
}

impl SystemError {
    /// The individual problems (empty for read and parse errors).
    pub fn problems(&self) -> &[Problem] {
        match self {
            SystemError::Invalid { problems, .. } => problems,
            _ => &[],
        }
    }
}

/// Command-line overrides applied before validation.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Overrides {
    /// Replaces `stop_time` (s).
    pub stop_time: Option<f64>,
    /// Replaces `step_size` (s).
    pub step_size: Option<f64>,
    /// Replaces `algorithm` (also a scenario's).
    pub algorithm: Option<AlgorithmKind>,
    /// `"instance.variable"` → start value, added to (or replacing) the file's; a value
    /// `{"path": "file"}` is a path relative to the working directory.
    pub start: Vec<(String, serde_json::Value)>,
}

/// A resolved instance.
#[derive(Debug, Clone)]
pub struct Instance {
    pub name: String,
    /// Alias in `fmus`.
    pub fmu_alias: String,
    pub fmu: Fmu,
    /// Start values, type-checked, in the order they are set.
    pub start: Vec<(ScalarVariable, Value)>,
}

/// A resolved connection (same ABI type on both ends).
#[derive(Debug, Clone, PartialEq)]
pub struct Connection {
    pub from: VariableRef,
    pub to: VariableRef,
}

/// A resolved inputs file.
#[derive(Debug, Clone)]
pub struct BoundInput {
    /// Index into [`System::instances`].
    pub instance: usize,
    pub binding: InputBinding,
}

/// What to record, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordPlan {
    /// Record every `every`-th communication point (k = 0, every, 2·every, ...).
    pub every: u64,
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
    pub connections: Vec<Connection>,
    pub inputs: Vec<BoundInput>,
    pub grid: TimeGrid,
    pub record: RecordPlan,
}

impl System {
    /// Reads, parses and validates a system file, a scenario file or an SSP archive (`.ssp`).
    pub fn load(file: &Path, overrides: &Overrides) -> Result<Self, SystemError> {
        // The FMUs are extracted again when opened, so the archive's folder is not needed later.
        Self::load_keeping_archive(file, overrides).map(|(system, _)| system)
    }

    /// Like [`System::load`], also returning the folder an `.ssp` archive was extracted to, which
    /// holds the `.fmu` files the instances were opened from until it is dropped.
    pub fn load_keeping_archive(
        file: &Path,
        overrides: &Overrides,
    ) -> Result<(Self, Option<tempfile::TempDir>), SystemError> {
        let files = SystemFiles::default();
        if ssp::is_ssp(file) {
            let archive = ssp::read(file, overrides)?;
            let system = Self::from_spec(archive.spec, file, archive.directory.path(), overrides, &files)?;
            return Ok((system, Some(archive.directory)));
        }
        let text = read_system_text(file).map_err(|source| SystemError::Read { file: file.to_path_buf(), source })?;
        if scenario::is_scenario(&text) {
            let (spec, system_file) = scenario::resolve(&text, file, &files)?;
            return Ok((Self::from_resolved_scenario(spec, file, &system_file, overrides, &files)?, None));
        }
        let spec = parse_spec(&text, file)?;
        let base = file.parent().unwrap_or_else(|| Path::new(""));
        Ok((Self::from_spec(spec, file, base, overrides, &files)?, None))
    }

    /// Validates an in-memory scenario as if it were the file `file` (its `system` path is
    /// relative to that file's folder), with its system file and FMUs taken from `files`.
    pub fn from_scenario(
        spec: &scenario::ScenarioSpec,
        file: &Path,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<Self, SystemError> {
        let (system, system_file) = scenario::resolve_spec(spec, file, files)?;
        Self::from_resolved_scenario(system, file, &system_file, overrides, files)
    }

    /// Names are reported against the scenario; the system's paths stay relative to its file.
    fn from_resolved_scenario(
        spec: SystemSpec,
        file: &Path,
        system_file: &Path,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<Self, SystemError> {
        let base = system_file.parent().unwrap_or_else(|| Path::new(""));
        Self::from_spec(spec, file, base, overrides, files)
    }

    /// Validates an in-memory specification; relative paths are resolved
    /// against `base`, FMUs are taken from `files`, and messages name `file`.
    pub fn from_spec(
        mut spec: SystemSpec,
        file: &Path,
        base: &Path,
        overrides: &Overrides,
        files: &SystemFiles,
    ) -> Result<Self, SystemError> {
        if let Some(stop) = overrides.stop_time {
            spec.stop_time = stop;
        }
        if let Some(step) = overrides.step_size {
            spec.step_size = step;
        }
        if let Some(algorithm) = overrides.algorithm {
            spec.algorithm = algorithm;
        }
        for instance in &mut spec.instances {
            for value in instance.start.values_mut() {
                *value = scenario::resolve_path_value(value, base);
            }
        }
        let start = overrides
            .start
            .iter()
            .map(|(key, value)| (key.as_str(), scenario::resolve_path_value(value, Path::new(""))));
        let problems = scenario::apply_start(start, |key| format!("--start {key}"), &mut spec);
        if !problems.is_empty() {
            return Err(SystemError::Invalid { file: file.to_path_buf(), problems });
        }
        validate::validate(spec, file, base, files)
    }

    /// The instance index of `name`.
    pub fn instance_index(&self, name: &str) -> Option<usize> {
        self.instances.iter().position(|i| i.name == name)
    }
}

/// Parses the JSON text of a system file.
pub fn parse_spec(text: &str, file: &Path) -> Result<SystemSpec, SystemError> {
    serde_json::from_str(text).map_err(|error| {
        let mut message = error.to_string();
        // serde_json appends " at line L column C"; the position is reported separately.
        if let Some(position) = message.rfind(" at line ") {
            message.truncate(position);
        }
        SystemError::Parse { file: file.to_path_buf(), line: error.line(), column: error.column(), message }
    })
}

/// A system or scenario file's text: a regular file of at most
/// [`MAX_TEXT_FILE_BYTES`](fmu_import::file::MAX_TEXT_FILE_BYTES), in UTF-8.
fn read_system_text(file: &Path) -> std::io::Result<String> {
    fmu_import::file::read_regular_text(file, fmu_import::file::MAX_TEXT_FILE_BYTES)
}

#[cfg(test)]
mod tests;
