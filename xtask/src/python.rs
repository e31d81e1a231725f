//! The Python environment of the cross-language tests: a venv in target/ with the pinned
//! requirements from tests/requirements.txt, reinstalled only when that file changes.

use crate::{root, run_command};
use anyhow::{Context, Result};
use std::path::PathBuf;
use std::process::Command;

pub fn venv() -> Result<PathBuf> {
    let dir = root().join("target/py-venv");
    let python = dir.join("bin/python");
    let requirements = root().join("tests/requirements.txt");
    let wanted = std::fs::read_to_string(&requirements).context("reading tests/requirements.txt")?;
    let stamp = dir.join("requirements.installed");
    if python.exists() && std::fs::read_to_string(&stamp).ok().as_deref() == Some(wanted.as_str()) {
        return Ok(python);
    }
    let interpreter = std::env::var("PYTHON").unwrap_or_else(|_| "python3".into());
    run_command(Command::new(interpreter).arg("-m").arg("venv").arg(&dir))?;
    run_command(Command::new(&python).args(["-m", "pip", "install", "--quiet", "--upgrade", "pip"]))?;
    run_command(Command::new(&python).args(["-m", "pip", "install", "--quiet", "-r"]).arg(&requirements))?;
    std::fs::write(&stamp, wanted)?;
    Ok(python)
}
