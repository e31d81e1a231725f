//! The map as docs/architecture.md writes it: the crate table (section "Crates") and each
//! crate's module layers (section "Module layers").
//!
//! Crate table: one row per crate, lowest first, with the columns `crate`, `folder`, `side`,
//! `depends on` and `dev-depends on` (names in backticks, `—` for none) and `what it holds`
//! (prose; for a binary, its subcommands in backticks). Module layers: a `### ` heading naming
//! the crate in backticks, then one list item per layer, lowest first: the layer's modules in
//! backticks, then optionally `: what they hold`.

use anyhow::{bail, Context, Result};
use std::collections::BTreeSet;

/// The crate table's heading and the module layers' heading in docs/architecture.md.
pub const CRATES_HEADING: &str = "## Crates";
pub const MODULES_HEADING: &str = "## Module layers";

/// Which part of the workspace a crate belongs to; an FMU-side crate (built into an `.fmu`) may
/// depend on FMU-side crates only.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    Fmu,
    Cosim,
    Tool,
}

/// One row of the crate table.
#[derive(Debug, Clone, PartialEq)]
pub struct CrateRow {
    /// The crate's package name (`crate` column).
    pub name: String,
    /// Its folder, relative to the workspace root (`folder` column).
    pub folder: String,
    /// The `side` column.
    pub side: Side,
    /// The workspace crates it depends on (`depends on` column).
    pub dependencies: BTreeSet<String>,
    /// The workspace crates it depends on for tests only (`dev-depends on` column).
    pub dev_dependencies: BTreeSet<String>,
    /// The names in backticks of the `what it holds` column (for a binary: its subcommands).
    pub holds: Vec<String>,
}

/// One crate's module layers, lowest first.
#[derive(Debug, Clone, PartialEq)]
pub struct ModuleLayers {
    /// The crate's package name, from the heading.
    pub krate: String,
    /// Each layer's modules, lowest layer first.
    pub layers: Vec<Vec<String>>,
}

/// The crate table and the module layers of the document.
#[derive(Debug, Clone, PartialEq)]
pub struct Map {
    /// The crate table's rows, lowest crate first.
    pub crates: Vec<CrateRow>,
    /// The module layers, one entry per crate heading.
    pub modules: Vec<ModuleLayers>,
}

impl Map {
    pub fn parse(text: &str) -> Result<Map> {
        let crates = crate_rows(section(text, CRATES_HEADING)?)?;
        let modules = module_layers(section(text, MODULES_HEADING)?)?;
        Ok(Map { crates, modules })
    }
}

/// The lines after `heading` up to the next heading of the same level.
fn section<'a>(text: &'a str, heading: &str) -> Result<Vec<&'a str>> {
    let mut lines = text.lines().skip_while(|l| l.trim_end() != heading);
    if lines.next().is_none() {
        bail!("no section {heading:?}");
    }
    Ok(lines.take_while(|l| !l.starts_with("## ")).collect())
}

fn crate_rows(lines: Vec<&str>) -> Result<Vec<CrateRow>> {
    let mut table = lines.into_iter().skip_while(|l| !l.starts_with('|')).take_while(|l| l.starts_with('|'));
    let header = cells(table.next().context("the crate table is missing")?);
    let column = |name: &str| header.iter().position(|h| *h == name).with_context(|| format!("no column {name:?}"));
    let [krate, folder, side, dependencies, dev, holds] = [
        column("crate")?,
        column("folder")?,
        column("side")?,
        column("depends on")?,
        column("dev-depends on")?,
        column("what it holds")?,
    ];
    table
        .skip(1) // the delimiter row
        .map(|line| {
            let row = cells(line);
            let cell = |index: usize| row.get(index).copied().with_context(|| format!("{line:?} is too short"));
            let one = |index: usize| -> Result<String> {
                let names = code_spans(cell(index)?);
                let [name] = names.as_slice() else { bail!("{line:?}: one name in backticks per cell") };
                Ok(name.clone())
            };
            Ok(CrateRow {
                name: one(krate)?,
                folder: one(folder)?,
                side: parse_side(cell(side)?).with_context(|| line.to_string())?,
                dependencies: code_spans(cell(dependencies)?).into_iter().collect(),
                dev_dependencies: code_spans(cell(dev)?).into_iter().collect(),
                holds: code_spans(cell(holds)?),
            })
        })
        .collect()
}

fn parse_side(cell: &str) -> Result<Side> {
    match cell {
        "FMU" => Ok(Side::Fmu),
        "co-simulation" => Ok(Side::Cosim),
        "tool" => Ok(Side::Tool),
        other => bail!("side {other:?} is none of FMU, co-simulation, tool"),
    }
}

fn module_layers(lines: Vec<&str>) -> Result<Vec<ModuleLayers>> {
    let mut crates: Vec<ModuleLayers> = Vec::new();
    for line in lines {
        if let Some(heading) = line.strip_prefix("### ") {
            let names = code_spans(heading);
            let [krate] = names.as_slice() else { bail!("{line:?}: the heading names one crate in backticks") };
            crates.push(ModuleLayers { krate: krate.clone(), layers: Vec::new() });
        } else if let Some(item) = list_item(line) {
            let current = crates.last_mut().with_context(|| format!("{line:?} comes before any crate heading"))?;
            let modules = code_spans(item.split(": ").next().unwrap_or_default());
            if modules.is_empty() {
                bail!("{line:?}: a layer names its modules in backticks");
            }
            current.layers.push(modules);
        }
    }
    Ok(crates)
}

/// The text of a list item (`- …` or `1. …`), not of its continuation lines.
fn list_item(line: &str) -> Option<&str> {
    if let Some(item) = line.strip_prefix("- ") {
        return Some(item);
    }
    let (number, item) = line.split_once(". ")?;
    (!number.is_empty() && number.chars().all(|c| c.is_ascii_digit())).then_some(item)
}

/// The cells of a table row, trimmed.
fn cells(line: &str) -> Vec<&str> {
    let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
    inner.split('|').map(str::trim).collect()
}

/// The texts in backticks.
fn code_spans(text: &str) -> Vec<String> {
    text.split('`').skip(1).step_by(2).map(str::to_string).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const FIXTURE: &str = "\
# Architecture

## Crates

| crate | folder | side | depends on | dev-depends on | what it holds |
| --- | --- | --- | --- | --- | --- |
| `base` | `base` | FMU | — | — | the bottom |
| `top` | `apps/top` | tool | `base` | `base`, `extra` | a `tool` |

## Module layers

### `top`

1. `error`, `time`: vocabulary, no `crate::` use
2. `engine`: uses both
   (a continuation line with `prose`)

## Next
";

    #[test]
    fn the_crate_table_and_the_module_layers_are_read() {
        let map = Map::parse(FIXTURE).unwrap();
        let names = |n: &[&str]| n.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>();
        assert_eq!(map.crates.len(), 2);
        assert_eq!(
            map.crates[1],
            CrateRow {
                name: "top".into(),
                folder: "apps/top".into(),
                side: Side::Tool,
                dependencies: names(&["base"]),
                dev_dependencies: names(&["base", "extra"]),
                holds: vec!["tool".into()],
            }
        );
        assert!(map.crates[0].dependencies.is_empty());
        assert_eq!(
            map.modules,
            [ModuleLayers {
                krate: "top".into(),
                layers: vec![vec!["error".into(), "time".into()], vec!["engine".into()]]
            }]
        );
    }

    #[test]
    fn a_malformed_map_is_refused() {
        assert!(Map::parse("## Crates\n").is_err());
        let bad_side = FIXTURE.replace("| FMU |", "| fmu |");
        assert!(format!("{:#}", Map::parse(&bad_side).unwrap_err()).contains("fmu"));
        let no_modules = FIXTURE.replace("2. `engine`: uses both", "2. engine");
        assert!(Map::parse(&no_modules).is_err());
    }
}
