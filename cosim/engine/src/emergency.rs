//! Ending the process when a run cannot end itself: an FMU call that does not return (a second
//! signal, a grace period, a step timeout) or an FMU that calls `exit()`.
//!
//! [`end`] writes every live recorder's computed rows (whole rows), every live run's summary
//! and removes the FMUs' temporary folders; the caller then leaves with `_exit`. It locks and
//! writes files, so it must run in an ordinary thread (a signal-watching thread or an `atexit`
//! handler), never in a signal handler.

use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Instant;

use crate::observer::{flush_live_recorders, RecordedRows};
use crate::summary::{RunStatus, RunSummary};
use crate::time::TimeGrid;

/// A run in progress as an emergency end sees it.
struct LiveRun {
    id: u64,
    summary: RunSummary,
    path: Option<PathBuf>,
    rows: Arc<dyn RecordedRows>,
    completed: Arc<AtomicU64>,
    grid: TimeGrid,
    started: Instant,
}

static RUNS: Mutex<Vec<LiveRun>> = Mutex::new(Vec::new());
static NEXT: AtomicU64 = AtomicU64::new(0);

/// Registered while a run steps; dropping it forgets the run (its own summary is written then).
pub(crate) struct Registration(u64);

impl Drop for Registration {
    fn drop(&mut self) {
        RUNS.lock().unwrap_or_else(PoisonError::into_inner).retain(|run| run.id != self.0);
    }
}

/// Notes a run whose summary so far is `summary` (to be written to `path`), recording into
/// `rows`, with `completed` steps published by the execution.
pub(crate) fn register(
    summary: &RunSummary,
    path: Option<PathBuf>,
    rows: Arc<dyn RecordedRows>,
    completed: Arc<AtomicU64>,
    grid: TimeGrid,
) -> Registration {
    let id = NEXT.fetch_add(1, Ordering::Relaxed);
    let run = LiveRun { id, summary: summary.clone(), path, rows, completed, grid, started: Instant::now() };
    RUNS.lock().unwrap_or_else(PoisonError::into_inner).push(run);
    Registration(id)
}

/// Writes every computed row, the summary of every live run with `status` and `error`, and
/// removes the temporary folders. The process must end right after (`_exit`).
pub fn end(status: RunStatus, error: &str) {
    flush_live_recorders();
    let runs = std::mem::take(&mut *RUNS.lock().unwrap_or_else(PoisonError::into_inner));
    for run in runs {
        let mut summary = run.summary;
        let completed = run.completed.load(Ordering::Relaxed);
        let (rows, _) = run.rows.recorded();
        summary.status = status;
        summary.error = Some(error.to_string());
        summary.reached(completed, run.grid.time(completed), run.grid.start(), rows);
        summary.timed(run.started.elapsed().as_secs_f64());
        // As at a normal end: a summary only beside rows.
        if let Some(path) = run.path.as_ref().filter(|_| rows > 0) {
            if let Err(write_error) = summary.write(path) {
                eprintln!("warning: cannot write the run summary {}: {write_error}", path.display());
            }
        }
    }
    fmu_import::watch::remove_temp_dirs();
}
