//! `crane-cosim export` and `crane-cosim run x.ssp`: the closed loop as an SSP archive runs bit
//! for bit like its scenario file; what cannot be exported or read is refused with a message.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use common::crane_cosim;

use std::path::Path;

fn succeeds(args: &[&str]) -> String {
    let out = crane_cosim(args, Path::new("."));
    assert!(out.status.success(), "crane-cosim {args:?} failed:\n{}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn fails(args: &[&str]) -> String {
    let out = crane_cosim(args, Path::new("."));
    assert!(!out.status.success(), "crane-cosim {args:?} succeeded");
    String::from_utf8_lossy(&out.stderr).into_owned()
}

fn path(p: &Path) -> &str {
    p.to_str().expect("UTF-8 path")
}

#[test]
fn the_compensated_closed_loop_runs_bit_for_bit_from_its_ssp_archive() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = common::workspace_root().join("scenarios/demo_still_compensated.json");
    let (archive, osp) = (dir.path().join("still.ssp"), dir.path().join("osp"));
    // Two seconds past the release and the start of compensation at 10 s; the stop time is
    // exported with the scenario's other settings.
    succeeds(&["export", path(&scenario), "--stop-time", "12", "--ssp", path(&archive), "--osp", path(&osp)]);
    let (from_json, from_ssp) = (dir.path().join("json.csv"), dir.path().join("ssp.csv"));
    succeeds(&["run", path(&scenario), "--stop-time", "12", "-o", path(&from_json), "-q"]);
    succeeds(&["run", path(&archive), "-o", path(&from_ssp), "-q"]);
    let (json, ssp) = (std::fs::read(&from_json).unwrap(), std::fs::read(&from_ssp).unwrap());
    assert_eq!(String::from_utf8_lossy(&json).lines().count(), 1202, "header and t = 0, 0.01, ..., 12 s");
    assert!(json == ssp, "the SSP run differs from the scenario's");

    let mut files: Vec<String> =
        std::fs::read_dir(&osp).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    files.sort();
    let expected = ["OspSystemStructure.xml", "controller.fmu", "crane.fmu", "imu.fmu", "pendulum.fmu", "platform.fmu"];
    assert_eq!(files, expected);
    let xml = std::fs::read_to_string(osp.join("OspSystemStructure.xml")).unwrap();
    assert_eq!(xml.matches("<VariableConnection>").count(), 88, "every connection of the closed loop");
    assert!(xml.contains(r#"<InitialValue variable="theta_x0"><Real value="-0.40142572795869574"/></InitialValue>"#));
}

#[test]
fn an_archive_exports_again_and_command_line_overrides_apply_to_it() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = common::workspace_root().join("scenarios/demo_still_off.json");
    let (first, second) = (dir.path().join("a.ssp"), dir.path().join("b.ssp"));
    succeeds(&["export", path(&scenario), "--ssp", path(&first)]);
    succeeds(&["export", path(&first), "--algorithm", "jacobi", "--step-size", "0.005", "--ssp", path(&second)]);
    let summary = dir.path().join("b.json");
    let csv = dir.path().join("b.csv");
    succeeds(&["run", path(&second), "--stop-time", "0.1", "-o", path(&csv), "--summary", path(&summary), "-q"]);
    let summary: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(summary).unwrap()).unwrap();
    assert_eq!((summary["algorithm"].as_str(), summary["step_size"].as_f64()), (Some("jacobi"), Some(0.005)));
    assert_eq!(summary["steps_completed"], 20);
}

#[test]
fn a_system_with_input_files_is_refused_naming_the_input_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tip.csv"), "time,tip.x\n0,0\n1,0.1\n").unwrap();
    let system = dir.path().join("driven.json");
    let fmu = common::pendulum_fmu();
    std::fs::write(
        &system,
        serde_json::json!({
            "fmus": {"pendulum": fmu},
            "instances": [{"name": "load", "fmu": "pendulum"}],
            "inputs": [{"instance": "load", "file": "tip.csv"}],
            "stop_time": 1.0, "step_size": 0.01
        })
        .to_string(),
    )
    .unwrap();
    let archive = dir.path().join("driven.ssp");
    let stderr = fails(&["export", path(&system), "--ssp", path(&archive)]);
    assert!(stderr.contains("inputs[0] feeds instance 'load' from tip.csv"), "{stderr}");
    assert!(!archive.exists());
    assert!(fails(&["export", path(&system)]).contains("--ssp"), "one format at least is required");
}

#[test]
fn a_broken_archive_is_an_error_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let archive = dir.path().join("broken.ssp");
    std::fs::write(&archive, "not a zip").unwrap();
    let stderr = fails(&["run", path(&archive), "-o", path(&dir.path().join("x.csv"))]);
    assert!(stderr.contains(&format!("{}: cannot extract the SSP archive", archive.display())), "{stderr}");
}
