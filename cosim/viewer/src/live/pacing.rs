//! Real-time pacing with absolute deadlines, and how far each step's completion is from its
//! deadline.

use std::time::{Duration, Instant};

use serde::Serialize;

/// How long before a deadline the loop stops sleeping and spins: the scheduler may wake a
/// sleeping thread this late, a spinning one sees the deadline to the microsecond.
const SPIN_MARGIN: Duration = Duration::from_millis(1);

/// The wall-clock deadlines of a run's steps: step k completes at `origin + (k − k0) · period`,
/// with `period` = step size / speed. Absolute deadlines keep errors from adding up.
#[derive(Debug, Clone, Copy)]
pub struct Clock {
    origin: Instant,
    k0: u64,
    period: Duration,
}

impl Clock {
    /// Deadlines for steps after `k0`, which completes now; `step` (s) of simulated time take
    /// `step / speed` of wall time.
    pub fn start(k0: u64, step: f64, speed: f64) -> Clock {
        Clock { origin: Instant::now(), k0, period: Duration::from_secs_f64(step / speed) }
    }

    /// When step `k` must complete.
    pub fn deadline(&self, k: u64) -> Instant {
        self.origin + self.period * u32::try_from(k.saturating_sub(self.k0)).unwrap_or(u32::MAX)
    }

    /// Waits for `deadline` (sleeping, then spinning for the last [`SPIN_MARGIN`]) and returns
    /// how late the wait ended (s): ≥ 0, and large when the step itself overran its deadline.
    pub fn wait(deadline: Instant) -> f64 {
        if let Some(sleep) = deadline.checked_duration_since(Instant::now() + SPIN_MARGIN) {
            std::thread::sleep(sleep);
        }
        while Instant::now() < deadline {
            std::hint::spin_loop();
        }
        Instant::now().duration_since(deadline).as_secs_f64()
    }
}

/// Asks the scheduler to run the calling thread before ordinary ones (Linux SCHED_FIFO, a low
/// real-time priority): on a machine busy with other work, an ordinary thread that wakes for
/// its deadline may wait for a CPU for milliseconds. Returns whether it was granted (it needs
/// root or CAP_SYS_NICE); the thread sleeps between steps, so it leaves the CPUs to others.
pub fn request_realtime() -> bool {
    #[cfg(target_os = "linux")]
    {
        let parameters = libc::sched_param { sched_priority: 10 };
        // SAFETY: sched_setscheduler reads the parameters it is given; 0 is the calling thread.
        unsafe { libc::sched_setscheduler(0, libc::SCHED_FIFO, &parameters) == 0 }
    }
    #[cfg(not(target_os = "linux"))]
    {
        false
    }
}

/// How far steps completed from their deadlines (ms).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Pacing {
    /// Steps measured.
    pub steps: usize,
    /// Simulated seconds per wall-clock second asked for.
    pub speed: f64,
    /// Whether the simulation thread ran with real-time priority (`request_realtime`).
    pub realtime: bool,
    /// Largest completion after a deadline (ms).
    pub max_ms: f64,
    /// 99th percentile of the completions after their deadlines (ms).
    pub p99_ms: f64,
    /// Mean completion after the deadlines (ms).
    pub mean_ms: f64,
    /// Steps that completed more than 1 ms after their deadline.
    pub late_over_1ms: usize,
}

impl Pacing {
    /// The statistics of the deviations `late` (s).
    pub fn of(late: &[f64], speed: f64, realtime: bool) -> Pacing {
        let mut ms: Vec<f64> = late.iter().map(|s| s * 1e3).collect();
        ms.sort_by(f64::total_cmp);
        let p99 = ms.get(((ms.len() as f64 * 0.99).ceil() as usize).saturating_sub(1)).copied();
        Pacing {
            steps: ms.len(),
            speed,
            realtime,
            max_ms: ms.last().copied().unwrap_or(0.0),
            p99_ms: p99.unwrap_or(0.0),
            mean_ms: if ms.is_empty() { 0.0 } else { ms.iter().sum::<f64>() / ms.len() as f64 },
            late_over_1ms: ms.iter().filter(|&&d| d > 1.0).count(),
        }
    }
}

impl std::fmt::Display for Pacing {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "pacing: {} steps at {}x real time ({} scheduling); completion after the deadline: max {:.3} ms, p99 {:.3} ms, \
             mean {:.3} ms; {} steps more than 1 ms late",
            self.steps,
            self.speed,
            if self.realtime { "real-time" } else { "ordinary" },
            self.max_ms, self.p99_ms, self.mean_ms, self.late_over_1ms
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_the_deviations() {
        let late: Vec<f64> = (1..=200).map(|i| f64::from(i) * 1e-5).collect(); // 0.01 … 2 ms
        let pacing = Pacing::of(&late, 1.0, false);
        assert_eq!(pacing.steps, 200);
        assert!((pacing.max_ms - 2.0).abs() < 1e-12);
        assert!((pacing.p99_ms - 1.98).abs() < 1e-12, "{}", pacing.p99_ms);
        assert!((pacing.mean_ms - 1.005).abs() < 1e-12);
        assert_eq!(pacing.late_over_1ms, 100);
    }

    #[test]
    fn deadlines_are_absolute_from_the_anchor_step() {
        let clock = Clock::start(100, 0.01, 2.0);
        assert_eq!(clock.deadline(104) - clock.deadline(100), Duration::from_millis(20));
        assert_eq!(clock.deadline(90), clock.deadline(100));
    }
}
