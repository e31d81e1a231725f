//! Merging the case files of an output folder into `results.csv`, one row per planned case.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use super::execute::{read_case, Manifest, Status};
use super::{write_atomically, SweepError};

/// How many cases of the manifest are in each state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Collected {
    pub done: usize,
    pub failed: usize,
    pub pending: usize,
}

/// Writes `out/results.csv`: columns `case`, `seed`, `status`, the parameters, then the metrics
/// (as named in the manifest); numbers in Rust's shortest round-trip form (read back, they are
/// the same bits); empty cells where a case has no value (pending, failed, or no sample in a
/// metric's window). Returns the file and the counts.
pub fn collect(out: &Path) -> Result<(PathBuf, Collected), SweepError> {
    let manifest_file = out.join("manifest.json");
    let text = std::fs::read_to_string(&manifest_file)
        .map_err(|source| SweepError::Read { file: manifest_file.clone(), source })?;
    let manifest: Manifest = serde_json::from_str(&text)
        .map_err(|e| SweepError::Invalid { file: manifest_file.clone(), message: e.to_string() })?;
    let mut csv = ["case", "seed", "status"].map(String::from).join(",");
    for name in manifest.parameters.iter().chain(&manifest.metrics) {
        csv.push(',');
        csv.push_str(name);
    }
    csv.push('\n');
    let mut counts = Collected::default();
    for entry in &manifest.cases {
        let record = read_case(out, &entry.id);
        let status = record.as_ref().map_or(Status::Pending, |r| r.status);
        match status {
            Status::Done => counts.done += 1,
            Status::Failed => counts.failed += 1,
            Status::Pending => counts.pending += 1,
        }
        let label = serde_json::to_value(status).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default();
        let _ = write!(csv, "{},{},{label}", entry.id, entry.seed);
        let parameters = manifest.parameters.iter().map(|p| record.as_ref().and_then(|r| r.parameters.get(p).copied()));
        let metrics =
            manifest.metrics.iter().map(|m| record.as_ref().and_then(|r| r.metrics.get(m).copied().flatten()));
        for value in parameters.chain(metrics) {
            let _ = write!(csv, ",{}", value.map(|v| v.to_string()).unwrap_or_default());
        }
        csv.push('\n');
    }
    let file = out.join("results.csv");
    write_atomically(&file, &csv)?;
    Ok((file, counts))
}
