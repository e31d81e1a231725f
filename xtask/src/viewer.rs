//! The viewer's JavaScript bundle: `viewer/src` and three.js (npm, versions pinned in
//! viewer/package-lock.json) bundled by esbuild into cosim/viewer/assets/viewer.js, which is
//! committed so that building the Rust workspace needs neither npm nor a network.

use crate::{root, run_command, setup};
use anyhow::{bail, Context, Result};
use std::path::PathBuf;
use std::process::Command;

/// The committed bundle.
fn committed() -> PathBuf {
    root().join("cosim/viewer/assets/viewer.js")
}

/// Installs the pinned npm packages and rebuilds the bundle: into the committed file, or with
/// `check` into target/ and fails if the committed one differs (esbuild's output is
/// deterministic, so a difference means the sources changed without a rebuild).
pub fn build(check: bool) -> Result<()> {
    setup::npm()?;
    let folder = root().join("viewer");
    run_command(Command::new("npm").args(["ci", "--no-audit", "--no-fund", "--prefix"]).arg(&folder))?;
    let output = if check { root().join("target/viewer/viewer.js") } else { committed() };
    std::fs::create_dir_all(output.parent().context("the bundle has a folder")?)?;
    run_command(Command::new("node").arg(folder.join("build.cjs")).arg(&output))?;
    if check {
        let fresh = std::fs::read(&output)?;
        let kept = std::fs::read(committed()).with_context(|| format!("reading {}", committed().display()))?;
        if fresh != kept {
            bail!("{} is stale: run `cargo xtask viewer` and commit it", committed().display());
        }
        println!("viewer: the committed bundle is up to date ({} bytes)", kept.len());
    } else {
        println!("viewer: wrote {}", output.display());
    }
    Ok(())
}
