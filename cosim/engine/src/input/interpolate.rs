//! Sampling an input table at a communication point; values exactly as
//! FMPy's `fmpy.simulation.Input.interpolate` (FMPy 0.3.x) computes them.
//! (Input derivatives are secants over the coming step, see
//! [`super::InputBinding::apply`].)
//!
//! * Before the first sample: the first value; after the last: the last
//!   value (a single-row table is constant).
//! * Between samples `t0 < t < t1`: `w0 = (t1 − t)/(t1 − t0)`, `w1 = 1 − w0`,
//!   value `w0·v0 + w1·v1` (same operations in the same order, so the results
//!   are bit-identical).
//! * At a repeated time (a discontinuity, compared with Python's
//!   `math.isclose`): before the event the value at the first of the equal
//!   samples; after the event the value at the last of them.
//! * Discrete signals (Integer, Boolean, Real with discrete variability) hold
//!   the value of the last sample at or before `t` ("after the event").
//!
//! FMPy samples with `after_event = false` during initialization and with
//! `after_event = true` before every `fmi2DoStep`.
//!
//! Unlike FMPy, the importer never adds communication points at input events:
//! discontinuities that do not lie on the grid are sampled where the grid
//! meets them.

use crate::time::is_close;

/// Where `time` falls in the table; the same for all columns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Segment {
    /// Value of row `index` (outside the table).
    Hold { index: usize },
    /// Value of row `index` (on a discontinuity).
    Event { index: usize },
    /// Linear interpolation between rows `i0` and `i0 + 1`.
    Between { i0: usize, w0: f64, w1: f64 },
}

/// Locates `time` (seconds) for continuous signals.
pub fn locate(times: &[f64], time: f64, after_event: bool) -> Segment {
    let n = times.len();
    if n < 2 {
        return Segment::Hold { index: 0 };
    }
    // numpy.searchsorted(t, time, side="left")
    let mut i0 = times.partition_point(|&t| t < time);
    if i0 == 0 {
        return Segment::Hold { index: 0 };
    }
    if i0 == n {
        return Segment::Hold { index: n - 1 };
    }
    if is_close(time, times[i0]) && i0 < n - 1 && is_close(times[i0], times[i0 + 1]) {
        if after_event {
            while i0 < n - 1 && is_close(times[i0], times[i0 + 1]) {
                i0 += 1;
            }
        }
        return Segment::Event { index: i0 };
    }
    let i0 = i0 - 1;
    let (t0, t1) = (times[i0], times[i0 + 1]);
    let w0 = (t1 - time) / (t1 - t0);
    let w1 = 1.0 - w0;
    Segment::Between { i0, w0, w1 }
}

impl Segment {
    /// The interpolated value of `column`.
    pub fn value(&self, column: &[f64]) -> f64 {
        match *self {
            Segment::Hold { index } | Segment::Event { index } => column[index],
            Segment::Between { i0, w0, w1 } => w0 * column[i0] + w1 * column[i0 + 1],
        }
    }
}

/// Row whose value a discrete signal has at `time`.
pub fn discrete_index(times: &[f64], time: f64, after_event: bool) -> usize {
    let n = times.len();
    if n < 2 {
        return 0;
    }
    let i0 = times.partition_point(|&t| t < time);
    if i0 == 0 {
        return 0;
    }
    if i0 == n {
        return n - 1;
    }
    let mut i = i0 - 1;
    if after_event {
        while i + 1 < n && (times[i + 1] < time || is_close(time, times[i + 1])) {
            i += 1;
        }
    }
    i
}

#[cfg(test)]
mod tests {
    use super::*;

    const T: [f64; 6] = [0.0, 1.0, 2.0, 2.0, 4.0, 4.0];
    const V: [f64; 6] = [0.0, 2.0, 3.0, 10.0, 6.0, -1.0];

    fn sample(time: f64, after_event: bool) -> f64 {
        locate(&T, time, after_event).value(&V)
    }

    #[test]
    fn linear_between_samples() {
        // Hand-computed: w0 = (1 - 0.25)/1 = 0.75, value 0.75·0 + 0.25·2 = 0.5.
        assert_eq!(sample(0.25, true), 0.5);
        // Between 1 and 2: w0 = 0.5, value 0.5·2 + 0.5·3 = 2.5.
        assert_eq!(sample(1.5, true), 2.5);
        // Exactly on a sample that is not an event: end of the previous segment.
        assert_eq!(sample(1.0, true), 2.0);
        // Between 2 (second row, 10) and 4 (first row, 6).
        assert_eq!(sample(3.0, true), 8.0);
    }

    #[test]
    fn holds_outside_the_table() {
        assert_eq!(sample(-1.0, true), 0.0);
        assert_eq!(sample(0.0, true), 0.0);
        assert_eq!(sample(5.0, true), -1.0);
        let single = locate(&[1.0], 3.0, true);
        assert_eq!(single.value(&[7.0]), 7.0);
    }

    #[test]
    fn discontinuities() {
        // At t = 2 before the event: value 3 (first of the equal samples).
        assert_eq!(sample(2.0, false), 3.0);
        // After the event: value 10.
        assert_eq!(sample(2.0, true), 10.0);
        // Event at the end of the table: last value after the event.
        assert_eq!(sample(4.0, true), -1.0);
        assert_eq!(sample(4.0, false), 6.0);
        // Times within Python's isclose tolerance count as equal.
        assert_eq!(sample(2.0 - 1e-12, true), 10.0);
        assert_eq!(sample(2.0 - 1e-12, false), 3.0);
    }

    #[test]
    fn discrete_hold() {
        assert_eq!(discrete_index(&T, -1.0, true), 0);
        assert_eq!(discrete_index(&T, 0.5, true), 0);
        assert_eq!(discrete_index(&T, 1.0, true), 1);
        assert_eq!(discrete_index(&T, 1.0, false), 0);
        assert_eq!(discrete_index(&T, 2.0, true), 3);
        assert_eq!(discrete_index(&T, 3.0, true), 3);
        assert_eq!(discrete_index(&T, 9.0, true), 5);
        assert_eq!(discrete_index(&[2.0], 0.0, true), 0);
    }

    #[test]
    fn bitwise_identical_arithmetic() {
        let times = [0.0, 0.1, 0.35];
        let values = [0.3, -0.7, 1.1];
        let t = 0.2;
        let segment = locate(&times, t, true);
        let (t0, t1, v0, v1) = (0.1f64, 0.35f64, -0.7f64, 1.1f64);
        let w0 = (t1 - t) / (t1 - t0);
        let w1 = 1.0 - w0;
        assert_eq!(segment.value(&values).to_bits(), (w0 * v0 + w1 * v1).to_bits());
    }
}
