//! A parameter study over a scenario (docs/sweeps.md): its cases planned, run by case, shard or
//! all, and collected into one table with plots.

use std::path::{Path, PathBuf};

use cosim_engine::interrupt::Interrupt;
use cosim_studies::sweep::execute::{run_cases, SweepOptions};
use cosim_studies::sweep::plan::{check_case_count, plan};
use cosim_studies::sweep::study::Study;
use fmu_import::fmu::ExtractLimits;

pub use cosim_studies::sweep::collect::{collect, Collection};
pub use cosim_studies::sweep::execute::{RunCount, Selection};
pub use cosim_studies::sweep::plan::MAX_CASES;
pub use cosim_studies::sweep::plots::ImageFormat;
pub use cosim_studies::StudyError;

use crate::campaign::read_scenario;
use crate::notice::{announce_system, Notice};

/// What a sweep run is asked for.
#[derive(Debug, Clone)]
pub struct SweepRequest {
    /// The study file (JSON).
    pub study: PathBuf,
    /// The output folder.
    pub output: PathBuf,
    /// Which cases of the plan to run.
    pub selection: Selection,
    /// Worker threads (0: one per core).
    pub jobs: usize,
    /// Refuse a study planning more cases than this.
    pub max_cases: usize,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Stops the cases between steps when requested (signals).
    pub interrupt: Option<Interrupt>,
    /// What each FMU archive may unpack to.
    pub limits: ExtractLimits,
}

impl SweepRequest {
    /// Every case of `study` into `output`, with the defaults of the command line.
    pub fn new(study: PathBuf, output: PathBuf) -> SweepRequest {
        SweepRequest {
            study,
            output,
            selection: Selection::All,
            jobs: 0,
            max_cases: MAX_CASES,
            progress: false,
            interrupt: None,
            limits: ExtractLimits::default(),
        }
    }
}

/// A study read and its size checked, not yet run.
#[derive(Debug)]
pub struct PreparedSweep {
    request: SweepRequest,
    study: Study,
}

/// Reads the request's study and refuses one that plans more cases than allowed.
pub fn prepare(request: &SweepRequest) -> Result<PreparedSweep, StudyError> {
    let study = load_study(&request.study, request.max_cases)?;
    Ok(PreparedSweep { request: request.clone(), study })
}

impl PreparedSweep {
    /// The system file and FMUs the cases start from, to show before they start.
    pub fn notices(&self) -> Vec<Notice> {
        let scenario = self.study.scenario_path(&self.request.study);
        system_of_scenario(&scenario)
            .and_then(|system| announce_system(&system, self.request.limits))
            .into_iter()
            .collect()
    }

    /// Runs the selected cases not done yet and rewrites the manifest.
    pub fn run(self) -> Result<RunCount, StudyError> {
        let request = &self.request;
        let options = SweepOptions {
            out: request.output.clone(),
            jobs: request.jobs,
            progress: request.progress,
            interrupt: request.interrupt.clone(),
            limits: request.limits,
        };
        run_cases(&request.study, &self.study, request.selection, &options)
    }
}

/// The numbered cases of the study in `file` as CSV rows `case,seed,<parameters>`, numbers in
/// their shortest round-trip form.
pub fn plan_csv(file: &Path, max_cases: usize) -> Result<String, StudyError> {
    let study = load_study(file, max_cases)?;
    let mut header = vec!["case".to_string(), "seed".to_string()];
    header.extend(study.parameters.iter().map(|p| p.name.clone()));
    let mut text = header.join(",") + "\n";
    for case in plan(&study)? {
        let mut row = vec![case.id.clone(), case.seed.to_string()];
        row.extend(case.values.iter().map(|(_, v)| format!("{v:?}")));
        text += &(row.join(",") + "\n");
    }
    Ok(text)
}

fn load_study(file: &Path, max_cases: usize) -> Result<Study, StudyError> {
    let study = Study::load(file)?;
    check_case_count(&study, file, max_cases)?;
    Ok(study)
}

/// The system file of the scenario `scenario` (its `system`, relative to the scenario), if the
/// scenario is a regular file that parses; one that does not is left to the run to report.
fn system_of_scenario(scenario: &Path) -> Option<PathBuf> {
    let spec = read_scenario(scenario, "scenario").ok()?;
    Some(scenario.parent().unwrap_or_else(|| Path::new("")).join(spec.system))
}
