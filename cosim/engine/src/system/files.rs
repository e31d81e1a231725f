//! What systems built from the same files share: opened FMUs and parsed system files.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

use fmu_import::fmu::{ExtractLimits, Fmu, FmuError};

use super::read::read_system_text;
use super::{parse_spec, SystemError, SystemSpec};

/// Opened FMUs and parsed system files by path, so that many systems built from the same files
/// (a campaign's runs, on any number of threads) extract, parse and load each only once; every
/// system still instantiates its own instances.
///
/// An FMU opened here stays extracted, and its library loaded once an instance needed it, until
/// this cache and every system built with it are dropped. Failures are not kept: the next request
/// tries again and reports its own error.
///
/// Every archive it opens (FMUs, SSP archives) must keep within its [`ExtractLimits`]; the
/// default is [`ExtractLimits::default`].
#[derive(Debug, Default)]
pub struct SystemFiles {
    limits: ExtractLimits,
    fmus: Mutex<HashMap<PathBuf, Fmu>>,
    specs: Mutex<HashMap<PathBuf, SystemSpec>>,
}

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

impl SystemFiles {
    /// An empty cache whose archives must keep within `limits`.
    pub fn new(limits: ExtractLimits) -> Self {
        Self { limits, ..Self::default() }
    }

    /// What an archive opened through this cache may unpack to.
    pub fn limits(&self) -> &ExtractLimits {
        &self.limits
    }

    /// The FMU at `path`, opened on first request ([`Fmu::open`] within [`SystemFiles::limits`]).
    pub fn fmu(&self, path: &Path) -> Result<Fmu, FmuError> {
        // Held while opening, so that threads asking for the same FMU at once extract it once.
        let mut fmus = lock(&self.fmus);
        if let Some(fmu) = fmus.get(path) {
            return Ok(fmu.clone());
        }
        let fmu = Fmu::open(path, &self.limits)?;
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
