//! Wall time spent inside a simulator's calls, measured by a wrapper that is only put in place
//! when timing is asked for (a run without it pays nothing).

use std::sync::Arc;
use std::time::Duration;

use super::wrapped::{Wrapped, Wrapper};
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

/// The wrapper that times a simulator's `do_step` and get/set calls into a shared [`CallTimes`].
pub struct Timing(Arc<CallTimes>);

/// A simulator timed by [`Timing`].
pub type Timed = Wrapped<Timing>;

/// Wraps `inner` in [`Timing`]; the returned [`CallTimes`] fill up as it is called.
pub fn timed(inner: Box<dyn Simulator>) -> (Timed, Arc<CallTimes>) {
    let times = Arc::new(CallTimes::default());
    (Wrapped::new(inner, Timing(Arc::clone(&times))), times)
}

impl Wrapper for Timing {
    fn around_step(&self, call: &mut dyn FnMut() -> Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        self.0.do_step.time(call)
    }

    fn around_get_set(&self, call: &mut dyn FnMut() -> Result<(), SimulatorError>) -> Result<(), SimulatorError> {
        self.0.get_set.time(call)
    }
}
