//! The binary against hostile files and ends: special files, zip bombs, closed pipes and FMU
//! libraries that end the process.
//!
//! Needs `target/fmu/pendulum.fmu` (`cargo xtask package`) and, for the FMU that calls `exit`,
//! a C compiler (`cc`).

#[path = "../../test_support.rs"]
mod common;

use common::{crane_cosim, text};

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Writes a ZIP of `entries` (name, content, deflated?) as `dir/name`.
fn write_zip(dir: &Path, name: &str, entries: &[(&str, &[u8], bool)]) -> PathBuf {
    let path = dir.join(name);
    let mut writer = zip::ZipWriter::new(std::fs::File::create(&path).expect("create"));
    for (entry, content, deflated) in entries {
        let method = if *deflated { zip::CompressionMethod::Deflated } else { zip::CompressionMethod::Stored };
        let options = zip::write::SimpleFileOptions::default().compression_method(method);
        writer.start_file(*entry, options).expect("entry");
        writer.write_all(content).expect("write");
    }
    writer.finish().expect("finish");
    path
}

#[test]
fn a_fifo_named_as_fmu_is_refused_without_blocking() {
    let dir = tempfile::tempdir().expect("tempdir");
    let fifo = dir.path().join("model.fmu");
    assert!(Command::new("mkfifo").arg(&fifo).status().expect("mkfifo").success());
    let started = Instant::now();
    let output = crane_cosim(&["info", "model.fmu"], dir.path());
    assert!(started.elapsed() < Duration::from_secs(20), "must not wait for a writer");
    assert!(!output.status.success());
    assert!(
        text(&output.stderr).contains("model.fmu") && text(&output.stderr).contains("not a regular file but a FIFO")
    );
}

#[test]
fn a_scenario_whose_system_is_a_device_is_refused() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("s.json"), r#"{ "system": "/dev/zero" }"#).expect("write");
    let output = crane_cosim(&["run", "s.json", "-q", "-o", "out.csv"], dir.path());
    assert!(!output.status.success());
    let message = text(&output.stderr);
    assert!(message.contains("/dev/zero") && message.contains("not a regular file but a device"), "{message}");
}

#[test]
fn a_zip_bomb_is_refused_and_the_message_names_the_option_that_allows_it() {
    let dir = tempfile::tempdir().expect("tempdir");
    let zeros = vec![0u8; 16 << 20];
    write_zip(dir.path(), "bomb.fmu", &[("modelDescription.xml", b"<x/>", false), ("resources/z.bin", &zeros, true)]);
    let output = crane_cosim(&["info", "bomb.fmu"], dir.path());
    assert!(!output.status.success());
    let message = text(&output.stderr);
    assert!(
        message.contains("bomb.fmu: refusing to extract") && message.contains("--max-compression-ratio"),
        "{message}"
    );

    let output = crane_cosim(&["info", "bomb.fmu", "--max-compression-ratio", "5000"], dir.path());
    let message = text(&output.stderr);
    assert!(!message.contains("refusing"), "raised ratio: extracted, then the bad XML is what fails: {message}");
    assert!(message.contains("modelDescription.xml"), "{message}");

    let output =
        crane_cosim(&["info", "bomb.fmu", "--max-compression-ratio", "5000", "--max-unpacked-size", "8M"], dir.path());
    let message = text(&output.stderr);
    assert!(
        message.contains("unpack to 16.0 MiB, more than the limit of 8.0 MiB (raise it with --max-unpacked-size)"),
        "{message}"
    );
}

#[cfg(unix)]
#[test]
fn a_closed_pipe_ends_info_quietly_like_other_tools() {
    use std::os::fd::{FromRawFd, OwnedFd};
    use std::os::unix::process::ExitStatusExt;
    let fmu = common::pendulum_fmu();
    // The reader is gone before the child starts: its first write must fail. (Closing the read
    // end after spawning races with a child that fits its whole output into the pipe's buffer.)
    let mut fds = [0; 2];
    // SAFETY: `pipe` fills two new descriptors, each owned exactly once below.
    let (read, write) = unsafe {
        assert_eq!(libc::pipe(fds.as_mut_ptr()), 0);
        (OwnedFd::from_raw_fd(fds[0]), OwnedFd::from_raw_fd(fds[1]))
    };
    drop(read);
    let output = common::crane_cosim_command()
        .arg("info")
        .arg(&fmu)
        .stdout(Stdio::from(write))
        .stderr(Stdio::piped())
        .output()
        .expect("run");
    assert_eq!(output.status.signal(), Some(libc::SIGPIPE), "{:?}", output.status);
    assert_eq!(text(&output.stderr), "", "nothing to say about a closed pipe");
}

#[cfg(target_os = "linux")]
#[test]
fn an_fmu_library_that_calls_exit_is_not_a_success() {
    let dir = tempfile::tempdir().expect("tempdir");
    let source = dir.path().join("quitter.c");
    std::fs::write(&source, "#include <stdlib.h>\n__attribute__((constructor)) static void quit(void) { exit(0); }\n")
        .expect("write C");
    let library = dir.path().join("quitter.so");
    let compiled = Command::new("cc").args(["-shared", "-fPIC", "-o"]).arg(&library).arg(&source).status();
    assert!(compiled.expect("a C compiler (cc)").success());
    let xml = br#"<fmiModelDescription fmiVersion="2.0" modelName="quitter" guid="q">
<CoSimulation modelIdentifier="quitter"/><ModelVariables/><ModelStructure/></fmiModelDescription>"#;
    let binary = std::fs::read(&library).expect("library");
    write_zip(
        dir.path(),
        "quitter.fmu",
        &[("modelDescription.xml", xml, false), ("binaries/linux64/quitter.so", &binary, false)],
    );
    let system = r#"{ "fmus": { "q": "quitter.fmu" }, "instances": [ { "name": "q", "fmu": "q" } ],
        "stop_time": 1.0, "step_size": 0.1 }"#;
    std::fs::write(dir.path().join("system.json"), system).expect("system");
    let output = crane_cosim(&["run", "system.json", "-q", "-o", "out.csv"], dir.path());
    assert_eq!(output.status.code(), Some(1), "exit(0) inside an FMU must not pass for success");
    assert!(
        text(&output.stderr).contains("an FMU library ended the process by calling exit()"),
        "{}",
        text(&output.stderr)
    );
}

/// A free pendulum from 0 to `stop` s at 10 ms, recording three variables.
fn write_pendulum_system(dir: &Path, start: f64, stop: f64) {
    let system = format!(
        r#"{{ "fmus": {{ "pendulum": {fmu:?} }},
        "instances": [ {{ "name": "load", "fmu": "pendulum", "start": {{ "theta_x0": -0.4, "lp": 0.7 }} }} ],
        "start_time": {start:?}, "stop_time": {stop:?}, "step_size": 0.01,
        "record": {{ "variables": ["load.theta_x", "load.theta_y", "load.tension"] }} }}"#,
        fmu = common::pendulum_fmu()
    );
    std::fs::write(dir.join("system.json"), system).expect("system");
}

#[cfg(unix)]
#[test]
fn signals_end_a_run_on_a_complete_row_with_a_summary_and_no_temporary_folder() {
    for (signal, name) in [(libc::SIGTERM, "SIGTERM"), (libc::SIGINT, "SIGINT"), (libc::SIGHUP, "SIGHUP")] {
        interrupt_a_run(signal, name);
    }
}

/// The results file a run in `dir` is writing: `<name>.<random>.partial`, renamed to `<name>`
/// when the run ends.
#[cfg(unix)]
fn partial_file(dir: &Path) -> Option<std::path::PathBuf> {
    let entries = std::fs::read_dir(dir).expect("dir").map(|entry| entry.expect("entry").path());
    entries.into_iter().find(|path| path.to_string_lossy().ends_with(".partial"))
}

#[cfg(unix)]
fn interrupt_a_run(signal: i32, name: &str) {
    let dir = tempfile::tempdir().expect("tempdir");
    let scratch = dir.path().join("tmp");
    std::fs::create_dir(&scratch).expect("scratch");
    // 10^7 steps: far longer than the test waits.
    write_pendulum_system(dir.path(), 0.0, 1e5);
    let child = common::crane_cosim_command()
        .args(["run", "system.json", "-q", "-o", "out.csv", "--flush-rows", "100"])
        .current_dir(dir.path())
        .env("TMPDIR", &scratch)
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    let csv = dir.path().join("out.csv");
    let started = Instant::now();
    while partial_file(dir.path()).and_then(|partial| std::fs::metadata(partial).ok()).map_or(0, |m| m.len()) < 100_000
    {
        assert!(started.elapsed() < Duration::from_secs(60), "the run never wrote 100 kB");
        std::thread::sleep(Duration::from_millis(20));
    }
    // SAFETY: sending a signal to our own child.
    assert_eq!(unsafe { libc::kill(child.id() as i32, signal) }, 0);
    let output = child.wait_with_output().expect("wait");
    assert_eq!(output.status.code(), Some(128 + signal), "{}", text(&output.stderr));
    assert!(text(&output.stderr).contains(&format!("interrupted by {name} at t = ")), "{}", text(&output.stderr));

    let text = std::fs::read_to_string(&csv).expect("csv");
    assert!(text.ends_with('\n'), "the CSV ends on a complete row");
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert!(rows.iter().all(|row| row.split(',').count() == 4), "every row has all four columns");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("out.summary.json")).expect("summary"))
            .expect("json");
    assert_eq!(summary["status"], "interrupted");
    assert_eq!(summary["rows_recorded"], rows.len() as u64, "no recorded row is lost");
    let last_time: f64 = rows.last().expect("rows").split(',').next().expect("time").parse().expect("number");
    assert_eq!(summary["end_time"].as_f64(), Some(last_time));
    let shown = cosim_engine::text::Decimal(last_time);
    assert!(summary["error"].as_str().is_some_and(|e| e.contains(&format!("t = {shown} s"))), "{summary}");
    let left: Vec<_> = std::fs::read_dir(&scratch).expect("scratch").collect();
    assert!(left.is_empty(), "temporary folders left behind: {left:?}");
}

#[test]
fn an_absurd_time_grid_needs_force() {
    let dir = tempfile::tempdir().expect("tempdir");
    write_pendulum_system(dir.path(), -1e9, 0.0);
    let output = crane_cosim(&["run", "system.json", "-q", "-o", "out.csv"], dir.path());
    assert!(!output.status.success());
    let message = text(&output.stderr);
    assert!(message.contains("the run has 100000000000 steps and would write about 7.6 TiB"), "{message}");
    assert!(message.contains("(without --force at most") && message.contains("or pass --force"), "{message}");
    assert!(!dir.path().join("out.csv").exists(), "nothing is written");

    write_pendulum_system(dir.path(), 0.0, 1.0);
    let output = crane_cosim(&["run", "system.json", "-q", "-o", "out.csv"], dir.path());
    assert!(output.status.success(), "an ordinary run needs no --force: {}", text(&output.stderr));
}

/// `pendulum.fmu` rewritten as `dir/pendulum.fmu` with its Linux library passed through `damage`.
#[cfg(target_os = "linux")]
fn pendulum_with_library(dir: &Path, damage: impl Fn(Vec<u8>) -> Vec<u8>) {
    use std::io::Read;
    let mut archive = zip::ZipArchive::new(std::fs::File::open(common::pendulum_fmu()).expect("fmu")).expect("zip");
    let mut entries = Vec::new();
    for index in 0..archive.len() {
        let mut entry = archive.by_index(index).expect("entry");
        let mut content = Vec::new();
        entry.read_to_end(&mut content).expect("read");
        let name = entry.name().to_string();
        let content = if name == "binaries/linux64/pendulum.so" { damage(content) } else { content };
        entries.push((name, content));
    }
    let entries: Vec<(&str, &[u8], bool)> = entries.iter().map(|(n, c)| (n.as_str(), c.as_slice(), true)).collect();
    write_zip(dir, "pendulum.fmu", &entries);
}

/// Runs `dir/pendulum.fmu` with TMPDIR set to an empty scratch folder: exit 1, no temporary
/// folder left, and the message.
#[cfg(target_os = "linux")]
fn run_damaged_pendulum(damage: impl Fn(Vec<u8>) -> Vec<u8>) -> String {
    let dir = tempfile::tempdir().expect("tempdir");
    let scratch = dir.path().join("tmp");
    std::fs::create_dir(&scratch).expect("scratch");
    pendulum_with_library(dir.path(), damage);
    let system = r#"{ "fmus": { "pendulum": "pendulum.fmu" }, "instances": [ { "name": "load", "fmu": "pendulum" } ],
        "stop_time": 0.1, "step_size": 0.01 }"#;
    std::fs::write(dir.path().join("system.json"), system).expect("system");
    let output = common::crane_cosim_command()
        .args(["run", "system.json", "-q", "-o", "out.csv"])
        .current_dir(dir.path())
        .env("TMPDIR", &scratch)
        .output()
        .expect("run");
    assert_eq!(output.status.code(), Some(1), "{:?}: {}", output.status, text(&output.stderr));
    let left: Vec<_> = std::fs::read_dir(&scratch).expect("scratch").collect();
    assert!(left.is_empty(), "temporary folders left behind: {left:?}");
    text(&output.stderr)
}

/// Builds `fixtures/blocker.c` with `-D<behaviour>` (BLOCK, QUIT, CRASH or ABORT) into `dir/blocker.fmu`,
/// and a system running it as instance `h` from 0 to 10 s at 1/128 s (exact in binary, so the
/// step from 5 s is h = 0.0078125 s), recording `h.x`.
#[cfg(target_os = "linux")]
fn write_blocker_system(dir: &Path, behaviour: &str) {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/blocker.c");
    let library = dir.join("blocker.so");
    let define = format!("-D{behaviour}");
    let compiled = Command::new("cc").args(["-shared", "-fPIC", &define, "-o"]).arg(&library).arg(&source).status();
    assert!(compiled.expect("a C compiler (cc)").success());
    let xml = br#"<fmiModelDescription fmiVersion="2.0" modelName="blocker" guid="b">
<CoSimulation modelIdentifier="blocker"/>
<ModelVariables><ScalarVariable name="x" valueReference="0" causality="output" variability="continuous"><Real/></ScalarVariable></ModelVariables>
<ModelStructure><Outputs><Unknown index="1"/></Outputs></ModelStructure></fmiModelDescription>"#;
    let binary = std::fs::read(&library).expect("library");
    write_zip(
        dir,
        "blocker.fmu",
        &[("modelDescription.xml", xml, false), ("binaries/linux64/blocker.so", &binary, false)],
    );
    let system = r#"{ "fmus": { "b": "blocker.fmu" }, "instances": [ { "name": "h", "fmu": "b" } ],
        "stop_time": 10.0, "step_size": 0.0078125, "record": { "variables": ["h.x"] } }"#;
    std::fs::write(dir.join("system.json"), system).expect("system");
}

/// A run of the blocker FMU with `args` after `run system.json -q -o out.csv`, TMPDIR `tmp/`.
#[cfg(target_os = "linux")]
fn spawn_blocker(dir: &Path, behaviour: &str, args: &[&str]) -> std::process::Child {
    write_blocker_system(dir, behaviour);
    std::fs::create_dir(dir.join("tmp")).expect("scratch");
    common::crane_cosim_command()
        .args(["run", "system.json", "-q", "-o", "out.csv"])
        .args(args)
        .current_dir(dir)
        .env("TMPDIR", dir.join("tmp"))
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn")
}

/// The 641 rows 0, 1/128, ..., 5.0 s computed before the step from 5.0 s, within `timeout`, in
/// the run's partial file (`out.csv.*.partial`, renamed to `out.csv` when the run ends).
#[cfg(target_os = "linux")]
fn wait_for_rows_before_the_block(dir: &Path, timeout: Duration) {
    let expected = 1 + 641;
    let started = Instant::now();
    let partial_lines =
        || partial_file(dir).and_then(|path| std::fs::read_to_string(path).ok()).map_or(0, |text| text.lines().count());
    while partial_lines() < expected {
        assert!(started.elapsed() < timeout, "the rows computed before the blocked step never reached the file");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The process ended with `code` and `message` (also in the summary, with `status`), the CSV
/// holds all 641 computed rows, and no temporary folder is left.
#[cfg(target_os = "linux")]
fn assert_ended(dir: &Path, output: &Output, code: i32, status: &str, message: &str) {
    assert_eq!(output.status.code(), Some(code), "{}", text(&output.stderr));
    assert!(text(&output.stderr).contains(&format!("error: {message}\n")), "{}", text(&output.stderr));
    let text = std::fs::read_to_string(dir.join("out.csv")).expect("csv");
    let rows: Vec<&str> = text.lines().skip(1).collect();
    assert_eq!((rows.len(), rows.first().copied(), rows.last().copied()), (641, Some("0.0,0.0"), Some("5.0,5.0")));
    assert!(text.ends_with('\n'), "the CSV ends on a complete row");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out.summary.json")).expect("summary")).expect("json");
    assert_eq!(summary["status"], status);
    assert_eq!(summary["error"], format!("error: {message}"));
    assert_eq!((summary["rows_recorded"].as_u64(), summary["end_time"].as_f64()), (Some(641), Some(5.0)));
    let left: Vec<_> = std::fs::read_dir(dir.join("tmp")).expect("scratch").collect();
    assert!(left.is_empty(), "temporary folders left behind: {left:?}");
    assert_eq!(partial_file(dir), None, "a partial results file is left behind");
}

/// [`assert_ended`] of a run whose blocked step did not return, `why` ending the message.
#[cfg(target_os = "linux")]
fn assert_hung(dir: &Path, output: &Output, code: i32, why: &str) {
    let message = format!("instance 'h' did not return from fmi2DoStep(t = 5.0 s, h = 0.0078125 s) {why}");
    assert_ended(dir, output, code, "hung", &message);
}

#[cfg(target_os = "linux")]
fn kill(child: &std::process::Child, signal: i32) {
    // SAFETY: sending a signal to our own child.
    assert_eq!(unsafe { libc::kill(child.id() as i32, signal) }, 0);
}

/// A run of the blocker FMU sent the signals `earlier` (200 ms apart) and then `last` once the
/// rows before its blocked step are in the file: its output and the time from `last` to its end.
#[cfg(target_os = "linux")]
fn signal_a_blocked_step(dir: &Path, earlier: &[i32], last: i32) -> (Output, Duration) {
    let child = spawn_blocker(dir, "BLOCK", &[]);
    // No signal yet: the rows reach the file within the flush interval (1 s) while blocked.
    wait_for_rows_before_the_block(dir, Duration::from_secs(30));
    for &signal in earlier {
        kill(&child, signal);
        std::thread::sleep(Duration::from_millis(200));
    }
    let sent = Instant::now();
    kill(&child, last);
    let output = child.wait_with_output().expect("wait");
    (output, sent.elapsed())
}

#[cfg(target_os = "linux")]
#[test]
fn a_truncated_fmu_library_is_refused_before_loading() {
    let message = run_damaged_pendulum(|mut library| {
        library.truncate(4096);
        library
    });
    assert!(
        message.contains("pendulum.fmu: binaries/linux64/pendulum.so is not a usable shared library: its program headers reach byte ")
            && message.contains(" of a 4096-byte file (truncated?)"),
        "{message}"
    );
}

#[cfg(target_os = "linux")]
#[test]
fn a_blocked_step_loses_no_row_and_a_second_signal_ends_the_run() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (output, elapsed) = signal_a_blocked_step(dir.path(), &[libc::SIGTERM], libc::SIGTERM);
    assert!(elapsed < Duration::from_secs(3), "the second signal ends the run at once");
    assert_hung(dir.path(), &output, 143, "before SIGTERM came again");
}

#[cfg(target_os = "linux")]
#[test]
fn an_fmu_library_that_is_not_elf_is_refused_before_loading() {
    let message = run_damaged_pendulum(|_| b"#!/bin/sh\necho not a library\n".to_vec());
    assert!(
        message.contains(
            "pendulum.fmu: binaries/linux64/pendulum.so is not a usable shared library: it does not start with the ELF magic bytes (7f 45 4c 46) (29 bytes)"
        ),
        "{message}"
    );
}

#[cfg(target_os = "linux")]
#[test]
fn a_blocked_step_ends_after_the_grace_period_of_one_signal() {
    let dir = tempfile::tempdir().expect("tempdir");
    let (output, elapsed) = signal_a_blocked_step(dir.path(), &[], libc::SIGINT);
    assert!((Duration::from_secs(5)..Duration::from_secs(9)).contains(&elapsed), "{elapsed:?}");
    assert_hung(dir.path(), &output, 130, "within 5 s of SIGINT");
}

#[cfg(target_os = "linux")]
#[test]
fn a_step_timeout_ends_a_blocked_step_without_a_signal() {
    let dir = tempfile::tempdir().expect("tempdir");
    let child = spawn_blocker(dir.path(), "BLOCK", &["--step-timeout", "1"]);
    let started = Instant::now();
    let output = child.wait_with_output().expect("wait");
    assert!(started.elapsed() < Duration::from_secs(20), "{:?}", started.elapsed());
    assert_hung(dir.path(), &output, 1, "within 1 s (--step-timeout)");
}

/// Before crashes were handled, all 641 rows were lost: they were still pending (fewer than the
/// 1,000 rows a write waits for) when the process died.
#[cfg(target_os = "linux")]
#[test]
fn an_fmu_that_crashes_or_aborts_in_a_step_loses_no_row_and_no_temporary_folder_is_left() {
    for (behaviour, signal, what) in
        [("CRASH", libc::SIGSEGV, "SIGSEGV, invalid memory access"), ("ABORT", libc::SIGABRT, "SIGABRT, abort")]
    {
        let dir = tempfile::tempdir().expect("tempdir");
        let output = spawn_blocker(dir.path(), behaviour, &[]).wait_with_output().expect("wait");
        let message = format!(
            "instance 'h' crashed ({what}) in fmi2DoStep(t = 5.0 s, h = 0.0078125 s); the run did not finish (the \
             rows computed so far are written)"
        );
        assert_ended(dir.path(), &output, 128 + signal, "failed", &message);
    }
}

#[cfg(target_os = "linux")]
#[test]
fn an_fmu_that_calls_exit_in_a_step_loses_no_row_and_no_temporary_folder_is_left() {
    let dir = tempfile::tempdir().expect("tempdir");
    let output = spawn_blocker(dir.path(), "QUIT", &[]).wait_with_output().expect("wait");
    let message = "an FMU library ended the process by calling exit() in fmi2DoStep(t = 5.0 s, h = 0.0078125 s) of \
                   instance 'h'; the run did not finish (the rows computed so far are written)";
    assert_ended(dir.path(), &output, 1, "failed", message);
}
