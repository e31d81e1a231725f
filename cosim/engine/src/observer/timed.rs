//! Wall time spent in an observer, measured by a wrapper that is only put in place when timing
//! is asked for.

use std::cell::Cell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use super::{Observer, ObserverError};
use crate::simulator::Simulator;

/// An observer whose `observe` and `finish` calls are timed into a shared total.
pub struct TimedObserver<O> {
    inner: O,
    spent: Rc<Cell<Duration>>,
}

impl<O: Observer> TimedObserver<O> {
    /// Wraps `inner`; the returned total grows with every call.
    pub fn new(inner: O) -> (Self, Rc<Cell<Duration>>) {
        let spent = Rc::new(Cell::new(Duration::ZERO));
        (Self { inner, spent: Rc::clone(&spent) }, spent)
    }

    fn timed<R>(&mut self, call: impl FnOnce(&mut O) -> R) -> R {
        let start = Instant::now();
        let result = call(&mut self.inner);
        self.spent.set(self.spent.get() + start.elapsed());
        result
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
