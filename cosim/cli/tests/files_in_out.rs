//! Commands take what crane-cosim writes and say what they expected: an FMU given where a system
//! is read, an OSP folder written by `export --osp` run back, a system without the closed loop's
//! instances given to `view`, and the demo's results viewed.
//!
//! Needs the packaged FMUs in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, failed, succeeded, workspace};

const EXPECTED: &str = "expected a system or scenario file (JSON), an SSP archive (.ssp) or an OSP system structure \
                        (a folder holding OspSystemStructure.xml, or that file), but this is";

#[test]
fn a_file_of_another_kind_is_named_with_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = common::pendulum_fmu();
    // An FMU under another name, a zip archive, binary data, a model description, an empty folder.
    std::fs::copy(&fmu, dir.path().join("pendulum.json")).unwrap();
    std::fs::write(dir.path().join("data.bin"), [0u8, 159, 146, 150, 0, 1]).unwrap();
    std::fs::write(dir.path().join("md.xml"), "<?xml version=\"1.0\"?>\n<fmiModelDescription fmiVersion=\"2.0\"/>\n")
        .unwrap();
    std::fs::create_dir(dir.path().join("empty")).unwrap();
    for (file, found) in [
        ("pendulum.json", "an FMU (a zip archive holding modelDescription.xml)"),
        ("data.bin", "binary data, not text"),
        ("md.xml", "an FMU's model description (modelDescription.xml), not an FMU"),
        ("empty", "a folder without OspSystemStructure.xml"),
    ] {
        for command in [&["run", file][..], &["export", file, "--ssp", "x.ssp"], &["view", file, "-o", "x.html"]] {
            let stderr = failed(&crane_cosim(command, dir.path()));
            assert!(stderr.contains(&format!("{file}: {EXPECTED} {found}")), "{command:?}: {stderr}");
            assert!(!stderr.contains("UTF-8") && !stderr.contains("JSON syntax"), "{stderr}");
        }
    }
    // `live` takes no lone FMU: it says so by kind.
    let stderr = failed(&crane_cosim(&["live", &fmu.display().to_string(), "--stop-time", "1"], dir.path()));
    assert!(stderr.contains(&format!("{EXPECTED} an FMU")), "{stderr}");
}

#[test]
fn export_takes_a_lone_fmu_as_run_does() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = common::pendulum_fmu().display().to_string();
    let stdout = succeeded(&crane_cosim(&["export", &fmu, "--ssp", "p.ssp", "--osp", "p_osp"], dir.path()));
    assert!(stdout.contains("wrote p.ssp") && stdout.contains("OspSystemStructure.xml"), "{stdout}");
    let alone = &["--stop-time", "2", "--step-size", "0.01", "-q"];
    succeeded(&crane_cosim(&[&["run", &fmu, "-o", "fmu.csv"][..], alone].concat(), dir.path()));
    succeeded(&crane_cosim(
        &[&["run", "p_osp", "-o", "osp.csv", "--algorithm", "gauss-seidel"][..], alone].concat(),
        dir.path(),
    ));
    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("fmu.csv"), read("osp.csv"), "one FMU alone runs the same from its OSP export");
}

#[test]
fn run_reads_back_the_osp_folder_export_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let system = workspace("systems/closed_loop.json");
    succeeded(&crane_cosim(&["export", &system, "--osp", "osp"], dir.path()));

    // Without a stop time (OSP has none) the run says which option gives it.
    let stderr = failed(&crane_cosim(&["run", "osp", "-q"], dir.path()));
    assert!(stderr.contains("an OSP system structure has no stop time: pass --stop-time"), "{stderr}");

    let stop = ["--stop-time", "2", "-q"];
    succeeded(&crane_cosim(&[&["run", "osp", "-o", "folder.csv"][..], &stop].concat(), dir.path()));
    let xml = "osp/OspSystemStructure.xml";
    succeeded(&crane_cosim(&[&["run", xml, "-o", "file.csv"][..], &stop].concat(), dir.path()));
    // The system file as OSP carries it: libcosim's fixed-step (Jacobi) algorithm without input
    // derivatives, every output recorded at every step.
    let scenario = serde_json::json!({ "system": system, "algorithm": "jacobi", "record": {} });
    std::fs::write(dir.path().join("jacobi.json"), scenario.to_string()).unwrap();
    let direct = ["run", "jacobi.json", "--no-input-derivatives", "-o", "direct.csv"];
    succeeded(&crane_cosim(&[&direct[..], &stop].concat(), dir.path()));

    let read = |name: &str| std::fs::read(dir.path().join(name)).unwrap();
    assert_eq!(read("folder.csv"), read("file.csv"), "the folder and its OspSystemStructure.xml are one system");
    assert!(read("folder.csv") == read("direct.csv"), "the OSP export runs as the system file it came from");
    assert_eq!(String::from_utf8(read("folder.csv")).unwrap().lines().count(), 202);

    // Exported again and viewed from the folder too.
    succeeded(&crane_cosim(&["export", "osp", "--ssp", "again.ssp", "--stop-time", "1"], dir.path()));
    let stdout = succeeded(&crane_cosim(&["view", "osp", "--stop-time", "1", "-o", "osp.html"], dir.path()));
    assert!(stdout.contains("wrote osp.html (101 frames"), "{stdout}");
}

#[test]
fn view_names_the_instances_it_needs_and_how_they_must_be_named() {
    let dir = tempfile::tempdir().unwrap();
    let fmu = common::pendulum_fmu().display().to_string();
    let stderr = failed(&crane_cosim(&["view", &fmu, "-o", "p.html"], dir.path()));
    for expected in [
        "lacks what the view draws: no instance platform, crane, controller (its instances: pendulum)",
        "the view reads platform.ship.x, platform.ship.y",
        "crane.joint.theta2z",
        "controller.sp.load.z",
        "there is no option to map other names: name the instances platform, crane (knuckle_boom for the \
         full-scale crane), pendulum and controller",
    ] {
        assert!(stderr.contains(expected), "{expected:?} in {stderr}");
    }
    let help = succeeded(&crane_cosim(&["view", "--help"], dir.path()));
    assert!(help.contains("There is no option to map other names"), "{help}");
}

#[test]
fn the_demo_records_what_view_draws() {
    let dir = tempfile::tempdir().unwrap();
    // The columns `cargo xtask demo` adds to the scenarios' (xtask/src/main.rs, DEMO_VIEW_RECORD).
    let view_record = ["--record", "platform.ship.*", "--record", "crane.joint.*", "--record", "controller.est.load.*"];
    for name in ["demo_still_off", "demo_still_compensated", "demo_profile1_off", "demo_profile1_compensated"] {
        let scenario = workspace(&format!("scenarios/{name}.json"));
        let csv = format!("{name}.csv");
        let run = ["run", &scenario, "--stop-time", "0.5", "-o", &csv, "-q"];
        succeeded(&crane_cosim(&[&run[..], &view_record[..]].concat(), dir.path()));
        let stdout = succeeded(&crane_cosim(&["view", &csv], dir.path()));
        assert!(stdout.contains(&format!("wrote {name}.html (51 frames")), "{stdout}");
    }
}
