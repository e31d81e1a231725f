//! What systems built from the same files share: opened FMUs and parsed system files.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use fmu_import::fmu::{Fmu, FmuError};

use super::{parse_spec, read_system_text, SystemError, SystemSpec};

/// Opened FMUs and parsed system files by path, so that many systems built from the same files
/// (a campaign's runs, on any number of threads) extract, parse and load each only once; every
/// system still instantiates its own instances.
///
/// An FMU opened here stays extracted, and its library loaded once an instance needed it, until
/// this cache and every system built with it are dropped. Failures are not kept: the next request
/// tries again and reports its own error.
#[derive(Debug, Default)]
pub struct SystemFiles {
    fmus: Mutex<HashMap<PathBuf, Fmu>>,
    specs: Mutex<HashMap<PathBuf, SystemSpec>>,
}

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

impl SystemFiles {
    /// The FMU at `path`, opened on first request ([`Fmu::open`]).
    pub fn fmu(&self, path: &Path) -> Result<Fmu, FmuError> {
        // Held while opening, so that threads asking for the same FMU at once extract it once.
        let mut fmus = lock(&self.fmus);
        if let Some(fmu) = fmus.get(path) {
            return Ok(fmu.clone());
        }
        let fmu = Fmu::open(path)?;
        fmus.insert(path.to_path_buf(), fmu.clone());
        Ok(fmu)
    }

    /// The system file `file`, read and parsed on first request.
    pub fn spec(&self, file: &Path) -> Result<SystemSpec, SystemError> {
        if let Some(spec) = lock(&self.specs).get(file) {
            return Ok(spec.clone());
        }
        let text = read_system_text(file).map_err(|source| SystemError::Read { file: file.to_path_buf(), source })?;
        let spec = parse_spec(&text, file)?;
        lock(&self.specs).insert(file.to_path_buf(), spec.clone());
        Ok(spec)
    }
}
