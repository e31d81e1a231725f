//! `target/fmu/index.json`: what `cargo xtask package` wrote, for the tools that are not cargo
//! (the Python tests read it through `tests/conftest.py`, the FMU fuzzer through its `index`
//! module), so that none of them keeps a list of the FMUs.
//!
//! ```json
//! { "fmus": [ { "model_identifier": "pendulum", "summary": "…", "archive": "pendulum.fmu",
//!               "platforms": ["linux64", "aarch64-linux", "win64"], "fmi3_archive": "fmi3/pendulum.fmu",
//!               "fmi3_platforms": ["x86_64-linux", "aarch64-linux", "x86_64-windows"],
//!               "readme": "fmus/pendulum/README.md",
//!               "reference": { "options": "pendulum_ref.opt", "inputs": "pendulum_in.csv",
//!                              "results": "pendulum_ref.csv" } } ] }
//! ```
//!
//! File names are relative to the folder of index.json, the README's to the workspace root;
//! `inputs` is null for an FMU without inputs.

use super::{Platform, Version};
use crate::reference::ReferenceFiles;
use crate::workspace::Crate;
use anyhow::{ensure, Context, Result};
use serde::Serialize;
use std::path::Path;

#[derive(Serialize)]
struct Index<'a> {
    fmus: Vec<Entry<'a>>,
}

#[derive(Serialize)]
struct Entry<'a> {
    model_identifier: &'a str,
    summary: &'a str,
    archive: String,
    platforms: Vec<&'static str>,
    fmi3_archive: String,
    fmi3_platforms: Vec<&'static str>,
    readme: String,
    reference: &'a ReferenceFiles,
}

/// Writes `out_dir/index.json` for `fmus`, whose archives (FMI 2.0 and 3.0) carry `platforms`
/// and whose reference files are `references` (in the order of `fmus`).
pub fn write(out_dir: &Path, fmus: &[Crate], platforms: &[Platform], references: &[ReferenceFiles]) -> Result<()> {
    let folders = |version: Version| platforms.iter().map(|p| version.platform_folder(*p)).collect::<Vec<_>>();
    ensure!(fmus.len() == references.len(), "one set of reference files per FMU");
    let entries = fmus.iter().zip(references).map(|(fmu, reference)| {
        let metadata = fmu.fmu.as_ref().context("an FMU crate has [package.metadata.fmu]")?;
        let readme = fmu.folder.join("README.md");
        Ok(Entry {
            model_identifier: &fmu.name,
            summary: &metadata.summary,
            archive: format!("{}.fmu", fmu.name),
            platforms: folders(Version::Fmi2),
            fmi3_archive: format!("{}/{}.fmu", Version::Fmi3.folder(), fmu.name),
            fmi3_platforms: folders(Version::Fmi3),
            readme: readme.to_str().context("a README path is UTF-8")?.replace('\\', "/"),
            reference,
        })
    });
    let index = Index { fmus: entries.collect::<Result<_>>()? };
    let path = out_dir.join("index.json");
    std::fs::write(&path, serde_json::to_string_pretty(&index)? + "\n")
        .with_context(|| format!("writing {}", path.display()))?;
    println!("index of the FMUs: {}", path.display());
    Ok(())
}
