//! The workspace's crates as cargo sees them (`cargo metadata`): the FMU list and the crate graph
//! come from here, not from lists kept by hand.
//!
//! An FMU crate declares itself in its Cargo.toml with a `[package.metadata.fmu]` table; its
//! crate name is the FMU's modelIdentifier (and the archive's name, `<name>.fmu`).

use crate::root;
use anyhow::{bail, Context, Result};
use cargo_metadata::{DependencyKind, MetadataCommand};
use serde::Deserialize;
use std::collections::BTreeSet;
use std::path::PathBuf;

/// One crate of the workspace.
#[derive(Debug, Clone)]
pub struct Crate {
    /// The package name.
    pub name: String,
    /// The folder of its Cargo.toml, relative to the workspace root (e.g. `fmus/pendulum`).
    pub folder: PathBuf,
    /// `[package.metadata.fmu]`, for the crates that are FMUs.
    pub fmu: Option<FmuMetadata>,
    /// The workspace crates it depends on, normal and build dependencies (sorted).
    pub dependencies: BTreeSet<String>,
    /// The workspace crates it depends on for tests, examples and benchmarks only (sorted).
    pub dev_dependencies: BTreeSet<String>,
}

/// What an FMU crate's `[package.metadata.fmu]` table says.
#[derive(Debug, Clone, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FmuMetadata {
    /// What the FMU models, in one line: its row in the README's FMU table.
    pub summary: String,
}

/// The workspace members in the order of the root Cargo.toml.
pub fn crates() -> Result<Vec<Crate>> {
    let mut command = MetadataCommand::new();
    command.no_deps().current_dir(root()).other_options(vec!["--offline".to_string()]);
    if let Ok(cargo) = std::env::var("CARGO") {
        command.cargo_path(cargo);
    }
    let metadata = command.exec().context("cargo metadata")?;
    let members = metadata.workspace_packages();
    let names: BTreeSet<&str> = members.iter().map(|p| p.name.as_ref()).collect();
    members
        .iter()
        .map(|package| {
            let folder = package.manifest_path.parent().context("a manifest has a folder")?;
            let folder = folder.strip_prefix(&metadata.workspace_root).context("a member inside the workspace")?;
            let workspace_dependencies = |dev: bool| {
                let kinds = package.dependencies.iter().filter(|d| (d.kind == DependencyKind::Development) == dev);
                kinds.filter(|d| names.contains(d.name.as_str())).map(|d| d.name.clone()).collect()
            };
            Ok(Crate {
                name: package.name.to_string(),
                folder: folder.into(),
                fmu: fmu_metadata(&package.metadata).with_context(|| format!("{}/Cargo.toml", folder))?,
                dependencies: workspace_dependencies(false),
                dev_dependencies: workspace_dependencies(true),
            })
        })
        .collect()
}

/// The FMU crates of the workspace, by name.
pub fn fmus() -> Result<Vec<Crate>> {
    let fmus: Vec<Crate> = fmu_crates(&crates()?).into_iter().cloned().collect();
    if fmus.is_empty() {
        bail!("no workspace crate declares [package.metadata.fmu]");
    }
    Ok(fmus)
}

/// The FMU crates among `crates`, by name (the order of the index and of the README's table).
pub fn fmu_crates(crates: &[Crate]) -> Vec<&Crate> {
    let mut fmus: Vec<&Crate> = crates.iter().filter(|c| c.fmu.is_some()).collect();
    fmus.sort_by(|a, b| a.name.cmp(&b.name));
    fmus
}

/// `[package.metadata.fmu]` out of a package's `metadata` value, if there is one.
fn fmu_metadata(metadata: &serde_json::Value) -> Result<Option<FmuMetadata>> {
    match metadata.get("fmu") {
        None => Ok(None),
        Some(table) => Ok(Some(FmuMetadata::deserialize(table).context("[package.metadata.fmu]")?)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fmu_table_is_read_and_unknown_keys_are_refused() {
        let declared = serde_json::json!({ "fmu": { "summary": "a pendulum" }, "docs": {} });
        assert_eq!(fmu_metadata(&declared).unwrap(), Some(FmuMetadata { summary: "a pendulum".into() }));
        assert_eq!(fmu_metadata(&serde_json::Value::Null).unwrap(), None);
        let typo = serde_json::json!({ "fmu": { "sumary": "a pendulum" } });
        assert!(format!("{:#}", fmu_metadata(&typo).unwrap_err()).contains("sumary"));
    }
}
