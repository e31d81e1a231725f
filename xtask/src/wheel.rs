//! `cargo xtask wheel`: the `crane_cosim` Python wheel (python/, maturin) with the packaged FMUs
//! inside, written to target/wheels/.

use crate::{python, root, run_command};
use anyhow::{bail, Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Where the wheel goes, relative to the workspace root.
const WHEELS: &str = "target/wheels";

/// Copies the FMI 2.0 and 3.0 FMUs of target/fmu/ into python/crane_cosim/fmu/ (replacing what
/// was there), builds the wheel with the Cargo profile `profile` ("release" for users) and the
/// pinned maturin, and returns its path. The FMUs must have been packaged (`cargo xtask package`).
pub fn build(profile: &str) -> Result<PathBuf> {
    let packaged = root().join("target/fmu");
    let shipped = root().join("python/crane_cosim/fmu");
    if shipped.exists() {
        std::fs::remove_dir_all(&shipped).with_context(|| format!("removing {}", shipped.display()))?;
    }
    let mut count = 0;
    for version in ["", "fmi3"] {
        count += copy_fmus(&packaged.join(version), &shipped.join(version))?;
    }
    if count == 0 {
        bail!("no FMU in {}: run `cargo xtask package` first", packaged.display());
    }
    ship_systems(&root().join("python/crane_cosim/systems"))?;
    // Only this build's wheel in the folder, so that whoever installs from it finds one.
    let wheels = root().join(WHEELS);
    if wheels.exists() {
        std::fs::remove_dir_all(&wheels).with_context(|| format!("removing {}", wheels.display()))?;
    }
    let python = python::maturin_venv()?;
    run_command(
        Command::new(&python)
            .args(["-m", "maturin", "build", "--profile", profile, "--quiet", "--manifest-path", "python/Cargo.toml"])
            .arg("--interpreter")
            .arg(&python)
            .arg("--out")
            .arg(&wheels),
    )?;
    let built: Vec<PathBuf> = std::fs::read_dir(&wheels)?
        .map(|entry| entry.map(|e| e.path()))
        .collect::<std::io::Result<Vec<_>>>()?
        .into_iter()
        .filter(|path| path.extension().is_some_and(|e| e == "whl"))
        .collect();
    match built.as_slice() {
        [wheel] => {
            println!("wheel: {} with {count} FMUs", wheel.display());
            Ok(wheel.clone())
        }
        _ => bail!("maturin wrote {} wheels to {WHEELS}, expected one", built.len()),
    }
}

/// The system files the package ships (the Gymnasium environment's closed loops).
const SHIPPED_SYSTEMS: [&str; 2] = ["closed_loop.json", "full_scale_ahc.json"];

/// Copies [`SHIPPED_SYSTEMS`] into `to` (replacing what was there) with their FMUs named inside
/// the package (`../fmu/x.fmu` instead of the checkout's `../target/fmu/x.fmu`).
fn ship_systems(to: &Path) -> Result<()> {
    if to.exists() {
        std::fs::remove_dir_all(to).with_context(|| format!("removing {}", to.display()))?;
    }
    std::fs::create_dir_all(to).with_context(|| format!("creating {}", to.display()))?;
    for name in SHIPPED_SYSTEMS {
        let from = root().join("systems").join(name);
        let text = std::fs::read_to_string(&from).with_context(|| format!("reading {}", from.display()))?;
        // Text replaced, not re-serialized: the file keeps its order (start values are set in it).
        let shipped = text.replace("\"../target/fmu/", "\"../fmu/");
        let system: serde_json::Value =
            serde_json::from_str(&shipped).with_context(|| format!("parsing {}", from.display()))?;
        let fmus = system.get("fmus").and_then(|f| f.as_object()).context("a system names its FMUs")?;
        if let Some(outside) = fmus.values().find(|path| !path.as_str().is_some_and(|p| p.starts_with("../fmu/"))) {
            bail!("{name}: an FMU outside ../target/fmu/: {outside}");
        }
        std::fs::write(to.join(name), shipped)?;
    }
    Ok(())
}

/// Copies the `.fmu` files of `from` into `to` (created); how many.
fn copy_fmus(from: &Path, to: &Path) -> Result<usize> {
    let Ok(entries) = std::fs::read_dir(from) else { return Ok(0) };
    std::fs::create_dir_all(to).with_context(|| format!("creating {}", to.display()))?;
    let mut count = 0;
    for entry in entries {
        let path = entry?.path();
        if path.is_file() && path.extension().is_some_and(|e| e == "fmu") {
            let target = to.join(path.file_name().context("a file has a name")?);
            std::fs::copy(&path, &target).with_context(|| format!("copying {}", path.display()))?;
            count += 1;
        }
    }
    Ok(count)
}
