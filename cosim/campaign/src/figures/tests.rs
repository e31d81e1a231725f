//! Figures of a small synthetic campaign: which files are written, and that they are PNGs of
//! the expected size.

use std::path::Path;

use super::*;
use crate::matrix::RunSpec;
use crate::results::RunResult;
use crane_metrics::decay::{decay_time_constant, Side};
use crane_metrics::run::{Evaluation, Signals};
use crane_metrics::{Trace, CAPTURE_RATE};

/// Metrics that vary with the test and variant; no θy decay anywhere.
fn metrics(number: u16, variant: Variant) -> Metrics {
    let k = f64::from(number) + f64::from(variant.number()) / 10.0;
    Metrics {
        tau_theta_x: Some(10.0 + k),
        tau_theta_y: None,
        tau_height: Some(5.0 + k / 2.0),
        distance: 0.1 * k,
        ellipsoid_volume: Some(1e-8 * k.powi(3)),
        rmse: 1e-3 * k,
        ..Metrics::default()
    }
}

fn result(number: u16, variant: Variant, metrics: Option<Metrics>) -> RunResult {
    let run = RunSpec::new(matrix::tests()[number as usize - 1], variant);
    let error = metrics.is_none().then(|| "synthetic failure".to_string());
    RunResult { id: run.id(), run, metrics, error, simulated_time: 130.0, wall_time: 1.0 }
}

/// A free swing released at −23°: θ = −θ0·e^(−t/τ)·cos ωt over 120 s at 30 Hz, with the load
/// on a 0.7 m cable and a stretch of missing (NaN) samples.
fn swing() -> Evaluation {
    let (theta0, tau, omega, lp) = (23f64.to_radians(), 60.0, 3.74, 0.7);
    let times: Vec<f64> = (0..=3600).map(|k| k as f64 / CAPTURE_RATE).collect();
    let mut theta_x: Vec<f64> = times.iter().map(|t| -theta0 * (-t / tau).exp() * (omega * t).cos()).collect();
    theta_x[1000..1010].fill(f64::NAN);
    let theta_y = vec![0.0; times.len()];
    let height: Vec<f64> = theta_x.iter().map(|th| lp * (1.0 - th.cos())).collect();
    let points = theta_x.iter().zip(&height).map(|(th, h)| [lp * th.sin(), 0.0, -h]).collect();
    let load = Trace { times: times.iter().map(|t| t + 10.0).collect(), points };
    let setpoint = Trace { times: load.times.clone(), points: vec![[0.0; 3]; times.len()] };
    let fit_theta_x = decay_time_constant(&times, &theta_x, Side::Positive, 0.01, 10);
    let fit_height = decay_time_constant(&times, &height, Side::Positive, 5e-4, 10);
    assert!(fit_theta_x.is_some() && fit_height.is_some());
    let signals = Signals { times, height, theta_x, theta_y, load, setpoint };
    Evaluation { metrics: metrics(20, Variant::Truth), signals, fit_theta_x, fit_theta_y: None, fit_height }
}

fn campaign(results: Vec<RunResult>, detailed: Vec<(String, Evaluation)>) -> Campaign {
    Campaign { results, detailed, wall_time: 1.0, jobs: 1, start: Default::default(), system: Default::default() }
}

/// Tests 20, 60, 84, 92 in both variants (092-2 failed), and the detailed response of 020-1.
fn small_campaign() -> Campaign {
    let mut results = Vec::new();
    for number in [20, 60, 84, 92] {
        for variant in Variant::BOTH {
            let failed = number == 92 && variant == Variant::Sensors;
            results.push(result(number, variant, (!failed).then(|| metrics(number, variant))));
        }
    }
    campaign(results, vec![("020-1".into(), swing())])
}

/// The (width, height) of the PNG at `path`, after checking its signature and IHDR chunk.
fn png_size(path: &Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert!(bytes.len() > 24 && bytes.starts_with(b"\x89PNG\r\n\x1a\n"), "{} is not a PNG", path.display());
    assert_eq!(&bytes[12..16], b"IHDR", "{}", path.display());
    let word = |at: usize| u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
    (word(16), word(20))
}

fn names(written: &[String]) -> Vec<&str> {
    let mut names: Vec<&str> = written.iter().map(String::as_str).collect();
    names.sort_unstable();
    names
}

/// Draws `campaign` with and without text (the fallback without a font), checks both give the
/// same files, and returns their names.
fn draw_both_ways(campaign: &Campaign) -> Vec<String> {
    let (plain, full) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let without_text = draw_with(plain.path(), campaign, false).unwrap();
    let with_text = draw_all(full.path(), campaign).unwrap();
    assert_eq!(names(&without_text), names(&with_text));
    for (dir, written) in [(plain.path(), &without_text), (full.path(), &with_text)] {
        for name in written {
            let expected = if name.contains("response") {
                response::SIZE
            } else if name.contains("7_1") || name.contains("7_20") {
                (1600, 600)
            } else {
                (1000, 600)
            };
            assert_eq!(png_size(&dir.join(name)), expected, "{name}");
        }
        let on_disk = std::fs::read_dir(dir.join(FOLDER)).unwrap().count();
        assert_eq!(on_disk, written.len(), "only the listed files are written");
    }
    with_text
}

#[test]
fn a_small_campaign_draws_the_figures_it_has_data_for() {
    let written = draw_both_ways(&small_campaign());
    assert_eq!(
        names(&written),
        [
            "figures/fig_7_16_tau_theta_x.png",
            "figures/fig_7_18_tau_height.png",
            "figures/fig_7_19_distance.png",
            "figures/fig_7_20_rmse.png",
            "figures/fig_7_23_distance.png",
            "figures/fig_7_23_ellipsoid_volume.png",
            "figures/fig_7_23_rmse.png",
            "figures/response_020-1.png",
        ],
        "no θy decay (7.17), no ship-motion (7.22) or variable set-point (7.25) runs"
    );
}

#[test]
fn a_campaign_with_only_a_few_tests_draws_only_their_figures() {
    // One compensated natural-frequency run, with an ellipsoid of zero volume (nothing for the
    // log axis) but a distance and an RMSE.
    let zero = Metrics { ellipsoid_volume: Some(0.0), ..metrics(92, Variant::Sensors) };
    let written = draw_both_ways(&campaign(vec![result(92, Variant::Sensors, Some(zero))], Vec::new()));
    assert_eq!(names(&written), ["figures/fig_7_23_distance.png", "figures/fig_7_23_rmse.png"]);
    // Nothing but failures: no figures, and no error.
    let failed = campaign(vec![result(97, Variant::Truth, None), result(101, Variant::Truth, None)], Vec::new());
    assert!(draw_both_ways(&failed).is_empty());
}

#[test]
fn the_series_pair_each_test_with_its_compensated_twin_in_both_variants() {
    let tests = matrix::tests();
    let pairs = pairs(&tests, &(84..=88));
    assert_eq!(
        pairs.iter().map(|(r, t)| (r.number, t.map(|t| t.number))).collect::<Vec<_>>(),
        (84..=88).map(|n| (n, Some(n + 8))).collect::<Vec<_>>()
    );
    assert_eq!(group_label(pairs[1].0, Scale::Test), "wn(0.40 m)");
    assert_eq!(group_label(&tests[0], Scale::Test), "400 / -8.5");
    assert_eq!(group_label(&tests[39], Scale::Full), "25000 / 24");
    let campaign = small_campaign();
    assert_eq!(variants_run(&campaign), Variant::BOTH);
    let series = series(&pairs, &metrics_by_run(&campaign), &variants_run(&campaign), MetricId::Rmse);
    let labels: Vec<&str> = series.iter().map(|(l, _)| l.as_str()).collect();
    assert_eq!(labels, ["No compensation (1)", "No compensation (2)", "Compensation (1)", "Compensation (2)"]);
    // 084 in both variants, 092-1; 092-2 failed; no other test ran.
    // RMSE in mm: 1e-3·k m, k = test + variant/10.
    let first: Vec<Option<f64>> = series.iter().map(|(_, v)| v[0]).collect();
    let expected = [Some(84.1), Some(84.2), Some(92.1), None];
    assert!(
        first.iter().zip(expected).all(|(a, b)| a.map(|a| (a - b.unwrap()).abs() < 1e-9).unwrap_or(b.is_none())),
        "{first:?}"
    );
    assert!(series.iter().all(|(_, v)| v.len() == 5 && v[1..].iter().all(Option::is_none)));
}

#[test]
fn a_campaign_with_variant_3_gets_its_series_beside_the_thesis_two() {
    let mut campaign = small_campaign();
    campaign.results.push(result(92, Variant::Estimated, Some(metrics(92, Variant::Estimated))));
    assert_eq!(variants_run(&campaign), Variant::ALL);
    let tests = matrix::tests();
    let pairs = pairs(&tests, &(84..=88));
    let series = series(&pairs, &metrics_by_run(&campaign), &variants_run(&campaign), MetricId::Rmse);
    let labels: Vec<&str> = series.iter().map(|(l, _)| l.as_str()).collect();
    assert_eq!(
        labels,
        [
            "No compensation (1)",
            "No compensation (2)",
            "No compensation (3)",
            "Compensation (1)",
            "Compensation (2)",
            "Compensation (3)"
        ]
    );
    // 084-3 did not run; 092-3's RMSE is 92.3 mm (1e-3·k m, k = test + variant/10).
    assert_eq!(series[2].1[0], None);
    assert!(series[5].1[0].is_some_and(|v| (v - 92.3).abs() < 1e-9), "{series:?}");
}

#[test]
fn a_bar_chart_without_any_value_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("empty.png");
    let groups = vec!["a".to_string(), "b".to_string()];
    let series = vec![("s".to_string(), vec![None, Some(-1.0)])];
    assert!(!bar_chart(&path, "t", "y", &groups, &series, true).unwrap());
    assert!(!path.exists());
    assert!(bar_chart(&path, "t", "y", &groups, &series, false).unwrap());
    assert_eq!(png_size(&path), (1000, 600));
}

#[test]
fn every_compared_metric_has_a_bar_chart_named_after_it() {
    for id in MetricId::compared() {
        assert!(COMPARISONS.iter().flat_map(|c| c.charts).any(|c| c.metric == id), "no figure draws {id}");
    }
    let files: Vec<String> = COMPARISONS.iter().flat_map(|c| c.charts).map(Chart::file).collect();
    assert_eq!(files[0], "fig_7_16_tau_theta_x");
    assert_eq!(files[5..8], ["fig_7_22_ellipsoid_volume", "fig_7_22_distance", "fig_7_22_rmse"]);
    assert_eq!(files.last().map(String::as_str), Some("fig_7_25_rmse"));
}
