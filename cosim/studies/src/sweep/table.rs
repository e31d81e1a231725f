//! The collected results of a study's output folder: one row per planned case, from the
//! manifest and the case files.

use std::path::Path;

use super::check_cases_folder;
use super::execute::{read_case, Manifest, Status, MANIFEST_FILE};
use crate::files::read_text;
use crate::StudyError;

/// How many cases of the manifest are in each state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Collected {
    /// Cases with results.
    pub done: usize,
    /// Cases whose run failed.
    pub failed: usize,
    /// Cases not run yet.
    pub pending: usize,
}

/// The merged results: the parameter and metric names (as in the manifest) and one row per
/// planned case, in plan order.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The swept parameters' names.
    pub parameters: Vec<String>,
    /// The metrics' names.
    pub metrics: Vec<String>,
    /// One per planned case, in plan order.
    pub rows: Vec<Row>,
}

/// One case: values in the order of [`Table::parameters`] and [`Table::metrics`], `None` where
/// the case has no value (pending, failed, or no sample in a metric's window).
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The case's id.
    pub id: String,
    /// 0-based index in the plan.
    pub index: usize,
    /// The case's noise seed.
    pub seed: u64,
    /// Whether it is pending, done or failed.
    pub status: Status,
    /// Its parameter values.
    pub parameters: Vec<Option<f64>>,
    /// Its metric values.
    pub metrics: Vec<Option<f64>>,
    /// Wall-clock time of the case's simulation (s); `None` for a pending case.
    pub wall_time: Option<f64>,
}

/// The manifest of `out` and the table of its cases.
pub fn read_table(out: &Path) -> Result<(Manifest, Table), StudyError> {
    let manifest_file = out.join(MANIFEST_FILE);
    check_cases_folder(&out.join("cases"))?;
    let text = read_text(&manifest_file)?;
    let manifest: Manifest = serde_json::from_str(&text)
        .map_err(|e| StudyError::Invalid { file: manifest_file.clone(), message: e.to_string() })?;
    let mut rows = Vec::with_capacity(manifest.cases.len());
    for (index, entry) in manifest.cases.iter().enumerate() {
        let record = read_case(out, &entry.id)?;
        let record = record.as_ref();
        rows.push(Row {
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
        });
    }
    let table = Table { parameters: manifest.parameters.clone(), metrics: manifest.metrics.clone(), rows };
    Ok((manifest, table))
}

impl Table {
    /// How many rows are in each state.
    pub fn counts(&self) -> Collected {
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
