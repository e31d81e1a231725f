//! Merging the case files of an output folder into one table, one row per planned case, written
//! as `results.csv` and `results.parquet`, with summary plots in `plots/`.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use super::execute::{read_case, Manifest, Status};
use super::parquet::results_parquet;
use super::plots::{write_plots, ImageFormat};
use super::{write_atomically, write_bytes_atomically, SweepError};

/// How many cases of the manifest are in each state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Collected {
    pub done: usize,
    pub failed: usize,
    pub pending: usize,
}

/// The files `collect` wrote and the cases' states.
#[derive(Debug, Clone, PartialEq)]
pub struct Collection {
    pub csv: PathBuf,
    pub parquet: PathBuf,
    /// The summary plots, in the order drawn (none without a format).
    pub plots: Vec<PathBuf>,
    pub counts: Collected,
}

/// The merged results: the parameter and metric names (as in the manifest) and one row per
/// planned case, in plan order.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    pub parameters: Vec<String>,
    pub metrics: Vec<String>,
    pub rows: Vec<Row>,
}

/// One case: values in the order of [`Table::parameters`] and [`Table::metrics`], `None` where
/// the case has no value (pending, failed, or no sample in a metric's window).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub id: String,
    /// 0-based index in the plan.
    pub index: usize,
    pub seed: u64,
    pub status: Status,
    pub parameters: Vec<Option<f64>>,
    pub metrics: Vec<Option<f64>>,
    /// Wall-clock time of the case's simulation (s); `None` for a pending case.
    pub wall_time: Option<f64>,
}

/// Reads `out/manifest.json` and every case file; writes `out/results.csv`,
/// `out/results.parquet` and, with a `plots` format, the summary plots into `out/plots/`; and
/// rewrites the manifest with the statuses found, since jobs that ran cases side by side may
/// each have written it before the others' cases were done.
pub fn collect(out: &Path, plots: Option<ImageFormat>) -> Result<Collection, SweepError> {
    let (mut manifest, table) = read_table(out)?;
    for (entry, row) in manifest.cases.iter_mut().zip(&table.rows) {
        entry.status = row.status;
    }
    let manifest_text = serde_json::to_string_pretty(&manifest).unwrap_or_default() + "\n";
    write_atomically(&out.join("manifest.json"), &manifest_text)?;
    let csv = out.join("results.csv");
    write_atomically(&csv, &results_csv(&table))?;
    let parquet = out.join("results.parquet");
    write_bytes_atomically(&parquet, &results_parquet(&table).map_err(|e| write_error(&parquet, e))?)?;
    let plots = match plots {
        Some(format) => write_plots(&out.join("plots"), &table, format)?,
        None => Vec::new(),
    };
    Ok(Collection { csv, parquet, plots, counts: table.counts() })
}

/// A write error of `file` from a library error.
pub(super) fn write_error(file: &Path, error: impl std::error::Error + Send + Sync + 'static) -> SweepError {
    SweepError::Write { file: file.to_path_buf(), source: std::io::Error::other(error) }
}

/// The manifest of `out` and the table of its cases.
pub fn read_table(out: &Path) -> Result<(Manifest, Table), SweepError> {
    let manifest_file = out.join("manifest.json");
    let text = std::fs::read_to_string(&manifest_file)
        .map_err(|source| SweepError::Read { file: manifest_file.clone(), source })?;
    let manifest: Manifest = serde_json::from_str(&text)
        .map_err(|e| SweepError::Invalid { file: manifest_file.clone(), message: e.to_string() })?;
    let rows = manifest.cases.iter().enumerate().map(|(index, entry)| {
        let record = read_case(out, &entry.id);
        let record = record.as_ref();
        Row {
            id: entry.id.clone(),
            index,
            seed: entry.seed,
            status: record.map_or(Status::Pending, |r| r.status),
            parameters: manifest.parameters.iter().map(|p| record.and_then(|r| r.parameters.get(p).copied())).collect(),
            metrics: manifest
                .metrics
                .iter()
                .map(|m| record.and_then(|r| r.metrics.get(m).copied().flatten()))
                .collect(),
            wall_time: record.map(|r| r.wall_time),
        }
    });
    let table =
        Table { parameters: manifest.parameters.clone(), metrics: manifest.metrics.clone(), rows: rows.collect() };
    Ok((manifest, table))
}

impl Table {
    fn counts(&self) -> Collected {
        let mut counts = Collected::default();
        for row in &self.rows {
            match row.status {
                Status::Done => counts.done += 1,
                Status::Failed => counts.failed += 1,
                Status::Pending => counts.pending += 1,
            }
        }
        counts
    }
}

/// The label of a status, as in the case files and the manifest.
pub fn status_label(status: Status) -> &'static str {
    match status {
        Status::Done => "done",
        Status::Failed => "failed",
        Status::Pending => "pending",
    }
}

/// `case,seed,status,<parameters>,<metrics>`; numbers in Rust's shortest round-trip form (read
/// back, they are the same bits), empty cells where a case has no value. No wall time: the file
/// is the same wherever and however fast the cases ran.
fn results_csv(table: &Table) -> String {
    let mut csv = ["case", "seed", "status"].map(String::from).join(",");
    for name in table.parameters.iter().chain(&table.metrics) {
        csv.push(',');
        csv.push_str(name);
    }
    csv.push('\n');
    for row in &table.rows {
        let _ = write!(csv, "{},{},{}", row.id, row.seed, status_label(row.status));
        for value in row.parameters.iter().chain(&row.metrics) {
            let _ = write!(csv, ",{}", value.map(|v| v.to_string()).unwrap_or_default());
        }
        csv.push('\n');
    }
    csv
}
