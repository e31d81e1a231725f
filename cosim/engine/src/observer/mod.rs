//! Read-only observers of a running execution (recorders, monitors).

mod csv_recorder;
mod csv_text;
mod progress;
mod row;
mod table_recorder;
mod timed;

pub(crate) use csv_recorder::Shared as SharedRows;
pub use csv_recorder::{flush_live_recorders, CsvRecorder, FlushPolicy, STANDARD_OUTPUT};
pub use progress::Progress;
pub use table_recorder::TableRecorder;
pub use timed::TimedObserver;

use std::path::PathBuf;

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
