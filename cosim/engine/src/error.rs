//! The crate-level error and error-chain formatting.

use std::path::PathBuf;

use fmu_import::fmu::FmuError;

use crate::execution::RunError;
use crate::observer::ObserverError;
use crate::system::SystemError;
use crate::workload::WorkloadTooLarge;

/// Anything that can stop a command.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    #[error(transparent)]
    System(#[from] SystemError),
    #[error(transparent)]
    Run(#[from] RunError),
    #[error(transparent)]
    Fmu(#[from] FmuError),
    #[error(transparent)]
    Output(#[from] ObserverError),
    #[error(transparent)]
    Workload(#[from] WorkloadTooLarge),
    #[error("cannot write the run summary {}", file.display())]
    Summary {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
}
