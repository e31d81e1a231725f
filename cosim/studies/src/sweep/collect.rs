//! Merging the case files of an output folder into one table, one row per planned case, written
//! as `results.csv` and `results.parquet`, with summary plots in `plots/`.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use super::check_marked;
use super::parquet::results_parquet;
use super::plots::{write_plots, ImageFormat};
use super::table::{read_table, status_label, Collected, Table};
use crate::files::{write_atomically, write_bytes_atomically};
use crate::StudyError;

/// The files `collect` wrote and the cases' states.
#[derive(Debug, Clone, PartialEq)]
pub struct Collection {
    /// `out/results.csv`.
    pub csv: PathBuf,
    /// `out/results.parquet`.
    pub parquet: PathBuf,
    /// The summary plots, in the order drawn (none without a format).
    pub plots: Vec<PathBuf>,
    /// How many cases are in each state.
    pub counts: Collected,
}

/// Reads `out/manifest.json` and every case file; writes `out/results.csv`,
/// `out/results.parquet` and, with a `plots` format, the summary plots into `out/plots/`; and
/// rewrites the manifest with the statuses found, since jobs that ran cases side by side may
/// each have written it before the others' cases were done.
pub fn collect(out: &Path, plots: Option<ImageFormat>) -> Result<Collection, StudyError> {
    check_marked(out)?;
    let (mut manifest, table) = read_table(out)?;
    for (entry, row) in manifest.cases.iter_mut().zip(&table.rows) {
        entry.status = row.status;
    }
    manifest.write(out)?;
    let csv = out.join("results.csv");
    write_atomically(&csv, &results_csv(&table))?;
    let parquet = out.join("results.parquet");
    let bytes = results_parquet(&table)
        .map_err(|e| StudyError::Write { file: parquet.clone(), source: std::io::Error::other(e) })?;
    write_bytes_atomically(&parquet, &bytes)?;
    let plots = match plots {
        Some(format) => write_plots(&out.join("plots"), &table, format)?,
        None => Vec::new(),
    };
    Ok(Collection { csv, parquet, plots, counts: table.counts() })
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
            let _ = write!(csv, ",{}", value.map(|v| format!("{v:?}")).unwrap_or_default());
        }
        csv.push('\n');
    }
    csv
}
