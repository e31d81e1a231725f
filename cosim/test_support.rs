//! Shared helpers of the co-simulation crates' integration tests (included with `#[path]`).
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The workspace root: every crate of the co-simulation side lives in `cosim/<crate>/`.
pub fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// `target/fmu/pendulum.fmu`, produced by `cargo xtask package`.
///
/// Fails the test (never skips it) when the file is missing.
pub fn pendulum_fmu() -> PathBuf {
    let path = workspace_root().join("target/fmu/pendulum.fmu");
    assert!(path.is_file(), "{} does not exist: run `cargo xtask package` first", path.display());
    path
}

/// Header and rows of a results CSV.
pub fn read_results(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let content = std::fs::read_to_string(path).expect("results exist");
    let mut lines = content.lines();
    let header = lines.next().expect("header").split(',').map(String::from).collect();
    let rows = lines.map(|line| line.split(',').map(|cell| cell.parse::<f64>().expect("number")).collect()).collect();
    (header, rows)
}
