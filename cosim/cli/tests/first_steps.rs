//! What a new user meets first: a file with a JSON syntax error, a changed step size, a stop time
//! off the step grid, and one FMU run on its own reference input.
//!
//! Needs `target/fmu/` as `cargo xtask package` leaves it (FMUs and reference files).

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, failed, succeeded};

use std::path::Path;

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

/// The times of a results CSV.
fn times(csv: &Path) -> Vec<f64> {
    common::read_results(csv).1.iter().map(|row| row[0]).collect()
}

#[test]
fn the_recording_interval_follows_the_step_unless_given() {
    let dir = tempfile::tempdir().unwrap();
    let pendulum = common::pendulum_fmu().display().to_string();
    let system = |record: serde_json::Value| {
        let system = serde_json::json!({
            "fmus": { "pendulum": pendulum },
            "instances": [ { "name": "load", "fmu": "pendulum" } ],
            "stop_time": 0.2, "step_size": 0.01, "record": record
        });
        system.to_string()
    };
    std::fs::write(dir.path().join("implicit.json"), system(serde_json::json!({ "variables": ["load.theta_x"] })))
        .unwrap();
    let args = ["run", "implicit.json", "--step-size", "0.02", "-q", "-o", "coarse.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    assert_eq!(times(&dir.path().join("coarse.csv")), (0..=10).map(|k| k as f64 * 0.02).collect::<Vec<_>>());

    // The shipped files leave the interval implicit: their scenarios follow the step.
    let scenario = common::workspace_root().join("scenarios/demo_still_off.json").display().to_string();
    let coarse = ["run", &scenario, "--step-size", "0.02", "--stop-time", "1"];
    succeeded(&crane_cosim(&[&coarse[..], &["-q", "-o", "coarse_scenario.csv"]].concat(), dir.path()));
    let expected: Vec<f64> = (0..=50).map(|k| k as f64 * 0.02).collect();
    let recorded = times(&dir.path().join("coarse_scenario.csv"));
    assert_eq!(recorded.len(), expected.len());
    assert!(recorded.iter().zip(&expected).all(|(a, b)| (a - b).abs() < 1e-12), "{recorded:?}");

    // An interval a file states explicitly that no longer fits: the message names the option,
    // which then makes the file run.
    let explicit = serde_json::json!({ "interval": 0.01, "variables": ["load.theta_x"] });
    std::fs::write(dir.path().join("explicit.json"), system(explicit)).unwrap();
    let coarse = ["run", "explicit.json", "--step-size", "0.02", "--stop-time", "0.2"];
    let stderr = failed(&crane_cosim(&[&coarse[..], &["-o", "x.csv"]].concat(), dir.path()));
    assert!(
        stderr.contains(
            "record.interval: 0.01 s is not a positive whole multiple of step_size 0.02 s: give one that is \
             (--record-interval)"
        ),
        "{stderr}"
    );
    succeeded(&crane_cosim(
        &[&coarse[..], &["--record-interval", "0.1", "-q", "-o", "sparse.csv"]].concat(),
        dir.path(),
    ));
    assert_eq!(times(&dir.path().join("sparse.csv")), [0.0, 5.0 * 0.02, 10.0 * 0.02]);
}

#[test]
fn a_stop_time_off_the_step_grid_is_reached_by_a_shorter_last_step() {
    let dir = tempfile::tempdir().unwrap();
    let pendulum = common::pendulum_fmu().display().to_string();
    let args = ["run", &pendulum, "--step-size", "0.7", "--stop-time", "2", "--record", "theta_x", "-o", "p.csv"];
    let stdout = succeeded(&crane_cosim(&args, dir.path()));
    assert!(stdout.starts_with("completed 3 steps to t = 2 s (last step shortened to 0.6 s)"), "{stdout}");
    assert_eq!(times(&dir.path().join("p.csv")), [0.0, 0.7, 2.0 * 0.7, 2.0]);
    let summary = std::fs::read_to_string(dir.path().join("p.summary.json")).unwrap();
    let summary: serde_json::Value = serde_json::from_str(&summary).unwrap();
    assert_eq!(summary["shortened_last_step"], 2.0 - 2.0 * 0.7);

    // A step longer than the run is one step to the stop time, not none.
    let args = ["run", &pendulum, "--step-size", "100", "--stop-time", "10", "--record", "theta_x", "-o", "q.csv"];
    let stdout = succeeded(&crane_cosim(&args, dir.path()));
    assert!(stdout.starts_with("completed 1 step to t = 10 s (last step shortened to 10 s)"), "{stdout}");
    assert_eq!(times(&dir.path().join("q.csv")), [0.0, 10.0]);

    // A whole number of steps: no note, no key in the summary.
    let args = ["run", &pendulum, "--stop-time", "0.5", "--record", "theta_x", "-o", "r.csv"];
    assert!(!succeeded(&crane_cosim(&args, dir.path())).contains("shortened"));
    assert!(!std::fs::read_to_string(dir.path().join("r.summary.json")).unwrap().contains("shortened"));
}

/// `pendulum.fmu` as `dir/fixed.fmu`, declaring that it cannot change its communication step size.
fn fixed_step_pendulum(dir: &Path) -> String {
    use std::io::{Read, Write};
    let mut archive = zip::ZipArchive::new(std::fs::File::open(common::pendulum_fmu()).unwrap()).unwrap();
    let path = dir.join("fixed.fmu");
    let mut writer = zip::ZipWriter::new(std::fs::File::create(&path).unwrap());
    for index in 0..archive.len() {
        let mut entry = archive.by_index(index).unwrap();
        let mut content = Vec::new();
        entry.read_to_end(&mut content).unwrap();
        if entry.name() == "modelDescription.xml" {
            let xml = String::from_utf8(content).unwrap();
            let flag = "canHandleVariableCommunicationStepSize=";
            content = xml.replace(&format!("{flag}\"true\""), &format!("{flag}\"false\"")).into_bytes();
        }
        writer.start_file(entry.name(), zip::write::SimpleFileOptions::default()).unwrap();
        writer.write_all(&content).unwrap();
    }
    writer.finish().unwrap();
    path.display().to_string()
}

#[test]
fn an_fmu_that_cannot_change_its_step_refuses_a_stop_time_off_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let fixed = fixed_step_pendulum(dir.path());
    let stderr = failed(&crane_cosim(&["run", &fixed, "--step-size", "0.7", "--stop-time", "2"], dir.path()));
    assert!(
        stderr.contains(
            "stop_time: 2 s is not a whole number of steps of 0.7 s, and instance \"fixed\" cannot shorten the last \
             step to 0.6 s (its FMU does not declare canHandleVariableCommunicationStepSize): give a \
             stop time (--stop-time) or step size (--step-size) that fit"
        ),
        "{stderr}"
    );
    let stderr = failed(&crane_cosim(&["run", &fixed, "--step-size", "100", "--stop-time", "10"], dir.path()));
    assert!(stderr.contains("10 s is not a whole number of steps of 100 s"), "{stderr}");
    let args = ["run", &fixed, "--step-size", "0.5", "--stop-time", "2", "-q", "--record", "theta_x", "-o", "ok.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
}

/// The rows of a CSV file as text, without its header (the reference files quote their names
/// and leave out the instance).
fn rows(csv: &Path) -> Vec<String> {
    std::fs::read_to_string(csv).unwrap().lines().skip(1).map(String::from).collect()
}

#[test]
fn one_fmu_on_its_reference_input_reproduces_its_reference_result() {
    let dir = tempfile::tempdir().unwrap();
    let fmus = common::workspace_root().join("target/fmu");
    let pendulum = common::pendulum_fmu().display().to_string();
    let input = fmus.join("pendulum_in.csv").display().to_string();
    let reference = fmus.join("pendulum_ref.csv");
    let options = std::fs::read_to_string(fmus.join("pendulum_ref.opt")).unwrap();
    assert!(options.contains("StopTime, 10.0\nStepSize, 0.01\n"), "the README's command line: {options}");

    let exact = ["run", &pendulum, "--input", &input, "--no-input-derivatives", "--stop-time", "10"];
    let output = crane_cosim(&[&exact[..], &["--step-size", "0.01", "-q", "-o", "out.csv"]].concat(), dir.path());
    succeeded(&output);
    assert!(output.stderr.is_empty(), "{}", String::from_utf8_lossy(&output.stderr));
    // Both files are written with round-trip formatting: the same text is the same numbers.
    assert_eq!(rows(&dir.path().join("out.csv")), rows(&reference));

    // With input derivatives (the default for inputs files) the result differs from the first step.
    let args = ["run", &pendulum, "--input", &input, "--stop-time", "10", "-q", "-o", "slopes.csv"];
    succeeded(&crane_cosim(&args, dir.path()));
    let (slopes, expected) = (rows(&dir.path().join("slopes.csv")), rows(&reference));
    assert_eq!(slopes[0], expected[0]);
    assert_ne!(slopes[1], expected[1]);

    // The FMU's default experiment runs 60 s: past the table, which is said.
    let args = ["run", &pendulum, "--input", &input, "--record", "theta_x", "-q", "-o", "long.csv"];
    let stderr = String::from_utf8_lossy(&crane_cosim(&args, dir.path()).stderr).into_owned();
    let expected = format!("warning: input table {input} ends at 10 s, the run goes to 60 s: the last row is held");
    assert!(stderr.contains(&expected), "{stderr}");
}
