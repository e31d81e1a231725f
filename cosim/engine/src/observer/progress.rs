//! Progress bars on the terminal (hidden when stderr is not a terminal, e.g. in CI logs): one
//! run's steps ([`Progress`], an observer), and a batch's runs ([`RunProgress`]: a campaign's
//! runs, a study's cases), kept here so that every batch shows the same bar.

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

/// A progress bar over the runs of a batch (indicatif draws nothing when stderr is not a
/// terminal).
pub struct RunProgress(ProgressBar);

impl RunProgress {
    /// A bar over `total` runs; a hidden one unless `show`.
    pub fn new(total: u64, show: bool) -> Self {
        if !show {
            return RunProgress(ProgressBar::hidden());
        }
        let bar = ProgressBar::new(total);
        if let Ok(style) =
            ProgressStyle::with_template("{bar:40} {pos}/{len} runs, {elapsed} elapsed, ~{eta} left  {msg}")
        {
            bar.set_style(style);
        }
        RunProgress(bar)
    }

    /// Counts the run `id` done, printing its error if it failed.
    pub fn advance(&self, id: &str, error: Option<&str>) {
        if let Some(error) = error {
            self.0.println(format!("failed: {error}"));
        }
        self.0.set_message(id.to_string());
        self.0.inc(1);
    }

    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}
