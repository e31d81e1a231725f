//! A simulator with something added around its calls: every call is passed on to the inner
//! simulator, and a [`Wrapper`] sees `do_step` and the get/set calls go by. Timing
//! ([`super::Timed`]) and an operator writing inputs before each step are wrappers; a new one
//! implements only what it adds.

use super::{Simulator, SimulatorError};

/// What a [`Wrapped`] simulator adds. Every method has a default that adds nothing.
pub trait Wrapper: Send {
    /// Runs before each `do_step`, with the inner simulator (e.g. to set its inputs).
    fn before_step(&mut self, _inner: &mut dyn Simulator) -> Result<(), SimulatorError> {
        Ok(())
    }

    /// Runs the inner `do_step` as `call` (e.g. timed).
    fn around_step(&self, call: &mut dyn FnMut() -> Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        call()
    }

    /// Runs one inner get/set call (values, input derivatives, start values) as `call`.
    fn around_get_set(&self, call: &mut dyn FnMut() -> Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        call()
    }
}

/// `inner` with `wrapper` around its calls.
pub struct Wrapped<W> {
    inner: Box<dyn Simulator>,
    wrapper: W,
}

impl<W: Wrapper> Wrapped<W> {
    pub fn new(inner: Box<dyn Simulator>, wrapper: W) -> Self {
        Self { inner, wrapper }
    }

    /// The wrapper.
    pub fn wrapper(&self) -> &W {
        &self.wrapper
    }
}

impl<W: Wrapper> Simulator for Wrapped<W> {
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
        self.wrapper.before_step(self.inner.as_mut())?;
        let inner = &mut self.inner;
        self.wrapper.around_step(&mut || inner.do_step(current, step))
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

    fn save_state(&mut self) -> Result<Vec<u8>, SimulatorError> {
        self.inner.save_state()
    }

    fn restore_state(&mut self, state: &[u8]) -> Result<(), SimulatorError> {
        self.inner.restore_state(state)
    }

    fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SimulatorError> {
        self.wrapper.around_get_set(&mut || self.inner.get_real(vrs, values))
    }

    fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SimulatorError> {
        self.wrapper.around_get_set(&mut || self.inner.get_integer(vrs, values))
    }

    fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SimulatorError> {
        self.wrapper.around_get_set(&mut || self.inner.get_boolean(vrs, values))
    }

    fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SimulatorError> {
        let mut strings = Vec::new();
        self.wrapper.around_get_set(&mut || {
            strings = self.inner.get_string(vrs)?;
            Ok(())
        })?;
        Ok(strings)
    }

    fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SimulatorError> {
        let inner = &mut self.inner;
        self.wrapper.around_get_set(&mut || inner.set_real(vrs, values))
    }

    fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SimulatorError> {
        let inner = &mut self.inner;
        self.wrapper.around_get_set(&mut || inner.set_integer(vrs, values))
    }

    fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SimulatorError> {
        let inner = &mut self.inner;
        self.wrapper.around_get_set(&mut || inner.set_boolean(vrs, values))
    }

    fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SimulatorError> {
        let inner = &mut self.inner;
        self.wrapper.around_get_set(&mut || inner.set_string(vrs, values))
    }

    fn set_real_input_derivatives(&mut self, vrs: &[u32], slopes: &[f64]) -> Result<(), SimulatorError> {
        let inner = &mut self.inner;
        self.wrapper.around_get_set(&mut || inner.set_real_input_derivatives(vrs, slopes))
    }
}
