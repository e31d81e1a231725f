//! The closed loop (systems/closed_loop.json and the demo scenarios) run by the `crane-cosim`
//! binary: energy dissipation, co-simulation error, a failing instance, a misspelt name.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, text};

use std::path::{Path, PathBuf};

use cosim_engine::table::SignalTable;
use crane_metrics::{run_metrics, Comparison, Trace};
use serde_json::Value;

/// The closed-loop system with absolute FMU paths, after `edit`, written into `dir`.
fn closed_loop(dir: &Path, edit: impl FnOnce(&mut Value)) -> PathBuf {
    let root = common::workspace_root();
    let mut system: Value =
        serde_json::from_str(&std::fs::read_to_string(root.join("systems/closed_loop.json")).unwrap()).unwrap();
    for (alias, path) in system["fmus"].as_object_mut().unwrap() {
        let fmu = root
            .join("target/fmu")
            .join(format!("{}.fmu", Path::new(path.as_str().unwrap()).file_stem().unwrap().to_str().unwrap()));
        assert!(fmu.is_file(), "{} ({alias}) does not exist: run `cargo xtask package` first", fmu.display());
        *path = Value::String(fmu.display().to_string());
    }
    edit(&mut system);
    let path = dir.join("system.json");
    std::fs::write(&path, serde_json::to_string_pretty(&system).unwrap()).unwrap();
    path
}

/// Applies `"instance.variable": value` start values.
fn set_starts(system: &mut Value, starts: &[(&str, Value)]) {
    for (key, value) in starts {
        let (name, variable) = key.split_once('.').unwrap();
        let instance = system["instances"].as_array_mut().unwrap().iter_mut().find(|i| i["name"] == name).unwrap();
        instance["start"][variable] = value.clone();
    }
}

fn run(system: &Path, output: &Path, extra: &[&str]) -> SignalTable {
    let mut args = vec!["run", system.to_str().unwrap(), "--output", output.to_str().unwrap(), "-q"];
    args.extend_from_slice(extra);
    let out = crane_cosim(&args, Path::new("."));
    assert!(out.status.success(), "{}", text(&out.stderr));
    SignalTable::read(output).unwrap()
}

/// The demo's release: 700 mm pendulum held at θx = −23° until 10 s, then `mode` from 10 s.
fn release(mode: i64, feedback: i64, profile: i64, noise: bool) -> Vec<(&'static str, Value)> {
    vec![
        ("pendulum.theta_x0", (-23f64).to_radians().into()),
        ("pendulum.release_time", 10.0.into()),
        ("controller.mode", mode.into()),
        ("controller.feedback", feedback.into()),
        ("controller.active_from", 10.0.into()),
        ("platform.profile", profile.into()),
        ("crane.noise", noise.into()),
        ("imu1.noise", noise.into()),
        ("imu2.noise", noise.into()),
    ]
}

#[test]
fn compensation_dissipates_the_swing_much_faster_than_the_crane_off() {
    let dir = tempfile::tempdir().unwrap();
    let mut results = Vec::new();
    for mode in [0, 2] {
        let system = closed_loop(dir.path(), |s| set_starts(s, &release(mode, 1, 0, true)));
        let table = run(&system, &dir.path().join(format!("mode{mode}.csv")), &["--stop-time", "50"]);
        results.push(run_metrics(&table, 10.0, &Comparison::default()).unwrap());
    }
    let (off, on) = (&results[0], &results[1]);
    println!(
        "40 s after release: distance travelled {:.2} m (off) vs {:.2} m (compensated); residual swing {:.2}° vs {:.2}°",
        off.distance,
        on.distance,
        off.final_swing.to_degrees(),
        on.final_swing.to_degrees()
    );
    assert!(on.distance < 0.3 * off.distance);
    assert!(on.final_swing < 0.2 * off.final_swing);
    assert!(off.settling.is_none() && on.settling.is_some());
}

#[test]
fn the_controller_winches_to_a_new_length_from_the_initial_length_it_is_given() {
    // The crane starts at 0.7 m (its default) and the set-point asks for 0.9 m. Counting the
    // encoder from the initial length (the default, §6.1), the controller must be told that
    // length: told 0.7 m it winches the load down to 0.9 m; not told, it takes the set-point as
    // the initial length and believes the load already there.
    let dir = tempfile::tempdir().unwrap();
    let final_lengths = |initial: f64| {
        let starts = [
            ("controller.feedback", Value::from(1)),
            ("controller.sp.lp", 0.9.into()),
            ("controller.encoder.lp0", initial.into()),
        ];
        let system = closed_loop(dir.path(), |s| {
            set_starts(s, &starts);
            s["record"]["variables"] = serde_json::json!(["crane.lp", "controller.est.lp"]);
        });
        let output = dir.path().join(format!("lp0_{initial}.csv"));
        let table = run(&system, &output, &["--stop-time", "20"]);
        let last = |name: &str| *table.columns[table.column(name).unwrap()].last().unwrap();
        (last("crane.lp"), last("controller.est.lp"))
    };
    let (told, told_estimate) = final_lengths(0.7);
    let (untold, untold_estimate) = final_lengths(0.0);
    println!("after 20 s: l_p {told:.4} m (estimated {told_estimate:.4} m) told 0.7 m; {untold:.4} m ({untold_estimate:.4} m) not told");
    assert!((told - 0.9).abs() < 2e-3 && (told_estimate - told).abs() < 1e-3);
    assert!((untold - 0.7).abs() < 1e-4 && (untold_estimate - 0.9).abs() < 1e-3);
}

/// RMSD (m) of the load position between the loop at 10 ms and at 1 ms macro steps (the
/// controller samples at its own 100 Hz in both).
fn cosimulation_error(starts: &[(&'static str, Value)]) -> f64 {
    let dir = tempfile::tempdir().unwrap();
    let system = closed_loop(dir.path(), |s| set_starts(s, starts));
    let coarse = run(&system, &dir.path().join("h10.csv"), &["--stop-time", "30"]);
    let fine = run(
        &system,
        &dir.path().join("h1.csv"),
        &["--stop-time", "30", "--step-size", "0.001", "--record-interval", "0.01"],
    );
    let a = Trace::from_table(&coarse, "pendulum.load.").unwrap();
    let b = Trace::from_table(&fine, "pendulum.load.").unwrap();
    assert_eq!(a.times.len(), b.times.len(), "both record at 10 ms");
    let sum: f64 =
        a.points.iter().zip(&b.points).map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).powi(2)).sum::<f64>()).sum();
    (sum / a.points.len() as f64).sqrt()
}

#[test]
fn cosimulation_error_of_the_inverse_kinematics_loop_under_ship_motion() {
    let ik = cosimulation_error(&release(1, 0, 1, false));
    println!("co-simulation error, IK control, ship profile 1, 10 ms vs 1 ms: load RMSD {:.3e} m", ik);
    assert!(ik < 1e-3);
}

#[test]
fn a_failing_instance_ends_the_run_with_a_clear_error_and_keeps_the_rows() {
    let dir = tempfile::tempdir().unwrap();
    // External set-point that turns into NaN at t = 5 s: the controller refuses it.
    std::fs::write(
        dir.path().join("setpoint.csv"),
        "time,sp_in.tip.x,sp_in.tip.y,sp_in.tip.z,sp_in.lp\n0,0.003,-0.502,-0.153,0.7\n5,0.003,-0.502,-0.153,0.7\n5,NaN,-0.502,-0.153,0.7\n9,NaN,-0.502,-0.153,0.7\n",
    )
    .unwrap();
    let system = closed_loop(dir.path(), |s| {
        set_starts(s, &[("controller.setpoint", 2.into()), ("controller.mode", 1.into())]);
        s["inputs"] = serde_json::json!([{ "instance": "controller", "file": "setpoint.csv" }]);
        s["stop_time"] = 10.0.into();
    });
    let output = dir.path().join("out.csv");
    let out =
        crane_cosim(&["run", system.to_str().unwrap(), "--output", output.to_str().unwrap(), "-q"], Path::new("."));
    assert!(!out.status.success());
    let message = text(&out.stderr);
    println!("{message}");
    assert!(message.contains("controller") && message.contains("sp_in.tip.x") && message.contains('5'), "{message}");
    let table = SignalTable::read(&output).unwrap();
    assert_eq!(table.times.first(), Some(&0.0));
    // Every communication point up to the failing step at t = 5 s was recorded.
    assert!((table.times.last().unwrap() - 5.0).abs() < 1e-9, "rows up to the failure: {:?}", table.times.last());
    assert_eq!(table.times.len(), 501);
}

#[test]
fn a_misspelt_variable_is_rejected_before_anything_runs() {
    let dir = tempfile::tempdir().unwrap();
    let system = closed_loop(dir.path(), |s| {
        s["connections"][0]["to"] = "crane.ship.xx".into();
    });
    let output = dir.path().join("out.csv");
    let out = crane_cosim(&["run", system.to_str().unwrap(), "--output", output.to_str().unwrap()], Path::new("."));
    assert!(!out.status.success());
    let message = text(&out.stderr);
    assert!(
        message.contains("connections[0]") && message.contains("ship.xx") && message.contains("ship.x"),
        "{message}"
    );
    assert!(!output.exists(), "nothing may be recorded for an invalid system");
}

/// The controller changes its commands every 10 ms, so the crane tip acceleration jumps at
/// communication points; the pendulum reconciles the acceleration ramp with the velocity slope
/// (15 mm here without that). Noise off: the sensors draw one noise sample per step.
#[test]
fn cosimulation_error_of_the_compensated_loop_under_ship_motion() {
    for (feedback, label) in [(0, "truth"), (1, "sensor")] {
        let error = cosimulation_error(&release(2, feedback, 1, false));
        println!("co-simulation error, compensated ({label} feedback), ship profile 1, 10 ms vs 1 ms: load RMSD {error:.3e} m");
        assert!(error < 1e-3);
    }
}
