//! Validation tests with a fake FMU whose binary is not even a library:
//! every check must happen before anything is loaded or instantiated.

use std::io::Write;
use std::path::{Path, PathBuf};

use super::*;

const MODEL: &str = r#"<fmiModelDescription fmiVersion="2.0" modelName="pendulum" guid="{g}">
<CoSimulation modelIdentifier="pendulum" canInterpolateInputs="true"/>
<ModelVariables>
  <ScalarVariable name="theta_x0" valueReference="0" causality="parameter" variability="fixed" initial="exact"><Real start="0"/></ScalarVariable>
  <ScalarVariable name="mass" valueReference="4" causality="parameter" variability="fixed" initial="exact"><Real start="0.3"/></ScalarVariable>
  <ScalarVariable name="seed" valueReference="9" causality="parameter" variability="fixed" initial="exact"><Integer start="1"/></ScalarVariable>
  <ScalarVariable name="held" valueReference="10" causality="parameter" variability="fixed" initial="exact"><Boolean start="false"/></ScalarVariable>
  <ScalarVariable name="tip.x" valueReference="100" causality="input"><Real start="0"/></ScalarVariable>
  <ScalarVariable name="lp" valueReference="109" causality="input"><Real start="1"/></ScalarVariable>
  <ScalarVariable name="theta_x" valueReference="200" causality="output" initial="calculated"><Real/></ScalarVariable>
  <ScalarVariable name="load.x" valueReference="204" causality="output" initial="calculated"><Real/></ScalarVariable>
  <ScalarVariable name="g" valueReference="7" causality="parameter" variability="constant"><Real start="9.81"/></ScalarVariable>
  <ScalarVariable name="theta_guess" valueReference="210" causality="output" initial="approx"><Real start="0"/></ScalarVariable>
  <ScalarVariable name="damping" valueReference="211" causality="local" initial="exact"><Real start="0.1"/></ScalarVariable>
  <ScalarVariable name="energy" valueReference="212" causality="local"><Real/></ScalarVariable>
  <ScalarVariable name="rope" valueReference="8" causality="local" variability="constant"><Real start="0.7"/></ScalarVariable>
</ModelVariables></fmiModelDescription>"#;

fn write_fmu(dir: &Path) -> PathBuf {
    let path = dir.join("pendulum.fmu");
    let mut writer = zip::ZipWriter::new(std::fs::File::create(&path).expect("create"));
    let options = zip::write::SimpleFileOptions::default();
    writer.start_file("modelDescription.xml", options).expect("start");
    writer.write_all(MODEL.as_bytes()).expect("write");
    writer.start_file("binaries/linux64/pendulum.so", options).expect("start");
    writer.write_all(b"not a shared library").expect("write");
    writer.finish().expect("finish");
    path
}

struct Fixture {
    dir: tempfile::TempDir,
}

impl Fixture {
    fn new() -> Self {
        let dir = tempfile::tempdir().expect("tempdir");
        write_fmu(dir.path());
        std::fs::write(dir.path().join("in.csv"), "time,tip.x,lp\n0,0,0.7\n1,0.1,0.7\n").expect("csv");
        Self { dir }
    }

    fn load(&self, json: &str) -> Result<System, SystemError> {
        let file = self.dir.path().join("system.json");
        std::fs::write(&file, json).expect("write system");
        System::load(&file, &Overrides::default(), &SystemFiles::default())
    }

    fn problems(&self, json: &str) -> Vec<String> {
        match self.load(json) {
            Ok(_) => panic!("expected problems in {json}"),
            Err(error) => {
                let listed: Vec<String> = error.problems().iter().map(ToString::to_string).collect();
                assert!(!listed.is_empty(), "{error}");
                let message = error.to_string();
                assert!(message.contains("system.json"), "{message}");
                listed
            }
        }
    }
}

fn system(instances: &str, rest: &str) -> String {
    format!(
        r#"{{ "fmus": {{ "pendulum": "pendulum.fmu" }}, "instances": [{instances}],
             "stop_time": 1.0, "step_size": 0.1 {rest} }}"#
    )
}

/// Asserts that the problems, joined by lines, contain every one of `expected`.
fn assert_mentions(problems: &[String], expected: &[&str]) {
    let all = problems.join("\n");
    for text in expected {
        assert!(all.contains(text), "{text:?} missing in:\n{all}");
    }
}

/// Asserts that there are as many problems as `expected` and that they mention each of them.
fn assert_problems(problems: &[String], expected: &[&str]) {
    assert_mentions(problems, expected);
    assert_eq!(problems.len(), expected.len(), "{problems:?}");
}

const LOAD: &str =
    r#"{ "name": "load", "fmu": "pendulum", "start": { "theta_x0": -0.349, "lp": 0.7, "seed": 3, "held": true } }"#;

#[test]
fn a_valid_system_resolves_everything() {
    let fixture = Fixture::new();
    let json = system(
        LOAD,
        r#", "inputs": [ { "instance": "load", "file": "in.csv" } ],
             "record": { "interval": 0.2, "variables": ["load.theta_x", "load.load.x", "load.lp"] }"#,
    );
    let system = fixture.load(&json).expect("valid");
    assert_eq!(system.grid.steps(), 10);
    assert_eq!(system.record.every, 2);
    let names: Vec<&str> = system.record.variables.iter().map(|v| v.variable.name.as_str()).collect();
    assert_eq!(names, ["theta_x", "load.x", "lp"], "instance separator is the first dot");
    assert_eq!(system.instances[0].start.len(), 4);
    assert!(system.instances[0].start.iter().any(|(v, value)| v.name == "seed" && *value == Value::Integer(3)));
    assert!(system.instances[0].start.iter().any(|(v, value)| v.name == "held" && *value == Value::Boolean(true)));
    assert_eq!(system.inputs.len(), 1);
    assert_eq!(system.inputs[0].binding.table().names, ["tip.x", "lp"]);
}

#[test]
fn default_recording_is_all_outputs() {
    let fixture = Fixture::new();
    let system = fixture.load(&system(LOAD, "")).expect("valid");
    let names: Vec<&str> = system.record.variables.iter().map(|v| v.qualified_name.as_str()).collect();
    assert_eq!(names, ["load.theta_x", "load.load.x", "load.theta_guess"]);
    assert_eq!(system.record.every, 1);
}

#[test]
fn unknown_instance_is_named_with_candidates() {
    let fixture = Fixture::new();
    let problems = fixture.problems(&system(
        LOAD,
        r#", "record": { "variables": ["lod.theta_x"] }, "inputs": [ { "instance": "loadd", "file": "in.csv" } ]"#,
    ));
    assert_eq!(problems.len(), 2, "{problems:?}");
    assert!(problems[0].starts_with("inputs[0].instance: unknown instance \"loadd\""), "{problems:?}");
    assert!(problems[0].contains("(did you mean \"load\"?); instances: \"load\""));
    assert!(problems[1].starts_with("record.variables[0]: unknown instance \"lod\" in \"lod.theta_x\""));
    assert!(problems[1].contains("did you mean \"load\"?"), "{problems:?}");
}

#[test]
fn unknown_variable_with_typo_suggests_and_lists() {
    let fixture = Fixture::new();
    let problems = fixture.problems(&system(
        r#"{ "name": "load", "fmu": "pendulum", "start": { "theta_x9": 0.1 } }"#,
        r#", "record": { "variables": ["load.thetax"] }"#,
    ));
    assert_eq!(problems.len(), 2, "{problems:?}");
    let start = &problems[0];
    assert!(start.starts_with("instances[0].start[\"theta_x9\"]:"), "{start}");
    assert!(start.contains("has no variable \"theta_x9\" (did you mean \"theta_x0\"?)"), "{start}");
    assert!(
        start.contains(
            "settable variables: \"theta_x0\", \"mass\", \"seed\", \"held\", \"tip.x\", \"lp\", \"theta_guess\", \"damping\""
        ),
        "{start}"
    );
    let record = &problems[1];
    assert!(record.starts_with("record.variables[0]:") && record.contains("did you mean \"theta_x\"?"), "{record}");
    assert!(record.contains("\"load.x\""), "lists what exists: {record}");
}

#[test]
fn wrong_types_and_causalities_are_refused() {
    let fixture = Fixture::new();
    let problems = fixture.problems(&system(
        r#"{ "name": "load", "fmu": "pendulum",
            "start": { "mass": "heavy", "seed": 1.5, "held": 1, "theta_x": 0.0, "g": 9.8 } }"#,
        "",
    ));
    assert_problems(
        &problems,
        &[
            "[\"mass\"]: variable \"mass\" is Real: expected a number, got \"heavy\"",
            "[\"seed\"]: variable \"seed\" is Integer: expected an integer, got 1.5",
            "[\"held\"]: variable \"held\" is Boolean: expected true or false, got 1",
            "[\"theta_x\"]: variable \"theta_x\" of instance \"load\" is a continuous output",
            "[\"g\"]: variable \"g\" of instance \"load\" is a constant parameter",
        ],
    );
}

#[test]
fn start_values_of_outputs_and_locals_follow_their_initial() {
    let fixture = Fixture::new();
    let loaded = fixture
        .load(&system(r#"{ "name": "load", "fmu": "pendulum", "start": { "theta_guess": 0.2, "damping": 0.3 } }"#, ""))
        .expect("initial approx and exact accept start values");
    let start: Vec<(&str, &Value)> =
        loaded.instances[0].start.iter().map(|(v, value)| (v.name.as_str(), value)).collect();
    assert_eq!(start, [("damping", &Value::Real(0.3)), ("theta_guess", &Value::Real(0.2))], "in name order");

    let problems = fixture.problems(&system(
        r#"{ "name": "load", "fmu": "pendulum", "start": { "load.x": 0.0, "energy": 1.0, "rope": 0.5 } }"#,
        "",
    ));
    assert_problems(
        &problems,
        &[
            "variable \"load.x\" of instance \"load\" is a continuous output with initial=\"calculated\"",
            // No initial attribute: a continuous local defaults to calculated.
            "variable \"energy\" of instance \"load\" is a continuous local with initial=\"calculated\"",
            "variable \"rope\" of instance \"load\" is a constant local;",
        ],
    );
}

#[test]
fn connections_are_checked() {
    let fixture = Fixture::new();
    let two = format!("{LOAD}, {}", r#"{ "name": "other", "fmu": "pendulum" }"#);
    let problems = fixture.problems(&system(
        &two,
        r#", "connections": [
              { "from": "load.theta_x", "to": "other.tip.x" },
              { "from": "load.load.x", "to": "other.tip.x" },
              { "from": "load.lp", "to": "other.lp" },
              { "from": "load.theta_x", "to": "other.load.x" },
              { "from": "loadtheta_x", "to": "other.lp" } ]"#,
    ));
    assert_mentions(
        &problems,
        &[
            "connections[1].to: input \"other.tip.x\" is already fed by connections[0].to",
            "connections[2].from: variable \"lp\" of instance \"load\" is an input, not an output",
            "connections[3].to: variable \"load.x\" of instance \"other\" is an output, not an input",
            "connections[4].from: \"loadtheta_x\" is not of the form",
        ],
    );
}

#[test]
fn input_files_are_checked() {
    let fixture = Fixture::new();
    std::fs::write(fixture.dir.path().join("bad.csv"), "time,tip.xx,theta_x\n0,1,2\n").expect("csv");
    let problems = fixture.problems(&system(
        LOAD,
        r#", "inputs": [ { "instance": "load", "file": "bad.csv" }, { "instance": "load", "file": "missing.csv" } ]"#,
    ));
    assert_mentions(
        &problems,
        &[
            "column \"tip.xx\")",
            "did you mean \"tip.x\"?",
            "inputs of \"load\": \"tip.x\", \"lp\"",
            "\"theta_x\" of instance \"load\" is an output, not an input",
            "inputs[1].file: ",
            "missing.csv",
        ],
    );
}

#[test]
fn fmu_aliases_files_and_times_are_checked() {
    let fixture = Fixture::new();
    let json = r#"{ "fmus": { "pendulum": "pendulum.fmu", "crane": "nowhere/crane.fmu" },
        "instances": [ { "name": "a.b", "fmu": "pendulm" }, { "name": "c", "fmu": "pendulum" }, { "name": "c", "fmu": "pendulum" } ],
        "stop_time": 1.0, "step_size": -0.1, "record": { "interval": 0.25 } }"#;
    let problems = fixture.problems(json);
    assert_mentions(
        &problems,
        &[
            "step_size: step_size must be positive",
            "record.interval: 0.25 s is not a positive whole multiple",
            "fmus[\"crane\"]: ",
            "nowhere/crane.fmu",
            "instances[0].name: instance name \"a.b\"",
            "instances[0].fmu: unknown FMU \"pendulm\" for instance \"a.b\" (did you mean \"pendulum\"?)",
            "instances[2].name: instance name \"c\" is used twice",
        ],
    );
}

#[test]
fn json_errors_have_positions_and_unknown_keys_are_refused() {
    let fixture = Fixture::new();
    let error = fixture.load("{ \"fmus\": {},\n  \"stop_tme\": 1 }").expect_err("unknown key");
    let message = error.to_string();
    assert!(message.contains("system.json:2:") && message.contains("unknown field `stop_tme`"), "{message}");
    let error = fixture.load("{ \"fmus\": ").expect_err("truncated");
    assert!(matches!(&error, SystemError::Parse { error, .. } if error.line == 1), "{error}");
    assert!(error.to_string().contains("JSON syntax error at line 1 column 10 (read as a system file)"), "{error}");
}

#[test]
fn overrides_replace_times() {
    let fixture = Fixture::new();
    let file = fixture.dir.path().join("system.json");
    std::fs::write(&file, system(LOAD, "")).expect("write");
    let overrides = Overrides {
        stop_time: Some(2.0),
        step_size: Some(0.05),
        algorithm: Some(AlgorithmKind::Jacobi),
        ..Overrides::default()
    };
    let system = System::load(&file, &overrides, &SystemFiles::default()).expect("valid");
    assert_eq!(system.grid.steps(), 40);
    assert_eq!(system.spec.stop_time, 2.0);
    assert_eq!(system.spec.algorithm, AlgorithmKind::Jacobi);
}

#[test]
fn a_start_override_on_a_connected_input_is_refused_and_never_suggested() {
    let fixture = Fixture::new();
    let file = fixture.dir.path().join("system.json");
    // The system file's own start value on the connected input stays allowed.
    let instances = r#"{ "name": "a", "fmu": "pendulum" }, { "name": "b", "fmu": "pendulum", "start": { "lp": 0.5 } }"#;
    std::fs::write(&file, system(instances, r#", "connections": [ { "from": "a.load.x", "to": "b.lp" } ]"#))
        .expect("write");
    System::load(&file, &Overrides::default(), &SystemFiles::default()).expect("a system file may set it");
    let start = |name: &str| Overrides { start: vec![(name.into(), serde_json::json!(20.0))], ..Overrides::default() };
    let error = System::load(&file, &start("b.lp"), &SystemFiles::default()).expect_err("connected input");
    let problems: Vec<String> = error.problems().iter().map(ToString::to_string).collect();
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert!(
        problems[0].starts_with("Overrides::start[\"b.lp\"]: b.lp is fed by the connection a.load.x -> b.lp"),
        "{problems:?}"
    );
    // The same input of the unconnected instance takes a start value; a misspelt name of the
    // connected one is not offered the connected input.
    System::load(&file, &start("a.lp"), &SystemFiles::default()).expect("unconnected input");
    let error = System::load(&file, &start("b.lpp"), &SystemFiles::default()).expect_err("misspelt");
    let listed = error.problems()[0].to_string();
    assert!(listed.contains("settable variables:") && !listed.contains("\"lp\""), "{listed}");
    assert!(!listed.contains("did you mean \"lp\""), "{listed}");
}
