//! The thesis' campaign (tests 001–104 in their feedback variants) at either scale: its runs
//! chosen, run in parallel, evaluated, reported and judged against docs/acceptance.md.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use cosim_engine::interrupt::Interrupt;
use cosim_engine::system::scenario::ScenarioSpec;
use cosim_engine::system::{json, FileKind};
use crane_campaign::matrix::{self, RunSpec, Variant};
pub use crane_campaign::matrix::{AttitudeFilter, Init};
use crane_campaign::output::OutputError;
use crane_campaign::results::Campaign;
use crane_campaign::summary::{bands, changes, mean_reduction, verdicts};
use crane_campaign::{figures, output, report, run_campaign, CampaignError, CampaignOptions};
pub use crane_names::Scale;
use fmu_import::fmu::ExtractLimits;
use serde_json::Value;

use crate::notice::{announce_system, Notice};

/// What a campaign is asked for.
#[derive(Debug, Clone)]
pub struct CampaignRequest {
    /// The crane: the thesis' test-scale rig, or the full-scale crane with the matrix mapped to it.
    pub scale: Scale,
    /// The closed-loop system file the scenarios start from (none: [`default_system`] of the
    /// scale's file).
    pub system: Option<PathBuf>,
    /// The tests, as "1-104" or "20,60,84,92".
    pub tests: String,
    /// Feedback variants: 1 truth, 2 sensors, 3 sensors and the controller's EKF.
    pub variants: Vec<u8>,
    /// The attitude estimator of the sensor variants.
    pub attitude_filter: AttitudeFilter,
    /// How the runs start: held for 10 s with aligned filters, or as the thesis' simulations did.
    pub init: Init,
    /// Start values every run gets on top of the system file's, after those of `start_file`.
    pub start: Vec<(String, Value)>,
    /// A scenario file whose start values every run gets (e.g. tuning's best.json).
    pub start_file: Option<PathBuf>,
    /// The full-scale crane's description, a catalogue name or a file (docs/crane-description.md):
    /// both the crane and its controller get it, after `start_file`'s start values and before
    /// `start`. `None`: the system file's crane.
    pub crane: Option<String>,
    /// Worker threads (0: one per core).
    pub jobs: usize,
    /// The output folder.
    pub output: PathBuf,
    /// Keep every run's results CSV.
    pub keep_results: bool,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Stops the campaign between steps when requested (signals).
    pub interrupt: Option<Interrupt>,
    /// What each FMU archive may unpack to.
    pub limits: ExtractLimits,
}

impl CampaignRequest {
    /// The whole test-scale campaign into `output`, both variants, with the defaults of the
    /// command line.
    pub fn new(output: PathBuf) -> CampaignRequest {
        CampaignRequest {
            scale: Scale::Test,
            system: None,
            tests: "1-104".into(),
            variants: vec![1, 2],
            attitude_filter: AttitudeFilter::Complementary,
            init: Init::Held,
            start: Vec::new(),
            start_file: None,
            crane: None,
            jobs: 0,
            output,
            keep_results: false,
            progress: false,
            interrupt: None,
            limits: ExtractLimits::default(),
        }
    }
}

/// Why a campaign could not run or be written.
#[derive(Debug, thiserror::Error)]
pub enum CampaignFailure {
    /// The request names something that does not exist (a test, a variant, a file).
    #[error("{0}")]
    Request(String),
    #[error(transparent)]
    Campaign(#[from] CampaignError),
    #[error(transparent)]
    Output(#[from] OutputError),
    /// A figure or the report could not be written.
    #[error("{0}")]
    Files(String),
}

/// A campaign's runs chosen and its system found, not yet run.
#[derive(Debug)]
pub struct PreparedCampaign {
    /// The runs chosen, in matrix order.
    pub runs: Vec<RunSpec>,
    /// The crane they run at.
    pub scale: Scale,
    options: CampaignOptions,
}

/// Chooses the request's runs, finds its system file and reads its start values.
pub fn prepare(request: &CampaignRequest) -> Result<PreparedCampaign, CampaignFailure> {
    let numbers = matrix::parse_selection(&request.tests).map_err(CampaignFailure::Request)?;
    let variants = request
        .variants
        .iter()
        .map(|&n| {
            Variant::from_number(n).ok_or_else(|| {
                CampaignFailure::Request(format!(
                    "variant {n}: expected 1 (truth), 2 (sensors) or 3 (sensors and the EKF)"
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let tests: Vec<_> = matrix::tests().into_iter().filter(|t| numbers.contains(&t.number)).collect();
    let (scale, attitude) = (request.scale, request.attitude_filter);
    // The attitude filter is the sensor variants' (the truth variant reads no filter).
    let runs: Vec<_> = matrix::runs(&tests, &variants, request.init)
        .into_iter()
        .map(|run| if run.variant.sensors() { RunSpec { attitude, ..run } } else { run })
        .map(|run| RunSpec { scale, ..run })
        .collect();
    for run in &runs {
        matrix::supported(run).map_err(CampaignFailure::Request)?;
    }
    let system = match &request.system {
        Some(file) => file.clone(),
        None => default_system(scale.system_file()).map_err(CampaignFailure::Request)?,
    };
    let options = CampaignOptions {
        system,
        out: request.output.clone(),
        jobs: request.jobs,
        keep_results: request.keep_results,
        progress: request.progress,
        interrupt: request.interrupt.clone(),
        start: start_values(request)?,
        limits: request.limits,
    };
    Ok(PreparedCampaign { runs, scale, options })
}

impl PreparedCampaign {
    /// The system file and FMUs the runs start from, to show before they start.
    pub fn notices(&self) -> Vec<Notice> {
        announce_system(&self.options.system, self.options.limits).into_iter().collect()
    }

    /// Runs, evaluates and writes the campaign: scenarios, metrics, report and figures. A run
    /// that fails does not stop it ([`CampaignOutcome::failures`]).
    pub fn run(self) -> Result<CampaignOutcome, CampaignFailure> {
        let out = &self.options.out;
        let campaign = run_campaign(&self.runs, &self.options)?;
        let written = figures::draw_all(out, &campaign)
            .and_then(|drawn| report::write_files(out, &campaign, &drawn))
            .map_err(CampaignFailure::Files);
        // Listed also when a figure or the report failed: the next campaign may then clear them.
        output::seal(out)?;
        written?;
        Ok(CampaignOutcome { campaign, scale: self.scale, report: out.join("report.md") })
    }
}

/// What a campaign produced.
#[derive(Debug)]
pub struct CampaignOutcome {
    /// Every run's result and the detailed evaluations.
    pub campaign: Campaign,
    /// The crane it ran at.
    pub scale: Scale,
    /// The Markdown report.
    pub report: PathBuf,
}

/// One row of Tables 7.1–7.3 in one variant, beside the thesis' simulated mean.
#[derive(Debug, Clone, PartialEq)]
pub struct TableRow {
    /// The table's group ("Table 7.1 …") and the metric's name.
    pub table: String,
    /// The metric's name.
    pub metric: String,
    /// The feedback variant (1, 2 or 3).
    pub variant: u8,
    /// The thesis' simulated mean reduction (%).
    pub thesis: Option<f64>,
    /// Ours (%), over `pairs` test pairs; none without a pair.
    pub reduction: Option<f64>,
    /// Test pairs the reduction averages.
    pub pairs: usize,
    /// The acceptance band of docs/acceptance.md ("" where none), and whether it is met.
    pub band: String,
    /// Whether the reduction is within the band; none without a band or a reduction.
    pub met: Option<bool>,
}

impl CampaignOutcome {
    /// The text of metrics.csv: one row per run.
    pub fn metrics_csv(&self) -> String {
        report::metrics_csv(&self.campaign.results)
    }

    /// `"id: error"` of each run that failed.
    pub fn failures(&self) -> Vec<String> {
        self.campaign.failures().map(|f| format!("{}: {}", f.id, f.error.clone().unwrap_or_default())).collect()
    }

    /// An error when any run failed, pointing to the report.
    pub fn all_completed(&self) -> Result<(), String> {
        match self.campaign.failures().count() {
            0 => Ok(()),
            failed => Err(format!(
                "{failed} of {} runs failed (see above and {})",
                self.campaign.results.len(),
                self.report.display()
            )),
        }
    }

    /// Every row of Tables 7.1–7.3 in both variants, with or without test pairs.
    pub fn tables(&self) -> Vec<TableRow> {
        let changes = changes(&self.campaign.results);
        bands(self.scale)
            .iter()
            .flat_map(|row| Variant::BOTH.into_iter().map(move |variant| (row, variant)))
            .map(|(row, variant)| {
                let index = usize::from(variant.number() - 1);
                let (reduction, pairs) =
                    mean_reduction(&changes, row.group, variant, row.metric).map_or((None, 0), |(r, n)| (Some(r), n));
                let acceptance = row.acceptance[index];
                TableRow {
                    table: row.group.title().to_string(),
                    metric: row.metric.name().to_string(),
                    variant: variant.number(),
                    thesis: row.simulation[index],
                    reduction,
                    pairs,
                    band: acceptance.map_or_else(String::new, |band| band.describe()),
                    met: acceptance.zip(reduction).map(|(band, r)| band.holds(r)),
                }
            })
            .collect()
    }

    /// One error listing every band of docs/acceptance.md the campaign misses, or saying that
    /// the selection judged none (a check that holds nothing must not pass).
    pub fn check(&self) -> Result<(), String> {
        let verdicts = verdicts(&changes(&self.campaign.results), self.scale);
        if verdicts.iter().all(|v| v.met().is_none()) {
            return Err(format!(
                "CampaignRequest::check: no acceptance band of docs/acceptance.md had data: the selection has no \
                 test pair for any (see {}); select both runs of a pair, e.g. CampaignRequest::tests[\"20,60\"]",
                self.report.display()
            ));
        }
        let missed: Vec<String> = verdicts
            .iter()
            .filter(|v| v.met() == Some(false))
            .map(|v| {
                let (reduction, pairs) = v.reduction.unwrap_or_default();
                format!(
                    "{}, {} ({}): {reduction:.1} % over {pairs} pairs, band {}",
                    v.row.group.title(),
                    v.row.metric.info().title,
                    v.variant.number(),
                    v.acceptance.describe()
                )
            })
            .collect();
        if missed.is_empty() {
            return Ok(());
        }
        Err(format!(
            "{} acceptance band(s) of docs/acceptance.md not met (see {}):\n  {}",
            missed.len(),
            self.report.display(),
            missed.join("\n  ")
        ))
    }
}

/// One run of the campaign as a scenario over its scale's system file: what an environment that
/// replays a campaign test (Python's Gymnasium environment) starts each episode from.
#[derive(Debug, Clone)]
pub struct RunScenario {
    /// `"089-2"`.
    pub id: String,
    /// The run's scenario description.
    pub description: String,
    /// Start values over the scale's system file.
    pub start: BTreeMap<String, Value>,
    /// The stop time (s) and when the test proper starts (s): release, control, ship motion.
    pub stop_time: f64,
    /// When the test proper starts (s).
    pub test_start: f64,
}

/// The campaign's run of `test` (1–104) in `variant` (1 truth, 2 sensors, 3 the EKF) at `scale`.
pub fn run_scenario(test: u16, variant: u8, scale: Scale) -> Result<RunScenario, String> {
    let all = matrix::tests();
    let case = usize::from(test)
        .checked_sub(1)
        .and_then(|i| all.get(i))
        .ok_or_else(|| format!("test {test}: the campaign's tests are 1-{}", all.len()))?;
    let variant = Variant::from_number(variant)
        .ok_or_else(|| format!("variant {variant}: expected 1 (truth), 2 (sensors) or 3 (sensors and the EKF)"))?;
    let run = RunSpec { scale, ..RunSpec::new(*case, variant) };
    matrix::supported(&run)?;
    let scenario = run.scenario("system".into());
    Ok(RunScenario {
        id: run.id(),
        description: scenario.description,
        start: scenario.start,
        stop_time: scenario.stop_time.unwrap_or(run.init_time() + run.test_time()),
        test_start: run.init_time(),
    })
}

/// The extra start values: the start file scenario's, then the request's.
fn start_values(request: &CampaignRequest) -> Result<BTreeMap<String, Value>, CampaignFailure> {
    let mut start = BTreeMap::new();
    if let Some(file) = &request.start_file {
        start.extend(scenario_start(file).map_err(CampaignFailure::Request)?);
    }
    if let Some(crane) = &request.crane {
        start.extend(crane_starts(request.scale, crane).map_err(CampaignFailure::Request)?);
    }
    start.extend(request.start.iter().cloned());
    Ok(start)
}

/// The start values of a scenario file.
fn scenario_start(file: &Path) -> Result<BTreeMap<String, Value>, String> {
    read_scenario(file, "CampaignRequest::start_file").map(|scenario| scenario.start)
}

/// The scenario file `file`, read like every input (never blocking on a FIFO); an error names
/// the file as the setting `setting` that gave it.
pub(crate) fn read_scenario(file: &Path, setting: &str) -> Result<ScenarioSpec, String> {
    let text = fmu_import::file::read_regular_text(file, SCENARIO_SIZE_LIMIT)
        .map_err(|e| format!("cannot read {setting} {}: {e}", file.display()))?;
    json::parse(&text, FileKind::Scenario)
        .map_err(|e| format!("{setting} {}:{}:{}: {e}", file.display(), e.line, e.column))
}

/// Larger than any scenario file (they are a few kilobytes).
pub const SCENARIO_SIZE_LIMIT: u64 = 64 << 20;

/// The system file `name` of `systems/`, looked for in this order: the working directory's
/// `systems/` (a checkout or a copy of one, whose own FMUs its system files name), the source
/// tree this was built from (`cargo build`, `cargo install --path`), and
/// `share/crane-cosim/systems/` next to the running binary's `bin/` folder (an installed package).
pub fn default_system(name: &str) -> Result<PathBuf, String> {
    let mut candidates = vec![Path::new("systems").join(name)];
    candidates.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("../../systems").join(name));
    if let Some(prefix) = std::env::current_exe().ok().and_then(|exe| Some(exe.parent()?.parent()?.to_path_buf())) {
        candidates.push(prefix.join("share/crane-cosim/systems").join(name));
    }
    candidates.iter().find(|c| c.is_file()).cloned().ok_or_else(|| {
        let looked: Vec<String> = candidates.iter().map(|c| c.display().to_string()).collect();
        format!("no closed-loop system file in {}: give one with CampaignRequest::system", looked.join(" or "))
    })
}

/// The start values that give the full-scale crane and its controller the crane description
/// `spec` (docs/crane-description.md): a catalogue name as it is, a file's path made absolute
/// (the FMUs run from wherever the runs start). Refused at test scale, whose crane has no
/// description.
pub fn crane_starts(scale: Scale, spec: &str) -> Result<Vec<(String, Value)>, String> {
    if scale.is_test() {
        return Err(
            "a crane description (CampaignRequest::crane) is for the full-scale crane: add CampaignRequest::scale = full"
                .into(),
        );
    }
    let path = Path::new(spec);
    let value = if path.is_file() {
        std::path::absolute(path).map_err(|e| format!("crane description {spec}: {e}"))?.display().to_string()
    } else {
        spec.to_string()
    };
    let names = scale.names();
    Ok([names.crane.0, names.controller.0]
        .map(|instance| (format!("{instance}.crane"), Value::from(value.clone())))
        .into())
}
