//! Sampled models: a fixed sample period independent of the communication step, and how close
//! two times must be to count as the same instant.
//!
//! A discrete controller samples at start + n·period (an integer count, so nothing drifts),
//! whatever step sizes the master chooses: `fmi2DoStep(t, h)` (or its FMI 3.0 counterpart)
//! processes every sample time in (t, t + h]. The outputs are held between samples, a zero-order
//! hold. The result is then independent of the master's step pattern as long as the inputs are
//! the same at the sample times.

use serde::{Deserialize, Serialize};

/// How far (s) a time given by the host may be from the instance's own value of it and still be
/// the same instant: 1e-9 relative absorbs the rounding of times accumulated step by step, but
/// never more than 1 µs, so that beyond t = 1000 s a communication point that is off by a real
/// amount is refused; and never less than 4 ulp of t, the rounding of one addition at large t.
pub fn time_tolerance(t: f64) -> f64 {
    (1e-9 * t.abs().max(1.0)).min(1e-6).max(4.0 * f64::EPSILON * t.abs())
}

/// The sample times of a sampled model: start + n·period, n = 0, 1, 2, …
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SampleClock {
    /// The sample period (s).
    pub period: f64,
    /// The time of sample 0 (s), the start time.
    start: f64,
    /// Samples taken after sample 0.
    samples: u64,
}

impl SampleClock {
    /// The sampled controllers' default period (s): 100 Hz, the myRIO's (thesis §6.1).
    pub const DEFAULT_PERIOD: f64 = 0.01;
    /// The sampled controllers' largest communication step (s): 100,000 samples at the default
    /// period.
    pub const MAX_STEP_SIZE: f64 = 1000.0;
    /// Most samples one step of a sampled controller processes (about half a second of work);
    /// more, e.g. a 1000 s step at the shortest period of 0.1 ms, are refused with an error.
    pub const MAX_SAMPLES_PER_STEP: u64 = 100_000;

    /// A clock with this period, started at t = 0 (restart it at initialization).
    pub const fn new(period: f64) -> SampleClock {
        SampleClock { period, start: 0.0, samples: 0 }
    }

    /// Starts counting again at `start` (sample 0's time); the model takes sample 0 itself.
    pub fn restart(&mut self, start: f64) {
        self.start = start;
        self.samples = 0;
    }

    /// Samples taken after sample 0 since the last restart.
    pub fn samples(&self) -> u64 {
        self.samples
    }

    /// Calls `sample(time)` for every sample time in (t, t + h], in order, up to
    /// `max_samples` of them; Err (and no sample taken) if the step spans more, and the first
    /// error `sample` returns.
    pub fn step(
        &mut self,
        t: f64,
        h: f64,
        max_samples: u64,
        mut sample: impl FnMut(f64) -> Result<(), String>,
    ) -> Result<(), String> {
        let end = t + h;
        // A sample time that lands on the step's end up to rounding belongs to this step.
        let tolerance = time_tolerance(end);
        // The samples due, counted before taking any: the work of one step is bounded, and at a
        // large t, where the period is below the resolution of t, the count is refused instead
        // of sampling forever at the same instant.
        let due = ((end + tolerance - self.start) / self.period).floor() - self.samples as f64;
        if !(due <= max_samples as f64) {
            return Err(format!(
                "a step to t = {end} s spans {due} samples of {} s; at most {max_samples} per step",
                self.period
            ));
        }
        // One more than counted, in case the count rounded down; the loop ends at the step's end.
        for _ in 0..=due as u64 + 1 {
            let next = self.start + (self.samples + 1) as f64 * self.period;
            if next > end + tolerance {
                break;
            }
            sample(next)?;
            self.samples += 1;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn times(clock: &mut SampleClock, t: f64, h: f64) -> Result<Vec<f64>, String> {
        let mut taken = Vec::new();
        clock.step(t, h, 1000, |time| {
            taken.push(time);
            Ok(())
        })?;
        Ok(taken)
    }

    #[test]
    fn samples_fall_on_the_period_whatever_the_steps() {
        let mut clock = SampleClock::new(0.01);
        clock.restart(1.0);
        assert_eq!(times(&mut clock, 1.0, 0.025).unwrap(), [1.01, 1.02]);
        // 1.03 lies in (1.025, 1.03] up to rounding of the step's end.
        assert_eq!(times(&mut clock, 1.025, 0.005).unwrap(), [1.03]);
        assert_eq!(times(&mut clock, 1.03, 0.001).unwrap(), Vec::<f64>::new());
        assert_eq!(clock.samples(), 3);
    }

    #[test]
    fn a_step_spanning_too_many_samples_is_refused_before_sampling() {
        let mut clock = SampleClock::new(1e-4);
        let message = times(&mut clock, 0.0, 1.0).unwrap_err();
        assert!(message.contains("spans 10000 samples of 0.0001 s; at most 1000 per step"), "{message}");
        assert_eq!(clock.samples(), 0);
    }
}
