//! Performance metrics of a recorded load trajectory (thesis §7.2.2), computed from a results
//! table: the load's world position resampled at 30 Hz (the thesis' motion-capture rate).
//!
//! Positions are in metres in the world frame W; times in seconds.
//!
//! This crate holds the traces, distance, RMSE and the settling comparison of `crane-cosim
//! compare` (here), and in modules the remaining §7.2 metrics: [`peaks`] and [`decay`] (time
//! constants of the height and the swing angles), [`mod@ellipsoid`] (the 95 % ellipsoid volume)
//! and [`change`] (eq. 7.1's percentage change, cable angles from positions); [`catalogue`] names,
//! titles and units every metric once; [`run`] computes all of them for one run's window. It does
//! not know the thesis' test matrix, scales or reports (`crane-campaign`) nor studies
//! (`cosim-studies`): both evaluate their runs with it.

pub mod catalogue;
pub mod change;
pub mod decay;
pub mod ellipsoid;
pub mod peaks;
pub mod run;

pub use catalogue::{MetricId, MetricInfo, CATALOGUE};
pub use change::{cable_angles, percent_change};
pub use decay::{decay_time_constant, fit_exponential, DecayFit, ExponentialFit, Side};
pub use ellipsoid::{ellipsoid, Ellipsoid};
pub use peaks::{find_peaks, interpolate_peak, prominence};

use cosim_engine::table::SignalTable;
use crane_names::TEST_SCALE;

/// The thesis' motion-capture rate (Hz).
pub const CAPTURE_RATE: f64 = 30.0;
/// Frame-to-frame moves at or below this (m) are measurement noise (3 mm at 30 Hz = 90 mm/s).
pub const DISTANCE_THRESHOLD: f64 = 0.003;

/// A load-position trace: sample times and positions.
#[derive(Debug, Clone, PartialEq)]
pub struct Trace {
    /// Sample times (s).
    pub times: Vec<f64>,
    /// Positions (m), one per sample.
    pub points: Vec<[f64; 3]>,
}

impl Trace {
    /// The columns `<prefix>x`, `<prefix>y`, `<prefix>z` of a results table.
    pub fn from_table(table: &SignalTable, prefix: &str) -> Result<Trace, String> {
        let column = |axis: &str| {
            let name = format!("{prefix}{axis}");
            table.column(&name).map(|c| &table.columns[c]).ok_or_else(|| no_column(table, &name))
        };
        let (x, y, z) = (column("x")?, column("y")?, column("z")?);
        let points = (0..table.times.len()).map(|i| [x[i], y[i], z[i]]).collect();
        Ok(Trace { times: table.times.clone(), points })
    }

    /// Linear interpolation at `rate` Hz over [from, to] (s).
    pub fn resample(&self, rate: f64, from: f64, to: f64) -> Trace {
        let n = ((to - from) * rate).floor() as usize + 1;
        let times: Vec<f64> = (0..n).map(|k| from + k as f64 / rate).collect();
        let points = times.iter().map(|&t| self.at(t)).collect();
        Trace { times, points }
    }

    fn at(&self, t: f64) -> [f64; 3] {
        let i = self.times.partition_point(|&s| s <= t);
        if i == 0 {
            return self.points[0];
        }
        if i >= self.times.len() {
            return self.points[self.times.len() - 1];
        }
        let (t0, t1) = (self.times[i - 1], self.times[i]);
        let w = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
        let (a, b) = (self.points[i - 1], self.points[i]);
        [0, 1, 2].map(|k| a[k] + w * (b[k] - a[k]))
    }
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// Distance travelled (m): the sum of frame-to-frame distances above `threshold` (§7.2.2).
pub fn distance_travelled(trace: &Trace, threshold: f64) -> f64 {
    // A fold from +0.0: an empty f64 `sum()` is −0.0, which would print as "-0".
    trace.points.windows(2).map(|w| distance(&w[0], &w[1])).filter(|d| *d > threshold).fold(0.0, |a, d| a + d)
}

/// Root-mean-square Euclidean distance (m) of the trace from `target` (same length).
pub fn rmse(trace: &Trace, target: &[[f64; 3]]) -> f64 {
    let sum: f64 = trace.points.iter().zip(target).map(|(p, q)| distance(p, q).powi(2)).sum();
    (sum / trace.points.len() as f64).sqrt()
}

/// Time (s, from the first sample) after which the signal's envelope stays within ±`band` to the
/// end; `None` if it never settles.
///
/// The envelope of a swing is the sequence of its peaks of |v|, one every half swing. A swing that
/// is crossing zero at the end of the record is inside the band between two peaks outside it, so
/// samples inside the band settle nothing until the next peak is due: when the last peak of |v|
/// lies outside the band and less than the time between the last two such peaks has passed since
/// it, the envelope has not been seen to come down and the signal has not settled.
pub fn settling_time(times: &[f64], values: &[f64], band: f64) -> Option<f64> {
    let Some(last_outside) = values.iter().rposition(|v| v.abs() > band) else {
        return Some(0.0);
    };
    let end = *times.last()?;
    if last_outside + 1 == times.len() || !envelope_inside(times, values, band, end) {
        return None;
    }
    Some(times[last_outside + 1] - times[0])
}

/// Whether the last peak of |v| is inside the band, or one more half swing has passed since the
/// last peak outside it without another one ([`settling_time`]).
fn envelope_inside(times: &[f64], values: &[f64], band: f64, end: f64) -> bool {
    let magnitude = |i: usize| values[i].abs();
    let peaks: Vec<usize> = (1..values.len().saturating_sub(1))
        .filter(|&i| magnitude(i) >= magnitude(i - 1) && magnitude(i) > magnitude(i + 1))
        .collect();
    match peaks.as_slice() {
        [.., last] if magnitude(*last) <= band => true,
        [.., before, last] => end - times[*last] >= times[*last] - times[*before],
        _ => true,
    }
}

/// Column names of a closed-loop results CSV (systems/closed_loop.json).
pub const LOAD_PREFIX: &str = TEST_SCALE.load.prefix;
pub const SETPOINT_PREFIX: &str = TEST_SCALE.setpoint.prefix;
pub const ANGLES: [&str; 2] = TEST_SCALE.theta;
/// A swing has settled when both angles stay within ±2°.
pub const SETTLED_BAND: f64 = 2.0 * std::f64::consts::PI / 180.0;
/// The final swing is the largest over this last part of the window (s).
pub const FINAL_SWING_WINDOW: f64 = 10.0;

/// Where the comparison's set-point comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// Columns `<prefix>x`, `<prefix>y`, `<prefix>z` (m), e.g. the controller's set-point.
    Columns(String),
    /// A fixed point (m).
    Point([f64; 3]),
}

/// Where the comparison's swing angles come from.
#[derive(Debug, Clone, PartialEq)]
pub enum Angles {
    /// Columns θx, θy (rad).
    Columns([String; 2]),
    /// The cable direction from the crane tip (columns `<prefix>x`, `<prefix>y`, `<prefix>z`, m)
    /// to the load position ([`cable_angles`]), for results that record positions only (the
    /// campaign's).
    FromTip(String),
}

/// Which columns [`run_metrics`] reads, and its settling band.
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The two swing angles.
    pub angles: Angles,
    /// Prefix of the load position columns `<prefix>x`, `<prefix>y`, `<prefix>z` (m).
    pub position: String,
    /// The set-point the RMSE is taken from (none: no RMSE).
    pub target: Option<Target>,
    /// Settled means both angles stay within ±band (rad).
    pub band: f64,
}

impl Default for Comparison {
    /// The closed loop's columns (systems/closed_loop.json) and ±2°.
    fn default() -> Self {
        Comparison {
            angles: Angles::Columns(ANGLES.map(String::from)),
            position: LOAD_PREFIX.into(),
            target: Some(Target::Columns(SETPOINT_PREFIX.into())),
            band: SETTLED_BAND,
        }
    }
}

/// The demo's comparison of one run, over the time after `from` (the release).
#[derive(Debug, Clone, PartialEq)]
pub struct RunMetrics {
    /// Time after `from` (s) until both swing angles stay within the band (None: never).
    pub settling: Option<f64>,
    /// Distance travelled by the load (m), 30 Hz, 3 mm threshold.
    pub distance: f64,
    /// RMSE of the load position from the target (m), 30 Hz; None without a target.
    pub rmse: Option<f64>,
    /// Largest |θx|, |θy| over the last [`FINAL_SWING_WINDOW`] of the window (rad).
    pub final_swing: f64,
}

/// Metrics of a results table over [from, end]; a window starting at or after the last sample
/// is refused.
pub fn run_metrics(table: &SignalTable, from: f64, comparison: &Comparison) -> Result<RunMetrics, String> {
    let end = *table.times.last().ok_or("the results table is empty")?;
    if !(from < end) {
        return Err(format!("the window starts at {from} s, not before the last sample at {end} s"));
    }
    let load = Trace::from_table(table, &comparison.position)?.resample(CAPTURE_RATE, from, end);
    let rmse = match &comparison.target {
        None => None,
        Some(Target::Columns(prefix)) => {
            let target = Trace::from_table(table, prefix)?.resample(CAPTURE_RATE, from, end);
            Some(rmse(&load, &target.points))
        }
        Some(Target::Point(point)) => Some(rmse(&load, &vec![*point; load.points.len()])),
    };
    let first = table.times.partition_point(|&t| t < from);
    let swing = swing(table, comparison, first)?;
    let last = table.times.partition_point(|&t| t < end - FINAL_SWING_WINDOW).max(first);
    Ok(RunMetrics {
        settling: settling_time(&table.times[first..], &swing, comparison.band),
        distance: distance_travelled(&load, DISTANCE_THRESHOLD),
        rmse,
        final_swing: swing[last - first..].iter().copied().fold(0.0, f64::max),
    })
}

/// max(|θx|, |θy|) (rad) at each sample from index `first` on.
fn swing(table: &SignalTable, comparison: &Comparison, first: usize) -> Result<Vec<f64>, String> {
    let rows = first..table.times.len();
    match &comparison.angles {
        Angles::Columns(names) => {
            let [x, y] = [&names[0], &names[1]]
                .map(|name| table.column(name).map(|c| &table.columns[c]).ok_or_else(|| no_column(table, name)));
            let (x, y) = (x?, y?);
            Ok(rows.map(|i| x[i].abs().max(y[i].abs())).collect())
        }
        Angles::FromTip(prefix) => {
            let (load, tip) = (Trace::from_table(table, &comparison.position)?, Trace::from_table(table, prefix)?);
            Ok(rows
                .map(|i| {
                    let (x, y) = cable_angles(load.points[i], tip.points[i]);
                    x.abs().max(y.abs())
                })
                .collect())
        }
    }
}

fn no_column(table: &SignalTable, name: &str) -> String {
    format!("no column '{name}' (columns: {})", table.names.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize, step: [f64; 3]) -> Trace {
        Trace {
            times: (0..n).map(|k| k as f64 / CAPTURE_RATE).collect(),
            points: (0..n).map(|k| step.map(|s| s * k as f64)).collect(),
        }
    }

    #[test]
    fn distance_of_a_straight_path_of_known_length() {
        // 100 frames of (3, 4, 0) mm = 5 mm each: 99 moves, 0.495 m.
        let trace = line(100, [0.003, 0.004, 0.0]);
        assert!((distance_travelled(&trace, DISTANCE_THRESHOLD) - 0.495).abs() < 1e-12);
        // Moves of 2 mm are below the 3 mm threshold and count as noise.
        let still = distance_travelled(&line(100, [0.002, 0.0, 0.0]), DISTANCE_THRESHOLD);
        assert!(still == 0.0 && still.is_sign_positive(), "{still}");
    }

    #[test]
    fn rmse_of_a_constant_offset() {
        let trace = line(10, [0.0, 0.0, 0.0]);
        let target = vec![[0.0, 0.03, 0.04]; 10];
        assert!((rmse(&trace, &target) - 0.05).abs() < 1e-15);
    }

    #[test]
    fn resampling_interpolates_linearly() {
        let trace = Trace { times: vec![0.0, 1.0], points: vec![[0.0; 3], [3.0, 0.0, -3.0]] };
        let r = trace.resample(30.0, 0.0, 1.0);
        assert_eq!(r.times.len(), 31);
        assert!((r.points[10][0] - 1.0).abs() < 1e-12 && (r.points[10][2] + 1.0).abs() < 1e-12);
    }

    /// 10 s of a load at rest at (0, 0, 1) m with the angles given per sample (10 ms).
    fn resting_load(angle: impl Fn(f64) -> f64) -> SignalTable {
        let times: Vec<f64> = (0..=1000).map(|k| k as f64 * 0.01).collect();
        let names = ["a.x", "a.y", "a.z", "p.x", "p.y", "p.z", "th.x", "th.y"].map(String::from).to_vec();
        let constant = |v: f64| vec![v; times.len()];
        let columns = vec![
            constant(0.0),
            constant(0.0),
            constant(1.0),
            constant(0.0),
            constant(0.0),
            constant(1.0),
            times.iter().map(|&t| angle(t)).collect(),
            constant(0.0),
        ];
        SignalTable { file: "rest.csv".into(), names, times, columns }
    }

    fn named(target: Option<Target>) -> Comparison {
        let angles = Angles::Columns(["th.x".into(), "th.y".into()]);
        Comparison { angles, position: "p.".into(), target, band: SETTLED_BAND }
    }

    #[test]
    fn metrics_of_named_columns_and_a_fixed_target() {
        // A swing of 0.1 rad that stops at t = 4 s.
        let table = resting_load(|t| if t < 4.0 { 0.1 } else { 0.0 });
        let m = run_metrics(&table, 1.0, &named(Some(Target::Point([0.03, 0.0, 1.04])))).unwrap();
        assert!((m.rmse.unwrap() - 0.05).abs() < 1e-15, "{m:?}");
        assert_eq!(m.settling, Some(3.0));
        assert_eq!(m.distance, 0.0);
        assert_eq!(run_metrics(&table, 0.0, &named(Some(Target::Columns("a.".into())))).unwrap().rmse, Some(0.0));
        assert_eq!(run_metrics(&table, 0.0, &named(None)).unwrap().rmse, None);
    }

    #[test]
    fn angles_from_the_crane_tip() {
        // The load 1 m below a tip at the origin, then swung to θx = 0.1 rad from t = 5 s.
        let mut table = resting_load(|_| 0.0);
        for (i, &t) in table.times.clone().iter().enumerate() {
            let theta: f64 = if t < 5.0 { 0.0 } else { 0.1 };
            (table.columns[4][i], table.columns[5][i]) = (-theta.sin(), theta.cos());
        }
        let comparison = Comparison { angles: Angles::FromTip("a.".into()), ..named(None) };
        // a.* is (0, 0, 1): shift the tip to the origin.
        table.columns[2] = vec![0.0; table.times.len()];
        let m = run_metrics(&table, 0.0, &comparison).unwrap();
        assert!((m.final_swing - 0.1).abs() < 1e-15, "{m:?}");
        assert_eq!(m.settling, None);
    }

    #[test]
    fn a_window_past_the_data_is_refused() {
        let table = resting_load(|_| 0.0);
        let error = run_metrics(&table, 10.0, &named(None)).unwrap_err();
        assert_eq!(error, "the window starts at 10 s, not before the last sample at 10 s");
        let error = run_metrics(&table, 0.0, &Comparison::default()).unwrap_err();
        assert!(error.starts_with("no column 'pendulum.load.x' (columns: a.x, a.y"), "{error}");
    }

    #[test]
    fn settling_of_a_decaying_oscillation() {
        // e^(−t/2) cos(2πt) leaves the ±0.1 band for the last time before t = 2 ln 10 ≈ 4.6 s.
        let times: Vec<f64> = (0..2000).map(|k| k as f64 * 0.01).collect();
        let values: Vec<f64> = times.iter().map(|t| (-t / 2.0).exp() * (std::f64::consts::TAU * t).cos()).collect();
        let settled = settling_time(&times, &values, 0.1).unwrap();
        assert!(settled > 3.9 && settled < 4.61, "{settled}");
        assert_eq!(settling_time(&times, &vec![1.0; 2000], 0.1), None);
    }

    #[test]
    fn a_swing_crossing_zero_at_the_end_has_not_settled() {
        // e^(−t/2) cos(2πt) up to t = 2.25 s, where it crosses zero with an envelope of
        // e^(−1.125) = 0.32, outside the ±0.1 band: the last few samples are inside the band.
        let times: Vec<f64> = (0..=225).map(|k| k as f64 * 0.01).collect();
        let values: Vec<f64> = times.iter().map(|t| (-t / 2.0).exp() * (std::f64::consts::TAU * t).cos()).collect();
        assert!(values.last().unwrap().abs() < 0.1);
        assert_eq!(settling_time(&times, &values, 0.1), None);
        // A decay with no swing settles when it enters the band, peak or not.
        let decay: Vec<f64> = times.iter().map(|t| (-2.0 * t).exp()).collect();
        let settled = settling_time(&times, &decay, 0.1).unwrap();
        assert!((settled - 10f64.ln() / 2.0).abs() < 0.011, "{settled}");
    }
}
