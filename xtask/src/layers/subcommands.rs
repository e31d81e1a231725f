//! The binaries' rows in the crate table name their subcommands, exactly those the code has: the
//! variants of the clap enum, as clap names them on the command line (kebab-case).

use super::map::CrateRow;
use crate::root;
use anyhow::{Context, Result};

/// The crates whose `what it holds` cell lists their subcommands: crate, source file, enum.
const BINARIES: [(&str, &str, &str); 2] =
    [("crane-cosim", "cosim/cli/src/cli.rs", "Command"), ("xtask", "xtask/src/main.rs", "Task")];

pub fn problems(rows: &[CrateRow]) -> Result<Vec<String>> {
    let mut problems = Vec::new();
    for (krate, file, enumeration) in BINARIES {
        let source = std::fs::read_to_string(root().join(file)).with_context(|| format!("reading {file}"))?;
        let code = subcommands(&source, enumeration).with_context(|| format!("{file}: no `enum {enumeration}`"))?;
        let Some(row) = rows.iter().find(|r| r.name == krate) else { continue };
        if row.holds != code {
            problems.push(format!(
                "crate `{krate}`: the subcommands are {code:?} ({file}), the table says {:?}",
                row.holds
            ));
        }
    }
    Ok(problems)
}

/// The variants of `enum <name> { … }` in kebab-case, in declaration order (rustfmt's layout:
/// variants at four spaces, their fields, docs and attributes not starting with a capital).
fn subcommands(source: &str, name: &str) -> Option<Vec<String>> {
    let (_, body) = source.split_once(&format!("enum {name} {{\n"))?;
    let variants = body.lines().take_while(|l| !l.starts_with('}')).filter_map(|line| {
        let variant = line.strip_prefix("    ")?;
        variant.starts_with(|c: char| c.is_ascii_uppercase()).then(|| kebab_case(variant))
    });
    Some(variants.collect())
}

/// `DryRun {` → `dry-run` (the identifier at the start of `text`).
fn kebab_case(text: &str) -> String {
    let mut name = String::new();
    for c in text.chars().take_while(|c| c.is_alphanumeric()) {
        if c.is_ascii_uppercase() && !name.is_empty() {
            name.push('-');
        }
        name.push(c.to_ascii_lowercase());
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn subcommands_are_the_enum_variants_in_kebab_case() {
        let source = "#[derive(Subcommand)]\nenum Task {\n    /// Doc.\n    Package,\n    \
                      #[command(hide = true)]\n    DryRun {\n        #[arg(long)]\n        check: bool,\n    },\n    \
                      Run(RunArgs),\n}\nenum Other {\n    X,\n}\n";
        assert_eq!(subcommands(source, "Task").unwrap(), ["package", "dry-run", "run"]);
        assert_eq!(subcommands(source, "Missing"), None);
    }
}
