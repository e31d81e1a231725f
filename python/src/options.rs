//! The options the package's functions pass to the extension, each a dictionary of named items
//! (built by python/crane_cosim/_options.py) read into a named struct, and the request it makes.

use std::path::PathBuf;

use crane_app::campaign::{AttitudeFilter, CampaignRequest, Init, Scale};
use crane_app::run::{Grid, RunRequest};
use crane_app::sweep::SweepRequest;
use crane_app::tune::TuneRequest;
use pyo3::prelude::*;

use crate::wording::error;

/// `run`'s and `Simulation`'s options: start values as `(name, JSON text)`.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct RunOptions {
    start: Vec<(String, String)>,
    stop_time: Option<f64>,
    step_size: Option<f64>,
    record_interval: Option<f64>,
    algorithm: Option<String>,
    record: Vec<String>,
    inputs: Vec<PathBuf>,
    force: bool,
}

impl RunOptions {
    /// The run these options ask for on `system`.
    pub fn request(self, system: PathBuf) -> PyResult<RunRequest> {
        let algorithm = self
            .algorithm
            .map(|name| name.parse().map_err(|e| error(format!("algorithm {name:?}: {e}"))))
            .transpose()?;
        Ok(RunRequest {
            start: start_values(self.start)?,
            grid: Grid {
                stop_time: self.stop_time,
                step_size: self.step_size,
                algorithm,
                extrapolate_inputs: false,
                record_interval: self.record_interval,
            },
            record: self.record,
            inputs: self.inputs,
            force: self.force,
            ..RunRequest::new(&system)
        })
    }
}

/// `campaign`'s options, every option of `crane-cosim campaign`.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct CampaignOptions {
    tests: String,
    variants: Vec<u8>,
    system: Option<PathBuf>,
    output: PathBuf,
    jobs: usize,
    start: Vec<(String, String)>,
    start_file: Option<PathBuf>,
    crane: Option<String>,
    keep_results: bool,
    full_scale: bool,
    attitude_filter: String,
    thesis_init: bool,
    pub check: bool,
}

impl CampaignOptions {
    pub fn request(self) -> PyResult<CampaignRequest> {
        let attitude_filter = match self.attitude_filter.as_str() {
            "complementary" => AttitudeFilter::Complementary,
            "madgwick" => AttitudeFilter::Madgwick,
            other => {
                return Err(error(format!("attitude_filter {other:?}: expected \"complementary\" or \"madgwick\"")))
            }
        };
        Ok(CampaignRequest {
            scale: if self.full_scale { Scale::Full } else { Scale::Test },
            system: self.system,
            tests: self.tests,
            variants: self.variants,
            attitude_filter,
            init: if self.thesis_init { Init::Thesis } else { Init::Held },
            start: start_values(self.start)?,
            start_file: self.start_file,
            crane: self.crane,
            jobs: self.jobs,
            keep_results: self.keep_results,
            ..CampaignRequest::new(self.output)
        })
    }
}

/// `sweep`'s options.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct SweepOptions {
    study: PathBuf,
    output: PathBuf,
    jobs: usize,
    max_cases: usize,
    pub plots: bool,
}

impl SweepOptions {
    pub fn request(&self) -> SweepRequest {
        SweepRequest {
            jobs: self.jobs,
            max_cases: self.max_cases,
            ..SweepRequest::new(self.study.clone(), self.output.clone())
        }
    }
}

/// `tune`'s options.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct TuneOptions {
    tuning: PathBuf,
    output: PathBuf,
    jobs: usize,
}

impl TuneOptions {
    pub fn request(&self) -> TuneRequest {
        TuneRequest { jobs: self.jobs, ..TuneRequest::new(self.tuning.clone(), self.output.clone()) }
    }
}

/// Start values given as `(name, JSON text)`, parsed.
fn start_values(start: Vec<(String, String)>) -> PyResult<Vec<(String, serde_json::Value)>> {
    start
        .into_iter()
        .map(|(name, json)| {
            serde_json::from_str(&json)
                .map(|value| (name.clone(), value))
                .map_err(|e| error(format!("start value of {name}: {e}")))
        })
        .collect()
}
