//! What a run records and where: patterns in a file's `record.variables`, `--record` and
//! `--input` on systems and scenarios, the warning for inputs nothing feeds, and results in
//! Parquet.
//!
//! Needs `target/fmu/` as `cargo xtask package` leaves it.

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, failed, succeeded, succeeded_stderr, text};

use std::path::Path;

use parquet::file::reader::{FileReader, SerializedFileReader};

fn header(csv: &Path) -> Vec<String> {
    common::read_results(csv).0
}

/// A system of one pendulum instance `load` with `record` and the tip's start values.
fn pendulum_system(dir: &Path, record: serde_json::Value, start: serde_json::Value) {
    let system = serde_json::json!({
        "fmus": { "pendulum": common::pendulum_fmu() },
        "instances": [ { "name": "load", "fmu": "pendulum", "start": start } ],
        "stop_time": 0.5, "step_size": 0.01, "record": record
    });
    std::fs::write(dir.join("system.json"), system.to_string()).unwrap();
}

/// Every input of the pendulum at its default, so that no warning is due.
fn all_inputs_started() -> serde_json::Value {
    let names = ["tip.x", "tip.y", "tip.z", "tip.vx", "tip.vy", "tip.vz", "tip.ax", "tip.ay", "tip.az", "lp"];
    let mut start: serde_json::Map<String, serde_json::Value> =
        names.iter().map(|n| (n.to_string(), 0.0.into())).collect();
    start.insert("lp".into(), 0.7.into());
    start.insert("lp_dot".into(), 0.0.into());
    start.insert("lp_ddot".into(), 0.0.into());
    start.into()
}

#[test]
fn patterns_in_the_file_and_on_the_command_line_add_columns_to_a_system() {
    let dir = tempfile::tempdir().unwrap();
    let record = serde_json::json!({ "variables": ["load.tension", "load.theta_*"] });
    pendulum_system(dir.path(), record, all_inputs_started());
    let stderr = succeeded_stderr(&crane_cosim(
        &["run", "system.json", "--record", "load.load.?", "-q", "-o", "a.csv"],
        dir.path(),
    ));
    assert!(!stderr.contains("warning"), "{stderr}");
    // The file's columns first (a pattern matches outputs and locals, not the parameters
    // theta_x0, theta_y0), then the added ones.
    assert_eq!(
        header(&dir.path().join("a.csv")),
        ["time", "load.tension", "load.theta_x", "load.theta_y", "load.load.x", "load.load.y", "load.load.z"]
    );
    // An exact name records a parameter; a name already recorded is not added twice.
    let args = ["run", "system.json", "--record", "load.theta_x0", "--record", "load.theta_x", "-q", "-o", "b.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    assert_eq!(
        header(&dir.path().join("b.csv"))[1..],
        ["load.tension", "load.theta_x", "load.theta_y", "load.theta_x0"]
    );

    // A pattern matching nothing names itself with a suggestion; one matching only parameters says so.
    let stderr = failed(&crane_cosim(&["run", "system.json", "--record", "load.thet_*", "-o", "c.csv"], dir.path()));
    assert!(
        stderr.contains("--record load.thet_*: pattern \"load.thet_*\" matches no output or local variable (did you mean \"load.theta_x\"?)"),
        "{stderr}"
    );
    let stderr = failed(&crane_cosim(&["run", "system.json", "--record", "load.theta_?0", "-o", "c.csv"], dir.path()));
    assert!(stderr.contains("it matches only parameters or inputs (\"load.theta_x0\", \"load.theta_y0\")"), "{stderr}");
    let record = serde_json::json!({ "variables": ["load.tension", "lod.*"] });
    pendulum_system(dir.path(), record, all_inputs_started());
    let stderr = failed(&crane_cosim(&["run", "system.json", "-o", "c.csv"], dir.path()));
    assert!(
        stderr.contains("record.variables[1]: unknown instance \"lod\" in \"lod.*\" (did you mean \"load\"?)"),
        "{stderr}"
    );

    // A scenario of the shipped closed loop takes --record too.
    let scenario = common::workspace_root().join("scenarios/demo_still_off.json").display().to_string();
    let args = ["run", &scenario, "--stop-time", "0.05", "--record", "crane.tip.*", "-q", "-o", "d.csv"];
    let output = crane_cosim(&args, dir.path());
    succeeded(&output);
    let stderr = text(&output.stderr);
    assert!(!stderr.contains("warning"), "the shipped closed loop feeds or starts every input: {stderr}");
    let columns = header(&dir.path().join("d.csv"));
    let tip: Vec<&String> = columns.iter().filter(|c| c.starts_with("crane.tip.")).collect();
    assert!(tip.len() >= 3 && columns.iter().position(|c| c == "crane.tip.x") > Some(1), "{columns:?}");
    assert_eq!(columns.iter().filter(|c| *c == "crane.tip.x").count(), 1, "{columns:?}");
}

#[test]
fn an_input_table_feeds_a_system_and_unfed_inputs_are_listed_once() {
    let dir = tempfile::tempdir().unwrap();
    let record = serde_json::json!({ "variables": ["load.tip.x", "load.theta_x"] });
    pendulum_system(dir.path(), record, serde_json::json!({ "lp": 0.7 }));
    std::fs::write(dir.path().join("tip.csv"), "time,load.tip.x,load.tip.vx\n0,0,0.1\n1,0.1,0.1\n").unwrap();
    let stderr =
        succeeded_stderr(&crane_cosim(&["run", "system.json", "--input", "tip.csv", "-q", "-o", "a.csv"], dir.path()));
    let warnings: Vec<&str> = stderr.lines().filter(|l| l.starts_with("warning:")).collect();
    assert_eq!(warnings.len(), 1, "{stderr}");
    assert!(warnings[0].contains("load.tip.y, load.tip.z, load.tip.vy"), "{stderr}");
    assert!(!warnings[0].contains("load.tip.x,") && !warnings[0].contains("load.lp,"), "{stderr}");
    let (_, rows) = common::read_results(&dir.path().join("a.csv"));
    // The input recorded at t = 0.5 s is the one set for the step that ended there (at 0.49 s).
    assert!((rows[50][1] - 0.049).abs() < 1e-12, "{:?}", rows[50]);

    std::fs::write(dir.path().join("bad.csv"), "time,load.theta_x,tip.y\n0,0,0\n1,0,0\n").unwrap();
    let stderr = failed(&crane_cosim(&["run", "system.json", "--input", "bad.csv", "-o", "b.csv"], dir.path()));
    assert!(
        stderr.contains("--input bad.csv (column \"load.theta_x\"): variable \"theta_x\" of instance \"load\" is"),
        "{stderr}"
    );
    assert!(stderr.contains("(column \"tip.y\"): unknown instance \"tip\" in \"tip.y\""), "{stderr}");
    // An input the file already feeds is refused.
    let args = ["run", "system.json", "--input", "tip.csv", "--input", "tip.csv", "-o", "c.csv"];
    assert!(failed(&crane_cosim(&args, dir.path())).contains("input \"load.tip.x\" is already fed by"));
}

/// The values of a Parquet file's columns, as f64 bits, with its names and units metadata.
fn read_parquet(file: &Path) -> (Vec<String>, Vec<Vec<u64>>, serde_json::Value) {
    let reader = SerializedFileReader::new(std::fs::File::open(file).unwrap()).unwrap();
    let metadata = reader.metadata().file_metadata();
    let units = metadata.key_value_metadata().unwrap().iter().find(|kv| kv.key == "units").unwrap();
    let units = serde_json::from_str(units.value.as_deref().unwrap()).unwrap();
    let names = metadata.schema_descr().columns().iter().map(|c| c.name().to_string()).collect();
    let rows = reader
        .get_row_iter(None)
        .unwrap()
        .map(|row| {
            let row = row.unwrap();
            (0..row.len()).map(|i| parquet::record::RowAccessor::get_double(&row, i).unwrap().to_bits()).collect()
        })
        .collect();
    (names, rows, units)
}

#[test]
fn results_in_parquet_hold_the_csv_values_bit_for_bit_with_their_units() {
    let dir = tempfile::tempdir().unwrap();
    let pendulum = common::pendulum_fmu().display().to_string();
    let run = |output: &str| {
        let args = ["run", &pendulum, "--stop-time", "1", "--start", "theta_x0=-0.3", "--flush-rows", "7", "-q"];
        succeeded(&crane_cosim(&[&args[..], &["-o", output]].concat(), dir.path()));
    };
    run("r.csv");
    run("r.parquet");
    let bytes = std::fs::read(dir.path().join("r.parquet")).unwrap();
    assert_eq!(&bytes[..4], b"PAR1", "not CSV text");
    let (csv_names, csv_rows) = common::read_results(&dir.path().join("r.csv"));
    let (names, rows, units) = read_parquet(&dir.path().join("r.parquet"));
    assert_eq!(names, csv_names);
    assert_eq!(rows.len(), 101);
    let csv_bits: Vec<Vec<u64>> = csv_rows.iter().map(|row| row.iter().map(|x| x.to_bits()).collect()).collect();
    assert_eq!(rows, csv_bits);
    assert_eq!(units["time"], "s");
    assert_eq!(units["pendulum.theta_x"], "rad");
    assert_eq!(units["pendulum.load.x"], "m");
    let summary = std::fs::read_to_string(dir.path().join("r.summary.json")).unwrap();
    assert!(summary.contains("\"rows_recorded\": 101"), "{summary}");
}

#[test]
fn a_run_that_fails_leaves_a_readable_parquet_file_with_its_rows() {
    let dir = tempfile::tempdir().unwrap();
    // An input table with NaN from t = 0.2 s: the pendulum refuses it and the run fails there.
    std::fs::write(dir.path().join("lp.csv"), "time,lp\n0,0.7\n0.2,0.7\n0.2,NaN\n1,NaN\n").unwrap();
    let pendulum = common::pendulum_fmu().display().to_string();
    let args = ["run", &pendulum, "--stop-time", "1", "--input", "lp.csv", "--record", "theta_x", "-o", "f.parquet"];
    let stderr = failed(&crane_cosim(&args, dir.path()));
    assert!(stderr.contains("simulation stopped at t = 0.2 s"), "{stderr}");
    let (names, rows, _) = read_parquet(&dir.path().join("f.parquet"));
    assert_eq!(names, ["time", "pendulum.theta_x"]);
    assert!(!rows.is_empty() && rows.len() < 101, "{} rows", rows.len());
}
