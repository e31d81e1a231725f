//! Read-only observers of a running execution (recorders, monitors).

mod csv_recorder;
mod csv_text;
mod parquet_recorder;
mod progress;
mod row;
mod table_recorder;
mod timed;

pub use csv_recorder::{CsvRecorder, FlushPolicy, STANDARD_OUTPUT};
pub use parquet_recorder::{is_parquet, ParquetRecorder, UNITS_KEY};
pub use progress::{Progress, RunProgress};
pub use table_recorder::TableRecorder;
pub use timed::TimedObserver;

use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError, Weak};

use crate::variable::VariableRef;

use crate::simulator::{Simulator, SimulatorError};

impl From<SimulatorError> for ObserverError {
    fn from(error: SimulatorError) -> Self {
        ObserverError::Read(error)
    }
}

/// Why an observer failed.
#[derive(Debug, thiserror::Error)]
pub enum ObserverError {
    #[error("cannot write {}", file.display())]
    Io {
        file: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("cannot read recorded variables")]
    Read(#[source] SimulatorError),
}

/// Sees the instances after initialization and after every macro step; it
/// gets shared references only, so it cannot change the simulation.
pub trait Observer {
    /// Called with `k = 0` after initialization and with `k` after step
    /// `k − 1 → k`; `time` is `t_k` in seconds.
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError>;

    /// Flushes everything; called once at the end, also after a failure.
    fn finish(&mut self) -> Result<(), ObserverError>;
}

/// A shared observer, so the caller can still inspect it (e.g. the number of
/// recorded rows) after handing it to an execution.
impl<T: Observer> Observer for std::rc::Rc<std::cell::RefCell<T>> {
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        self.borrow_mut().observe(k, time, slaves)
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        self.borrow_mut().finish()
    }
}

/// Writes every live recorder's pending (complete) rows, and closes every Parquet file: the
/// process is about to end without unwinding (an FMU call that does not return, or `exit()`
/// inside an FMU).
pub fn flush_live_recorders() {
    csv_recorder::flush_live_recorders();
    parquet_recorder::close_live();
}

/// The recorders of one kind alive in the process (weakly held: a dropped recorder is not kept
/// alive), so that an emergency end can write what each holds.
struct Live<T>(Mutex<Vec<Weak<T>>>);

impl<T> Live<T> {
    const fn new() -> Self {
        Live(Mutex::new(Vec::new()))
    }

    /// The list, whether or not a thread panicked holding it: an emergency end must still reach it.
    fn list(&self) -> MutexGuard<'_, Vec<Weak<T>>> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }

    fn add(&self, shared: &Arc<T>) {
        self.list().push(Arc::downgrade(shared));
    }

    /// Forgets `shared`, and any recorder already gone.
    fn remove(&self, shared: &Arc<T>) {
        self.list().retain(|weak| weak.strong_count() > 0 && !std::ptr::eq(weak.as_ptr(), Arc::as_ptr(shared)));
    }

    /// Calls `f` on every recorder still alive, without holding the list meanwhile.
    fn each(&self, mut f: impl FnMut(&T)) {
        let live = self.list().clone();
        for shared in live.iter().filter_map(Weak::upgrade) {
            f(&shared);
        }
    }
}

/// Rows a recorder has recorded and the time of the last one, readable from another thread (an
/// emergency end's summary).
pub(crate) trait RecordedRows: Send + Sync {
    fn recorded(&self) -> (u64, Option<f64>);
}

/// The results file of a run: CSV, or Parquet when its name ends in `.parquet`.
#[derive(Debug)]
pub enum Recorder {
    Csv(CsvRecorder),
    Parquet(ParquetRecorder),
}

impl Recorder {
    /// Creates the recorder `file`'s name asks for ([`is_parquet`]), writing rows as `flush` says.
    pub fn create(
        file: &Path,
        variables: &[VariableRef],
        every: u64,
        flush: FlushPolicy,
    ) -> Result<Self, ObserverError> {
        Ok(if is_parquet(file) {
            Recorder::Parquet(ParquetRecorder::create(file, variables, every)?.with_flush(flush))
        } else {
            Recorder::Csv(CsvRecorder::create(file, variables, every)?.with_flush(flush))
        })
    }

    /// Data rows recorded so far.
    pub fn rows(&self) -> u64 {
        match self {
            Recorder::Csv(recorder) => recorder.rows(),
            Recorder::Parquet(recorder) => recorder.rows(),
        }
    }

    /// The recorded rows, for an emergency end's summary.
    pub(crate) fn shared(&self) -> Arc<dyn RecordedRows> {
        match self {
            Recorder::Csv(recorder) => Arc::clone(recorder.shared()) as Arc<dyn RecordedRows>,
            Recorder::Parquet(recorder) => Arc::clone(recorder.shared()) as Arc<dyn RecordedRows>,
        }
    }
}

impl Observer for Recorder {
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        match self {
            Recorder::Csv(recorder) => recorder.observe(k, time, slaves),
            Recorder::Parquet(recorder) => recorder.observe(k, time, slaves),
        }
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        match self {
            Recorder::Csv(recorder) => recorder.finish(),
            Recorder::Parquet(recorder) => recorder.finish(),
        }
    }
}
