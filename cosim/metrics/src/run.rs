//! The §7.2.2 metrics of one run from its results table: the load's world position (and the
//! crane tip, for the cable angles) resampled at 30 Hz over a window (a campaign test's time
//! after the release, a study's metric window), the decay fits behind the time constants.
//!
//! Conventions: W is North-East-Down, so the height above the set-point is `z_sp − z`; angles
//! are the pendulum's θx, θy (X-Y sequence) recovered from the cable direction tip → load.

use serde::Serialize;

use cosim_engine::table::SignalTable;
use crane_names::{CraneNames, Xyz, TEST_SCALE};

use crate::decay::{decay_time_constant, DecayFit, Side};
use crate::ellipsoid::ellipsoid;
use crate::{cable_angles, distance_travelled, rmse, MetricId, Trace, CAPTURE_RATE, DISTANCE_THRESHOLD};

/// Standard gravity (m/s²), for the natural frequency ω = √(g/l_p).
pub const G: f64 = 9.80665;

/// Crane tip columns of the test-scale closed-loop results.
pub const TIP_PREFIX: &str = TEST_SCALE.tip.prefix;
/// The variables a test-scale run records (every communication step): load, tip and set-point
/// (a full-scale campaign run records the same three of its crane).
pub const RECORDED: [&str; 9] = TEST_SCALE_TRACES.names();

/// Smallest angle peak that counts as a swing worth fitting (rad): the thesis fits no decay to
/// a response without "significant peak angles" (§7.2, Fig. 7.2's θy).
pub const MIN_ANGLE_PEAK: f64 = 0.25 * std::f64::consts::PI / 180.0;
/// Smallest height peak worth fitting (m).
pub const MIN_HEIGHT_PEAK: f64 = 0.0005;
/// Fraction of the points inside the ellipsoid (§7.2.2).
pub const ELLIPSOID_FRACTION: f64 = 0.95;

/// The §7.2.2 metrics of one run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, serde::Deserialize)]
pub struct Metrics {
    /// Time constants (s) of the exponential decay of the θx, θy and height peaks; `None`
    /// where no significant decaying peaks exist.
    pub tau_theta_x: Option<f64>,
    /// Decay time constant of the θy peaks (s), as `tau_theta_x`.
    pub tau_theta_y: Option<f64>,
    /// Decay time constant of the height peaks (s), as `tau_theta_x`.
    pub tau_height: Option<f64>,
    /// Distance travelled above the 3 mm frame-to-frame threshold (m).
    pub distance: f64,
    /// Volume of the ellipsoid holding 95 % of the load positions relative to the set-point (m³).
    pub ellipsoid_volume: Option<f64>,
    /// RMS Euclidean distance of the load from its set-point (m).
    pub rmse: f64,
    /// Largest height above the set-point (m) and largest |θx|, |θy| (rad) during the test.
    pub peak_height: f64,
    /// Largest |θx| during the test (rad).
    pub peak_theta_x: f64,
    /// Largest |θy| during the test (rad).
    pub peak_theta_y: f64,
}

impl Metrics {
    /// The value of the catalogue's metric `id` (SI unit of [`MetricId::info`]); `None` where
    /// the run has none.
    pub fn get(&self, id: MetricId) -> Option<f64> {
        match id {
            MetricId::TauThetaX => self.tau_theta_x,
            MetricId::TauThetaY => self.tau_theta_y,
            MetricId::TauHeight => self.tau_height,
            MetricId::Distance => Some(self.distance),
            MetricId::EllipsoidVolume => self.ellipsoid_volume,
            MetricId::Rmse => Some(self.rmse),
            MetricId::PeakHeight => Some(self.peak_height),
            MetricId::PeakThetaX => Some(self.peak_theta_x),
            MetricId::PeakThetaY => Some(self.peak_theta_y),
        }
    }
}

/// The 30 Hz signals a run's metrics come from (kept for the response plots).
#[derive(Debug, Clone)]
pub struct Signals {
    /// Time since release (s).
    pub times: Vec<f64>,
    /// Height of the load above its set-point (m).
    pub height: Vec<f64>,
    /// Swing angle θx (rad).
    pub theta_x: Vec<f64>,
    /// Swing angle θy (rad).
    pub theta_y: Vec<f64>,
    /// Load and set-point positions (m, W).
    pub load: Trace,
    /// The set-point's positions (m, W).
    pub setpoint: Trace,
}

/// Metrics with the fits behind them.
#[derive(Debug, Clone)]
pub struct Evaluation {
    /// The run's metrics.
    pub metrics: Metrics,
    /// The signals they come from.
    pub signals: Signals,
    /// The decay fit behind `tau_theta_x`, where there is one.
    pub fit_theta_x: Option<DecayFit>,
    /// The decay fit behind `tau_theta_y`, where there is one.
    pub fit_theta_y: Option<DecayFit>,
    /// The decay fit behind `tau_height`, where there is one.
    pub fit_height: Option<DecayFit>,
}

/// The metrics of the `signals` of a test with the pendulum length `lp` (m; it sets the
/// spacing of the peaks) released at the cable angles `theta0` (rad; they choose the side of
/// the peaks fitted, §7.2).
pub fn evaluate_signals(signals: Signals, lp: f64, theta0: [f64; 2]) -> Evaluation {
    let period = natural_period(lp);
    let samples = |fraction: f64| ((fraction * period * CAPTURE_RATE) as usize).max(1);
    let angle_fit = |values: &[f64], initial: f64| {
        decay_time_constant(&signals.times, values, swing_side(values, initial), MIN_ANGLE_PEAK, samples(0.6))
    };
    let fit_theta_x = angle_fit(&signals.theta_x, theta0[0]);
    let fit_theta_y = angle_fit(&signals.theta_y, theta0[1]);
    // The height peaks twice per swing period.
    let fit_height =
        decay_time_constant(&signals.times, &signals.height, Side::Positive, MIN_HEIGHT_PEAK, samples(0.3));
    let relative: Vec<[f64; 3]> =
        signals.load.points.iter().zip(&signals.setpoint.points).map(|(p, s)| [0, 1, 2].map(|k| p[k] - s[k])).collect();
    let largest = |v: &[f64]| v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let metrics = Metrics {
        tau_theta_x: fit_theta_x.as_ref().map(|f| f.fit.tau),
        tau_theta_y: fit_theta_y.as_ref().map(|f| f.fit.tau),
        tau_height: fit_height.as_ref().map(|f| f.fit.tau),
        distance: distance_travelled(&signals.load, DISTANCE_THRESHOLD),
        ellipsoid_volume: ellipsoid(&relative, ELLIPSOID_FRACTION).map(|e| e.volume),
        rmse: rmse(&signals.load, &signals.setpoint.points),
        peak_height: signals.height.iter().copied().fold(0.0, f64::max),
        peak_theta_x: largest(&signals.theta_x),
        peak_theta_y: largest(&signals.theta_y),
    };
    Evaluation { metrics, signals, fit_theta_x, fit_theta_y, fit_height }
}

/// The swing side whose peaks measure the decay (§7.2): opposite to a non-zero initial angle
/// (positive peaks for a negative θx0, negative for a positive θy0); for the off-axis angle
/// (initial 0), the side that swings furthest.
fn swing_side(values: &[f64], initial: f64) -> Side {
    let opposite_to = |v: f64| if v < 0.0 { Side::Positive } else { Side::Negative };
    if initial != 0.0 {
        return opposite_to(initial);
    }
    let high = values.iter().copied().fold(0.0, f64::max);
    let low = values.iter().copied().fold(0.0, f64::min);
    if high >= -low {
        Side::Positive
    } else {
        Side::Negative
    }
}

/// Small-angle period 2π√(l/g) (s) of a pendulum of length `lp` (m).
fn natural_period(lp: f64) -> f64 {
    std::f64::consts::TAU * (lp / G).sqrt()
}

/// The three position traces a run is evaluated from (W, m).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Traces {
    /// The load's position.
    pub load: Xyz,
    /// The crane tip's position.
    pub tip: Xyz,
    /// The load's set-point.
    pub setpoint: Xyz,
}

impl Traces {
    /// The load, tip and set-point of a closed loop's names.
    pub const fn of(names: &CraneNames) -> Traces {
        Traces { load: names.load, tip: names.tip, setpoint: names.setpoint }
    }

    /// The nine columns: load, tip and set-point, each x, y, z.
    pub const fn names(&self) -> [&'static str; 9] {
        let [l, t, s] = [self.load.axes, self.tip.axes, self.setpoint.axes];
        [l[0], l[1], l[2], t[0], t[1], t[2], s[0], s[1], s[2]]
    }
}

/// The test-scale closed loop's traces (systems/closed_loop.json).
pub const TEST_SCALE_TRACES: Traces = Traces::of(&TEST_SCALE);

/// The 30 Hz signals of `table` over [`from`, `to`] (s), times counted from `from` (the
/// release); an error if the table lacks a load, tip or set-point column or ends before `to`.
pub fn signals(table: &SignalTable, from: f64, to: f64) -> Result<Signals, String> {
    signals_of(table, &TEST_SCALE_TRACES, from, to)
}

/// [`signals`] from the columns `traces`.
pub fn signals_of(table: &SignalTable, traces: &Traces, from: f64, to: f64) -> Result<Signals, String> {
    let end = *table.times.last().ok_or("the results table is empty")?;
    if end < to - 1e-9 {
        return Err(format!("the results end at t = {end} s, before the end of the test at {to} s"));
    }
    let load = Trace::from_table(table, traces.load.prefix)?.resample(CAPTURE_RATE, from, to);
    let tip = Trace::from_table(table, traces.tip.prefix)?.resample(CAPTURE_RATE, from, to);
    let setpoint = Trace::from_table(table, traces.setpoint.prefix)?.resample(CAPTURE_RATE, from, to);
    let (theta_x, theta_y) = load.points.iter().zip(&tip.points).map(|(l, t)| cable_angles(*l, *t)).unzip();
    let height = load.points.iter().zip(&setpoint.points).map(|(l, s)| s[2] - l[2]).collect();
    let times = load.times.iter().map(|t| t - from).collect();
    Ok(Signals { times, height, theta_x, theta_y, load, setpoint })
}
