//! What a new user meets first: a file with a JSON syntax error, a changed step size, a stop time
//! off the step grid, and one FMU run on its own reference input.
//!
//! Needs `target/fmu/` as `cargo xtask package` leaves it (FMUs and reference files).

#[path = "../../test_support.rs"]
mod common;

use std::path::Path;
use std::process::{Command, Output};

fn crane_cosim(args: &[&str], dir: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_crane-cosim")).args(args).current_dir(dir).output().expect("crane-cosim runs")
}

fn failed(output: &Output) -> String {
    assert!(!output.status.success(), "expected a failure: {}", String::from_utf8_lossy(&output.stdout));
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// `text` with a comma after its last member, as a hand edit leaves it.
fn with_trailing_comma(text: &str) -> String {
    let end = text.trim_end().strip_suffix('}').expect("a JSON object").trim_end();
    format!("{end},\n}}\n")
}

#[test]
fn a_json_syntax_error_is_reported_as_one_with_the_kind_of_file() {
    let dir = tempfile::tempdir().unwrap();
    let root = common::workspace_root();
    let scenario = std::fs::read_to_string(root.join("scenarios/demo_still_compensated.json")).unwrap();
    let scenario = with_trailing_comma(&scenario);
    let line = scenario.lines().count();
    std::fs::write(dir.path().join("scenario.json"), &scenario).unwrap();
    let stderr = failed(&crane_cosim(&["run", "scenario.json"], dir.path()));
    let expected = format!(
        "scenario.json:{line}:1: JSON syntax error at line {line} column 1 (read as a scenario file): trailing comma"
    );
    assert!(stderr.contains(&expected), "{stderr}");

    let system = std::fs::read_to_string(root.join("systems/pendulum_free_decay.json")).unwrap();
    std::fs::write(dir.path().join("system.json"), with_trailing_comma(&system)).unwrap();
    let stderr = failed(&crane_cosim(&["run", "system.json"], dir.path()));
    assert!(stderr.contains("JSON syntax error at line") && stderr.contains("(read as a system file)"), "{stderr}");

    let study = std::fs::read_to_string(root.join("studies/monte_carlo.json")).unwrap();
    std::fs::write(dir.path().join("study.json"), with_trailing_comma(&study)).unwrap();
    let stderr = failed(&crane_cosim(&["sweep", "plan", "study.json"], dir.path()));
    assert!(stderr.contains("JSON syntax error at line") && stderr.contains("(read as a study file)"), "{stderr}");

    // Valid JSON with a wrong field is still reported as a wrong field of that kind of file.
    std::fs::write(dir.path().join("typo.json"), "{\"system\": \"x.json\", \"stop_tme\": 1}").unwrap();
    let stderr = failed(&crane_cosim(&["run", "typo.json"], dir.path()));
    assert!(stderr.contains("typo.json:1:31: invalid scenario file: unknown field `stop_tme`"), "{stderr}");
}

fn succeeded(output: &Output) -> String {
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The times of a results CSV.
fn times(csv: &Path) -> Vec<f64> {
    common::read_results(csv).1.iter().map(|row| row[0]).collect()
}

#[test]
fn the_recording_interval_follows_the_step_unless_given() {
    let dir = tempfile::tempdir().unwrap();
    let root = common::workspace_root();
    let scenario = root.join("scenarios/demo_still_off.json").display().to_string();
    let out = dir.path().join("coarse.csv").display().to_string();
    let args = ["run", &scenario, "--step-size", "0.02", "--stop-time", "0.2", "-q", "-o", &out];
    succeeded(&crane_cosim(&args, dir.path()));
    assert_eq!(times(Path::new(&out)), (0..=10).map(|k| k as f64 * 0.02).collect::<Vec<_>>());

    // An interval the file gives explicitly no longer fits: the message names the option.
    let pendulum = common::pendulum_fmu().display().to_string();
    let system = serde_json::json!({
        "fmus": { "pendulum": pendulum },
        "instances": [ { "name": "load", "fmu": "pendulum" } ],
        "stop_time": 0.2, "step_size": 0.01,
        "record": { "interval": 0.01, "variables": ["load.theta_x"] }
    });
    std::fs::write(dir.path().join("system.json"), system.to_string()).unwrap();
    let stderr = failed(&crane_cosim(&["run", "system.json", "--step-size", "0.02", "-o", "x.csv"], dir.path()));
    assert!(
        stderr.contains("record.interval: 0.01 s is not a positive whole multiple of step_size 0.02 s: give one that is (--record-interval)"),
        "{stderr}"
    );
    let args = ["run", "system.json", "--step-size", "0.02", "--record-interval", "0.1", "-q", "-o", "sparse.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    assert_eq!(times(&dir.path().join("sparse.csv")), [0.0, 5.0 * 0.02, 10.0 * 0.02]);
}
