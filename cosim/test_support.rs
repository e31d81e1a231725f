//! Shared helpers of the co-simulation crates' integration tests (included with `#[path]`).
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root: every crate of the co-simulation side lives in `cosim/<crate>/`.
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `target/fmu/<name>.fmu`, produced by `cargo xtask package`.
///
/// Fails the test (never skips it) when the file is missing.
pub fn fmu_file(name: &str) -> PathBuf {
    let path = workspace_root().join(format!("target/fmu/{name}.fmu"));
    assert!(path.is_file(), "{} does not exist: run `cargo xtask package` first", path.display());
    path
}

/// `target/fmu/pendulum.fmu` (see [`fmu_file`]).
pub fn pendulum_fmu() -> PathBuf {
    fmu_file("pendulum")
}

/// Header and rows of a results CSV.
pub fn read_results(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let content = std::fs::read_to_string(path).expect("results exist");
    let mut lines = content.lines();
    let header = lines.next().expect("header").split(',').map(String::from).collect();
    let rows = lines.map(|line| line.split(',').map(|cell| cell.parse::<f64>().expect("number")).collect()).collect();
    (header, rows)
}

// The command line's helpers, for the CLI crate's integration tests.

/// `target/fmu/<name>.fmu` as an argument (see [`fmu_file`]).
pub fn fmu(name: &str) -> String {
    fmu_file(name).display().to_string()
}

/// A path below the workspace root, as an argument.
pub fn workspace(path: &str) -> String {
    workspace_root().join(path).display().to_string()
}

/// The `crane-cosim` binary as a command, for a test that adds more than arguments and a folder.
pub fn crane_cosim_command() -> Command {
    // `option_env!`: Cargo names the binary only to the integration tests of its own crate; the
    // other crates that include this file build without it and never call this.
    let Some(binary) = option_env!("CARGO_BIN_EXE_crane-cosim") else {
        panic!("only the CLI crate's integration tests run crane-cosim")
    };
    Command::new(binary)
}

/// `crane-cosim args…` run in `dir`, to its end.
pub fn crane_cosim(args: &[&str], dir: &Path) -> Output {
    crane_cosim_command().args(args).current_dir(dir).output().expect("crane-cosim runs")
}

/// Bytes of an output stream as text.
pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The standard output of a run that must have succeeded (its standard error otherwise fails
/// the test).
pub fn succeeded(output: &Output) -> String {
    assert!(output.status.success(), "{}", text(&output.stderr));
    text(&output.stdout)
}

/// The standard error of a run that must have succeeded: its notes and warnings (messages go
/// there even with `-q`, which only silences what a command prints on success).
pub fn succeeded_stderr(output: &Output) -> String {
    assert!(output.status.success(), "{}", text(&output.stderr));
    text(&output.stderr)
}

/// The standard error of a run that must have failed.
pub fn failed(output: &Output) -> String {
    assert!(!output.status.success(), "expected a failure: {}", text(&output.stdout));
    text(&output.stderr)
}
