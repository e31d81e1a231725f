//! Wall time spent inside a simulator's calls, measured by a wrapper that is only put in place
//! when timing is asked for (a run without it pays nothing).

use std::sync::Arc;
use std::time::Duration;

use super::{Simulator, SimulatorError};
use crate::time::WallTotal;

/// Wall time one simulator spent in `do_step` and in its get/set calls (values, input
/// derivatives and start values; start values go through `set_*`), summed over the run.
#[derive(Debug, Default)]
pub struct CallTimes {
    do_step: WallTotal,
    get_set: WallTotal,
}

impl CallTimes {
    /// Time inside `fmi2DoStep`.
    pub fn do_step(&self) -> Duration {
        self.do_step.get()
    }

    /// Time inside `fmi2Get*`, `fmi2Set*` and `fmi2SetRealInputDerivatives`.
    pub fn get_set(&self) -> Duration {
        self.get_set.get()
    }
}

/// A simulator whose `do_step` and get/set calls are timed into a shared [`CallTimes`].
pub struct Timed {
    inner: Box<dyn Simulator>,
    times: Arc<CallTimes>,
}

impl Timed {
    /// Wraps `inner`; the returned [`CallTimes`] fill up as it is called.
    pub fn new(inner: Box<dyn Simulator>) -> (Self, Arc<CallTimes>) {
        let times = Arc::new(CallTimes::default());
        (Self { inner, times: Arc::clone(&times) }, times)
    }
}

impl Simulator for Timed {
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Result<(), SimulatorError> {
        self.inner.setup_experiment(start, stop)
    }

    fn enter_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        self.inner.enter_initialization_mode()
    }

    fn exit_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        self.inner.exit_initialization_mode()
    }

    fn do_step(&mut self, current: f64, step: f64) -> Result<(), SimulatorError> {
        self.times.do_step.time(|| self.inner.do_step(current, step))
    }

    fn terminated(&self) -> Result<bool, SimulatorError> {
        self.inner.terminated()
    }

    fn last_successful_time(&self) -> Result<f64, SimulatorError> {
        self.inner.last_successful_time()
    }

    fn terminate(&mut self) -> Result<(), SimulatorError> {
        self.inner.terminate()
    }

    fn set_time_hint(&mut self, time: f64) {
        self.inner.set_time_hint(time)
    }

    fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.get_real(vrs, values))
    }

    fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.get_integer(vrs, values))
    }

    fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.get_boolean(vrs, values))
    }

    fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SimulatorError> {
        self.times.get_set.time(|| self.inner.get_string(vrs))
    }

    fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.set_real(vrs, values))
    }

    fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.set_integer(vrs, values))
    }

    fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.set_boolean(vrs, values))
    }

    fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.set_string(vrs, values))
    }

    fn set_real_input_derivatives(
        &mut self,
        vrs: &[u32],
        orders: &[i32],
        values: &[f64],
    ) -> Result<(), SimulatorError> {
        self.times.get_set.time(|| self.inner.set_real_input_derivatives(vrs, orders, values))
    }
}
