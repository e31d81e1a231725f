//! End-to-end tests of the `crane-cosim` binary with the packaged pendulum.
//!
//! Needs `target/fmu/pendulum.fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, text};

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

/// Writes `system` as `name` into `dir`.
fn write_system(dir: &Path, name: &str, system: &Value) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, serde_json::to_string_pretty(system).expect("json")).expect("write system");
    path
}

/// Tip motion on x: position, velocity and acceleration of 5 cm · sin(2 t).
fn write_tip_inputs(dir: &Path, name: &str, nan_from: Option<f64>) {
    let mut csv = String::from("time,tip.x,tip.y,tip.z,tip.vx,tip.vy,tip.vz,tip.ax,tip.ay,tip.az\n");
    let mut rows: Vec<(f64, bool)> = (0..=40).map(|i| (i as f64 * 0.05, false)).collect();
    if let Some(t) = nan_from {
        // A discontinuity: the signal is finite up to `t` and NaN from `t` on.
        rows.retain(|(time, _)| *time <= t);
        rows.push((t, true));
        rows.push((t + 1.0, true));
    }
    for (t, nan) in rows {
        let (x, v, a) = if nan {
            (f64::NAN, 0.0, 0.0)
        } else {
            (0.05 * (2.0 * t).sin(), 0.1 * (2.0 * t).cos(), -0.2 * (2.0 * t).sin())
        };
        csv.push_str(&format!("{t:?},{x:?},0,0,{v:?},0,0,{a:?},0,0\n"));
    }
    std::fs::write(dir.join(name), csv).expect("write inputs");
}

fn pendulum_system(inputs: &str, extra: Value) -> Value {
    let mut system = json!({
        "description": "driven pendulum",
        "fmus": { "pendulum": common::pendulum_fmu() },
        "instances": [ { "name": "load", "fmu": "pendulum", "start": { "theta_x0": -0.2, "lp": 0.7 } } ],
        "inputs": [ { "instance": "load", "file": inputs } ],
        "start_time": 0.0, "stop_time": 1.0, "step_size": 0.01,
        "input_derivatives": true,
        "record": { "variables": ["load.theta_x", "load.theta_y", "load.load.x", "load.tip.x", "load.tension"] }
    });
    if let (Some(target), Some(extra)) = (system.as_object_mut(), extra.as_object()) {
        for (key, value) in extra {
            target.insert(key.clone(), value.clone());
        }
    }
    system
}

fn read_summary(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).expect("summary exists")).expect("summary is JSON")
}

#[test]
fn runs_a_pendulum_with_an_inputs_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    write_system(dir.path(), "driven.json", &pendulum_system("tip.csv", json!({})));

    let output = crane_cosim(&["run", "driven.json", "--output", "results/driven.csv"], dir.path());
    assert!(output.status.success(), "stderr: {}", text(&output.stderr));
    assert!(text(&output.stdout).contains("completed 100 steps"), "{}", text(&output.stdout));

    let (header, rows) = common::read_results(&dir.path().join("results/driven.csv"));
    assert_eq!(header, ["time", "load.theta_x", "load.theta_y", "load.load.x", "load.tip.x", "load.tension"]);
    assert_eq!(rows.len(), 101, "t = 0, 0.01, ..., 1.0");
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len());
        assert_eq!(row[0], k as f64 * 0.01, "time column is k·h");
        assert!(row.iter().all(|v| v.is_finite()), "row {k}: {row:?}");
    }
    assert_eq!(rows[0][1], -0.2, "theta_x0 start value applied");
    // An input recorded at t_{k+1} holds the value set at t_k for that step:
    // row 51 shows the CSV sample at t = 0.5 exactly.
    assert_eq!(rows[51][4], 0.05 * (2.0f64 * 0.5).sin());
    assert_eq!(rows[0][4], 0.0);

    let summary = read_summary(&dir.path().join("results/driven.summary.json"));
    assert_eq!(summary["status"], "completed");
    assert_eq!(summary["steps"], 100);
    assert_eq!(summary["steps_completed"], 100);
    assert_eq!(summary["rows_recorded"], 101);
    assert_eq!(summary["end_time"], 1.0);
    assert_eq!(summary["algorithm"], "gauss-seidel");
    assert!(summary["error"].is_null());
    assert!(summary["wall_time"].as_f64().is_some_and(|w| w > 0.0));
    assert!(summary["real_time_factor"].as_f64().is_some_and(|f| f > 0.0));
    assert_eq!(summary["instances"][0]["model_name"], "pendulum");
}

#[test]
fn timing_is_in_the_summary_only_when_asked_for() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    write_system(dir.path(), "driven.json", &pendulum_system("tip.csv", json!({})));

    let output = crane_cosim(&["run", "driven.json", "-o", "plain.csv", "-q"], dir.path());
    assert!(output.status.success(), "stderr: {}", text(&output.stderr));
    assert!(read_summary(&dir.path().join("plain.summary.json")).get("timing").is_none());

    let output = crane_cosim(&["run", "driven.json", "-o", "timed.csv", "-q", "--timing"], dir.path());
    assert!(output.status.success(), "stderr: {}", text(&output.stderr));
    let timing = &read_summary(&dir.path().join("timed.summary.json"))["timing"];
    assert_eq!(timing["steps"], 100);
    let seconds = |value: &Value| value.as_f64().filter(|&s| s > 0.0).unwrap_or_else(|| panic!("{timing}"));
    let total = seconds(&timing["total_s"]);
    assert!(seconds(&timing["recording_s"]) < total, "{timing}");
    let instances = timing["instances"].as_array().expect("instances");
    assert_eq!(instances.len(), 1);
    assert_eq!(instances[0]["name"], "load");
    let inside = seconds(&instances[0]["do_step_s"]) + seconds(&instances[0]["get_set_s"]);
    assert!(inside < total, "{timing}");
    // The results do not depend on timing.
    assert_eq!(
        std::fs::read(dir.path().join("plain.csv")).expect("plain"),
        std::fs::read(dir.path().join("timed.csv")).expect("timed")
    );
}

#[test]
fn command_line_overrides_and_record_interval() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    let system = pendulum_system("tip.csv", json!({ "record": { "interval": 0.1 } }));
    write_system(dir.path(), "sparse.json", &system);
    let output = crane_cosim(
        &["run", "sparse.json", "-o", "sparse.csv", "--summary", "s.json", "--stop-time", "2", "--step-size", "0.005"],
        dir.path(),
    );
    assert!(output.status.success(), "stderr: {}", text(&output.stderr));
    let (header, rows) = common::read_results(&dir.path().join("sparse.csv"));
    // Default recording: every output of the pendulum.
    assert!(header.len() > 20 && header.contains(&"load.load.x".to_string()), "{header:?}");
    assert_eq!(rows.len(), 21, "every 0.1 s from 0 to 2 s");
    assert_eq!(rows[20][0], 400.0 * 0.005);
    let summary = read_summary(&dir.path().join("s.json"));
    assert_eq!(summary["steps"], 400);
    assert_eq!(summary["step_size"], 0.005);
}

#[test]
fn failing_run_keeps_rows_and_names_instance_call_variable_and_time() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "nan.csv", Some(0.5));
    let system = pendulum_system("nan.csv", json!({ "input_derivatives": false }));
    write_system(dir.path(), "nan.json", &system);

    let output = crane_cosim(&["run", "nan.json", "-o", "nan.csv.out"], dir.path());
    assert!(!output.status.success(), "the run must fail");
    let stderr = text(&output.stderr);
    let error = stderr.lines().find(|l| l.starts_with("error: ")).unwrap_or_else(|| panic!("no error line: {stderr}"));
    for expected in ["t = 0.5 s", "instance \"load\"", "fmi2SetReal", "tip.x = NaN", "fmi2Error", "the FMU logged"] {
        assert!(error.contains(expected), "{expected:?} missing from: {error}");
    }

    let (header, rows) = common::read_results(&dir.path().join("nan.csv.out"));
    assert_eq!(header.len(), 6);
    assert_eq!(rows.len(), 51, "rows t = 0 ... 0.5 are kept");
    assert_eq!(rows.last().map(|r| r[0]), Some(0.5));
    assert!(rows.iter().all(|row| row.iter().all(|v| v.is_finite())));

    let summary = read_summary(&dir.path().join("nan.csv.summary.json"));
    assert_eq!(summary["status"], "failed");
    assert_eq!(summary["steps_completed"], 50);
    assert_eq!(summary["rows_recorded"], 51);
    assert!(summary["error"].as_str().is_some_and(|e| e.contains("tip.x = NaN")), "{summary}");
}

#[test]
fn invalid_system_file_is_reported_before_running() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    let mut system = pendulum_system("tip.csv", json!({}));
    system["instances"][0]["start"] = json!({ "theta_x9": 0.1 });
    system["record"]["variables"] = json!(["load.thetax", "lod.theta_x"]);
    write_system(dir.path(), "typo.json", &system);

    let output = crane_cosim(&["run", "typo.json", "-o", "typo.csv"], dir.path());
    assert!(!output.status.success());
    let stderr = text(&output.stderr);
    assert!(stderr.contains("typo.json: invalid system file (3 problems)"), "{stderr}");
    assert!(
        stderr.contains("instances[0].start[\"theta_x9\"]") && stderr.contains("did you mean \"theta_x0\"?"),
        "{stderr}"
    );
    assert!(stderr.contains("record.variables[0]") && stderr.contains("did you mean \"theta_x\"?"), "{stderr}");
    assert!(stderr.contains("record.variables[1]: unknown instance \"lod\""), "{stderr}");
    assert!(!dir.path().join("typo.csv").exists(), "nothing ran");
    assert!(!dir.path().join("typo.summary.json").exists(), "no summary without results");
}

/// Before results were written beside their target and renamed into place, a run that failed
/// at initialisation replaced `k.csv` with a bare header (and `k.parquet` with an empty file)
/// and `k.summary.json` with the failure's.
#[test]
fn a_run_that_fails_to_start_leaves_earlier_results_as_they_were() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fmu = common::pendulum_fmu();
    let fmu = fmu.to_str().expect("UTF-8 path");
    for output in ["k.csv", "k.parquet"] {
        std::fs::write(dir.path().join(output), "earlier results").expect("results");
        std::fs::write(dir.path().join("k.summary.json"), "earlier summary").expect("summary");
        let failed = crane_cosim(&["run", fmu, "-o", output, "--start", "theta_x0=99"], dir.path());
        assert_eq!(failed.status.code(), Some(1), "{}", text(&failed.stderr));
        assert!(text(&failed.stderr).contains("'theta_x0' = 99 is outside its range"), "{}", text(&failed.stderr));
        assert_eq!(std::fs::read_to_string(dir.path().join(output)).expect("results"), "earlier results");
        assert_eq!(std::fs::read_to_string(dir.path().join("k.summary.json")).expect("summary"), "earlier summary");
        let names = std::fs::read_dir(dir.path()).expect("dir").map(|e| e.expect("entry").file_name());
        let partial: Vec<_> = names.filter(|name| name.to_string_lossy().ends_with(".partial")).collect();
        assert!(partial.is_empty(), "the partial file of a run without rows is removed: {partial:?}");
    }
    // A misspelled FMU creates neither a results folder nor a summary.
    let missing = crane_cosim(&["run", "cranee.fmu"], dir.path());
    assert_eq!(missing.status.code(), Some(1));
    assert!(!dir.path().join("out").exists(), "out/ was created for a run that never started");
}

#[test]
fn connections_follow_gauss_seidel_and_jacobi_ordering() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    for algorithm in ["gauss-seidel", "jacobi"] {
        write_system(dir.path(), "chain.json", &chain_system(algorithm));
        let output = crane_cosim(&["run", "chain.json", "-o", "chain.csv"], dir.path());
        assert!(output.status.success(), "{algorithm}: {}", text(&output.stderr));
        let (_, rows) = common::read_results(&dir.path().join("chain.csv"));
        assert_eq!(rows.len(), 51);
        assert!(rows.iter().any(|r| r[1] != rows[0][1]), "a.load.y moves");
        assert_eq!(rows[0][2], rows[0][1], "{algorithm}: initialization passes a's output at t0");
        for k in 1..rows.len() {
            let expected = if algorithm == "gauss-seidel" { rows[k][1] } else { rows[k - 1][1] };
            assert_eq!(rows[k][2], expected, "{algorithm}: b.tip.y at row {k}");
        }
        let summary = read_summary(&dir.path().join("chain.summary.json"));
        assert_eq!(summary["algorithm"], algorithm);
    }
}

/// Two pendulums, `b` driven by `a`'s load position, under `algorithm`.
fn chain_system(algorithm: &str) -> Value {
    json!({
        "fmus": { "pendulum": common::pendulum_fmu() },
        "instances": [
            { "name": "a", "fmu": "pendulum", "start": { "theta_x0": 0.3 } },
            { "name": "b", "fmu": "pendulum" }
        ],
        "connections": [ { "from": "a.load.y", "to": "b.tip.y" } ],
        "inputs": [ { "instance": "a", "file": "tip.csv" } ],
        "stop_time": 0.5, "step_size": 0.01, "algorithm": algorithm,
        "record": { "variables": ["a.load.y", "b.tip.y", "b.load.y"] }
    })
}

#[test]
fn extrapolate_inputs_moves_jacobi_only() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    write_system(dir.path(), "chain.json", &chain_system("gauss-seidel"));
    let run = |csv: &str, args: &[&str]| {
        let mut all = vec!["run", "chain.json", "-o", csv, "-q"];
        all.extend(args);
        let output = crane_cosim(&all, dir.path());
        assert!(output.status.success(), "{csv}: {}", text(&output.stderr));
        common::read_results(&dir.path().join(csv)).1
    };
    let seidel = run("seidel.csv", &[]);
    assert_eq!(run("seidel_x.csv", &["--extrapolate-inputs"]), seidel, "Gauss-Seidel ignores the setting");
    let jacobi = run("jacobi.csv", &["--algorithm", "jacobi"]);
    let extrapolated = run("jacobi_x.csv", &["--algorithm", "jacobi", "--extrapolate-inputs"]);
    // Columns: time, a.load.y, b.tip.y, b.load.y. The input's value is still that of t_k; its
    // slope moves b's load from the second step on.
    for (held, moved) in jacobi.iter().zip(&extrapolated) {
        assert_eq!(held[..3], moved[..3]);
    }
    assert_eq!(jacobi[1][3], extrapolated[1][3], "no slope at the first step");
    assert!(jacobi.iter().zip(&extrapolated).any(|(held, moved)| held[3] != moved[3]), "b.load.y moves");
}

#[test]
fn algorithm_option_overrides_the_system_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_tip_inputs(dir.path(), "tip.csv", None);
    write_system(dir.path(), "seidel.json", &chain_system("gauss-seidel"));
    write_system(dir.path(), "jacobi.json", &chain_system("jacobi"));
    let runs = [
        ("seidel.json", "seidel.csv", None),
        ("seidel.json", "overridden.csv", Some("jacobi")),
        ("jacobi.json", "jacobi.csv", None),
    ];
    for (system, csv, algorithm) in runs {
        let mut args = vec!["run", system, "-o", csv, "-q"];
        args.extend(algorithm.iter().flat_map(|a| ["--algorithm", a]));
        let output = crane_cosim(&args, dir.path());
        assert!(output.status.success(), "{csv}: {}", text(&output.stderr));
    }
    let summary = read_summary(&dir.path().join("overridden.summary.json"));
    assert_eq!(summary["algorithm"], "jacobi");
    let results = |csv: &str| std::fs::read(dir.path().join(csv)).expect("results exist");
    assert_eq!(results("overridden.csv"), results("jacobi.csv"), "same as a Jacobi system file");
    // b.tip.y lags a.load.y by one step under Jacobi only.
    assert_ne!(results("overridden.csv"), results("seidel.csv"));

    let output = crane_cosim(&["run", "seidel.json", "--algorithm", "newton"], dir.path());
    assert!(!output.status.success());
    assert!(text(&output.stderr).contains("expected gauss-seidel or jacobi"), "{}", text(&output.stderr));
}

#[test]
fn failed_initialization_frees_the_other_instances_without_terminating_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    let system = common::workspace_root().join("systems/closed_loop.json");
    let scenario = json!({
        "system": system,
        "start": { "platform.profile": 5, "platform.motion_file": "no_such_motion.csv" },
        "stop_time": 0.1
    });
    write_system(dir.path(), "missing_motion.json", &scenario);
    let output = crane_cosim(&["run", "missing_motion.json", "-o", "missing.csv", "--fmu-log"], dir.path());
    assert!(!output.status.success());
    let stderr = text(&output.stderr);
    assert!(stderr.contains("no_such_motion.csv"), "{stderr}");
    // The platform's error is the only one: the other five instances are still in
    // initialization mode, where fmi2Terminate is not allowed, so they are only freed.
    assert_eq!(stderr.matches("logStatusError").count(), 1, "{stderr}");
    assert!(!stderr.contains("fmi2Terminate"), "{stderr}");
}

#[test]
fn info_prints_the_variables_table() {
    let fmu = common::pendulum_fmu();
    let output = crane_cosim(&["info", &fmu.display().to_string()], &common::workspace_root());
    assert!(output.status.success(), "{}", text(&output.stderr));
    let stdout = text(&output.stdout);
    assert!(stdout.contains("model          pendulum"), "{stdout}");
    assert!(stdout.contains("canInterpolateInputs"), "{stdout}");
    let header = stdout.lines().find(|l| l.starts_with("name ")).expect("table header");
    assert!(header.contains("causality") && header.contains("unit"), "{header}");
    for variable in ["theta_x0", "tip.x", "lp_ddot", "load.q0", "tension"] {
        assert!(stdout.lines().any(|l| l.starts_with(&format!("{variable} "))), "{variable} missing:\n{stdout}");
    }
}

#[test]
fn info_lists_the_range_and_the_platforms_and_filters_by_causality_as_json() {
    let fmu = common::pendulum_fmu();
    let fmu = fmu.to_str().expect("utf-8 path");
    let output = crane_cosim(&["info", fmu, "--json", "--causality", "parameter,input"], &common::workspace_root());
    assert!(output.status.success(), "{}", text(&output.stderr));
    let info: serde_json::Value = serde_json::from_str(&text(&output.stdout)).expect("JSON on stdout");
    assert_eq!(info["modelName"], "pendulum");
    assert!(info["platforms"].as_array().expect("platforms").iter().any(|p| p == "linux64"), "{info}");
    let variables = info["variables"].as_array().expect("variables");
    assert!(variables.iter().all(|v| v["causality"] == "parameter" || v["causality"] == "input"), "{info}");
    assert!(variables.iter().any(|v| v["causality"] == "input"), "{info}");
    let theta = variables.iter().find(|v| v["name"] == "theta_x0").expect("theta_x0");
    // The model description's attributes, the start typed as the variable is.
    assert_eq!((theta["min"].as_str(), theta["max"].as_str()), (Some("-1.5"), Some("1.5")), "{theta}");
    assert_eq!(theta["start"], serde_json::json!(0.0));
    assert_eq!(theta["valueReference"], 0);
}

#[test]
fn info_table_shows_min_max_and_only_the_causality_asked_for() {
    let fmu = common::pendulum_fmu();
    let fmu = fmu.to_str().expect("utf-8 path");
    let output = crane_cosim(&["info", fmu, "--causality", "input", "--width", "0"], &common::workspace_root());
    assert!(output.status.success(), "{}", text(&output.stderr));
    let stdout = text(&output.stdout);
    // The folder names under binaries/, sorted (aarch64-linux and win64 too when cross-built).
    let platforms = stdout.lines().find_map(|l| l.strip_prefix("platforms ")).expect("platforms line");
    assert!(platforms.split_whitespace().any(|p| p == "linux64"), "{stdout}");
    let header = stdout.lines().find(|l| l.starts_with("name ")).expect("table header");
    assert!(header.contains(" min ") && header.contains(" max "), "{header}");
    let rows: Vec<&str> = stdout.lines().skip_while(|l| !l.starts_with("name ")).skip(1).collect();
    assert!(rows.iter().any(|r| r.starts_with("tip.x ")), "{stdout}");
    assert!(rows.iter().all(|r| r.contains(" input ")), "{stdout}");
    let refused = crane_cosim(&["info", fmu, "--causality", "inptu"], &common::workspace_root());
    assert!(!refused.status.success());
    assert!(text(&refused.stderr).contains("'inptu' is not a causality: one of"), "{}", text(&refused.stderr));
}

#[test]
fn info_lines_fit_the_width_for_every_packaged_fmu() {
    let root = common::workspace_root();
    let fmus: Vec<_> = std::fs::read_dir(root.join("target/fmu"))
        .expect("target/fmu")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "fmu"))
        .collect();
    assert!(fmus.len() >= 5, "{fmus:?}");
    for fmu in &fmus {
        for width in ["100", "140"] {
            let fmu_text = fmu.to_str().expect("utf-8 path");
            let output = crane_cosim(&["info", fmu_text, "--width", width], &root);
            assert!(output.status.success(), "{}", text(&output.stderr));
            let stdout = text(&output.stdout);
            let limit: usize = width.parse().expect("width");
            // The first line carries the path the test passed, which the FMU cannot shorten.
            for line in stdout.lines().skip(1) {
                assert!(line.chars().count() <= limit, "{} at width {width}:\n{line}", fmu.display());
            }
            // Every description is still there, wrapped rather than cut.
            let words = |s: &str| s.split_whitespace().map(String::from).collect::<Vec<_>>().join(" ");
            let wide = text(&crane_cosim(&["info", fmu_text, "--json"], &root).stdout);
            let info: serde_json::Value = serde_json::from_str(&wide).expect("JSON");
            let all = words(&stdout);
            for v in info["variables"].as_array().expect("variables") {
                let description = v["description"].as_str().unwrap_or_default();
                assert!(all.contains(&words(description)), "{description} missing at width {width}");
            }
        }
    }
}

#[test]
fn info_of_a_missing_file_fails_cleanly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let output = crane_cosim(&["info", "nothing.fmu"], dir.path());
    assert!(!output.status.success());
    let stderr = text(&output.stderr);
    assert!(stderr.starts_with("error: cannot open nothing.fmu"), "{stderr}");
}

#[test]
fn output_dash_writes_the_csv_to_standard_output_and_the_messages_to_standard_error() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fmu = common::pendulum_fmu();
    let fmu = fmu.to_str().expect("utf-8 path");
    let args =
        |output: &str| ["run", fmu, "--start", "theta_x0=-0.2", "--stop-time", "0.5", "-o", output].map(String::from);
    let to_file = crane_cosim(&args("file.csv").iter().map(String::as_str).collect::<Vec<_>>(), dir.path());
    assert!(to_file.status.success(), "{}", text(&to_file.stderr));
    let piped = crane_cosim(&args("-").iter().map(String::as_str).collect::<Vec<_>>(), dir.path());
    assert!(piped.status.success(), "{}", text(&piped.stderr));
    // The same bytes as the file, and nothing else on standard output.
    assert_eq!(text(&piped.stdout), std::fs::read_to_string(dir.path().join("file.csv")).expect("file.csv"));
    assert!(text(&piped.stderr).contains("51 rows written to standard output"), "{}", text(&piped.stderr));
    // No summary unless asked for, and no file named "-".
    let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").map(|e| e.expect("entry").file_name()).collect();
    assert_eq!(left.len(), 2, "{left:?}");
    assert!(dir.path().join("file.summary.json").is_file());
}

#[test]
fn a_lone_fmu_takes_start_values_named_like_its_columns_and_bad_durations_name_their_option() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fmu = common::pendulum_fmu();
    let fmu = fmu.to_str().expect("utf-8 path");
    // `pendulum.theta_x0` as the CSV's column names it, and `theta_x0` as the FMU does: the same run.
    for (name, csv) in [("pendulum.theta_x0", "qualified.csv"), ("theta_x0", "plain.csv")] {
        let start = format!("{name}=-0.2");
        let out = crane_cosim(&["run", fmu, "--start", &start, "--stop-time", "0.2", "-q", "-o", csv], dir.path());
        assert!(out.status.success(), "{name}: {}", text(&out.stderr));
    }
    let read = |csv: &str| std::fs::read_to_string(dir.path().join(csv)).expect("csv");
    assert_eq!(read("qualified.csv"), read("plain.csv"));
    assert!(read("plain.csv").lines().nth(1).expect("first row").starts_with("0.0,-0.2,"));
    // A bad step or recording interval is the option's error, not the system file's.
    for (option, value) in [("--step-size", "-1"), ("--step-size", "0"), ("--record-interval", "nan")] {
        let out = crane_cosim(&["run", fmu, option, value], dir.path());
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{option} {value}");
        assert!(stderr.starts_with(&format!("error: invalid value '{value}' for '{option} ")), "{stderr}");
        assert!(!stderr.contains("system file"), "{stderr}");
    }
}

#[test]
fn a_step_longer_than_a_controllers_sample_period_is_warned_of_by_the_fmu() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = common::workspace_root().join("scenarios/demo_still_off.json").display().to_string();
    let run = |step: &str| {
        let args = ["run", &scenario, "--step-size", step, "--stop-time", "0.2", "-q", "-o", "s.csv"];
        let output = crane_cosim(&args, dir.path());
        assert!(output.status.success(), "{}", text(&output.stderr));
        text(&output.stderr)
    };
    // The controller samples at 100 Hz: a 50 ms step holds its inputs over five samples.
    let stderr = run("0.05");
    let warning = "communicationStepSize 0.05 s is longer than this FMU's largest sensible step, 0.01 s";
    assert_eq!(stderr.matches(warning).count(), 1, "{stderr}");
    assert!(stderr.lines().any(|line| line.starts_with("controller: ") && line.contains(warning)), "{stderr}");
    assert!(!run("0.01").contains("largest sensible step"));
}
