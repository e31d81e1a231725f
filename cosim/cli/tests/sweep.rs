//! A small study through the `crane-cosim sweep` commands, end to end: four short closed-loop
//! cases over a cable-length grid, planned, run by case index, by shard and on a pool,
//! collected, and one case checked against a direct `crane-cosim run` of the same scenario.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use std::path::Path;
use std::process::{Command, Output};

use cosim_engine::table::SignalTable;
use cosim_studies::sweep::plan::variable_seed;
use cosim_studies::sweep::study::Stat;
use crane_metrics::{rmse, Trace, CAPTURE_RATE, LOAD_PREFIX, SETPOINT_PREFIX};

/// The base scenario's start values: a 23° swing released at 10 s with the crane off (recorded
/// every 0.02 s, twice the step, which the cases' metrics must keep).
const START: &str = r#""pendulum.theta_x0": -0.4, "pendulum.release_time": 10.0, "controller.mode": 0,
    "controller.active_from": 10.0, "imu1.noise": true, "imu2.noise": true"#;

fn write_study(dir: &Path) {
    let system = common::workspace_root().join("systems/closed_loop.json");
    let base = format!(
        r#"{{"system": {:?}, "start": {{{START}}}, "stop_time": 12.0, "record": {{"interval": 0.02}}}}"#,
        system.to_str().unwrap()
    );
    std::fs::write(dir.join("base.json"), base).unwrap();
    let study = r#"{"scenario": "base.json", "sampling": "grid", "seed": 42,
        "seed_variables": ["imu1.seed", "imu2.seed"],
        "parameters": [{"name": "crane.lp0", "grid": [0.5, 0.7, 0.9, 1.1]}],
        "metrics": [{"variable": "pendulum.theta_x", "stat": "rms", "from": 10},
                    {"variable": "imu2.gyro.x", "stat": "std", "from": 10.5},
                    {"metric": "rmse", "from": 10, "to": 11.5}]}"#;
    std::fs::write(dir.join("study.json"), study).unwrap();
}

/// Rewrites the study file in `dir` with `from` replaced by `to`.
fn edit_study(dir: &Path, from: &str, to: &str) {
    let study = std::fs::read_to_string(dir.join("study.json")).unwrap();
    std::fs::write(dir.join("study.json"), study.replace(from, to)).unwrap();
}

fn crane_cosim(dir: &Path, args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut command = common::crane_cosim_command();
    command.current_dir(dir).args(args).env_remove("SLURM_ARRAY_TASK_ID").env_remove("JOB_COMPLETION_INDEX");
    command.envs(env.iter().copied()).output().expect("crane-cosim runs")
}

fn succeed(dir: &Path, args: &[&str]) -> String {
    let output = crane_cosim(dir, args, &[]);
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stdout).unwrap()
}

fn status(dir: &Path, out: &str) -> Vec<String> {
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join(out).join("manifest.json")).unwrap()).unwrap();
    manifest["cases"].as_array().unwrap().iter().map(|c| c["status"].as_str().unwrap().to_string()).collect()
}

#[test]
fn a_study_is_planned_run_in_parts_rerun_without_repeats_and_collected() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_study(dir);

    succeed(dir, &["sweep", "plan", "study.json", "-o", "cases.csv"]);
    let plan = std::fs::read_to_string(dir.join("cases.csv")).unwrap();
    let rows: Vec<Vec<&str>> = plan.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 5, "{plan}");
    assert_eq!(rows[0], ["case", "seed", "crane.lp0"]);
    assert_eq!((rows[3][0], rows[3][2]), ("0002", "0.9"));
    assert_eq!(succeed(dir, &["sweep", "plan", "study.json"]), plan, "printed and written plans agree");

    let ran = succeed(dir, &["sweep", "run", "study.json", "-o", "out", "--case-index", "2"]);
    assert!(ran.starts_with("1 done, 0 failed, 0 already done"), "{ran}");
    assert_eq!(status(dir, "out"), ["pending", "pending", "done", "pending"]);
    let rerun = crane_cosim(dir, &["sweep", "run", "study.json", "-o", "out", "--case-index", "2"], &[]);
    assert!(String::from_utf8_lossy(&rerun.stdout).starts_with("0 done, 0 failed, 1 already done"));
    // Before the cases, the system file the study's scenario runs and its FMUs.
    let said = String::from_utf8_lossy(&rerun.stderr);
    let root = std::fs::canonicalize(common::workspace_root()).unwrap();
    assert!(said.starts_with("system: "), "{said}");
    assert!(said.contains(&format!("  FMU pendulum: {}", root.join("target/fmu/pendulum.fmu").display())), "{said}");

    // An array job's index comes from the environment; one past the plan is refused.
    let output = crane_cosim(dir, &["sweep", "run", "study.json", "-o", "out"], &[("SLURM_ARRAY_TASK_ID", "4")]);
    let error = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success() && error.contains("case index 4 is not in the plan (cases 0 to 3)"), "{error}");
    let output = crane_cosim(dir, &["sweep", "run", "study.json", "-o", "out"], &[("JOB_COMPLETION_INDEX", "0")]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(status(dir, "out"), ["done", "pending", "done", "pending"]);

    let rest = succeed(dir, &["sweep", "run", "study.json", "-o", "out", "--jobs", "2"]);
    assert!(rest.starts_with("2 done, 0 failed, 2 already done"), "{rest}");
    assert_eq!(status(dir, "out"), ["done"; 4]);

    succeed(dir, &["sweep", "run", "study.json", "-o", "shard", "--shard", "1/2"]);
    assert_eq!(status(dir, "shard"), ["pending", "done", "pending", "done"]);

    let collected = succeed(dir, &["sweep", "collect", "out"]);
    assert!(collected.ends_with("results.csv: 4 done, 0 failed, 0 pending\n"), "{collected}");
    let results = std::fs::read_to_string(dir.join("out/results.csv")).unwrap();
    let rows: Vec<Vec<&str>> = results.lines().map(|l| l.split(',').collect()).collect();
    assert_eq!(rows[0], ["case", "seed", "status", "crane.lp0", "pendulum.theta_x.rms", "imu2.gyro.x.std", "rmse"]);
    assert_eq!(rows.len(), 5, "{results}");
    // The swing angle depends on the cable length: no two cases share a metric.
    let rms: Vec<f64> = rows[1..].iter().map(|r| r[4].parse().unwrap()).collect();
    assert!(rms.windows(2).all(|w| w[0] != w[1]), "{rms:?}");
    assert_direct_run_agrees(dir, &rows[3]);
}

/// Case 0002 run directly as a scenario (its cable length and IMU seeds written by hand, all
/// outputs recorded) gives the same bits for every metric.
fn assert_direct_run_agrees(dir: &Path, row: &[&str]) {
    let seed: u64 = row[1].parse().unwrap();
    let system = common::workspace_root().join("systems/closed_loop.json");
    let scenario = format!(
        r#"{{"system": {:?}, "start": {{{START}, "crane.lp0": 0.9, "imu1.seed": {}, "imu2.seed": {}}}, "stop_time": 12.0,
            "record": {{"interval": 0.02}}}}"#,
        system.to_str().unwrap(),
        variable_seed(seed, 0),
        variable_seed(seed, 1)
    );
    std::fs::write(dir.join("case2.json"), scenario).unwrap();
    succeed(dir, &["run", "case2.json", "-o", "case2.csv", "-q"]);
    let table = SignalTable::read(&dir.join("case2.csv")).unwrap();
    let column = |name: &str| &table.columns[table.names.iter().position(|n| n == name).unwrap()];
    let end = f64::INFINITY;
    let rms = Stat::Rms.of(&table.times, column("pendulum.theta_x"), 10.0, end).unwrap();
    let std = Stat::Std.of(&table.times, column("imu2.gyro.x"), 10.5, end).unwrap();
    // §7.2.2: the load against its set-point at the 30 Hz capture rate.
    let trace = |prefix| Trace::from_table(&table, prefix).unwrap().resample(CAPTURE_RATE, 10.0, 11.5);
    let rmse = rmse(&trace(LOAD_PREFIX), &trace(SETPOINT_PREFIX).points);
    assert_eq!(row[4].parse::<f64>().unwrap().to_bits(), rms.to_bits(), "{row:?}: direct rms {rms}");
    assert_eq!(row[5].parse::<f64>().unwrap().to_bits(), std.to_bits(), "{row:?}: direct std {std}");
    assert_eq!(row[6].parse::<f64>().unwrap().to_bits(), rmse.to_bits(), "{row:?}: direct rmse {rmse}");
}

#[test]
fn a_failing_case_is_recorded_failed_reported_and_run_again_and_another_study_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_study(dir);
    // Case 1's cable length is outside the crane FMU's range: the case fails, not the study.
    edit_study(dir, "0.5, 0.7, 0.9", "0.5, -0.7, 0.9");
    for _ in 0..2 {
        let output = crane_cosim(dir, &["sweep", "run", "study.json", "-o", "out", "--case-index", "1"], &[]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success() && stderr.contains("1 of 1 cases run failed"), "{stderr}");
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(stdout.starts_with("0 done, 1 failed, 0 already done"), "a failed case is run again: {stdout}");
    }
    let case: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/cases/0001.json")).unwrap()).unwrap();
    assert_eq!(case["status"], "failed");
    assert!(case["error"].as_str().unwrap().contains("'lp0' = -0.7 is outside its range"), "{case}");
    assert_eq!(status(dir, "out"), ["pending", "failed", "pending", "pending"]);
    let collected = succeed(dir, &["sweep", "collect", "out"]);
    assert!(collected.ends_with("0 done, 1 failed, 3 pending\n"), "{collected}");

    // Another study (here another seed) does not take over the folder's cases.
    edit_study(dir, r#""seed": 42"#, r#""seed": 43"#);
    let output = crane_cosim(dir, &["sweep", "run", "study.json", "-o", "out", "--case-index", "1"], &[]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!output.status.success() && stderr.contains("0001.json holds a case of another study"), "{stderr}");
}

#[test]
fn a_start_value_naming_no_variable_is_refused_before_any_case_runs() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_study(dir);
    let study = std::fs::read_to_string(dir.join("study.json")).unwrap();
    let cases = [
        (r#""name": "crane.lp0""#, r#""name": "winch.lp0""#, "unknown instance"),
        (r#""name": "crane.lp0""#, r#""name": "l", "set": ["crane.lp0", "controller.lp0"]"#, "lp0"),
        (r#""imu2.seed""#, r#""imu2.sed""#, "sed"),
        (r#""name": "crane.lp0""#, r#""name": "crane.lp""#, "lp"),
    ];
    for (from, to, named) in cases {
        std::fs::write(dir.join("study.json"), study.replace(from, to)).unwrap();
        let output = crane_cosim(dir, &["sweep", "run", "study.json", "-o", "out"], &[]);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(!output.status.success() && stderr.contains("study.json") && stderr.contains(named), "{to}: {stderr}");
        assert!(!dir.join("out/cases").exists(), "{to}: no case may run");
    }
}

/// Writes `study.json` in `dir`: `sampling` over one parameter given as `values` (a JSON member,
/// e.g. `"normal": [0, 1]`), with `cases` cases unless `None`.
fn write_small_study(dir: &Path, sampling: &str, cases: Option<u64>, values: &str) {
    let cases = cases.map(|n| format!(r#""cases": {n},"#)).unwrap_or_default();
    let study = format!(
        r#"{{"scenario": "base.json", "sampling": "{sampling}", {cases} "seed": 3,
            "parameters": [{{"name": "load.lp", {values}}}],
            "metrics": [{{"variable": "pendulum.theta_x", "stat": "rms"}}]}}"#
    );
    std::fs::write(dir.join("study.json"), study).unwrap();
}

/// Runs crane-cosim in `dir`, stopping it (and failing) if it has not ended within 60 s: what
/// blocks on a FIFO would otherwise hang the test.
fn crane_cosim_within(dir: &Path, args: &[&str]) -> Output {
    let mut command = common::crane_cosim_command();
    command.current_dir(dir).args(args).env_remove("SLURM_ARRAY_TASK_ID").env_remove("JOB_COMPLETION_INDEX");
    let mut child = command
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("crane-cosim starts");
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > std::time::Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("{args:?} still running after 60 s");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child.wait_with_output().unwrap()
}

fn fail(dir: &Path, args: &[&str]) -> String {
    let output = crane_cosim_within(dir, args);
    assert!(!output.status.success(), "{args:?} succeeded");
    assert_eq!(output.status.code(), Some(1), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
    String::from_utf8(output.stderr).unwrap()
}

fn mkfifo(file: &Path) {
    assert!(Command::new("mkfifo").arg(file).status().unwrap().success());
}

#[test]
fn a_study_of_more_cases_than_the_ceiling_is_refused_unless_raised() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_small_study(dir, "random", Some(1_000_000_000), r#""uniform": [0, 1]"#);
    let expected = "error: study study.json plans 1000000000 cases, more than the 1000000 allowed \
                    (raise it with --max-cases)\n";
    assert_eq!(fail(dir, &["sweep", "plan", "study.json"]), expected);
    assert_eq!(fail(dir, &["sweep", "run", "study.json", "-o", "out", "--case-index", "0"]), expected);
    write_small_study(dir, "grid", None, r#""grid": [1, 2, 3]"#);
    assert_eq!(
        fail(dir, &["sweep", "plan", "study.json", "--max-cases", "2"]),
        "error: study study.json plans 3 cases, more than the 2 allowed (raise it with --max-cases)\n"
    );
    let plan = crane_cosim_within(dir, &["sweep", "plan", "study.json", "--max-cases", "3"]);
    assert!(plan.status.success(), "{}", String::from_utf8_lossy(&plan.stderr));
}

#[test]
fn a_sample_overflowing_to_infinity_is_refused_with_its_parameter() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_small_study(dir, "random", Some(20), r#""normal": [1e308, 1e308]"#);
    assert_eq!(
        fail(dir, &["sweep", "plan", "study.json"]),
        "error: parameter 'load.lp': sample 5 is inf (normal [1e308, 1e308]): choose a distribution whose \
         samples are finite\n"
    );
}

#[test]
fn plan_values_are_written_in_their_shortest_round_trip_form() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_small_study(dir, "grid", None, r#""grid": [1e300, 0.1, 2, -1e-7]"#);
    let plan = crane_cosim_within(dir, &["sweep", "plan", "study.json"]);
    let text = String::from_utf8(plan.stdout).unwrap();
    let values: Vec<&str> = text.lines().skip(1).map(|line| line.rsplit(',').next().unwrap()).collect();
    assert_eq!(values, ["1e300", "0.1", "2.0", "-1e-7"], "{text}");
}

#[test]
fn a_study_or_scenario_that_is_a_fifo_or_a_device_is_refused_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    mkfifo(&dir.join("fifo.json"));
    assert_eq!(
        fail(dir, &["sweep", "plan", "fifo.json"]),
        "error: cannot read fifo.json: not a regular file but a FIFO\n"
    );
    write_small_study(dir, "grid", None, r#""grid": [1]"#);
    std::os::unix::fs::symlink("/dev/zero", dir.join("base.json")).unwrap();
    assert_eq!(
        fail(dir, &["sweep", "run", "study.json", "-o", "out"]),
        "error: cannot read base.json: not a regular file but a device\n"
    );
}

/// `out/manifest.json` of a one-case study, as `sweep run` writes it (with its folder's mark).
fn write_manifest(out: &Path) {
    cosim_studies::sweep::mark_folder(out).unwrap();
    let manifest = r#"{"study": "study.json", "parameters": ["crane.lp0"], "metrics": ["rms(pendulum.theta_x)"],
        "cases": [{"id": "0000", "seed": 1, "status": "pending"}]}"#;
    std::fs::write(out.join("manifest.json"), manifest).unwrap();
}

#[test]
fn collect_refuses_a_fifo_case_file_and_a_linked_cases_folder_without_blocking() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_manifest(&dir.join("out"));
    std::fs::create_dir(dir.join("out/cases")).unwrap();
    mkfifo(&dir.join("out/cases/0000.json"));
    assert_eq!(
        fail(dir, &["sweep", "collect", "out", "--plots", "none"]),
        "error: cannot read out/cases/0000.json: not a regular file but a FIFO\n"
    );
    std::fs::remove_dir_all(dir.join("out/cases")).unwrap();
    std::fs::create_dir(dir.join("elsewhere")).unwrap();
    std::os::unix::fs::symlink(dir.join("elsewhere"), dir.join("out/cases")).unwrap();
    assert_eq!(
        fail(dir, &["sweep", "collect", "out", "--plots", "none"]),
        "error: out/cases: the cases folder is a symbolic link: give an output folder of its own\n"
    );
}

#[test]
fn run_refuses_a_case_file_linked_to_a_device_or_a_fifo_and_a_linked_cases_folder() {
    let dir = tempfile::tempdir().unwrap();
    let dir = dir.path();
    write_study(dir);
    cosim_studies::sweep::mark_folder(&dir.join("out")).unwrap();
    std::fs::create_dir_all(dir.join("out/cases")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("out/cases/0000.json")).unwrap();
    let run = ["sweep", "run", "study.json", "-o", "out", "--case-index", "0", "--quiet"];
    assert_eq!(fail(dir, &run), "error: cannot read out/cases/0000.json: not a regular file but a device\n");
    std::fs::remove_file(dir.join("out/cases/0000.json")).unwrap();
    mkfifo(&dir.join("out/cases/0000.json"));
    assert_eq!(fail(dir, &run), "error: cannot read out/cases/0000.json: not a regular file but a FIFO\n");
    std::fs::remove_dir_all(dir.join("out/cases")).unwrap();
    std::fs::create_dir(dir.join("elsewhere")).unwrap();
    std::os::unix::fs::symlink(dir.join("elsewhere"), dir.join("out/cases")).unwrap();
    assert_eq!(
        fail(dir, &run),
        "error: out/cases: the cases folder is a symbolic link: give an output folder of its own\n"
    );
}
