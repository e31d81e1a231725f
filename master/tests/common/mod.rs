//! Shared helpers of the integration tests.
#![allow(dead_code)]

use std::path::PathBuf;

/// The workspace root.
pub fn workspace_root() -> PathBuf {
    let manifest = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().map(PathBuf::from).unwrap_or(manifest)
}

/// `target/fmu/pendulum.fmu`, produced by `cargo xtask package`.
///
/// Fails the test (never skips it) when the file is missing.
pub fn pendulum_fmu() -> PathBuf {
    let path = workspace_root().join("target/fmu/pendulum.fmu");
    assert!(path.is_file(), "{} does not exist: run `cargo xtask package` first", path.display());
    path
}
