//! Recording variables to a CSV file.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Condvar, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::row::{Cell, Row};
use super::{csv_text, Live, Observer, ObserverError};

use crate::partial::PartialFile;
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
/// complete row and lacks at most the rows of one flush interval. The interval is kept by a
/// flusher thread too, so rows computed before an FMU call that never returns still reach the
/// file; `flush_live_recorders` writes every pending row at an emergency end.
pub struct CsvRecorder {
    file: PathBuf,
    every: u64,
    /// The recorded variables' values, in column order (time excluded).
    row: Row,
    line: Vec<u8>,
    digits: zmij::Buffer,
    /// The last text of each Real column (see [`csv_text::RealText`]).
    texts: Vec<csv_text::RealText>,
    sink: Arc<Shared>,
    flusher: Option<JoinHandle<()>>,
}

/// The file and its pending rows, shared with the flusher thread (and an emergency end).
#[derive(Debug)]
pub(crate) struct Shared {
    sink: Mutex<Sink>,
    /// Wakes the flusher when the recorder is dropped.
    wake: Condvar,
}

#[derive(Debug)]
struct Sink {
    output: File,
    /// Renamed to the target at the end (none for standard output).
    partial: Option<PartialFile>,
    /// Complete rows not yet written to `output`.
    pending: Vec<u8>,
    pending_rows: u64,
    flush: FlushPolicy,
    last_flush: Instant,
    /// Rows recorded (written or pending) and the time of the last one.
    rows: u64,
    last_time: Option<f64>,
    stop: bool,
}

impl Sink {
    /// Writes the pending rows in one call, so the file grows by whole rows.
    fn write_pending(&mut self) -> std::io::Result<()> {
        self.output.write_all(&self.pending)?;
        self.pending.clear();
        self.pending_rows = 0;
        self.last_flush = Instant::now();
        Ok(())
    }

    /// Writes the pending rows and puts the file in place if it holds any ([`crate::partial`]).
    fn settle(&mut self) -> std::io::Result<()> {
        self.write_pending()?;
        match &mut self.partial {
            Some(partial) => partial.settle(self.rows),
            None => Ok(()),
        }
    }
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Sink> {
        self.sink.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl super::RecordedRows for Shared {
    fn recorded(&self) -> (u64, Option<f64>) {
        let sink = self.lock();
        (sink.rows, sink.last_time)
    }
}

/// Recorders alive in the process, for [`flush_live_recorders`].
static LIVE: Live<Shared> = Live::new();

/// Writes every live recorder's pending (complete) rows and puts its file in place: the
/// process is about to end without unwinding (an FMU call that does not return, `exit()` or a
/// crash inside an FMU).
pub(super) fn flush_live_recorders() {
    LIVE.each(|shared| {
        let _ = shared.lock().settle();
    });
}

/// Writes the pending rows once `interval` passed since the last write, while the run may be
/// inside an FMU call, until the recorder is dropped.
fn flush_on_time(shared: &Shared) {
    let mut sink = shared.lock();
    while !sink.stop {
        let interval = sink.flush.interval;
        let since = sink.last_flush.elapsed();
        if sink.pending_rows > 0 && since >= interval {
            // An error stays for the recorder's own next write to report.
            let _ = sink.write_pending();
            continue;
        }
        // A zero interval is kept by `observe` alone.
        let wait = if interval.is_zero() { Duration::from_secs(1) } else { interval.saturating_sub(since) };
        sink = shared
            .wake
            .wait_timeout(sink, wait.max(Duration::from_millis(1)))
            .unwrap_or_else(PoisonError::into_inner)
            .0;
    }
}

/// The results file name that means standard output (`crane-cosim run -o -`).
pub const STANDARD_OUTPUT: &str = "-";

/// A file on the process's standard output, so that the sink writes rows there unbuffered and
/// in order like to any file (nothing else may write to standard output during the run).
fn standard_output() -> std::io::Result<File> {
    #[cfg(unix)]
    let handle = std::os::fd::AsFd::as_fd(&std::io::stdout()).try_clone_to_owned()?;
    #[cfg(windows)]
    let handle = std::os::windows::io::AsHandle::as_handle(&std::io::stdout()).try_clone_to_owned()?;
    Ok(File::from(handle))
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
        f.debug_struct("CsvRecorder").field("file", &self.file).field("rows", &self.rows()).finish_non_exhaustive()
    }
}

impl CsvRecorder {
    /// Writes the header to a partial file beside `file` (creating its parent directories),
    /// renamed to `file` when the run ends with a row ([`crate::partial`]); the file `-`
    /// ([`STANDARD_OUTPUT`]) is the process's standard output.
    pub fn create(file: &Path, variables: &[VariableRef], every: u64) -> Result<Self, ObserverError> {
        let io_error = |source| ObserverError::Io { file: file.to_path_buf(), source };
        let (mut output, partial) = if file == Path::new(STANDARD_OUTPUT) {
            (standard_output().map_err(io_error)?, None)
        } else {
            let (output, partial) = PartialFile::create(file).map_err(io_error)?;
            (output, Some(partial))
        };
        let flusher_error = |source| ObserverError::Io { file: file.to_path_buf(), source };

        let mut line = Vec::new();
        csv_text::push_field(&mut line, "time");
        for variable in variables {
            line.push(b',');
            csv_text::push_field(&mut line, &variable.qualified_name);
        }
        line.push(b'\n');
        output.write_all(&line).map_err(io_error)?;
        let sink = Sink {
            output,
            partial,
            pending: Vec::new(),
            pending_rows: 0,
            flush: FlushPolicy::default(),
            last_flush: Instant::now(),
            rows: 0,
            last_time: None,
            stop: false,
        };
        let sink = Arc::new(Shared { sink: Mutex::new(sink), wake: Condvar::new() });
        let shared = Arc::clone(&sink);
        let flusher = std::thread::Builder::new()
            .name("csv-flush".into())
            .spawn(move || flush_on_time(&shared))
            .map_err(flusher_error)?;
        LIVE.add(&sink);
        Ok(Self {
            file: file.to_path_buf(),
            every: every.max(1),
            row: Row::new(variables),
            line,
            digits: zmij::Buffer::new(),
            texts: vec![csv_text::RealText::default(); variables.len()],
            sink,
            flusher: Some(flusher),
        })
    }

    /// Writes rows to the file as `policy` says instead of the default.
    pub fn with_flush(self, policy: FlushPolicy) -> Self {
        self.sink.lock().flush = policy;
        self.sink.wake.notify_all();
        self
    }

    /// The shared file and rows, for an emergency end's summary.
    pub(crate) fn shared(&self) -> &Arc<Shared> {
        &self.sink
    }

    /// Data rows written so far.
    pub fn rows(&self) -> u64 {
        self.sink.lock().rows
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
        for (cell, text) in self.row.cells().iter().zip(&mut self.texts) {
            line.push(b',');
            match cell {
                Cell::Real(value) => text.push(line, &mut self.digits, *value),
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
        let mut sink = self.sink.lock();
        sink.pending.extend_from_slice(&self.line);
        sink.pending_rows += 1;
        sink.rows += 1;
        sink.last_time = Some(time);
        if sink.pending_rows >= sink.flush.rows || sink.last_flush.elapsed() >= sink.flush.interval {
            sink.write_pending().map_err(|source| ObserverError::Io { file: self.file.clone(), source })?;
        }
        Ok(())
    }

    /// Writes the pending rows and puts the file in place (called also after a failed run).
    fn finish(&mut self) -> Result<(), ObserverError> {
        self.sink.lock().settle().map_err(|source| ObserverError::Io { file: self.file.clone(), source })
    }
}

impl Drop for CsvRecorder {
    /// Stops the flusher, and settles the file of a run that ended before `finish` (one that
    /// failed to start: its partial file, without a row, is removed).
    fn drop(&mut self) {
        {
            let mut sink = self.sink.lock();
            let _ = sink.settle();
            sink.stop = true;
        }
        self.sink.wake.notify_all();
        if let Some(flusher) = self.flusher.take() {
            let _ = flusher.join();
        }
        LIVE.remove(&self.sink);
    }
}
