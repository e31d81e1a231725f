//! The shipped studies (`studies/*.json`), each reduced to a few short cases and run through
//! `crane-cosim sweep run` and `collect`: the linked, scaled and baseline start values must reach
//! the FMUs, which the asserted numbers show.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use std::collections::BTreeMap;
use std::path::Path;

use crane_metrics::change::percent_change;
use serde_json::{json, Value};

/// Writes `dir/study.json`: the shipped study `name` with `cases` cases, its base scenario
/// (`dir/base.json`) stopped at `stop_time` (s), and `extra` metrics after its own.
fn write_reduced(dir: &Path, name: &str, cases: usize, stop_time: f64, extra: Value) {
    let studies = common::workspace_root().join("studies");
    let read = |file: &Path| -> Value { serde_json::from_str(&std::fs::read_to_string(file).unwrap()).unwrap() };
    let mut study = read(&studies.join(format!("{name}.json")));
    let mut base = read(&studies.join(study["scenario"].as_str().unwrap()));
    base["system"] = json!(common::workspace_root().join("systems/closed_loop.json"));
    base["stop_time"] = json!(stop_time);
    std::fs::write(dir.join("base.json"), base.to_string()).unwrap();
    study["scenario"] = json!("base.json");
    study["cases"] = json!(cases);
    study["metrics"].as_array_mut().unwrap().extend(extra.as_array().unwrap().iter().cloned());
    std::fs::write(dir.join("study.json"), study.to_string()).unwrap();
}

/// Runs and collects `dir/study.json` into `dir/out`; the collected columns by name, one value
/// per case (NaN where a case has none).
fn run_study(dir: &Path) -> BTreeMap<String, Vec<f64>> {
    for args in [&["sweep", "run", "study.json", "-o", "out", "--jobs", "2", "-q"][..], &["sweep", "collect", "out"]] {
        let output = common::crane_cosim_command()
            .current_dir(dir)
            .args(args)
            .env_remove("SLURM_ARRAY_TASK_ID")
            .env_remove("JOB_COMPLETION_INDEX")
            .output()
            .unwrap();
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    }
    let results = std::fs::read_to_string(dir.join("out/results.csv")).unwrap();
    let mut lines = results.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let mut columns: BTreeMap<String, Vec<f64>> = header.iter().map(|h| (h.to_string(), Vec::new())).collect();
    for line in lines {
        assert!(line.contains(",done,"), "every case is done: {line}");
        for (name, cell) in header.iter().zip(line.split(',')) {
            columns.get_mut(*name).unwrap().push(cell.parse().unwrap_or(f64::NAN));
        }
    }
    columns
}

/// Largest over smallest of `values`.
fn spread(values: &[f64]) -> f64 {
    let max = values.iter().copied().fold(f64::MIN, f64::max);
    let min = values.iter().copied().fold(f64::MAX, f64::min);
    max / min
}

#[test]
fn the_monte_carlo_study_links_the_cable_length_and_scales_every_sensor_noise() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    // Before 10 s the deck is still and the crane idle: the readings are pure noise and the
    // lengths those set at the start.
    let extra = json!([
        {"variable": "crane.lp", "stat": "mean", "to": 9.9},
        {"variable": "controller.sp.load.z", "stat": "mean", "to": 9.9},
        {"variable": "imu1.gyro.x", "stat": "std", "to": 9.9},
        {"variable": "imu2.acc.y", "stat": "std", "to": 9.9},
        {"variable": "crane.pot.base", "stat": "std", "to": 9.9}
    ]);
    write_reduced(dir, "monte_carlo", 4, 12.0, extra);
    let c = run_study(dir);
    let lengths = &c["cable_length"];
    println!("{c:#?}");
    assert!(spread(lengths) > 1.5, "the plan spans the lengths: {lengths:?}");
    for (k, &length) in lengths.iter().enumerate() {
        // crane.lp0: the plant starts at the sampled length (not the system's 0.7 m).
        assert!((c["crane.lp.mean"][k] - length).abs() < 1e-9, "case {k}: {length} m");
        // controller.sp.lp: the load's set-point sits the same length below the fixed tip
        // set-point (z down, 0.153 m above the deck origin).
        assert!((c["controller.sp.load.z.mean"][k] - (length - 0.153)).abs() < 1e-9, "case {k}: {length} m");
        assert!([1.0, 2.0, 3.0].contains(&c["sea_state"][k]));
        assert!(c["rmse"][k] > 0.0 && c["peak_theta_x"][k] < 0.2, "case {k}");
    }
    // noise_scale multiplies the FMUs' defaults (no scenario gives them): σ_gyro = 0.0035 rad/s,
    // σ_acc = 0.01 m/s², σ_pot = 1.2 mV (quantised in 1.22 mV steps, which widens a small σ).
    let scales = &c["noise_scale"];
    assert!(spread(scales) > 2.0, "the plan spans the scales: {scales:?}");
    for (k, &scale) in scales.iter().enumerate() {
        let gyro = c["imu1.gyro.x.std"][k] / (scale * 0.0035);
        let acc = c["imu2.acc.y.std"][k] / (scale * 0.01);
        let pot = c["crane.pot.base.std"][k] / (scale * 0.0012);
        assert!((gyro - 1.0).abs() < 0.1 && (acc - 1.0).abs() < 0.1, "case {k}: ×{scale}: {gyro} {acc}");
        assert!(pot > 0.85 && pot < 1.3, "case {k}: ×{scale}: pot {pot}");
    }
}

#[test]
fn the_uncertainty_study_scales_the_drag_and_compares_with_the_crane_off() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_reduced(dir, "uncertainty", 3, 20.0, json!([]));
    let c = run_study(dir);
    println!("{c:#?}");
    let drag = &c["drag_scale"];
    assert!(spread(drag) > 1.15, "the plan spans the drag: {drag:?}");
    // With the crane off the swing decays through the drag alone (τ ∝ 1/κ): the scaled κ makes
    // τ·scale the same in every case, where an unscaled κ would leave τ the same instead.
    let tau_times_scale: Vec<f64> = c["tau_theta_x.baseline"].iter().zip(drag).map(|(tau, s)| tau * s).collect();
    assert!(spread(&tau_times_scale) < 1.01, "{tau_times_scale:?}");
    for metric in ["rmse", "tau_theta_x", "peak_theta_x"] {
        let columns = [metric.to_string(), format!("{metric}.baseline"), format!("{metric}.change")].map(|n| &c[&n]);
        for (k, value) in columns[0].iter().enumerate() {
            let (reference, change) = (columns[1][k], columns[2][k]);
            assert_eq!(change.to_bits(), percent_change(*value, reference).to_bits(), "case {k}: {metric}");
        }
    }
    // Compensation damps the swing: shorter time constant, smaller RMSE than the crane off.
    let reductions = c["tau_theta_x.change"].iter().zip(&c["rmse.change"]);
    assert!(reductions.clone().all(|(tau, rmse)| *tau < -50.0 && *rmse < 0.0), "{:?}", reductions.collect::<Vec<_>>());
}

#[test]
fn scaled_start_values_that_are_no_real_variables_stop_the_run_before_any_case() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    for (parameter, message) in [
        (
            json!({"name": "noise", "scale": ["pendulum.kappa_x", "crane.noise"], "uniform": [0.5, 2.0]}),
            "parameter noise: crane.noise cannot be scaled: not a Real with a start value",
        ),
        (
            json!({"name": "drag", "scale": ["pendulum.kappa_x", "load.kappa_y"], "uniform": [0.8, 1.2]}),
            "parameter drag: load.kappa_y: unknown instance 'load'",
        ),
        (
            json!({"name": "drag", "scale": ["pendulum.kappa_z"], "uniform": [0.8, 1.2]}),
            "parameter drag: pendulum.kappa_z: the FMU of 'pendulum' has no variable 'kappa_z'",
        ),
    ] {
        write_reduced(dir, "monte_carlo", 2, 1.0, json!([]));
        let mut study: Value = serde_json::from_str(&std::fs::read_to_string(dir.join("study.json")).unwrap()).unwrap();
        study["parameters"].as_array_mut().unwrap().push(parameter);
        std::fs::write(dir.join("study.json"), study.to_string()).unwrap();
        let output = common::crane_cosim_command()
            .current_dir(dir)
            .args(["sweep", "run", "study.json", "-o", "out", "-q"])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success() && stderr.contains(message), "{stderr}");
        assert!(!dir.join("out/cases/0000.json").exists(), "no case ran");
    }
}
