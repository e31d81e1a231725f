//! The command line without system files and on any results: `run X.fmu`, `--start`, start
//! values that are paths, `compare` on named columns and `plot` with several columns.
//!
//! Needs `target/fmu/pendulum.fmu` and `target/fmu/platform.fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, failed, fmu, succeeded};

use std::path::{Path, PathBuf};

use serde_json::{json, Value};

/// Writes the CSV `path`: the line `header`, then the line `row(t)` for each t = k · `step`,
/// k = 0 to `last`.
fn write_samples(path: &Path, header: &str, last: u32, step: f64, row: impl Fn(f64) -> String) {
    let mut csv = format!("{header}\n");
    for k in 0..=last {
        csv += &row(k as f64 * step);
        csv.push('\n');
    }
    std::fs::write(path, csv).unwrap();
}

/// A free pendulum (instance `load`) released from −0.3 rad, recorded to `decay.csv` in `dir`.
fn free_pendulum_run(dir: &Path) -> PathBuf {
    let system = json!({
        "fmus": { "pendulum": fmu("pendulum") },
        "instances": [ { "name": "load", "fmu": "pendulum", "start": { "theta_x0": -0.3, "lp": 0.7 } } ],
        "stop_time": 20.0, "step_size": 0.01,
        "record": { "variables": ["load.theta_x", "load.theta_y", "load.load.x", "load.load.y", "load.load.z"] }
    });
    std::fs::write(dir.join("decay.json"), system.to_string()).unwrap();
    succeeded(&crane_cosim(&["run", "decay.json", "-o", "decay.csv", "-q"], dir));
    dir.join("decay.csv")
}

#[test]
fn an_fmu_runs_alone_with_start_values_record_patterns_and_units_in_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let pendulum = fmu("pendulum");
    let args = ["run", &pendulum, "--start", "theta_x0=-0.4", "--stop-time", "2", "--record", "theta_?"];
    succeeded(&crane_cosim(&[&args[..], &["--record", "load.?", "-o", "single.csv"]].concat(), dir.path()));
    let (header, rows) = common::read_results(&dir.path().join("single.csv"));
    // `theta_?` matches theta_x and theta_y, not the parameter theta_x0; the instance is named
    // after the file.
    let expected =
        ["time", "pendulum.theta_x", "pendulum.theta_y", "pendulum.load.x", "pendulum.load.y", "pendulum.load.z"];
    assert_eq!(header, expected);
    assert_eq!(rows.len(), 201, "2 s at the default experiment's 10 ms");
    assert_eq!(rows[0][1], -0.4, "the start value reached the FMU");

    let summary: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("single.summary.json")).unwrap())
            .expect("summary is JSON");
    assert_eq!(summary["columns"][0], json!({ "name": "pendulum.theta_x", "unit": "rad" }));
    assert_eq!(summary["columns"][4], json!({ "name": "pendulum.load.z", "unit": "m" }));

    // Without --stop-time the FMU's default experiment (60 s) holds.
    succeeded(&crane_cosim(&["run", &pendulum, "--record", "theta_x", "-o", "default.csv", "-q"], dir.path()));
    assert_eq!(common::read_results(&dir.path().join("default.csv")).1.len(), 6001);

    let stderr = failed(&crane_cosim(&["run", &pendulum, "--record", "thet_*", "-o", "x.csv"], dir.path()));
    assert!(
        stderr.contains(
            "--record pendulum.thet_*: pattern \"pendulum.thet_*\" matches no output or local variable (did you \
             mean \"pendulum.theta_x\"?)"
        ),
        "{stderr}"
    );
}

#[test]
fn an_fmu_runs_alone_on_an_inputs_file() {
    let dir = tempfile::tempdir().unwrap();
    // Tip x = 5 cm · sin(2t) at 50 ms samples.
    write_samples(&dir.path().join("tip.csv"), "time,tip.x,tip.vx,tip.ax", 40, 0.05, |t| {
        format!("{t:?},{:?},{:?},{:?}", 0.05 * (2.0 * t).sin(), 0.1 * (2.0 * t).cos(), -0.2 * (2.0 * t).sin())
    });
    let pendulum = fmu("pendulum");
    let args = ["run", &pendulum, "--input", "tip.csv", "--stop-time", "1", "--record", "tip.x", "-o", "driven.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    let (_, rows) = common::read_results(&dir.path().join("driven.csv"));
    // An input recorded at t_{k+1} holds the value set at t_k for that step: row 51 shows the
    // file's sample at t = 0.5 s exactly.
    assert_eq!(rows[51][1], 0.05 * 1f64.sin());
    assert_eq!(rows[0][1], 0.0);
}

/// A system of one pendulum `load` in `systems/`, and a scenario of it in `cases/`.
fn pendulum_scenario(dir: &Path) {
    std::fs::create_dir_all(dir.join("systems")).unwrap();
    std::fs::create_dir_all(dir.join("cases")).unwrap();
    let system = json!({
        "fmus": { "pendulum": fmu("pendulum") },
        "instances": [ { "name": "load", "fmu": "pendulum", "start": { "lp": 0.7 } } ],
        "stop_time": 0.1, "step_size": 0.01,
        "record": { "variables": ["load.theta_x"] }
    });
    std::fs::write(dir.join("systems/one.json"), system.to_string()).unwrap();
    let scenario = json!({ "system": "../systems/one.json", "start": { "load.theta_x0": -0.2 } });
    std::fs::write(dir.join("cases/tilted.json"), scenario.to_string()).unwrap();
}

#[test]
fn start_values_on_the_command_line_replace_a_scenario_s() {
    let dir = tempfile::tempdir().unwrap();
    pendulum_scenario(dir.path());
    succeeded(&crane_cosim(&["run", "cases/tilted.json", "-o", "a.csv", "-q"], dir.path()));
    assert_eq!(common::read_results(&dir.path().join("a.csv")).1[0][1], -0.2);
    let args = ["run", "cases/tilted.json", "--start", "load.theta_x0=-0.3", "-o", "b.csv", "-q"];
    succeeded(&crane_cosim(&args, dir.path()));
    assert_eq!(common::read_results(&dir.path().join("b.csv")).1[0][1], -0.3);

    let stderr = failed(&crane_cosim(&["run", "cases/tilted.json", "--start", "lod.theta_x0=1"], dir.path()));
    assert!(stderr.contains("--start lod.theta_x0: unknown instance 'lod' (instances: load)"), "{stderr}");
    let stderr = failed(&crane_cosim(&["run", "cases/tilted.json", "--start", "theta_x0"], dir.path()));
    assert!(stderr.contains("\"theta_x0\": expected NAME=VALUE"), "{stderr}");
}

#[test]
fn a_path_start_value_is_relative_to_the_scenario_file() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("systems")).unwrap();
    std::fs::create_dir_all(dir.path().join("cases")).unwrap();
    let system = json!({
        "fmus": { "platform": fmu("platform") },
        "instances": [ { "name": "platform", "fmu": "platform", "start": { "profile": 5 } } ],
        "stop_time": 0.5, "step_size": 0.01,
        "record": { "variables": ["platform.ship.x"] }
    });
    std::fs::write(dir.path().join("systems/platform.json"), system.to_string()).unwrap();
    // 2 cm of surge throughout, next to the scenario (the FMU alone would look in its resources/).
    std::fs::write(dir.path().join("cases/surge.csv"), "0,0.02,0,0,0,0,0\n10,0.02,0,0,0,0,0\n").unwrap();
    let scenario = json!({
        "system": "../systems/platform.json",
        "start": { "platform.motion_file": { "path": "surge.csv" } }
    });
    std::fs::write(dir.path().join("cases/surge.json"), scenario.to_string()).unwrap();
    succeeded(&crane_cosim(&["run", "cases/surge.json", "-o", "surge_out.csv", "-q"], dir.path()));
    let (_, rows) = common::read_results(&dir.path().join("surge_out.csv"));
    assert!(rows.iter().all(|r| (r[1] - 0.02).abs() < 1e-12), "the deck follows the file: {:?}", rows[10]);
}

#[test]
fn compare_reads_named_columns_and_refuses_a_window_past_the_data() {
    let dir = tempfile::tempdir().unwrap();
    free_pendulum_run(dir.path());
    // The closed loop's columns are the default: a free pendulum has none of them.
    let stderr = failed(&crane_cosim(&["compare", "decay.csv"], dir.path()));
    assert!(stderr.contains("no column 'pendulum.load.x'") && stderr.contains("--position"), "{stderr}");

    let named = ["compare", "--angles", "load.theta_x,load.theta_y", "--position", "load.load."];
    let table = succeeded(&crane_cosim(&[&named[..], &["--target", "none", "decay.csv"]].concat(), dir.path()));
    let row = table.lines().nth(1).expect("a row");
    assert!(row.starts_with("decay") && row.contains("never") && row.contains(" — "), "{table}");

    // The load as its own target: RMSE 0; 20 s of a 0.3 rad swing travel metres.
    let json =
        succeeded(&crane_cosim(&[&named[..], &["--target", "load.load.", "--json", "decay.csv"]].concat(), dir.path()));
    let rows: Value = serde_json::from_str(&json).expect("JSON output");
    assert_eq!(rows[0]["rmse_m"], json!(0.0));
    assert!(rows[0]["distance_m"].as_f64().unwrap() > 1.0, "{json}");
    assert!(rows[0]["final_swing_rad"].as_f64().unwrap() > 0.2, "{json}");
    assert_eq!(rows[0]["settling_s"], Value::Null);

    let stderr =
        failed(&crane_cosim(&[&named[..], &["--target", "none", "--from", "25", "decay.csv"]].concat(), dir.path()));
    assert!(stderr.contains("decay.csv: the window starts at 25 s, not before the last sample at 20 s"), "{stderr}");
    std::fs::create_dir(dir.path().join("folder.csv")).unwrap();
    let stderr = failed(&crane_cosim(&["compare", "folder.csv"], dir.path()));
    assert!(stderr.contains("folder.csv: cannot read: not a regular file"), "{stderr}");
}

#[test]
fn compare_does_not_call_a_swing_settled_that_crosses_zero_at_the_end() {
    // A 0.3 rad swing of period 1.6 s that decays slowly, recorded up to a zero crossing: the
    // last samples are inside the ±2° band, but the swing's envelope is not.
    let dir = tempfile::tempdir().unwrap();
    let header = "time,a.theta_x,a.theta_y,a.load.x,a.load.y,a.load.z";
    write_samples(&dir.path().join("swing.csv"), header, 2000, 0.01, |t| {
        let theta = 0.3 * (-t / 200.0).exp() * (std::f64::consts::TAU * t / 1.6).sin();
        format!("{t},{theta},0,{},0,0.7", 0.7 * theta.sin())
    });
    let named = ["compare", "--angles", "a.theta_x,a.theta_y", "--position", "a.load.", "--target", "none"];
    let json = succeeded(&crane_cosim(&[&named[..], &["--json", "swing.csv"]].concat(), dir.path()));
    let rows: Value = serde_json::from_str(&json).expect("JSON output");
    assert_eq!(rows[0]["settling_s"], Value::Null, "{json}");
    assert!(rows[0]["final_swing_rad"].as_f64().unwrap() > 0.2, "{json}");
}

#[test]
fn plot_says_what_it_wrote_and_suggests_the_closest_column_for_a_misspelt_one() {
    let dir = tempfile::tempdir().unwrap();
    free_pendulum_run(dir.path());
    let stdout = succeeded(&crane_cosim(&["plot", "-c", "load.theta_x", "-o", "x.svg", "decay.csv"], dir.path()));
    assert_eq!(stdout, "wrote x.svg (1 curve)\n");
    let stdout =
        succeeded(&crane_cosim(&["plot", "-c", "load.load.*", "--panels", "-o", "l.png", "decay.csv"], dir.path()));
    assert_eq!(stdout, "wrote l.png (3 curves in 3 panels)\n");
    let stderr = failed(&crane_cosim(&["plot", "-c", "load.thetax", "-o", "x.svg", "decay.csv"], dir.path()));
    assert!(stderr.contains("decay: no column matches \"load.thetax\" (did you mean \"load.theta_x\"?)"), "{stderr}");
    assert!(!stderr.contains("columns:"), "{stderr}");
}

#[test]
fn archive_limits_are_options_of_the_commands_that_open_fmus_only() {
    let dir = tempfile::tempdir().unwrap();
    for command in ["run", "export", "info", "campaign", "tune", "view", "live"] {
        let help = succeeded(&crane_cosim(&[command, "--help"], dir.path()));
        assert!(help.contains("--max-unpacked-size <SIZE>"), "{command}: {help}");
    }
    let help = succeeded(&crane_cosim(&["sweep", "run", "--help"], dir.path()));
    assert!(help.contains("--max-archive-entries <N>"), "{help}");
    for command in [&["compare"][..], &["plot"], &["completions"], &["man"], &["sweep", "collect"], &["sweep", "plan"]]
    {
        let help = succeeded(&crane_cosim(&[command, &["--help"]].concat(), dir.path()));
        assert!(!help.contains("--max-unpacked-size") && !help.contains("archive limits"), "{command:?}: {help}");
    }
    let stderr = failed(&crane_cosim(&["compare", "--max-unpacked-size", "1G", "a.csv"], dir.path()));
    assert!(stderr.contains("unexpected argument '--max-unpacked-size'"), "{stderr}");
}

/// The curves of an SVG plot (polylines of width 2), as their point counts.
fn curves(svg: &str) -> Vec<usize> {
    svg.split("<polyline")
        .skip(1)
        .filter(|element| element.contains("stroke-width=\"2\""))
        .filter_map(|element| {
            element.split("points=\"").nth(1)?.split('"').next().map(|p| p.split_whitespace().count())
        })
        .filter(|&points| points > 2) // legend samples are two points
        .collect()
}

#[test]
fn plot_draws_several_columns_and_files_in_svg_within_a_time_window() {
    let dir = tempfile::tempdir().unwrap();
    free_pendulum_run(dir.path());
    std::fs::copy(dir.path().join("decay.csv"), dir.path().join("again.csv")).unwrap();
    let args =
        ["plot", "-c", "load.theta_?", "--from", "5", "--to", "10", "-o", "angles.svg", "decay.csv", "again.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    let svg = std::fs::read_to_string(dir.path().join("angles.svg")).unwrap();
    // Two columns of two files, 5 s of 10 ms samples each.
    assert_eq!(curves(&svg), vec![501; 4], "curves and their points");

    let args = ["plot", "-c", "load.load.*", "--panels", "-o", "load.png", "decay.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    let png = std::fs::read(dir.path().join("load.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");

    let stderr = failed(&crane_cosim(&["plot", "-c", "load.theta_x", "-o", "x.jpg", "decay.csv"], dir.path()));
    assert!(stderr.contains("x.jpg: unknown image format: the file name must end in .png or .svg"), "{stderr}");
    let stderr =
        failed(&crane_cosim(&["plot", "-c", "load.theta_x", "--from", "30", "-o", "x.svg", "decay.csv"], dir.path()));
    assert!(stderr.contains("no data between --from and --to for load.theta_x"), "{stderr}");
    let stderr = failed(&crane_cosim(&["plot", "-c", "theta", "-o", "x.svg", "decay.csv"], dir.path()));
    assert!(stderr.contains("decay: no column matches \"theta\" (columns: load.theta_x,"), "{stderr}");
}

#[test]
fn a_bad_start_value_of_the_command_line_is_named_by_its_option_not_by_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let pendulum = fmu("pendulum");
    // Alone: the FMU is no system file, and the value was the command line's.
    let alone = failed(&crane_cosim(&["run", &pendulum, "--start", "theta_x0=abc", "--stop-time", "1"], dir.path()));
    assert!(alone.contains("invalid start value (1 problem)"), "{alone}");
    assert!(alone.contains("--start pendulum.theta_x0: variable \"theta_x0\" is Real: expected a number"), "{alone}");
    assert!(!alone.contains("instances[0]") && !alone.contains("system file"), "{alone}");
    // In a system file: the same words, and the file's own mistakes still name the file's place.
    let system = common::workspace_root().join("systems/pendulum_free_decay.json");
    let system = system.to_str().unwrap();
    let ours = failed(&crane_cosim(&["run", system, "--start", "load.theta_x0=abc", "--stop-time", "1"], dir.path()));
    assert!(ours.contains("--start load.theta_x0: variable \"theta_x0\" is Real"), "{ours}");
    let broken = json!({
        "fmus": { "pendulum": pendulum },
        "instances": [ { "name": "load", "fmu": "pendulum", "start": { "lp": "long" } } ],
        "stop_time": 1.0, "step_size": 0.01
    });
    std::fs::write(dir.path().join("broken.json"), broken.to_string()).unwrap();
    let both = failed(&crane_cosim(&["run", "broken.json", "--start", "load.theta_x0=abc"], dir.path()));
    assert!(both.contains("invalid system file (2 problems)"), "{both}");
    assert!(both.contains("instances[0].start[\"lp\"]") && both.contains("--start load.theta_x0"), "{both}");
}
