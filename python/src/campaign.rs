//! The thesis' campaign, sweeps and tuning from Python, through the front door: one run's
//! scenario (what the Gymnasium environment starts each episode from), the whole campaign, a
//! sweep study run and collected, and a tuning.

use crane_app::campaign::{prepare, run_scenario, Scale, TableRow};
use crane_app::sweep::{collect, ImageFormat};
use crane_app::tune::StepResult;
use pyo3::prelude::*;

use crate::options::{CampaignOptions, SweepOptions, TuneOptions};
use crate::wording::{chained, error};

/// One campaign run: its id (`"089-2"`), description, start values over the scale's system
/// (`(name, JSON text)`), stop time (s) and the time (s) its test proper starts (release,
/// control, ship motion).
type CampaignRun = (String, String, Vec<(String, String)>, f64, f64);

/// The campaign's run of `test` (1–104) in `variant` (1 truth, 2 sensors, 3 the EKF) at test
/// scale or, with `full_scale`, over the full-scale system.
#[pyfunction]
#[pyo3(signature = (test, variant, full_scale))]
pub fn campaign_run(test: u16, variant: u8, full_scale: bool) -> PyResult<CampaignRun> {
    let scale = if full_scale { Scale::Full } else { Scale::Test };
    let run = run_scenario(test, variant, scale).map_err(error)?;
    let start = run.start.iter().map(|(name, value)| (name.clone(), value.to_string())).collect();
    Ok((run.id, run.description, start, run.stop_time, run.test_start))
}

/// One row of Tables 7.1–7.3 in one variant: (table, metric, variant, the thesis' simulated mean
/// reduction %, ours %, pairs, the acceptance band of docs/acceptance.md or "", met).
type Row = (String, String, u8, Option<f64>, Option<f64>, usize, String, Option<bool>);

fn row(row: TableRow) -> Row {
    (row.table, row.metric, row.variant, row.thesis, row.reduction, row.pairs, row.band, row.met)
}

/// Runs the campaign as `crane-cosim campaign` does (scenarios, metrics, report, figures; the
/// lock released); returns metrics.csv's text, the Tables 7.1–7.3 rows and the failed runs'
/// errors. With `check`, a band of docs/acceptance.md not met raises after the files are written.
#[pyfunction]
pub fn campaign(py: Python<'_>, options: CampaignOptions) -> PyResult<(String, Vec<Row>, Vec<String>)> {
    let check = options.check;
    let request = options.request()?;
    let outcome = py.detach(|| prepare(&request)?.run()).map_err(|e| chained(&e))?;
    if check {
        outcome.check().map_err(error)?;
    }
    let rows = outcome.tables().into_iter().map(row).collect();
    Ok((outcome.metrics_csv(), rows, outcome.failures()))
}

/// Runs every case of a sweep study not done yet and collects the folder (results.csv,
/// results.parquet, PNG plots with `plots`), as `crane-cosim sweep run` and `sweep collect` do
/// (the lock released); returns results.csv's text and (done, failed, skipped).
#[pyfunction]
pub fn sweep(py: Python<'_>, options: SweepOptions) -> PyResult<(String, (usize, usize, usize))> {
    let request = options.request();
    let plots = options.plots.then_some(ImageFormat::Png);
    let (count, collection) = py
        .detach(|| {
            let count = crane_app::sweep::prepare(&request)?.run()?;
            Ok::<_, crane_app::sweep::StudyError>((count, collect(&request.output, plots)?))
        })
        .map_err(|e| chained(&e))?;
    let csv = std::fs::read_to_string(&collection.csv)
        .map_err(|e| error(format!("cannot read {}: {e}", collection.csv.display())))?;
    Ok((csv, (count.done, count.failed, count.skipped)))
}

/// Runs a whole tuning (or resumes it) as `crane-cosim tune` does (the lock released); returns
/// the report's file and the best candidate's id.
#[pyfunction]
pub fn tune(py: Python<'_>, options: TuneOptions) -> PyResult<(String, String)> {
    let request = options.request();
    let result = py.detach(|| crane_app::tune::tune(&request)).map_err(|e| chained(&e))?;
    match result {
        StepResult::Done(summary) => Ok((request.output.join("report.md").display().to_string(), summary.best.clone())),
        _ => Err(error("the tuning stopped before its end")),
    }
}
