//! Wall time spent in an observer, measured by a wrapper that is only put in place when timing
//! is asked for.

use std::sync::Arc;

use super::{Observer, ObserverError};
use crate::simulator::Simulator;
use crate::time::WallTotal;

/// An observer whose `observe` and `finish` calls are timed into a shared total.
pub struct TimedObserver<O> {
    inner: O,
    spent: Arc<WallTotal>,
}

impl<O: Observer> TimedObserver<O> {
    /// Wraps `inner`; the returned total grows with every call.
    pub fn new(inner: O) -> (Self, Arc<WallTotal>) {
        let spent = Arc::new(WallTotal::default());
        (Self { inner, spent: Arc::clone(&spent) }, spent)
    }

    fn timed<R>(&mut self, call: impl FnOnce(&mut O) -> R) -> R {
        let inner = &mut self.inner;
        self.spent.time(|| call(inner))
    }
}

impl<O: Observer> Observer for TimedObserver<O> {
    fn observe(&mut self, k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        self.timed(|inner| inner.observe(k, time, slaves))
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        self.timed(|inner| inner.finish())
    }
}
