//! The safe `Slave` API against the packaged pendulum: name lookup, error
//! messages, typed values, status queries and the drop sequence.
//!
//! Needs `target/fmu/pendulum.fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use fmu_import::fmi::Status;
use fmu_import::fmu::{ExtractLimits, Fmu};
use fmu_import::slave::{InstantiateOptions, Phase, Slave, SlaveError};
use fmu_import::value::Value;

fn pendulum() -> Fmu {
    Fmu::open(&common::pendulum_fmu(), &ExtractLimits::default()).expect("the pendulum FMU opens")
}

fn quiet() -> InstantiateOptions {
    InstantiateOptions { echo: fmu_import::fmi::LogEcho::Off, ..InstantiateOptions::default() }
}

#[test]
fn variable_lookup_suggests_and_lists() {
    let fmu = pendulum();
    let slave = Slave::instantiate(&fmu, "load", quiet()).expect("instantiate");
    assert_eq!(
        slave.variable("load.x").map(|v| v.value_reference).ok(),
        fmu.model_description().variable("load.x").map(|v| v.value_reference)
    );
    let message = slave.variable("thetax").expect_err("typo").to_string();
    assert!(message.contains("instance \"load\" (model \"pendulum\") has no variable \"thetax\""), "{message}");
    assert!(message.contains("(did you mean \"theta_x\"?)") && message.contains("\"tension\""), "{message}");
}

#[test]
fn call_errors_name_instance_call_time_status_and_log() {
    let fmu = pendulum();
    let mut slave = Slave::instantiate(&fmu, "crane_load", quiet()).expect("instantiate");
    slave.setup_experiment(None, 0.0, Some(10.0)).expect("setup");
    slave.enter_initialization_mode().expect("enter");
    slave.exit_initialization_mode().expect("exit");
    slave.do_step(0.0, 0.01).expect("step");
    assert_eq!(slave.time(), 0.01);
    let error = slave.do_step(0.5, 0.01).expect_err("wrong communication point");
    let failure = error.call_failure().expect("a failed call");
    assert_eq!(failure.call, "fmi2DoStep");
    assert_eq!(failure.status, Status::Error);
    assert_eq!(failure.time, Some(0.5));
    assert!(failure.last_log().is_some(), "the FMU's message is kept");
    assert!(!error.is_discard());
    let message = error.to_string();
    assert!(message.starts_with("instance \"crane_load\": fmi2DoStep (currentCommunicationPoint = 0.5"), "{message}");
    assert!(message.contains("returned fmi2Error at t = 0.5 s; the FMU logged: "), "{message}");
    assert_eq!(slave.phase(), Phase::Failed);
    slave.reset().expect("reset after the error");
    assert_eq!(slave.phase(), Phase::Instantiated);
}

#[test]
fn typed_values_and_mismatches() {
    let fmu = pendulum();
    let mut slave = Slave::instantiate(&fmu, "typed", quiet()).expect("instantiate");
    slave.setup_experiment(None, 0.0, None).expect("setup");
    let mass = slave.variable("mass").expect("mass").clone();
    slave.set_value(&mass, &Value::Real(0.5)).expect("set mass");
    slave.enter_initialization_mode().expect("enter");
    assert_eq!(slave.get_value(&mass).expect("get mass"), Value::Real(0.5));
    let error = slave.set_value(&mass, &Value::Boolean(true)).expect_err("wrong type");
    assert!(matches!(error, SlaveError::TypeMismatch { .. }), "{error}");
    assert!(error.to_string().contains("\"mass\" is Real, not Boolean"), "{error}");
    let error = slave.set_real(&[mass.value_reference], &[1.0, 2.0]).expect_err("length mismatch");
    assert!(error.to_string().contains("1 value references but 2 values"), "{error}");
}

#[test]
fn instance_names_with_nul_are_refused() {
    let fmu = pendulum();
    let slave = Slave::instantiate(&fmu, "bad\0name", quiet());
    assert!(matches!(slave, Err(SlaveError::InvalidArgument { .. })));
}

/// Repacks the pendulum with another GUID in its model description.
fn pendulum_with_stale_guid(dir: &std::path::Path) -> std::path::PathBuf {
    use std::io::{Read, Write};
    let source = std::fs::File::open(common::pendulum_fmu()).expect("open");
    let mut archive = zip::ZipArchive::new(source).expect("zip");
    let path = dir.join("stale.fmu");
    let mut writer = zip::ZipWriter::new(std::fs::File::create(&path).expect("create"));
    for index in 0..archive.len() {
        let mut entry = archive.by_index(index).expect("entry");
        let name = entry.name().to_string();
        let mut bytes = Vec::new();
        entry.read_to_end(&mut bytes).expect("read");
        if name == "modelDescription.xml" {
            let xml = String::from_utf8(bytes).expect("utf-8");
            let start = xml.find("guid=\"").expect("guid") + 6;
            let end = start + xml[start..].find('"').expect("end of guid");
            bytes = format!("{}{{stale-guid}}{}", &xml[..start], &xml[end..]).into_bytes();
        }
        if entry.is_dir() {
            continue;
        }
        writer.start_file(name, zip::write::SimpleFileOptions::default()).expect("start");
        writer.write_all(&bytes).expect("write");
    }
    writer.finish().expect("finish");
    path
}

#[test]
fn instantiation_failure_quotes_the_fmu() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fmu = Fmu::open(&pendulum_with_stale_guid(dir.path()), &ExtractLimits::default()).expect("opens");
    let error = Slave::instantiate(&fmu, "stale", quiet()).expect_err("GUID mismatch");
    let message = error.to_string();
    assert!(matches!(error, SlaveError::InstantiateFailed { .. }), "{message}");
    assert!(message.starts_with("instance \"stale\": fmi2Instantiate of "), "{message}");
    assert!(message.contains("stale.fmu returned NULL; the FMU logged: "), "{message}");
}

#[test]
fn dropping_running_and_failed_instances_is_clean() {
    let fmu = pendulum();
    for fail in [false, true] {
        let mut slave = Slave::instantiate(&fmu, "dropped", quiet()).expect("instantiate");
        slave.setup_experiment(None, 0.0, None).expect("setup");
        slave.enter_initialization_mode().expect("enter");
        slave.exit_initialization_mode().expect("exit");
        slave.do_step(0.0, 0.01).expect("step");
        if fail {
            assert!(slave.do_step(0.0, -1.0).is_err());
        }
        drop(slave);
    }
    // The FMU outlives nothing it must not: a new instance still works.
    let mut slave = Slave::instantiate(&fmu, "after", quiet()).expect("instantiate again");
    slave.setup_experiment(None, 0.0, None).expect("setup");
}

#[test]
fn status_queries_ask_for_terminated_and_the_last_successful_time() {
    let fmu = pendulum();
    let mut slave = Slave::instantiate(&fmu, "status", quiet()).expect("instantiate");
    slave.setup_experiment(None, 0.0, None).expect("setup");
    slave.enter_initialization_mode().expect("enter");
    slave.exit_initialization_mode().expect("exit");
    slave.do_step(0.0, 0.01).expect("step");
    slave.do_step(0.01, 0.01).expect("step");
    // The pendulum answers fmi2Terminated (never true) and fmi2LastSuccessfulTime, and refuses
    // any other status kind with fmi2Error.
    assert!(!slave.terminated().expect("fmi2Terminated"));
    assert_eq!(slave.last_successful_time().expect("fmi2LastSuccessfulTime"), 0.02);
    assert_eq!(slave.phase(), Phase::StepMode, "status queries do not change the state");
    slave.do_step(0.02, 0.01).expect("stepping goes on");
}
