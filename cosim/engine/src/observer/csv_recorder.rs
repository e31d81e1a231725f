//! Recording variables to a CSV file.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use super::row::{Cell, Row};
use super::{csv_text, Observer, ObserverError};

use crate::simulator::Simulator;
use crate::variable::VariableRef;

/// Writes `time,<instance>.<variable>,...` rows to a CSV file.
///
/// * Header: `time` then the qualified names, quoted by CSV rules only when needed (the
///   validated names never need it). `fmpy.util.read_csv` reads it as a structured array whose
///   field names keep the dots, e.g. `result["load.theta_x"]`.
/// * Reals (and time) are written exactly as Rust's `{:?}` writes them: the shortest decimal
///   that reads back to the same bits, plain for `1e-4 <= |x| < 1e16` (`0.1`, `1.0`, `-0.0`)
///   and e-notation outside (`1e-7`, `1.5e-5`, `1e16`), and `NaN`, `inf`, `-inf`; Python's
///   `float`, NumPy and Rust's `parse` read every one back bit-exactly.
/// * Booleans are `0`/`1`, integers and enumerations decimal; strings are
///   quoted by CSV rules when needed (FMPy cannot read string columns).
/// * Lines end with LF. A row is written at `k = 0, every, 2·every, ...`.
/// * Values are what the FMUs report at `t_k`; for an input that is the
///   value set for the step that ended at `t_k` (set at `t_{k−1}`), since
///   inputs for the next step are set only just before it.
///
/// A row costs one get call per instance and type and no allocation (except for strings):
/// numbers are formatted into a reused line buffer. Rows are written to the file in whole rows
/// only, as the [`FlushPolicy`] says, so a process killed mid-run leaves a CSV that ends on a
/// complete row and lacks at most the rows of one flush interval.
pub struct CsvRecorder {
    file: PathBuf,
    output: File,
    every: u64,
    /// The recorded variables' values, in column order (time excluded).
    row: Row,
    line: Vec<u8>,
    digits: zmij::Buffer,
    rows: u64,
    /// Complete rows not yet written to `output`.
    pending: Vec<u8>,
    pending_rows: u64,
    flush: FlushPolicy,
    last_flush: Instant,
}

/// When recorded rows reach the file: after `rows` rows or `interval` of wall time since the
/// last write, whichever comes first (and at the end of the run).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlushPolicy {
    pub rows: u64,
    pub interval: Duration,
}

impl Default for FlushPolicy {
    /// 1,000 rows (about 250 KB of the closed loop's 24 columns) or 1 s.
    fn default() -> Self {
        Self { rows: 1000, interval: Duration::from_secs(1) }
    }
}

impl std::fmt::Debug for CsvRecorder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CsvRecorder").field("file", &self.file).field("rows", &self.rows).finish_non_exhaustive()
    }
}

impl CsvRecorder {
    /// Creates `file` (and its parent directories) and writes the header.
    pub fn create(file: &Path, variables: &[VariableRef], every: u64) -> Result<Self, ObserverError> {
        let io_error = |source| ObserverError::Io { file: file.to_path_buf(), source };
        if let Some(parent) = file.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent).map_err(io_error)?;
        }
        let mut output = File::create(file).map_err(io_error)?;

        let mut line = Vec::new();
        csv_text::push_field(&mut line, "time");
        for variable in variables {
            line.push(b',');
            csv_text::push_field(&mut line, &variable.qualified_name);
        }
        line.push(b'\n');
        output.write_all(&line).map_err(io_error)?;
        Ok(Self {
            file: file.to_path_buf(),
            output,
            every: every.max(1),
            row: Row::new(variables),
            line,
            digits: zmij::Buffer::new(),
            rows: 0,
            pending: Vec::new(),
            pending_rows: 0,
            flush: FlushPolicy::default(),
            last_flush: Instant::now(),
        })
    }

    /// Writes rows to the file as `policy` says instead of the default.
    pub fn with_flush(mut self, policy: FlushPolicy) -> Self {
        self.flush = policy;
        self
    }

    /// Data rows written so far.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// The output file.
    pub fn file(&self) -> &Path {
        &self.file
    }
}

impl CsvRecorder {
    /// Formats the row of `time` into the line buffer.
    fn format_row(&mut self, time: f64) {
        let line = &mut self.line;
        line.clear();
        csv_text::push_real(line, &mut self.digits, time);
        for cell in self.row.cells() {
            line.push(b',');
            match cell {
                Cell::Real(value) => csv_text::push_real(line, &mut self.digits, *value),
                Cell::Integer(value) => csv_text::push_integer(line, *value),
                Cell::Boolean(value) => line.push(if *value { b'1' } else { b'0' }),
                Cell::String(value) => csv_text::push_field(line, value),
            }
        }
        line.push(b'\n');
    }
}

impl Observer for CsvRecorder {
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        if !k.is_multiple_of(self.every) {
            return Ok(());
        }
        self.row.read(slaves)?;
        self.format_row(time);
        self.pending.extend_from_slice(&self.line);
        self.rows += 1;
        self.pending_rows += 1;
        if self.pending_rows >= self.flush.rows || self.last_flush.elapsed() >= self.flush.interval {
            self.write_pending()?;
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        self.write_pending()
    }
}

impl CsvRecorder {
    /// Writes the pending rows in one call, so the file grows by whole rows.
    fn write_pending(&mut self) -> Result<(), ObserverError> {
        self.output.write_all(&self.pending).map_err(|source| ObserverError::Io { file: self.file.clone(), source })?;
        self.pending.clear();
        self.pending_rows = 0;
        self.last_flush = Instant::now();
        Ok(())
    }
}
