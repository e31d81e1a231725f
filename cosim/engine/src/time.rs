//! The communication time grid `t_k = start + k·h`.
//!
//! Times are always computed from the integer step count, never by adding
//! `h` repeatedly, so there is no drift; the expression is the one FMPy's
//! `simulateCS` uses (`start_time + n_steps * output_interval`), so both
//! importers hit bit-identical communication points. A stop time off the
//! grid is reached by a shorter last step, as FMPy does for FMUs that can
//! handle a variable communication step size.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Wall time summed over timed calls (`run --timing`), shareable with whoever reports it.
#[derive(Debug, Default)]
pub struct WallTotal {
    nanos: AtomicU64,
}

impl WallTotal {
    /// Runs `call`, adding its wall time to the total.
    pub fn time<R>(&self, call: impl FnOnce() -> R) -> R {
        let start = Instant::now();
        let result = call();
        let nanos = u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX);
        self.nanos.fetch_add(nanos, Ordering::Relaxed);
        result
    }

    /// The time summed so far.
    pub fn get(&self) -> Duration {
        Duration::from_nanos(self.nanos.load(Ordering::Relaxed))
    }
}

/// Invalid time grid settings.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TimeGridError {
    #[error("{name} must be a finite number, got {value:?}")]
    NotFinite { name: &'static str, value: f64 },
    #[error("step_size must be positive, got {0:?}")]
    NonPositiveStep(f64),
    #[error("stop_time ({stop:?}) is before start_time ({start:?})")]
    StopBeforeStart { start: f64, stop: f64 },
    #[error("{steps} steps of {step:?} s are too many")]
    TooManySteps { steps: f64, step: f64 },
}

/// `math.isclose(a, b)` of Python with its defaults (relative tolerance 1e-9,
/// no absolute tolerance): how FMPy compares times.
pub fn is_close(a: f64, b: f64) -> bool {
    if a == b {
        return true;
    }
    if a.is_infinite() || b.is_infinite() {
        return false;
    }
    let difference = (b - a).abs();
    difference <= (1e-9 * b).abs() || difference <= (1e-9 * a).abs()
}

/// Fixed-step communication grid: `steps` steps from `start` (seconds), the last one shortened
/// to end at the stop time when that is not on the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeGrid {
    start: f64,
    step: f64,
    steps: u64,
    /// The stop time, when the last step is shortened to end there.
    shortened_to: Option<f64>,
}

/// More steps than this are refused (a typo such as `1e-9` s, not a simulation).
pub const MAX_STEPS: u64 = 1 << 40;

impl TimeGrid {
    /// The grid from `start` to `stop` with step `step` (all in seconds).
    ///
    /// The number of whole steps follows FMPy's fixed-step loop: step while
    /// `t_k < stop` (and not close to it), and only if `t_{k+1}` does not
    /// overshoot `stop` by more than the `is_close` tolerance. A stop time that
    /// is not a multiple of `h` is then reached by one more, shorter step
    /// ([`TimeGrid::shortened_last_step`]); the whole steps keep their times.
    pub fn new(start: f64, stop: f64, step: f64) -> Result<Self, TimeGridError> {
        for (name, value) in [("start_time", start), ("stop_time", stop), ("step_size", step)] {
            if !value.is_finite() {
                return Err(TimeGridError::NotFinite { name, value });
            }
        }
        if step <= 0.0 {
            return Err(TimeGridError::NonPositiveStep(step));
        }
        if stop < start {
            return Err(TimeGridError::StopBeforeStart { start, stop });
        }
        let estimate = ((stop - start) / step).round();
        if estimate.is_nan() || estimate >= MAX_STEPS as f64 {
            return Err(TimeGridError::TooManySteps { steps: estimate, step });
        }
        let mut grid = Self { start, step, steps: 0, shortened_to: None };
        let proceeds = |k: u64| {
            let t = grid.time(k);
            let next = grid.time(k + 1);
            // FMPy: stop if t_k is at or past stop, or if t_{k+1} overshoots it.
            let done = t > stop || is_close(t, stop);
            let overshoots = next > stop && !is_close(next, stop);
            !done && !overshoots
        };
        // The exact count is within a step or two of the estimate.
        let mut k = (estimate as u64).saturating_sub(2);
        while k > 0 && !proceeds(k - 1) {
            k -= 1;
        }
        while proceeds(k) {
            k += 1;
        }
        grid.steps = k;
        let end = grid.time(k);
        if end < stop && !is_close(end, stop) {
            grid.steps += 1;
            grid.shortened_to = Some(stop);
        }
        Ok(grid)
    }

    /// `t_k = start + k·h` in seconds; the stop time for the end of a shortened last step.
    pub fn time(&self, k: u64) -> f64 {
        match self.shortened_to {
            Some(stop) if k == self.steps => stop,
            _ => self.start + (k as f64) * self.step,
        }
    }

    /// The length of the last step (s) when it is shorter than `h` to end at the stop time.
    pub fn shortened_last_step(&self) -> Option<f64> {
        self.shortened_to.map(|_| self.step_size(self.steps - 1))
    }

    /// The step actually passed to `fmi2DoStep` at step `k`: `t_{k+1} − t_k`.
    pub fn step_size(&self, k: u64) -> f64 {
        self.time(k + 1) - self.time(k)
    }

    /// Nominal step `h` in seconds.
    pub fn nominal_step(&self) -> f64 {
        self.step
    }

    /// Start time in seconds.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// Last communication point `t_steps` in seconds.
    pub fn end(&self) -> f64 {
        self.time(self.steps)
    }

    /// Number of steps.
    pub fn steps(&self) -> u64 {
        self.steps
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_drift_over_1000_steps_of_0_1() {
        let grid = TimeGrid::new(0.0, 100.0, 0.1).expect("valid");
        assert_eq!(grid.steps(), 1000);
        assert_eq!(grid.end(), 100.0);
        for k in 0..=1000u64 {
            assert_eq!(grid.time(k), k as f64 * 0.1, "t_{k}");
            assert!((grid.time(k) - k as f64 / 10.0).abs() <= 1e-12 * (k as f64).max(1.0));
        }
        // Accumulating h drifts; the grid does not.
        let mut accumulated = 0.0f64;
        for _ in 0..1000 {
            accumulated += 0.1;
        }
        assert_ne!(accumulated, 100.0);
        assert!((accumulated - 100.0).abs() > 1e-12);
    }

    #[test]
    fn step_counts_follow_fmpy() {
        assert_eq!(TimeGrid::new(0.0, 60.0, 0.01).expect("valid").steps(), 6000);
        assert_eq!(TimeGrid::new(0.0, 0.0, 0.1).expect("valid").steps(), 0);
        assert_eq!(TimeGrid::new(1.0, 2.0, 0.1).expect("valid").steps(), 10);
        let grid = TimeGrid::new(0.5, 0.8, 0.1).expect("valid");
        assert_eq!(grid.steps(), 3);
        assert_eq!(grid.time(3), 0.5 + 3.0 * 0.1);
        assert_eq!(grid.step_size(0), grid.time(1) - 0.5);
        // 0.5 + 3·0.1 is not 0.8 in binary, but close to it: no sliver of a step is added.
        assert_eq!(grid.shortened_last_step(), None);
    }

    #[test]
    fn a_stop_time_off_the_grid_is_reached_by_a_shorter_last_step() {
        let grid = TimeGrid::new(0.0, 1.0, 0.3).expect("valid");
        assert_eq!((grid.steps(), grid.end()), (4, 1.0));
        assert_eq!([grid.time(2), grid.time(3)], [2.0 * 0.3, 3.0 * 0.3]);
        assert_eq!(grid.shortened_last_step(), Some(1.0 - 3.0 * 0.3));
        // A step longer than the run: one step, to the stop time.
        let grid = TimeGrid::new(0.0, 10.0, 100.0).expect("valid");
        assert_eq!((grid.steps(), grid.end(), grid.step_size(0)), (1, 10.0, 10.0));
        assert_eq!(TimeGrid::new(0.0, 2.0, 0.7).expect("valid").shortened_last_step(), Some(2.0 - 2.0 * 0.7));
    }

    #[test]
    fn invalid_settings() {
        assert_eq!(TimeGrid::new(0.0, 1.0, 0.0), Err(TimeGridError::NonPositiveStep(0.0)));
        assert_eq!(TimeGrid::new(0.0, 1.0, -0.1), Err(TimeGridError::NonPositiveStep(-0.1)));
        assert!(matches!(TimeGrid::new(0.0, f64::NAN, 0.1), Err(TimeGridError::NotFinite { name: "stop_time", .. })));
        assert!(matches!(TimeGrid::new(1.0, 0.0, 0.1), Err(TimeGridError::StopBeforeStart { .. })));
        assert!(matches!(TimeGrid::new(0.0, 1e9, 1e-9), Err(TimeGridError::TooManySteps { .. })));
    }

    #[test]
    fn python_isclose() {
        assert!(is_close(1.0, 1.0 + 1e-10));
        assert!(!is_close(1.0, 1.0 + 1e-8));
        assert!(!is_close(0.0, 1e-300));
        assert!(is_close(f64::INFINITY, f64::INFINITY));
        assert!(!is_close(f64::INFINITY, 1e308));
        assert!(!is_close(f64::NAN, f64::NAN));
    }
}
