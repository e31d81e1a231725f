//! The FMU list has one source, each FMU crate's `[package.metadata.fmu]`: a crate under `fmus/`
//! that exports an FMU (`export_fmu!` in its `src/lib.rs`) without declaring itself would be
//! neither packaged nor tested, and the README's FMU table is the list's summaries, checked here.

use crate::root;
use crate::workspace::{fmu_crates, Crate};
use anyhow::{Context, Result};
use std::collections::BTreeSet;
use std::path::PathBuf;

/// Where the README's FMU table starts and ends.
const TABLE_START: &str = "<!-- FMU table: one row per [package.metadata.fmu], checked by `cargo xtask layers` -->";
const TABLE_END: &str = "<!-- end of the FMU table -->";

/// What is wrong with the FMU list, one message per problem.
pub fn problems(crates: &[Crate]) -> Result<Vec<String>> {
    let fmus = fmu_crates(crates);
    let declared: BTreeSet<PathBuf> = fmus.iter().map(|c| c.folder.clone()).collect();
    let mut problems = undeclared(&exporting_folders()?, &declared);
    for fmu in &fmus {
        if !root().join(&fmu.folder).join("README.md").is_file() {
            problems.push(format!("the FMU crate `{}` has no README.md (its documentation page)", fmu.name));
        }
    }
    let readme = std::fs::read_to_string(root().join("README.md")).context("reading README.md")?;
    problems.extend(readme_table_problem(&readme, &fmus));
    Ok(problems)
}

/// The folders `fmus/<name>` whose `src/lib.rs` calls `export_fmu!`.
fn exporting_folders() -> Result<BTreeSet<PathBuf>> {
    let mut folders = BTreeSet::new();
    for entry in std::fs::read_dir(root().join("fmus")).context("reading fmus/")? {
        let folder = entry?.path();
        let Ok(lib) = std::fs::read_to_string(folder.join("src/lib.rs")) else { continue };
        if exports_fmu(&lib) {
            folders.insert(PathBuf::from("fmus").join(folder.file_name().context("a folder has a name")?));
        }
    }
    Ok(folders)
}

/// Whether code (not a comment) invokes an `export_fmu!` macro.
fn exports_fmu(lib_rs: &str) -> bool {
    lib_rs.lines().map(|l| l.split("//").next().unwrap_or_default()).any(|code| code.contains("export_fmu!("))
}

/// The exporting folders that are not FMU crates, and the FMU crates that export nothing.
fn undeclared(exporting: &BTreeSet<PathBuf>, declared: &BTreeSet<PathBuf>) -> Vec<String> {
    let missing = exporting.difference(declared).map(|f| {
        format!(
            "{} exports an FMU but is no workspace crate with [package.metadata.fmu], so it is neither packaged \
             nor tested",
            f.display()
        )
    });
    let empty = declared
        .difference(exporting)
        .map(|f| format!("{} declares [package.metadata.fmu] but its src/lib.rs calls no export_fmu!", f.display()));
    missing.chain(empty).collect()
}

/// The table the README must have between its markers: one row per FMU, by name.
fn readme_table(fmus: &[&Crate]) -> String {
    let mut table = String::from("| FMU | what it models |\n| --- | --- |\n");
    for fmu in fmus {
        let summary = fmu.fmu.as_ref().map_or("", |m| m.summary.as_str());
        table += &format!("| [`{0}`]({1}/README.md) | {summary} |\n", fmu.name, fmu.folder.display());
    }
    table
}

/// Whether the README's FMU table is the one [`readme_table`] gives; if not, the message shows it.
fn readme_table_problem(readme: &str, fmus: &[&Crate]) -> Option<String> {
    let expected = readme_table(fmus);
    let found = readme.split_once(TABLE_START).and_then(|(_, rest)| rest.split_once(TABLE_END)).map(|(t, _)| t);
    match found {
        Some(table) if table.trim() == expected.trim() => None,
        Some(_) => {
            Some(format!("README.md's FMU table differs from the FMU crates' summaries; it should be:\n{expected}"))
        }
        None => Some(format!("README.md has no FMU table between {TABLE_START} and {TABLE_END}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::workspace::FmuMetadata;

    #[test]
    fn an_exporting_crate_that_does_not_declare_itself_is_found() {
        assert!(exports_fmu("use fmu_export::Model;\nfmu_export::export_fmu!(Pendulum);\n"));
        assert!(!exports_fmu("//! `export_fmu!(MyModel)` in a cdylib crate\nmacro_rules! export_fmu {}\n"));
        let folders = |f: &[&str]| f.iter().map(PathBuf::from).collect::<BTreeSet<_>>();
        let exporting = folders(&["fmus/crane", "fmus/rigging"]);
        let problems = undeclared(&exporting, &folders(&["fmus/crane", "fmus/physics"]));
        assert_eq!(problems.len(), 2, "{problems:?}");
        assert!(problems[0].starts_with("fmus/rigging exports an FMU but is no workspace crate"));
        assert!(problems[1].starts_with("fmus/physics declares [package.metadata.fmu] but"));
        assert!(undeclared(&exporting, &exporting).is_empty());
    }

    #[test]
    fn the_readme_table_is_the_fmu_summaries() {
        let fmu = |name: &str, summary: &str| Crate {
            name: name.into(),
            folder: PathBuf::from("fmus").join(name),
            fmu: Some(FmuMetadata { summary: summary.into() }),
            dependencies: BTreeSet::new(),
            dev_dependencies: BTreeSet::new(),
        };
        let (crane, imu) = (fmu("crane", "a crane"), fmu("imu", "an IMU"));
        let table = "| FMU | what it models |\n| --- | --- |\n| [`crane`](fmus/crane/README.md) | a crane |\n\
                     | [`imu`](fmus/imu/README.md) | an IMU |\n";
        let readme = format!("# Title\n\n{TABLE_START}\n{table}{TABLE_END}\n\nMore.\n");
        assert_eq!(readme_table_problem(&readme, &[&crane, &imu]), None);
        let problem = readme_table_problem(&readme, &[&crane, &imu, &fmu("rigging", "ropes")]).expect("a new FMU");
        assert!(problem.contains("| [`rigging`](fmus/rigging/README.md) | ropes |"), "{problem}");
        assert!(readme_table_problem(&readme.replace(TABLE_END, ""), &[&crane]).unwrap().contains("no FMU table"));
    }
}
