//! The metrics of one campaign run (thesis §7.2.2) from its results table over the test proper,
//! i.e. the test's time after the release ([`RunSpec::test_time`], [`RunSpec::init_time`]),
//! from the columns of the run's scale; the metrics themselves are `crane_metrics::run`'s.

use cosim_engine::table::SignalTable;
use crane_metrics::run::{evaluate_signals, signals_of, Evaluation};

use crate::matrix::RunSpec;
use crate::scale::CampaignScale;

/// Evaluates a run's results table.
pub fn evaluate(run: &RunSpec, table: &SignalTable) -> Result<Evaluation, String> {
    let release = run.init_time();
    let signals = signals_of(table, &run.scale.traces(), release, release + run.test_time())?;
    Ok(evaluate_signals(signals, run.lp(), run.test.theta0_deg.map(f64::to_radians)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::{tests, Variant};
    use crane_metrics::run::{G, RECORDED};

    /// A results table of a load swinging below a fixed tip (l = 0.7 m, NED) with
    /// θx(t) = θ0·e^(−t/τ)·cos(ωt) after a release at 10 s (held before), θy = 0.
    fn free_swing(theta0: f64, tau: f64) -> SignalTable {
        let (lp, omega) = (0.7, (G / 0.7).sqrt());
        let tip = [0.003, -0.502, -0.153];
        let times: Vec<f64> = (0..=13_000).map(|k| k as f64 * 0.01).collect();
        let mut columns = vec![Vec::new(); 9];
        for &t in &times {
            let s = (t - INIT).max(0.0);
            let theta = theta0 * (-s / tau).exp() * (omega * s).cos();
            // Load = tip + l·(0, −sin θx, cos θx) for θy = 0 (X-Y sequence, z down).
            let load = [tip[0], tip[1] - lp * theta.sin(), tip[2] + lp * theta.cos()];
            let setpoint = [tip[0], tip[1], tip[2] + lp];
            for (k, v) in load.into_iter().chain(tip).chain(setpoint).enumerate() {
                columns[k].push(v);
            }
        }
        let names = RECORDED.iter().map(|s| s.to_string()).collect();
        SignalTable { file: "synthetic.csv".into(), names, times, columns }
    }

    const INIT: f64 = 10.0;

    #[test]
    fn a_synthetic_free_swing_gives_its_time_constants_from_the_opposite_peaks() {
        let run = RunSpec::new(tests()[19], Variant::Truth); // 020: 700 mm, θx0 = −23°
        let theta0 = (-23f64).to_radians();
        let e = evaluate(&run, &free_swing(theta0, 73.5)).unwrap();
        let m = e.metrics;
        // θx peaks on the positive side (opposite to the negative initial angle).
        assert!(e.fit_theta_x.as_ref().unwrap().peaks.iter().all(|(_, v)| *v > 0.0));
        assert!((m.tau_theta_x.unwrap() / 73.5 - 1.0).abs() < 1e-3, "{m:?}");
        assert_eq!(m.tau_theta_y, None, "no θy swing, no fit");
        // Height l(1 − cos θ) ≈ l θ²/2 decays with τ/2 (to the small-angle error).
        assert!((m.tau_height.unwrap() / 36.75 - 1.0).abs() < 0.02, "{m:?}");
        assert!((m.peak_theta_x - 23f64.to_radians()).abs() < 1e-3);
        assert!((m.peak_height - 0.7 * (1.0 - theta0.cos())).abs() < 1e-4);
        // The swing lies in the y-z plane: the ellipsoid is flat (volume 0).
        assert_eq!(m.ellipsoid_volume, Some(0.0));
        assert!(m.rmse > 0.05 && m.distance > 10.0);
    }

    #[test]
    fn results_that_end_before_the_test_does_are_an_error() {
        let mut table = free_swing(0.1, 10.0);
        table.times.truncate(5000);
        table.columns.iter_mut().for_each(|c| c.truncate(5000));
        let run = RunSpec::new(tests()[19], Variant::Truth);
        assert!(evaluate(&run, &table).unwrap_err().contains("before the end of the test"));
    }
}
