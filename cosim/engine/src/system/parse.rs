//! Step 2 of loading a system: the [`Source`] read in step 1 as a [`SystemSpec`] and the folder its
//! relative paths start from.
//!
//! A system file is the specification itself; a scenario file names a system file (read and
//! parsed here, through [`SystemFiles`]) and changes its settings ([`scenario`]); an SSP archive
//! is read from its `SystemStructure.ssd` ([`ssp`]); a lone FMU becomes a system of one instance
//! ([`single`]).

use std::path::{Path, PathBuf};

use fmu_import::fmu::Fmu;

use super::json::{self, FileKind, ParseError};
use super::read::Source;
use super::single::{self, SingleFmu};
use super::{osp, scenario, ssp, Overrides, SystemError, SystemFiles, SystemSpec};

/// A parsed specification and the folder its relative paths (FMUs, inputs files, start values
/// given as `{"path": …}`) are relative to.
#[derive(Debug)]
pub(super) struct Parsed {
    pub spec: SystemSpec,
    pub base: PathBuf,
}

/// Parses what [`super::read::read`] read from `file`. An SSP archive may lack the stop time or
/// step size, and an OSP system structure has no stop time; `overrides` supply them then.
pub(super) fn parse(
    source: &Source,
    file: &Path,
    overrides: &Overrides,
    files: &SystemFiles,
) -> Result<Parsed, SystemError> {
    match source {
        Source::Ssp(directory) => {
            let spec = ssp::parse(file, directory.path(), overrides)?;
            Ok(Parsed { spec, base: directory.path().to_path_buf() })
        }
        Source::Xml { text, folder } => {
            let spec = osp::parse(file, text, overrides)?;
            Ok(Parsed { spec, base: folder.clone() })
        }
        Source::Json(text) => match json::system_or_scenario(text).map_err(|error| parse_error(file, error))? {
            FileKind::Scenario => {
                let (spec, system_file) = scenario::resolve(text, file, files)?;
                Ok(Parsed { spec, base: folder_of(&system_file) })
            }
            _ => Ok(Parsed { spec: parse_spec(text, file)?, base: folder_of(file) }),
        },
    }
}

/// The system that runs `fmu` (opened from `file`) alone; its paths are kept as given (relative
/// to the working directory). The FMU's default experiment gives the times `overrides` leave out.
pub(super) fn parse_fmu(
    file: &Path,
    fmu: &Fmu,
    single: &SingleFmu,
    overrides: &Overrides,
) -> Result<Parsed, SystemError> {
    Ok(Parsed { spec: single::spec(file, fmu, single, overrides)?, base: PathBuf::new() })
}

/// The system file of an in-memory scenario with the scenario's settings, as if the scenario were
/// the file `file`; its system's paths stay relative to the system file.
pub(super) fn parse_scenario(
    spec: &scenario::ScenarioSpec,
    file: &Path,
    files: &SystemFiles,
) -> Result<Parsed, SystemError> {
    let (spec, system_file) = scenario::resolve_spec(spec, file, files)?;
    Ok(Parsed { spec, base: folder_of(&system_file) })
}

/// The folder of `file` (empty for a bare file name: the working directory).
fn folder_of(file: &Path) -> PathBuf {
    file.parent().unwrap_or_else(|| Path::new("")).to_path_buf()
}

/// Parses the JSON text of a system file.
pub fn parse_spec(text: &str, file: &Path) -> Result<SystemSpec, SystemError> {
    json::parse(text, FileKind::System).map_err(|error| parse_error(file, error))
}

/// The error of parsing `file`.
pub(super) fn parse_error(file: &Path, error: ParseError) -> SystemError {
    SystemError::Parse { file: file.to_path_buf(), error }
}
