//! The thesis' campaign and the sweeps from Python: one run's scenario (what the Gymnasium
//! environment starts each episode from), the whole campaign as `crane-cosim campaign` runs it,
//! and a sweep study as `crane-cosim sweep run` and `sweep collect` run it.

use cosim_studies::sweep::collect::collect;
use cosim_studies::sweep::execute::{run_cases, Selection, SweepOptions};
use cosim_studies::sweep::plan::{check_case_count, MAX_CASES};
use cosim_studies::sweep::plots::ImageFormat;
use cosim_studies::sweep::study::Study;
use cosim_studies::StudyError as SweepError;
use crane_campaign::matrix::{parse_selection, runs, supported, tests, Init, RunSpec, Variant};
use crane_campaign::scale::Scale;
use crane_campaign::summary::{bands, changes, mean_reduction};
use crane_campaign::{figures, output, report, run_campaign, CampaignOptions};
use fmu_import::fmu::ExtractLimits;
use pyo3::prelude::*;

use crate::SimulationError;

/// One campaign run: its id (`"089-2"`), description, start values over the scale's system
/// (`(name, JSON text)`), stop time (s) and the time (s) its test proper starts (release,
/// control, ship motion).
type CampaignRun = (String, String, Vec<(String, String)>, f64, f64);

/// The campaign's run of `test` (1–104) in `variant` (1 truth, 2 sensors, 3 the EKF) at test
/// scale or, with `full_scale`, over the full-scale system.
#[pyfunction]
#[pyo3(signature = (test, variant, full_scale))]
pub fn campaign_run(test: u16, variant: u8, full_scale: bool) -> PyResult<CampaignRun> {
    let all = tests();
    let case = usize::from(test)
        .checked_sub(1)
        .and_then(|i| all.get(i))
        .ok_or_else(|| SimulationError::new_err(format!("test {test}: the campaign's tests are 1-{}", all.len())))?;
    let variant = Variant::from_number(variant).ok_or_else(|| {
        SimulationError::new_err(format!("variant {variant}: expected 1 (truth), 2 (sensors) or 3 (EKF)"))
    })?;
    let scale = if full_scale { Scale::Full } else { Scale::Test };
    let run = RunSpec { scale, ..RunSpec::new(*case, variant) };
    supported(&run).map_err(SimulationError::new_err)?;
    let scenario = run.scenario("system".into());
    let start = scenario.start.iter().map(|(name, value)| (name.clone(), value.to_string())).collect();
    let stop = scenario.stop_time.unwrap_or(run.init_time() + run.test_time());
    Ok((run.id(), scenario.description, start, stop, run.init_time()))
}

/// One row of Tables 7.1–7.3 in one variant: (table, metric, variant, the thesis' simulated mean
/// reduction %, ours %, pairs, the acceptance band of docs/acceptance.md or "", met).
type TableRow = (String, String, u8, Option<f64>, Option<f64>, usize, String, Option<bool>);

/// Runs the campaign's `tests` in `variants` over `system` into `output` as `crane-cosim
/// campaign` does (scenarios, metrics, report, figures; the lock released); returns metrics.csv's
/// text, the Tables 7.1–7.3 rows and the failed runs' errors.
#[pyfunction]
#[pyo3(signature = (tests, variants, system, output, jobs, start, keep_results, full_scale))]
#[allow(clippy::too_many_arguments)]
pub fn campaign(
    py: Python<'_>,
    tests: String,
    variants: Vec<u8>,
    system: std::path::PathBuf,
    output: std::path::PathBuf,
    jobs: usize,
    start: Vec<(String, String)>,
    keep_results: bool,
    full_scale: bool,
) -> PyResult<(String, Vec<TableRow>, Vec<String>)> {
    let scale = if full_scale { Scale::Full } else { Scale::Test };
    let numbers = parse_selection(&tests).map_err(SimulationError::new_err)?;
    let variants = variants
        .iter()
        .map(|&n| {
            Variant::from_number(n).ok_or_else(|| SimulationError::new_err(format!("variant {n}: expected 1, 2 or 3")))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let cases: Vec<_> = crane_campaign::matrix::tests().into_iter().filter(|t| numbers.contains(&t.number)).collect();
    let runs: Vec<RunSpec> =
        runs(&cases, &variants, Init::Held).into_iter().map(|run| RunSpec { scale, ..run }).collect();
    for run in &runs {
        supported(run).map_err(SimulationError::new_err)?;
    }
    let start = crate::start_values(start)?.into_iter().collect();
    let options = CampaignOptions {
        system,
        out: output.clone(),
        jobs,
        keep_results,
        progress: false,
        interrupt: None,
        start,
        limits: ExtractLimits::default(),
    };
    let outcome = py.detach(|| {
        let campaign = run_campaign(&runs, &options).map_err(|e| fmu_import::error_chain(&e))?;
        let written =
            figures::draw_all(&output, &campaign).and_then(|drawn| report::write_files(&output, &campaign, &drawn));
        output::seal(&output).map_err(|e| fmu_import::error_chain(&e))?;
        written?;
        let changes = changes(&campaign.results);
        let rows = bands(scale)
            .iter()
            .flat_map(|row| Variant::BOTH.into_iter().map(move |variant| (row, variant)))
            .map(|(row, variant)| {
                let index = usize::from(variant.number() - 1);
                let mean = mean_reduction(&changes, row.group, variant, row.metric);
                let (ours, pairs) = mean.map_or((None, 0), |(r, n)| (Some(r), n));
                let acceptance = row.acceptance[index];
                let met = acceptance.zip(ours).map(|(band, r)| band.holds(r));
                let band = acceptance.map_or_else(String::new, |band| band.describe());
                let (table, metric) = (row.group.title().to_string(), row.metric.name().to_string());
                (table, metric, variant.number(), row.simulation[index], ours, pairs, band, met)
            })
            .collect();
        let failures =
            campaign.failures().map(|f| format!("{}: {}", f.id, f.error.clone().unwrap_or_default())).collect();
        Ok::<_, String>((report::metrics_csv(&campaign.results), rows, failures))
    });
    outcome.map_err(|message| SimulationError::new_err(crate::flags::name_flags(&message)))
}

/// Runs every case of the sweep study `study` not done yet into `output` and collects the folder
/// (results.csv, results.parquet, plots as PNG with `plots`), as `crane-cosim sweep run` and
/// `sweep collect` do (the lock released); returns results.csv's text and (done, failed, skipped).
#[pyfunction]
#[pyo3(signature = (study, output, jobs, plots))]
pub fn sweep(
    py: Python<'_>,
    study: std::path::PathBuf,
    output: std::path::PathBuf,
    jobs: usize,
    plots: bool,
) -> PyResult<(String, (usize, usize, usize))> {
    let outcome = py.detach(|| {
        let chain = |e: SweepError| fmu_import::error_chain(&e);
        let loaded = Study::load(&study).map_err(chain)?;
        check_case_count(&loaded, &study, MAX_CASES).map_err(chain)?;
        let options = SweepOptions {
            out: output.clone(),
            jobs,
            progress: false,
            interrupt: None,
            limits: ExtractLimits::default(),
        };
        let count = run_cases(&study, &loaded, Selection::All, &options).map_err(chain)?;
        let collection = collect(&output, plots.then_some(ImageFormat::Png)).map_err(chain)?;
        let csv = std::fs::read_to_string(&collection.csv)
            .map_err(|e| format!("cannot read {}: {e}", collection.csv.display()))?;
        Ok::<_, String>((csv, (count.done, count.failed, count.skipped)))
    });
    outcome.map_err(|message| SimulationError::new_err(crate::flags::name_flags(&message)))
}
