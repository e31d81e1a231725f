//! Tuning controller parameters with CMA-ES over campaign runs (docs/tuning.md): the whole
//! search, or one step of it for an external scheduler.

use std::path::PathBuf;

use cosim_engine::interrupt::Interrupt;
use crane_names::Scale;
use crane_tune::{tune as run_tuning, TuneOptions};
use fmu_import::fmu::ExtractLimits;

pub use crane_tune::{Step, StepResult, TuneError};

use crate::campaign::default_system;

/// What a tuning is asked for.
#[derive(Debug, Clone)]
pub struct TuneRequest {
    /// The tuning file (JSON).
    pub tuning: PathBuf,
    /// The output folder: new, empty, or one this tuning wrote (it resumes).
    pub output: PathBuf,
    /// Worker threads (0: one per core).
    pub jobs: usize,
    /// The whole search, the next generation's candidates, or one candidate.
    pub step: Step,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Stops the runs between steps when requested (signals).
    pub interrupt: Option<Interrupt>,
    /// What each FMU archive may unpack to.
    pub limits: ExtractLimits,
}

impl TuneRequest {
    /// The whole search of `tuning` into `output`, with the defaults of the command line.
    pub fn new(tuning: PathBuf, output: PathBuf) -> TuneRequest {
        TuneRequest {
            tuning,
            output,
            jobs: 0,
            step: Step::All,
            progress: false,
            interrupt: None,
            limits: ExtractLimits::default(),
        }
    }
}

/// Runs the requested step of the tuning; a tuning file that names no system tunes the
/// test-scale closed loop ([`default_system`]).
pub fn tune(request: &TuneRequest) -> Result<StepResult, TuneError> {
    let default_system = default_system(Scale::Test.system_file()).map_err(TuneError::Run)?;
    let options = TuneOptions {
        tuning_file: request.tuning.clone(),
        default_system,
        out: request.output.clone(),
        jobs: request.jobs,
        progress: request.progress,
        interrupt: request.interrupt.clone(),
        limits: request.limits,
    };
    run_tuning(&options, &request.step)
}
