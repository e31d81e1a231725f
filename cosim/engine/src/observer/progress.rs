//! A progress bar on the terminal (hidden when stderr is not a terminal, e.g. in CI logs).

use indicatif::{ProgressBar, ProgressStyle};

use super::{Observer, ObserverError};
use crate::simulator::Simulator;

/// Shows the simulated time against the stop time; a read-only observer.
pub struct Progress {
    bar: ProgressBar,
}

impl Progress {
    /// A bar over `steps` macro steps.
    pub fn new(steps: u64) -> Self {
        let bar = ProgressBar::new(steps);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} steps, t = {msg} s, {elapsed} (eta {eta})")
        {
            bar.set_style(style);
        }
        Progress { bar }
    }
}

impl Observer for Progress {
    fn observe(&mut self, k: u64, time: f64, _slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        // Redrawing is rate-limited by indicatif; updating every 100 steps keeps the cost nil.
        if k.is_multiple_of(100) {
            self.bar.set_position(k);
            self.bar.set_message(format!("{time:.2}"));
        }
        Ok(())
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        self.bar.finish_and_clear();
        Ok(())
    }
}
