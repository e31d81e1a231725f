//! Python environments in target/: a venv per requirements file, with its pinned packages,
//! reinstalled only when that file changes.

use crate::{root, run_command};
use anyhow::{Context, Result};
use std::path::PathBuf;
use std::process::Command;

/// The cross-language tests' venv (target/py-venv, tests/requirements.txt).
pub fn venv() -> Result<PathBuf> {
    venv_for("target/py-venv", "tests/requirements.txt")
}

/// The benchmark's venv (target/bench-venv, bench/requirements.txt): FMPy and libcosimpy, kept
/// apart from the test venv so that neither pins the other's packages.
pub fn bench_venv() -> Result<PathBuf> {
    venv_for("target/bench-venv", "bench/requirements.txt")
}

/// The venv that builds the Python wheel (target/maturin-venv, python/requirements-build.txt:
/// maturin).
pub fn maturin_venv() -> Result<PathBuf> {
    venv_for("target/maturin-venv", "python/requirements-build.txt")
}

/// The interpreter of the venv in `dir` with the packages of `requirements` (both relative to
/// the workspace root).
fn venv_for(dir: &str, requirements: &str) -> Result<PathBuf> {
    let dir = root().join(dir);
    let python = dir.join("bin/python");
    let requirements = root().join(requirements);
    let wanted =
        std::fs::read_to_string(&requirements).with_context(|| format!("reading {}", requirements.display()))?;
    let stamp = dir.join("requirements.installed");
    if python.exists() && std::fs::read_to_string(&stamp).ok().as_deref() == Some(wanted.as_str()) {
        return Ok(python);
    }
    crate::setup::python_venv()?;
    let interpreter = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    run_command(Command::new(interpreter).arg("-m").arg("venv").arg(&dir))?;
    run_command(Command::new(&python).args(["-m", "pip", "install", "--quiet", "--upgrade", "pip"]))?;
    run_command(Command::new(&python).args(["-m", "pip", "install", "--quiet", "-r"]).arg(&requirements))?;
    std::fs::write(&stamp, wanted)?;
    Ok(python)
}
